"""Paper 004's scenario plumbing (issue 17): loadings, the trough start, the dataset of a small run."""

import numpy as np
import pytest

from stabflow.config import load_pipeline, load_ship
from stabflow.constants import G
from stabflow.dynamics import _kernels as K
from stabflow.dynamics.broaching import (heavy_kg, map_step_row, scenario, scenario_step_row, six_dof_model,
                                         trough_phase)
from stabflow.geometry import build_hull
from stabflow.hydrostatics.statics import compute_statics

from ..conftest import ROOT, SHIPS


def test_heavy_loading_puts_g_above_the_waterline():
    ship = load_ship(SHIPS / "barge.yaml")
    st = compute_statics(ship, build_hull(ship))
    assert heavy_kg(ship, 0.08) == pytest.approx(float(st["draft_mid"]) + 0.08, abs=1e-12)


def test_records_start_in_the_trough():
    """eta at G's station at t = 0 is -a (paper 004: the ship starts at the bottom of the wave)."""
    ship = load_ship(SHIPS / "barge.yaml")
    model = six_dof_model(ship, 45.0, 10.0, tables=(37, 21))
    lam = 60.0
    w = np.sqrt(G * 2 * np.pi / lam)
    ph = trough_phase(model, w)
    k = 2 * np.pi / lam
    xi_g = float(model.p[K.P_XG]) * np.cos(np.radians(45.0))
    assert np.cos(k * xi_g + ph) == pytest.approx(-1.0, abs=1e-12)


def test_scenario_dataset_of_the_test_profile():
    """Shapes, integer events, time histories NaN only after a record's end."""
    cfg = load_pipeline(ROOT / "config" / "test.yaml")["broaching"]
    ship = load_ship(SHIPS / f"{cfg['ship']}.yaml")
    ds = scenario(ship, cfg)
    assert ds.sizes["loading"] == len(cfg["loadings"])
    assert list(ds.case.values) == ["R-1", "IR-1"]
    for v in ("capsized", "broach", "surf_riding"):
        assert ds[v].dtype.kind == "i" and set(np.unique(ds[v].values)) <= {0, 1}
    for c in ds.case.values:
        r = ds.sel(loading=ds.loading.values[0], case=c)
        n = int(round(float(r["end_time"]) / ds.attrs["dt"])) + 1
        assert np.isfinite(r["roll"].values[:n]).all()
        assert np.isnan(r["roll"].values[n:]).all()
    # the step's check: each record's first 15 s again at dt / 5, its row the largest error
    e = ds["step_error"].values
    assert e.shape == (ds.sizes["loading"], ds.sizes["case"]) and np.all(np.isfinite(e)) and np.all(e > 0)
    row = scenario_step_row(ds)
    assert row.value == float(np.max(e)) and row.status == "PASS" and "15 s" in row.check


def test_probability_map_counts_and_intervals():
    """Counts are integers out of the records, each exact binomial interval holds its estimate."""
    from stabflow.dynamics.broaching import probability_map

    cfg = load_pipeline(ROOT / "config" / "test.yaml")["broaching"]
    ship = load_ship(SHIPS / f"{cfg['ship']}.yaml")
    ds = probability_map(ship, cfg)
    n = ds.attrs["map_records"]
    for name in ("capsize", "broach"):
        k = ds[f"map_{name}_count"].values
        assert k.dtype.kind == "i" and np.all((0 <= k) & (k <= n))
        p = ds[f"map_{name}_probability"].values
        assert np.all(ds[f"map_{name}_lower"].values <= p) and np.all(p <= ds[f"map_{name}_upper"].values)
        # 0 of 2: the exact upper bound is 1 - 0.025^(1/2)
        zero = k == 0
        np.testing.assert_allclose(ds[f"map_{name}_upper"].values[zero], 1 - 0.025 ** 0.5, rtol=1e-9)
    # the step's check: each cell's first record again at dt / 5, its row the largest error
    e = ds["map_step_error"].values
    assert np.all(np.isfinite(e)) and np.all(e > 0)
    row = map_step_row(ds)
    assert row.value == float(np.max(e)) and row.kind == "consistency" and row.tolerance == 1.0


def test_probability_map_step_row_grows_with_the_step_and_fails_when_too_long():
    """The map's step row against the records at dt / 5 (test profile: the barge, PM Hs 3.1 m, 40
    components, 20-s records): measured 0.0023 % at 0.2 s (float32 wave tables' rounding), 0.24 % at
    1.0 s, 2.3 % at 2.0 s; so 0.2 s passes the 1 % and 2.0 s fails it, and a cell without its error
    makes the row FAIL with the reason."""
    from stabflow.dynamics.broaching import probability_map

    cfg = load_pipeline(ROOT / "config" / "test.yaml")["broaching"]
    ship = load_ship(SHIPS / f"{cfg['ship']}.yaml")
    pm = {dt: probability_map(ship, dict(cfg, map=dict(cfg["map"], records=1, duration=20.0, dt=dt)))
          for dt in (0.2, 2.0)}
    err = {dt: float(p["map_step_error"].max()) for dt, p in pm.items()}
    assert err[0.2] < 1.0 < err[2.0], err
    assert err[2.0] / err[0.2] > 100.0, err
    assert map_step_row(pm[0.2]).status == "PASS" and map_step_row(pm[2.0]).status == "FAIL"
    pm = pm[0.2]
    pm["map_step_error"][:] = np.nan
    row = map_step_row(pm)
    assert row.status == "FAIL" and "records without a step error" in row.reason


def test_manoeuvring_added_mass_does_not_depend_on_blas_threads():
    """The trawler's Capytaine manoeuvring added mass, solved again at every 6-DOF model build, is
    the same bit for bit whatever BLAS's thread count: Snakemake gives each job its own
    (OPENBLAS_NUM_THREADS), and a two-thread split-time job's records had parted from the
    one-thread ensemble shards' through it (3e-11 relative)."""
    from threadpoolctl import threadpool_limits

    from stabflow.dynamics.hydro import bem_mesh, manoeuvring_added_mass
    from stabflow.dynamics.tables import Sections
    from stabflow.hydrostatics.statics import equilibrium

    ship = load_ship(ROOT / "config" / "ships" / "trawler.yaml").modified(stations=21)
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    h0, th0, _ = equilibrium(Sections(hull), float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    mesh = bem_mesh(ship)
    out = []
    for n in (1, 2, 1):
        with threadpool_limits(limits=n, user_api="blas"):
            out.append(manoeuvring_added_mass(mesh, h0, th0, float(st["lcg"]), float(st["kg"]), ship.rho))
    np.testing.assert_array_equal(out[0], out[1])
    np.testing.assert_array_equal(out[0], out[2])
    assert out[0][1, 1] > 0 and out[0][2, 2] > 0
