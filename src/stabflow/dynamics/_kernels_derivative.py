"""Numba kernels of the derivative model (paper 001): sampling of the generalized FK + HS restoring
forces at hull positions, and the RK4 of heave-roll-pitch with polynomial restoring forces."""

from __future__ import annotations

import numpy as np
from numba import njit

from stabflow.dynamics._kernels import (N_STATE, S_AMP, S_PITCH, S_RATE, S_ROLL, S_Z, _b44q, _generalized_system,
                                        _loads, _update_amplitude)

DOF3 = (S_Z, S_ROLL, S_PITCH)


@njit(cache=True)
def _restoring_samples(xs, dx, ys, zs, npts, tab, lim, p, waves, q, out):
    """Generalized restoring forces (heave, roll, pitch) [N, N m, N m] at rest: ``q`` (n, 6)
    generalized coordinates, ``waves`` (nw, nst, nq) wave snapshots at the stations; ``out`` (nw, n, 3).
    Gravity included, velocities zero (so damping and the velocity terms vanish)."""
    f = np.empty(6)
    work = np.empty((xs.shape[0], 5))
    mq = np.empty((6, 6))
    r = np.empty(6)
    s = np.zeros(N_STATE)
    for w in range(waves.shape[0]):
        for i in range(q.shape[0]):
            for j in range(6):
                s[j] = q[i, j]
            _loads(xs, dx, ys, zs, npts, tab, lim, p, waves[w], s, f, work)
            _generalized_system(p, s, f, mq, r)
            out[w, i, 0] = r[S_Z]
            out[w, i, 1] = r[S_ROLL]
            out[w, i, 2] = r[S_PITCH]


@njit(cache=True, inline="always")
def _poly(coef, expo, pw, row):
    """sum_j coef[row, j] z^e0 phi^e1 theta^e2 with the powers ``pw`` (3, 4)."""
    acc = 0.0
    for j in range(expo.shape[0]):
        acc += coef[row, j] * pw[0, expo[j, 0]] * pw[1, expo[j, 1]] * pw[2, expo[j, 2]]
    return acc


@njit(cache=True)
def _derivative_rhs(p, q0, minv, damp, calm, cexp, wave, wexp, s, ds, pw, f):
    """State derivative of the derivative model: minv (3, 3) (M + A)^-1 at equilibrium, damp (3, 3)
    linear damping, calm (3, nc) restoring polynomial on exponents cexp (nc, 3), wave (3, nw) the
    wave-dependent coefficients at this instant on exponents wexp (nw, 3); the quadratic roll
    damping B44q(running amplitude) as in the full model. ``pw`` (3, 4) and ``f`` (3,) scratch."""
    for k in range(3):
        x = s[DOF3[k]] - q0[k]
        pw[k, 0] = 1.0
        pw[k, 1] = x
        pw[k, 2] = x * x
        pw[k, 3] = x * x * x
    for i in range(3):
        f[i] = _poly(calm, cexp, pw, i) + _poly(wave, wexp, pw, i)
        for k in range(3):
            f[i] -= damp[i, k] * s[S_RATE + DOF3[k]]
    pd = s[S_RATE + S_ROLL]
    f[1] -= _b44q(p, s[S_AMP]) * pd * abs(pd)
    for j in range(N_STATE):
        ds[j] = 0.0
    for k in range(3):
        ds[DOF3[k]] = s[S_RATE + DOF3[k]]
        ds[S_RATE + DOF3[k]] = minv[k, 0] * f[0] + minv[k, 1] * f[1] + minv[k, 2] * f[2]


@njit(cache=True, nogil=True)
def _simulate_derivative(p, q0, minv, damp, calm, cexp, ctab, wexp, dt, n0, nsteps, s0, phi_cap, out):
    """Fixed-step RK4 of the derivative model from ``s0`` (N_STATE,) at step ``n0`` up to step
    ``nsteps``; ``ctab`` (2 nsteps + 1, 3, nw) the wave-dependent coefficients on the half-step
    grid. ``out`` (nsteps + 1, N_STATE) receives the states. Returns the last step done (< nsteps
    when |roll| passed ``phi_cap``)."""
    ns = N_STATE
    s = s0.copy()
    k1 = np.empty(ns)
    k2 = np.empty(ns)
    k3 = np.empty(ns)
    k4 = np.empty(ns)
    tmp = np.empty(ns)
    pw = np.empty((3, 4))
    f = np.empty(3)
    out[n0] = s
    for n in range(n0, nsteps):
        j = 2 * n
        _derivative_rhs(p, q0, minv, damp, calm, cexp, ctab[j], wexp, s, k1, pw, f)
        for q in range(ns):
            tmp[q] = s[q] + 0.5 * dt * k1[q]
        _derivative_rhs(p, q0, minv, damp, calm, cexp, ctab[j + 1], wexp, tmp, k2, pw, f)
        for q in range(ns):
            tmp[q] = s[q] + 0.5 * dt * k2[q]
        _derivative_rhs(p, q0, minv, damp, calm, cexp, ctab[j + 1], wexp, tmp, k3, pw, f)
        for q in range(ns):
            tmp[q] = s[q] + dt * k3[q]
        _derivative_rhs(p, q0, minv, damp, calm, cexp, ctab[j + 2], wexp, tmp, k4, pw, f)
        prev = s[S_ROLL]
        for q in range(ns):
            s[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
        _update_amplitude(prev, s)
        out[n + 1] = s
        if abs(s[S_ROLL]) > phi_cap:
            return n + 1
    return nsteps
