"""1-DOF roll in Gaussian excitation: the excitation's law, the free period, the separatrix found by
the motion-perturbation bisection, and reproducible brute force."""

import numpy as np
import pytest
from scipy import integrate

from stabflow.dynamics._kernels import _r1_run
from stabflow.dynamics.one_dof import OneDof, critical_perturbation, crossing_state, record_seeds, restoring_table


def _softening(max_deg=60.0):
    """GZ / GM = sin(phi) (1 - (phi / 40 deg)^2)-like softening curve vanishing at 40 deg."""
    phiv = np.radians(40.0)
    return restoring_table(lambda a: np.radians(a) * (1 - (np.radians(a) / phiv) ** 2), 1.0, max_deg, 0.05)


def _model(sigma=np.radians(1.0), zeta=0.05, zf=0.1, duration=3600.0):
    tab, dphi = _softening()
    return OneDof(w0=0.5, zeta=zeta, restoring=tab, dphi=dphi, cap=np.radians(40.0), wf=0.5, zf=zf, sigma=sigma,
                  dt=2 * np.pi / 0.5 / 20, warmup=200.0, duration=duration)


def test_excitation_has_the_filters_stationary_law():
    """Variance sigma^2 from the first sample on, lag correlations of the exact transition
    (Phi^k Sigma)[0, 0] / sigma^2 (1e5 samples: within 0.02), and the spectrum integrates to sigma^2."""
    m = _model(duration=1e5 * 12.566 / 20)
    e = m.excitation(7)[:, 0]
    assert np.std(e) == pytest.approx(m.sigma, rel=0.05)
    Phi, _, cs = m.filter_matrices
    S = cs @ cs.T
    for k in (1, 5, 20):
        exact = (np.linalg.matrix_power(Phi, k) @ S)[0, 0] / S[0, 0]
        assert np.corrcoef(e[:-k], e[k:])[0, 1] == pytest.approx(exact, abs=0.02)
    assert integrate.quad(m.excitation_spectrum, 0, np.inf, limit=200)[0] == pytest.approx(m.sigma**2, rel=1e-6)
    # first samples across records: stationary from the start (no warm-up transient in the excitation)
    first = np.array([m.excitation(s)[0, 0] for s in record_seeds(1, 0, range(400))])
    assert np.std(first) == pytest.approx(m.sigma, rel=0.15)


def test_small_free_roll_has_the_natural_period():
    """Unforced, undamped, released at 0.5 deg: period 2 pi / w0 within 1e-3 (RK4, 20 steps a period)."""
    m = _model(zeta=0.0)
    n = 2000
    out = np.empty((n + 1, 2))
    _r1_run(np.zeros((n + 2, 2)), m.dt, 0, n, np.radians(0.5), 0.0, m.q, m.restoring, m.cap, out)
    x = out[:, 0]
    up = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    tz = (up + x[up] / (x[up] - x[up + 1])) * m.dt
    assert np.mean(np.diff(tz)) == pytest.approx(2 * np.pi / m.w0, rel=1e-3)


def test_critical_perturbation_is_the_separatrix_of_the_unforced_oscillator():
    """Unforced and undamped, the motion capsizes from a crossing of 20 deg when its energy exceeds
    the barrier's: phidot_cr = w0 sqrt(2 (V(40 deg) - V(20 deg))), V = int GZ / GM dphi. The exact
    crossing state and the bisection on the perturbation (runs followed up to 40 periods) give it
    within the tolerance plus the RK4 error (1e-3 rad/s); an unperturbed run above the barrier gives
    a negative perturbation to the same critical rate."""
    m = _model(zeta=0.0, sigma=0.0)
    phiv, thr = np.radians(40.0), np.radians(20.0)
    V = lambda p: p**2 / 2 - p**4 / (4 * phiv**2)  # noqa: E731
    crit = m.w0 * np.sqrt(2 * (V(phiv) - V(thr)))
    exc = np.zeros((m.nsteps + 2, 2))
    for energy, sign in ((0.6, 1), (1.2, -1)):
        v0 = m.w0 * np.sqrt(2 * energy * V(phiv))
        states = np.full((m.nsteps + 1, 2), np.nan)
        last = _r1_run(exc, m.dt, 0, m.nsteps, 0.0, v0, m.q, m.restoring, m.cap, states)
        n0 = int(np.nonzero((states[:-1, 0] < thr) & (states[1:, 0] >= thr))[0][0])
        tc, xc, vc = crossing_state(m, exc, states, n0, thr)
        assert xc == pytest.approx(thr, abs=1e-12)
        d, runs, tc2, vc2, und = critical_perturbation(m, exc, states, last, n0, thr, 1, 10**9, np.radians(30.0),
                                                       1e-5, 0.01, int(40 * 20))
        assert np.sign(d) == sign and vc2 + d == pytest.approx(crit, abs=1e-3)


def test_bruteforce_is_reproducible_and_thread_independent():
    """The last step of each record does not depend on the threads and equals the record's own run."""
    m = _model(sigma=np.radians(2.0), duration=600.0)
    seeds = record_seeds(3, 0, range(40))
    a = m.bruteforce(seeds, threads=1)
    b = m.bruteforce(seeds, threads=2)
    assert np.array_equal(a, b)
    assert (a < m.nsteps).any() and (a == m.nsteps).any()  # some capsize, some survive
    for s, last in zip(seeds[:10], a[:10]):
        assert m.record(int(s))[1] == last
    # a sub-step of a whole step is the grid step (the Hermite excitation passes through the samples)
    exc = m.excitation(int(seeds[0]))
    st, _ = m.record(int(seeds[0]), exc)
    k = 57
    x, v = m.substep(exc, k * m.dt, m.dt, *st[k])
    assert x == pytest.approx(st[k + 1, 0], abs=1e-12) and v == pytest.approx(st[k + 1, 1], abs=1e-12)
