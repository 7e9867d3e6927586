"""Numba kernels (private): volume-based FK + HS forces (paper 000 eqs 9, 11, 12, 15) and RK4.

Wave input is precomputed at the stations (3-DOF: their earth positions are known beforehand,
paper 000 section 3) on the half-step grid t_j = j dt / 2 as columns
(eta, eta_x, eta_y, dphi_zt): elevation [m], longitudinal and lateral slopes [-] and the
effective d2(phi0)/dz dt [m/s^2] (zero when that option is off).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .._kernels import _section


@njit(cache=True)
def _fkhs(xs, dx, ys, zs, npts, rho, g, xg, zg, h, phi, theta, wave, out):
    """Volume-based FK + HS force and moments about G in earth axes.

    ``wave`` (nst, 4) holds (eta, eta_x, eta_y, dphi_zt) at each station. ``out`` (6,) receives
    (Fx, Fy, Fz, Mx, My, Mz) [N, N m]. Per station (paper 000, steps 1-7): waterline height and
    effective heel (roll + lateral slope) → clipped section volume dV and centre →
    dF = rho g dV (-eta_x, -eta_y, 1) + rho dV dphi_zt (0, 0, 1) (eq. 9), dM = r_CV x dF
    (eqs 11, 12, 15; r from G, earth axes). Returns the total submerged volume [m^3].
    """
    ct = np.cos(theta)
    st = np.sin(theta)
    cp = np.cos(phi)
    sp = np.sin(phi)
    fx = 0.0
    fy = 0.0
    fz = 0.0
    mx = 0.0
    my = 0.0
    mz = 0.0
    vol = 0.0
    for i in range(xs.shape[0]):
        eta = wave[i, 0]
        ex = wave[i, 1]
        ey = wave[i, 2]
        dz = wave[i, 3]
        a = ct * sp - ey * cp
        b = ct * cp + ey * sp
        c = eta + st * xs[i] - h
        A, Sy, Sz = _section(ys[i], zs[i], npts[i], a, b, c)
        if A <= 0.0:
            continue
        dV = A * dx[i]
        vol += dV
        # volume centre relative to G, body axes -> earth axes (R = Ry(theta) Rx(phi))
        bx = xs[i] - xg
        by = Sy / A
        bz = Sz / A - zg
        y1 = cp * by - sp * bz
        z1 = sp * by + cp * bz
        rx = ct * bx + st * z1
        ry = y1
        rz = -st * bx + ct * z1
        f0 = rho * g * dV
        dfx = -f0 * ex
        dfy = -f0 * ey
        dfz = f0 + rho * dV * dz
        fx += dfx
        fy += dfy
        fz += dfz
        mx += ry * dfz - rz * dfy
        my += rz * dfx - rx * dfz
        mz += rx * dfy - ry * dfx
    out[0] = fx
    out[1] = fy
    out[2] = fz
    out[3] = mx
    out[4] = my
    out[5] = mz
    return vol


@njit(cache=True)
def _rhs(xs, dx, ys, zs, npts, p, wave, s, ds, f):
    """State derivative. s = (h, phi, theta, hdot, phidot, thetadot); p = parameters:
    (rho, g, xg, zg, mass, m33, i44, i55, b33, b44, b44q, b55)."""
    _fkhs(xs, dx, ys, zs, npts, p[0], p[1], p[2], p[3], s[0], s[1], s[2], wave, f)
    ds[0] = s[3]
    ds[1] = s[4]
    ds[2] = s[5]
    ds[3] = (f[2] - p[4] * p[1] - p[8] * s[3]) / p[5]
    ds[4] = (f[3] - p[9] * s[4] - p[10] * s[4] * abs(s[4])) / p[6]
    ds[5] = (f[4] - p[11] * s[5]) / p[7]


@njit(cache=True)
def _simulate(xs, dx, ys, zs, npts, p, wtab, dt, nsteps, s0, phi_cap, out, forces):
    """Fixed-step RK4 over ``nsteps``; ``wtab`` (2 nsteps + 1, nst, 4) on the half-step grid.

    ``out`` (nsteps + 1, 6) receives the state; ``forces`` (nsteps + 1, 6) the FK+HS loads.
    Stops when |phi| > phi_cap (capsize). Returns the number of steps done; no allocation in the loop.
    """
    n6 = 6
    s = np.empty(n6)
    k1 = np.empty(n6)
    k2 = np.empty(n6)
    k3 = np.empty(n6)
    k4 = np.empty(n6)
    tmp = np.empty(n6)
    f = np.empty(6)
    for q in range(n6):
        s[q] = s0[q]
        out[0, q] = s0[q]
    _fkhs(xs, dx, ys, zs, npts, p[0], p[1], p[2], p[3], s[0], s[1], s[2], wtab[0], f)
    for q in range(6):
        forces[0, q] = f[q]
    for n in range(nsteps):
        j = 2 * n
        _rhs(xs, dx, ys, zs, npts, p, wtab[j], s, k1, f)
        for q in range(n6):
            tmp[q] = s[q] + 0.5 * dt * k1[q]
        _rhs(xs, dx, ys, zs, npts, p, wtab[j + 1], tmp, k2, f)
        for q in range(n6):
            tmp[q] = s[q] + 0.5 * dt * k2[q]
        _rhs(xs, dx, ys, zs, npts, p, wtab[j + 1], tmp, k3, f)
        for q in range(n6):
            tmp[q] = s[q] + dt * k3[q]
        _rhs(xs, dx, ys, zs, npts, p, wtab[j + 2], tmp, k4, f)
        for q in range(n6):
            s[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
            out[n + 1, q] = s[q]
        _fkhs(xs, dx, ys, zs, npts, p[0], p[1], p[2], p[3], s[0], s[1], s[2], wtab[j + 2], f)
        for q in range(6):
            forces[n + 1, q] = f[q]
        if abs(s[1]) > phi_cap:
            return n + 1
    return nsteps
