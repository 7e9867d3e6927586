"""The direct stability assessment engine: failure angle, declustered failures, cell grid, a small
assessment of the barge (methods, determinism, screening bound)."""

import math

import numpy as np
import pytest
import xarray as xr

from stabflow.config import load_ship
from stabflow.criteria import dsa, dsa_run
from stabflow.criteria.standards import Standards
from tests.conftest import SHIPS

CFG = {"headings_deg": [90.0, 180.0], "froude_numbers": [0.05], "records": 1, "duration": 300.0, "dt": 0.5,
       "stations": 11, "n_components": 40, "seed": 7, "alpha": 0.05, "max_lag": 120.0, "hs_max": 5.5, "dynamics": {},
       "initial_heel_deg": 1.0,
       "screen": {"records": 1, "duration": 300.0, "sigma_factor": 1.5, "rate": 1e-9, "parametric_deg": 15.0,
                  "parametric_fraction": 0.05, "parametric_band": 0.3, "parametric_wavelength_ratio": [0.5, 2.0]}}


def test_failure_angle_is_the_smallest_limit():
    std = Standards()
    assert dsa_run.failure_angle(std, 70.0, math.nan) == (40.0, "DSA roll limit")
    assert dsa_run.failure_angle(std, 35.0, math.nan) == (35.0, "angle of vanishing stability")
    assert dsa_run.failure_angle(std, 70.0, 25.0) == (25.0, "flooding angle")


def test_failures_are_declustered_per_record():
    ens = xr.Dataset({"crossing_record": ("crossing", [0, 0, 0, 1, 2, 2]),
                      "crossing_time": ("crossing", [10.0, 12.0, 50.0, 100.0, 5.0, 9.9])})
    # record 0: 10 and 12 s are one failure, 50 s another; record 1: one; record 2: one (4.9 s apart)
    assert dsa_run.failures_per_record(ens, 5.0).sum() == 4
    assert dsa_run.failures_per_record(ens.isel(crossing=slice(0, 0)), 5.0).sum() == 0
    np.testing.assert_array_equal(dsa_run.failures_per_record(ens, 5.0), [2, 1, 1])


def test_count_dispersion():
    """Var k / E k from the records: equal counts give 0, Poisson counts about 1, clustered ones more."""
    from stabflow.criteria.dsa import count_dispersion

    assert count_dispersion([np.array([2, 2, 2])], 1.0) == (0.0, 2)
    rng = np.random.default_rng(3)
    d, dof = count_dispersion([rng.poisson(3.0, 4) for _ in range(500)], 1.0)
    assert dof == 1500 and abs(d - 1) < 0.12
    d2, _ = count_dispersion([2 * rng.poisson(1.5, 4) for _ in range(500)], 1.0)
    assert d2 > 1.6
    assert np.isnan(count_dispersion([np.array([0, 0]), np.array([3])], 1.0)[0])


def test_cell_grid_probabilities():
    std = Standards()
    g = dsa_run.cell_grid(std, [30.0, 90.0], [5.0, 10.0, 15.0])
    assert g.sizes["cell"] % 6 == 0
    assert float(g.probability.sum()) == pytest.approx(g.attrs["scatter_covered_fraction"], rel=1e-12)
    assert (g.probability > 0).all()


@pytest.mark.parametrize("headings, span, weights", [
    ([60.0, 90.0, 120.0], (45.0, 135.0), [1 / 3, 1 / 3, 1 / 3]),
    ([0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0], (0.0, 180.0), [1 / 12] + [1 / 6] * 5 + [1 / 12]),
    ([0.0, 90.0], (0.0, 135.0), [1 / 3, 2 / 3]),
    ([90.0, 180.0], (45.0, 180.0), [2 / 3, 1 / 3]),
    ([90.0], (90.0, 90.0), [1.0]),
    ([20.0, 90.0, 160.0], (0.0, 180.0), [55 / 180, 70 / 180, 55 / 180])])
def test_headings_stand_for_a_uniform_heading_over_their_span(headings, span, weights):
    """Each equally spaced heading stands for the interval of one spacing around it, clipped to 0-180
    deg (0 and 180 deg: half of one): the weights are those intervals' shares of the span (a first
    heading nearer 0 than half a spacing weighs less), and the span is written where the
    probabilities are described; unequally spaced or unordered headings are an error naming the
    config field."""
    from stabflow import StabflowError

    g = dsa_run.cell_grid(Standards(), headings, [5.0])
    assert g.attrs["heading_span"] == f"{span[0]:g}-{span[1]:g} deg"
    per = g.probability.groupby("heading").sum().values / float(g.probability.sum())
    np.testing.assert_allclose(per, weights, rtol=1e-12)
    if len(headings) > 1:  # the shares are the intervals' lengths over the span
        d = headings[1] - headings[0]
        lengths = [min(h + d / 2, span[1]) - max(h - d / 2, span[0]) for h in headings]
        np.testing.assert_allclose(per, np.array(lengths) / (span[1] - span[0]), rtol=1e-12)
    assert f"{span[0]:g}-{span[1]:g} deg" in g.attrs["probabilities"]
    for bad in ([0.0, 90.0, 120.0], [120.0, 90.0, 60.0]):
        with pytest.raises(StabflowError, match="dsa.headings_deg"):
            dsa_run.cell_grid(Standards(), bad, [5.0])


def test_cells_are_simulated_after_a_warmup_of_roll_periods(monkeypatch):
    """Every run of a cell (screening, simulation, recheck) is an engine condition with the warm-up
    of ``warmup_roll_periods`` natural roll periods of the cell's model (default 10, from the
    config schema), so its records' transient from rest is left out (the engine's warmup_s,
    tested in tests/statistics)."""
    seen = []
    real = dsa_run.run_cell

    def spy(model, cond):
        seen.append((cond["warmup_s"], model.roll_period))
        return real(model, cond)

    monkeypatch.setattr(dsa_run, "run_cell", spy)
    cfg = dict(CFG, hs_max=2.5, warmup_roll_periods=3.0)
    cells = dsa_run.assess_cells(load_ship(SHIPS / "barge.yaml"), cfg, 40.0, 100.0, crew_z=10.0)
    assert seen and all(w == pytest.approx(3.0 * t, rel=1e-12) and w > 0 for w, t in seen)
    assert cells.attrs["warmup_roll_periods"] == 3.0 and "3 natural roll periods" in cells.attrs["warmup"]
    assert len(seen) >= cells.sizes["cell"]  # a run per cell at least (screening or simulation)
    seen.clear()
    dsa_run.assess_cells(load_ship(SHIPS / "barge.yaml"), dict(CFG, hs_max=2.5), 40.0, 100.0, crew_z=10.0)
    assert seen and all(w == pytest.approx(10.0 * t, rel=1e-12) for w, t in seen)


def test_a_cell_whose_records_all_capsize_in_their_warmup_is_counted_from_rest(monkeypatch):
    """A simulated cell whose every record is lost in its warm-up (made so here: its runs with a
    warm-up report no exposure) is run again from rest, counted so and flagged (warmup_fallback), its
    lost records noted (warmup_lost); the other cells are untouched."""
    real = dsa_run.run_cell
    runs = []

    def all_lost(model, cond):
        ens = real(model, cond)
        runs.append(cond["warmup_s"])
        if cond["warmup_s"] > 0 and cond["heading_deg"] == 180.0 and cond["sea"]["hs"] == 2.5:
            ens = ens.copy()
            ens["exposure_hours"] = 0.0 * ens["exposure_hours"]
            ens["warmup_lost_count"] = ens["warmup_lost_count"] * 0 + cond["records"]
        return ens

    monkeypatch.setattr(dsa_run, "run_cell", all_lost)
    cells = dsa_run.assess_cells(load_ship(SHIPS / "barge.yaml"), dict(CFG, hs_max=2.5), 40.0, 100.0, crew_z=10.0)
    hit = (cells.heading.values == 180.0) & (cells.hs.values == 2.5)
    assert hit.any() and 0.0 in runs
    np.testing.assert_array_equal(cells.warmup_fallback.values, hit.astype(np.int8))
    assert (cells.warmup_lost.values[hit] >= 1).all() and not cells.warmup_lost.values[~hit].any()
    assert (cells.exposure.values[hit] > 0).all()
    assert f"({int(hit.sum())} cells)" in cells.attrs["warmup"]


CRIT = xr.Dataset({"heel_vanishing": 75.0, "flooding_angle": np.nan, "lwl": 100.0, "ea_crew_height": 10.0})


#: the small assessment's cells as assess_cells returned them (kept by the ``small`` fixture)
CELLS = {}


@pytest.fixture(scope="module")
def small():
    ship = load_ship(SHIPS / "barge.yaml")
    real = dsa_run.assess_cells

    def keep(*args, **kwargs):
        CELLS["barge"] = real(*args, **kwargs)
        return CELLS["barge"]

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(dsa_run, "assess_cells", keep)
        out = dsa_run.assess_dsa(ship, CRIT, CFG)
    return ship, out


def test_small_assessment(small):
    ship, cells = small
    m = cells.method.values.astype(str)
    assert set(m) <= {"screened", "counted", "extrapolated"} and len(m) == cells.sizes["cell"]
    scr = m == "screened"
    # a screened cell's bound is below the screening rate and its run stayed below half the failure angle
    assert (cells.cell_rate_hi.values[scr] < CFG["screen"]["rate"]).all()
    cnt = m == "counted"
    assert scr.any() and cnt.any()  # both kinds occur here (the tail fit is tested on its own below)
    assert (cells.exposure.values[cnt] > 0).all() and (cells.failures.values[cnt] >= 0).all()
    # the roll grows with the sea: the steepest cell rolls more than the mildest
    i, j = int(np.argmin(cells.hs.values / cells.tz.values**2)), int(np.argmax(cells.hs.values / cells.tz.values**2))
    assert cells.roll_sigma.values[j] > cells.roll_sigma.values[i]


def test_long_term_rate_and_row(small):
    """The long-term rate is the sum of the cells' contributions, inside its interval; the DSA row
    judges the interval against the sourced standard (Circ.1627 3.1.2, 2.6e-3 per ship per year):
    PASS when its upper bound meets it, FAIL when its lower bound exceeds it; the failure angle is the sourced 40 deg, the lateral-acceleration
    limit the sourced 9.81 m/s2 at the crew location (10 m above the baseline, KG 7 m)."""
    _, ds = small
    assert float(ds.contribution.sum()) == pytest.approx(float(ds.rate), rel=1e-9)
    assert float(ds.rate_lo) <= float(ds.rate) <= float(ds.rate_hi)
    assert float(ds.failure_angle) == 40.0 and ds.attrs["failure_angle_governed_by"] == "DSA roll limit"
    # the bare barge fails by far: its interval's lower bound is above the standard
    assert float(ds.rate_lo) > 2.6e-3 and ds.attrs["row_limit"] == 2.6e-3
    assert ds.attrs["row_value"] == float(ds.rate_lo) and ds.attrs["row_verdict"] == "FAIL"
    assert "lower bound of its 95 % interval" in ds.attrs["row_criterion"]
    assert "3.1.2" in ds.attrs["row_source"] and "lateral acceleration beyond 9.81 m/s2" in ds.attrs["row_criterion"]
    assert ds.attrs["lateral_acceleration_limit"] == 9.81 and ds.attrs["crew_height_above_g"] == pytest.approx(3.0)
    assert "3.2.1.2" in ds.attrs["lateral_acceleration_source"]
    # the screening checked by simulating the screened cells as the others: every screened cell and
    # no other was re-simulated; none of them failed nor rolled beyond half the failure angle; the
    # longer rechecks of two likelier beam-sea cells (Hs 2.5 m, Tz 6.5 and 7.5 s; with the records'
    # warm-up since 2026-12-07: before it, three cells of Hs 1.5 m) fit a roll tail above the
    # Gaussian bound: those cells are overruled and enter the rate as extrapolated
    m = ds.method.values.astype(str)
    rc = ds.recheck_method.values.astype(str)
    over = ds.screen_overruled.values.astype(bool)
    np.testing.assert_array_equal(rc != "none", (m == "screened") | over)
    assert ds.attrs["screen_recheck_cells"] == int((rc != "none").sum()) > 0
    assert over.sum() == ds.attrs["screen_overruled_cells"] == 2
    assert (rc[over] == "extrapolated").all() and (m[over] == "extrapolated").all()
    assert (ds.cell_rate.values[over] > ds.recheck_rate.values[over] * 0.999).all()
    assert ds.attrs["screen_recheck_failures"] == 0 and (ds.recheck_failures.values[rc == "counted"] == 0).all()
    assert np.nanmax(ds.recheck_roll_max.values) < 0.5 * float(ds.failure_angle)
    assert (ds.recheck_rate_hi.values[rc != "none"] > 0).all()
    # every recheck ran records x ceil(p / mean p) records, so no cell weighs more than mean p / (records
    # x duration) in the pooled bound; no failure: the estimate is 0 and the Fay-Feuer upper bound of
    # zero counts is -ln(alpha / 2) max p / T (exact for zero counts)
    sel = rc != "none"
    p, pm = ds.probability.values, float(ds.probability.mean())
    np.testing.assert_array_equal(ds.recheck_records.values[sel], np.ceil(p[sel] / pm - 1e-12).astype(int))
    assert (ds.recheck_records.values[~sel] == 0).all() and ds.recheck_records.values[sel].max() > 1
    np.testing.assert_array_equal(ds.recheck_exposure.values[sel], ds.recheck_records.values[sel] * CFG["duration"])
    w = p[sel] / ds.recheck_exposure.values[sel]
    assert w.max() <= pm / CFG["duration"] * (1 + 1e-12)
    yr = 365.25 * 86400.0
    assert float(ds.screen_recheck_rate) == 0.0
    assert float(ds.screen_recheck_rate_hi) == pytest.approx(-math.log(0.025) * w.max() * yr, rel=1e-9)
    assert ds.attrs["screen_recheck_w_max"] == pytest.approx(w.max() * yr, rel=1e-12)
    # the per-cell Poisson bounds summed (the check before pooling) would be several times larger
    assert float(ds.screen_recheck_rate_hi) < 0.2 * float(np.sum(p[sel] * ds.recheck_rate_hi.values[sel]) * yr)
    up, width = float(ds.screen_recheck_rate_hi), float(ds.interval_width)
    assert ds.attrs["screen_recheck_verdict"] == ("PASS" if up <= width else "NOT SHOWN")
    # the barge in beam seas up to Hs 5.5 m: failures are counted in some cells, and they carry the rate
    assert (ds.failures.values[m == "counted"] > 0).any()
    assert float(ds.part_share.sel(part="counted")) > 0.5
    # beam seas vary nothing along the ship: no cell is left out of the screening for parametric roll
    assert ds.attrs["parametric_cells"] == 0 and (ds.parametric_fraction.values[ds.heading.values == 90.0] == 0).all()
    # head seas are never screened (parametric roll is not Gaussian); headings 90 and 180 at 2:1 weight
    head = ds.heading.values == 180.0
    assert (m[head] != "screened").all()
    same = (ds.hs.values == ds.hs.values[0]) & (ds.tz.values == ds.tz.values[0])
    p90, p180 = (float(ds.probability.values[same & (ds.heading.values == h)][0]) for h in (90.0, 180.0))
    assert p90 == pytest.approx(2 * p180)


def test_small_assessment_is_deterministic(small):
    ship, cells = small
    again = dsa_run.assess_cells(ship, CFG, 40.0, 100.0, crew_z=10.0)
    np.testing.assert_array_equal(cells.roll_sigma.values, again.roll_sigma.values)
    np.testing.assert_array_equal(cells.failures.values, again.failures.values)
    np.testing.assert_array_equal(cells.cell_rate_hi.values[cells.method.values != "counted"],
                                  again.rate_hi.values[again.method.values != "counted"])


def test_row_straddling_the_standard_has_no_verdict(small, tmp_path, monkeypatch):
    """An interval that straddles the standard decides nothing: NOT EVALUATED, saying so (the
    standard overridden to lie inside the barge's interval). The long-term standard does not enter
    the cells, so the assessment aggregates the small assessment's own cells again."""
    ship, ds = small
    p = tmp_path / "over.yaml"
    mid = float(np.sqrt(float(ds.rate_lo) * float(ds.rate_hi)))
    p.write_text("criteria_overrides:\n"
                 f"  - {{key: sgisc.direct_stability_assessment.long_term_standard, value: {mid}, source: 'test'}}\n")
    monkeypatch.setattr(dsa_run, "assess_cells", lambda *a, **k: CELLS["barge"].copy(deep=True))
    again = dsa_run.assess_dsa(ship, CRIT, CFG, std=Standards(p))
    assert float(again.rate) == float(ds.rate) and float(again.rate_hi) == float(ds.rate_hi)
    assert again.attrs["row_verdict"] == "NOT EVALUATED" and "straddles the standard" in again.attrs["row_reason"]
    assert again.attrs["row_value"] == float(again.rate)


def test_cell_seeds_depend_on_the_cell_only():
    assert dsa_run.cell_seed(1, 2, 3, 4, 5, 0) == dsa_run.cell_seed(1, 2, 3, 4, 5, 0)
    assert len({dsa_run.cell_seed(0, i, j, 0, 0, s) for i in range(5) for j in range(5) for s in (0, 1)}) == 50
    assert dsa_run.cell_seed(0, 1, 0, 0, 0, 0) != dsa_run.cell_seed(1000, 0, 0, 0, 0, 0)


def test_acceleration_limit_comes_from_the_standards(tmp_path):
    """The sourced lateral-acceleration limit (Circ.1627 3.2.1.2) is a failure the engine counts;
    without one (a data file whose entry is null) the DSA row names it missing, never a verdict on
    roll alone; an override changes it."""
    from stabflow.criteria.dsa_run import ACC_KEY, acceleration_limit, acceleration_missing

    assert acceleration_limit(Standards()) == 9.81 and acceleration_missing(Standards()) == []
    std = Standards()
    std.entries[ACC_KEY] = {**std.entries[ACC_KEY], "value": None, "missing": "not found (test)"}
    assert acceleration_missing(std) == [f"{ACC_KEY} (lateral acceleration failure not assessed)"]
    assert acceleration_limit(std) is None
    with pytest.raises(Exception, match="crew location"):
        dsa_run.assess_cells(load_ship(SHIPS / "barge.yaml"), CFG, 40.0, 100.0)
    p = tmp_path / "over.yaml"
    p.write_text("criteria_overrides:\n"
                 f"  - {{key: {ACC_KEY}, value: 4.0, source: 'stricter requirement of an Administration'}}\n")
    assert acceleration_limit(Standards(p)) == 4.0


def test_failures_are_the_union_of_roll_and_acceleration_crossings():
    """Roll and lateral-acceleration crossings closer than the window are one failure; crossings of
    a second acceleration level do not count."""
    ens = xr.Dataset({"crossing_record": ("crossing", [0, 1]), "crossing_time": ("crossing", [10.0, 40.0]),
                      "lateral_crossing_record": ("lateral_crossing", [0, 0, 1, 1]),
                      "lateral_crossing_limit": ("lateral_crossing", [0, 0, 0, 1]),
                      "lateral_crossing_time": ("lateral_crossing", [12.0, 30.0, 100.0, 70.0])},
                     coords={"record": [0, 1]})
    # record 0: 10 (roll) and 12 (acceleration) one failure, 30 another; record 1: 40 and 100; 70 is level 1
    np.testing.assert_array_equal(dsa_run.failures_per_record(ens, 5.0), [2, 2])


def test_a_lower_acceleration_limit_adds_failures(small, tmp_path):
    """The same small assessment with a lateral-acceleration limit of 1.5 m/s2 (an override) instead
    of 9.81: with the same roll (same seeds), every cell simulated in both runs that counted failures
    still counts some, and more are counted in all (not necessarily in every cell: an acceleration
    crossing between two roll failures further apart than the declustering window joins them into one,
    as in one barge cell, Hs 4.5 m, Tz 7.5 s, beam seas: 2 -> 1); the cells' acceleration sigma grows
    with the sea; the row names the limit."""
    from stabflow.criteria.dsa_run import ACC_KEY

    ship, base = small
    p = tmp_path / "over.yaml"
    p.write_text("criteria_overrides:\n"
                 f"  - {{key: {ACC_KEY}, value: 1.5, source: 'test document 3.1'}}\n")
    low = dsa_run.assess_dsa(ship, CRIT, CFG, std=Standards(p))
    m0, m1 = base.method.values.astype(str), low.method.values.astype(str)
    # (an overruled cell carries its recheck's run: other seeds and records)
    sim = (m0 != "screened") & (m1 != "screened") & ~base.screen_overruled.values.astype(bool) \
        & ~low.screen_overruled.values.astype(bool)
    assert sim.any()
    np.testing.assert_array_equal(low.roll_sigma.values[sim], base.roll_sigma.values[sim])
    k0, k1 = base.failures.values[sim & (m0 == "counted")], low.failures.values[sim & (m0 == "counted")]
    assert ((k1 >= 1) | (k0 == 0)).all() and (k1 > k0).any() and k1.sum() > k0.sum()
    assert float(low.rate) > float(base.rate)
    i, j = int(np.argmin(low.hs.values)), int(np.argmax(low.hs.values))
    assert low.lateral_sigma.values[j] > low.lateral_sigma.values[i] > 0
    assert "lateral acceleration beyond 1.5 m/s2" in low.attrs["row_criterion"]
    assert ACC_KEY not in low.attrs["row_reason"]


def test_the_dsa_step_reads_the_override_file(small, tmp_path):
    """The dsa step (as the pipeline's rule and the CLI call it) applies the criteria override file
    as the criteria step does: the override's lateral-acceleration limit is the one the row judges
    by, and the file's entries are recorded in the results (``standards_overridden``); without the
    file, "none" and the sourced 9.81 m/s2."""
    from stabflow.criteria.dsa_run import ACC_KEY
    from stabflow.steps import run_dsa

    ship, base = small
    assert base.attrs["standards_overridden"] == "none"
    assert "lateral acceleration beyond 9.81 m/s2" in base.attrs["row_criterion"]
    crit = tmp_path / "crit.nc"
    CRIT.to_netcdf(crit)
    p = tmp_path / "over.yaml"
    p.write_text("criteria_overrides:\n"
                 f"  - {{key: {ACC_KEY}, value: 1.5, source: 'test document 3.1'}}\n")
    out = run_dsa(SHIPS / "barge.yaml", crit, CFG, tmp_path / "dsa.nc", progress=False, overrides=p)
    assert "lateral acceleration beyond 1.5 m/s2" in out.attrs["row_criterion"]
    assert ACC_KEY in out.attrs["standards_overridden"] and "test document 3.1" in out.attrs["standards_overridden"]
    on_disk = xr.open_dataset(tmp_path / "dsa.nc")
    assert on_disk.attrs["standards_overridden"] == out.attrs["standards_overridden"]
    on_disk.close()


def test_no_cell_interval_is_a_bare_zero(small):
    """Every cell carries a positive upper bound: counted cells their Poisson bound, screened ones
    their Gaussian bound, or ``SCREEN_FLOOR`` where its exp() underflows (calm cells of the small
    barge assessment: roll sigma well below 1/38 of the failure angle)."""
    _, out = small
    hi = out.cell_rate_hi.values
    assert np.all(hi > 0)
    m = out.method.values.astype(str)
    scr = m == "screened"
    assert np.all(hi[scr] >= dsa_run.SCREEN_FLOOR)
    floored = scr & (hi == dsa_run.SCREEN_FLOOR)
    assert floored.any()  # the underflow case is exercised here
    assert np.all(out.roll_sigma.values[floored] < float(out.failure_angle) / 38.0)


def _peaks_ensemble(seed, hours, sigma=2.0, period=10.0):
    """A stand-in for a zero-failure cell's ensemble: one record of ``hours`` with a roll peak every
    ``period`` s, Rayleigh-distributed with scale ``sigma`` [degree] and alternating in sign."""
    rng = np.random.default_rng(seed)
    n = int(hours * 3600 / period)
    v = sigma * np.sqrt(-2 * np.log(rng.uniform(size=n))) * np.where(np.arange(n) % 2, -1.0, 1.0)
    return xr.Dataset({"peak_record": ("peak", np.zeros(n, np.int64)), "peak_time": ("peak", period * np.arange(n)),
                       "peak_value": ("peak", v), "capsized": ("record", [False]), "capsize_time": ("record", [np.nan]),
                       "exposure_hours": hours, "roll_std": sigma},
                      coords={"record": [0]})


def test_zero_count_cells_are_extrapolated_from_a_lower_threshold():
    """A 20-min zero-failure cell (Rayleigh roll peaks, sigma 2 degree): too few peaks beyond 3.5 sigma
    to fit, so the tail fit runs from 3.0 or 2.5 sigma and gives a rate at the failure angle (40
    degree, 20 sigma) inside its profile-likelihood interval, with an upper bound far below the
    Poisson bound of a zero count (3.69 per exposure); a peak floor above 2.5 sigma leaves it
    unfitted (NaN: the zero count then stays counted); an 8-hour cell fits at 3.5 sigma."""
    from stabflow.statistics.extremes import MIN_EXCEEDANCES

    short = _peaks_ensemble(1, 1 / 3)
    assert np.sum(np.abs(short.peak_value.values) > 3.5 * 2.0) < MIN_EXCEEDANCES
    r, lo, hi, used = dsa_run._extrapolate(short, 40.0, 0.05, 10.0)
    assert used[0] in (3.0, 2.5) and math.isnan(used[1])
    assert 0.0 <= lo <= r <= hi < 3.69 / 1200.0
    *rr, used = dsa_run._extrapolate(short, 40.0, 0.05, 10.0, floors=(2.6 * 2.0, 0.0))
    assert all(math.isnan(x) for x in rr) and math.isnan(used[0])
    long = _peaks_ensemble(2, 8.0)
    r, lo, hi, used = dsa_run._extrapolate(long, 40.0, 0.05, 10.0)
    assert used[0] == 3.5 and 0.0 <= lo <= r <= hi


def test_a_simulation_overrules_the_screening():
    """A screened cell whose simulation counts failures, or fits a tail rate above the Gaussian
    bound, is overruled; a zero count without a fit, or a fitted rate at or below the bound, is not."""
    assert dsa_run.overrules("counted", 1, np.nan, 1e-9)
    assert not dsa_run.overrules("counted", 0, 0.0, 1e-9)
    assert dsa_run.overrules("extrapolated", -1, 2e-9, 1e-9)
    assert not dsa_run.overrules("extrapolated", -1, 1e-9, 1e-9)


def test_overruled_cells_enter_the_rate_as_simulated(small, monkeypatch):
    """An overruled screened cell carries its simulation into the long-term rate: method, count,
    exposure, roll sigma and largest roll become the recheck's, the rest of the cells are those of
    the run without overruling (same seeds). The rule is forced here for every counted recheck (a
    calm Gaussian barge cell never contradicts its Gaussian bound; on the shipped DTC the default
    run overrules 18 cells: 16 that pass 40 degree within 20 minutes, 2 whose tail fit exceeds the bound)."""
    ship, base = small
    monkeypatch.setattr(dsa_run, "overrules", lambda method, failures, rate, bound: method == "counted")
    cells = dsa_run.assess_cells(ship, CFG, 40.0, 100.0, crew_z=10.0)
    over = cells.screen_overruled.values.astype(bool)
    was = base.method.values.astype(str) == "screened"
    np.testing.assert_array_equal(over, was & (base.recheck_method.values.astype(str) == "counted"))
    assert over.any()
    assert (cells.method.values.astype(str)[over] == "counted").all()
    np.testing.assert_array_equal(cells.failures.values[over], base.recheck_failures.values[over])
    np.testing.assert_array_equal(cells.exposure.values[over], base.recheck_records.values[over] * CFG["duration"])
    np.testing.assert_array_equal(cells.roll_max_cell.values[over], base.recheck_roll_max.values[over])
    assert (cells.roll_sigma.values[over] != base.roll_sigma.values[over]).all()  # the 20-min record's, not the screen's
    rest = ~over & ~base.screen_overruled.values.astype(bool)  # (the base run's overruled cells are extrapolated)
    np.testing.assert_array_equal(cells.method.values.astype(str)[rest], base.method.values.astype(str)[rest])
    np.testing.assert_array_equal(cells.failures.values[rest], base.failures.values[rest])


def test_screening_recheck_verdicts():
    """The recheck's verdict on synthetic cells: the screened cells' counts pooled by Fay & Feuer
    (an overruled cell's failures included: the bound is on all screened cells, free of selecting the
    cells that stay screened by their zero counts; an extrapolated recheck enters with its zero
    count). PASS when the pooled upper bound is within the simulated cells' interval width, FAIL when
    the estimate exceeds it, NOT SHOWN in between; SKIPPED when nothing was screened or the recheck is off."""
    yr = 365.25 * 86400.0

    def cells(rates, his, methods, failures, exposure, p=0.1):
        n = len(rates)
        over = [int(dsa_run.overrules(m, k, r, 1e-8)) for m, k, r in zip(methods, failures, rates)]
        return xr.Dataset({"probability": ("cell", np.broadcast_to(np.asarray(p, float), (n,))),
                           "recheck_method": ("cell", methods),
                           "recheck_rate": ("cell", np.array(rates, float)),
                           "recheck_rate_hi": ("cell", np.array(his, float)),
                           "recheck_failures": ("cell", np.array(failures)), "screen_overruled": ("cell", over),
                           "recheck_exposure": ("cell", np.array(exposure, float))})

    # an extrapolated tail above the bound (overruled, its count 0), a zero count, a cell not screened
    ds = cells([2e-8, 0.0, 0.0], [3e-8, 1e-7, 0.0], ["extrapolated", "counted", "none"], [-1, 0, -1],
               [3600.0, 7200.0, np.nan], p=[0.1, 0.1, 0.3])
    a = dsa_run.screening_recheck(ds, width=1.0)
    assert a["screen_recheck_cells"] == 2 and a["screen_overruled_cells"] == 1 and a["screen_recheck_zero_unfitted"] == 1
    assert a["screen_overruled_rate"] == pytest.approx(0.1 * 2e-8 * yr)
    # zero counts: -ln(0.025) x the largest weight, 0.1 / 3600 s per year
    up = -math.log(0.025) * 0.1 / 3600.0 * yr
    assert float(ds.screen_recheck_rate) == 0.0 and float(ds.screen_recheck_rate_hi) == pytest.approx(up, rel=1e-9)
    assert a["screen_recheck_hours"] == pytest.approx(3.0)
    assert a["screen_recheck_verdict"] == "NOT SHOWN"
    assert dsa_run.screening_recheck(ds, width=1.01 * up)["screen_recheck_verdict"] == "PASS"
    # counted failures (the overruled cell's too) enter the estimate sum p k / T
    bad = cells([1e-9, 1e-4], [2e-9, 2e-4], ["extrapolated", "counted"], [-1, 3], [3600.0, 3600.0])
    est = 0.1 * 3 / 3600.0 * yr
    _, _, up = dsa.fay_feuer_interval([0, 3], [0.1 / 3600.0, 0.1 / 3600.0])
    b = dsa_run.screening_recheck(bad, width=0.5 * (est + up * yr))
    assert float(bad.screen_recheck_rate) == pytest.approx(est, rel=1e-12)
    assert float(bad.screen_recheck_rate_hi) == pytest.approx(up * yr, rel=1e-12) and up * yr > 2 * est
    assert b["screen_recheck_failures"] == 3 and "3 failures" in b["screen_recheck_reason"]
    assert b["screen_overruled_cells"] == 1 and b["screen_recheck_verdict"] == "NOT SHOWN"
    assert dsa_run.screening_recheck(bad, width=up * yr)["screen_recheck_verdict"] == "PASS"
    assert dsa_run.screening_recheck(bad, width=0.9 * est)["screen_recheck_verdict"] == "FAIL"
    none = cells([0.0], [0.0], ["none"], [-1], [np.nan])
    assert dsa_run.screening_recheck(none, 1.0)["screen_recheck_verdict"] == "SKIPPED"
    assert dsa_run.screening_recheck(none.drop_vars("recheck_method"), 1.0)["screen_recheck_reason"] == \
        "screen.recheck is off"


def test_recheck_records_follow_the_probability():
    """records x ceil(p / mean p): no cell weighs more than mean p / (records x duration) in the pooled
    bound; 'uniform' gives every cell the records; anything else is refused."""
    p = np.array([0.001, 0.01, 0.0105, 0.05])
    n = [dsa_run.recheck_records(x, 0.01, 2, "probability") for x in p]
    assert n == [2, 2, 4, 10]
    assert np.all(p / np.array(n) <= 0.01 / 2 * (1 + 1e-12))
    assert dsa_run.recheck_records(0.05, 0.01, 2, "uniform") == 2
    with pytest.raises(ValueError, match="recheck_allocation"):
        dsa_run.recheck_records(0.05, 0.01, 2, "more")


def test_pooled_bound_covers_heterogeneous_screened_cells():
    """The pooled Fay-Feuer upper bound of mostly-zero counts misses the true sum C = sum w mu at most
    alpha / 2 of the time when C lies just beyond what zero counts can bound (C = 3.75 w_M > -ln(0.025)
    w_M: every replicate without a failure misses; exp(-sum mu) <= exp(-C / w_M) = 0.0235), both with
    the expected counts spread over four decades across 200 cells and with all of them in the
    heaviest cell (where that inequality is tight). 20000 replicates each."""
    rng = np.random.default_rng(3)
    n = 200
    w = rng.uniform(0.2, 1.0, n)
    w[0] = 1.0
    for shape in (10 ** rng.uniform(-4, 0, n), np.eye(n)[0]):
        mu = shape * 3.75 / np.sum(w * shape)  # sum w mu = 3.75 = 3.75 w_M
        k = rng.poisson(mu, (20000, n))
        hi = np.array([dsa.fay_feuer_interval(ki, w)[2] for ki in k])
        miss = float(np.mean(hi < 3.75))
        assert float(np.mean(~k.any(axis=1))) <= miss  # the zero replicates all miss
        assert miss <= 0.025 + 3 * math.sqrt(0.025 * 0.975 / 20000)


def test_parametric_fraction_against_the_closed_form():
    """At zero speed in following seas the components that drive principal parametric roll form one
    frequency interval: w in 2 w_phi (1 +- band) with lambda = 2 pi g / w^2 within [0.5, 2] L. The
    Bretschneider spectrum A w^-5 exp(-B w^-4) integrates in closed form, (A / 4B) exp(-B w^-4), so
    the fraction is exact: the grid integral matches it to 1e-4. Beam seas vary nothing along the
    ship: 0. A long roll period puts the resonance in stern-quartering seas at speed (the DTC)."""
    from stabflow.constants import G

    hs, tz, T_roll = 4.0, 7.0, 12.0
    w2 = 4 * math.pi / T_roll
    L = 2 * math.pi * G / w2**2  # lambda = L at twice the roll frequency
    f = dsa_run.parametric_fraction(hs, tz, 0.0, 0.0, T_roll, L, 0.3, (0.5, 2.0))
    # the spectrum's B from two of its values: S w^5 = A exp(-B w^-4)
    wa, wb = 0.6, 1.2
    sa, sb = (dsa.bretschneider_tz(w, hs, tz) * w**5 for w in (wa, wb))
    B = math.log(sb / sa) / (wa**-4 - wb**-4)
    lo, hi = dsa.spectrum_band(hs, tz)
    # lambda in [0.5, 2] L <=> w in [w2 / sqrt(2), w2 sqrt(2)]; the band 2 w_phi (1 +- 0.3) lies inside it
    a, b = max(w2 * 0.7, w2 / math.sqrt(2), lo), min(w2 * 1.3, w2 * math.sqrt(2), hi)
    F = lambda w: math.exp(-B * w**-4)  # noqa: E731
    exact = (F(b) - F(a)) / (F(hi) - F(lo))
    assert 0.2 < exact < 0.9
    assert f == pytest.approx(exact, abs=1e-3)  # the mask on a 2000-point grid (measured 2e-4)
    assert dsa_run.parametric_fraction(hs, tz, 90.0, 5.0, T_roll, L, 0.3, (0.5, 2.0)) == 0.0
    # the DTC at Fn 0.1 (5.9 m/s, L 364 m, roll period 38 s): 30 deg off the stern in Hs 6.5 m, Tz 10.5 s
    # a quarter of the sea drives it, bow-quartering (120 deg) nothing
    assert dsa_run.parametric_fraction(6.5, 10.5, 60.0, 5.94, 38.4, 363.6, 0.3, (0.5, 2.0)) > 0.1
    assert dsa_run.parametric_fraction(6.5, 10.5, 120.0, 5.94, 38.4, 363.6, 0.3, (0.5, 2.0)) < 0.01


def test_the_pressure_decay_term_reaches_the_cells_models():
    """``dsa.dphi_dzdt`` (the pipeline's default: true) puts the depth-averaged d2phi/dzdt term in
    every cell's model (the sections' pressure decay is built); off, the condition has no key
    and the model no decay (paper 000's kernel)."""
    on = dsa_run.condition(dict(CFG, dphi_dzdt=True), "barge", 2.0, 7.0, 90.0, 5.0, 1, 60.0, 0, 40.0, 1.0)
    off = dsa_run.condition(CFG, "barge", 2.0, 7.0, 90.0, 5.0, 1, 60.0, 0, 40.0, 1.0)
    assert on["dphi_dzdt"] is True and "dphi_dzdt" not in off
    ship = load_ship(SHIPS / "barge.yaml")
    m_on, m_off = (next(iter(dsa_run._models(ship, c, [90.0], [5.0], None, 40.0).values()))
                   for c in (dict(CFG, dphi_dzdt=True), CFG))
    assert m_off.decay is None and m_on.decay is not None
    # the wall-sided box of draft 6 m: every section's area-averaged e^(k z) is (1 - e^(-6 k)) / (6 k)
    k = np.array([0.01, 0.1, 1.0])
    np.testing.assert_allclose(m_on.decay(k), np.broadcast_to(-np.expm1(-6 * k) / (6 * k), (len(m_on.sec.x), 3)),
                               rtol=1e-9)
    from stabflow.config import schema

    assert schema("config")["properties"]["dsa"]["properties"]["dphi_dzdt"]["default"] is True
