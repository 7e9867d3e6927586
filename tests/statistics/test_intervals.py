"""Bootstrap over records: the resampling unit and its reproducibility."""

import numpy as np

from stabflow.statistics.intervals import record_bootstrap


def test_record_bootstrap_resamples_whole_records():
    """Every resample holds whole records (all of a record's values or none, as often as it was
    drawn), records without values contribute nothing, and the draws follow the generator."""
    values = np.array([1.0, 2.0, 3.0, 10.0, 20.0])
    value_records = np.array([0, 0, 0, 2, 2])
    records = np.array([0, 1, 2])
    rows = list(record_bootstrap(np.random.default_rng(5), records, values, value_records, 200))
    assert len(rows) == 200
    ref = np.random.default_rng(5)
    for pick, v in rows:
        assert np.array_equal(pick, ref.choice(records, size=3, replace=True))
        expect = np.concatenate([values[value_records == r] for r in pick])
        assert np.array_equal(v, expect)
        assert len(v) == 3 * np.sum(pick == 0) + 2 * np.sum(pick == 2)
    # the mean over resamples of the resampled total approaches the total (unbiased)
    totals = [v.sum() for _, v in rows]
    assert abs(np.mean(totals) - values.sum()) < 4 * np.std(totals) / np.sqrt(len(totals))
