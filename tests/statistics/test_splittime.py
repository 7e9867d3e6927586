"""Split-time pieces: bisection on an analytic softening oscillator, rate intervals, GPD to y = 1."""

import numpy as np
import pytest
from scipy import stats

from stabflow.statistics.splittime import bisect_critical, capsize_probability, crossing_rate, poisson_interval


def _softening_capsizes(phi0, rate0, w=0.5, phiv=1.0, dt=0.002, T=40.0):
    """phi'' = -w^2 phi (1 - phi^2 / phiv^2), undamped (RK4): capsize if phi passes phiv."""
    def f(s):
        return np.array([s[1], -w**2 * s[0] * (1 - s[0] ** 2 / phiv**2)])

    s = np.array([phi0, rate0])
    for _ in range(int(T / dt)):
        k1 = f(s)
        k2 = f(s + 0.5 * dt * k1)
        k3 = f(s + 0.5 * dt * k2)
        k4 = f(s + dt * k3)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if abs(s[0]) > phiv:
            return True
    return False


def test_bisection_finds_separatrix_of_softening_oscillator():
    """Energy E = phidot^2 / 2 + w^2 (phi^2 / 2 - phi^4 / (4 phiv^2)); the separatrix through the
    saddle phi = phiv has E = w^2 phiv^2 / 4, so at phi0 the critical rate is
    sqrt(2 (E_s - V(phi0))). The bisection on the perturbation recovers it to the tolerance."""
    w, phiv, phi0, rate_u = 0.5, 1.0, 0.4, 0.1
    V = w**2 * (phi0**2 / 2 - phi0**4 / (4 * phiv**2))
    crit = np.sqrt(2 * (w**2 * phiv**2 / 4 - V))
    delta, runs = bisect_critical(lambda d: _softening_capsizes(phi0, rate_u + d, w, phiv), 2.0, 1e-3)
    assert delta + rate_u == pytest.approx(crit, abs=2e-3)
    assert runs < 20
    assert bisect_critical(lambda d: True, 1.0, 1e-3) == (0.0, 1)
    assert bisect_critical(lambda d: False, 1.0, 1e-3)[0] == np.inf


def test_crossing_rate_eq2_and_intervals():
    lam, lo, hi = crossing_rate(50, 720000, 0.5)
    assert lam == pytest.approx(50 / 100.0)  # 720000 samples of 0.5 s = 100 h
    assert lo < lam < hi
    r, lo, hi = poisson_interval(10, 1000.0)
    assert r == 0.01 and lo == pytest.approx(0.0047954, rel=1e-3) and hi == pytest.approx(0.0183904, rel=1e-3)


def test_capsize_probability_from_gpd_tail():
    """Metrics drawn as u + GPD(xi < 0) with a fraction above u: P(y >= 1) recovers the exact
    value n_u / n * GPD survival(1 - u) within sampling error."""
    rng = np.random.default_rng(2)
    n, frac, u, xi, sig = 20000, 0.3, 0.5, -0.2, 0.15
    body = rng.uniform(0.0, u, int(n * (1 - frac)))
    tail = u + stats.genpareto.rvs(xi, scale=sig, size=int(n * frac), random_state=rng)
    y = np.concatenate([body, tail])
    p, xh, sh, nu = capsize_probability(y, u)
    exact = frac * stats.genpareto.sf(1 - u, xi, scale=sig)
    assert p == pytest.approx(exact, rel=0.3)
    assert xh == pytest.approx(xi, abs=0.05)
