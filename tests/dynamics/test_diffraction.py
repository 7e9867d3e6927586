"""The body-linear diffraction force (stabflow.dynamics.diffraction) and its place in the 3-DOF
equations."""

from __future__ import annotations

import numpy as np
import pytest

from stabflow.config import load_ship
from stabflow.constants import G
from stabflow.dynamics import _kernels as K
from stabflow.dynamics.diffraction import DOFS6, Diffraction, diffraction_dataset
from stabflow.dynamics.hydro import bem_mesh, lidded_body
from stabflow.dynamics.rao import first_harmonic

from ..conftest import SHIPS

BARGE = SHIPS / "barge.yaml"
#: the barge's calm-water equilibrium: draft 6 m (loading.draft), G at (0, 7 m) (loading.kg)
H0, KG = -6.0, 7.0


@pytest.fixture(scope="module")
def barge_body():
    return lidded_body(bem_mesh(load_ship(BARGE)), H0, 0.0, 0.0, KG, DOFS6)


@pytest.fixture(scope="module")
def barge_table(barge_body):
    # lambda = 1.5 L and 0.75 L (L = 100 m), and a long wave (8 km)
    lams = np.array([8000.0, 150.0, 75.0])
    return diffraction_dataset(barge_body, 1025.0, omegas=np.sort(np.sqrt(2 * np.pi * G / lams)),
                               headings_deg=[45.0, 90.0])


def _ensemble_model(dif: str):
    from stabflow.statistics.ensemble import build_model

    ship = load_ship(BARGE)
    cond = dict(name="t", ship=ship.name, stations=41, heading_deg=90.0, speed_kn=0.0, dt=0.1, duration=60.0, seed=1,
                dphi_dzdt=True, dynamics={"diffraction": dif})
    return build_model(ship, cond)


@pytest.mark.parametrize("speed", [0.0, 5.0])
def test_force_series_follows_the_kernels_wave_convention(barge_table, speed):
    """Capytaine's Froude-Krylov force, synthesised as a time series by the diffraction route, equals the
    first harmonic of the kernel's own FK loads on the barge held at equilibrium (the same phase
    convention, axes, y to port, moments about G, and the encounter phase at speed): a different
    method (panels against the volume-based sections). Barge at lambda 1.5 L, at rest and at 5 m/s:
    magnitudes within 3 %, phases within 2 degree."""
    from stabflow.dynamics.linear import KernelLoads
    from stabflow.waves.synthesis import encounter_frequency

    m = _ensemble_model("none")
    lcg, kg = float(m.st["lcg"]), float(m.st["kg"])
    assert lcg == pytest.approx(0.0, abs=1e-9) and kg == KG
    w = float(np.sqrt(2 * np.pi * G / 150.0))
    for beta in (45.0, 90.0):
        fk = Diffraction(barge_table, beta, which="froude_krylov")
        waves = ([0.05], [w], [0.4])
        we = abs(float(encounter_frequency(w, speed, beta)))
        kl = KernelLoads(m.sec, 1025.0, lcg, kg, waves, beta, speed, m.decay)
        t = np.arange(64) * 2 * np.pi / we / 64
        ker = np.array([kl.loads(tt, H0, 0.0, 0.0) for tt in t])
        cap = fk.force_table(*waves, speed, t)
        dofs = (1, 2, 3) if beta == 90.0 else (1, 2, 3, 4)
        for q in dofs:
            ak, pk = first_harmonic(t, ker[:, q] - ker[:, q].mean(), we)
            ac, pc = first_harmonic(t, cap[:, q], we)
            assert ak == pytest.approx(ac, rel=0.03), (beta, DOFS6[q])
            assert abs((pk - pc + np.pi) % (2 * np.pi) - np.pi) < np.radians(2.0), (beta, DOFS6[q])


def test_long_wave_diffraction_is_added_mass_times_fluid_acceleration(barge_body, barge_table):
    """Long-wave limit (G. I. Taylor's relation, the body much smaller than the wave): the diffraction
    force is the added mass times the undisturbed fluid's acceleration, F_D,j = w^2 A_j2 a for a beam
    wave (horizontal particle acceleration w^2 a at the surface). Checked against Capytaine's own
    radiation problem for sway and for roll about G (A_42: the moment reference): within 2 % at
    lambda = 8 km (k T = 0.005). The error is of first order in k T: measured 0.4 / 1.1 % (sway /
    roll) there, 3.4 / 7.6 % at 1 km."""
    import capytaine as cpt

    w = float(barge_table["diffraction_omega"].values[1])
    x = Diffraction(barge_table, 90.0, which="diffraction").transfer([w])[0]
    res = cpt.BEMSolver().solve(cpt.RadiationProblem(body=barge_body, radiating_dof="Sway", omega=w, rho=1025.0, g=G))
    for q, name in ((1, "Sway"), (3, "Roll")):
        expected = w**2 * res.added_mass[name]
        assert abs(x[q]) == pytest.approx(abs(expected), rel=0.02), name
    # in phase with the fluid's horizontal acceleration: for the elevation Re(e^(-i w t)) at the
    # origin, the particle's horizontal acceleration is Re(-i w^2 e^(-i w t)) (waves along +y), so
    # X_sway = -i w^2 A22 to the same 2 %
    assert abs(x[1] - (-1j) * w**2 * res.added_mass["Sway"]) < 0.02 * abs(x[1])
    # with the sway free (the force the sway-held records take), the sway's radiation reaction takes
    # the diffraction's roll moment away: what is left is of the order of k T (below 5 %)
    free = Diffraction(barge_table, 90.0).transfer([w])[0]
    assert abs(free[3]) < 0.05 * abs(x[3])


def test_transfer_is_zero_at_rest_and_beyond_the_resolved_frequency(barge_table):
    d = Diffraction(barge_table, 90.0)
    x = d.transfer([0.0, d.omega_max * 1.01])
    assert np.all(x == 0.0)
    with pytest.raises(ValueError, match="not in the diffraction table"):
        Diffraction(barge_table.isel(diffraction_heading=[1]), 45.0)


def test_force_table_is_the_sum_of_the_components(barge_table):
    """force_table against the direct sum Re(a X(w) e^(i(e - w_e t))) at a forward speed (encounter
    frequency), random components."""
    from stabflow.waves.synthesis import encounter_frequency

    d = Diffraction(barge_table, 45.0)
    rng = np.random.default_rng(3)
    amp = rng.uniform(0.1, 1.0, 7)
    w = rng.uniform(0.1, 0.9, 7)
    ph = rng.uniform(0, 2 * np.pi, 7)
    t = np.arange(50) * 0.37
    table = d.force_table(amp, w, ph, 4.0, t)
    we = encounter_frequency(w, 4.0, 45.0)
    X = d.transfer(w)
    direct = np.real((amp[:, None] * X)[None] * np.exp(1j * (ph[None, :] - we[None, :] * t[:, None]))[..., None]).sum(1)
    np.testing.assert_allclose(table, direct, rtol=0, atol=1e-9 * np.abs(direct).max())


def test_kernel_adds_the_force_to_the_loads():
    """A constant force table (heave force F, roll moment M) in calm water: the ship settles at the
    static offsets F / C33 and M / C44 of the restoring matrix (1 %); an empty table and a table of
    zeros give the same record bit for bit."""
    from stabflow.dynamics.linear import stiffness_matrix
    from stabflow.dynamics.tables import kernel_args

    m = _ensemble_model("none")
    lcg, kg = float(m.st["lcg"]), float(m.st["kg"])
    C = stiffness_matrix(m.sec, 1025.0, lcg, kg, H0, 0.0)
    n = 3000
    wtab = np.zeros((2 * n + 1, len(m.sec.x), 2))
    F, M = 0.002 * C[0, 0], np.radians(0.2) * C[1, 1]
    ftab = np.zeros((2 * n + 1, 6))
    ftab[:, 2], ftab[:, 3] = F, M
    p = m.p.copy()
    p[K.P_DAMPING + 6 * K.S_Z + K.S_Z] *= 20  # settle quickly
    p[K.P_DAMPING + 6 * K.S_ROLL + K.S_ROLL] *= 20
    out = np.empty((n + 1, K.N_STATE))
    K._simulate(*kernel_args(m.sec), p, wtab, ftab, 0.1, 0, n, m.s0, np.radians(90.0), out, np.empty((0, 6)))
    assert out[-1, K.S_Z] - m.s0[K.S_Z] == pytest.approx(0.002, rel=0.01)
    assert out[-1, K.S_ROLL] == pytest.approx(np.radians(0.2), rel=0.01)
    s0 = m.s0.copy()
    s0[K.S_ROLL] = np.radians(5.0)
    runs = []
    for f in (np.empty((0, 6)), np.zeros((2 * n + 1, 6))):
        o = np.empty((n + 1, K.N_STATE))
        K._simulate(*kernel_args(m.sec), p, wtab, f, 0.1, 0, 200, s0, np.radians(90.0), o, np.empty((0, 6)))
        runs.append(o[:201])
    assert np.array_equal(runs[0], runs[1]) and abs(runs[0][200, K.S_ROLL]) < np.radians(5.0)


def test_beam_sea_linear_model_carries_the_same_force(barge_table, monkeypatch):
    """The linear beam-sea model (criteria.beam_seas, the dead-ship and acceleration checks) adds the
    same diffraction force as the time domain: small regular beam waves, roll amplitude of the time
    domain within 1 % of the linear model's at 1.5 and 2 times the roll frequency. At the roll
    resonance the force matters: with the free sway's reaction the barge's linear roll there is
    0.74 of the model's without it (0.17 with the bare diffraction force of a sway-held ship)."""
    from stabflow.criteria.beam_seas import beam_sea_model
    from stabflow.dynamics import diffraction as D
    from stabflow.dynamics.model import simulate
    from stabflow.waves.synthesis import regular

    # a denser table of the barge at 90 degree, solved once (24 frequencies)
    body = lidded_body(bem_mesh(load_ship(BARGE)), H0, 0.0, 0.0, KG, DOFS6)
    table = diffraction_dataset(body, 1025.0, omegas=np.linspace(0.3, 1.2, 24), headings_deg=[90.0])
    monkeypatch.setattr(D, "_TABLES", {})
    monkeypatch.setattr(D, "ship_diffraction", lambda *a, **k: table)
    m = _ensemble_model("capytaine")
    assert m.diffraction is not None
    bsm = beam_sea_model(m, w_min=0.3, w_max=1.2, n_coarse=60)
    wn = 2 * np.pi / m.roll_period
    plain = beam_sea_model(_ensemble_model("none"), w_min=0.3, w_max=1.2, n_coarse=60)
    for r in (1.5, 2.0):
        w = r * wn
        lam = 2 * np.pi * G / w**2
        a = lam / 2000
        ds = simulate(m.sec, m.st, m.co, 1025.0, regular(2 * a, lam), 90.0, 0.0, 60 * 2 * np.pi / w, 0.02 * 2 * np.pi / w,
                      dphi_dzdt=True, diffraction=m.diffraction)
        t = ds["time"].values
        sel = t > 0.6 * t[-1]
        amp, _ = first_harmonic(t[sel], np.radians(ds["roll"].values[sel]), w)
        lin = np.interp(w, bsm.omega, np.abs(bsm.roll_rao()))
        assert amp / a == pytest.approx(lin, rel=0.01), r
    ratio = np.interp(wn, bsm.omega, np.abs(bsm.roll_rao())) / np.interp(wn, plain.omega, np.abs(plain.roll_rao()))
    assert 0.6 < ratio < 0.9


def test_ensemble_paths_carry_the_force(barge_table, monkeypatch):
    """An ensemble condition of a ship with dynamics.diffraction: capytaine: the batch records equal a
    record regenerated alone and a restart from inside it, bit for bit (the split-time step relies on
    both); split-time's off-grid RK4 step from the record's state equals the record's own step; the
    records differ from those without the force; the files say which model ran."""
    from stabflow.config import load_pipeline
    from stabflow.dynamics import diffraction as D
    from stabflow.statistics.ensemble import build_model, merge, run_shard, simulate_record
    from stabflow.statistics.splittime import sub_step

    from ..conftest import ROOT

    monkeypatch.setattr(D, "ship_diffraction", lambda *a, **k: barge_table)
    cond = dict(load_pipeline(ROOT / "config" / "test.yaml")["ensembles"][0], name="barge_beam", duration=300.0,
                samples=3, heading_deg=90.0)
    ship = load_ship(BARGE)
    with_force = build_model(ship, dict(cond, dynamics={"diffraction": "capytaine"}))
    plain = build_model(ship, cond)
    ens = merge([run_shard(with_force, range(0, 3), progress=False)])
    assert ens.attrs["diffraction"].startswith("capytaine")
    assert merge([run_shard(plain, range(0, 1), progress=False)]).attrs["diffraction"] == "none"
    out, last = simulate_record(with_force, 2)
    np.testing.assert_array_equal(np.degrees(out[: last + 1, K.S_ROLL]), ens["sample_roll"].values[2, : last + 1])
    n0 = 500
    again, last2 = simulate_record(with_force, 2, s_start=out[n0], n_start=n0)
    np.testing.assert_array_equal(again[n0: last2 + 1], out[n0: last + 1])
    comps = with_force.sea.components(cond["seed"], 2)
    step = sub_step(with_force, comps, out[n0], n0 * with_force.dt, with_force.dt)
    np.testing.assert_allclose(step[:K.N_STATE], out[n0 + 1], rtol=0, atol=1e-6 * np.abs(out[n0 + 1]).max())
    base, _ = simulate_record(plain, 2)
    assert np.abs(np.degrees(base[:last + 1, K.S_ROLL] - out[:last + 1, K.S_ROLL])).max() > 0.01
