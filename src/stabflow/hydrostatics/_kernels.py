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

import numpy as np
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


@njit(cache=True)
def _hydro_state(xs, dx, ys, zs, npts, phi, theta, h, xg, zg, work, amp=0.0, k=0.0, xc=0.0):
    """Volume and earth-frame lever arms at heel phi, trim theta, heave h, in calm water or on a
    long-crested regular wave eta = amp cos(k (x_e - xc)) along the ship (quasi-static wave pass,
    paper 002 eqs A12, A18-A19).

    Body origin sits at earth height h. A section point is wet when its earth height is below the
    wave at the station's centreline (paper 000 step 2; no lateral slope along the ship):
    cos(theta)(sin(phi) y + cos(phi) z) <= eta_i + sin(theta) x_i - h, with the wave evaluated at
    the station's earth abscissa x_i cos(theta).
    Returns (V, dx_e, dy_e): volume and the earth-frame x and y of B minus those of G [m].
    """
    ct = np.cos(theta)
    st = np.sin(theta)
    sp = np.sin(phi)
    cp = np.cos(phi)
    V = 0.0
    Mx = 0.0
    My = 0.0
    Mz = 0.0
    for i in range(xs.shape[0]):
        eta = amp * np.cos(k * (xs[i] * ct - xc)) if amp != 0.0 else 0.0
        A, Sy, Sz = _section(ys[i], zs[i], npts[i], ct * sp, ct * cp, eta + st * xs[i] - h)
        work[i, 0] = A
        work[i, 1] = Sy
        work[i, 2] = Sz
        V += A * dx[i]
        Mx += A * dx[i] * xs[i]
        My += Sy * dx[i]
        Mz += Sz * dx[i]
    if V <= 0.0:
        return 0.0, 0.0, 0.0
    xb = Mx / V
    yb = My / V
    zb = Mz / V
    # earth x and y of (B - G), rotation R = Ry(theta) Rx(phi); G on the centreline
    rx = xb - xg
    ry = yb
    rz = zb - zg
    ex = ct * rx + st * (sp * ry + cp * rz)
    ey = cp * ry - sp * rz
    return V, ex, ey


@njit(cache=True)
def _equilibrium(xs, dx, ys, zs, npts, phi, vol, xg, zg, h0, th0, tol, work, amp=0.0, k=0.0, xc=0.0):
    """Newton solve of heave h and trim theta for volume ``vol`` and B above G (free trim).

    Returns (h, theta, gz, iterations). ``gz`` = y_G - y_B in earth axes [m]. Damped steps keep
    the iteration inside the hull's range; finite-difference Jacobian.
    """
    h = h0
    th = th0
    L = xs[-1] - xs[0] + dx[0]
    dh = 1e-6 * L
    dt = 1e-7
    it = 0
    V, ex, ey = _hydro_state(xs, dx, ys, zs, npts, phi, th, h, xg, zg, work, amp, k, xc)
    for it in range(100):
        f1 = (V - vol) / vol
        f2 = ex / L
        if abs(f1) < tol and abs(f2) < tol:
            break
        Vh, exh, eyh = _hydro_state(xs, dx, ys, zs, npts, phi, th, h + dh, xg, zg, work, amp, k, xc)
        Vt, ext, eyt = _hydro_state(xs, dx, ys, zs, npts, phi, th + dt, h, xg, zg, work, amp, k, xc)
        j11 = (Vh - V) / vol / dh
        j12 = (Vt - V) / vol / dt
        j21 = (exh - ex) / L / dh
        j22 = (ext - ex) / L / dt
        det = j11 * j22 - j12 * j21
        if det == 0.0 or not np.isfinite(det):
            # no trim authority (e.g. prismatic hull): solve heave alone
            if j11 == 0.0:
                break
            sh = -f1 / j11
            st_ = 0.0
        else:
            sh = -(j22 * f1 - j12 * f2) / det
            st_ = -(-j21 * f1 + j11 * f2) / det
        # limit steps: 5 % of length in heave, 0.1 rad in trim
        lim = 0.05 * L
        if abs(sh) > lim:
            sh = lim * np.sign(sh)
        if abs(st_) > 0.1:
            st_ = 0.1 * np.sign(st_)
        # backtracking on the residual norm
        r0 = f1 * f1 + f2 * f2
        lam = 1.0
        for _ in range(30):
            hn = h + lam * sh
            tn = th + lam * st_
            Vn, exn, eyn = _hydro_state(xs, dx, ys, zs, npts, phi, tn, hn, xg, zg, work, amp, k, xc)
            g1 = (Vn - vol) / vol
            g2 = exn / L
            if g1 * g1 + g2 * g2 < r0 or lam < 1e-6:
                break
            lam *= 0.5
        h = hn
        th = tn
        V = Vn
        ex = exn
        ey = eyn
    return h, th, -ey, it


@njit(cache=True)
def _gz_curve(xs, dx, ys, zs, npts, heels, vol, xg, zg, h0, th0, tol, out, amp=0.0, k=0.0, xc=0.0):
    """GZ at each heel with free trim, continuation from one heel to the next.

    ``out`` (nheel, 4) receives (gz, h, theta, iterations).
    """
    work = np.empty((xs.shape[0], 3))
    h = h0
    th = th0
    for j in range(heels.shape[0]):
        h, th, gz, it = _equilibrium(xs, dx, ys, zs, npts, heels[j], vol, xg, zg, h, th, tol, work, amp, k, xc)
        out[j, 0] = gz
        out[j, 1] = h
        out[j, 2] = th
        out[j, 3] = it
