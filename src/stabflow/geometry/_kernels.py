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
def _edge_add(iyy, iyz, izz, j0, j1, j2, j3, ay, az, by, bz, cr, p, q, chord):
    """Add one output edge (a -> b, shoelace cross product ``cr``) of :func:`_clip_half_moments`
    to the running second-moment sums (x 12, 24, 12) and, for an edge along the clip line
    (``chord``), to int s^k ds, k = 0..3, s = p*y + q*z; returns the seven sums."""
    iyy += (ay * ay + ay * by + by * by) * cr
    iyz += (ay * bz + 2.0 * ay * az + 2.0 * by * bz + by * az) * cr
    izz += (az * az + az * bz + bz * bz) * cr
    if chord:
        s0 = p * ay + q * az
        s1 = p * by + q * bz
        j0 += s1 - s0
        j1 += (s1 * s1 - s0 * s0) / 2.0
        j2 += (s1 * s1 * s1 - s0 * s0 * s0) / 3.0
        j3 += (s1 * s1 * s1 * s1 - s0 * s0 * s0 * s0) / 4.0
    return iyy, iyz, izz, j0, j1, j2, j3


@njit(cache=True, fastmath=False, inline="always")
def _clip_half_moments(ys, zs, n, a, b, c, p, q, full=True):
    """Area, first and second moments of {a*y + b*z <= c} ∩ (half contour closed on the
    centreline), and moments of the wet chords of the waterline.

    Returns (area, int y dA, int z dA, int y^2 dA, int y z dA, int z^2 dA, J0, J1, J2, J3) [m^2,
    m^3, m^3, m^4, m^4, m^4, m, m^2, m^3, m^4]: shoelace sums over the Sutherland-Hodgman output
    polygon, accumulated on the fly (no allocation), and J_k = int s^k ds over the parts of the line
    a*y + b*z = c inside the half section, s = p*y + q*z along it (the output polygon's edges
    between two consecutive crossing points; with several chords, the gaps between them are left
    out; signed so that J0 >= 0). With ``full`` False only the area and first moments are formed
    (the rest stay zero): :func:`_clip_half`'s hot path.
    """
    area = 0.0
    sy = 0.0
    sz = 0.0
    iyy = 0.0
    iyz = 0.0
    izz = 0.0
    j0 = 0.0
    j1 = 0.0
    j2 = 0.0
    j3 = 0.0
    have = False
    fy = 0.0
    fz = 0.0
    fx = False  # the first emitted point is a crossing
    py = 0.0
    pz = 0.0
    px = False  # the previous emitted point is a crossing
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
            cross = False
            if m == 0:
                if (d0 <= 0.0) != (d1 <= 0.0):
                    t = d0 / (d0 - d1)
                    ey = y0 + t * (y1 - y0)
                    ez = z0 + t * (z1 - z0)
                    emit = True
                    cross = True
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
                        # an edge between two crossings lies on the clip line: a wet chord
                        iyy, iyz, izz, j0, j1, j2, j3 = _edge_add(iyy, iyz, izz, j0, j1, j2, j3, py, pz, ey, ez, cr,
                                                                  p, q, cross and px)
                else:
                    fy = ey
                    fz = ez
                    fx = cross
                    have = True
                py = ey
                pz = ez
                px = cross
        y0 = y1
        z0 = z1
        d0 = d1
    if have:
        cr = py * fz - fy * pz
        area += cr
        sy += (py + fy) * cr
        sz += (pz + fz) * cr
        if full:
            iyy, iyz, izz, j0, j1, j2, j3 = _edge_add(iyy, iyz, izz, j0, j1, j2, j3, py, pz, fy, fz, cr, p, q,
                                                      px and fx)
    if j0 < 0.0:
        j0 = -j0
        j1 = -j1
        j2 = -j2
        j3 = -j3
    return 0.5 * area, sy / 6.0, sz / 6.0, iyy / 12.0, iyz / 24.0, izz / 12.0, j0, j1, j2, j3


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
    int z^2 dA, J0, J1, J2, J3) with J_k = int s^k ds over the wet chords of the waterline
    a*y + b*z = c, s = b*y - a*z along it (:func:`_clip_half_moments`; the two halves' chords meet
    on the centreline)."""
    r1 = _clip_half_moments(ys, zs, n, a, b, c, b, -a, True)
    # starboard half in mirrored coordinates y' = -y: a -> -a; odd moments in y change sign, and
    # s = b y - a z = -b y' - a z
    r2 = _clip_half_moments(ys, zs, n, -a, b, c, -b, -a, True)
    return (r1[0] + r2[0], r1[1] - r2[1], r1[2] + r2[2], r1[3] + r2[3], r1[4] - r2[4], r1[5] + r2[5],
            r1[6] + r2[6], r1[7] + r2[7], r1[8] + r2[8], r1[9] + r2[9])
