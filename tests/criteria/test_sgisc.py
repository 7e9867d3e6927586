"""Second-generation level-1 physics on the box barge in closed form."""

import math

import numpy as np
import pytest

from stabflow.config import load_ship
from stabflow.criteria import sgisc
from stabflow.criteria.standards import Standards
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics
from tests.conftest import SHIPS

L, B, T, KG = 100.0, 20.0, 6.0, 7.0


@pytest.fixture(scope="module")
def box():
    ship = load_ship(SHIPS / "barge.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    gw = sgisc.gm_on_wave(Sections(hull), float(st["volume"]), float(st["lcg"]), KG, float(st["lwl"]),
                          [0.01, 0.03, 0.05], n_crest=8, draft=T)
    return st, gw


def test_gm_on_wave_box_closed_form(box):
    """Wall-sided box on a wave of its own length (amplitude a, no sinkage over a whole wave):
    crest or trough amidships, KB = T/2 + a^2/(4T) and BM unchanged, so GM = GM0 + a^2/(4T);
    crest at a quarter length, the trim tan(theta) = -12 a / (k L^2) that keeps LCB gives
    GM = GM0 + a^2/T (1/4 - 6/(kL)^2) to first order in the trim."""
    st, gw = box
    gm0 = float(st["gm"])
    kL = 2 * math.pi
    for s in gw.steepness.values:
        a = 0.5 * s * L
        g = gw["gm_wave"].sel(steepness=s)
        assert float(g.sel(crest_position=0.0)) == pytest.approx(gm0 + a**2 / (4 * T), abs=1e-9)
        assert float(g.sel(crest_position=-L / 2)) == pytest.approx(gm0 + a**2 / (4 * T), abs=1e-9)
        quarter = float(g.sel(crest_position=-L / 4))
        assert quarter == pytest.approx(gm0 + a**2 / T * (0.25 - 6 / kL**2), rel=2e-3)
        assert float(gw["gm_wave_min"].sel(steepness=s)) == pytest.approx(quarter, abs=1e-12)


def test_waterplane_route_box_is_zero(box):
    """Wall-sided: the waterplane inertia does not change with draft, delta GM1 = 0 exactly."""
    _, gw = box
    assert np.abs(gw["delta_gm_waterplane"].values).max() < 1e-12
    assert sgisc.waterplane_inertia(Sections(build_hull(load_ship(SHIPS / "barge.yaml"))), T) == pytest.approx(B**3 * L / 12, rel=1e-12)


def _rows(gw, std, fn=0.2):
    simple = {m: sgisc.simplified_level1(Sections(build_hull(load_ship(SHIPS / "barge.yaml"))), L * B * T, KG, T, 12.0, L,
                                         sw, 0.25) for m, sw in (("pure_loss", 0.0334), ("parametric", 0.0167))}
    return {r.criterion: r for r in sgisc.level1_rows(gw, simple, 1.5556, L, fn, std, (0.17, "test"), 1.0)}


def test_simplified_level1_box_closed_form():
    """Box: d_L = d - min(0.75 d, L SW/2), d_H = d + min(D - d, L SW/2); GMmin = d_L/2 + (B^3 L/12)/V - KG;
    delta GM1 = 0 (wall-sided)."""
    sec = Sections(build_hull(load_ship(SHIPS / "barge.yaml")))
    for sw in (0.0167, 0.0334, 0.2):
        r = sgisc.simplified_level1(sec, L * B * T, KG, T, 12.0, L, sw, 0.25)
        dl = T - min(0.75 * T, L * sw / 2)
        assert r["d_L"] == pytest.approx(dl) and r["d_H"] == pytest.approx(T + min(12.0 - T, L * sw / 2))
        assert r["gm_min"] == pytest.approx(dl / 2 + B**3 * L / 12 / (L * B * T) - KG, rel=1e-9)
        assert abs(r["delta_gm1"]) < 1e-12


def test_rpr_formula():
    """R_PR = 0.17 + c min(100 Ak/(L B), 4), c by Cm (sgisc.yaml): continuous at Cm 0.94 and 0.96."""
    std = Standards()
    ak = 0.01 * L * B  # 100 Ak / (L B) = 1
    assert sgisc.rpr(std, 0.90, 0.0, L, B, "round")[0] == pytest.approx(0.17)
    assert sgisc.rpr(std, 0.90, ak, L, B, "round")[0] == pytest.approx(0.17 + 0.2125)
    assert sgisc.rpr(std, 0.94, ak, L, B, "round")[0] == pytest.approx(0.17 + 0.2125)
    assert sgisc.rpr(std, 0.96, ak, L, B, "round")[0] == pytest.approx(0.17 + 0.425)
    assert sgisc.rpr(std, 0.99, 10 * ak, L, B, "round")[0] == pytest.approx(0.17 + 0.425 * 4)


def test_level1_rows(box):
    """Sourced level-1 standards give verdicts; the surf-riding limits, read in drafts only, stay NOT
    EVALUATED with the verdict against the drafts (L 200 m, Fn 0.3) beside it as indicative."""
    _, gw = box
    rows = _rows(gw, Standards())
    assert rows["pure loss: GMmin by waterplane inertia at d_L"].verdict == "PASS"
    assert rows["parametric rolling: delta GM1 / GM by waterplane inertias"].verdict == "PASS"
    k = "surf-riding/broaching: L above the limit or Fn below the limit"
    assert rows[k].verdict == "NOT EVALUATED" and "missing: sgisc." in rows[k].reason
    # L 100 m below the draft's 200 m: Fn decides, 0.2 below the draft's 0.3
    assert rows[k].draft_verdict == "PASS" and rows[k].draft_limit == 0.3
    assert "Indicative, against the draft's limit 0.3" in rows[k].reason and "ISSW_2017_s07-p2.pdf" in rows[k].draft_source
    rows = _rows(gw, Standards(), fn=0.35)
    assert rows[k].verdict == "NOT EVALUATED" and rows[k].draft_verdict == "FAIL"
    # without a service speed the row has a missing item no draft covers: no indicative verdict
    rows = _rows(gw, Standards(), fn=None)
    assert rows[k].verdict == "NOT EVALUATED" and rows[k].draft_verdict == "" and "service speed" in rows[k].reason


def test_surf_riding_draft_length_limit(box, tmp_path):
    """A ship longer than the draft's 200 m: indicative PASS on its length, the row's unit metres."""
    _, gw = box
    simple = {m: sgisc.simplified_level1(Sections(build_hull(load_ship(SHIPS / "barge.yaml"))), L * B * T, KG, T, 12.0, L,
                                         sw, 0.25) for m, sw in (("pure_loss", 0.0334), ("parametric", 0.0167))}
    rows = {r.criterion: r for r in sgisc.level1_rows(gw, simple, 1.5556, 250.0, 0.35, Standards(), (0.17, "test"), 1.0)}
    r = rows["surf-riding/broaching: L above the limit or Fn below the limit"]
    assert r.verdict == "NOT EVALUATED" and r.draft_verdict == "PASS" and r.unit == "m" and r.draft_limit == 200.0


def test_override_makes_a_verdict(box, tmp_path):
    """A user who holds the circular supplies the values: the rows turn into verdicts, sourced."""
    _, gw = box
    p = tmp_path / "over.yaml"
    p.write_text(
        "criteria_overrides:\n"
        "  - {key: sgisc.failure_modes.surf_riding_broaching.level_1.length_limit_m, value: 50.0, source: 'test document 1.2'}\n"
        "  - {key: sgisc.failure_modes.surf_riding_broaching.level_1.froude_number_limit, value: 0.1, source: 'test document 1.3'}\n")
    rows = _rows(gw, Standards(p))
    k = "surf-riding/broaching: L above the limit or Fn below the limit"
    assert rows[k].verdict == "PASS" and "not vulnerable" in rows[k].note  # L 100 m above 50 m
    assert rows[k].draft_verdict == "" and rows[k].draft_limit is None  # the adopted value replaces the draft
    assert "test document 1.2" in rows[k].source and "override file" in rows[k].source
    p.write_text(
        "criteria_overrides:\n"
        "  - {key: sgisc.failure_modes.surf_riding_broaching.level_1.length_limit_m, value: 200.0, source: 'test document 1.2'}\n"
        "  - {key: sgisc.failure_modes.surf_riding_broaching.level_1.froude_number_limit, value: 0.1, source: 'test document 1.3'}\n")
    rows = _rows(gw, Standards(p))
    assert rows[k].verdict == "FAIL"  # L below 200 m and Fn 0.2 above 0.1
    assert "test document 1.3" in rows[k].source
    # only the Froude limit supplied: Fn below it clears the ship whatever the length limit
    p.write_text("criteria_overrides:\n  - {key: sgisc.failure_modes.surf_riding_broaching.level_1.froude_number_limit, "
                 "value: 0.25, source: 'test document 1.3'}\n")
    rows = _rows(gw, Standards(p))
    assert rows[k].verdict == "PASS" and rows[k].draft_verdict == ""
    # Fn above it: the length limit decides, drafted only: NOT EVALUATED, indicative FAIL against the
    # adopted 0.1, which the reason does not call a draft's
    p.write_text("criteria_overrides:\n  - {key: sgisc.failure_modes.surf_riding_broaching.level_1.froude_number_limit, "
                 "value: 0.1, source: 'test document 1.3'}\n")
    rows = _rows(gw, Standards(p))
    assert rows[k].verdict == "NOT EVALUATED" and rows[k].draft_verdict == "FAIL" and rows[k].draft_limit == 0.1
    assert "the draft's limit" not in rows[k].reason and "drafts' values of the other missing standards" in rows[k].reason

def test_roll_1dof_free_decay_and_mathieu():
    """Constant restoring (no wave): linear free decay with the damped frequency and decrement of
    the oscillator; restoring GM (1 + eps cos w_e t) at w_e = 2 w0 (the passing wave as a table in
    crest position): grows for eps above the Mathieu threshold 4 zeta, decays below it."""
    from stabflow.criteria.sgisc import roll_1dof

    heel = np.arange(0.0, 70.01, 0.5)
    gm, inertia, weight, lam = 1.0, 1.0, 0.25, 100.0  # w0 = 0.5 rad/s
    w0 = math.sqrt(weight * gm / inertia)
    zeta = 0.02
    b44 = 2 * zeta * w0 * inertia
    flat = np.tile(gm * np.sin(np.radians(heel)), (24, 1))
    roll = roll_1dof(flat, heel, lam, 0.0, inertia, b44, 0.0, weight, 2.0, 200.0, 0.05)
    t = np.arange(len(roll)) * 0.05
    wd = w0 * math.sqrt(1 - zeta**2)
    # small amplitude: sin(phi) ~ phi to 2e-4 relative at 2 deg
    exact = 2.0 * np.exp(-zeta * w0 * t) * (np.cos(wd * t) + zeta * w0 / wd * np.sin(wd * t))
    assert np.abs(roll - exact).max() < 2e-3
    # the wave passes at v_rel: one wave length per encounter period 2 pi / (2 w0)
    v_rel = lam * 2 * w0 / (2 * math.pi)
    xc = np.arange(24) / 24 * 2 * math.pi
    for eps, grows in ((0.16, True), (0.04, False)):
        tab = np.array([gm * (1 + eps * math.cos(x)) * np.radians(heel) for x in xc])
        r = roll_1dof(tab, heel, lam, v_rel, inertia, b44, 0.0, weight, 1.0, 300.0, 0.05)
        late = np.nanmax(np.abs(r[-1000:]))
        assert (late > 2.0) if grows else (late < 0.5), (eps, late)


def test_surf_riding_level2_physics():
    """Melnikov's critical Froude number for the trawler: finite, falling with steepness (steeper
    waves capture the ship at lower speed), rising with wave length; the row stays NOT EVALUATED
    (R_SR and the wave cases are not sourced) and reports the lowest threshold."""
    trawler = load_ship(SHIPS / "trawler.yaml")
    L = float(compute_statics(trawler, build_hull(trawler))["lwl"])
    sr = sgisc.surf_riding_thresholds(trawler, {"wavelength_ratios": [1.0, 2.0], "steepness": [0.02, 0.05]}, L)
    f = sr.sr_froude_critical.values
    assert np.isfinite(f).all() and (f > 0.1).all() and (f < 0.6).all()
    assert (f[:, 1] < f[:, 0]).all() and (f[1] > f[0]).all()
    row = sgisc.surf_riding_level2_row(sr, 0.2, Standards())
    assert row.verdict == "NOT EVALUATED" and "R_SR" in row.reason and f"{f.min():.3f}" in row.note
    # the trawler keeps the heave-pitch memory model: without the radiation step's file no wave force
    assert "sr_froude_critical_wave_force" not in sr and "not given" in sr.attrs["sr_wave_force_not_computed"]


def test_surf_riding_level2_with_the_mean_wave_force():
    """With the radiation step's heave-pitch memory (a synthetic passive system here) the grid is
    computed again with the mean wave-induced surge force: each cell is Melnikov's threshold of the
    memory model with ``wave_force=True`` (direct call, 1e-12), and below the plain one (in following
    seas below the celerity the absorbed wave momentum pushes the ship forward); a ship with
    constant heave-pitch coefficients gets none, saying why."""
    from stabflow.dynamics.broaching import six_dof_model
    from stabflow.dynamics.surf_riding import melnikov_threshold
    from tests.conftest import synthetic_memory_dataset

    trawler = load_ship(SHIPS / "trawler.yaml")
    st = compute_statics(trawler, build_hull(trawler))
    L = float(st["lwl"])
    rad = synthetic_memory_dataset(float(st["lcg"]))
    cfg = {"wavelength_ratios": [1.0, 2.0], "steepness": [0.03]}
    sr = sgisc.surf_riding_thresholds(trawler, cfg, L, rad)
    f, w = sr.sr_froude_critical.values, sr.sr_froude_critical_wave_force.values
    assert np.isfinite(w).any() and "sr_wave_force_not_computed" not in sr.attrs
    assert (w[np.isfinite(w)] < f[np.isfinite(w)]).all()
    i = int(np.argmax(np.isfinite(w[:, 0])))
    ship = trawler.modified(dynamics={"hydro": "config", "roll_damping": "coefficients"})
    m = six_dof_model(ship, 0.0, 10.0, tables=(91, 51), radiation=rad)
    lam = cfg["wavelength_ratios"][i] * L
    u = melnikov_threshold(m, lam, 0.03 * lam, wave_force=True)
    assert w[i, 0] == pytest.approx(u / math.sqrt(9.80665 * L), rel=1e-12)
    barge = load_ship(SHIPS / "barge.yaml")
    sb = sgisc.surf_riding_thresholds(barge, cfg, 100.0)
    assert "constant heave-pitch" in sb.attrs.get("sr_wave_force_not_computed", sb.attrs.get("sr_not_computed", ""))


def test_parametric_c1_box_closed_form():
    """C1 (2013 draft, 2.11.3.2) on the wall-sided box in waves of whole sub-multiples of its length
    (lambda = L, L/2): no sinkage, the trim tan(theta) = -/+12 a sin(k x_c) / (k L^2) that keeps the
    LCB, so (first order in the trim) GM(x_c) = GM0 + a^2/T (1/4 - 6 sin^2(k x_c) / (kL)^2): over the ten
    crest positions of a wave length (x_c = 0, +-0.1 ... lambda) the mean GM0 + a^2/T (1/4 - 3/(kL)^2) and
    half the range 3 a^2 sin^2(0.4 pi) / (T (kL)^2) (the largest sin^2 on those positions, 72 deg);
    measured: the mean within 2e-4, the half range within 0.1 % at lambda = L and 0.74 % at L/2 (41
    stations, 20 a wave length). V_PR = |2 lambda / T_phi sqrt(GM(H, lambda)/GM0) - sqrt(g lambda / 2 pi)| exactly
    of the mean; both ratios dGM/GM are below R_PR 0.17, so C_i = 0."""
    from stabflow.constants import G

    ship = load_ship(SHIPS / "barge.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    gm0 = float(st["gm"])
    cases = np.array([[0.25, L, 2.0], [0.75, L / 2, 1.0]])
    c1 = sgisc.parametric_c1(Sections(hull), float(st["volume"]), float(st["lcg"]), KG, gm0, cases, 0.17, 10.0, 5.0)
    a, kL = cases[:, 2] / 2, 2 * math.pi * L / cases[:, 1]
    np.testing.assert_allclose(c1["c1_gm_wave"].values, gm0 + a**2 / T * (0.25 - 3 / kL**2), rtol=2e-4)
    np.testing.assert_allclose(c1["c1_delta_gm"].values, 3 * a**2 * math.sin(0.4 * math.pi) ** 2 / (T * kL**2), rtol=1e-2)
    gmw = c1["c1_gm_wave"].values
    vpr = np.abs(2 * cases[:, 1] / 10.0 * np.sqrt(gmw / gm0) - np.sqrt(G * cases[:, 1] / (2 * math.pi)))
    np.testing.assert_allclose(c1["c1_speed_resonance"].values, vpr, rtol=1e-12)
    assert list(c1["c1_fails"].values) == [0.0, 0.0] and float(c1["c1"]) == 0.0


def test_parametric_c1_requirements(monkeypatch):
    """C_i = 0 where either requirement holds, 1 where neither; GM(H, lambda) <= 0 fails both (V_PR is
    undefined); no service speed: the GM requirement alone (an upper bound); C1 = sum W_i C_i."""
    # stand-in GM on the wave: per case (lambda) a mean and a half range over the crest positions
    spec = {50.0: (1.0, 0.1), 60.0: (1.0, 0.5), 70.0: (-0.2, 0.1), 80.0: (1.0, 0.5)}

    def fake(sec, volume, lcg, kg, amp, k, xc, guess):
        mean, half = spec[round(2 * math.pi / k, 6)]
        return mean + half * math.cos(2 * math.pi * (xc - lcg) * k / (2 * math.pi)), 0.0, 0.0, guess

    monkeypatch.setattr(sgisc, "wave_gm", fake)
    cases = np.array([[0.1, 50.0, 1.0], [0.2, 60.0, 1.0], [0.3, 70.0, 1.0], [0.4, 80.0, 1.0]])
    t_phi, gm0 = 10.0, 1.0
    from stabflow.constants import G

    vpr = np.abs(2 * cases[:, 1] / t_phi - np.sqrt(G * cases[:, 1] / (2 * math.pi)))
    # case 1: ratio 0.1 < 0.3 (GM holds); cases 2 and 4: ratio 0.5 (GM fails), the speed decides:
    # V_PR(60 m) 2.2 < V_D < V_PR(80 m) 4.7 m/s, so case 4 holds on speed and case 2 fails both; case 3 GM < 0
    assert vpr[1] < vpr[3]
    vd = 0.5 * (vpr[1] + vpr[3])
    c1 = sgisc.parametric_c1(None, 1.0, 0.0, 0.0, gm0, cases, 0.3, t_phi, vd)
    np.testing.assert_allclose(c1["c1_gm_ratio"].values[[0, 1, 3]], [0.1, 0.5, 0.5], rtol=1e-12)
    assert np.isnan(c1["c1_gm_ratio"].values[2]) and np.isnan(c1["c1_speed_resonance"].values[2])
    np.testing.assert_allclose(c1["c1_speed_resonance"].values[[0, 1, 3]], vpr[[0, 1, 3]], rtol=1e-12)
    assert list(c1["c1_fails"].values) == [0.0, 1.0, 1.0, 0.0]
    assert float(c1["c1"]) == pytest.approx(0.2 + 0.3)
    assert c1.attrs["c1_speed_requirement"] == "evaluated"
    no_speed = sgisc.parametric_c1(None, 1.0, 0.0, 0.0, gm0, cases, 0.3, t_phi, None)
    assert list(no_speed["c1_fails"].values) == [0.0, 1.0, 1.0, 1.0] and float(no_speed["c1"]) == pytest.approx(0.9)
    assert no_speed.attrs["c1_speed_requirement"] == "not evaluated: no service speed (criteria.service_speed_kn)"
    # a lolling ship (GM <= 0, NaN) or no roll period: the speed requirement is not evaluated either
    for g, t, why in ((0.0, t_phi, "calm-water GM 0 m, not positive"), (np.nan, t_phi, "calm-water GM nan m, not positive"),
                      (gm0, np.nan, "no finite calm-water roll period")):
        d = sgisc.parametric_c1(None, 1.0, 0.0, 0.0, g, cases, 0.3, t, vd)
        assert d.attrs["c1_speed_requirement"] == f"not evaluated: {why}" and float(d["c1"]) == pytest.approx(0.9)
        assert np.isnan(d["c1_speed_resonance"].values).all()
        r = sgisc.parametric_c1_row(d, Standards(), "test")
        assert r.draft_verdict == "" and "the speed requirement" in r.reason
    # no equilibrium on a wave (wave_gm raises): that case NaN, C1 NaN, the row names it
    from stabflow import StabflowError

    def no_eq(sec, volume, lcg, kg, amp, k, xc, guess):
        if round(2 * math.pi / k, 6) == 70.0:
            raise StabflowError("no equilibrium on the wave")
        return fake(sec, volume, lcg, kg, amp, k, xc, guess)

    monkeypatch.setattr(sgisc, "wave_gm", no_eq)
    d = sgisc.parametric_c1(None, 1.0, 0.0, 0.0, gm0, cases, 0.3, t_phi, vd)
    assert np.isnan(d["c1_gm_wave"].values[2]) and np.isnan(d["c1_fails"].values[2]) and np.isnan(float(d["c1"]))
    assert d.attrs["c1_no_equilibrium"] == "3"
    r = sgisc.parametric_c1_row(d, Standards(), "test")
    assert r.verdict == "NOT EVALUATED" and r.draft_verdict == "" and "no equilibrium on wave case(s) 3" in r.reason


def test_c1_cases_adopted_table_and_bad_values():
    """An adopted (overridden) table is read in its entry's columns_expected order (case, W_i, H_i,
    lambda_i) and returned as (W, lambda, H); a value that is not such a table is an error naming the entry."""
    import dataclasses

    from stabflow import StabflowError

    std = Standards()
    base = std.get(sgisc.C1_CASES)

    class Fake:
        def __init__(self, value):
            self.s = dataclasses.replace(base, value=value, read_at="here", draft=None)

        def get(self, key):
            assert key == sgisc.C1_CASES
            return self.s

    cases, src = sgisc.c1_cases(Fake([[1, 0.4, 2.0, 100.0], [2, 0.6, 3.0, 150.0]]))
    np.testing.assert_array_equal(cases, [[0.4, 100.0, 2.0], [0.6, 150.0, 3.0]])
    assert "here" in src
    for bad in (3, [[0.4, 100.0, 2.0]], [1, 2, 3, 4]):
        with pytest.raises(StabflowError, match="must be a table of rows"):
            sgisc.c1_cases(Fake(bad))


def test_parametric_c1_row_and_draft_cases():
    """The 2013 draft's 16 waves are the cases (weights summing to 1 within the table's rounding, the
    Rec. 34 column sums); the row stays NOT EVALUATED with RPR0's and the cases' drafts cited and an
    indicative verdict only where the service speed is known."""
    std = Standards()
    cases, src = sgisc.c1_cases(std)
    assert cases.shape == (16, 3) and abs(cases[:, 0].sum() - 1) < 2e-5 and "Table 3-A-1" in src
    c1 = xr_c1(0.02, 8.0)
    row = sgisc.parametric_c1_row(c1, std, src)
    assert row.verdict == "NOT EVALUATED" and row.draft_verdict == "PASS" and row.draft_limit == 0.06
    assert "Table 3-A-1" in row.draft_source and "RPR0" in row.reason
    assert sgisc.parametric_c1_row(xr_c1(0.2, 8.0), std, src).draft_verdict == "FAIL"
    assert sgisc.parametric_c1_row(xr_c1(0.02, np.nan), std, src).draft_verdict == ""


def xr_c1(value, speed):
    import xarray as xr

    ds = xr.Dataset({"c1_fails": ("c1_case", np.zeros(16))}, coords={"c1_case": np.arange(1, 17)})
    ds["c1"] = value
    ds.attrs.update(c1_r_pr=0.2, c1_roll_period=10.0, c1_service_speed=speed, c1_no_equilibrium="none",
                    c1_speed_requirement="evaluated" if np.isfinite(speed) else "not evaluated: no service speed")
    return ds
