"""Surf-riding threshold in regular following waves (issue 17): Melnikov's method on the surge
equation alone against bisection on the commanded speed with the 6-DOF model.

Surge equation. With x the position of G relative to a wave crest travelling at the celerity c,
the ship speed is u = c + x' and

    (m + A11) x'' = T - R(c + x') - f sin(k x + e),

T the constant thrust (the calm-water resistance at the commanded speed U, :mod:`.manoeuvring`),
R(u) the resistance of the 6-DOF model, f and e the amplitude and phase of the Froude-Krylov surge
force on the hull at its calm-water equilibrium (first harmonic over the crest position).

Melnikov's method. Without thrust and resistance the equation is a pendulum; its heteroclinic
orbits join the saddles one wavelength apart, with x'_0(x) = -2 sqrt(f / (M k)) |cos((k x + e) / 2)|
on the lower branch (the wave overtaking the ship), M = m + A11. Taking T - R as the perturbation,
the Melnikov integral along that orbit is int (T - R(c + x'_0)) x'_0 dt = int_0^lambda (T - R) dx,
and the heteroclinic bifurcation (beyond which periodic surging no longer exists and the ship
surf-rides from any initial condition) is where it vanishes:

    R(U_cr) = T = (1 / lambda) int_0^lambda R(c - 2 sqrt(f / (M k)) |cos(k x / 2)|) dx.

The same construction underlies the surf-riding level-2 vulnerability criterion of the IMO
second-generation criteria (Melnikov's method); its circular's text and tables could not be read
here, so this derivation uses the model's own R(u) and f instead of the circular's.

The mean wave-induced surge force. With heave and pitch free, the surge equation alone misses a
second-order mean force. In the frame moving with the wave (celerity c) the incident-wave pressure
field is steady, so its Froude-Krylov + hydrostatic loads are conservative: over a periodic motion
their mean work vanishes, and the power they feed into heave and pitch (dissipated by the damping)
is paid for by a mean surge force F0 with F0 (c - u) = D, D the mean dissipated power. This is the
momentum of the wave energy the ship absorbs, the radiated-energy argument of Gerritsma &
Beukelman (1972) for added resistance (a resistance in head seas, a thrust in following seas below
the celerity). From the linear frequency-domain response X at the encounter frequency
w_e = k (c - u): D = w_e^2 Re(X^H B X) / 2 - w_e^3 Im(X^H A X) / 2 with B the linear damping and A
the added mass (the second term vanishes for a symmetric A; the BEM's A35 and A53 differ by about
1 %, and strip theory's forward-speed terms are not symmetric), so

    F0(u) = k D / w_e = k w_e Re(X^H B X) / 2 - k w_e^2 Im(X^H A X) / 2,

which vanishes at u = c (quasi-static motions). ``melnikov_threshold(..., wave_force=True)`` uses
R(u) - F0(u) as the resistance along the orbit, F0 taken at the instantaneous speed (slowly varying
speed: valid when F0 is small against f and the speed changes little over an encounter period).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy import integrate, interpolate, optimize

from stabflow.constants import G
from stabflow.dynamics import _kernels as K
from stabflow.dynamics import _kernels_6dof as K6
from stabflow.dynamics.manoeuvring import SixDof, simulate_six_dof
from stabflow.dynamics.tables import kernel_args
from stabflow.waves.synthesis import station_wave_table


def resistance(model: SixDof, u):
    """Calm-water resistance R(u) [N] of the 6-DOF model: the kernel's own (``_kernels_6dof._resistance``,
    the method of the ship's ``manoeuvring.resistance``)."""
    u = np.asarray(u, float)
    return np.reshape([K6._resistance(model.m, float(x)) for x in u.ravel()], u.shape)


def surge_force(model: SixDof, wavelength: float, height: float, n: int = 72) -> tuple[float, float]:
    """Amplitude f [N] and phase e [rad] of the Froude-Krylov surge force (with the model's pressure
    decay, if any) in a regular following wave on the hull held at its calm-water equilibrium, F_x = -f sin(k x + e) with x the crest's
    position aft of G's station (first harmonic of n crest positions)."""
    k = 2 * np.pi / wavelength
    a = 0.5 * height
    p = model.p.copy()
    p[K.P_COS_BETA], p[K.P_SIN_BETA] = 1.0, 0.0
    xs = model.sec.x
    s = model.s0
    fx = np.empty(n)
    xc = np.arange(n) * wavelength / n
    work = np.empty((len(xs), 5))
    out = np.empty(6)
    w = np.sqrt(G * k)
    for j, x0 in enumerate(xc):
        # crest at x = -x0 relative to the frame origin: eta = a cos(k (x + x0)) (with the model's
        # pressure decay, if any, the wave's columns of it)
        wave = station_wave_table([a], [w], [k * x0], xs, 0.0, 0.0, [0.0], model.decay)[0]
        K._loads(*kernel_args(model.sec, model.tables), p, wave, s, out, work)
        fx[j] = out[0]
    # F = -f sin(k x0 + e) = -f cos(e) sin(k x0) - f sin(e) cos(k x0)
    sn = 2.0 * np.mean(fx * np.sin(k * xc))
    cs = 2.0 * np.mean(fx * np.cos(k * xc))
    f = float(np.hypot(sn, cs))
    return f, float(np.arctan2(-cs, -sn))


def mean_wave_surge_force(model: SixDof, wavelength: float, height: float, speeds) -> np.ndarray:
    """Mean wave-induced surge force F0 [N] (positive forward) in a regular following wave at each
    ship speed in ``speeds`` [m/s] (module docstring): F0 = k D / w_e from the linear
    6-DOF response X (:func:`.manoeuvring.linear_regular_response`) and the model's linear damping
    and added mass (with a radiation memory, its heave-pitch coefficients at the encounter
    frequency, with the forward-speed terms if the model has them); 0 at the celerity."""
    from stabflow.dynamics.broaching import with_condition
    from stabflow.dynamics.manoeuvring import linear_regular_response

    k = 2 * np.pi / wavelength
    c = np.sqrt(G / k)
    out = np.zeros(len(np.atleast_1d(speeds)))
    for i, u in enumerate(np.atleast_1d(np.asarray(speeds, float))):
        if abs(c - u) < 1e-6 * c:
            continue  # w_e = 0: the motions are quasi-static, nothing is dissipated
        we = k * (c - u)
        B = model.p[K.P_DAMPING:K.P_DAMPING + 36].reshape(6, 6).copy()
        X = linear_regular_response(with_condition(model, 0.0, float(u)), wavelength, 0.5 * height)
        # mean power dissipated, w_e^2 Re(X^H B X) / 2 - w_e^3 Im(X^H A X) / 2 (the second from an
        # added mass that is not symmetric, as the forward-speed terms make it), with the memory's
        # heave-pitch radiation at the encounter frequency (at speed u with its forward-speed terms)
        A = model.p[K.P_ADDED_MASS:K.P_ADDED_MASS + 36].reshape(6, 6).copy()
        if model.memory is not None:  # its A(inf) is in the memory's A(w) below
            A[np.ix_([K.S_Z, K.S_PITCH], [K.S_Z, K.S_PITCH])] = 0.0
        power = 0.5 * we * we * float(np.real(np.conj(X) @ B @ X)) - 0.5 * we**3 * float(np.imag(np.conj(X) @ A @ X))
        if model.memory is not None:
            from stabflow.dynamics.radiation import forward_speed_coefficients, memory_forward_speed

            fwd = memory_forward_speed(model)
            if fwd is not None:
                Ah, Bh = (x[0] for x in forward_speed_coefficients(model.memory, [we], float(u), fwd))
            else:
                Ah, Bh = model.memory.added_mass([we])[0], model.memory.damping([we])[0]
            xh = X[[K.S_Z, K.S_PITCH]]
            power += 0.5 * we * we * float(np.real(np.conj(xh) @ Bh @ xh)) \
                - 0.5 * we**3 * float(np.imag(np.conj(xh) @ Ah @ xh))
        out[i] = k * power / we
    return out


def melnikov_threshold(model: SixDof, wavelength: float, height: float, wave_force: bool = False) -> float:
    """Commanded speed U_cr [m/s] at the heteroclinic bifurcation of the surge equation (module
    docstring): R(U_cr) = mean of R(c + x'_0(x)) over one wavelength; with ``wave_force``, R - F0
    along the orbit (the mean wave-induced surge force of the heave-pitch response, interpolated on
    24 speeds over the orbit's range). Raises ValueError if that mean is not positive (the ship
    surf-rides at any commanded speed)."""
    k = 2 * np.pi / wavelength
    c = np.sqrt(G / k)
    f, _ = surge_force(model, wavelength, height)
    mass = float(model.p[K.P_MASS]) + float(model.m[K6.M_AB])
    amp = 2.0 * np.sqrt(f / (mass * k))

    spline = None
    if wave_force:
        grid = np.linspace(max(c - amp, 0.0), c, 24)
        spline = interpolate.CubicSpline(grid, mean_wave_surge_force(model, wavelength, height, grid))

    def net(x):
        u = c - amp * abs(np.cos(0.5 * k * x))
        return float(resistance(model, u)) - (0.0 if spline is None else float(spline(max(u, grid[0]))))

    mean_r = integrate.quad(net, 0.0, wavelength, limit=200)[0] / wavelength
    if mean_r <= 0.0:
        raise ValueError(f"the mean wave-induced surge force exceeds the resistance along the orbit (mean net "
                         f"resistance {mean_r:.0f} N): surf-riding at any commanded speed")
    return float(optimize.brentq(lambda u: float(resistance(model, u)) - mean_r, 1e-3, c))


def at_commanded_speed(model: SixDof, speed: float) -> SixDof:
    """A copy of the model at the commanded ``speed`` [m/s], its thrust the calm-water resistance there."""
    m = replace(model, speed=float(speed), m=model.m.copy())
    m.m[K6.M_SPEED] = speed
    m.m[K6.M_THRUST] = float(resistance(m, speed))
    return m


def surf_rides(model: SixDof, wavelength: float, height: float, speed: float, *, encounters: float = 40.0,
               dt: float = 0.05) -> bool:
    """True if the 6-DOF model at commanded ``speed`` [m/s] is captured by the regular following
    wave: the wave grows from zero over ``encounters`` encounter periods at the commanded speed (so
    the ship enters it on the periodic surging motion, not inside the surf-riding basin by the
    chance of its starting phase), then stays for as many; captured when over that second part
    the waves overtake the ship by less than half a wavelength."""
    k = 2 * np.pi / wavelength
    w = np.sqrt(G * k)
    c = w / k
    m = at_commanded_speed(model, speed)
    te = wavelength / max(c - speed, 1e-3 * c)
    ramp = encounters * te
    ds = simulate_six_dof(m, (np.array([0.5 * height]), np.array([w]), np.array([0.0])), 2.0 * ramp, dt, ramp_s=ramp)
    if ds.attrs["status"] != K6.OK:
        return False
    t = ds["time"].values
    rel = ds["surge"].values + (speed - c) * t  # G's position relative to the wave
    half = np.searchsorted(t, ramp)
    return bool(rel[-1] - rel[half] > -0.5 * wavelength)


def simulated_threshold(model: SixDof, wavelength: float, height: float, lo: float, hi: float,
                        tol: float = 0.01, **kw) -> float:
    """Bisection on the commanded speed [m/s] between ``lo`` (periodic surging) and ``hi`` (surf-riding
    from every start) to ``tol`` [m/s]."""
    if surf_rides(model, wavelength, height, lo, **kw) or not surf_rides(model, wavelength, height, hi, **kw):
        raise ValueError(f"surf-riding threshold not bracketed by {lo:g} and {hi:g} m/s")
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if surf_rides(model, wavelength, height, mid, **kw):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def following_wave_loads(model: SixDof, vertices, faces, wavelength: float, height: float, speed: float, *,
                         periods: int = 4, ramp_periods: float = 40.0, dt: float = 0.05) -> dict[str, float]:
    """The 6-DOF kernel's FK + HS loads on the heaving, pitching and surging hull in a regular
    following wave against surface-pressure integration on the hull mesh at the same poses.

    The 6-DOF record at the commanded ``speed`` [m/s] grows the wave over ``ramp_periods`` encounter
    periods (as :func:`surf_rides`), then ``periods`` encounter periods are sampled every step; the
    ship must be surging periodically there (the waves overtaking it by about a wavelength each
    encounter period, not captured: ValueError). At each pose the kernel's loads (``_kernels_6dof._wave_loads``, as the
    record's right-hand side) and :class:`stabflow.dynamics.pressure.PressureModel`'s (exact surface,
    decay off as the kernel's eq 9, or on for a model with the pressure-decay term
    (``dphi_dzdt``); the body origin moved to where the pose puts it) are formed.

    Returns the mean and first-harmonic amplitude at the surging motion's encounter frequency
    (``encounter_frequency`` [rad/s], lower than at the commanded speed) of the surge force
    ``fx``, heave force ``fz`` [N] and pitch moment ``my`` [N m] for ``kernel`` and ``pressure``
    (keys ``"{kernel|pressure}_{fx|fz|my}_{mean|h1}"``), the first harmonics' complex difference
    |kernel - pressure| / |pressure| (``"{fx|fz|my}_h1_difference"``, amplitude and phase), and the
    pitch amplitude ``pitch_deg``.
    The mean surge force is the second-order force that, with the resistance, sets the
    surf-riding threshold."""
    from stabflow.dynamics.manoeuvring import line_waves, run_six_dof, wave_line
    from stabflow.dynamics.pressure import PressureModel

    if model.heading_deg != 0.0:
        raise ValueError(f"following_wave_loads: a following-wave model (heading 0), not {model.heading_deg:g} degree")
    k = 2 * np.pi / wavelength
    w = np.sqrt(G * k)
    c = w / k
    a = 0.5 * height
    if not 0.0 <= speed < c:
        raise ValueError(f"speed {speed:g} m/s: periodic surging needs 0 <= U < c = {c:.3f} m/s")
    m = at_commanded_speed(model, speed)
    we = w - k * speed
    te = 2 * np.pi / we
    waves = (np.array([a]), np.array([w]), np.array([0.0]))
    ramp = ramp_periods * te
    # surging slows the waves' passage: room for 3 x the nominal periods, sampled over the last
    # ``periods`` passages of a crest (the motion's own period)
    states, _, status = run_six_dof(m, waves, ramp + 3 * periods * te, dt, ramp_s=ramp)
    if status != K6.OK:
        raise ValueError(f"the following-wave record at {speed:g} m/s did not complete (status {status})")
    t = np.arange(len(states)) * dt
    rel = states[:, K.S_X] + (speed - c) * t  # G's position relative to the wave
    after = np.nonzero((t >= ramp) & (rel >= rel[-1] + periods * wavelength))[0]
    if len(after) == 0:
        raise ValueError(f"at {speed:g} m/s the ship is not surging periodically in the wave (lambda {wavelength:g} m): "
                         f"{(rel[np.searchsorted(t, ramp)] - rel[-1]) / wavelength:.2f} waves passed it in "
                         f"{3 * periods} encounter periods (captured: surf-riding)")
    pick = np.arange(after[-1], len(states) - 1)
    we = 2 * np.pi * periods / (t[pick[-1] + 1] - t[pick[0]])  # the surging motion's encounter frequency
    p = m.p
    xg, zg, rho = float(p[K.P_XG]), float(p[K.P_ZG]), float(p[K.P_RHO])
    pm = PressureModel(vertices, faces, rho, xg, zg, waves, 0.0, speed, decay=m.decay is not None)
    args = kernel_args(m.sec, m.tables)
    nst = len(m.sec.x)
    wave, work, f = np.empty((nst, K6.WAVE_BUFFER)), np.empty((nst, 5)), np.empty(6)
    loads = np.empty((2, len(pick), 3))
    # the sampled steps' wave (one periodic table, its rows on the half-step grid from the first)
    lw = line_waves(m, waves)
    line, xi0, h, wrap = wave_line(m, lw, t[pick[0]], len(pick) - 1, dt, 0.0, 0.0)
    weights = np.ascontiguousarray(lw.decay_weights)
    mm = m.m.copy()
    mm[K6.M_XI0], mm[K6.M_DXI], mm[K6.M_WRAP], mm[K6.M_XI_RATE] = xi0, h, wrap, 0.0
    for j, i in enumerate(pick):
        s = states[i]
        K6._wave_loads(*args, p, mm, line[2 * j], weights, s, f, wave, work)
        loads[0, j] = f[[0, 2, 4]]
        th, ph = s[K.S_PITCH], s[K.S_ROLL]
        # the body origin's horizontal position: G's less R (x_G, 0, z_G)'s (pitch only: no yaw, sway)
        xo = s[K.S_X] + xg - (xg * np.cos(th) + zg * np.sin(th) * np.cos(ph))
        pm.phase = np.array([k * xo])
        loads[1, j] = pm.loads(t[i], K._origin_height(s[K.S_Z], ph, th, xg, zg), ph, th)[[0, 2, 4]]
    rot = np.exp(1j * we * t[pick])
    out = {"pitch_deg": float(np.degrees(0.5 * np.ptp(states[pick, K.S_PITCH]))), "encounter_frequency": float(we)}
    for b_, q in enumerate(("fx", "fz", "my")):
        h1 = [2.0 * np.mean(loads[a_, :, b_] * rot) for a_ in range(2)]
        for a_, src in enumerate(("kernel", "pressure")):
            out[f"{src}_{q}_mean"] = float(np.mean(loads[a_, :, b_]))
            out[f"{src}_{q}_h1"] = float(abs(h1[a_]))
        # amplitude and phase together: a station read at the wrong place along the ship shifts the phase
        out[f"{q}_h1_difference"] = float(abs(h1[0] - h1[1]) / abs(h1[1]))
    return out
