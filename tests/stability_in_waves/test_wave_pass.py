"""Wave-pass statics (paper 002, Appendix 2)."""

import numpy as np
import pytest

from stabflow.config import load_ship
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics
from stabflow.stability_in_waves.wave_pass import crest_trough_calm, wave_gm, wave_gz, wave_pass

from ..conftest import SHIPS


@pytest.fixture(scope="module")
def dtmb():
    ship = load_ship(SHIPS / "dtmb5415.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    return ship, Sections(hull), st, tuple(float(st[k]) for k in ("volume", "lcg", "kg", "lwl"))


def test_zero_height_reproduces_calm(dtmb):
    _, sec, st, (V, lcg, kg, L) = dtmb
    k = 2 * np.pi / L
    for x in np.linspace(-0.5 * L, 0.5 * L, 5):
        assert wave_gm(sec, V, lcg, kg, 1e-7 * L, k, x)[0] == pytest.approx(float(st.gm), abs=1e-4)
    heel = np.arange(0.0, 181.0, 10.0)
    gz = wave_gz(sec, V, lcg, kg, 1e-7 * L, k, 0.3 * L, heel)
    assert np.abs(gz - st.gz.sel(heel=heel).values).max() < 1e-4 * float(st.gz_max)


def test_box_barge_gm_on_a_wave_is_analytic():
    """Wall-sided box on a wave: waterline breadth stays B, so BM changes only through nothing:
    GM(x_c) = KB(x_c) + B^3 L / (12 V) - KG with KB from the wave-profile volume centre."""
    ship = load_ship(SHIPS / "barge.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    sec = Sections(hull)
    L, B = 100.0, 20.0
    gm, kb, bm, _ = wave_gm(sec, 12000.0, 0.0, 7.0, 2.0, 2 * np.pi / L, 0.0)
    assert bm == pytest.approx(B**3 * L / 12 / 12000.0, rel=1e-12)
    # heave of a box on a full wavelength: local drafts T + eta, KB = mean((T+eta)^2)/2 / T
    assert kb == pytest.approx((36.0 + 0.5 * 2.0**2) / 2 / 6.0, rel=2e-3)
    assert gm == pytest.approx(kb + bm - 7.0)
    assert float(st.gm) < gm  # a box gains KB on a wave


def test_crest_below_trough_above_for_dtmb(dtmb):
    """Paper 002: crest amidships lowers GZ of a flared hull, trough amidships raises it."""
    _, sec, st, (V, lcg, kg, L) = dtmb
    heel = np.arange(5.0, 91.0, 5.0)
    ct = crest_trough_calm(sec, V, lcg, kg, L, 0.05, heel)
    assert np.all(ct.gz_crest < ct.gz_calm)
    assert np.all(ct.gz_trough > ct.gz_calm)
    assert np.allclose(ct.gz_calm, st.gz.sel(heel=heel), atol=1e-6)


def test_gm_and_gz_converge_with_stations(dtmb):
    ship, sec, st, (V, lcg, kg, L) = dtmb
    sec2 = Sections(build_hull(ship.modified(stations=2 * ship.hull["stations"])))
    k = 2 * np.pi / L
    for x in (0.0, 0.25 * L, 0.5 * L):
        a = wave_gm(sec, V, lcg, kg, 3.5, k, x)[0]
        b = wave_gm(sec2, V, lcg, kg, 3.5, k, x)[0]
        assert abs(a - b) < 0.02 * float(st.gm)
    heel = np.arange(0.0, 61.0, 10.0)
    for x in (0.0, 0.5 * L):
        ga = wave_gz(sec, V, lcg, kg, 3.5, k, x, heel)
        gb = wave_gz(sec2, V, lcg, kg, 3.5, k, x, heel)
        assert np.abs(ga - gb).max() < 0.02 * float(st.gz_max)


def test_sweep_dataset(dtmb):
    _, sec, st, (V, lcg, kg, L) = dtmb
    ds = wave_pass(sec, V, lcg, kg, L, [1.0], [0.02, 0.05], 5, np.arange(0.0, 61.0, 15.0))
    assert ds.gm_wave.dims == ("wavelength_ratio", "steepness", "crest_position")
    assert ds.gz_wave.attrs["units"] == "m"
    # GZ slope at 0 equals GM on the wave (two independent routes)
    d = 0.05
    slope = wave_gz(sec, V, lcg, kg, 0.5 * 0.05 * L, 2 * np.pi / L, 0.0, [0.0, d])[1] / np.sin(np.radians(d))
    assert slope == pytest.approx(float(ds.gm_wave.sel(steepness=0.05).isel(wavelength_ratio=0, crest_position=2)), abs=1e-3)
    # steeper wave, crest amidships -> lower GM
    mid = ds.gm_wave.isel(wavelength_ratio=0, crest_position=2)
    assert float(mid.sel(steepness=0.05)) < float(mid.sel(steepness=0.02)) < float(st.gm)
