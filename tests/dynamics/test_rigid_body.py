"""Rigid-body equations about G (issue 15 part 1): energy, G's vertical line, the box barge's
exact free-roll period. None of these holds for Newton's law of G written for the keel point."""

import dataclasses

import numpy as np
import pytest
from scipy import integrate

from stabflow.constants import G
from stabflow.dynamics import _kernels as K
from stabflow.dynamics import coefficients
from stabflow.dynamics.model import initial_state, parameters
from stabflow.dynamics.rigid_body import SIX_DOF, THREE_DOF, accelerations, mechanical_energy, origin_height
from stabflow.dynamics.tables import kernel_args
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics
from stabflow.validation.references import exact_box_gz

from .conftest import ship_model


def undamped(co):
    return dataclasses.replace(co, b33=0.0, b44=0.0, b44q=0.0, b55=0.0)


def free_roll(sec, st, co, rho, phi0_deg, duration, dt, free=THREE_DOF):
    """Calm-water free roll from the heeled equilibrium: states (n, N_STATE), exact clipping."""
    p = parameters(co, rho, float(st.lcg), float(st.kg), 0.0, free=free)
    n = int(round(duration / dt))
    wtab = np.zeros((2 * n + 1, len(sec.x), 2))
    out = np.empty((n + 1, K.N_STATE))
    s0 = initial_state(sec, st, phi0_deg)
    last = K._simulate(*kernel_args(sec), p, wtab, np.empty((0, 6)), dt, 0, n, s0, np.radians(90.0), out, np.empty((0, 6)))
    assert last == n, "capsized"
    return p, out


@pytest.fixture(scope="module", params=["barge", "dtmb5415"])
def ship(request):
    s, sec, st, co = ship_model(request.param)
    if request.param == "dtmb5415":
        # the measured case below: DTMB 5415 with the schema's default kxx 0.40 B_wl (its ship file
        # has the published 7.363 m since 2026-12-07; the free roll's vertex crossings, which set the
        # observed order, move with the inertia: 1.6e-6 / 1.3e-7 / 2.9e-8, order 3.6, 2.2 there)
        co = dataclasses.replace(co, i44=co.mass * (0.40 * float(st["bwl"])) ** 2)
    return s, sec, st, co


def energy_drifts(s, sec, st, co, phi0_deg, steps, duration=20.0):
    """Max |E - E0| over an undamped calm-water free roll, relative to the potential energy
    released between phi0 and upright, for each step in ``steps``; and the roll range [deg]."""
    co = undamped(co)
    drifts = []
    for dt in steps:
        p, out = free_roll(sec, st, co, s.rho, phi0_deg, duration, dt)
        e = mechanical_energy(sec, p, out)
        scale = e[0] - mechanical_energy(sec, p, initial_state(sec, st))[0]
        assert scale > 0
        drifts.append(np.abs(e - e[0]).max() / scale)
    drifts = np.array(drifts)
    return drifts, np.log2(drifts[:-1] / drifts[1:]), np.degrees(out[:, K.S_ROLL])


def test_energy_is_conserved_to_rk4_accuracy(ship):
    """Undamped calm-water free roll from 60 deg: the total mechanical energy (kinetic of the
    rigid body and added mass + potential of G + hydrostatic potential of the sections) drifts
    only by the integration error, which vanishes as dt shrinks. Measured over 20 s, relative to
    the potential energy released between 60 deg and upright, at dt = 0.1 / 0.05 / 0.025 s: barge
    1.9e-5 / 2.6e-6 / 3.3e-7 (order 2.9, 3.0), dtmb5415 1.0e-6 / 1.1e-7 / 1.3e-8 (order 3.2, 3.1).
    The order is 3, not 4, over this range: the sectional loads are only once continuously
    differentiable where a hull vertex (the box corners at 31 deg, the mesh's vertices) crosses
    the waterline, and RK4's local error over such a step is O(dt^3). Within a smooth range the
    order is 4: see the next test. (Newton's law for G applied at the keel point, the previous
    equations, gives drifts of 2.5 times the released energy on dtmb5415 at every dt, and the
    barge capsizes from 60 deg instead of swinging back to -58 deg.)"""
    s, sec, st, co = ship
    drifts, order, roll = energy_drifts(s, sec, st, co, 60.0, (0.1, 0.05, 0.025))
    msg = f"relative drift {drifts}, order {order}"
    assert roll.min() < -45.0  # it swung through large angles to the other side
    assert drifts[-1] < 1e-6, msg
    assert order.min() > 2.7, msg


def test_energy_drift_is_fourth_order_where_the_loads_are_smooth():
    """Box barge released at 25 deg (wall-sided range, no section corner crosses the waterline,
    so the loads are smooth): RK4's 4th-order convergence of the energy drift. Measured at dt =
    0.2 / 0.1 / 0.05 s: 3.5e-6 / 8.9e-8 / 3.1e-9 (order 5.3, 4.9)."""
    s, sec, st, co = ship_model("barge")
    drifts, order, roll = energy_drifts(s, sec, st, co, 25.0, (0.2, 0.1, 0.05))
    msg = f"relative drift {drifts}, order {order}"
    assert roll.min() < -24.0
    assert drifts[-1] < 1e-8, msg
    assert order.min() > 3.9, msg


def test_g_moves_on_a_vertical_line(ship):
    """All six coordinates free, damped calm-water free roll from 60 deg: no horizontal force, so
    G stays on its vertical line (to round-off) while it moves vertically and the keel swings
    sideways by meters."""
    s, sec, st, co = ship
    p, out = free_roll(sec, st, co, s.rho, 60.0, 30.0, 0.05, free=SIX_DOF)
    assert np.abs(out[:, [K.S_X, K.S_Y]]).max() < 1e-9
    assert np.ptp(out[:, K.S_Z]) > 0.2
    # the keel point's sideways excursion: y of the origin = -(R r_G)_y = -sin(phi) cos(...) z_G
    y_keel = np.sin(out[:, K.S_ROLL]) * float(st.kg)
    assert np.ptp(y_keel) > 5.0


def test_six_dof_equals_three_dof_for_the_symmetric_barge():
    """Box barge (fore-aft and port-starboard symmetric) in calm water: with surge, sway and yaw
    free the motion is the 3-DOF one to round-off (no force or moment to excite them)."""
    s, sec, st, co = ship_model("barge")
    _, a = free_roll(sec, st, co, s.rho, 40.0, 30.0, 0.05, free=THREE_DOF)
    _, b = free_roll(sec, st, co, s.rho, 40.0, 30.0, 0.05, free=SIX_DOF)
    assert np.abs(a - b).max() < 1e-9


def test_box_barge_free_roll_period_is_the_energy_integral():
    """Box barge with G in the waterplane (KG = T = 6 m), released at 30 deg (wall-sided up to
    atan(6/10) = 31 deg): the waterline pivots about G's line, so G does not move and the motion
    is exactly 1-DOF: roll between +-phi0 with T = 4 int_0^phi0 dphi / sqrt(2 (V(phi0) - V(phi)) / I),
    V = m g int GZ from the exact box GZ, I = I44 + A44. Measured deviation of the period and the
    amplitude well below 1e-5."""
    base = ship_model("barge")[0]
    s = base.modified(kg=6.0)
    hull = build_hull(s)
    st = compute_statics(s, hull)
    sec = Sections(hull)
    co = undamped(coefficients(s, sec, st))
    phi0 = 30.0
    h = s.hull
    volume = float(st.volume)

    def gz(phi):
        return float(exact_box_gz(h["length"], h["breadth"], h["depth"], volume, 6.0, [np.degrees(phi)])[0])

    m = co.mass
    inertia = co.i44 + co.a44

    def V(phi):
        return m * G * integrate.quad(gz, 0.0, phi, epsabs=0, epsrel=1e-12)[0]

    a = np.radians(phi0)
    va = V(a)
    # phi = phi0 sin(u) removes the square-root singularity at the turning point
    T_ref = 4 * integrate.quad(lambda u: a * np.cos(u) / np.sqrt(2 * (va - V(a * np.sin(u))) / inertia),
                               0.0, np.pi / 2, epsabs=0, epsrel=1e-10, limit=200)[0]
    dt = 0.02
    p, out = free_roll(sec, st, co, s.rho, phi0, 3.2 * T_ref, dt)
    roll = np.degrees(out[:, K.S_ROLL])
    t = np.arange(len(roll)) * dt
    # downward zero crossings, linear interpolation (error O(dt^2 phi''') ~ 1e-7 s here)
    i = np.nonzero((roll[:-1] > 0) & (roll[1:] <= 0))[0]
    tc = t[i] + dt * roll[i] / (roll[i] - roll[i + 1])
    periods = np.diff(tc)
    # released at +phi0 and run for 3.2 periods: downward crossings at T/4, 5T/4, 9T/4
    assert len(periods) == 2
    assert periods == pytest.approx(T_ref, rel=1e-5)
    # symmetric swing between +-phi0, G motionless
    assert roll.min() == pytest.approx(-phi0, rel=1e-5)
    assert roll.max() == pytest.approx(phi0, rel=1e-9)
    assert np.ptp(out[:, K.S_Z]) < 1e-6
    assert np.abs(out[:, K.S_PITCH]).max() < 1e-9


def test_three_dof_accelerations_match_the_textbook_form():
    """At zero rates and zero heel, the generalized equations reduce to (m + A33) z'' = Fz - m g,
    (I44 + A44) phi'' = cos(theta) Mx - sin(theta) Mz, (I55 + A55) theta'' = My."""
    s, sec, st, co = ship_model("dtmb5415")
    p = parameters(co, s.rho, float(st.lcg), float(st.kg), 0.0)
    state = np.zeros(K.N_STATE)
    th = np.radians(0.7)
    state[K.S_PITCH] = th
    f = np.array([1e5, -2e5, 9.0e7, 3e6, -4e6, 5e5])
    acc = accelerations(p, state, f)
    assert acc[[K.S_X, K.S_Y, K.S_YAW]] == pytest.approx([0, 0, 0], abs=0)
    assert acc[K.S_Z] == pytest.approx((f[2] - co.mass * G) / (co.mass + co.a33), rel=1e-12)
    assert acc[K.S_ROLL] == pytest.approx((np.cos(th) * f[3] - np.sin(th) * f[5]) / (co.i44 + co.a44), rel=1e-12)
    assert acc[K.S_PITCH] == pytest.approx(f[4] / (co.i55 + co.a55), rel=1e-12)
    # and the origin sits below G by the rotated lever arm
    q = state[:6]
    assert origin_height(p, q) == pytest.approx(np.sin(th) * float(st.lcg) - np.cos(th) * float(st.kg), abs=1e-12)


def test_running_roll_amplitude_follows_lamp():
    """LAMP's running amplitude (paper 004, after eq 19): after each zero crossing of roll the
    memory state holds the largest |roll| of the half-cycle just ended; a table of B44q rising
    with amplitude damps the first large swings harder than a constant one at the small-amplitude
    value."""
    s, sec, st, co = ship_model("barge")
    co = dataclasses.replace(co, b44q_table=np.linspace(0.0, 5e9, K.N_AMPLITUDES))
    p, out = free_roll(sec, st, co, s.rho, 20.0, 60.0, 0.05)
    roll = out[:, K.S_ROLL]
    cross = np.nonzero(np.sign(roll[1:]) != np.sign(roll[:-1]))[0] + 1
    assert len(cross) > 4
    assert out[0, K.S_AMP] == pytest.approx(np.radians(20.0))
    for a, b in zip(cross[:-1], cross[1:]):
        # between crossings the amplitude is held at the previous half-cycle's largest |roll|
        assert np.all(out[a:b, K.S_AMP] == out[a, K.S_AMP])
        assert out[b, K.S_AMP] == pytest.approx(np.abs(roll[a:b]).max(), rel=1e-12)
    const = dataclasses.replace(co, b44q_table=None, b44q=0.0)
    _, base = free_roll(sec, st, const, s.rho, 20.0, 60.0, 0.05)
    assert np.abs(roll[cross[2]:]).max() < np.abs(base[cross[2]:, K.S_ROLL]).max()


def test_lateral_specific_force_of_harmonic_roll():
    """Prescribed roll phi = A sin(w t), heave and pitch still: f_y = g sin(phi) + h A w^2 sin(w t)
    (the linear (g + w^2 h) phi for small A); central differences of the rate: error O(dt^2)."""
    from stabflow.constants import G
    from stabflow.dynamics._kernels import N_STATE, S_RATE, S_ROLL
    from stabflow.dynamics.rigid_body import lateral_specific_force

    A, w, h, dt = 0.3, 0.6, 4.0, 0.05
    t = np.arange(2000) * dt
    st = np.zeros((len(t), N_STATE))
    st[:, S_ROLL] = A * np.sin(w * t)
    st[:, S_RATE + S_ROLL] = A * w * np.cos(w * t)
    f = lateral_specific_force(st, dt, h)
    exact = G * np.sin(st[:, S_ROLL]) + h * A * w**2 * np.sin(w * t)
    np.testing.assert_allclose(f[1:-1], exact[1:-1], atol=h * A * w**4 * dt**2)


def test_lateral_specific_force_with_heave_and_pitch():
    """Roll with heave and pitch: f_y = (g + z'') cos(theta) sin(phi) - h phi'' - h theta'^2 sin(phi)
    cos(phi) for prescribed harmonic z, phi, theta (the heave and pitch terms checked, not only roll)."""
    from stabflow.constants import G
    from stabflow.dynamics._kernels import N_STATE, S_PITCH, S_RATE, S_ROLL, S_Z
    from stabflow.dynamics.rigid_body import lateral_specific_force

    dt, h = 0.02, 3.0
    t = np.arange(3000) * dt
    (A, w), (Z, wz), (T, wt) = (0.4, 0.5), (2.0, 0.9), (0.2, 1.3)
    st = np.zeros((len(t), N_STATE))
    st[:, S_ROLL], st[:, S_RATE + S_ROLL] = A * np.sin(w * t), A * w * np.cos(w * t)
    st[:, S_Z], st[:, S_RATE + S_Z] = Z * np.sin(wz * t), Z * wz * np.cos(wz * t)
    st[:, S_PITCH], st[:, S_RATE + S_PITCH] = T * np.sin(wt * t), T * wt * np.cos(wt * t)
    phi, th = st[:, S_ROLL], st[:, S_PITCH]
    exact = ((G - Z * wz**2 * np.sin(wz * t)) * np.cos(th) * np.sin(phi) + h * A * w**2 * np.sin(w * t)
             - h * (T * wt * np.cos(wt * t)) ** 2 * np.sin(phi) * np.cos(phi))
    f = lateral_specific_force(st, dt, h)
    np.testing.assert_allclose(f[1:-1], exact[1:-1], atol=2e-3)
    # each term matters at this tolerance: dropping heave's or pitch's term misses by far more
    assert np.max(np.abs(Z * wz**2 * np.sin(wz * t) * np.cos(th) * np.sin(phi))) > 0.5
    assert np.max(np.abs(h * (T * wt) ** 2 * np.sin(phi) * np.cos(phi))) > 0.05
