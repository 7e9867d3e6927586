"""The 1-DOF capsize-rate validation case: its model, its dataset and its rows."""

import numpy as np
import pytest

from stabflow.config import load_pipeline
from stabflow.constants import G
from stabflow.validation.capsize_1dof import analyse, box_model, capsize_1dof_checks, cases, reported_threshold

from ..conftest import ROOT


@pytest.fixture(scope="module")
def cfg():
    return load_pipeline(ROOT / "config" / "test.yaml")["capsize_1dof"]


def test_box_model_particulars(cfg):
    """GM = T / 2 + B^2 / (12 T) - KG = 2.0556 m for 100 x 20 x 8 m at draft 6 m, KG 6.5 m; the
    vanishing angle where the exact box GZ (independent polygon clipping) changes sign; the table
    is GZ / GM (slope 1 at the origin)."""
    from scipy.optimize import brentq

    from stabflow.validation.references import exact_box_gz

    name, band, sigma, _ = cases(cfg)[0]
    m = box_model(cfg, band, sigma)
    gm = 3.0 + 400.0 / 72.0 - 6.5
    assert m.w0 == pytest.approx(np.sqrt(G * gm) / 8.0)
    avs = brentq(lambda a: exact_box_gz(100, 20, 8, 12000, 6.5, [a])[0], 30.0, 40.0, xtol=1e-6)
    assert np.degrees(m.cap) == pytest.approx(avs, abs=0.01)
    assert m.restoring[10] / (10 * m.dphi) == pytest.approx(1.0, rel=1e-3)


def test_reported_threshold_rule():
    assert reported_threshold({2.5: 300, 3.0: 80, 3.5: 12}, [2.5, 3.0, 3.5], 50) == 3.0
    assert reported_threshold({2.5: 30, 3.0: 8}, [2.5, 3.0], 50) == 2.5


def test_case_runs_end_to_end_and_rows_never_vanish(cfg):
    """config/test.yaml's case: brute force, 3 samples, both methods at every threshold; every row is
    present with a status, coverage and ratios are finite, and a brute force without capsizes turns
    the comparison rows into FAIL with the reason."""
    ds = analyse(cfg, threads=2)
    n = ds.sizes["sample"]
    assert n == cfg["samples"] and int(ds["bruteforce_capsizes"][0]) > 0
    assert np.all(ds["sample_hours"].values > 0)
    for m in ("splittime", "extremes"):
        cov = ds[f"{m}_coverage"].values
        inside = ds[f"{m}_inside"].values
        assert np.all((cov >= 0) & (cov <= 1)) and np.allclose(cov, inside.mean(axis=1))
        assert np.isfinite(ds[f"{m}_median_ratio"].values).all()
    assert np.all(ds["perturbed_runs"].values > 0)
    rows = capsize_1dof_checks(ds)
    assert len(rows) == 7 and {r.kind for r in rows} == {"independent", "consistency"}
    assert all(r.status in ("PASS", "FAIL") for r in rows)
    z = ds.copy(deep=True)
    z["bruteforce_capsizes"][:] = 0
    z["capsize_rate_bruteforce"][:] = 0.0
    bad = capsize_1dof_checks(z)
    assert bad[0].status == "FAIL"
    assert [r.reason for r in bad if "no rate to compare" in r.reason]
