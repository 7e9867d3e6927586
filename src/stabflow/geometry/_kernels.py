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


@njit(cache=True, fastmath=False)
def _clip_half(ys, zs, n, a, b, c):
    """Area and first moments of {a*y + b*z <= c} ∩ (half contour closed on the centreline).

    Returns (area, int y dA, int z dA) [m^2, m^3, m^3]. Shoelace sums over the Sutherland-Hodgman
    output polygon, accumulated on the fly (no allocation).
    """
    area = 0.0
    sy = 0.0
    sz = 0.0
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
    return 0.5 * area, sy / 6.0, sz / 6.0


@njit(cache=True)
def _section(ys, zs, n, a, b, c):
    """Both halves of a symmetric section: (area, int y dA, int z dA)."""
    a1, y1, z1 = _clip_half(ys, zs, n, a, b, c)
    # starboard half in mirrored coordinates y' = -y: a -> -a, int y dA changes sign
    a2, y2, z2 = _clip_half(ys, zs, n, -a, b, c)
    return a1 + a2, y1 - y2, z1 + z2
