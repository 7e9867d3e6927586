"""Extremes: declustering (against pyextremes), capsizes as censored clusters, block estimates."""

import numpy as np
import pandas as pd

from stabflow.statistics.extremes import block_estimates, decluster, record_maxima, timeline


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


def test_capsized_record_is_one_censored_cluster():
    """Peaks of a record that capsized at t = 1000 s: the run of exceedances ending at the capsize
    (880, 950, 990 s: gaps below tau = 100 s) is the capsize's cluster (right-censored, not
    returned); the peak at 100 s and the other record's peaks stay."""
    rec = np.array([0, 0, 0, 0, 1, 1])
    t = np.array([100.0, 880.0, 950.0, 990.0, 950.0, 990.0])
    v = np.array([30.0, 70.0, 60.0, 80.0, 31.0, 32.0])
    mx, mr, mt = record_maxima(rec, t, v, 20.0, 100.0, [0], [1000.0])
    assert sorted(zip(mr.tolist(), mx.tolist())) == [(0, 30.0), (1, 32.0)]


def test_block_estimates_cover_a_known_tail_and_fail_honestly():
    """Peaks drawn so that cluster maxima above u = 10 deg are u + GPD(0, 2): the rate of maxima
    beyond 20 deg (100 clusters per 100 h) is held by the interval at two thresholds; a block with
    fewer than 3 exceedances gives NaN, never a rate of 0."""
    rng = np.random.default_rng(5)
    n = 100
    rec = np.arange(n)
    t = np.full(n, 500.0)
    v = 10.0 + rng.exponential(2.0, n)
    R, LO, HI, XI, NU, fixed = block_estimates(rec, t, v, np.zeros(0, int), np.zeros(0), rec, 100.0, [10.0, 11.0],
                                               np.array([20.0]), 100.0, 0.05, 0)
    truth = 1.0 * np.exp(-10.0 / 2.0)
    assert np.all(LO[:, 0] <= truth) and np.all(truth <= HI[:, 0])
    assert fixed[0, 0] >= LO[0, 0] and fixed[1, 0] <= HI[0, 0]
    R2, LO2, HI2, *_ = block_estimates(rec[:2], t[:2], v[:2], np.zeros(0, int), np.zeros(0), rec[:2], 2.0, [10.0],
                                       np.array([20.0]), 100.0, 0.05, 0)
    assert np.isnan(R2).all() and np.isnan(LO2).all()
