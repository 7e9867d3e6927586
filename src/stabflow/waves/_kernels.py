"""Numba kernels (private): time factors of the wave components by phasor recurrence."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def _trig_table(we, t0, dt, out):
    """Fill ``out`` (nt, 2 nc) with cos(we_n t_j) and sin(we_n t_j), t_j = t0 + j dt.

    Each phasor exp(i we t) is advanced by the constant rotation exp(i we dt) (one complex
    multiply instead of a cos and a sin) and reset to the exact value every 256 steps.
    """
    nt = out.shape[0]
    nc = we.shape[0]
    for n in range(nc):
        rr = np.cos(we[n] * dt)
        ri = np.sin(we[n] * dt)
        cr = 1.0
        ci = 0.0
        for j in range(nt):
            if (j & 255) == 0:
                ph = we[n] * (t0 + j * dt)
                cr = np.cos(ph)
                ci = np.sin(ph)
            out[j, n] = cr
            out[j, nc + n] = ci
            nr = cr * rr - ci * ri
            ci = cr * ri + ci * rr
            cr = nr
