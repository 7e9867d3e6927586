"""Extremes: GPD fit, declustering (against pyextremes), rates and the block validation."""

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from stabflow.statistics.extremes import decluster, exceedance_rate, gpd_mle, pyextremes_fit, timeline


def test_gpd_fit_recovers_known_parameters():
    """5000 GPD samples (xi = 0.1, sigma = 3 deg) above u = 10 deg: pyextremes' MLE and the scipy
    refit used by the bootstrap agree and recover both parameters within 3 standard errors
    (asymptotic: se(xi) = (1 + xi) / sqrt(n), se(sigma) = sigma sqrt(2 (1 + xi) / n))."""
    xi, sig, u, n = 0.1, 3.0, 10.0, 5000
    x = u + stats.genpareto.rvs(xi, scale=sig, size=n, random_state=3)
    rec = np.arange(n) // 10
    t = (np.arange(n) % 10) * 150.0
    eva = pyextremes_fit(x, rec, t, u, 100.0, 1800.0)
    c, s = eva.model.fit_parameters["c"], eva.model.fit_parameters["scale"]
    assert abs(c - xi) < 3 * (1 + xi) / np.sqrt(n)
    assert abs(s - sig) < 3 * sig * np.sqrt(2 * (1 + xi) / n)
    c2, s2 = gpd_mle(x - u)
    assert c2 == pytest.approx(c, abs=1e-3) and s2 == pytest.approx(s, rel=1e-3)
    # rate above x = n / hours * survival
    assert exceedance_rate([u + 5.0], u, n, 100.0, c, s)[0] == pytest.approx(n / 100 * stats.genpareto.sf(5, c, scale=s))


def test_declustering_keeps_one_peak_per_cluster_and_matches_pyextremes():
    """Clusters of 1-5 peaks 20 s apart, clusters >= 200 s apart, window 100 s: exactly one
    maximum per cluster, never across records; same maxima as pyextremes' POT on the timeline."""
    from pyextremes import EVA

    rng = np.random.default_rng(1)
    rec, t, v, truth = [], [], [], []
    for r in range(30):
        start = 0.0
        while start < 1500:
            k = rng.integers(1, 6)
            vals = 10 + rng.exponential(3.0, k)
            rec += [r] * k
            t += list(start + 20.0 * np.arange(k))
            v += list(vals)
            truth.append(vals.max())
            start += 20.0 * k + rng.uniform(200, 400)
    rec, t, v = np.array(rec), np.array(t), np.array(v)
    mx, mr, mt = decluster(rec, t, v, 10.0, 100.0)
    assert len(mx) == len(truth)
    np.testing.assert_allclose(np.sort(mx), np.sort(truth))
    # last peak of a record and first of the next are never merged, even if close in time
    mx2, _, _ = decluster(np.array([0, 1]), np.array([1790.0, 5.0]), np.array([12.0, 13.0]), 10.0, 100.0)
    assert len(mx2) == 2
    gap = 2 * 100.0 + 60.0
    s = pd.Series(v, index=timeline(rec, t, 1800.0, gap)).sort_index()
    eva = EVA(s)
    eva.get_extremes("POT", threshold=10.0, r=pd.Timedelta(seconds=100.0))
    np.testing.assert_allclose(np.sort(eva.extremes.to_numpy()), np.sort(mx))


def test_failed_fit_is_nan_not_zero():
    """Too few exceedances (or a failed fit) give NaN parameters and NaN rates, never a rate of 0."""
    xi, sig = gpd_mle(np.array([0.5, 1.0]))
    assert np.isnan(xi) and np.isnan(sig)
    r = exceedance_rate([12.0, 15.0], 10.0, 2, 100.0, xi, sig)
    assert np.all(np.isnan(r))


def test_bootstrap_interval_ranks_unfittable_resamples_lowest():
    """Resamples with too few exceedances (-inf) rank below the fitted ones: a few of them leave the
    lower bound determined; past alpha/2 it is undetermined (NaN), never 0. Failed fits (NaN) are
    left out and counted."""
    from stabflow.statistics.extremes import bootstrap_interval

    fitted = np.linspace(1.0, 2.0, 97)[:, None]
    boots = np.vstack([fitted, [[-np.inf]], [[-np.inf]], [[np.nan]]])
    lo, hi, few, failed = bootstrap_interval(boots, 0.05)
    assert few == 2 and failed == 1
    assert np.isfinite(lo[0]) and 1.0 <= lo[0] < 1.1 and hi[0] == pytest.approx(np.quantile(boots[:99], 0.975))
    boots = np.vstack([fitted[:90], np.full((10, 1), -np.inf)])
    lo, hi, few, failed = bootstrap_interval(boots, 0.05)
    assert np.isnan(lo[0]) and np.isfinite(hi[0]) and few == 10
