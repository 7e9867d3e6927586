"""Grim's effective wave: the closed-form transfer function against the least-squares projection
it stands for, and the stability tables on the box barge against the wall-sided closed form."""

import math

import numpy as np
import pytest

from stabflow.config import load_ship
from stabflow.constants import G
from stabflow.criteria import effective_wave as ew
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics
from stabflow.validation.criteria import TOL_GRIM, grim_check
from tests.conftest import SHIPS


def test_transfer_is_the_projection_of_one_component():
    """(2/L) int cos(k x) cos(2 pi x / L) dx over the ship's length, by quadrature on 4001 points,
    equals F(k) to 1e-9 for short, equal and long waves, and F = 1 at lambda = L."""
    L = 120.0
    x = np.linspace(-L / 2, L / 2, 4001)
    for lam in (0.3 * L, 0.7 * L, L, 1.0000001 * L, 1.6 * L, 5 * L):
        k = 2 * math.pi / lam
        w = math.sqrt(G * k)
        direct = float(ew.projection(x, np.cos(k * x), L))
        assert float(ew.grim_transfer(w, L)) == pytest.approx(direct, abs=1e-9)
    assert float(ew.grim_transfer(math.sqrt(G * 2 * math.pi / L), L)) == pytest.approx(1.0, abs=1e-12)
    assert abs(float(ew.grim_transfer(1e-3, L))) < 1e-6


def test_random_sea_projection_matches_the_spectral_sigma():
    """The validation row: 4000 random profiles projected over L, their sigma within TOL_GRIM of
    sqrt(int S F^2) (measured 0.8 %, sampling error about 1.1 %)."""
    c = grim_check()
    assert c.status == "PASS" and abs(c.value) <= TOL_GRIM


def test_vanishing_angle():
    h = np.arange(0.0, 91.0, 1.0)
    assert ew.vanishing_angle(h, np.sin(np.radians(2 * h))) == pytest.approx(90.0)
    assert ew.vanishing_angle(h, np.sin(np.radians(3 * h))) == pytest.approx(60.0, abs=0.05)
    # an angle of loll at 10 deg before a positive range that vanishes at 60 deg
    loll = np.sin(np.radians(3 * h)) * (h - 10.0)
    assert ew.vanishing_angle(h, loll) == pytest.approx(60.0, abs=0.05)
    assert ew.vanishing_angle(h, -np.abs(np.sin(np.radians(h)))) == 0.0
    # two humps: the first positive stretch ends at 30 deg; the second hump does not count
    humps = np.sin(np.radians(6 * h)) + 0.2
    first = float((180.0 - np.degrees(np.arcsin(-0.2))) / 6)  # sin(6 h) = -0.2 just past 30 deg
    assert ew.vanishing_angle(h, humps) == pytest.approx(first, abs=0.05)
    # a curve ended by a failed equilibrium (NaN) ends there
    g = np.sin(np.radians(h))
    g[50:] = np.nan
    assert ew.vanishing_angle(h, g) == 49.0


def test_box_table_closed_form():
    """Wall-sided box: with the crest or trough amidships GM = GM0 + a^2 / (4 T), the largest over
    crest positions (a quarter-length crest gives less); at zero height GM0."""
    ship = load_ship(SHIPS / "barge.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    import xarray as xr

    heff = xr.DataArray([[2.0, 6.0]], dims=("hs", "tz"), coords={"hs": [3.0], "tz": [8.0, 9.0]})
    T, gm0 = 6.0, float(st["gm"])
    ds = ew.stability_on_effective_waves(Sections(hull), float(st["volume"]), float(st["lcg"]), float(st["kg"]),
                                         float(st["lwl"]), heff, gm0, n_heights=4, n_crest=8, heel_deg=np.arange(0, 61, 2.0))
    a = 0.5 * ds.ew_height.values
    np.testing.assert_allclose(ds.ew_table_gm_max.values, gm0 + a**2 / (4 * T), atol=1e-9)
    assert float(ds.ew_table_gm_min[0]) == pytest.approx(gm0, abs=1e-9)
    assert float(ds.ew_gm_max.sel(tz=9.0, hs=3.0)) == pytest.approx(gm0 + 9.0 / (4 * T), abs=1e-9)  # H_eff = 6 m is the table's top
    assert float(ds.ew_delta_gm_ratio.sel(tz=9.0, hs=3.0)) == pytest.approx(
        (float(ds.ew_gm_max.sel(tz=9.0, hs=3.0)) - float(ds.ew_gm_min.sel(tz=9.0, hs=3.0))) / 2 / gm0)
