"""Irregular-sea validation rows: seaway, step size, extremes and split-time (stabflow.validation.ensemble)."""

import dataclasses
import re

import numpy as np
import pytest
import xarray as xr

from stabflow.statistics import extremes, splittime
from stabflow.config import load_pipeline, load_ship
from stabflow.statistics.ensemble import build_model, merge, run_shard
from stabflow.validation import KINDS, STATUSES, Check, checks_dataset
from stabflow.validation.ensemble import (MIN_COVERAGE, RATIO_BAND, ensemble_checks, extremes_checks,
                                          seaway_checks, splittime_checks, step_checks)
from stabflow.waves.seaway import Seaway

from ..conftest import ROOT, SHIPS

RECORDS = 6


@pytest.fixture(scope="module")
def model():
    """The test profile's barge beam-sea condition (Bretschneider Hs 3.5 m, Tp 10 s, 120 components,
    0 kn, heading 90 deg, 900 s records), schema defaults filled in."""
    cond = dict(load_pipeline(ROOT / "config" / "test.yaml")["ensembles"][0], name="barge_beam")
    return build_model(load_ship(SHIPS / "barge.yaml"), cond)


@pytest.fixture(scope="module")
def ens(model):
    return merge([run_shard(model, range(RECORDS), progress=False)])


@pytest.fixture(scope="module")
def rows(model, ens):
    return ensemble_checks(model, ens)


def _by_name(rows, start):
    found = [c for c in rows if c.check.startswith(start)]
    assert found, f"no row starting with {start!r} in {[c.check for c in rows]}"
    return found


def test_rows_exist_with_kinds_and_statuses(rows):
    """Five seaway rows (independent), regeneration, the trajectory, two step-size rows and their
    two paired-bootstrap rows (consistency), and the extremes and split-time rows SKIPPED with the
    reason when those steps do not run."""
    assert all(c.kind in KINDS and c.status in STATUSES for c in rows)
    seaway = _by_name(rows, "seaway:")
    assert len(seaway) == 5 and all(c.kind == "independent" for c in seaway)
    step = _by_name(rows, "step size:")
    assert len(step) == 5 and all(c.kind == "consistency" for c in step)
    (reg,) = _by_name(rows, "ensemble records regenerated")
    assert reg.kind == "consistency"
    skipped = [c for c in rows if c.status == "SKIPPED"]
    assert len(skipped) == 4
    assert sum("extremes step does not run" in c.reason for c in skipped) == 2
    assert sum("split-time step does not run" in c.reason for c in skipped) == 2
    assert len(rows) == 15
    ds = checks_dataset("barge", "ensemble", rows)  # the rows make a validation dataset
    assert list(ds["status"].values).count("SKIPPED") == 4


def test_seaway_rows_pass_with_the_test_tolerances(rows):
    """The condition's own seaway (80 records x 900 s = 20 h) meets the tolerances of
    tests/waves/test_seaway.py: variance 3 %, density 15 %, skewness 0.05, kurtosis 0.1, CDF 0.01."""
    seaway = _by_name(rows, "seaway:")
    assert [c.tolerance for c in seaway] == [3.0, 15.0, 0.05, 0.1, 0.01]
    assert all(c.status == "PASS" and not c.reason for c in seaway), [(c.check, c.value) for c in seaway]
    assert "80 records x 900 s" in seaway[0].check


def test_step_rows(rows):
    """Records regenerate bit for bit; the roll trajectory over 30 s, roll sigma and q0.999 at
    dt = 0.5 s agree with dt = 0.1 s."""
    (reg,) = _by_name(rows, "ensemble records regenerated")
    assert reg.value == 0.0 and reg.status == "PASS"
    traj, sig, q, _, _ = _by_name(rows, "step size:")
    assert "roll trajectory over the first 30 s of 6 records at dt = 0.5 s vs dt = 0.1 s" in traj.check
    assert traj.tolerance == 1.0 and traj.status == "PASS" and 0.0 < traj.value < 1.0, traj.value
    assert "dt = 0.5 s vs dt = 0.1 s" in sig.check and sig.tolerance == 0.5 and q.tolerance == 1.0
    assert sig.unit == q.unit == "%"
    assert sig.status == "PASS" and q.status == "PASS", (sig.value, q.value)
    assert "capsized records" in sig.reference and "degree" in sig.reference


def test_bootstrap_rows_hold_the_effect_and_fail_below_the_fewest_records(rows):
    """Each step-size statistic has a paired-bootstrap row whose interval (in its name) holds the
    effect of the fixed-tolerance row; over the fixture's 6 records (fewer than
    BOOTSTRAP_MIN_RECORDS) both rows FAIL with that reason, never PASS on so few records."""
    from stabflow.validation.ensemble import BOOTSTRAP_MIN_RECORDS

    _, sig, q, bsig, bq = _by_name(rows, "step size:")
    assert BOOTSTRAP_MIN_RECORDS > 6
    for fixed, boot in ((sig, bsig), (q, bq)):
        assert "paired-bootstrap interval" in boot.check and boot.tolerance == fixed.tolerance and boot.unit == "%"
        d, lo, hi = (float(v) for v in re.search(r"effect ([-+.\d]+) % in \[([-+.\d]+), ([-+.\d]+)\] %",
                                                     boot.check).groups())
        assert d == pytest.approx(fixed.value, abs=0.006) and lo <= d <= hi
        assert boot.status == "FAIL" and f"6 records, fewer than {BOOTSTRAP_MIN_RECORDS}" in boot.reason


def test_bootstrap_checks_verdicts():
    """The rows' verdicts from given intervals: inside the tolerance PASS (value = largest |bound|);
    reaching beyond it FAIL, named 'holds 0' or 'excludes 0: a step effect'; no effect FAIL with the
    reason; the same intervals over fewer than BOOTSTRAP_MIN_RECORDS records FAIL with the reason."""
    from stabflow.validation.ensemble import BOOTSTRAP_MIN_RECORDS, TOL_Q999, TOL_SIGMA, bootstrap_checks

    n = BOOTSTRAP_MIN_RECORDS
    ok = bootstrap_checks({"sig": (0.1, -0.2, 0.4), "q": (-0.3, -0.9, 0.2)}, n, 0.2, 0.04)
    assert [c.status for c in ok] == ["PASS", "PASS"] and [c.value for c in ok] == [0.4, 0.9]
    assert [c.tolerance for c in ok] == [TOL_SIGMA, TOL_Q999] and all(c.kind == "consistency" for c in ok)
    assert all("holds 0" in c.check and f"({n} records)" in c.check for c in ok)
    wide, shifted = bootstrap_checks({"sig": (0.1, -0.6, 0.4), "q": (2.0, 1.5, 2.5)}, n, 0.2, 0.04)
    assert wide.status == "FAIL" and wide.value == 0.6 and "holds 0" in wide.check and not wide.reason
    assert shifted.status == "FAIL" and shifted.value == 2.5 and "excludes 0: a step effect" in shifted.check
    assert all(c.status == "FAIL" and "ValueError: x" == c.reason for c in bootstrap_checks(None, n, 0.2, 0.04, "ValueError: x"))
    few = bootstrap_checks({"sig": (0.1, -0.2, 0.4), "q": (-0.3, -0.9, 0.2)}, n - 1, 0.2, 0.04)
    assert all(c.status == "FAIL" and f"fewer than {n}" in c.reason and "in [" in c.check for c in few)
    nan = bootstrap_checks({"sig": (0.1, 0.0, np.nan), "q": (0.0, 0.0, 0.0)}, n, 0.2, 0.04)
    assert [c.status for c in nan] == ["FAIL", "PASS"]


def _gaussian_records(rng, records, samples, scale=1.0):
    """record_arrays of Gaussian roll records (sigma ``scale`` degree), histogram bins of 0.01 degree."""
    bins = np.arange(0.005, 8.0, 0.01)
    edges = np.concatenate([bins - 0.005, [bins[-1] + 0.005]])
    x = scale * rng.standard_normal((records, samples))
    hist = np.array([np.histogram(np.abs(r), edges)[0] for r in x], float)
    return dict(n=np.full(records, float(samples)), s1=x.sum(1), s2=(x * x).sum(1), hist=hist, bins=bins)


def test_paired_bootstrap_interval_matches_the_sampling_theory_of_gaussian_records():
    """Two independent sets of 400 Gaussian records of 250 samples (N = 100,000 each, the chaotic
    limit: the steps share nothing), eight seeds: the bootstrap's mean 95 % half-width against the
    large-sample theory, sigma: 1.96 sqrt(1/N) (var ln s = 1/(2N) per set), within 10 %; q0.999 of
    |x|: 1.96 sqrt(2 p(1-p) / (N f^2)) / x_p with f = 2 phi(x_p) (the sample quantile's variance),
    within 12 % (measured 0.975 and 0.979 of theory; a 90 % interval would give 0.84)."""
    from scipy.stats import norm

    from stabflow.validation.ensemble import paired_step_effect

    N = 100_000
    xp = norm.ppf(1 - 0.0005)
    theory = {"sig": 196.0 / np.sqrt(N), "q": 196.0 * np.sqrt(2 * 0.999 * 0.001 / (N * (2 * norm.pdf(xp)) ** 2)) / xp}
    half = {"sig": [], "q": []}
    for seed in range(8):
        rng = np.random.default_rng(seed)
        a, b = _gaussian_records(rng, 400, 250), _gaussian_records(rng, 400, 250)
        for key, (d, lo, hi) in paired_step_effect(a, b).items():
            half[key].append(0.5 * (hi - lo))
            assert lo <= d <= hi
    assert np.mean(half["sig"]) == pytest.approx(theory["sig"], rel=0.10), (half, theory)
    assert np.mean(half["q"]) == pytest.approx(theory["q"], rel=0.12), (half, theory)


def test_paired_bootstrap_cancels_what_the_steps_share_and_finds_a_step_effect():
    """The same records at both steps: the interval is [0, 0]; every record's roll 2 % larger at one
    step (a systematic step effect): sigma's interval is [+2, +2] %, the row FAILs excluding 0."""
    from stabflow.validation.ensemble import TOL_SIGMA, paired_step_effect

    a = _gaussian_records(np.random.default_rng(3), 20, 1000)
    assert paired_step_effect(a, a) == {"sig": (0.0, 0.0, 0.0), "q": (0.0, 0.0, 0.0)}
    b = dict(a, s1=a["s1"] / 1.02, s2=a["s2"] / 1.02**2)
    d, lo, hi = paired_step_effect(a, b)["sig"]
    assert d == pytest.approx(2.0, abs=1e-9) and lo == pytest.approx(2.0, abs=1e-9) and hi == pytest.approx(2.0, abs=1e-9)
    assert max(abs(lo), abs(hi)) > TOL_SIGMA
    with pytest.raises(ValueError, match="same records"):
        paired_step_effect(a, dict(a, n=a["n"][:5]))
    one = {k: (v[:1] if k != "bins" else v) for k, v in a.items()}
    with pytest.raises(ValueError, match="at least 2 records"):
        paired_step_effect(one, one)
    still = dict(a, s1=0.0 * a["s1"], s2=0.0 * a["s2"])  # roll identically 0 at the reference step
    with pytest.raises(ValueError, match="the roll standard deviation is zero or not finite"):
        paired_step_effect(a, still)


def test_trajectory_error_grows_with_the_step_and_fails_when_too_long(model):
    """The trajectory measure is small at a converged step and beyond its tolerance at a step
    of a quarter of the roll period, where RK4 misses the motion (the row can fail)."""
    from stabflow.validation.ensemble import TOL_TRAJECTORY, trajectory_error

    good = trajectory_error(model, [0, 1], 0.5, 0.1)
    coarse = dataclasses.replace(model, cond=dict(model.cond, dt=2.5))
    bad = trajectory_error(coarse, [0, 1], 2.5, 0.5)
    assert good < 0.5 * TOL_TRAJECTORY < 2.0 * TOL_TRAJECTORY < bad, (good, bad)


def test_trajectory_error_compares_the_first_seconds_from_rest_whatever_the_warm_up(model):
    """The trajectory row's "first 30 s" are the first seconds from rest: a condition's warm-up
    (warmup_s) does not lengthen the compared records (it did: 100 s of warm-up made them 130 s)."""
    import dataclasses

    from stabflow.validation.ensemble import trajectory_error

    warm = dataclasses.replace(model, cond=dict(model.cond, warmup_s=60.0))
    assert trajectory_error(warm, [0, 1], 0.5, 0.1, seconds=20.0) == trajectory_error(model, [0, 1], 0.5, 0.1, seconds=20.0)


def test_regeneration_detects_a_model_that_is_not_the_ensembles(model, ens):
    """A dataset whose moment sums differ from the model's records fails the regeneration row, and
    an ensemble without records gives FAIL rows with the reason, never NaN quietly."""
    other = ens.copy(deep=True)
    other["moment_sums"] = other["moment_sums"] * 1.01
    reg = step_checks(model, other, records=2)[0]
    assert reg.status == "FAIL" and reg.value == pytest.approx(0.01 / 1.01, rel=1e-6)
    empty = step_checks(model, ens.isel(record=slice(0, 0)))
    assert len(empty) == 6 and all(c.status == "FAIL" for c in empty)
    assert all("the ensemble has no record" in c.reason for c in empty)


def test_seaway_failure_is_a_fail_row(model):
    bad = dataclasses.replace(model, sea=Seaway("no_such_spectrum", 3.5, 10.0, n_components=120))
    seaway = seaway_checks(bad)
    assert len(seaway) == 5 and all(c.kind == "independent" for c in seaway)
    assert all(c.status == "FAIL" and c.reason.startswith("seaway synthesis failed") for c in seaway)


# --------------------------------------------------------------------------------------------
# extremes: synthetic datasets with known coverage, ratios and zero brute force


def _extremes(cover, ratio, zero_bf=(), nan_est=(), partial_zero=(), blocks=50):
    """Dataset shaped like extremes.analyse's: ``cover[j]`` of the blocks inside, estimate =
    ``ratio[j]`` x brute force; targets in ``zero_bf`` never counted by the brute force."""
    targets = np.array([30.0, 40.0, 50.0, 60.0])[: len(cover)]
    nt = len(targets)
    bf = np.tile(1e-3 * np.arange(1, nt + 1), (blocks, 1))
    est = bf * np.asarray(ratio)
    inside = np.zeros((blocks, nt), np.int8)
    for j, c in enumerate(cover):
        inside[: int(round(c * blocks)), j] = 1
        if j in zero_bf:
            bf[:, j] = 0.0
        if j in nan_est:
            est[:, j] = np.nan
        if j in partial_zero:
            bf[: blocks // 2, j] = 0.0
    lo, hi = np.where(inside == 1, 0.5 * bf, 2 * bf + 1), np.where(inside == 1, 2 * bf + 1, 3 * bf + 2)
    ratio_v = np.where(bf > 0, est / np.where(bf > 0, bf, 1), np.nan)
    return xr.Dataset(
        {"rate_estimate": (("block", "target"), est), "rate_lower": (("block", "target"), lo),
         "rate_upper": (("block", "target"), hi), "rate_bruteforce": (("block", "target"), bf),
         "bruteforce_hours": ("block", np.full(blocks, 9900.0)), "inside": (("block", "target"), inside),
         "coverage": ("target", inside.mean(axis=0)), "rate_ratio": (("block", "target"), ratio_v)},
        coords={"block": np.arange(blocks), "target": targets},
        attrs={"interval": "bootstrap over records, 100 resamples, 95 %"})


def test_extremes_rows_known_coverage_and_ratio():
    """Coverage 94 % passes, 78 % and 84 % fail (the criterion is 0.90); median ratio 1.0 passes,
    0.5 fails; two rows per target, both independent."""
    rows = extremes_checks(_extremes([0.94, 0.78, 0.84], [1.0, 0.5, 1.39]))
    assert len(rows) == 6 and all(c.kind == "independent" for c in rows)
    cov = [c for c in rows if "coverage" in c.check]
    rat = [c for c in rows if "median" in c.check]
    assert [c.check.split(":")[0] for c in cov] == ["extremes 30 deg", "extremes 40 deg", "extremes 50 deg"]
    assert "by the 95 % interval over 50 samples" in cov[0].check
    assert [c.value for c in cov] == pytest.approx([0.94, 0.78, 0.84])
    assert [c.status for c in cov] == ["PASS", "FAIL", "FAIL"]
    assert all(c.lower == MIN_COVERAGE and c.upper is None and not c.reason for c in cov)
    assert [c.value for c in rat] == pytest.approx([1.0, 0.5, 1.39])
    assert [c.status for c in rat] == ["PASS", "FAIL", "PASS"]
    assert all((c.lower, c.upper) == RATIO_BAND for c in rat)
    assert "(9900.0 h on average)" in cov[0].reference


def test_extremes_zero_brute_force_and_nan_ratio_are_fail_rows_with_reason():
    rows = extremes_checks(_extremes([0.94, 1.0, 0.9, 0.9], [1.0, 1.0, 1.0, 1.0], zero_bf=(1,), nan_est=(2,),
                                     partial_zero=(3,)))
    assert len(rows) == 8
    zero = [c for c in rows if c.check.startswith("extremes 40 deg")]
    assert [c.status for c in zero] == ["FAIL", "FAIL"]
    assert all("no exceedance of 40 deg in any of the 50 samples" in c.reason for c in zero)
    assert all(np.isnan(c.value) for c in zero)  # NaN only as the value of a FAIL row with its reason
    cov50, rat50 = [c for c in rows if c.check.startswith("extremes 50 deg")]
    assert cov50.status == "PASS"
    assert rat50.status == "FAIL" and "NaN in every sample with a brute-force count" in rat50.reason
    cov60, rat60 = [c for c in rows if c.check.startswith("extremes 60 deg")]
    assert rat60.status == "PASS" and rat60.value == pytest.approx(1.0)
    assert "(median over 25 of 50 samples: brute force 0 or estimate NaN in the others)" in rat60.check


def test_extremes_broken_or_absent_dataset():
    broken = extremes_checks(_extremes([0.94], [1.0]).drop_vars("rate_bruteforce"))
    assert [c.status for c in broken] == ["FAIL", "FAIL"] and all("rate_bruteforce" in c.reason for c in broken)
    skipped = extremes_checks(None)
    assert [c.status for c in skipped] == ["SKIPPED", "SKIPPED"]
    assert all("extremes step does not run for this condition" in c.reason for c in skipped)


# --------------------------------------------------------------------------------------------
# split-time: synthetic datasets with known ratios and zero brute force


def _splittime(lam, lo, hi, k=56, hours=10000.0):
    thr = np.array([20.0, 25.0, 30.0])[: len(lam)]
    return xr.Dataset(
        {"capsize_rate_splittime": ("split_threshold", np.asarray(lam, float)),
         "capsize_rate_lower": ("split_threshold", np.asarray(lo, float)),
         "capsize_rate_upper": ("split_threshold", np.asarray(hi, float)),
         "inside": ("split_threshold", np.zeros(len(lam), np.int8)),
         "capsize_rate_bruteforce": ((), k / hours), "capsize_rate_bruteforce_lower": ((), 0.8 * k / hours),
         "capsize_rate_bruteforce_upper": ((), 1.25 * k / hours), "bruteforce_capsizes": ((), k),
         "bruteforce_hours": ((), hours)},
        coords={"split_threshold": thr},
        attrs={"interval": "bootstrap over records, 200 resamples"})


def test_splittime_rows_known_ratios():
    """Known results: 20 deg 4.0e-3 vs 5.6e-3 (0.71, passes), 25 deg 3.8e-3 (0.68, fails), 30 deg 0
    (fails); inside 1 for 20 and 25 deg, 0 for 30 deg."""
    rows = splittime_checks(_splittime([4.0e-3, 3.8e-3, 0.0], [2e-3, 1.9e-3, 0.0], [6e-3, 5.7e-3, 0.0]))
    assert len(rows) == 6 and all(c.kind == "independent" for c in rows)
    inside = [c for c in rows if "inside" in c.check]
    ratio = [c for c in rows if "/ brute-force rate" in c.check]
    assert [c.check.split(":")[0] for c in inside] == ["split-time 20 deg", "split-time 25 deg", "split-time 30 deg"]
    assert [c.value for c in inside] == [1.0, 1.0, 0.0]
    assert [c.status for c in inside] == ["PASS", "PASS", "FAIL"]
    assert all((c.lower, c.upper) == (1.0, 1.0) for c in inside)
    assert [c.value for c in ratio] == pytest.approx([4.0 / 5.6, 3.8 / 5.6, 0.0])
    assert [c.status for c in ratio] == ["PASS", "FAIL", "FAIL"]
    assert all(not c.reason for c in rows)
    assert "56 capsized records in 10000.0 h" in ratio[0].reference


def test_splittime_zero_brute_force_is_fail_with_reason_and_none_is_skipped():
    rows = splittime_checks(_splittime([4.0e-3, 0.0], [2e-3, 0.0], [6e-3, 0.0], k=0))
    assert len(rows) == 4 and all(c.status == "FAIL" for c in rows)
    assert all("no capsize in 10000.0 h" in c.reason for c in rows)
    nan = splittime_checks(_splittime([np.nan], [np.nan], [np.nan]))
    assert [c.status for c in nan] == ["FAIL", "FAIL"]
    assert "interval is NaN" in nan[0].reason and "rate is NaN" in nan[1].reason
    broken = splittime_checks(_splittime([4.0e-3], [2e-3], [6e-3]).drop_vars("bruteforce_capsizes"))
    assert [c.status for c in broken] == ["FAIL", "FAIL"]
    assert all("split-time dataset unreadable" in c.reason and "bruteforce_capsizes" in c.reason for c in broken)
    skipped = splittime_checks(None)
    assert [c.status for c in skipped] == ["SKIPPED", "SKIPPED"]
    assert all("split-time step does not run for this condition" in c.reason for c in skipped)


def test_with_step_datasets_rows_are_appended(model, ens):
    """With the datasets given, ensemble_checks carries their rows instead of the SKIPPED ones (a
    model whose seaway cannot be built and an empty ensemble keep this fast: those rows FAIL)."""
    bad = dataclasses.replace(model, sea=Seaway("no_such_spectrum", 3.5, 10.0, n_components=120))
    rows = ensemble_checks(bad, ens.isel(record=slice(0, 0)), _extremes([0.94, 0.78], [1.0, 1.0]),
                           _splittime([4.0e-3], [2e-3], [6e-3]))
    assert len(rows) == 5 + 6 + 4 + 2
    assert not any(c.status == "SKIPPED" for c in rows)
    assert [c.status for c in rows[11:]] == ["PASS", "PASS", "FAIL", "PASS", "PASS", "PASS"]
    assert all(isinstance(c, Check) for c in rows)


def test_rows_from_the_steps_own_datasets(model, ens):
    """The rows read the real datasets of extremes.analyse and splittime.analyse (test profile, half-
    hour samples of the 6 records): two independent rows and one threshold-consistency row per
    target, two rows per split-time threshold and one consistency row, no NaN without a reason.
    The brute force of the split-time step sees no capsize in records 2-5: every comparison row
    says so."""
    cfg = load_pipeline(ROOT / "config" / "test.yaml")
    ex, _ = extremes.analyse(ens, dict(cfg["extremes"], sample_hours=0.5))
    sp = splittime.analyse(model, ens, dict(cfg["splittime"], sample_hours=0.5))
    rows = extremes_checks(ex)
    assert len(rows) == 3 * ex.sizes["target"]
    for c in rows:
        assert c.status in ("PASS", "FAIL") and c.kind == ("consistency" if "other thresholds" in c.check
                                                           else "independent")
        assert np.isfinite(c.value) or (c.status == "FAIL" and c.reason), c
    assert int(sp["bruteforce_capsizes"]) == 0
    rows = splittime_checks(sp)
    assert len(rows) == 2 * sp.sizes["split_threshold"] + 1
    assert all(c.status == "FAIL" and "counted no capsize" in c.reason for c in rows[:-1])
    assert rows[-1].kind == "consistency" and np.isfinite(rows[-1].value)


def test_step_reruns_per_record_threads_and_subsets():
    """The step-size re-runs simulate each record once, as its own shard: a 6-DOF condition's records
    in two threads give the same datasets bit for bit as in one, and the merge of a subset of them
    (the records that capsize at neither step) equals the subset simulated directly."""
    import tempfile

    import yaml

    from stabflow.geometry import build_hull
    from stabflow.hydrostatics.statics import compute_statics
    from stabflow.validation.ensemble import _rerun

    from ..conftest import synthetic_memory_dataset

    d = {"ships": ["trawler"], "ensembles": [{"name": "sq6", "ship": "trawler", "sea": {"spectrum": "pierson_moskowitz",
         "hs": 3.1, "n_components": 40}, "speed_kn": 10.0, "heading_deg": 45.0, "dof": 6, "dt": 0.2, "duration": 60.0,
         "records": 3, "samples": 0, "stations": 11}]}
    with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
        yaml.safe_dump(d, f)
    cond = dict(load_pipeline(f.name)["ensembles"][0], name="sq6")
    ship = load_ship(ROOT / "config" / "ships" / "trawler.yaml")
    mem = synthetic_memory_dataset(float(compute_statics(ship, build_hull(ship))["lcg"]))
    six = build_model(ship, cond, None, mem)
    one, two = _rerun(six, 0.2, [0, 1, 2], threads=1), _rerun(six, 0.2, [0, 1, 2], threads=2)
    assert list(one) == list(two) == [0, 1, 2]
    for r in one:
        xr.testing.assert_identical(one[r], two[r])
    sub = merge([one[0], one[2]])
    direct = merge([run_shard(six, [0, 2], progress=False)])
    np.testing.assert_array_equal(sub["record"].values, [0, 2])
    for v in ("moment_sums", "hist_roll", "capsized", "steps"):
        np.testing.assert_array_equal(sub[v].values, direct[v].values, err_msg=v)
    np.testing.assert_allclose(float(sub["roll_std"]), float(direct["roll_std"]), rtol=1e-12)
