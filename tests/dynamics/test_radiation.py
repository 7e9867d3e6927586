"""Heave-pitch radiation with memory (issue 17): the state-space model's algebra, the rational fit
against a known system, the kernel's memory states against the linear frequency-domain solution
and against constant coefficients at the encounter frequency, and the BEM on a box barge."""

from dataclasses import replace

import numpy as np
import pytest
import xarray as xr

from stabflow.constants import G, KNOT
from stabflow.dynamics import _kernels as K
from stabflow.dynamics.manoeuvring import Manoeuvring, build_six_dof, linear_regular_response, simulate_six_dof
from stabflow.dynamics.radiation import (Memory, bem_frequencies, bem_from_dataset, fit_memory,
                                         infinite_frequency_estimate, memory_from_dataset, model_order, passivity,
                                         radiation_checks, radiation_dataset, retardation)
from stabflow.dynamics.tables import section_tables

from ..conftest import synthetic_radiation as _synthetic
from .conftest import ship_model

HP = np.ix_([K.S_Z, K.S_PITCH], [K.S_Z, K.S_PITCH])


def test_kernel_and_response_are_one_transform_pair():
    """K^(w) of the model equals the numerical Fourier-Laplace transform of its K(t) (to 1e-6), and
    K(t) equals the cosine transform of its damping (Ogilvie), for complex and real poles."""
    mem = Memory(np.array([-0.4 + 1.1j, -0.9 + 0j]), np.array([[[3.0 + 1.0j, 2.0], [1.0 - 0.5j, -1.0]],
                                                              [[0.5j, 0.3], [2.0 + 2.0j, 4.0]]]), np.eye(2))
    t = np.linspace(0.0, 60.0, 60001)
    kt = mem.kernel(t)
    for w in (0.3, 1.0, 2.5):
        num = np.trapezoid(kt * np.exp(-1j * w * t)[:, None, None], t, axis=0)
        assert np.allclose(num, mem.response([w])[0], rtol=0, atol=1e-6 * np.max(np.abs(num)))
    wg = np.linspace(1e-4, 200.0, 400001)
    k_from_b = retardation(wg, mem.damping(wg), np.array([0.0, 0.5, 2.0]))
    assert np.allclose(k_from_b[1:], mem.kernel([0.5, 2.0]), atol=2e-3 * np.max(np.abs(kt)))


def test_fit_recovers_a_known_system_and_its_infinite_frequency_added_mass():
    """The rational fit of a synthetic fourth-order system recovers its poles (1e-5) and reproduces
    A(w), B(w) to 1e-6; A(inf) extrapolated from the finite frequencies alone equals the true one to
    1e-6; the checks pass."""
    ds, poles = _synthetic()
    mem = fit_memory(ds, order=4)
    assert np.sort_complex(mem.poles) == pytest.approx(np.sort_complex(poles), abs=1e-5)
    w = ds["omega"].values
    assert np.allclose(mem.damping(w), ds["damping"].values, atol=1e-6 * np.abs(ds["damping"].values).max())
    assert np.allclose(mem.added_mass(w), ds["added_mass"].values, rtol=1e-6)
    est = infinite_frequency_estimate(ds, 4)
    assert np.allclose(est, ds["added_mass_inf"].values, rtol=1e-6)
    rows = radiation_checks(ds, mem)
    assert len(rows) == 9 and all(r.status == "PASS" for r in rows)
    # the chosen order when left to the fit: the smallest within 2 % (at most the true one)
    assert model_order(fit_memory(ds)) <= 4
    # no damping at zero frequency: K^(0) = 0
    assert np.max(np.abs(mem.response([1e-9]))) < 1e-6 * np.max(np.abs(ds["damping"].values))


def test_checks_fail_when_the_fit_misses():
    """A second-order fit (one pole pair) of the fourth-order system misses by more than the 5 %
    tolerance: its damping and added-mass rows FAIL."""
    ds, _ = _synthetic()
    rows = radiation_checks(ds, fit_memory(ds, order=2))
    assert sum(r.status == "FAIL" for r in rows if "of the fit vs the BEM" in r.check) >= 2


def test_passivity_flags_negative_heave_damping():
    """A system whose heave damping dips to about -20 % of its peak near 0.3 rad/s (a negative
    resonant term) while the pitch damping, 23 times larger in its units, stays positive: fitted
    exactly, it is not passive (scaled by the diagonal the smallest eigenvalue is below -0.1; unscaled
    by the largest entry it would be about -0.01) and the passivity row FAILs."""
    ds, _ = _synthetic()
    assert passivity(fit_memory(ds, order=4), 3.0) > -1e-9
    w = ds["omega"].values
    s_ = 1j * w
    H = ds["damping"].values + 1j * w[:, None, None] * (ds["added_mass"].values - ds["added_mass_inf"].values)
    peak = ds["damping"].values[:, 0, 0].max()
    H[:, 0, 0] -= 0.3 * peak * 2 * 0.1 * 0.3 * s_ / (s_**2 + 2 * 0.1 * 0.3 * s_ + 0.09)
    bad = ds.copy(deep=True)
    bad["damping"].values[:] = H.real
    bad["added_mass"].values[:] = ds["added_mass_inf"].values + H.imag / w[:, None, None]
    assert bad["damping"].values[:, 0, 0].min() < -0.1 * peak
    mem = fit_memory(bad, order=6)
    assert passivity(mem, 3.0) < -0.1
    rows = [r for r in radiation_checks(bad, mem) if "passive" in r.check]
    assert rows[0].status == "FAIL"


def test_stored_model_round_trips():
    ds, _ = _synthetic()
    mem = fit_memory(ds, order=4)
    back = memory_from_dataset(radiation_dataset(ds, mem))
    assert np.array_equal(back.poles, mem.poles) and np.array_equal(back.residues, mem.residues)


def test_bem_frequencies_follow_the_panel_rule():
    """The last frequency's deep-water wavelength is at least 13 largest panel radii, and the next
    step's would not be."""
    w = bem_frequencies(0.598)
    assert w[0] == pytest.approx(0.1) and np.allclose(np.diff(w), 0.1)
    lam = 2 * np.pi * G / w**2
    assert lam[-1] >= 13 * 0.598 > 2 * np.pi * G / (w[-1] + 0.1) ** 2


@pytest.fixture(scope="module")
def trawler_memory():
    """The trawler with constant coefficients and with a synthetic heave-pitch memory."""
    ship, sec, st, co = ship_model("trawler")
    ds, _ = _synthetic()
    mem = fit_memory(ds, order=4)
    tabs = section_tables(sec, 181, 101)
    from stabflow.dynamics.manoeuvring import Foil

    man = Manoeuvring(foils=(Foil(x=-10.4, z=1.45, span=2.9, chord=0.43, rudder=True),),
                      added_mass=np.diag([1.0e4, 1.0e5, 3.0e6]), hull="slender_body")

    def build(memory=None, heading=45.0, forward_speed=False):
        return build_six_dof(sec, st, co, ship.rho, heading, 10.0 * KNOT,
                             replace(man, radiation_forward_speed=forward_speed), tables=tabs, memory=memory)

    return build, mem


def _frozen_at(const, mem, we, coefficients=None):
    """The constant model's parameter vector with the heave-pitch added mass and damping of ``mem``
    at the frequency ``we`` [rad/s] (or the given ``coefficients`` (A, B) (2, 2))."""
    p = const.p.copy()
    A = p[K.P_ADDED_MASS:K.P_ADDED_MASS + 36].reshape(6, 6)
    B = p[K.P_DAMPING:K.P_DAMPING + 36].reshape(6, 6)
    A[HP], B[HP] = coefficients if coefficients is not None else (mem.added_mass([we])[0], mem.damping([we])[0])
    p[K.P_ADDED_MASS:K.P_ADDED_MASS + 36] = A.ravel()
    p[K.P_DAMPING:K.P_DAMPING + 36] = B.ravel()
    return p


def test_memory_states_equal_constant_coefficients_at_the_encounter_frequency(trawler_memory):
    """The linear response of the memory model equals that of the constant-coefficient model whose
    heave-pitch added mass and damping are the memory model's A(w_e), B(w_e) (to 1e-6): the kernel's
    states are the fitted transfer function."""
    build, mem = trawler_memory
    # asymmetric residues, so that a swap of i and j between the parameters and the kernel shows
    res = mem.residues.copy()
    res[0, 1] *= 1.3
    res[1, 0] *= 0.7
    mem = Memory(mem.poles, res, mem.added_mass_inf)
    m = build(mem)
    assert m.s0.size == 16 + mem.n_states
    lam = 30.0
    k = 2 * np.pi / lam
    we = np.sqrt(G * k) - k * m.speed * np.cos(np.radians(45.0))
    const = build()
    p = _frozen_at(const, mem, we)
    x_mem = linear_regular_response(m, lam, 1.0)
    x_const = linear_regular_response(replace(const, p=p), lam, 1.0)
    assert np.allclose(x_mem, x_const, rtol=1e-5, atol=1e-7 * np.max(np.abs(x_const)))
    # and the memory changes the heave-pitch response against the ship file's constants
    assert abs(abs(x_mem[2]) / abs(linear_regular_response(const, lam, 1.0)[2]) - 1.0) > 0.01


def _asymmetric(mem):
    """``mem`` with its coupling residues and A(inf) made unsymmetric (heave-pitch 1.3 and 1.2 times,
    pitch-heave 0.7 times), so that a swap of i and j shows."""
    res = mem.residues.copy()
    res[0, 1] *= 1.3
    res[1, 0] *= 0.7
    ai = mem.added_mass_inf.copy()
    ai[0, 1] *= 1.2
    return Memory(mem.poles, res, ai)


def _stf(mem, we, U, xt=0.0, at=0.0):
    """Salvesen, Tuck & Faltinsen's (1970) heave-pitch coefficients at speed U of zero-speed A, B
    (symmetric), their table of speed corrections with the transom terms of a transom at x_T of
    added mass a_T (its damping b^A zero)."""
    A, B = mem.added_mass([we])[0], mem.damping([we])[0]
    w2 = we * we
    Au = np.array([[A[0, 0], A[0, 1] - U * B[0, 0] / w2 - U * U * at / w2],
                   [A[1, 0] + U * B[0, 0] / w2, A[1, 1] + U * U * A[0, 0] / w2 + U * U * xt * at / w2]])
    Bu = np.array([[B[0, 0] + U * at, B[0, 1] + U * A[0, 0] - U * xt * at],
                   [B[1, 0] - U * A[0, 0] - U * xt * at, B[1, 1] + U * U * B[0, 0] / w2 + U * xt * xt * at]])
    return Au, Bu


def test_transom_added_mass_of_lewis_sections_in_closed_form():
    """The transom's heave added mass: a semicircle rho pi R^2 / 2, a flat plate rho pi b^2 / 2,
    and the trawler's broad shallow transom (6.11 m x 0.63 m, H0 4.8) within 10 % of the plate's."""
    from stabflow.dynamics.radiation import transom
    from stabflow.dynamics.roll_damping import lewis_coefficients

    def sp(b, t, sigma):
        a1, a3 = lewis_coefficients(b / (2 * t), sigma)
        return xr.Dataset({"x": ("s", [-5.0, 0.0]), "dx": ("s", [1.0, 1.0]), "breadth": ("s", [b, b]),
                           "draft": ("s", [t, t]), "valid": ("s", [True, True]),
                           "lewis_a1": ("s", [float(a1), float(a1)]), "lewis_a3": ("s", [float(a3), float(a3)])})

    xt, a = transom(sp(4.0, 2.0, np.pi / 4), 1.0, 1025.0)
    assert xt == pytest.approx(-6.5)
    assert a == pytest.approx(1025.0 * np.pi * 4.0 / 2, rel=1e-9)
    _, a = transom(sp(4.0, 1e-6, 1.0), 0.0, 1025.0)  # wide and flat: the plate
    assert a == pytest.approx(1025.0 * np.pi * 4.0 / 2, rel=1e-4)
    ship, sec, st, co = ship_model("trawler")
    from stabflow.dynamics.roll_damping import section_parameters

    xt, a = transom(section_parameters(sec, st), float(st["lcg"]), ship.rho)
    assert xt < -0.4 * 25.0
    assert a == pytest.approx(1025.0 * np.pi * (6.11 / 2) ** 2 / 2, rel=0.1)  # H0 4.8: near the plate


@pytest.mark.parametrize("lam", [21.3, 42.7])
def test_forward_speed_terms_are_strip_theory_at_the_encounter_frequency(trawler_memory, lam):
    """With the forward-speed terms, the memory model's linear response in a quartering wave equals
    that of the constant model given strip theory's A(U), B(U) at the encounter frequency (1e-5);
    the kernel's time-domain form (relative vertical velocity, -u d/dx of the momentum) is the
    frequency-domain table. Symmetric zero-speed coefficients, as potential flow has them."""
    build, mem = trawler_memory
    res = mem.residues.copy()
    res[1, 0] = res[0, 1] = 0.5 * (res[0, 1] + res[1, 0])
    ai = 0.5 * (mem.added_mass_inf + mem.added_mass_inf.T)
    mem = Memory(mem.poles, res, ai)
    m = build(mem, forward_speed=True)
    k = 2 * np.pi / lam
    we = np.sqrt(G * k) - k * m.speed * np.cos(np.radians(45.0))
    const = build()
    from stabflow.dynamics.radiation import memory_forward_speed

    xt, at = memory_forward_speed(m)
    assert at > 0.0  # the trawler's transom
    p = _frozen_at(const, mem, we, _stf(mem, we, m.speed, xt, at))
    x_fwd = linear_regular_response(m, lam, 1.0)
    x_const = linear_regular_response(replace(const, p=p), lam, 1.0)
    assert np.allclose(x_fwd, x_const, rtol=1e-5, atol=1e-7 * np.max(np.abs(x_const)))
    # the speed terms matter: the zero-speed memory gives another pitch
    x_zero = linear_regular_response(build(mem), lam, 1.0)
    assert abs(x_fwd[4] - x_zero[4]) > 0.01 * abs(x_zero[4])


def test_forward_speed_coefficients_follow_the_kernel_with_asymmetric_fits(trawler_memory):
    """forward_speed_coefficients (the F0 and report's A(U), B(U)) equal the kernel's linear
    response for a fit whose coupling is not symmetric (1e-5), and strip theory's table when it is."""
    from stabflow.dynamics.radiation import forward_speed_coefficients

    build, mem = trawler_memory
    mem = _asymmetric(mem)
    res, ai = mem.residues, mem.added_mass_inf
    m = build(mem, forward_speed=True)
    lam = 30.0
    k = 2 * np.pi / lam
    we = np.sqrt(G * k) - k * m.speed * np.cos(np.radians(45.0))
    const = build()
    from stabflow.dynamics.radiation import memory_forward_speed

    tr = memory_forward_speed(m)
    Au, Bu = (x[0] for x in forward_speed_coefficients(mem, [we], m.speed, tr))
    x_fwd = linear_regular_response(m, lam, 1.0)
    x_const = linear_regular_response(replace(const, p=_frozen_at(const, mem, we, (Au, Bu))), lam, 1.0)
    assert np.allclose(x_fwd, x_const, rtol=1e-5, atol=1e-7 * np.max(np.abs(x_const)))
    sym = Memory(mem.poles, 0.5 * (res + res.transpose(1, 0, 2)), 0.5 * (ai + ai.T))
    for got, want in zip((x[0] for x in forward_speed_coefficients(sym, [we], m.speed, tr)), _stf(sym, we, m.speed, *tr)):
        assert np.allclose(got, want, rtol=1e-12, atol=1e-9 * np.max(np.abs(want)))


def test_memory_time_domain_against_the_linear_solution(trawler_memory):
    """Small stern-quartering waves (H/lambda 1/2000), autopilot on: the 6-DOF record with the memory
    states and their forward-speed terms has the first harmonics of its linear frequency-domain solution within 0.5 %."""
    from stabflow.dynamics.manoeuvring import first_harmonic

    build, mem = trawler_memory
    m = build(mem, forward_speed=True)
    lam = 21.7
    a = lam / 4000
    k = 2 * np.pi / lam
    w = np.sqrt(G * k)
    we = w - k * m.speed * np.cos(np.radians(45.0))
    X = linear_regular_response(m, lam, a)
    xi_g = float(m.p[K.P_XG]) * np.cos(np.radians(45.0))
    ds = simulate_six_dof(m, (np.array([a]), np.array([w]), np.array([-k * xi_g])), 300.0, 0.05, ramp_s=50.0)
    fh = first_harmonic(ds, we, 165.0)
    for v, ref in zip(("heave", "pitch", "roll"), (abs(X[2]), np.degrees(abs(X[4])), np.degrees(abs(X[3])))):
        assert fh[v] == pytest.approx(ref, rel=0.005), v


def test_mean_wave_force_uses_the_damping_at_the_encounter_frequency(trawler_memory):
    """F0 of the memory model equals F0 of the constant model given the memory's A, B at w_e."""
    from dataclasses import replace

    from stabflow.dynamics.surf_riding import mean_wave_surge_force

    build, mem = trawler_memory
    m = build(mem, heading=0.0)
    lam, u = 42.7, 3.0
    k = 2 * np.pi / lam
    we = k * (np.sqrt(G / k) - u)
    const = build(heading=0.0)
    p = _frozen_at(const, mem, we)
    f_mem = mean_wave_surge_force(m, lam, 1.8, [u])[0]
    f_const = mean_wave_surge_force(replace(const, p=p), lam, 1.8, [u])[0]
    assert f_mem == pytest.approx(f_const, rel=1e-5)
    # with the forward-speed terms: the constant model given their A(U), B(U) at w_e (the power of
    # the asymmetric added mass included), and the speed terms change F0
    from stabflow.dynamics.radiation import forward_speed_coefficients

    m_fwd = build(mem, heading=0.0, forward_speed=True)
    from stabflow.dynamics.radiation import memory_forward_speed

    tr = memory_forward_speed(m_fwd)
    p_fwd = _frozen_at(const, mem, we, tuple(x[0] for x in forward_speed_coefficients(mem, [we], u, tr)))
    f_fwd = mean_wave_surge_force(m_fwd, lam, 1.8, [u])[0]
    assert f_fwd == pytest.approx(mean_wave_surge_force(replace(const, p=p_fwd), lam, 1.8, [u])[0], rel=1e-5)
    assert abs(f_fwd / f_mem - 1.0) > 0.01


def test_box_barge_bem_and_fit():
    """Capytaine on the box barge (4 m panels, a few frequencies): symmetric-shaped positive heave
    damping, A(inf) below A(0.2 rad/s), and a fit within the checks' 5 % on its own data."""
    from stabflow.dynamics.hydro import bem_mesh
    from stabflow.dynamics.radiation import bem_radiation
    from stabflow.hydrostatics.statics import equilibrium

    ship, sec, st, co = ship_model("barge")
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    w = np.array([0.2, 0.4, 0.6, 0.8, 1.0])
    ds = bem_radiation(bem_mesh(ship), h0, th0, float(st["lcg"]), float(st["kg"]), ship.rho, w)
    B = ds["damping"].values
    assert np.all(B[:, 0, 0] > 0) and np.all(B[:, 1, 1] > 0)
    assert ds["added_mass_inf"].values[0, 0] < ds["added_mass"].values[0, 0, 0]
    mem = fit_memory(ds)
    assert ds.attrs["lid_panels"] > 0
    rows = radiation_checks(ds, mem)
    assert all(r.status == "PASS" for r in rows if "of the fit vs the BEM" in r.check or "passive" in r.check)
    # the results file round-trips the BEM coefficients and the model
    back = bem_from_dataset(radiation_dataset(ds, mem))
    assert np.array_equal(back["damping"].values, ds["damping"].values)
    assert np.array_equal(back["added_mass_inf"].values, ds["added_mass_inf"].values)


def test_ship_memory_follows_the_config_and_refuses_another_lcg():
    """The trawler's config asks for the memory model, the barge's does not; a radiation dataset about
    another LCG is refused with the ship file and field named."""
    from stabflow import StabflowError
    from stabflow.config import load_ship
    from stabflow.dynamics.radiation import ship_memory, uses_memory

    from ..conftest import SHIPS, synthetic_memory_dataset

    trawler, barge = load_ship(SHIPS / "trawler.yaml"), load_ship(SHIPS / "barge.yaml")
    assert uses_memory(trawler) and not uses_memory(barge)
    assert ship_memory(barge, 0.0) is None
    rad = synthetic_memory_dataset(-0.81)
    assert ship_memory(trawler, -0.81, rad).n_states == 8
    with pytest.raises(StabflowError, match="trawler.yaml: manoeuvring.heave_pitch_radiation"):
        ship_memory(trawler, 0.5, rad)
    rad.attrs.update(ship="barge")
    with pytest.raises(StabflowError, match="of ship 'barge'"):
        ship_memory(trawler, -0.81, rad)


def test_step_too_long_for_the_memory_poles_is_refused(trawler_memory):
    """RK4 with |l| dt beyond 2.5 is refused with the largest step named."""
    from stabflow import StabflowError

    build, mem = trawler_memory
    m = build(mem)
    fast = float(np.max(np.abs(mem.poles)))
    with pytest.raises(StabflowError, match="too long for the heave-pitch memory model"):
        simulate_six_dof(m, ([], [], []), 10.0, 2.6 / fast)


def test_radiation_command_refuses_a_ship_without_the_memory_model(tmp_path):
    """`stabflow radiation` on a ship that keeps the constant coefficients: one error line naming the
    file and field, exit status 2, nothing written."""
    import subprocess
    import sys

    from ..conftest import SHIPS

    out = tmp_path / "barge_radiation.nc"
    r = subprocess.run([sys.executable, "-m", "stabflow.cli", "radiation", str(SHIPS / "barge.yaml"), "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "manoeuvring.heave_pitch_radiation" in r.stderr and not out.exists()


def test_forward_speed_terms_vanish_in_calm_water_and_the_tail_holds_trim_and_transom(trawler_memory):
    """At the calm-water rest state (trimmed by theta_0, at speed) the forward-speed terms add
    nothing: the right-hand side equals the zero-speed model's (the trim's sign and slot); the
    tail carries the calm-water trim and the hull's transom."""
    from stabflow.dynamics import _kernels_6dof as K6
    from stabflow.dynamics.manoeuvring import _linear_system
    from stabflow.dynamics.radiation import transom
    from stabflow.dynamics.roll_damping import section_parameters

    build, mem = trawler_memory
    m_fwd, m_off = build(mem, forward_speed=True), build(mem)
    ds_fwd = _linear_system(m_fwd)[2](m_fwd.s0, 0.0)
    ds_off = _linear_system(m_off)[2](m_off.s0, 0.0)
    assert abs(m_fwd.s0[K.S_PITCH]) > 1e-4  # the trawler trims: a wrong theta_0 would show
    assert np.allclose(ds_fwd, ds_off, rtol=0.0, atol=1e-9 * np.max(np.abs(ds_off)))
    ship, sec, st, co = ship_model("trawler")
    e = K6.M_MEMORY + 1 + 10 * len(mem.poles)
    assert m_fwd.m.size == e + 4 and m_fwd.m[e] == 1.0 and m_off.m[e] == 0.0
    assert m_fwd.m[e + 1] == m_fwd.s0[K.S_PITCH]
    assert tuple(m_fwd.m[e + 2:e + 4]) == transom(section_parameters(sec, st), float(st["lcg"]), ship.rho)


def test_mean_wave_force_is_the_mean_power_of_the_radiation_forces(trawler_memory):
    """F0 = k P / w_e with P the time average of x' . (A x'' + B x') over an encounter period of the
    linear response, A and B the model's (the memory's heave-pitch A(w_e), B(w_e), or A(U), B(U)
    with the speed terms, in place of the parameter vector's A(inf)): a fit whose coupling and
    A(inf) are not symmetric, so that the power of the added mass's antisymmetric part counts."""
    from stabflow.dynamics.broaching import with_condition
    from stabflow.dynamics.radiation import forward_speed_coefficients
    from stabflow.dynamics.radiation import memory_forward_speed
    from stabflow.dynamics.surf_riding import mean_wave_surge_force

    build, mem = trawler_memory
    mem = _asymmetric(mem)
    lam, u = 42.7, 3.0
    k = 2 * np.pi / lam
    we = k * (np.sqrt(G / k) - u)
    t = np.linspace(0.0, 2 * np.pi / we, 4001)[:-1]
    ph = np.exp(1j * we * t)
    for fwd in (False, True):
        m = build(mem, heading=0.0, forward_speed=fwd)
        X = linear_regular_response(with_condition(m, 0.0, u), lam, 0.9)
        A = m.p[K.P_ADDED_MASS:K.P_ADDED_MASS + 36].reshape(6, 6).copy()
        B = m.p[K.P_DAMPING:K.P_DAMPING + 36].reshape(6, 6).copy()
        if fwd:
            A[HP], B[HP] = (x[0] for x in forward_speed_coefficients(mem, [we], u, memory_forward_speed(m)))
        else:
            A[HP], B[HP] = mem.added_mass([we])[0], mem.damping([we])[0]
        xd = np.real(1j * we * X[:, None] * ph)
        xdd = np.real(-we * we * X[:, None] * ph)
        power = float(np.mean(np.sum(xd * (A @ xdd + B @ xd), axis=0)))
        assert mean_wave_surge_force(m, lam, 1.8, [u])[0] == pytest.approx(k * power / we, rel=1e-6), fwd
