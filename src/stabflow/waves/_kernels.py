"""Numba kernels (private): time factors of the wave components by phasor recurrence."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def _trig_table(we, t0, dt, out, j0=0):
    """Fill ``out`` (nt, 2 nc) with cos(we_n t_j) and sin(we_n t_j), t_j = t0 + (j0 + j) dt.

    Each phasor exp(i we t) is advanced by the constant rotation exp(i we dt) (one complex
    multiply instead of a cos and a sin) and reset to the exact value every 256 steps of the
    absolute index j0 + j (so a table built in blocks starting at multiples of 256 equals the
    whole table bit for bit). Rows are written contiguously (time outer, components inner).
    """
    nt = out.shape[0]
    nc = we.shape[0]
    rr = np.cos(we * dt)
    ri = np.sin(we * dt)
    cr = np.empty(nc)
    ci = np.empty(nc)
    for j in range(nt):
        if ((j0 + j) & 255) == 0 or j == 0:
            for n in range(nc):
                ph = we[n] * (t0 + (j0 + j) * dt)
                cr[n] = np.cos(ph)
                ci[n] = np.sin(ph)
        for n in range(nc):
            out[j, n] = cr[n]
            out[j, nc + n] = ci[n]
            nr = cr[n] * rr[n] - ci[n] * ri[n]
            ci[n] = cr[n] * ri[n] + ci[n] * rr[n]
            cr[n] = nr
