"""Numba kernels (private) of the criteria: the 1-DOF roll with GZ on the passing wave."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _gz_on_wave(tab, heel, phi, s):
    """GZ [m] at roll ``phi`` [rad] with the crest at table row position ``s`` (periodic, linear
    between rows; linear in heel, ``heel`` the table's heels [rad], odd and increasing)."""
    n = tab.shape[0]
    j = int(s)
    f = s - j
    k = j + 1 if j + 1 < n else 0
    a = np.interp(phi, heel, tab[j])
    b = np.interp(phi, heel, tab[k])
    return (1.0 - f) * a + f * b


@njit(cache=True)
def _rhs(tab, heel, lam, v_rel, inertia, b44, b44q, weight, t, phi, p):
    s = (v_rel * t / lam * tab.shape[0]) % tab.shape[0]
    return p, -(b44 * p + b44q * p * abs(p) + weight * _gz_on_wave(tab, heel, phi, s)) / inertia


@njit(cache=True)
def _roll_1dof(tab, heel, lam, v_rel, inertia, b44, b44q, weight, phi0, n, dt, out):
    """RK4 of (I + A) phi'' + B44 phi' + B44q phi'|phi'| + W GZ(phi; x_c = v_rel t) = 0 from rest at
    ``phi0`` [rad]; ``out`` (n + 1) receives phi [rad], NaN after |phi| leaves the table. Returns
    the last step done."""
    out[:] = np.nan
    phi, p = phi0, 0.0
    out[0] = phi
    top = heel[-1]
    for i in range(n):
        t = i * dt
        k1a, k1b = _rhs(tab, heel, lam, v_rel, inertia, b44, b44q, weight, t, phi, p)
        k2a, k2b = _rhs(tab, heel, lam, v_rel, inertia, b44, b44q, weight, t + dt / 2, phi + dt / 2 * k1a, p + dt / 2 * k1b)
        k3a, k3b = _rhs(tab, heel, lam, v_rel, inertia, b44, b44q, weight, t + dt / 2, phi + dt / 2 * k2a, p + dt / 2 * k2b)
        k4a, k4b = _rhs(tab, heel, lam, v_rel, inertia, b44, b44q, weight, t + dt, phi + dt * k3a, p + dt * k3b)
        phi = phi + dt / 6 * (k1a + 2 * k2a + 2 * k3a + k4a)
        p = p + dt / 6 * (k1b + 2 * k2b + 2 * k3b + k4b)
        if not abs(phi) < top:
            return i
        out[i + 1] = phi
    return n
