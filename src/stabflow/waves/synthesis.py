"""Incident-wave kinematics at the stations of a ship moving at constant speed and heading.

Long-crested linear waves: component n has amplitude a_n [m], frequency w_n [rad/s], wave number
k_n = w_n^2 / g [rad/m] and phase e_n. Heading beta: 0 = following seas (waves travel along +x with
the ship), 90 deg = waves travelling to port (beam seas from starboard), 180 deg = head seas.
Station i sits at earth (X, Y) = (U t + x_i, 0), so psi_n = k_n x_i cos(beta) - (w_n - k_n U cos beta) t + e_n
(encounter frequency) and

    eta = sum a cos(psi),  eta_x = -sum a k cos(beta) sin(psi),  eta_y = -sum a k sin(beta) sin(psi).

d2(phi0)/dz dt at the surface is -g sum k a cos(psi) (Wheeler stretching). Its linear extrapolation
over the section depth (paper 000 eq. 4) grows without bound for short waves; stabflow uses it
averaged over the section's calm-water area with the exact exponential decay,
F_i(k_n) = (1 / A_i) int e^(k_n z) dA (:class:`stabflow.dynamics.model.SectionDecay`; for a
rectangle of draft T, (1 - exp(-k T)) / (k T)): F -> 1 for long waves (the seed's term) and the
term stays bounded for short ones; it makes the section's linear FK heave force exact.
"""

from __future__ import annotations

import contextlib
import functools
import os
import threading
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from stabflow.waves._kernels import _crossbeam_node, _equally_spaced, _line_coefficients, _trig_table

from stabflow.constants import G

#: point-coefficient arrays a :class:`LineWaves` keeps (the oldest goes first)
OFFSET_TABLES = 4

#: memory of one block of time factors in :func:`_time_series_table` [bytes]
TRIG_BLOCK_BYTES = 64 * 2**20


def _time_series_table(we, times, cols, dtype) -> np.ndarray:
    """sum_n [C_pn cos(we_n t) + D_pn sin(we_n t)] for every column p of ``cols`` (a list of (C, D)
    pairs, each (npoints, nc)): one matrix product of the time factors (nt, 2 nc) with the
    coefficients (2 nc, npoints nq) → (nt, npoints, nq) in ``dtype``."""
    nq = len(cols)
    npt, nc = cols[0][0].shape
    coef = np.empty((2 * nc, npt, nq))
    for q, (c, d) in enumerate(cols):
        coef[:nc, :, q] = c.T
        coef[nc:, :, q] = d.T
    return _time_series_product(we, times, coef.reshape(2 * nc, npt * nq).astype(dtype), nq)


def _time_series_product(we, times, coef, nq, spaced: bool = False, shift=None) -> np.ndarray:
    """The product of :func:`_time_series_table` with the coefficients ``coef`` (2 nc, npoints nq)
    already assembled (in the table's dtype) → (nt, npoints, nq); ``spaced``: the caller's times
    are equally spaced by construction (not checked again); ``shift`` (nc,) [rad]: the time factors
    are cos(we t - shift) and sin(we t - shift) (None: zeros)."""
    times = np.asarray(times, float)
    t0 = times[0] if len(times) else 0.0
    dt = times[1] - times[0] if len(times) > 1 else 0.0
    if not spaced and len(times) > 2 and not np.allclose(np.diff(times), dt, rtol=1e-9, atol=1e-12):
        raise ValueError("times must be equally spaced")
    nc = len(we)
    npt = coef.shape[1] // nq
    dtype = coef.dtype
    shift = np.zeros(nc) if shift is None else np.asarray(shift, float)
    out = np.empty((len(times), npt * nq), dtype=dtype)
    # in blocks of time rows (multiples of the phasor reset interval, so the values do not depend on
    # the block size): the time factors of thousands of components over a 3-hour record would take
    # gigabytes at once
    block = max(256, (TRIG_BLOCK_BYTES // max(1, 2 * nc * np.dtype(dtype).itemsize)) // 256 * 256)
    trig = np.empty((min(block, len(times)), 2 * nc), dtype=dtype)
    with one_blas_thread():
        for j0 in range(0, len(times), block):
            m = min(block, len(times) - j0)
            _trig_table(we, t0, dt, trig[:m], j0, shift)
            np.matmul(trig[:m], coef, out=out[j0: j0 + m])
    return out.reshape(len(times), npt, nq)


@contextlib.contextmanager
def one_blas_thread():
    """Context in which BLAS runs on one thread. A BLAS product's rounding depends on how many
    threads share it (OpenBLAS splits the sums differently), so the wave tables would differ in the
    last bits between a job given one thread and one given eight (Snakemake exports the rule's
    threads to OPENBLAS/OMP_NUM_THREADS): same config and seed must give the same files.

    The limit is process-wide, so the context counts its users: the first to enter sets it and the
    last to leave restores it. (Restoring on every exit let one Python thread of the split-time
    step lift the limit while another was still in its product: the SLURM and local files differed.)
    Both are done on one helper thread: OpenBLAS (0.3.30 and 0.3.31 of the scipy and numpy wheels)
    can ignore a raise of its thread count from a thread other than the one that lowered it, so a
    limit set by one Python thread and restored by another stayed at one thread (found by CI).
    """
    global _blas_users, _blas_limiter
    with _blas_lock:
        if _blas_users == 0:
            _blas_limiter = _on_control_thread(lambda: _blas_controller().limit(limits=1, user_api="blas"))
        _blas_users += 1
    try:
        yield
    finally:
        with _blas_lock:
            _blas_users -= 1
            if _blas_users == 0:
                _on_control_thread(_blas_limiter.restore_original_limits)
                _blas_limiter = None


_blas_lock = threading.Lock()
_blas_users = 0
_blas_limiter = None


@functools.lru_cache(maxsize=1)
def _blas_control() -> ThreadPoolExecutor:
    """The one thread that sets and restores the BLAS limit (see :func:`one_blas_thread`)."""
    return ThreadPoolExecutor(max_workers=1, thread_name_prefix="stabflow-blas-limit")


def _on_control_thread(fn):
    """``fn()`` on the helper thread, or in the calling thread where none can run: at interpreter
    shutdown (an atexit handler, a thread still inside the context when the main thread returned)
    no new work is accepted, and the limit is then set or restored as well as this thread can."""
    try:
        future = _blas_control().submit(fn)
    except RuntimeError:
        return fn()
    return future.result()


def _after_fork_in_child():
    """A forked child has none of the parent's threads (the helper's included) and a copy of the lock
    that another thread may have held: start afresh. The child's BLAS keeps the parent's count; its
    first entry records that count as the one to restore."""
    global _blas_lock, _blas_users, _blas_limiter
    _blas_lock, _blas_users, _blas_limiter = threading.Lock(), 0, None
    _blas_control.cache_clear()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_after_fork_in_child)


@functools.lru_cache(maxsize=1)
def _blas_controller():
    """The BLAS libraries loaded in this process, found once (threadpoolctl scans the process's
    libraries, milliseconds per scan: too slow for every wave table)."""
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def encounter_frequency(omega, speed: float, heading_deg: float):
    """Encounter frequency [rad/s] of deep-water waves of frequency ``omega`` [rad/s] for a ship at
    ``speed`` [m/s], wave heading [degree] (0 following): w - k U cos(beta), k = w^2 / g (signed)."""
    omega = np.asarray(omega, float)
    return omega - omega**2 / G * speed * np.cos(np.radians(heading_deg))


def station_wave_table(amp, omega, phase, xs, heading_deg, speed, times, decay=None,
                       dtype=np.float64, curvature: bool = False) -> np.ndarray:
    """(nt, nst, nq) table of the stations' wave (eta, S[, the pressure decay's twelve columns][, eta_xixi]: the
    layouts of ``dynamics._kernels``) at stations ``xs`` and equally spaced
    ``times``.

    S is the slope along the direction of propagation (eta_x = cos(beta) S, eta_y = sin(beta) S).
    ``decay`` (:class:`stabflow.dynamics.model.SectionDecay`: the sections' area averages F_i(k),
    Z_i(k), Y_i(k) of e^(k z), (z - z_c) e^(k z) and y^2 e^(k z), and the cross-beam correction X_i(k),
    interpolated on its wave-number grid, ``SectionDecay.tabulated``) adds the pressure's decay with
    depth as twelve columns (nq = 14, ``dynamics._kernels``'s layouts): the d2phi/dzdt term
    -g sum_n a_n k_n F_i(k_n) cos psi_n, the area-averaged slope S_h = -sum a k F sin psi, its
    moment about the centroid S_hz = -sum a k Z sin psi [m], T_yy = sum a k^2 Y sin psi [m] and
    U_yy = -sum a k^2 Y cos psi [m], then the heeled section's six terms H_1 ... H_6
    (``dynamics._kernels``) and the cross-beam correction W = sum a X cos psi [m^2]
    (``SectionDecay.moments``' X at this heading), 14 columns; S_h, S_hz, T_yy, U_yy and the heeled
    H_2, H_3 with their cross-beam remainders (``SectionDecay.moments``' D: F + dF, Z + dZ, Y + dY_r,
    Y + dY_y, w_2 + (X + dF_y) / k, w_3 - Gamma_B / k; none with ``curvature``); None leaves it out (nq = 2). ``curvature`` adds the second derivative along the direction of
    propagation eta_xixi [1/m] for the curved waterline across each section
    (``waterline="curved"``, the last column: nq = 4, the dphi_zt column then zero, or 15 with
    ``decay``). Each quantity is sum_n [C_in cos(we_n t) + D_in sin(we_n t)], so
    the table is one matrix product of the time factors (nt, 2 nc) with the station coefficients
    (2 nc, nst nq), in ``dtype`` (float32 halves the cost of long ensembles).
    """
    amp = np.asarray(amp, dtype=float)
    omega = np.asarray(omega, float)
    phase = np.asarray(phase, float)
    xs = np.asarray(xs, float)
    k = omega**2 / G
    cb = np.cos(np.radians(heading_deg))
    we = encounter_frequency(omega, speed, heading_deg)
    # psi = P - we t with P = k cos(beta) x + e: cos psi = cos P cos(we t) + sin P sin(we t)
    P = (k * cb)[None, :] * xs[:, None] + phase[None, :]
    cP, sP = np.cos(P), np.sin(P)
    ak = amp * k
    cols = [(amp * cP, amp * sP), (-ak * sP, ak * cP)]  # eta = sum a cos psi, S = -sum a k sin psi
    if decay is not None:
        # dphi_zt = -g sum a k F cos psi, S_h = -sum a k F sin psi, S_hz = -sum a k Z sin psi,
        # T_yy = sum a k^2 Y sin psi, U_yy = -sum a k^2 Y cos psi
        F, Z, Y, X, (dF, dZ, dYr, dYy, gB, xf) = decay.tabulated(k, np.sin(np.radians(heading_deg)))
        if curvature:
            # the curved waterline's parabola carries a part of the cross-beam phase (``_kernels._fkhs``)
            dF = dZ = dYr = dYy = gB = xf = 0.0
        Fh, Zh, Yr, Yy = F + dF, Z + dZ, Y + dYr, Y + dYy  # the cross-beam remainders (``SectionDecay.moments``)
        cols.append((-G * ak * F * cP, -G * ak * F * sP))
        cols.append((-ak * Fh * sP, ak * Fh * cP))
        cols.append((-ak * Zh * sP, ak * Zh * cP))
        cols.append((ak * k * Yr * sP, -ak * k * Yr * cP))
        cols.append((-ak * k * Yy * cP, -ak * k * Yy * sP))  # U_yy = -sum a k^2 Y cos psi
        # the heeled section's terms (``SectionDecay.heel_weights``): sum a k w cos psi, then sin psi
        hw = list(decay.heel_weights(k, (F, Z, Y)))
        # the heeled section's cross-beam remainders (``SectionDecay.moments``' D)
        hw[1], hw[2] = hw[1] + xf / k, hw[2] - gB / k
        for w in hw[:3]:
            cols.append((ak * w * cP, ak * w * sP))
        for w in hw[3:]:
            cols.append((ak * w * sP, -ak * w * cP))
        cols.append((amp * X * cP, amp * X * sP))  # W = sum a X cos psi, the cross-beam correction
    elif curvature:
        cols.append((np.zeros_like(cP), np.zeros_like(sP)))
    if curvature:
        cols.append((-ak * k * cP, -ak * k * sP))  # eta_xixi = -sum a k^2 cos psi
    return _time_series_table(we, times, cols, dtype)


#: the pressure-decay terms of a line table (:class:`LineWaves` with ``decay``) are a rank-r
#: factorisation whose error's standard deviation (random phases) is at most this fraction of the
#: term's at every station, for each of F and Z (:func:`decay_factors`)
DECAY_RANK_TOLERANCE = 0.01
#: the largest rank (four table columns each)
DECAY_RANK_MAX = 6
#: the station weights' blocks of :func:`decay_factors`: WF, WZ, WY of a_n k_n times F, Z, k Y
#: (the upright terms), then the heeled section's six (``SectionDecay.heel_weights``), WX_a,
#: WX_b of a_n k_n times X / k at the two cross-beam nodes (:func:`crossbeam_node`) and the
#: remainders of the horizontal terms there, each at the two nodes: a_n k_n times dF, dZ, k dY_r
#: and k dY_y, and of the heeled section's W_2 and W_3: a_n (X + dF_y) and -a_n Gamma_B
#: (``SectionDecay.moments``' D)
DECAY_BLOCKS = 23
#: the blocks of the remainders dF, dZ, dY_r, dY_y, X + dF_y and -Gamma_B at the first node (the
#: second node's follow each) and the block each corrects (WF, WZ, WY, WY, W_2, W_3)
DECAY_REMAINDER_BLOCKS = ((11, 0), (13, 1), (15, 2), (17, 2), (19, 4), (21, 5))


def crossbeam_node(sin_beta: float) -> float:
    """The first of the two nodes in sin^2 of the relative wave heading (the second is 1, beam
    waves) at which :func:`decay_factors` gives the cross-beam correction X of
    ``SectionDecay.moments``: sin^2 of the course's heading, or 1/2 where that is within 0.01 of 0
    or 1. A 6-DOF record's ship yaws, and X depends on the relative heading (about as its sine
    squared in long waves), so ``_kernels_6dof._station_wave`` interpolates X in u = sin^2 on the
    nodes 0 (where X = 0), u_a and 1 (quadratic; exact at the course's heading, so the held-yaw
    case equals the 3-DOF model; at u = 0.0076 between nodes 0.25 and 1 the interpolation error is
    about 2.7e-4 (k b / 2)^4 of X). The kernel calls the same function (``_kernels._crossbeam_node``)."""
    return float(_crossbeam_node(float(sin_beta)))


def decay_factors(amp, k, decay, sin_beta: float = 0.0):
    """The stations' pressure-decay terms (``dynamics._kernels``'s layouts: dphi_zt, S_h, S_hz, T_yy, U_yy)
    as sums of r products of a station weight and a line quantity.

    With F_i(k), Z_i(k), Y_i(k) of :class:`stabflow.dynamics.model.SectionDecay` ``decay`` (interpolated
    on its wave-number grid, ``SectionDecay.tabulated``), the
    terms -g sum_n a_n k_n F_i(k_n) cos psi_n, -sum_n a_n k_n F_i(k_n) sin psi_n,
    -sum_n a_n k_n Z_i(k_n) sin psi_n, sum_n a_n k_n^2 Y_i(k_n) sin psi_n and
    -sum_n a_n k_n^2 Y_i(k_n) cos psi_n need
    a_n k_n (F_i, Z_i, k_n Y_i)(k_n) ~ sum_j (WF_ij, WZ_ij, WY_ij) C_nj, and the heeled section's
    six terms a_n k_n w_i(k_n) ~ sum_j W_ij C_nj (w of ``SectionDecay.heel_weights``) and the
    cross-beam correction a_n X_i(k_n) ~ sum_j WX_ij C_nj (X of ``SectionDecay.moments`` at the two
    nodes of :func:`crossbeam_node` for the course's heading sine ``sin_beta``), and at the same
    nodes the remainders of the horizontal terms, a_n k_n (dF, dZ, k dY_r, k dY_y), and of the
    heeled W_2 and W_3, a_n (X + dF_y) and -a_n Gamma_B (D of ``SectionDecay.moments``;
    ``DECAY_REMAINDER_BLOCKS``): one
    truncated singular value decomposition of the (component, ``DECAY_BLOCKS`` x station) matrix
    of the twenty-three, each station's column scaled to unit norm, the cross-beam columns to the norm of
    the term they correct where that is larger (X: the planar waterline's linear vertical force
    a_n (b_i - k_n A_i F_i); the remainders: their upright block's column), so that a correction is
    carried to 1 % of the station's term, not of itself. Its r is the least for which every column's residual norm over the components (the
    standard deviation of the term's error over random phases) is within ``DECAY_RANK_TOLERANCE`` of
    the column's scale, at most ``DECAY_RANK_MAX`` (a RuntimeWarning names the error left if that
    is not enough). Returns the line factors C (nc, r) and the station
    weights (nst, ``DECAY_BLOCKS`` r): WF, WZ, WY, the six heeled ones, WX_a, WX_b and the
    remainders' twelve (WdF_a, WdF_b, WdZ_a, WdZ_b, WdYr_a, WdYr_b, WdYy_a, WdYy_b, then W_2's and W_3's
    at the two nodes: a_n (X + dF_y) and -a_n Gamma_B), each factor's sign
    chosen so that its weights WF sum to >= 0 (one regular wave's weights then do not depend on
    its amplitude's sign)."""
    M, norm, full = decay_matrix(amp, k, decay, sin_beta)
    nst = len(decay.total)
    live = norm > 0
    Mn = M / np.where(live, norm, 1.0)
    # the leading singular triplets from the eigenvectors of the smaller Gram matrix (a fifth of a
    # full SVD's time for a 220-component record on 81 stations; only the r <= DECAY_RANK_MAX leading
    # ones are kept, far above the Gram matrix's round-off)
    nc, ncol = Mn.shape
    with one_blas_thread():  # BLAS products (their rounding depends on the thread count)
        lam, E = np.linalg.eigh(Mn @ Mn.T if nc <= ncol else Mn.T @ Mn)
        lam, E = np.maximum(lam[::-1], 0.0), E[:, ::-1]
        S = np.sqrt(lam)
        # rows of S_j V_j^T: the kept part of each column is the sum of their squares
        SVt = E[:, :DECAY_RANK_MAX].T @ Mn if nc <= ncol else E[:, :DECAY_RANK_MAX].T * S[:DECAY_RANK_MAX, None]
    r = 0
    if np.any(live):
        kept = np.zeros(M.shape[1])
        for r in range(1, min(DECAY_RANK_MAX, len(S)) + 1):
            kept += SVt[r - 1] ** 2
            if np.all(full[live] - kept[live] <= DECAY_RANK_TOLERANCE**2):
                break
        worst = float(np.sqrt(max(np.max(full[live] - kept[live]), 0.0)))
        if worst > DECAY_RANK_TOLERANCE and r < len(S):
            warnings.warn(f"pressure-decay factorisation: rank {r} (DECAY_RANK_MAX) leaves a {100 * worst:.2g} % "
                          f"error at its worst station, above DECAY_RANK_TOLERANCE {100 * DECAY_RANK_TOLERANCE:g} %",
                          RuntimeWarning, stacklevel=2)
    # C = U_r S_r and the weights V_r scaled back by the columns' norms: C W^T = U_r S_r V_r^T diag(norm)
    safe = np.where(S[:r] > 0, S[:r], 1.0)
    if nc <= ncol:
        C = E[:, :r] * S[:r]
        W = (SVt[:r] / safe[:, None]).T * norm[:, None]
    else:
        with one_blas_thread():
            C = Mn @ E[:, :r]
        W = E[:, :r] * norm[:, None]
    flip = np.where(W[:nst].sum(axis=0) < 0, -1.0, 1.0)
    return C * flip, np.ascontiguousarray(np.concatenate([W[b * nst:(b + 1) * nst] * flip
                                                          for b in range(DECAY_BLOCKS)], axis=1))


def decay_matrix(amp, k, decay, sin_beta: float = 0.0):
    """The (component, ``DECAY_BLOCKS`` x station) matrix M that :func:`decay_factors` factorises,
    its columns' scales (their norms; for the cross-beam blocks at least the norm of the planar
    vertical force a_n (b_i - k_n A_i F_i)) and the squared norm of each scaled column (1 but where
    the cross-beam scale is the larger)."""
    amp = np.asarray(amp, float)
    k = np.asarray(k, float)
    ua = crossbeam_node(float(sin_beta))
    F, Z, Y, (Xa, Xb), (Da, Db) = decay.tabulated(k, (np.sqrt(ua), 1.0))  # (nst, nc) each
    nst = F.shape[0]
    ak = (amp * k)[:, None]
    kk = k[None, :]
    # the remainders in the order of DECAY_REMAINDER_BLOCKS and the units of the blocks they correct
    # (a_n k_n times these): dF, dZ, k dY_r, k dY_y, then W_2's (X + dF_y) / k (D[5]) and W_3's
    # -Gamma_B / k (D[4])
    unit = ((0, lambda d: d), (1, lambda d: d), (2, lambda d: kk * d), (3, lambda d: kk * d), (5, lambda d: d / kk),
            (4, lambda d: -d / kk))
    remainders = [f(d) for q, f in unit for d in (Da[q], Db[q])]
    M = np.concatenate([F, Z, Y * kk, *decay.heel_weights(k, (F, Z, Y)), Xa / kk, Xb / kk, *remainders]).T * ak
    norm = np.sqrt(np.sum(M**2, axis=0))
    full = np.ones_like(norm)
    vertical = np.sqrt(np.sum((amp[:, None] * (decay.waterline_breadth[None, :] - k[:, None] * decay.total[None, :]
                                                * F.T)) ** 2, axis=0))
    # each cross-beam block's scale: at least that of the term it corrects (the planar vertical force
    # for X, the upright block for the remainders)
    scales = [(9, vertical), (10, vertical)]
    for b, base in DECAY_REMAINDER_BLOCKS:
        scales += [(b, norm[base * nst:(base + 1) * nst]), (b + 1, norm[base * nst:(base + 1) * nst])]
    for b, scale in scales:
        cols = slice(b * nst, (b + 1) * nst)
        own = norm[cols].copy()
        norm[cols] = np.maximum(own, scale)
        full[cols] = np.where(norm[cols] > 0, (own / np.where(norm[cols] > 0, norm[cols], 1.0)) ** 2, 1.0)
    return M, norm, full


class LineWaves:
    """A record's wave components ready for its line tables (:func:`line_wave_table`), one chunk
    after another (the 6-DOF records, ``dynamics.manoeuvring.run_six_dof``): the wave numbers and
    encounter frequencies are found once.

    Parameters
    ----------
    amp, omega, phase : array_like
        Amplitudes [m], frequencies [rad/s] and phases [rad] of the components.
    heading_deg : float
        Wave heading [degree] (0 following).
    speed : float
        Speed of the frame along x [m/s].
    decay : SectionDecay, optional
        The ship's sections' pressure decay (:class:`stabflow.dynamics.model.SectionDecay`): the
        tables then carry r = ``decay_coef.shape[1]`` groups of four columns (:func:`decay_factors`),
        P_j = -g sum_n C_nj cos psi_n, its slope dP_j/dxi, Q_j = -sum_n C_nj sin psi_n and dQ_j/dxi;
        at station i, dphi_zt = sum_j WF_ij P_j, S_h = sum_j WF'_ij Q_j, S_hz = sum_j WZ'_ij Q_j,
        T_yy = -sum_j WY_r,ij Q_j and U_yy = sum_j WY_y,ij P_j / g, the heeled section's terms and the
        cross-beam correction W = -sum_j (L_a WX_a,ij + L_b WX_b,ij) P_j / g (the nodes' weights at the
        instantaneous relative heading, :func:`crossbeam_node`), where WF' = WF + L_a WdF_a + L_b WdF_b
        and likewise WZ', WY_r and WY_y (the horizontal terms' cross-beam remainders), with
        ``decay_weights`` (nst, ``DECAY_BLOCKS`` r) = (WF, WZ, WY, W_1 ... W_6, WX_a, WX_b, WdF_a,
        WdF_b, WdZ_a, WdZ_b, WdYr_a, WdYr_b, WdYy_a, WdYy_b, W2_a, W2_b, W3_a, W3_b; the heeled W_2 and
        W_3 take their cross-beam remainders the same way).
    """

    def __init__(self, amp, omega, phase, heading_deg: float, speed: float, decay=None):
        self.amp = np.asarray(amp, dtype=float)
        self.omega = np.asarray(omega, float)
        self.phase = np.asarray(phase, float)
        self.heading_deg = heading_deg
        self.speed = speed
        self.k = self.omega**2 / G
        self.we = encounter_frequency(self.omega, speed, heading_deg)
        if decay is not None and len(self.amp):
            self.decay_coef, self.decay_weights = decay_factors(self.amp, self.k, decay,
                                                                np.sin(np.radians(heading_deg)))
        else:
            self.decay_coef = np.zeros((len(self.amp), 0))
            self.decay_weights = np.zeros((0 if decay is None else len(decay.total), 0))
        self._offsets = {}  # the points' coefficients of equally spaced tables by (count, spacing, dtype)

    @property
    def columns(self) -> int:
        """Columns of a table: eta, S, dS/dxi and the decay terms' groups of four."""
        return 3 + 4 * self.decay_coef.shape[1]

    def table(self, xi, times, dtype=np.float64, drift: float = 0.0, uniform: bool | None = None,
              spaced: bool = False, spacing: float | None = None) -> np.ndarray:
        """(nt, npoints, columns) table of (eta, S, dS/dxi[, P_1, dP_1/dxi, Q_1, dQ_1/dxi, ...]) at the points ``xi`` [m]
        (moving along xi at ``drift`` [m/s]) at ``times`` [s], as :func:`line_wave_table`; ``uniform`` (points equally
        spaced; None: found here) and ``spaced`` (times equally spaced, not checked) spare a
        caller who builds them so the checks. ``spacing`` [m]: the points are xi[0] + j ``spacing`` (the
        caller's construction, not checked; the 6-DOF records' chunks): their coefficients are then
        the record's, found once for each point count and kept."""
        xi = np.asarray(xi, float)
        if uniform is None:
            uniform = _equally_spaced(xi, 1e-12)
        we = self.we - self.k * drift
        t_first = float(times[0]) if len(times) else 0.0
        nq = self.columns
        phase = self.phase - self.k * drift * t_first
        if spacing is None or len(xi) < 2:
            coef = np.empty((2 * len(self.amp), nq * len(xi)), dtype=dtype)
            _line_coefficients(self.amp, self.k, phase, xi, uniform, self.decay_coef, G, coef)
            return _time_series_product(we, times, coef, nq, spaced=spaced)
        # equally spaced points xi_0 + j h (the 6-DOF tables): a cos(k (xi_0 + j h) - we t + phase) =
        # a cos(k j h - (we t - k xi_0 - phase)), so the points' coefficients at the offsets j h are
        # the record's, found once for each (count, spacing), and the chunk's start, drift and the
        # components' phases shift the time factors instead (nc values a chunk, not nc x npoints x columns)
        key = (len(xi), float(spacing), np.dtype(dtype).str)
        coef = self._offsets.get(key)
        if coef is None:
            coef = np.empty((2 * len(self.amp), nq * len(xi)), dtype=dtype)
            _line_coefficients(self.amp, self.k, np.zeros_like(self.k), key[1] * np.arange(len(xi)), True,
                               self.decay_coef, G, coef)
            if len(self._offsets) >= OFFSET_TABLES:  # a record's chunks use one or two counts
                self._offsets.pop(next(iter(self._offsets)))
            self._offsets[key] = coef
        return _time_series_product(we, times, coef, nq, spaced=spaced, shift=self.k * float(xi[0]) + phase)


def line_wave_table(amp, omega, phase, xi, heading_deg, speed, times, dtype=np.float64,
                    drift: float = 0.0) -> np.ndarray:
    """(nt, npoints, 3) table of (eta, S, dS/dxi) at the points ``xi`` [m] of the
    propagation coordinate xi = X cos(beta) + Y sin(beta) of the frame moving with ``speed`` [m/s]
    along x, at equally spaced ``times``; with ``drift`` [m/s] the points move along xi, point j
    being at xi_j + drift (t - times[0]) at time t (a line that follows the ship's drift along the
    waves needs only the ship's length: a cos(k xi - we t + phase) is then a cos(k xi_j - (we - k
    drift) t + phase - k drift times[0])).

    Long-crested waves depend on (X, Y) only through xi, so this one line of points serves stations
    anywhere in the horizontal plane (6-DOF: the stations move with surge, sway and yaw); the kernel
    interpolates eta with its slope S and S with dS/dxi by cubic Hermite polynomials. A station at
    X = x_i on the ship's axis (Y = 0) has xi = x_i cos(beta): the values equal
    :func:`station_wave_table`'s there (dS/dxi = -sum a k^2 cos psi).
    """
    return LineWaves(amp, omega, phase, heading_deg, speed).table(xi, times, dtype, drift)


def regular(height: float, wavelength: float):
    """One regular component (amp, omega, phase) for height H [m] and length lambda [m]."""
    k = 2 * np.pi / wavelength
    return np.array([0.5 * height]), np.array([np.sqrt(G * k)]), np.array([0.0])
