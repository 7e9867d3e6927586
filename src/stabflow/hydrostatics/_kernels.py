"""Numba kernels (private): the station walk and the free-trim equilibrium on the sections.

``_station_sections`` clips every station by its waterline (``stabflow.geometry._kernels``: the
half-plane clipping of one section, paper 000 steps 2-6) for heel, trim, heave and a wave; it serves
the calm-water statics and the wave pass here and the time-domain FK + HS loads in
``stabflow.dynamics._kernels``. ``_hydro_state`` sums volume and centre of buoyancy, ``_equilibrium``
and ``_gz_curve`` solve heave and trim (free trim) at each heel.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from stabflow.geometry._kernels import _section


#: columns of the hydrostatic work array: area, int y dA, int z dA, waterline height, lateral slope
WORK_COLUMNS = 5


@njit(cache=True)
def _station_sections(xs, ys, zs, npts, ct, st, cp, sp, h, eta, ey, out):
    """The station walk shared by statics, the wave pass and the time domain: clip every station by
    its waterline a y + b z <= c, with the effective heel of roll and the lateral wave slope ey
    (paper 000 step 3: a = cos(theta) sin(phi) - ey cos(phi), b = cos(theta) cos(phi) + ey sin(phi))
    and c = eta + sin(theta) x - h, the waterline height over the station (step 2). ``ct, st, cp,
    sp`` are cos/sin of trim and heel. out[i] = (area, int y dA, int z dA) of the wet section."""
    for i in range(xs.shape[0]):
        A, Sy, Sz = _section(ys[i], zs[i], npts[i], ct * sp - ey[i] * cp, ct * cp + ey[i] * sp, eta[i] + st * xs[i] - h)
        out[i, 0] = A
        out[i, 1] = Sy
        out[i, 2] = Sz


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
        work[i, 3] = amp * np.cos(k * (xs[i] * ct - xc)) if amp != 0.0 else 0.0
        work[i, 4] = 0.0  # no lateral slope along a long-crested wave running along the ship
    _station_sections(xs, ys, zs, npts, ct, st, cp, sp, h, work[:, 3], work[:, 4], work)
    for i in range(xs.shape[0]):
        A = work[i, 0]
        Sy = work[i, 1]
        Sz = work[i, 2]
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
    work = np.empty((xs.shape[0], WORK_COLUMNS))
    h = h0
    th = th0
    for j in range(heels.shape[0]):
        h, th, gz, it = _equilibrium(xs, dx, ys, zs, npts, heels[j], vol, xg, zg, h, th, tol, work, amp, k, xc)
        out[j, 0] = gz
        out[j, 1] = h
        out[j, 2] = th
        out[j, 3] = it
