"""Early-stage metric C (paper 002, section 3)."""

import numpy as np
import pytest
from scipy import integrate

from stabflow.config import load_pipeline, load_ship
from stabflow.hydrostatics.statics import Particulars
from stabflow.stability_in_waves.early_stage import assess, critical_gm, heel_of_gz_max, joint_pdf, time_below, wave_statistics, weights
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics, gz_curve
from stabflow.waves.spectra import spectrum

from ..conftest import ROOT, SHIPS


def test_joint_pdf_normalised_and_rayleigh_marginal():
    S = spectrum("bretschneider", 5.0, 12.4)
    sigma, k1, k2 = wave_statistics(S, 2 * np.pi / 12.4)
    assert 4 * sigma == pytest.approx(5.0, rel=2e-3)
    assert 0 < k1 < k2
    tot = integrate.dblquad(lambda k, A: joint_pdf(A, k, sigma, k1, k2), 0, 8 * sigma, 0, k1 + 40 * k2)[0]
    # small amplitudes spread k widely (std ~ 1/A), so a finite k range misses ~1.5e-4 of the mass
    assert tot == pytest.approx(1.0, abs=5e-4)
    for A in [0.3 * sigma, sigma, 2.5 * sigma]:
        marg = integrate.quad(lambda k: joint_pdf(A, k, sigma, k1, k2), 0, k1 + 60 * k2, limit=200)[0]
        assert marg == pytest.approx(A / sigma**2 * np.exp(-A * A / (2 * sigma**2)), rel=1e-6)
    W = weights(np.linspace(0, 8 * sigma, 9), np.linspace(0, k1 + 40 * k2, 41), sigma, k1, k2)
    assert W.sum() == pytest.approx(1.0, abs=2e-3) and np.all(W >= 0)


def test_time_below_sinusoid():
    x = np.arange(21) / 21
    g = 1.0 + 0.5 * np.cos(2 * np.pi * x)
    # exactly half of the period below the mean; a third below 1 - 0.25 (cos < -1/2)
    assert time_below(g, 1.0, 100.0, 5.0) == pytest.approx(0.5 * 100.0 / 5.0, rel=0.02)
    assert time_below(g, 0.75, 100.0, 5.0) == pytest.approx(100.0 / 3 / 5.0, rel=0.05)
    assert time_below(g, 0.4, 100.0, 5.0) == 0.0


def test_critical_gm_puts_gz_max_at_30_deg():
    ship = load_ship(SHIPS / "dtmb5415.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    sec = Sections(hull)
    gm_cr, kg_cr = critical_gm(sec, float(st.volume), float(st.lcg), float(st.km), 30.0, 0.2)
    heel = np.arange(0.0, 90.01, 0.5)
    phi = heel_of_gz_max(gz_curve(sec, float(st.volume), float(st.lcg), kg_cr, heel)["gz"].values, heel)
    assert phi == pytest.approx(30.0, abs=0.1)
    assert gm_cr == pytest.approx(float(st.km) - kg_cr)
    assert gm_cr >= 0.2


def test_tumblehome_vs_flare():
    """Paper 002's key finding (ONRTH vs ONRFL): same underwater hull, tumblehome topsides give a
    smaller angle of GZ maximum, a larger critical GM and a larger C (on the test profile's coarser
    grid of wave amplitudes, wavenumbers and crest positions; the default run's grid shows it in the
    report)."""
    cfg = load_pipeline(ROOT / "config" / "test.yaml")["early_stage"]
    states = [s for s in cfg["sea_states"] if s["name"] in ("SS5", "SS7")]
    out = {}
    for name in ["dtmb5415_flare", "dtmb5415_tumblehome"]:
        ship = load_ship(SHIPS / f"{name}.yaml")
        hull = build_hull(ship)
        st = compute_statics(ship, hull)
        m = assess(Sections(hull), Particulars.from_statics(st), states, cfg)
        out[name] = (st, m)
    (sf, mf), (sth, mth) = out["dtmb5415_flare"], out["dtmb5415_tumblehome"]
    assert float(sf.volume) == pytest.approx(float(sth.volume))  # same underwater hull
    assert float(sth.heel_gz_max) < float(sf.heel_gz_max)
    assert float(mth.gm_cr) > float(mf.gm_cr)
    assert np.all(mth.metric_c.values > mf.metric_c.values)
