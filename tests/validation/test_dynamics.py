"""Validation rows of the 3-DOF time-domain model (stabflow.validation.dynamics)."""

import re

import numpy as np
import pytest

from stabflow.config import load_ship
from stabflow.geometry import build_hull
from stabflow.hydrostatics.statics import compute_statics
from stabflow.validation import checks_dataset
from stabflow.validation import dynamics as vd

from ..conftest import SHIPS

SMALL = "small waves vs linear frequency domain"
GM = "GM in quartering waves lambda = L, H = T/3, ship held"
GM_ROWS = [f"{GM}: {stat} vs {label}"
           for label in ("pressure integration with the sections' planar waterline",
                         "pressure integration (exact wave surface)",
                         "pressure integration (exact wave surface), curved waterline",
                         "pressure integration with decay on the exact wave surface, the kernel with the pressure decay")
           for stat in ("mean", "first-harmonic variation")]
GM_DECAY_ROWS = GM_ROWS[6:]
GM_EXACT_VARIATION = GM_ROWS[3]
CURVED_ROWS = [f"quartering waves lambda = L, H = T/3: {v} amplitude with the curved waterline vs pressure integration"
               for v in vd.DOFS]
PRESSURE_ROWS = (
    [f"quartering waves lambda = L, H = T/3: {v} amplitude vs pressure integration" for v in vd.DOFS]
    + CURVED_ROWS + GM_ROWS
    + [f"{SMALL} (pressure-integrated FK): {v}, largest over lambda/L = 1-3" for v in vd.DOFS]
    + [f"d2phi/dzdt option, lambda = L, H/lambda = 1/50: {v} vs pressure integration with decay" for v in ("heave", "pitch")]
)
BEAM_ROW = ("d2phi/dzdt option, beam waves at twice the roll frequency, H/lambda = 1/500: heave vs pressure "
            "integration with decay")
ROLL_DECAY_ROW = ("pressure decay, beam waves at the roll frequency, ship held: roll excitation vs pressure "
                  "integration with decay")
ROLL_DECAY_ROW2 = ("pressure decay, beam waves at twice the roll frequency, ship held: roll excitation vs pressure "
                   "integration with decay")
HEEL_DECAY_ROW = (f"pressure decay, beam waves at twice the roll frequency, ship held at +-{vd.HEEL_DECAY_SMALL_DEG:g} "
                  "deg: heel's part of the roll moment vs pressure integration with decay on the exact wave surface")
HEEL_DECAY_EXACT_ROW = (f"pressure decay, beam waves at twice the roll frequency, ship held at +-{vd.HEEL_DECAY_DEG:g} "
                        "deg: heel's part of the roll moment vs pressure integration with decay on the exact wave surface")
HYBRID_ROWS = [f"diffraction option, beam waves, ship held: {label}, kernel FK with decay + Capytaine diffraction vs "
               "Capytaine FK + diffraction" for label in ("roll at the roll frequency", "heave at twice the roll frequency")]
PRESSURE_ROWS = PRESSURE_ROWS + [BEAM_ROW, ROLL_DECAY_ROW, ROLL_DECAY_ROW2, HEEL_DECAY_ROW, HEEL_DECAY_EXACT_ROW] + HYBRID_ROWS
IKEDA_ROWS = [f"Ikeda roll damping, viscous sum at {vd.IKEDA_AMPLITUDE:g} deg, Fn {fn:g}: component / simplified method"
              for fn in vd.IKEDA_FROUDE]
PERIOD_ROW = vd.PERIOD_CHECK
#: every row, in order, with its kind
EXPECTED = (
    [("roll decay: period vs damped natural period", "independent"),
     ("roll decay: logarithmic decrement vs 2 pi zeta / sqrt(1 - zeta^2)", "independent")]
    + [(f"calm-water rest: max |{v}| over 600 s", "consistency") for v in vd.DOFS]
    + [(n, "independent") for n in PRESSURE_ROWS[:14]]
    + [(f"{SMALL} (kernel FK): {v}, largest over lambda/L = 1-3", "consistency") for v in vd.DOFS]
    + [(n, "consistency") for n in PRESSURE_ROWS[14:17]]
    + [(n, "independent") for n in PRESSURE_ROWS[17:]]
    + [("long head waves: heave / a vs long-wave limit", "consistency"),
       ("long head waves: pitch / (k a) vs long-wave limit", "consistency"),
       ("long head waves: roll / (k a)", "consistency")]
    + [(n, "independent") for n in IKEDA_ROWS]
    + [(PERIOD_ROW, "independent")]
)


def inputs(name):
    ship = load_ship(SHIPS / f"{name}.yaml")
    hull = build_hull(ship)
    return ship, hull, compute_statics(ship, hull)


@pytest.fixture(scope="module")
def barge_rows():
    return {r.check: r for r in vd.dynamics_checks(*inputs("barge"))}


@pytest.fixture(scope="module")
def wigley():
    return inputs("wigley")


def test_barge_every_row_present_and_passes(barge_rows):
    """Every row but two passes; the exceptions are the planar waterline's cost in GM variation, in
    quartering waves without the decay and in beam waves with it (the heeled section's phase across
    the beam; its cost in heave in short beam waves, +12 % twice, is gone with the decay's cross-beam
    correction, and in the upright roll moment with its remainders)."""
    assert [(r.check, r.kind) for r in barge_rows.values()] == EXPECTED
    for r in barge_rows.values():
        if r.check in IKEDA_ROWS:  # the barge's roll damping is the config's
            assert r.status == "SKIPPED" and "dynamics.roll_damping" in r.reason
            continue
        if r.check == PERIOD_ROW:
            assert r.status == "SKIPPED" and "no published natural roll period" in r.reason
            continue
        if r.check in (GM_EXACT_VARIATION, HEEL_DECAY_EXACT_ROW):
            continue
        assert r.status == "PASS", (r.check, r.value, r.criterion, r.reason)
        assert r.reason == ""
    # the measured numbers behind the tolerances (module docstring)
    rows = barge_rows
    assert abs(rows["roll decay: period vs damped natural period"].value) < 0.01
    for v in vd.DOFS:
        assert abs(rows[f"{SMALL} (kernel FK): {v}, largest over lambda/L = 1-3"].value) < 0.1
    # the sections' planar waterline: about 1 / sinc(k_y B / 2) - 1 = +3.4 % in heave at lambda = L
    heave = rows[f"{SMALL} (pressure-integrated FK): heave, largest over lambda/L = 1-3"]
    assert 3.0 < heave.value < 4.0
    assert "per lambda/L 1: +3.59 %" in heave.reference
    dphi = rows[PRESSURE_ROWS[17]]
    assert "without the option +51" in dphi.reference
    # short beam waves (lambda 78 m at 2 w_phi, B 20 m): the term takes heave from +82 % to +12 %, the
    # planar waterline across the beam's 1 / sinc(k B / 2) - 1 = +12 %, and the cross-beam
    # correction (SectionDecay.moments' X) the rest: measured +0.11 %; the curved waterline with the
    # term undershoots by 8 %
    beam = rows[BEAM_ROW]
    assert beam.status == "PASS" and abs(beam.value) < 0.5
    assert "without the option +8" in beam.reference and "curved waterline too -7.9 %" in beam.reference
    # the pressure decay's roll moment at the roll frequency (lambda 310 m): the kernel equals
    # pressure integration with decay on the exact surface (measured +0.03 %); without the decay it
    # is 28 % high. At twice the roll frequency (lambda 77.6 m) +1.2 % (the cross-beam remainders;
    # +22.6 % against the phase linearised across the beam, and the kernel without them was -16.9 %
    # off the exact surface)
    roll = rows[ROLL_DECAY_ROW]
    assert abs(roll.value) < 0.1 and "lambda 310.2 m; without the decay +28.0 %" in roll.reference
    roll2 = rows[ROLL_DECAY_ROW2]
    assert roll2.status == "PASS" and abs(roll2.value) < 1.5 and "across the beam (the sections' planar " \
        "waterline's assumption) +22.6 %" in roll2.reference
    # its heel's part at +-2 deg in the parametric wave (lambda 77.6 m) against the exact surface:
    # measured 0.81 % (with the phase linearised across the beam, as before the heeled section's
    # cross-beam terms, the kernel was 0.67 % off that reference at +-10 deg, and 31 % without the
    # heeled section's decay terms)
    heel = rows[HEEL_DECAY_ROW]
    assert heel.status == "PASS" and heel.value < 1.0 and "at lambda 77.6 m" in heel.reference
    # at +-10 deg the heeled section's cross-beam terms, of the first order in the heel, leave 7.8 %
    # (45.9 % without them: the heeled sections took the phase as linear across the beam, GM
    # amplitude 0.076 against 0.052 m); on this box their field's heel part at 10 deg is 18 % below
    # its first-order value
    heel_exact = rows[HEEL_DECAY_EXACT_ROW]
    assert heel_exact.status == "FAIL" and 5.0 < heel_exact.value < 10.0
    # GM in waves: the kernel equals pressure integration with its own planar waterline (measured
    # +0.01 % mean, +0.18 % variation); with the exact surface the variation is 0.0477 m, not 0.0595
    for n in GM_ROWS[:2]:
        assert abs(rows[n].value) < 0.5, n
    assert 0.3 < rows[GM_ROWS[2]].value < 0.6
    exact = rows[GM_EXACT_VARIATION]
    assert exact.status == "FAIL" and 20.0 < exact.value < 30.0
    assert "volume 1.6051 m + 0.0595 m" in exact.reference and "exact 1.5977 m + 0.0477 m" in exact.reference
    # the curved waterline: GM variation 0.0475 m against 0.0477 (measured -0.4 %), and heave and
    # pitch in the time domain within 0.3 % of pressure integration (+3.7 % planar)
    for n in GM_ROWS[4:6]:
        assert abs(rows[n].value) < 1.0, n
    # the kernel with the pressure decay (the DSA's, the 6-DOF records'): its cross-beam and heeled-
    # section terms take the variation to pressure integration's with the decay on the exact
    # surface, measured +0.28 % mean and +0.23 % variation (paper 000's planar kernel: +24.8 %)
    for n in GM_DECAY_ROWS:
        assert rows[n].status == "PASS" and abs(rows[n].value) < 1.0, (n, rows[n].value)
    assert "e^{kz} decay" in rows[GM_DECAY_ROWS[1]].reference
    for n in (CURVED_ROWS[0], CURVED_ROWS[2]):
        assert abs(rows[n].value) < 1.0, n
    # the diffraction option's beam-sea excitation against Capytaine's FK + diffraction (with the free
    # sway's reaction): the kernel's FK alone is +1.8 % (roll, lambda 310 m; +1.3 % before the cross-
    # beam remainders, which take it to pressure integration's on the exact surface, +0.03 %: the
    # rest is Capytaine's panels) and, with the cross-beam correction, -0.0 % (heave, lambda 78 m;
    # +11.8 % with the planar waterline alone) off Capytaine's: an independent BEM; measured +2.4 %
    # and -0.04 % (+11.7 % before)
    hroll, hheave = (rows[n] for n in HYBRID_ROWS)
    assert hroll.status == "PASS" and 1.0 < hroll.value < 3.0 and "alone against Capytaine's +1.8 %" in hroll.reference
    assert hheave.status == "PASS" and abs(hheave.value) < 0.5 and "/ |FK| 0.77" in hheave.reference
    fk = re.search(r"alone against Capytaine's ([+-]?[0-9.]+) %", hheave.reference)
    assert fk and abs(float(fk.group(1))) < 0.5, hheave.reference
    ds = checks_dataset("barge", "dynamics", list(rows.values()))
    assert list(ds["name"].values[ds["status"].values == "FAIL"]) == [GM_EXACT_VARIATION, HEEL_DECAY_EXACT_ROW]
    assert ds.sizes["check"] == len(EXPECTED)


def test_wigley_skips_pressure_rows_with_reason(wigley):
    rows = vd.dynamics_checks(*wigley)
    assert [(r.check, r.kind) for r in rows] == EXPECTED
    for r in rows:
        if r.check in PRESSURE_ROWS:
            assert r.status == "SKIPPED"
            assert "'wigley'" in r.reason and "mesh" in r.reason
        elif r.check in IKEDA_ROWS or r.check == PERIOD_ROW:
            assert r.status == "SKIPPED"
        else:
            assert r.status == "PASS", (r.check, r.value, r.reason)


def test_pressure_mesh_applicability():
    flare = load_ship(SHIPS / "dtmb5415_flare.yaml")
    with pytest.raises(vd.NotApplicable, match="topside"):
        vd.pressure_mesh(flare, reach=7.0)  # above the replaced topsides (z = 6.5 m)
    v, f = vd.pressure_mesh(flare, reach=6.3)  # small waves stay below them
    assert len(f) > 1000 and v.shape[1] == 3
    with pytest.raises(vd.NotApplicable, match="triangles"):
        vd.pressure_mesh(load_ship(SHIPS / "dtmb5415.yaml"), max_faces=100)


def test_broken_coefficients_give_fail_rows_not_an_exception(monkeypatch, wigley):
    def broken(*args, **kwargs):
        raise RuntimeError("broken coefficients")

    monkeypatch.setattr(vd, "config_coefficients", broken)
    rows = vd.dynamics_checks(*wigley)
    assert [(r.check, r.kind) for r in rows] == EXPECTED
    for r in rows:
        if r.check in PRESSURE_ROWS:  # does not apply, whatever else fails
            assert r.status == "SKIPPED" and "mesh" in r.reason
        elif r.check in IKEDA_ROWS:
            assert r.status == "SKIPPED" and "dynamics.roll_damping" in r.reason
        elif r.check == PERIOD_ROW:
            assert r.status == "SKIPPED" and "no published" in r.reason
        else:
            assert r.status == "FAIL"
            assert r.reason == "RuntimeError: broken coefficients"


def test_broken_simulation_on_barge_fails_rows_fast(monkeypatch):
    def broken(*args, **kwargs):
        raise FloatingPointError("diverged")

    monkeypatch.setattr(vd, "simulate", broken)
    rows = {r.check: r for r in vd.dynamics_checks(*inputs("barge"))}
    assert list(rows) == [n for n, _ in EXPECTED]
    # the GM-in-waves and roll-excitation rows hold the ship still: they need no simulation
    depends = [n for n, _ in EXPECTED
               if not n.startswith("long head waves") and n not in IKEDA_ROWS and n not in GM_ROWS and n != PERIOD_ROW
               and n not in (ROLL_DECAY_ROW, ROLL_DECAY_ROW2, HEEL_DECAY_ROW, HEEL_DECAY_EXACT_ROW, *HYBRID_ROWS)]
    for n in depends:
        assert rows[n].status == "FAIL" and rows[n].reason == "FloatingPointError: diverged", n
        assert np.isnan(rows[n].value)


def test_nan_value_is_a_fail_row_with_reason(monkeypatch, wigley):
    monkeypatch.setattr(vd, "first_harmonic", lambda t, x, w: (np.nan, 0.0))
    rows = {r.check: r for r in vd.dynamics_checks(*wigley)}
    r = rows[f"{SMALL} (kernel FK): roll, largest over lambda/L = 1-3"]
    assert r.status == "FAIL" and "nan" in r.reason
    assert rows["roll decay: period vs damped natural period"].status == "PASS"


def test_peaks_of_a_damped_oscillation():
    t = np.arange(0.0, 60.0, 0.05)
    wd, s = 2 * np.pi / 7.0, 0.03
    tp, xp = vd.peaks(t, np.exp(-s * t) * np.cos(wd * t))
    assert np.diff(tp) == pytest.approx(7.0, rel=1e-4)
    assert np.log(xp[:-1] / xp[1:]) == pytest.approx(s * 7.0, rel=1e-3)


def test_ikeda_vs_simplified_dtmb5415():
    """DTMB 5415 (roll_damping: ikeda, with its bilge keels since 2026-12-07): viscous component sum
    over the simplified method at 10 deg. Measured 0.90 at Fn 0 and 0.86 at Fn 0.2 (the keels' terms,
    which both methods carry, now dominate; the bare hull gave 1.75, from the hull's eddy making at the
    sonar-dome stations that Ikeda's section model was not fitted to, and 1.03); the regression itself
    is outside its C_M range."""
    from stabflow.dynamics.model import config_coefficients
    from stabflow.geometry import Sections

    ship, hull, st = inputs("dtmb5415")
    sec = Sections(hull)
    out = vd.ikeda_vs_simplified(ship, sec, st, config_coefficients(ship, sec, st))
    assert out["ratio"] == pytest.approx([0.90, 0.86], abs=0.02)
    assert "cm" in out["out_of_range"]


def test_trawler_roll_decay_matches_linear_theory():
    """The lightly damped trawler (zeta 0.005): from DECAY_HEEL (0.25 deg) the decrement and the
    period are within the row's 0.1 % of linear theory (measured +0.015 % and -0.0006 %); the
    deviation grows as phi0^2 (0.23 % from 1 deg), so it is the restoring's curvature, not damping."""
    from stabflow.dynamics.model import config_coefficients
    from stabflow.geometry import Sections

    ship, hull, st = inputs("trawler")
    sec = Sections(hull)
    co = config_coefficients(ship, sec, st)
    d = vd.roll_decay(sec, st, co, ship.rho)
    assert abs(100 * (d["log_decrement"] / d["log_decrement_ref"] - 1)) < vd.TOL_DECAY
    assert abs(100 * (d["period"] / d["period_ref"] - 1)) < vd.TOL_DECAY
    big = vd.roll_decay(sec, st, co, ship.rho, phi0_deg=1.0)
    assert 100 * (big["log_decrement"] / big["log_decrement_ref"] - 1) > 0.1


def test_published_roll_period_dtmb5415():
    """DTMB 5415's natural roll period against Araki, Ohashi & Hirata (ISSW 2014, Table 1): the row's
    value is 100 (T / 10.51 s - 1) with T = 2 pi sqrt((I44 + A44) / C44), A44 Capytaine's at T (the
    fixed point, checked here: one more solve at 2 pi / T changes T by < 1e-3), I44 the ship file's
    k44 (the paper's 0.158 m x 46.6), C44 the kernel's restoring. Measured +9.4 %: FAIL at 5 %
    (README: the paper's period equals 2 pi k44 / sqrt(g GM) with no added inertia)."""
    import capytaine as cpt

    from stabflow.dynamics.hydro import bem_mesh, immersed_body
    from stabflow.dynamics.model import config_coefficients

    ship, hull, st = inputs("dtmb5415")
    sec = vd.Sections(hull)
    ref, src = vd.PUBLISHED_ROLL_PERIOD["dtmb5415"]
    row = vd.published_period_check(ship, st, lambda: sec)
    T = ref * (1 + row.value / 100)
    co = config_coefficients(ship, sec, st)
    assert co.i44 == pytest.approx(co.mass * 7.363 ** 2, rel=1e-12)  # the paper's 0.158 m x 46.6
    h0, th0, _ = vd.equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    body = immersed_body(bem_mesh(ship), h0, th0, float(st["lcg"]), float(st["kg"]))
    w = 2 * np.pi / T
    a44 = cpt.BEMSolver().solve(cpt.RadiationProblem(body=body, radiating_dof="Roll", omega=w, rho=ship.rho,
                                                     g=vd.G)).added_mass["Roll"]
    assert 2 * np.pi * np.sqrt((co.i44 + a44) / co.c44) == pytest.approx(T, rel=1e-3)
    assert ref == pytest.approx(10.513, abs=1e-3) and "Araki" in src
    assert 0.05 < a44 / co.i44 < 0.5  # Capytaine's added inertia about G: 17 % of the rigid body's
    assert row.check == PERIOD_ROW and row.kind == "independent" and row.tolerance == 5.0
    assert row.status == "FAIL" and 8.0 < row.value < 11.0
