"""Numba kernels (private): time factors of the wave components by phasor recurrence, and the
cross-beam correction's first heading node (``synthesis.crossbeam_node``)."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _crossbeam_node(sin_beta):
    """sin^2 of the course's heading, or 1/2 within 0.01 of 0 or 1 (``synthesis.crossbeam_node``;
    ``dynamics._kernels_6dof._station_wave`` interpolates on it)."""
    ua = sin_beta * sin_beta
    return 0.5 if ua < 0.01 or ua > 0.99 else ua


@njit(cache=True, nogil=True)
def _trig_table(we, t0, dt, out, j0, shift):
    """Fill ``out`` (nt, 2 nc) with cos(we_n t_j - shift_n) and sin(we_n t_j - shift_n), t_j = t0 +
    (j0 + j) dt (``shift`` (nc,) [rad]: zeros for the plain time factors).

    Each phasor exp(i (we t - shift)) is advanced by the constant rotation exp(i we dt) (one complex
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
                ph = we[n] * (t0 + (j0 + j) * dt) - shift[n]
                cr[n] = np.cos(ph)
                ci[n] = np.sin(ph)
        for n in range(nc):
            out[j, n] = cr[n]
            out[j, nc + n] = ci[n]
            nr = cr[n] * rr[n] - ci[n] * ri[n]
            ci[n] = cr[n] * ri[n] + ci[n] * rr[n]
            cr[n] = nr


@njit(cache=True, nogil=True)
def _line_coefficients(amp, k, phase, xi, uniform, dec, g, out):
    """Fill ``out`` (2 nc, nq npoints), nq = 3 + 4 r, with the coefficients of (eta, S, dS/dxi[, P_j,
    dP_j/dxi, Q_j, dQ_j/dxi for j < r]) at the points ``xi`` [m] of the cos(we t) rows (first nc) and
    sin(we t) rows (last nc) of a line wave table: a cos(k xi - we t + phase) = C cos(we t) + D sin(we t)
    with C = a cos P, D = a sin P, P = k xi + phase; its slope S (C = -a k sin P, D = a k cos P) and
    dS/dxi (C = -a k^2 cos P, D = -a k^2 sin P); P_j = -g sum_n dec[n, j] cos(psi_n) and
    Q_j = -sum_n dec[n, j] sin(psi_n) with their slopes (``dec`` (nc, r): the pressure decay's line
    factors, ``synthesis.decay_factors``; ``g`` [m/s^2]). Columns are point-major: nq j + (0, 1, 2, ...).

    With ``uniform`` (equally spaced points) the phasor exp(i P) is advanced point to point by the
    constant rotation exp(i k h) and reset to the exact value every 32 points, as ``_trig_table``
    does in time; otherwise cos and sin are evaluated at every point. The components are the inner
    loop, so that their independent recurrences overlap (each is a chain of dependent multiplies)."""
    nc = amp.shape[0]
    npt = xi.shape[0]
    nr = dec.shape[1]
    nq = 3 + 4 * nr
    h = xi[1] - xi[0] if npt > 1 else 0.0
    ak = np.empty(nc)
    ak2 = np.empty(nc)
    rr = np.empty(nc)
    ri = np.empty(nc)
    c = np.ones(nc)
    s = np.zeros(nc)
    for n in range(nc):
        ak[n] = amp[n] * k[n]
        ak2[n] = ak[n] * k[n]
        rr[n] = np.cos(k[n] * h)
        ri[n] = np.sin(k[n] * h)
    for j in range(npt):
        if not uniform or (j & 31) == 0:
            for n in range(nc):
                P = k[n] * xi[j] + phase[n]
                c[n] = np.cos(P)
                s[n] = np.sin(P)
        q = nq * j
        for n in range(nc):
            cn = c[n]
            sn = s[n]
            out[n, q] = amp[n] * cn
            out[nc + n, q] = amp[n] * sn
            out[n, q + 1] = -ak[n] * sn
            out[nc + n, q + 1] = ak[n] * cn
            out[n, q + 2] = -ak2[n] * cn
            out[nc + n, q + 2] = -ak2[n] * sn
            for r in range(nr):
                d = dec[n, r]
                gd = g * d
                dk = d * k[n]
                gdk = gd * k[n]
                b = q + 3 + 4 * r
                out[n, b] = -gd * cn  # P = -g d cos psi
                out[nc + n, b] = -gd * sn
                out[n, b + 1] = gdk * sn  # dP/dxi = g d k sin psi
                out[nc + n, b + 1] = -gdk * cn
                out[n, b + 2] = -d * sn  # Q = -d sin psi
                out[nc + n, b + 2] = d * cn
                out[n, b + 3] = -dk * cn  # dQ/dxi = -d k cos psi
                out[nc + n, b + 3] = -dk * sn
            c[n] = cn * rr[n] - sn * ri[n]
            s[n] = cn * ri[n] + sn * rr[n]


@njit(cache=True)
def _equally_spaced(x, rtol):
    """True if every step of ``x`` is within ``rtol`` of its first step (numpy's
    ``allclose(diff(x), x[1] - x[0], rtol, atol=0)``, without its arrays) and ``x`` has more than
    two points."""
    n = x.shape[0]
    if n <= 2:
        return False
    h = x[1] - x[0]
    tol = rtol * abs(h)
    for j in range(1, n):
        if not abs((x[j] - x[j - 1]) - h) <= tol:
            return False
    return True
