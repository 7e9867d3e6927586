"""1-DOF roll with softening restoring in Gaussian excitation: the analytic-grade capsize case.

    phi'' + 2 zeta w0 phi' + w0^2 GZ(phi) / GM = w0^2 e(t)

GZ(phi) is a tabulated restoring curve (the box barge's exact GZ in the validation case), zeta the
linear damping ratio, w0 the natural frequency and e(t) [rad] a stationary Gaussian excitation, the
output of the second-order filter

    e'' + 2 zeta_f w_f e' + w_f^2 e = white noise,   var(e) = sigma_e^2,

whose spectrum S_e(w) ~ 1 / ((w_f^2 - w^2)^2 + (2 zeta_f w_f w)^2) is narrow-banded for small zeta_f
and broad-banded for zeta_f near 1. The filter state (e, e') is sampled exactly (its transition
matrix Phi = expm(A h) and the innovation covariance Q = Sigma - Phi Sigma Phi^T, Sigma the
stationary covariance), so the process has exactly its stationary law at every sample (spacing dt);
between samples e is the cubic-Hermite interpolant of (e, e'). Each record draws its normals from
its own numpy Generator (PCG64, seeded from the master seed, a stream number and the record). Records start from rest and are counted after
a warm-up; capsize is |phi| beyond the capsize angle (the angle of vanishing stability), after
which the motion has no restoring and the record stops.

Cheap (about 10^8 RK4 steps per CPU-minute), so brute force reaches 10^6 simulated hours on this
machine and validates the split-time and extreme-value estimates far beyond any sample.
"""

from __future__ import annotations

import functools
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from stabflow.dynamics._kernels import (_r1_excitation, _r1_perturbed, _r1_record_last, _r1_run, _r1_substep)


@dataclass(frozen=True)
class OneDof:
    """The 1-DOF roll model and its excitation.

    Attributes
    ----------
    w0 : natural roll frequency [rad/s].
    zeta : linear damping ratio [-].
    restoring : GZ / GM on ``0, dphi, 2 dphi, ...`` [-] (odd extension to negative roll).
    dphi : table step [rad].
    cap : capsize angle [rad].
    wf, zf : filter natural frequency [rad/s] and damping ratio [-].
    sigma : standard deviation of the excitation e [rad].
    dt : time step [s].
    warmup : seconds from rest before a record is counted [s].
    duration : counted seconds of a record [s].
    """

    w0: float
    zeta: float
    restoring: np.ndarray
    dphi: float
    cap: float
    wf: float
    zf: float
    sigma: float
    dt: float
    warmup: float
    duration: float

    @property
    def q(self) -> np.ndarray:
        return np.array([self.w0, self.zeta, self.dphi])

    @property
    def nwarm(self) -> int:
        """Grid steps of the warm-up."""
        return int(round(self.warmup / self.dt))

    @property
    def nsteps(self) -> int:
        """Grid steps of a whole record (warm-up + counted)."""
        return self.nwarm + int(round(self.duration / self.dt))

    @property
    def nexc(self) -> int:
        """Excitation samples of a record (spacing dt)."""
        return self.nsteps + 1

    @functools.cached_property
    def filter_matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(Phi, chol(Q), chol(Sigma)) of the excitation filter at spacing dt."""
        A = np.array([[0.0, 1.0], [-self.wf**2, -2.0 * self.zf * self.wf]])
        S = linalg.solve_continuous_lyapunov(A, -np.array([[0.0, 0.0], [0.0, 1.0]]))
        S *= self.sigma**2 / S[0, 0]
        Phi = linalg.expm(A * self.dt)
        Q = S - Phi @ S @ Phi.T
        return Phi, np.linalg.cholesky(0.5 * (Q + Q.T)), np.linalg.cholesky(S)

    def excitation_spectrum(self, w) -> np.ndarray:
        """One-sided spectral density of e [rad^2 s] (integrates to sigma^2 over 0 < w < inf)."""
        w = np.asarray(w, float)
        # |H|^2 of the filter, normalised by its integral over 0 < w < inf, pi / (4 zeta_f w_f^3)
        h2 = 1.0 / ((self.wf**2 - w**2) ** 2 + (2 * self.zf * self.wf * w) ** 2)
        return self.sigma**2 * h2 * 4.0 * self.zf * self.wf**3 / np.pi

    def excitation(self, seed: int) -> np.ndarray:
        """Excitation samples (e [rad], e' [rad/s]) of one record, shape (nexc, 2)."""
        Phi, cq, cs = self.filter_matrices
        out = np.empty((self.nexc, 2))
        _r1_excitation(np.random.default_rng(int(seed)), self.nexc, Phi, cq, cs, out)
        return out

    def record(self, seed: int, exc: np.ndarray | None = None) -> tuple[np.ndarray, int]:
        """(roll [rad], rate [rad/s]) on the grid from rest, shape (nsteps + 1, 2), and the last step
        done (< nsteps: capsized; rows after it are NaN)."""
        exc = self.excitation(seed) if exc is None else exc
        out = np.full((self.nsteps + 1, 2), np.nan)
        last = _r1_run(exc, self.dt, 0, self.nsteps, 0.0, 0.0, self.q, self.restoring, self.cap, out)
        return out, int(last)

    def bruteforce(self, seeds, threads: int = 1, progress: bool = False) -> np.ndarray:
        """Last step of each record from rest (< nsteps: capsized); records run in threads (the
        kernel releases the GIL), each with its own Generator: the result does not depend on threads."""
        from tqdm import tqdm

        Phi, cq, cs = self.filter_matrices
        seeds = np.asarray(seeds)
        last = np.empty(len(seeds), np.int64)
        chunks = np.array_split(np.arange(len(seeds)), max(1, len(seeds) // 16))

        def run(idx):
            exc = np.empty((self.nexc, 2))
            for i in idx:
                last[i] = _r1_record_last(np.random.default_rng(int(seeds[i])), self.nsteps, self.dt, Phi, cq, cs,
                                          self.q, self.restoring, self.cap, exc)
            return len(idx)

        with ThreadPoolExecutor(max_workers=max(1, threads)) as ex:
            for _ in tqdm(ex.map(run, chunks), total=len(chunks), desc="1-DOF brute force", disable=not progress,
                          mininterval=10):
                pass
        return last

    def substep(self, exc: np.ndarray, t0: float, tau: float, x: float, v: float) -> tuple[float, float]:
        """RK4 step of length ``tau`` [s] from time ``t0`` [s] off the grid."""
        return _r1_substep(exc, self.dt, t0, tau, x, v, self.q, self.restoring)

    def perturbed(self, exc, base, base_last, n0, tc, x, v, ret, nmax) -> int:
        """1 capsized, 0 returned to ``base``, -1 neither by step ``nmax`` (see ``_r1_perturbed``)."""
        return int(_r1_perturbed(exc, self.dt, base, base_last, n0, tc, x, v, self.q, self.restoring, self.cap,
                                 ret, nmax))


def record_seeds(master: int, stream: int, records) -> np.ndarray:
    """Seeds of records: 64-bit integers from numpy's SeedSequence of (master, stream, record), so
    streams (brute force, samples) and records are independent."""
    return np.array([np.random.SeedSequence([int(master), int(stream), int(r)]).generate_state(1, np.uint64)[0]
                     for r in np.asarray(records)], np.uint64)


def restoring_table(gz, gm: float, max_deg: float, step_deg: float = 0.1) -> tuple[np.ndarray, float]:
    """Tabulate GZ / GM from a callable ``gz(heel_deg) -> GZ [m]`` on 0..max_deg; returns (table, dphi [rad])."""
    a = np.arange(0.0, max_deg + 0.5 * step_deg, step_deg)
    return np.asarray(gz(a), float) / gm, float(np.radians(step_deg))


def crossing_state(model: OneDof, exc: np.ndarray, states: np.ndarray, n0: int, level: float,
                   iterations: int = 8) -> tuple[float, float, float]:
    """(time [s], roll [rad], rate [rad/s]) at the instant roll crosses ``level`` [rad] between grid
    steps n0 and n0 + 1: an RK4 sub-step from step n0 whose length is refined by Newton's method on
    roll(tau) - level (start: linear interpolation)."""
    x0, v0 = states[n0]
    x1 = states[n0 + 1, 0]
    tau = model.dt * (level - x0) / (x1 - x0) if x1 != x0 else 0.0
    x, v = x0, v0
    for _ in range(iterations):
        tau = min(max(tau, 0.0), model.dt)
        x, v = model.substep(exc, n0 * model.dt, tau, x0, v0)
        if abs(x - level) <= 1e-13 or v == 0.0:
            break
        tau -= (x - level) / v
    return n0 * model.dt + tau, x, v


def critical_perturbation(model: OneDof, exc: np.ndarray, states: np.ndarray, last: int, n0: int, level: float,
                          side: int, next_crossing: int, dmax: float, tol: float, ret: float, follow: int):
    """Critical roll-rate perturbation [rad/s] of one crossing (paper 003, motion perturbation method).

    The exact state at the crossing instant is perturbed by ``side * delta`` in roll rate and followed
    until it capsizes or returns to the unperturbed solution (distance sqrt(droll^2 + (drate / w0)^2)
    below ``ret`` times its initial value |delta| / w0), at most ``follow`` grid steps (then it counts
    as not capsized and is reported). A run that returns shares the unperturbed outcome: capsized when
    the unperturbed record capsizes before its next crossing of the threshold (``next_crossing``:
    that step, or a large number), which is also the outcome at delta = 0. Bisection to ``tol``
    (``splittime.bisect_critical``): in [0, dmax] when the unperturbed run survives (inf when dmax
    does not capsize), in [-|rate|, 0] when it capsizes (the critical rate is below the crossing's).
    Returns (delta [rad/s], runs, crossing time [s], roll rate at the crossing [rad/s], runs that
    reached ``follow`` without an answer)."""
    from stabflow.statistics.splittime import bisect_critical

    tc, xc, vc = crossing_state(model, exc, states, n0, level)
    undecided = [0]
    nmax = min(n0 + 1 + follow, model.nsteps)
    base_capsizes = bool(last < model.nsteps and last <= next_crossing)

    def capsizes(d):
        if d == 0.0:
            return base_capsizes
        out = model.perturbed(exc, states, last, n0, tc, xc, vc + side * d, ret * abs(d) / model.w0, nmax)
        undecided[0] += out < 0
        return out > 0 or (out == 0 and base_capsizes)

    delta, runs = bisect_critical(capsizes, dmax, tol, dmin=-abs(vc))
    return delta, runs, tc, vc, undecided[0]
