"""Numba kernels (private): sectional volumes by half-plane clipping of Bonjean contours.

Every station is stored as its y >= 0 half contour, from the keel on the centreline up the side to
the deck and back to the centreline (paper 000, section 3: the half section used for the Bonjean
tables). The submerged part of a section is the section polygon clipped by the inclined waterline

    a * y + b * z <= c

(section-plane coordinates, body frame). For heel phi, trim theta and lateral wave slope eta_y
(paper 000, step 3: effective heel = roll + lateral wave slope),
a = cos(theta) sin(phi) - eta_y cos(phi), b = cos(theta) cos(phi) + eta_y sin(phi), and c is the
local waterline height. The clipping walks the contour once, so emerged and submerged sections,
deck-edge immersion and the inverted ship (phi up to 180 deg) are exact for the polygonal section.
It is the same result as the seed's steps 4-6 (Bonjean interpolation up to the waterline point plus
the triangle correction) wherever those apply, and stays valid where they do not.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, fastmath=False, inline="always")
def _clip_half_moments(ys, zs, n, a, b, c, p, q, full=True):
    """Area, first and second moments of {a*y + b*z <= c} ∩ (half contour closed on the
    centreline), and the span of the waterline across the hull.

    Returns (area, int y dA, int z dA, int y^2 dA, int y z dA, int z^2 dA, s_min, s_max) [m^2,
    m^3, m^3, m^4, m^4, m^4, m^2]: shoelace sums over the Sutherland-Hodgman output polygon,
    accumulated on the fly (no allocation), and the extreme values of s = p*y + q*z over the points
    where the line crosses the hull contour (not the centreline closing edge); s_min > s_max when
    it crosses none. With ``full`` False only the area and first moments are formed (the rest stay
    zero and the span empty): :func:`_clip_half`'s hot path.
    """
    area = 0.0
    sy = 0.0
    sz = 0.0
    iyy = 0.0
    iyz = 0.0
    izz = 0.0
    smin = 1e300
    smax = -1e300
    have = False
    fy = 0.0
    fz = 0.0
    py = 0.0
    pz = 0.0
    # edge k -> k+1, the last edge (n-1 -> 0) runs down the centreline
    y0 = ys[n - 1]
    z0 = zs[n - 1]
    d0 = a * y0 + b * z0 - c
    for k in range(n):
        y1 = ys[k]
        z1 = zs[k]
        d1 = a * y1 + b * z1 - c
        for m in range(2):
            emit = False
            if m == 0:
                if (d0 <= 0.0) != (d1 <= 0.0):
                    t = d0 / (d0 - d1)
                    ey = y0 + t * (y1 - y0)
                    ez = z0 + t * (z1 - z0)
                    emit = True
                    if full and k > 0:
                        sv = p * ey + q * ez
                        smin = min(smin, sv)
                        smax = max(smax, sv)
            else:
                if d1 <= 0.0:
                    ey = y1
                    ez = z1
                    emit = True
            if emit:
                if have:
                    cr = py * ez - ey * pz
                    area += cr
                    sy += (py + ey) * cr
                    sz += (pz + ez) * cr
                    if full:
                        iyy += (py * py + py * ey + ey * ey) * cr
                        iyz += (py * ez + 2.0 * py * pz + 2.0 * ey * ez + ey * pz) * cr
                        izz += (pz * pz + pz * ez + ez * ez) * cr
                else:
                    fy = ey
                    fz = ez
                    have = True
                py = ey
                pz = ez
        y0 = y1
        z0 = z1
        d0 = d1
    if have:
        cr = py * fz - fy * pz
        area += cr
        sy += (py + fy) * cr
        sz += (pz + fz) * cr
        if full:
            iyy += (py * py + py * fy + fy * fy) * cr
            iyz += (py * fz + 2.0 * py * pz + 2.0 * fy * fz + fy * pz) * cr
            izz += (pz * pz + pz * fz + fz * fz) * cr
    return 0.5 * area, sy / 6.0, sz / 6.0, iyy / 12.0, iyz / 24.0, izz / 12.0, smin, smax


@njit(cache=True, fastmath=False, inline="always")
def _clip_half(ys, zs, n, a, b, c):
    """Area and first moments of {a*y + b*z <= c} ∩ (half contour closed on the centreline):
    (area, int y dA, int z dA) [m^2, m^3, m^3] of :func:`_clip_half_moments`."""
    r = _clip_half_moments(ys, zs, n, a, b, c, 0.0, 0.0, False)
    return r[0], r[1], r[2]


@njit(cache=True)
def _section(ys, zs, n, a, b, c):
    """Both halves of a symmetric section: (area, int y dA, int z dA)."""
    a1, y1, z1 = _clip_half(ys, zs, n, a, b, c)
    # starboard half in mirrored coordinates y' = -y: a -> -a, int y dA changes sign
    a2, y2, z2 = _clip_half(ys, zs, n, -a, b, c)
    return a1 + a2, y1 - y2, z1 + z2


@njit(cache=True)
def _section_moments(ys, zs, n, a, b, c):
    """Both halves of a symmetric section: (area, int y dA, int z dA, int y^2 dA, int y z dA,
    int z^2 dA, s_min, s_max) with s = b*y - a*z along the waterline a*y + b*z = c over its
    crossings of the hull contour (:func:`_clip_half_moments`)."""
    r1 = _clip_half_moments(ys, zs, n, a, b, c, b, -a, True)
    # starboard half in mirrored coordinates y' = -y: a -> -a; odd moments in y change sign, and
    # s = b y - a z = -b y' - a z
    r2 = _clip_half_moments(ys, zs, n, -a, b, c, -b, -a, True)
    return (r1[0] + r2[0], r1[1] - r2[1], r1[2] + r2[2], r1[3] + r2[3], r1[4] - r2[4], r1[5] + r2[5],
            min(r1[6], r2[6]), max(r1[7], r2[7]))
