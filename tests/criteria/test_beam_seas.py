"""The linear beam-sea model (dead ship, lateral acceleration): excitation interpolation, stochastic
linearisation, Rice rates, and the model against the 3-DOF time domain in small waves."""

import dataclasses
import math

import numpy as np
import pytest
import xarray as xr

from stabflow.config import load_ship
from stabflow.constants import G
from stabflow.criteria import beam_seas as bs
from stabflow.criteria import dsa_run
from stabflow.criteria.dsa import band_spectrum, moments, rice_rate
from stabflow.config import _fill_defaults, schema
from stabflow.statistics.ensemble import build_model
from tests.conftest import SHIPS


@pytest.fixture(scope="module")
def trawler():
    ship = load_ship(SHIPS / "trawler.yaml")
    cfg = _fill_defaults(schema("config")["properties"]["dsa"], {})
    c = dsa_run.condition(dict(cfg, stations=21), ship.name, 1.0, 8.0, 90.0, 0.0, 1, 60.0, 0, 90.0, 1.0)
    model = build_model(ship, c, None)
    return ship, model, bs.beam_sea_model(model)


def test_excitation_interpolation(trawler):
    """The spline of the coarse FK excitation against the direct first harmonic between its nodes:
    within 0.5 % of the largest roll moment."""
    from stabflow.dynamics.linear import KernelLoads, fk_excitation
    from stabflow.hydrostatics.statics import equilibrium
    from stabflow.waves.synthesis import regular

    _, m, b = trawler
    st = m.st
    h0, th0, _ = equilibrium(m.sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    top = np.abs(b.force[:, 1]).max()
    coarse = np.linspace(0.05, 4.0, 80)
    for w in 0.5 * (coarse[10:70:12] + coarse[11:71:12]):
        lam = 2 * math.pi * G / w**2
        amp = 0.5 * bs.EXCITATION_STEEPNESS * lam
        loads = KernelLoads(m.sec, m.ship.rho, float(st["lcg"]), float(st["kg"]), regular(2 * amp, lam), 90.0, 0.0, m.decay)
        direct = fk_excitation(loads, h0, th0, w)[1] / amp
        i = int(np.argmin(np.abs(b.omega - w)))
        assert abs(b.force[i, 1] - direct) < 5e-3 * top


def test_roll_column_by_cramer_equals_the_solve(trawler):
    """X_roll by Cramer's rule (only Z[1, 1] carries b44 and c44) equals the full 3 x 3 solve."""
    _, _, b = trawler
    for b44, c44 in ((None, None), (3.0 * b.damping[1], None), (2.0 * b.damping[1], 0.7 * b.stiffness[1, 1])):
        full = b.rao(b44, c44)[:, 1]
        np.testing.assert_allclose(b.roll_rao(b44, c44), full, rtol=1e-9, atol=1e-12 * np.abs(full).max())


def test_stochastic_linearisation_fixed_point(trawler):
    """B44_eq = B44 + sqrt(8/pi) sigma_rate B44q(sqrt(2) sigma) at the response it gives; without
    quadratic damping the linear coefficient itself."""
    _, _, b = trawler
    S = band_spectrum(b.omega, 2.0, 5.5)
    X, beq = bs.linearised_response(b, S)
    m0, m2 = moments(b.omega, np.abs(X) ** 2 * S)
    assert beq == pytest.approx(b.damping[1] + bs.STOCHASTIC * math.sqrt(m2) * b.b44q_at(math.sqrt(2 * m0)), rel=1e-5)
    assert beq > b.damping[1]
    lin = dataclasses.replace(b, b44q=np.zeros_like(b.b44q))
    assert bs.linearised_response(lin, S)[1] == b.damping[1]


def test_cells_rates_and_acceleration(trawler):
    """Per sea state: without wind the failure rate is twice Rice's rate at the failure angle; the
    lateral acceleration at h above G is (g + w^2 h) times roll, its exceedance twice Rice's rate;
    a steady heel gives Rice's rates at phi_f -+ phi_w with the heeled restoring (the acceleration
    stays the upright one); a heel at the failure angle or no equilibrium (infinite heel) gives an
    infinite rate; zero-probability states are skipped."""
    _, _, b = trawler
    p = xr.DataArray([[0.01, 0.0]], dims=("hs", "tz"), coords={"hs": [2.5], "tz": [5.5, 6.5]})
    h = 3.0
    ds = bs.beam_sea_cells(b, p, 30.0, 0.0, None, h, [1.0, 2.0])
    S = band_spectrum(b.omega, 2.5, 5.5)
    X, _ = bs.linearised_response(b, S)
    m0, m2 = moments(b.omega, np.abs(X) ** 2 * S)
    assert float(ds.ds_roll_std[0, 0]) == pytest.approx(math.degrees(math.sqrt(m0)))
    assert float(ds.ds_failure_rate[0, 0]) == pytest.approx(2 * rice_rate(m0, m2, math.radians(30.0)))
    A = np.abs((G + b.omega**2 * h) * X) ** 2 * S
    a0, a2 = moments(b.omega, A)
    assert float(ds.ea_acceleration_std[0, 0]) == pytest.approx(math.sqrt(a0), rel=1e-12)
    assert float(ds.ea_exceedance_rate[1, 0, 0]) == pytest.approx(2 * rice_rate(a0, a2, 2.0), rel=1e-12)
    # the (g + w^2 h) factor: above G the acceleration exceeds g times roll
    assert float(ds.ea_acceleration_std[0, 0]) > 1.05 * G * math.sqrt(m0)
    assert np.isnan(float(ds.ds_roll_std[0, 1]))
    c44 = 0.8 * b.stiffness[1, 1]
    heeled = bs.beam_sea_cells(b, p, 30.0, 5.0, c44, h, [1.0])
    Xh, _ = bs.linearised_response(b, S, c44)
    n0, n2 = moments(b.omega, np.abs(Xh) ** 2 * S)
    assert float(heeled.ds_failure_rate[0, 0]) == pytest.approx(rice_rate(n0, n2, math.radians(25.0))
                                                                + rice_rate(n0, n2, math.radians(35.0)), rel=1e-12)
    assert float(heeled.ea_acceleration_std[0, 0]) == float(ds.ea_acceleration_std[0, 0])
    for phi_w in (30.0, math.inf):
        assert math.isinf(float(bs.beam_sea_cells(b, p, 30.0, phi_w, None, h, [1.0]).ds_failure_rate[0, 0]))
    # the log10 rates equal the rates' log10 where those are representable
    for x, lx in ((ds.ds_failure_rate, ds.ds_failure_log10_rate), (ds.ea_exceedance_rate, ds.ea_exceedance_log10_rate),
                  (heeled.ds_failure_rate, heeled.ds_failure_log10_rate)):
        ok = np.isfinite(lx.values)
        assert ok.any()
        np.testing.assert_allclose(lx.values[ok], np.log10(x.values[ok]), rtol=0, atol=1e-12)


def test_log10_rates_keep_what_underflows():
    """Rice's rate far in the Gaussian tail underflows to 0 as a double; its log10 keeps the order of
    magnitude (exact: log10(sqrt(m2/m0)/2pi) - a^2/(2 m0 ln 10)), and the long-term sum in log space
    equals the plain one where that is representable."""
    from stabflow.criteria.dsa import rice_log10_rate
    from stabflow.criteria.sea_states import _long_term, _long_term_log10

    m0, m2 = 1e-3, 4e-3
    assert rice_rate(m0, m2, 2.0) == 0.0
    assert rice_log10_rate(m0, m2, 2.0) == pytest.approx(math.log10(1 / math.pi) - 2000 / math.log(10.0), rel=1e-14)
    assert rice_log10_rate(m0, m2, 0.1) == pytest.approx(math.log10(rice_rate(m0, m2, 0.1)), abs=1e-12)
    assert rice_log10_rate(0.0, 0.0, 1.0) == -math.inf
    p = xr.DataArray([[0.25, 0.75, np.nan]], dims=("hs", "tz"))
    lx = xr.DataArray([[-3.0, -5.0, 0.0]], dims=("hs", "tz"))
    assert _long_term_log10(p, lx) == pytest.approx(math.log10(_long_term(p, 10.0**lx)), abs=1e-12)
    far = xr.DataArray([[-900.0, -901.0, 0.0]], dims=("hs", "tz"))
    assert _long_term(p, 10.0**far) == 0.0
    assert _long_term_log10(p, far) == pytest.approx(-900 + math.log10(0.25 + 0.075), abs=1e-12)


def test_band_beyond_the_grid_is_an_error(trawler):
    """A sea state whose spectrum reaches beyond the model's frequency grid raises, naming it."""
    _, _, b = trawler
    short = dataclasses.replace(b, omega=b.omega[b.omega < 2.0], force=b.force[b.omega < 2.0])
    p = xr.DataArray([[0.01]], dims=("hs", "tz"), coords={"hs": [1.5], "tz": [4.5]})
    with pytest.raises(ValueError, match="Tz 4.5 s"):
        bs.beam_sea_cells(short, p, 30.0, 0.0, None, 0.0, [1.0])
