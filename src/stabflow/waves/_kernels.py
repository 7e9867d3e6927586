"""Numba kernels (private): incident-wave tables at the stations by phasor recurrence."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _wave_table(amp, k, we, phase0, cb, sb, smith, use_dz, g, dt, nt, out):
    """Fill ``out`` (nt, nst, 4) with (eta, eta_x, eta_y, dphi_zt) at t_j = j dt.

    Component n at station i has phase psi = phase0[i, n] - we[n] t; its phasor exp(i psi) is
    advanced by the constant rotation exp(-i we dt) each step (one complex multiply instead of a
    cos and a sin), and re-normalised every 256 steps against round-off drift.
    """
    nst = phase0.shape[0]
    nc = phase0.shape[1]
    for i in range(nst):
        for n in range(nc):
            cr = np.cos(phase0[i, n])
            ci = np.sin(phase0[i, n])
            rr = np.cos(we[n] * dt)
            ri = -np.sin(we[n] * dt)
            a = amp[n]
            ak = amp[n] * k[n]
            dz = -g * ak * smith[i, n] if use_dz else 0.0
            for j in range(nt):
                out[j, i, 0] += a * cr
                out[j, i, 1] -= ak * cb * ci
                out[j, i, 2] -= ak * sb * ci
                out[j, i, 3] += dz * cr
                nr = cr * rr - ci * ri
                ci = cr * ri + ci * rr
                cr = nr
                if (j & 255) == 255:
                    # exact phasor at step j + 1 (no accumulated drift)
                    ph = phase0[i, n] - we[n] * dt * (j + 1)
                    cr = np.cos(ph)
                    ci = np.sin(ph)
