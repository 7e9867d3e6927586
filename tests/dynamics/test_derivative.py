"""Derivative model (paper 001): Taylor fit, transfer-function phase convention, agreement with the
full volume-based model it is fitted from."""

import numpy as np
import pytest

from stabflow.config import load_pipeline, load_ship
from stabflow.dynamics import _kernels as K
from stabflow.dynamics import derivative as D

from ..conftest import ROOT, SHIPS


@pytest.fixture(scope="module")
def dtc():
    """The default config's DTC derivative study condition (21 stations, KG 21.7 m), fitted."""
    from stabflow.statistics.ensemble import build_model

    cfg = load_pipeline(ROOT / "config" / "config.yaml")["derivative"]
    model = build_model(load_ship(SHIPS / "dtc.yaml"), D.study_condition(cfg))
    return model, D.fit_for(model, cfg["fit"]), cfg


def test_taylor_fit_recovers_a_known_cubic():
    """Value and slopes given, higher orders by least squares: a cubic is recovered exactly."""
    rng = np.random.default_rng(1)
    rel = rng.uniform(-1, 1, (200, 3)) * [2.0, 0.5, 0.05]
    true = rng.normal(size=len(D.CALM_TERMS))
    A = np.column_stack([np.prod(rel ** np.array(e), axis=1) for e in D.CALM_TERMS])
    R = A @ true
    lin = [D.CALM_TERMS.index(e) for e in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    c, fit = D._taylor_fit(rel, R, np.float64(true[0]), true[lin], list(D.CALM_TERMS), [2.0, 0.5, 0.05])
    np.testing.assert_allclose(c, true, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(fit, R, rtol=1e-10, atol=1e-10)


def test_calm_linear_terms_are_the_stiffness_matrix(dtc):
    """The first-order calm-water terms equal the restoring matrix by central differences with exact
    section clipping (linear.stiffness_matrix) within 1 % of the diagonal (tabulated sections in the
    fit); the roll row has no heave or pitch term (port-starboard symmetry)."""
    from stabflow.dynamics.linear import stiffness_matrix

    model, dm, _ = dtc
    lcg, kg = float(model.st["lcg"]), float(model.st["kg"])
    th0 = model.s0[K.S_PITCH]
    C = stiffness_matrix(model.sec, model.ship.rho, lcg, kg, K._origin_height(model.s0[K.S_Z], 0, th0, lcg, kg), th0)
    idx = [D.CALM_TERMS.index(e) for e in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    mine = -dm.calm[:, idx]
    for i in range(3):
        for j in range(3):
            assert abs(mine[i, j] - C[i, j]) <= 0.01 * np.sqrt(abs(C[i, i] * C[j, j])), (i, j, mine[i, j], C[i, j])


def test_coefficient_series_phase_and_speed(dtc):
    """The excitation series of a regular head wave at speed, from the phase-sampled transfer
    function, equals the wave force at equilibrium sampled in time with the moving stations
    (within 2 % of its amplitude, about the second harmonic's share in a 0.5 m, 500 m wave): phase
    convention, encounter frequency, speed independence. (In a 1 m, 96 m wave the phase mean is 56 %
    and the second harmonic 16 % of the first: the transfer functions keep the first and the mean.)"""
    from stabflow.dynamics.tables import kernel_args
    from stabflow.waves.synthesis import station_wave_table

    model, dm, _ = dtc
    i = int(np.argmin(np.abs(dm.frequency - 0.35)))  # lambda 500 m: second harmonic about 1 % at a = 0.5 m
    w = float(dm.frequency[i])
    waves = (np.array([0.5]), np.array([w]), np.array([0.7]))
    we = w + w**2 / 9.80665 * model.speed  # head seas
    t = np.linspace(0.0, 3 * 2 * np.pi / we, 96, endpoint=False)  # whole encounter periods
    ctab = dm.coefficient_table(waves, t)
    snaps = station_wave_table(*waves, model.sec.x, dm.heading_deg, model.speed, t, model.decay)
    args = kernel_args(model.sec, model.tables)
    R = D._sample(args, model.p, dm.q0, np.zeros((1, 3)), snaps)[:, 0, :]
    R0 = D._sample(args, model.p, dm.q0, np.zeros((1, 3)), 0 * snaps[:1])[0, 0]
    for k in (0, 2):
        ref = R[:, k] - R0[k]
        ref = ref - ref.mean()
        series = ctab[:, k, 0] - 0.25 * dm.mean_over_a2[i, k, 0]  # without the second-order mean
        assert np.max(np.abs(series - ref)) <= 0.02 * np.max(np.abs(ref)), k


def test_small_waves_and_parametric_roll_against_the_full_model(dtc):
    """Small head waves (H 0.5 m, lambda/L 1.2): steady heave and pitch within 3 % of the full model.
    Regular waves at omega_e / omega_roll = 2.2 and H = 8 m: both models develop parametric roll
    (above 10 deg from 2 deg); at 1.8 neither does (below 1 deg)."""
    from stabflow.validation.derivative import derivative_checks

    model, dm, cfg = dtc
    rm = D.regular_map(model, dm, [1.8, 2.2], [8.0], 1800.0, 0.1)
    assert float(rm["roll_full"].sel(frequency_ratio=2.2, wave_height=8.0)) > 10 and float(rm["roll_derivative"].sel(frequency_ratio=2.2, wave_height=8.0)) > 10
    assert float(rm["roll_full"].sel(frequency_ratio=1.8, wave_height=8.0)) < 1 and float(rm["roll_derivative"].sel(frequency_ratio=1.8, wave_height=8.0)) < 1
    rows = derivative_checks(model, dm, dm.dataset.merge(rm), wavelengths=(1.2,))
    small = [r for r in rows if "0.5 m regular wave" in r.check]
    assert len(small) == 2 and all(abs(r.value) <= 0.03 for r in small), [(r.check, r.value) for r in small]
    exc = [r for r in rows if "wave excitation" in r.check]
    assert all(abs(r.value) <= 0.03 for r in exc), [(r.check, r.value) for r in exc]


def test_exceedance_probability_is_clopper_pearson():
    """P(largest roll > level) and its interval equal scipy's exact binomial (Clopper-Pearson) interval."""
    from scipy import stats

    x = np.array([10.0, 30.0, 26.0, 5.0, 40.0, 24.9, 25.0])
    p, lo, hi = D.exceedance_probability(x, 25.0)
    ci = stats.binomtest(3, 7).proportion_ci(0.95, method="exact")
    assert p == pytest.approx(3 / 7) and lo == pytest.approx(ci.low) and hi == pytest.approx(ci.high)
    assert D.exceedance_probability(np.zeros(5), 25.0)[1:] == pytest.approx((0.0, 1 - 0.025 ** (1 / 5)))


def test_wave_autocorrelation_of_a_synthesized_record():
    """The analytic autocorrelation equals the sample autocorrelation of the synthesized elevation
    at short lags (a 3-hour record of 3000 components, within 0.02; at lags of minutes one record's
    sampling error is several hundredths); random frequencies give no repetition (below 0.1 beyond
    10 min: the envelope), equal frequency spacing without randomisation repeats at 2 pi / d omega."""
    from stabflow.waves.seaway import Seaway
    from stabflow.waves.synthesis import station_wave_table

    sea = Seaway(kind="jonswap", hs=10.0, tp=14.5, n_components=3000, method="equal_energy")
    comps = sea.components(1, 0)
    dt = 1.0
    t = np.arange(0.0, 10800.0, dt)
    eta = station_wave_table(*comps, np.array([0.0]), 180.0, 0.0, t)[:, 0, 0]
    lags = np.array([0.0, 3.0, 5.0, 8.0, 12.0])
    r = D.wave_autocorrelation(comps, lags)
    for lag, v in zip(lags, r):
        k = int(lag / dt)
        sample = np.mean(eta[: len(eta) - k] * eta[k:]) / np.mean(eta**2)
        assert abs(v - sample) < 0.02, (lag, v, sample)
    assert np.max(D.wave_autocorrelation(comps, np.arange(600.0, 10800.0, 1.0), envelope=True)) < 0.1
    uniform = Seaway(kind="jonswap", hs=10.0, tp=14.5, n_components=200, method="uniform", randomise=False)
    w = uniform.components(1, 0)[1]
    period = 2 * np.pi / (w[1] - w[0])
    assert D.wave_autocorrelation(uniform.components(1, 0), [period], envelope=True)[0] > 0.99
    assert D.wave_autocorrelation(uniform.components(1, 0), [0.5 * period], envelope=True)[0] < 0.1
