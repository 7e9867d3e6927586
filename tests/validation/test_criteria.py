"""Criteria validation rows (``stabflow.validation.criteria``)."""

import math

import numpy as np
import xarray as xr

from stabflow.validation.criteria import TOL_ROUTE_DGM, TOL_ROUTE_GMMIN, route_checks


def _crit(dgm_plane, dgm_wave, gmmin_plane, gmmin_wave, gm=2.0):
    names = ["pure loss: GMmin by waterplane inertia at d_L", "pure loss: GMmin on the wave lambda = L, H = SW L",
             "parametric rolling: delta GM1 / GM by waterplane inertias",
             "parametric rolling: delta GM / GM on the wave lambda = L (stabflow's direct route)"]
    return xr.Dataset({"criterion_name": ("criterion", names),
                       "criterion_value": ("criterion", [gmmin_plane, gmmin_wave, dgm_plane, dgm_wave]), "gm": gm})


def test_level1_routes_rows():
    """The two level-1 routes: delta GM / GM relative to the wave pass's, GMmin per GM0; PASS within
    the tolerances, FAIL beyond, SKIPPED when a route is NOT EVALUATED (NaN value)."""
    ok = route_checks(_crit(0.105, 0.10, 1.0, 1.1))
    assert [c.status for c in ok] == ["PASS", "PASS"]
    assert np.isclose(ok[0].value, 0.05) and np.isclose(ok[1].value, -0.05)
    bad = route_checks(_crit(0.10 * (1 + 2 * TOL_ROUTE_DGM), 0.10, 1.0, 1.0 + 2.0 * 2 * TOL_ROUTE_GMMIN))
    assert [c.status for c in bad] == ["FAIL", "FAIL"]
    skipped = route_checks(_crit(math.nan, 0.1, 1.0, 1.0))
    assert [c.status for c in skipped] == ["SKIPPED", "PASS"]


def test_dsa_screening_row():
    """The DSA screening row: the upper bound of the cells that stay screened, by simulation, against
    the simulated cells' interval width, PASS inside [0, width], FAIL beyond (also when the records
    cannot show it); SKIPPED with the reason when the ship has no DSA or nothing was screened."""
    from stabflow.validation.criteria import screening_check

    def out(hi, width=10.0, verdict="PASS"):
        d = xr.Dataset({"screen_recheck_rate_hi": hi, "interval_width": width})
        d.attrs.update(screen_recheck_verdict=verdict, screen_recheck_cells=5, screen_recheck_failures=2,
                       screen_overruled_cells=1, screen_recheck_reason="no cell was screened")
        return d

    ok = screening_check(out(3.0))
    assert ok.status == "PASS" and ok.value == 3.0 and ok.kind == "consistency"
    assert "5 cells, 2 failures, 1 cells overruled" in ok.check
    assert screening_check(out(30.0, verdict="NOT SHOWN")).status == "FAIL"
    skipped = screening_check(out(0.0, verdict="SKIPPED"))
    assert skipped.status == "SKIPPED" and skipped.reason == "no cell was screened"
    none = screening_check(None)
    assert none.status == "SKIPPED" and "dsa.ships" in none.reason
