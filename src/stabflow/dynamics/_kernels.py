"""Numba kernels (private): volume-based FK + HS forces (paper 000 eqs 9, 11, 12, 15) and RK4.

Wave input is precomputed at the stations (3-DOF: their earth positions are known beforehand,
paper 000 section 3) on the half-step grid t_j = j dt / 2 as columns (eta, S[, dphi_zt]):
elevation [m], slope along the direction of propagation S [-] (eta_x = cos(beta) S,
eta_y = sin(beta) S for long-crested waves of heading beta) and, optionally, the effective
d2(phi0)/dz dt [m/s^2].

Sections are clipped exactly (``_section``) or, when tables are given (``tab.shape[0] > 0``), read
from per-station tables of area and first moments over (effective heel psi, waterline distance d)
built by the same exact clipping (``_build_tables``): the clipped area depends on the waterline
only through its normal angle psi = atan2(a, b) and distance d = c / |(a, b)|.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from stabflow.geometry.frames import _rotate
from stabflow.geometry._kernels import _section
from stabflow.hydrostatics._kernels import _station_sections


@njit(cache=True)
def _build_tables(ys, zs, npts, tab, lim):
    """Fill ``tab`` (nst, npsi, nu, 3) with (area, int y dA, int z dA) and ``lim`` (nst, npsi, 3)
    with the waterline distances at which the section starts and ends being wet and (nu - 1) / span, for psi on
    [0, pi] (npsi equal steps) and d on nu equal steps between those limits."""
    nst, npsi, nu, _ = tab.shape
    dpsi = np.pi / (npsi - 1)
    for i in range(nst):
        n = npts[i]
        for j in range(npsi):
            a = np.sin(j * dpsi)
            b = np.cos(j * dpsi)
            lo = np.inf
            hi = -np.inf
            for k in range(n):
                for sgn in (-1.0, 1.0):
                    p = sgn * a * ys[i, k] + b * zs[i, k]
                    lo = min(lo, p)
                    hi = max(hi, p)
            lim[i, j, 0] = lo
            lim[i, j, 1] = hi
            lim[i, j, 2] = (nu - 1) / (hi - lo)
            for m in range(nu):
                d = lo + (hi - lo) * m / (nu - 1)
                A, Sy, Sz = _section(ys[i], zs[i], n, a, b, d)
                tab[i, j, m, 0] = A
                tab[i, j, m, 1] = Sy
                tab[i, j, m, 2] = Sz


@njit(cache=True, inline="always")
def _atan_poly(x):
    """arctan(x) for |x| <= 1: Abramowitz & Stegun 4.4.49 polynomial (|error| < 2e-8 rad)."""
    x2 = x * x
    p = 0.0028662257
    p = p * x2 - 0.0161657367
    p = p * x2 + 0.0429096138
    p = p * x2 - 0.0752896400
    p = p * x2 + 0.1065626393
    p = p * x2 - 0.1420889944
    p = p * x2 + 0.1999355085
    p = p * x2 - 0.3333314528
    return x * (1.0 + p * x2)


@njit(cache=True, inline="always")
def _row(tab, lim, i, j, d, nu):
    """Linear read of table row (i, j) at waterline distance d: (area, int y dA, int z dA)."""
    u = (d - lim[i, j, 0]) * lim[i, j, 2]
    if u <= 0.0:
        return 0.0, 0.0, 0.0
    if u >= nu - 1:
        return tab[i, j, nu - 1, 0], tab[i, j, nu - 1, 1], tab[i, j, nu - 1, 2]
    k = int(u)
    r = u - k
    t0 = tab[i, j, k]
    t1 = tab[i, j, k + 1]
    return t0[0] + r * (t1[0] - t0[0]), t0[1] + r * (t1[1] - t0[1]), t0[2] + r * (t1[2] - t0[2])


@njit(cache=True, inline="always")
def _section_tab(tab, lim, i, psi, d):
    """Bilinear read of station ``i``'s table at (psi [rad], d [m]); symmetry for psi < 0."""
    npsi = tab.shape[1]
    nu = tab.shape[2]
    sgn = 1.0
    if psi < 0.0:
        psi = -psi
        sgn = -1.0
    f = psi * ((npsi - 1) / np.pi)
    j = min(int(f), npsi - 2)
    w = min(f - j, 1.0)
    a0, y0, z0 = _row(tab, lim, i, j, d, nu)
    a1, y1, z1 = _row(tab, lim, i, j + 1, d, nu)
    return a0 + w * (a1 - a0), sgn * (y0 + w * (y1 - y0)), z0 + w * (z1 - z0)


@njit(cache=True)
def _fkhs(xs, dx, ys, zs, npts, tab, lim, rho, g, xg, zg, h, phi, theta, cb, sb, wave, out, work):
    """Volume-based FK + HS force and moments about G in earth axes.

    ``wave`` (nst, 2 or 3) holds (eta, S[, dphi_zt]) at each station. ``out`` (6,) receives
    (Fx, Fy, Fz, Mx, My, Mz) [N, N m]. Per station (paper 000, steps 1-7): waterline height and
    effective heel (roll + lateral slope) → clipped section volume dV and centre b (from G, body
    axes) → dF = rho g dV w with w = (-eta_x, -eta_y, 1 + dphi_zt / g) (eq. 9) and dM = (R b) x dF
    (eqs 11, 12, 15). ``work`` (nst, 5) is scratch. Since w = S (-cos beta, -sin beta, 0) + (1 + dphi_zt / g) e_z, the sums
    P = sum b dV S and Q = sum b dV (1 + dphi_zt / g) are formed in body axes (b dV needs only the
    section's area and first moments, no division) and rotated once. Returns the volume [m^3].
    """
    ct = np.cos(theta)
    st = np.sin(theta)
    cp = np.cos(phi)
    sp = np.sin(phi)
    ict = 1.0 / ct
    vol = 0.0
    vs = 0.0
    vq = 0.0
    px = 0.0
    py = 0.0
    pz = 0.0
    qx = 0.0
    qy = 0.0
    qz = 0.0
    use_tab = tab.shape[0] > 0
    use_dz = wave.shape[1] > 2
    nst = xs.shape[0]
    if use_tab:
        # branch-free pass over the stations (vectorised by LLVM): waterline normal angle and
        # distance, psi = phi - atan(ey / ct), d = c / sqrt(ct^2 + ey^2); slopes clipped to 45 deg
        for i in range(nst):
            ey = sb * wave[i, 1]
            x = min(max(ey * ict, -1.0), 1.0)
            work[i, 0] = phi - _atan_poly(x)
            work[i, 1] = (wave[i, 0] + st * xs[i] - h) / math.sqrt(ct * ct + ey * ey)
    if use_tab:
        for i in range(nst):
            A, Sy, Sz = _section_tab(tab, lim, i, work[i, 0], work[i, 1])
            work[i, 2] = A
            work[i, 3] = Sy
            work[i, 4] = Sz
    else:
        # exact clipping: the station walk of the hydrostatics, with the lateral slope of the wave
        for i in range(nst):
            work[i, 0] = sb * wave[i, 1]
        _station_sections(xs, ys, zs, npts, ct, st, cp, sp, h, wave[:, 0], work[:, 0], work[:, 2:])
    for i in range(nst):
        # dry sections add zeros
        S = wave[i, 1]
        A = work[i, 2]
        dV = A * dx[i]
        wz = 1.0 + wave[i, 2] / g if use_dz else 1.0
        bx = (xs[i] - xg) * dV
        by = work[i, 3] * dx[i]
        bz = (work[i, 4] - zg * A) * dx[i]
        vol += dV
        vs += dV * S
        vq += dV * wz
        px += bx * S
        py += by * S
        pz += bz * S
        qx += bx * wz
        qy += by * wz
        qz += bz * wz
    f = rho * g
    ux = -cb
    uy = -sb
    out[0] = f * ux * vs
    out[1] = f * uy * vs
    out[2] = f * vq
    rpx, rpy, rpz = _rotate(px, py, pz, cp, sp, ct, st)
    rqx, rqy, rqz = _rotate(qx, qy, qz, cp, sp, ct, st)
    # (R P) x u + (R Q) x e_z
    out[3] = f * (-rpz * uy + rqy)
    out[4] = f * (rpz * ux - rqx)
    out[5] = f * (rpx * uy - rpy * ux)
    return vol


# positions in the parameter vector ``p`` of the RK4 kernels (built by
# ``stabflow.dynamics.model.ModelParameters.vector``)
P_RHO = 0
P_G = 1
P_XG = 2
P_ZG = 3
P_MASS = 4
P_M33 = 5
P_M44 = 6
P_M55 = 7
P_B33 = 8
P_B44 = 9
P_B44Q = 10
P_B55 = 11
P_COS_BETA = 12
P_SIN_BETA = 13
N_PARAMETERS = 14


@njit(cache=True)
def _rhs(xs, dx, ys, zs, npts, tab, lim, p, wave, s, ds, f, work):
    """State derivative. s = (h, phi, theta, hdot, phidot, thetadot); p = parameter vector (P_*)."""
    _fkhs(xs, dx, ys, zs, npts, tab, lim, p[P_RHO], p[P_G], p[P_XG], p[P_ZG], s[0], s[1], s[2], p[P_COS_BETA],
          p[P_SIN_BETA], wave, f, work)
    ds[0] = s[3]
    ds[1] = s[4]
    ds[2] = s[5]
    ds[3] = (f[2] - p[P_MASS] * p[P_G] - p[P_B33] * s[3]) / p[P_M33]
    ds[4] = (f[3] - p[P_B44] * s[4] - p[P_B44Q] * s[4] * abs(s[4])) / p[P_M44]
    ds[5] = (f[4] - p[P_B55] * s[5]) / p[P_M55]


@njit(cache=True, nogil=True)
def _simulate(xs, dx, ys, zs, npts, tab, lim, p, wtab, dt, n0, nsteps, s0, phi_cap, out, forces):
    """Fixed-step RK4 from step ``n0`` to ``nsteps``; ``wtab`` (2 nsteps + 1, nst, nq) on the
    half-step grid.

    ``out`` (nsteps + 1, 6) receives the state (row n0 is set to ``s0``); ``forces``
    (nsteps + 1, 6) the FK+HS loads, or pass a (0, 6) array to skip them. Stops when
    |phi| > phi_cap (capsize). Returns the index of the last step done; no allocation in the loop.
    """
    n6 = 6
    s = np.empty(n6)
    k1 = np.empty(n6)
    k2 = np.empty(n6)
    k3 = np.empty(n6)
    k4 = np.empty(n6)
    tmp = np.empty(n6)
    f = np.empty(6)
    work = np.empty((xs.shape[0], 5))
    keep = forces.shape[0] > 0
    for q in range(n6):
        s[q] = s0[q]
        out[n0, q] = s0[q]
    if keep:
        _fkhs(xs, dx, ys, zs, npts, tab, lim, p[P_RHO], p[P_G], p[P_XG], p[P_ZG], s[0], s[1], s[2], p[P_COS_BETA], p[P_SIN_BETA],
              wtab[2 * n0], f, work)
        for q in range(6):
            forces[n0, q] = f[q]
    for n in range(n0, nsteps):
        j = 2 * n
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j], s, k1, f, work)
        for q in range(n6):
            tmp[q] = s[q] + 0.5 * dt * k1[q]
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 1], tmp, k2, f, work)
        for q in range(n6):
            tmp[q] = s[q] + 0.5 * dt * k2[q]
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 1], tmp, k3, f, work)
        for q in range(n6):
            tmp[q] = s[q] + dt * k3[q]
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 2], tmp, k4, f, work)
        for q in range(n6):
            s[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
            out[n + 1, q] = s[q]
        if keep:
            _fkhs(xs, dx, ys, zs, npts, tab, lim, p[P_RHO], p[P_G], p[P_XG], p[P_ZG], s[0], s[1], s[2], p[P_COS_BETA], p[P_SIN_BETA],
                  wtab[j + 2], f, work)
            for q in range(6):
                forces[n + 1, q] = f[q]
        if abs(s[1]) > phi_cap:
            return n + 1
    return nsteps


@njit(cache=True, parallel=True)
def _simulate_batch(xs, dx, ys, zs, npts, tab, lim, p, wtabs, dt, nsteps, s0, phi_cap, out, last):
    """Records in parallel (``prange``): ``wtabs`` (nrec, 2 nsteps + 1, nst, nq) → ``out``
    (nrec, nsteps + 1, 6), ``last`` (nrec,) index of the last step done. Each record is the same
    computation as ``_simulate``, so results do not depend on the number of threads."""
    nofo = np.empty((0, 6))
    for r in prange(wtabs.shape[0]):
        last[r] = _simulate(xs, dx, ys, zs, npts, tab, lim, p, wtabs[r], dt, 0, nsteps, s0, phi_cap, out[r], nofo)
