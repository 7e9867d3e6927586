"""Calm-water resistance: Holtrop's method against the 1982 paper's worked example, the hull's
particulars against a box, and the kernel's R(u) against the method it tabulates."""

import math

import numpy as np
import pytest

from stabflow import StabflowError
from stabflow.constants import G
from stabflow.dynamics import _kernels_6dof as K6
from stabflow.dynamics.resistance import (PEER_1984, TABLE_FROUDE, TABLE_POINTS, WORKED_EXAMPLE_1982, form_factor,
                                          holtrop_mennen, holtrop_wetted_area, hull_form, ittc57_friction,
                                          kernel_resistance, outside_range, reference_rows, wave_resistance,
                                          wetted_area)

from .conftest import ship_model

EX = WORKED_EXAMPLE_1982
EXAMPLE = EX["form"]
PRINTED_KN = EX["printed_kn"]


@pytest.fixture(scope="module")
def example():
    return holtrop_mennen(EXAMPLE, EX["speed"], EX["rho"], EX["nu"], EX["g"], variant="1982")


def test_worked_example_components(example):
    """The 1982 paper's example: 1 + k1 1.156, R_F 869.63, R_APP 8.83, R_W 557.11, R_B 0.049 kN
    within 0.2 %; R_A 221.98 kN within 1 % (the paper's C_A 0.000352 is printed rounded: with the
    formula's 0.0003525 both public implementations get 220.57 kN); R_T 1793.26 kN within 0.2 %."""
    d = example
    k1 = d.attrs["hm_form_factor"]
    assert k1 == pytest.approx(1.156, abs=6e-4)
    assert float(d["froude"][0]) == pytest.approx(0.2868, abs=5e-5)
    assert float(d["r_friction"][0]) / k1 / 1e3 == pytest.approx(PRINTED_KN["r_friction_bare"], rel=2e-3)
    for name in ("r_appendages", "r_wave", "r_total"):
        assert float(d[name][0]) / 1e3 == pytest.approx(PRINTED_KN[name], rel=2e-3), name
    assert float(d["r_bulb"][0]) / 1e3 == pytest.approx(PRINTED_KN["r_bulb"], rel=2e-2)
    assert float(d["r_transom"][0]) == 0.0  # F_nT 5.43 > 5
    assert float(d["r_correlation"][0]) / 1e3 == pytest.approx(PRINTED_KN["r_correlation"], rel=1e-2)
    # printed intermediates (OpenHull's test): i_E 12.08 deg, c1 1.398, c2 0.7595, m1 -2.1274, lambda 0.6513
    for key, val in (("hm_i_e", 12.08), ("hm_c1", 1.398), ("hm_c2", 0.7595), ("hm_m1", -2.1274),
                     ("hm_lambda", 0.6513), ("hm_c5", 0.9592)):
        assert d.attrs[key] == pytest.approx(val, rel=1e-3), key


def test_wetted_surface_regression_reproduces_the_example():
    """The example's S 7381.45 m^2 is the 1982 regression's (with C_B = nabla / (L B T))."""
    assert holtrop_wetted_area(EXAMPLE) == pytest.approx(7381.45, rel=1e-4)


def test_1984_set_against_a_peer_implementation():
    """Holtrop (1984) on a small beamy hull against a public peer module run on the same inputs
    (PEER_1984's source): R_W and R_T at Fn 0.25-1.0 within 1e-5 (the peer's 6 printed digits),
    through the 0.40-0.55 interpolation."""
    pe = PEER_1984
    v = np.asarray(pe["froude"]) * math.sqrt(pe["g"] * pe["form"].length)
    d = holtrop_mennen(pe["form"], v, pe["rho"], pe["nu"], pe["g"])
    np.testing.assert_allclose(d["r_wave"].values / 1e3, pe["r_wave_kn"], rtol=1e-5)
    np.testing.assert_allclose(d["r_total"].values / 1e3, pe["r_total_kn"], rtol=1e-5)
    assert d.attrs["hm_form_factor"] == pytest.approx(1.47702, rel=1e-5)  # the peer's 1 + k1
    assert d.attrs["hm_correlation_allowance"] == pytest.approx(0.000732873, rel=1e-5)


def test_reference_rows_pass():
    rows = reference_rows()
    assert len(rows) == 4 and all(abs(r.value) <= r.tolerance for r in rows), [(r.check, r.value) for r in rows]


def test_1984_wave_resistance_is_continuous_and_bridges_linearly():
    """Holtrop (1984): R_W-A below Fn 0.40, R_W-B above 0.55, linear in Fn between them."""
    fn = np.array([0.3999999, 0.40, 0.45, 0.50, 0.55, 0.5500001])
    rw = wave_resistance(EXAMPLE, fn, variant="1984")
    assert rw[0] == pytest.approx(rw[1], rel=1e-5)
    assert rw[4] == pytest.approx(rw[5], rel=1e-5)
    assert rw[2] - rw[1] == pytest.approx(rw[3] - rw[2], rel=1e-9)
    assert rw[3] - rw[2] == pytest.approx(rw[4] - rw[3], rel=1e-9)


def test_1984_form_factor_differs_from_1982():
    """The two form-factor regressions differ (1984 replaces c12, c13 by c14) but agree to 10 %
    on the example ship."""
    a, b = form_factor(EXAMPLE, "1982"), form_factor(EXAMPLE, "1984")
    assert a != b and b == pytest.approx(a, rel=0.1)
    with pytest.raises(StabflowError, match="variant"):
        form_factor(EXAMPLE, "1999")


def test_wave_resistance_vanishes_at_rest_and_rises():
    fn = np.linspace(0.0, 1.2, 121)
    rw = wave_resistance(EXAMPLE, fn)
    assert rw[0] == 0.0 and np.all(np.isfinite(rw)) and rw[-1] > rw[60] > rw[20] > 0.0


def test_box_barge_particulars_are_exact(barge):
    """A box of L 100, B 20 at draft 6 m: girth-integrated wetted surface L (B + 2T) = 3200 m^2
    (no end faces), C_M = C_WP = 1, lcb at 0.5 L, the immersed transom B T = 120 m^2; its blunt
    bow's whole section counts as A_BT (the section at the waterline's forward end: Holtrop's
    method is not meant for a box), its centroid T / 2 below the waterline."""
    ship, sec, st, _ = barge
    f = hull_form(sec, st)
    assert wetted_area(sec, st) == pytest.approx(100.0 * (20.0 + 12.0), rel=1e-9)
    assert (f.length, f.breadth, f.draft) == pytest.approx((100.0, 20.0, 6.0), rel=1e-9)
    assert (f.cm, f.cwp, f.cp, f.cb) == pytest.approx((1.0, 1.0, 1.0, 1.0), rel=1e-9)
    assert f.lcb == pytest.approx(0.0, abs=1e-9)
    assert f.transom_area == pytest.approx(120.0, rel=1e-9)
    assert f.bulb_area == pytest.approx(120.0, rel=1e-9) and f.draft - f.bulb_height == pytest.approx(3.0, rel=1e-9)
    g = hull_form(sec, st, {"transom_area": 0.0, "bulb_area": 0.0})
    assert g.transom_area == 0.0 and g.bulb_area == 0.0


def test_trawler_particulars_refer_to_the_waterline(trawler_sections):
    """The trawler: lcb from the waterline's midpoint (not the immersed extent, which its bulb
    stretches 0.85 m forward), a bulb and a transom at the waterline's ends, and particulars that
    move little with the station count (81 against 161 stations: S, A_T; lcb -1.11 and -0.77 % L,
    A_BT 1.61 and 1.80 m^2, both read at the waterline's ends, which the slabs quantise)."""
    sec, st = trawler_sections
    f = hull_form(sec, st)
    assert f.length == pytest.approx(float(st["lwl"]))
    assert -2.0 < f.lcb < 0.0 and f.bulb_area > 1.0 and 2.5 < f.transom_area < 3.5
    ship, _, _, _ = ship_model("trawler")
    # the ship file's resistance section (its schema defaults filled in) leaves A_T and A_BT to the hull
    f_cfg = hull_form(sec, st, ship.data["manoeuvring"]["resistance"])
    assert (f_cfg.bulb_area, f_cfg.transom_area, f_cfg.bulb_height) == (f.bulb_area, f.transom_area, f.bulb_height)
    from stabflow.geometry import Sections, build_hull
    from stabflow.hydrostatics.statics import compute_statics

    fine = ship.modified(stations=161)
    hull = build_hull(fine)
    g = hull_form(Sections(hull), compute_statics(fine, hull))
    assert g.wetted_area == pytest.approx(f.wetted_area, rel=0.01)
    # the waterline's ends fall on slab faces (0.28 m at 81 stations): lcb to half a slab, 0.65 % L
    assert g.lcb == pytest.approx(f.lcb, abs=0.65)
    assert g.transom_area == pytest.approx(f.transom_area, rel=0.03)
    # A_BT is read at the waterline's forward end, which moves with the slabs: 1.61 and 1.80 m^2
    assert g.bulb_area == pytest.approx(f.bulb_area, rel=0.15)


def test_a_resistance_that_falls_with_speed_is_refused(trawler_sections):
    sec, st = trawler_sections
    with pytest.raises(StabflowError, match="falls between"):
        kernel_resistance({"method": "curve", "speeds": [0.0, 3.0, 6.0], "values": [0.0, 9e3, 5e3]}, sec, st, 1025.0,
                          1.0, 0.0, float(st["lwl"]))


def test_outside_range_names_each_item():
    text = outside_range(EXAMPLE, 0.5)
    assert text == ["Fn 0.5 outside 0-0.38", "L/B 6.41 outside 3.9-6.3", "B/T 3.2 outside 2.1-3"]
    assert outside_range(EXAMPLE) == [t for t in text if not t.startswith("Fn")]


@pytest.fixture(scope="module")
def trawler_sections():
    _, sec, st, _ = ship_model("trawler")
    return sec, st


def _model_m(res_cfg, sec, st, rho=1025.0, kato=200.0, k=0.0):
    L = float(st["lwl"])
    m = np.zeros(K6.N_M)
    m[K6.M_RES], m[K6.M_RR_DU], table, attrs = kernel_resistance(res_cfg, sec, st, rho, kato, k, L)
    m[K6.M_RR:K6.M_RR + K6.N_RR] = table
    m[K6.M_LNU] = L / 1.18831e-6
    return m, attrs, L


def test_kernel_tabulates_holtrop_exactly_at_its_points_and_closely_between(trawler_sections):
    """The kernel's R(u) equals Holtrop's R_T at the table's points (1e-9) and within 1 % (or 20 N,
    at the lowest speeds) halfway between them below Fn 1 (linear interpolation of the wave part,
    friction exact); odd in u;
    beyond the table, R grows as u^2 from its last point."""
    sec, st = trawler_sections
    m, attrs, L = _model_m({"method": "holtrop_mennen"}, sec, st)
    f = hull_form(sec, st)
    u = np.linspace(0.0, TABLE_FROUDE * math.sqrt(G * L), TABLE_POINTS)
    ref = holtrop_mennen(f, u, 1025.0, 1.18831e-6)["r_total"].values
    got = np.array([K6._resistance(m, x) for x in u])
    np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-6)
    mid = 0.5 * (u[1:] + u[:-1])
    ref = holtrop_mennen(f, mid, 1025.0, 1.18831e-6)
    keep = ref["froude"].values < 1.0
    got = np.array([K6._resistance(m, x) for x in mid])
    np.testing.assert_allclose(got[keep], ref["r_total"].values[keep], rtol=1e-2, atol=20.0)
    assert K6._resistance(m, -6.0) == -K6._resistance(m, 6.0)
    table_only = m.copy()
    table_only[K6.M_RES] = 0.0
    assert K6._resistance(table_only, 2 * u[-1]) == pytest.approx(4 * K6._resistance(table_only, u[-1]), rel=1e-12)
    assert attrs["resistance_form_factor"] == pytest.approx(form_factor(f), rel=1e-12)


def test_kernel_friction_method_is_the_ittc_line(trawler_sections):
    sec, st = trawler_sections
    m, attrs, L = _model_m({}, sec, st, kato=200.0, k=0.1)
    u = 5.0
    line = 0.5 * 1025.0 * 200.0 * 1.1 * float(ittc57_friction(u * L / 1.18831e-6)) * u * u
    assert K6._resistance(m, u) == pytest.approx(line, rel=1e-13)
    assert m[K6.M_RR_DU] == 0.0 and attrs["resistance_method"].startswith("friction")


def test_kernel_curve_method_passes_through_the_given_points(trawler_sections):
    sec, st = trawler_sections
    speeds, values = [0.0, 3.0, 6.0, 9.0], [0.0, 4e3, 30e3, 120e3]
    m, attrs, L = _model_m({"method": "curve", "speeds": speeds, "values": values, "source": "test"}, sec, st)
    du = m[K6.M_RR_DU]
    # the table's points are the monotone cubic's; between them the kernel is linear: within 2 %
    for s, v in zip(speeds[1:], values[1:]):
        assert K6._resistance(m, s) == pytest.approx(v, rel=2e-2)
    u = np.arange(0.0, 9.0, 0.05)
    r = np.array([K6._resistance(m, x) for x in u])
    assert np.all(np.diff(r) >= 0.0)
    assert K6._resistance(m, 18.0) == pytest.approx(4 * 120e3, rel=5e-2)
    assert du > 0 and attrs["resistance_source"] == "test"
    with pytest.raises(StabflowError, match="speeds"):
        kernel_resistance({"method": "curve", "speeds": [1.0, 2.0], "values": [1.0, 2.0]}, sec, st, 1025.0, 1.0, 0.0, L)
    with pytest.raises(StabflowError, match="method"):
        kernel_resistance({"method": "model_test"}, sec, st, 1025.0, 1.0, 0.0, L)


def test_branch_coefficients_are_continuous_at_their_switches():
    """Holtrop's piecewise coefficients meet at their switches (a slip in a branch's constants
    would break it): c7 at B/L 0.11 and 0.25, c12 at T/L 0.05 (1982 form factor), c15 at
    L^3/nabla 512 and 1726.91, c16 at C_P 0.8 (the worked example's ship varied one ratio at a time)."""
    from dataclasses import replace

    from stabflow.dynamics.resistance import _wave_coefficients

    def coef(key, eps=1e-7, **kw):
        lo = _wave_coefficients(replace(EXAMPLE, **{k: v * (1 - eps) for k, v in kw.items()}))[key]
        hi = _wave_coefficients(replace(EXAMPLE, **{k: v * (1 + eps) for k, v in kw.items()}))[key]
        return lo, hi

    L = EXAMPLE.length
    for bl in (0.11, 0.25):
        lo, hi = coef("c7", breadth=bl * L)
        assert lo == pytest.approx(hi, rel=5e-5), bl  # measured 7e-6 at 0.11 (the 1/3 exponent's 0.33333)
    # L^3 / nabla = 512 and 1726.91 (L / nabla^(1/3) = 8 and 12.0): c15 -1.69385 and about 0
    for ratio in (512.0, 1726.91):
        lo, hi = coef("c15", volume=L**3 / ratio)
        assert lo == pytest.approx(hi, abs=5e-5), ratio  # measured 1e-7 and 4e-6
    # C_P 0.8 through C_M (C_P = nabla / (C_M B T L))
    cm = EXAMPLE.volume / (0.8 * EXAMPLE.breadth * EXAMPLE.draft * L)
    lo, hi = coef("c16", cm=cm)
    assert lo == pytest.approx(hi, abs=5e-5)  # measured 3e-6
    # c12 at T/L 0.05 inside the 1982 form factor
    a = form_factor(replace(EXAMPLE, draft=0.05 * L * (1 - 1e-7)), "1982")
    b = form_factor(replace(EXAMPLE, draft=0.05 * L * (1 + 1e-7)), "1982")
    assert a == pytest.approx(b, rel=1e-5)  # measured 1e-7
