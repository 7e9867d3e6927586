"""6-DOF manoeuvring in waves with course keeping (issue 17, paper 004).

The 3-DOF hybrid model (:mod:`stabflow.dynamics.model`) with surge, sway and yaw set free
(:data:`stabflow.dynamics.rigid_body.SIX_DOF`), the incident wave evaluated at the stations'
instantaneous positions, and the forces a free course needs:

* calm-water resistance R(u) (:mod:`stabflow.dynamics.resistance`, the ship's
  ``manoeuvring.resistance``): the ITTC-57 friction line with a form factor on Kato's wetted
  surface (ITTC roll-damping procedure eq 40), Holtrop & Mennen (1982) with Holtrop (1984), wave
  resistance included, from the hull's own particulars, or a given curve; and a constant thrust
  equal to the resistance at the commanded speed, so that the commanded speed holds in calm water;
* linear hull manoeuvring forces Y = u (Y_v v + Y_r r), N = u (N_v v + N_r r) about midships, from
  Clarke, Gedling & Hine (1983) (:func:`clarke_derivatives`) or slender-body theory on the hull's
  lateral profile (:func:`slender_body_derivatives`), unless given, acting at a height
  ``side_force_height`` above the keel for the roll moment, and the inertia of the horizontal
  added mass of (u, v, r) in body axes: given (e.g. Capytaine's zero-frequency limit,
  :func:`stabflow.dynamics.hydro.manoeuvring_added_mass`) or from Clarke's regression; the
  velocity-dependent ideal-fluid forces (Munk moment) are inside the derivatives;
* cross-flow drag of the hull's strips, Y = -1/2 rho sum T(x) C_D(x) |v + r x| (v + r x) dx (the
  cross-flow principle), with the 2-D section drag C_D against B / 2T from Hoerner's curve
  (:data:`HOERNER_CROSSFLOW`): it bounds drift and yaw rate where the linear derivatives alone
  would let a directionally unstable hull spin;
* foils (rudder, skeg) as lifting surfaces, paper 004 eqs 5-11: effective aspect ratio 2 S / C
  (eq 6, "groundboarded"), lift slope pi A_R / 2 below A_R = 2 (eq 7) and 2 pi A_R / (A_R + 2)
  above (eq 8), stall at 24 degree and trailing-edge stall at 12 degree (paper 004's table after
  eq 9, "Foils");
* the hull's side force and yaw moment and the foils' forces in body axes: from the flow's
  body-axis velocity (heeled by phi, the sway velocity meets the centreplane and the foils at
  v cos(phi)), acting normal to the centreplane, turned into the heading frame with their moments
  about G (``_kernels_6dof._manoeuvring_loads``): a heeled foil's horizontal lift goes as
  cos^2(phi), and its vertical part and the foils' pitch moment are kept. The flow is paper 004's
  eq 1: the ship's whole velocity and rotation (heave and pitch rates too), without the waves'
  particle velocities (as LAMP, paper 004 section 2.2.2), in the axes of the ship at its calm-water
  trim (the derivatives refer to the trimmed ship; the roll is taken about the trimmed horizontal
  axis, which leaves out a yaw rate -phi' sin(theta_0), 1e-3 rad/s on the trawler); the pitch angle
  alone without the heave and pitch rates (a first version) gave the sq6 condition's first 40
  records 11 capsizes, against 1 with the heading-frame loads and 3 with eq 1's whole motion (1
  with the pitch from the baseline instead of the trim);
* the PD autopilot and the rudder servo of paper 004 eqs 30-34: G_a 0.9, G_b 20 s, proportional
  band 5 degree, slew rate 5.5 degree/s (tau = P_B / R_m), maximum 35 degree.

Sign conventions: x forward, y to port, z up; yaw psi positive to port (counter-clockwise seen
from above); rudder angle positive with the trailing edge to starboard, which turns the ship to
starboard (psi decreasing), so that eq 30's delta_c = G_a (psi - psi_d) + G_b psi' corrects.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from stabflow import StabflowError
from stabflow.dynamics import _kernels as K
from stabflow.dynamics import _kernels_6dof as K6
from stabflow.dynamics.model import Coefficients, initial_state, parameters, section_decay
from stabflow.dynamics.resistance import kernel_resistance
from stabflow.dynamics.rigid_body import SIX_DOF
from stabflow.dynamics.roll_damping import NU, friction_radius_area, particulars, section_parameters
from stabflow.dynamics.tables import SectionTables, kernel_args
from stabflow.geometry import Sections
from stabflow.io import annotate
from stabflow.waves.synthesis import LineWaves, one_blas_thread


#: Hoerner's 2-D cross-flow drag coefficient C_D against B / (2 T): the digitised curve of the
#: Marine Systems Simulator (Fossen), HYDRO/Hoerner.m, after Leite, Aranha, Umeda & de Conti (1998),
#: "Current forces in tankers and bifurcation of equilibrium of turret systems", Applied Ocean
#: Research 20, 145-156
HOERNER_CROSSFLOW = np.array([
    [0.0108623, 1.96608], [0.176606, 1.96573], [0.353025, 1.89756], [0.451863, 1.78718],
    [0.472838, 1.58374], [0.492877, 1.27862], [0.493252, 1.21082], [0.558473, 1.08356],
    [0.646401, 0.998631], [0.833589, 0.87959], [0.988002, 0.828415], [1.30807, 0.759941],
    [1.63918, 0.691442], [1.85998, 0.657076], [2.31288, 0.630693], [2.59998, 0.596186],
    [3.00877, 0.586846], [3.45075, 0.585909], [3.7379, 0.559877], [4.00309, 0.559315]])


def crossflow_drag_coefficient(breadth, draft) -> np.ndarray:
    """2-D cross-flow drag coefficient of sections of ``breadth`` and ``draft`` [m] (Hoerner's
    curve, held at its ends)."""
    r = np.asarray(breadth, float) / (2.0 * np.maximum(np.asarray(draft, float), 1e-9))
    return np.interp(r, HOERNER_CROSSFLOW[:, 0], HOERNER_CROSSFLOW[:, 1])


def clarke_derivatives(length: float, breadth: float, draft: float, cb: float) -> dict[str, float]:
    """Linear manoeuvring derivatives in the prime system (forces / (1/2 rho L^2 U^2), moments /
    (1/2 rho L^3 U^2), v' = v / U, r' = r L / U) from the regressions of Clarke, Gedling & Hine
    (1983), "The application of manoeuvring criteria in hull design using linear theory", Trans.
    RINA 125, 45-68, as restated in the Marine Systems Simulator (Fossen), ``clarke83.m``.

    Returns ``yv, yr, nv, nr`` (damping) and ``yvdot, yrdot, nvdot, nrdot`` (added mass, prime
    system with L^3, L^4, L^4, L^5).
    """
    L, B, T = length, breadth, draft
    S = np.pi * (T / L) ** 2
    return {
        # Clarke et al. (1983), rotating-arm and PMM regressions
        "yvdot": -S * (1 + 0.16 * cb * B / T - 5.1 * (B / L) ** 2),
        "yrdot": -S * (0.67 * B / L - 0.0033 * (B / T) ** 2),
        "nvdot": -S * (1.1 * B / L - 0.041 * B / T),
        "nrdot": -S * (1 / 12 + 0.017 * cb * B / T - 0.33 * B / L),
        "yv": -S * (1 + 0.4 * cb * B / T),
        "yr": -S * (-1 / 2 + 2.2 * B / L - 0.08 * B / T),
        "nv": -S * (1 / 2 + 2.4 * T / L),
        "nr": -S * (1 / 4 + 0.039 * B / T - 0.56 * B / L),
    }


def slender_body_derivatives(x, draft, dx, length: float, band: float = 0.01) -> dict[str, float]:
    """Linear manoeuvring derivatives of the hull's own lateral profile by slender-body theory, in
    Clarke's prime system (:func:`clarke_derivatives`), about x = 0.

    Each station of draft T(x) carries the sway added mass of a vertical flat plate reflected in the
    free surface, m(x) = rho pi T^2 / 2 per unit length (a plate of span 2 T in unbounded fluid has
    rho pi T^2; half of it is below the surface). Moving at U with the local lateral velocity
    w = v + x r, a strip of water passing the hull from bow to stern takes the momentum m w, so the
    steady force per unit length is f = U d(m w)/dx. The flow is taken to leave the hull where the
    profile stops deepening: m is replaced by its running maximum from the bow, and the hull ends at
    the trailing edge x_T, the aft face of the aftmost station whose m is within ``band`` of the
    largest (a level keel ends at the stern whatever its last digits); behind it the wake carries
    the shed momentum and the hull takes no force (a rudder or skeg there is a foil). x_T must lie
    aft of midships: a profile whose deepest point is a bow bulb or a sonar dome is refused.
    Integrating,

        Y_v = -U m_T,   Y_r = -U x_T m_T,
        N_v = -U (x_T m_T + int m~ dx),   N_r = -U (x_T^2 m_T + int m~ x dx),

    the integrals over [x_T, bow] as sums over the stations' slabs. For a plate of constant draft T
    over the length L these are the leading terms of Clarke, Gedling & Hine's regressions, -S, S/2,
    -S/2 and -S/4 with S = pi (T / L)^2 (tested); a deadwood or a keel raked aft moves the trailing
    edge's lift aft and makes the hull more stable, which those regressions on L, B, T and C_B cannot
    see. Left out: the beam (flat-plate sections; Clarke's Y'v grows with C_B B / T) and viscous lift
    beyond the cross-flow drag (nonlinear) of :func:`build_six_dof`.

    Parameters
    ----------
    x, dx : array
        Station centres and slab widths [m] (:class:`stabflow.geometry.Sections`).
    draft : array
        Station drafts [m] (0 where the station is out of the water).
    length : float
        Reference length L [m] of the prime system.
    band : float
        Relative tolerance on the largest added mass that still counts as the deepest [-].

    Returns
    -------
    dict
        ``yv, yr, nv, nr`` as :func:`clarke_derivatives`, and the trailing edge ``x_trailing`` [m].
    """
    x = np.asarray(x, float)
    o = np.argsort(x)
    x, w = x[o], np.asarray(dx, float)[o]
    a = 0.5 * np.pi * np.asarray(draft, float)[o] ** 2  # added mass / rho [m^2]
    if not np.any(a > 0.0):
        raise StabflowError("slender-body derivatives: no station has a draft")
    run = np.maximum.accumulate(a[::-1])[::-1]  # running maximum from the bow aft
    it = int(np.flatnonzero(a >= (1.0 - band) * a.max())[0])  # the aftmost deepest station
    xt, mt = float(x[it] - 0.5 * w[it]), float(run[it])        # its aft face: the trailing edge
    if xt > 0.0:
        raise StabflowError(f"slender-body derivatives: the deepest station is forward of midships (x = {x[it]:.2f} m; "
                            "a bulb or a sonar dome deeper than the aft body?), where the flow would leave the hull: "
                            "use hull_derivatives: clarke, or give all four of yv, yr, nv, nr in manoeuvring.derivatives")
    ms, xs, ws = run[it:], x[it:], w[it:]
    L = float(length)
    m0, m1 = float(np.sum(ms * ws)), float(np.sum(ms * xs * ws))
    return {"yv": -mt / (0.5 * L**2), "yr": -xt * mt / (0.5 * L**3),
            "nv": -(xt * mt + m0) / (0.5 * L**3), "nr": -(xt**2 * mt + m1) / (0.5 * L**4), "x_trailing": xt}


#: the sources of the hull derivatives (``Manoeuvring.hull``)
HULL_DERIVATIVES = ("clarke", "slender_body")
#: the linear hull derivatives the kernel uses (prime system, about midships)
LINEAR_DERIVATIVES = ("yv", "yr", "nv", "nr")


def normal_pressure_coefficient(span: float, chord: float) -> float:
    """Kato's coefficient of normal pressure C_N of a flat plate of ``span`` and ``chord`` (paper 004
    eq 14): 1.98 exp(-11 s/C) for s/C < 0.07, 1.98 exp(-11 C/s) for C/s < 0.07, else 1.18."""
    r = span / chord
    if r < 0.07:
        return float(1.98 * np.exp(-11.0 * r))
    if 1.0 / r < 0.07:
        return float(1.98 * np.exp(-11.0 / r))
    return 1.18


def lift_slope(span: float, chord: float) -> float:
    """Lift-curve slope C_La [1/rad] of a foil (paper 004 eqs 6-8): effective aspect ratio
    A_R = 2 S / C (groundboarded), C_La = pi A_R / 2 if A_R < 2 else 2 pi A_R / (A_R + 2)."""
    ar = 2.0 * span / chord  # eq 6
    return np.pi / 2.0 * ar if ar < 2.0 else 2.0 * np.pi / (1.0 + 2.0 / ar)  # eqs 7, 8


@dataclass(frozen=True)
class Foil:
    """A vertical lifting surface: centre ``x`` (from midships, + forward) and ``z`` (above the
    baseline) [m], ``span`` and ``chord`` [m], stall angles [degree] (paper 004: foils 24 and 12),
    ``rudder`` True if it turns with the rudder angle."""

    x: float
    z: float
    span: float
    chord: float
    rudder: bool = False
    stall_deg: float = 24.0
    trail_deg: float = 12.0


@dataclass(frozen=True)
class Autopilot:
    """Steering: paper 004 eqs 30-34 (its values as defaults): gains ``ga`` [-] and ``gb`` [s],
    proportional band and slew rate of the servo [degree, degree/s], maximum rudder angle [degree],
    desired heading [degree]. ``mode`` "autopilot" (eq 30), "fixed" (the servo turns the rudder to
    ``rudder_deg`` and holds it: turning circles) or "zigzag" (``rudder_deg`` to starboard, reversed
    each time the heading deviation reaches ``zigzag_deg``: the 10/10 and 20/20 tests)."""

    ga: float = 0.9
    gb: float = 20.0
    proportional_band_deg: float = 5.0
    slew_rate_deg_s: float = 5.5
    max_deg: float = 35.0
    heading_deg: float = 0.0
    mode: str = "autopilot"
    rudder_deg: float = 0.0
    zigzag_deg: float = 10.0


@dataclass(frozen=True)
class Manoeuvring:
    """The 6-DOF additions for one ship and condition (see the module docstring).

    ``hull`` names where the linear hull derivatives come from: ``"clarke"`` (the regression,
    :func:`clarke_derivatives`) or ``"slender_body"`` (the hull's own lateral profile,
    :func:`slender_body_derivatives`); ``derivatives`` overrides their prime-system values by name;
    ``form_factor`` k of the
    friction-line resistance [-] (0: the friction line alone); ``resistance`` the config's
    ``manoeuvring.resistance`` (its ``method`` and items,
    :func:`stabflow.dynamics.resistance.kernel_resistance`; empty: the friction line);
    ``side_force_height`` [m above the keel] where the
    hull side force acts (None: half the draft, the centre of a rectangular lateral area);
    ``added_mass`` (3, 3) of (surge, sway, yaw) about G in body axes [kg, kg m, kg m^2], or None for
    Clarke's regression (which has no surge term: A11 = 0), whichever ``hull`` derivatives.
    """

    foils: tuple = ()
    autopilot: Autopilot = field(default_factory=Autopilot)
    derivatives: dict = field(default_factory=dict)
    hull: str = "clarke"
    form_factor: float = 0.0
    resistance: dict = field(default_factory=dict)
    side_force_height: float | None = None
    added_mass: np.ndarray | None = None
    #: with a radiation memory: strip theory's forward-speed terms of the heave-pitch radiation
    #: (``_kernels_6dof._memory``; False, the default: the zero-speed coefficients alone, consistent
    #: with an excitation of Froude-Krylov forces without diffraction; see :mod:`.radiation`)
    radiation_forward_speed: bool = False
    #: the hull derivative sets (:func:`hull_derivative_sets`) of a finer lateral profile than the
    #: model's stations (:func:`stabflow.dynamics.broaching.profile_derivative_sets`); None: from
    #: the model's own stations
    hull_sets: dict | None = None


@dataclass(frozen=True)
class SixDof:
    """Kernel inputs of a 6-DOF simulation: sections, tables, ``p`` (N_PARAMETERS,), ``m`` (N_M,),
    ``foils`` (nf, F_N), the rest state ``s0`` (N_STATE6,), the commanded ``speed`` [m/s] and the
    wave heading [degree] relative to the mean course."""

    sec: Sections
    tables: SectionTables | None
    p: np.ndarray
    m: np.ndarray
    foils: np.ndarray
    strips: np.ndarray
    s0: np.ndarray
    speed: float
    heading_deg: float
    length: float
    derivatives: dict
    #: the heave-pitch radiation memory (:class:`stabflow.dynamics.radiation.Memory`), None for the
    #: constant coefficients
    memory: object = None
    #: the sections' pressure decay (:class:`stabflow.dynamics.model.SectionDecay`) for the
    #: d2phi/dzdt term, None without it (paper 000's kernel)
    decay: object = None
    #: how the calm-water resistance was made (:func:`stabflow.dynamics.resistance.kernel_resistance`)
    resistance: dict = field(default_factory=dict)

    def continuous_index(self) -> np.ndarray:
        """Indices of those states in the state vector (the roll amplitude, rudder and helm left out)."""
        return np.r_[0:12, K6.S_MEMORY:self.s0.size]


def build_six_dof(sec: Sections, st: xr.Dataset, co: Coefficients, rho: float, heading_deg: float, speed: float,
                  man: Manoeuvring, tables: SectionTables | None = None, memory=None,
                  waterline: str = "planar", dphi_dzdt: bool = False) -> SixDof:
    """Assemble the 6-DOF kernel inputs for a ship (sections, statics, 3-DOF coefficients ``co``),
    water density ``rho`` [kg/m^3], wave heading [degree] relative to the course, commanded
    ``speed`` [m/s] and the manoeuvring description ``man``. With ``memory``
    (:class:`stabflow.dynamics.radiation.Memory`) heave and pitch radiate through it: their added mass
    is its A(inf) and their constant damping is replaced by its states (Cummins' equation).
    ``waterline`` and ``dphi_dzdt`` (the incident wave's pressure decaying with depth in the
    vertical force) as :func:`stabflow.dynamics.simulate` (``"curved"``: exact clipping of the
    sections, the tables unused in the waves). The hull derivatives are ``man.hull_sets``'s (the
    finely cut profile of :func:`stabflow.dynamics.broaching.manoeuvring_from_ship`); without
    them, those of ``sec``'s own stations, whose slender-body trailing edge moves with the station
    count (a slab's aft face)."""
    from stabflow.dynamics.model import _check_waterline

    curved = _check_waterline(waterline)
    lcg, kg = float(st["lcg"]), float(st["kg"])
    sp = section_parameters(sec, st)
    hp = particulars(sp)
    L, B, T = hp.length, hp.breadth, hp.draft
    if man.hull not in HULL_DERIVATIVES:
        raise StabflowError(f"manoeuvring: hull derivatives {man.hull!r} are not one of {list(HULL_DERIVATIVES)}")
    sets = man.hull_sets if man.hull_sets is not None else hull_derivative_sets(sp)
    der = sets[man.hull]
    if isinstance(der, str):
        if not set(LINEAR_DERIVATIVES) <= set(man.derivatives):
            raise StabflowError(f"manoeuvring: {der}")
        der = {}
    der = der | dict(man.derivatives)
    q = 0.5 * rho
    p = parameters(co, rho, lcg, kg, heading_deg, free=SIX_DOF)
    rest = initial_state(sec, st)
    m = np.zeros(K6.N_M)
    m[K6.M_CURVED] = 1.0 if curved else 0.0
    m[K6.M_KEEL_LINE] = 1.0
    # the calm waterline's height above the keel at G's station, body axes (``_station_wave``)
    h0 = K._origin_height(rest[K.S_Z], 0.0, rest[K.S_PITCH], lcg, kg)
    m[K6.M_WL_HEIGHT] = (lcg * np.sin(rest[K.S_PITCH]) - h0) / np.cos(rest[K.S_PITCH])
    m[K6.M_TRIM] = rest[K.S_PITCH]
    decay = section_decay(sec, h0, float(rest[K.S_PITCH])) if dphi_dzdt else None
    if memory is not None:
        from stabflow.dynamics.radiation import memory_parameters, transom

        hp_ = (K.S_Z, K.S_PITCH)
        for a, i in enumerate(hp_):
            for b, j in enumerate(hp_):
                p[K.P_ADDED_MASS + 6 * i + j] = memory.added_mass_inf[a, b]
                p[K.P_DAMPING + 6 * i + j] = 0.0
        m = np.concatenate([m, memory_parameters(memory, man.radiation_forward_speed, float(rest[K.S_PITCH]),
                                                 transom(sp, lcg, rho))])
    m[K6.M_SPEED] = speed
    _set_hull_derivatives(m, der, rho, L)
    zh = 0.5 * T if man.side_force_height is None else float(man.side_force_height)
    m[K6.M_ZH] = zh - kg
    s_w, _ = friction_radius_area(L, B, T, hp.cb, hp.og)  # ITTC eq 40
    m[K6.M_RES], m[K6.M_RR_DU], table, res_attrs = kernel_resistance(man.resistance, sec, st, rho, s_w,
                                                                     man.form_factor, L)
    m[K6.M_RR:K6.M_RR + K6.N_RR] = table
    # the friction line alone (Kato's surface, the form factor), for comparison in the report
    res_attrs["resistance_friction_line_factor"] = q * s_w * (1.0 + man.form_factor)
    m[K6.M_LNU] = L / NU
    m[K6.M_THRUST] = K6._resistance(m, float(speed))
    ap = man.autopilot
    m[K6.M_GA] = ap.ga
    m[K6.M_GB] = ap.gb
    m[K6.M_TAU] = ap.proportional_band_deg / ap.slew_rate_deg_s  # eq 31: tau = P_B / R_m
    m[K6.M_SLEW] = np.radians(ap.slew_rate_deg_s)
    m[K6.M_MAX] = np.radians(ap.max_deg)
    m[K6.M_PSID] = np.radians(ap.heading_deg)
    modes = {"fixed": K6.STEER_FIXED, "autopilot": K6.STEER_AUTOPILOT, "zigzag": K6.STEER_ZIGZAG}
    if ap.mode not in modes:
        raise StabflowError(f"manoeuvring: autopilot.mode {ap.mode!r} is not one of {sorted(modes)}")
    m[K6.M_STEERING] = modes[ap.mode]
    m[K6.M_HELM] = np.radians(ap.rudder_deg)
    m[K6.M_ZIGZAG] = np.radians(ap.zigzag_deg)
    if man.added_mass is None:
        # body-axis added mass of (u, v, r): -(prime added-mass derivatives) 1/2 rho L^n
        cl = sets["clarke"]
        ab = np.zeros((3, 3))
        ab[1, 1] = -q * L**3 * cl["yvdot"]
        ab[1, 2] = -q * L**4 * cl["yrdot"]
        ab[2, 1] = -q * L**4 * cl["nvdot"]
        ab[2, 2] = -q * L**5 * cl["nrdot"]
        # the derivatives are about midships: velocities there are (u, v - x_G r, r)
        H = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, -lcg], [0.0, 0.0, 1.0]])
        ab = H.T @ ab @ H
        src = (f"Clarke et al. (1983) regression at B/L {B / L:.3f}, B/T {B / T:.2f}, C_B {hp.cb:.3f}: give the added "
               "mass (e.g. Capytaine's zero-frequency limit, stabflow.dynamics.hydro.manoeuvring_added_mass)")
    else:
        ab = np.asarray(man.added_mass, float).reshape(3, 3)
        src = "the given added mass"
    # the horizontal inertia (rigid body about G plus added) must be positive definite
    rigid = np.diag([co.mass, co.mass, co.i66])
    total = rigid + 0.5 * (ab + ab.T)
    if np.min(np.linalg.eigvalsh(total)) <= 0.0:
        raise StabflowError(f"manoeuvring: the surge-sway-yaw inertia (rigid body + added mass) is not positive "
                            f"definite with {src}")
    m[K6.M_AB:K6.M_AB + 9] = ab.ravel()
    foils = np.zeros((len(man.foils), K6.F_N))
    for j, f in enumerate(man.foils):
        foils[j] = (f.x - lcg, f.z - kg, f.span * f.chord, lift_slope(f.span, f.chord), np.radians(f.stall_deg),
                    np.radians(f.trail_deg), 1.0 if f.rudder else 0.0, 2.0 * f.span / f.chord,
                    normal_pressure_coefficient(f.span, f.chord))
    ok = sp["valid"].values
    cd = crossflow_drag_coefficient(sp["breadth"].values, sp["draft"].values)
    strips = np.column_stack([sp["x"].values[ok] - lcg, q * (sp["draft"].values * cd * sp["dx"].values)[ok]])
    s0 = np.zeros(K6.N_STATE6 + (0 if memory is None else memory.n_states))
    s0[:K.N_STATE] = rest
    s0[K6.S_HELM] = 1.0
    return SixDof(sec, tables, p, m, foils, strips, s0, float(speed), float(heading_deg), float(L), der, memory,
                  decay, res_attrs)


def hull_derivative_sets(sp: xr.Dataset) -> dict[str, dict | str]:
    """Both sets of prime-system hull derivatives (:data:`HULL_DERIVATIVES`) of a hull from its
    section parameters (:func:`stabflow.dynamics.roll_damping.section_parameters`); a set that
    cannot be had for this hull is the reason why (a string)."""
    hp = particulars(sp)
    out = {"clarke": clarke_derivatives(hp.length, hp.breadth, hp.draft, hp.cb)}
    try:
        out["slender_body"] = slender_body_derivatives(sp["x"].values, np.where(sp["valid"].values, sp["draft"].values, 0.0),
                                                       sp["dx"].values, hp.length)
    except StabflowError as e:
        out["slender_body"] = str(e)
    return out


def _set_hull_derivatives(m: np.ndarray, der: dict, rho: float, length: float) -> None:
    """Write the dimensional hull derivatives per unit surge velocity (prime values times
    1/2 rho L^n) into the kernel's ``m``."""
    q, L = 0.5 * rho, length
    m[K6.M_YV] = q * L**2 * der["yv"]
    m[K6.M_YR] = q * L**3 * der["yr"]
    m[K6.M_NV] = q * L**3 * der["nv"]
    m[K6.M_NR] = q * L**4 * der["nr"]


def with_hull_derivatives(model: SixDof, der: dict) -> SixDof:
    """The ``model`` with other linear hull derivatives (prime system, keys ``yv, yr, nv, nr``); its
    added mass is kept."""
    from dataclasses import replace

    m = model.m.copy()
    _set_hull_derivatives(m, der, float(model.p[K.P_RHO]), model.length)
    return replace(model, m=m, derivatives={k: der[k] for k in LINEAR_DERIVATIVES})


def line_waves(model: SixDof, waves) -> LineWaves:
    """:class:`~stabflow.waves.synthesis.LineWaves` of the components ``waves`` (amp, omega, phase)
    for the model's heading, speed and pressure decay (its tables then carry the d2phi/dzdt term
    and ``decay_weights`` the stations' weights of it for ``_kernels_6dof._simulate6``)."""
    return LineWaves(*waves, model.heading_deg, model.speed, decay=model.decay)


def wave_line(model: SixDof, waves, t0: float, nsteps: int, dt: float, centre: float, reach: float,
              points_per_wavelength: float = 8.0, dtype=np.float64, drift: float = 0.0):
    """Line table (2 nsteps + 1, npoints, 3 + 4 r) of (eta, S, dS/dxi[, the pressure-decay terms'
    groups of four]) from time ``t0`` [s] on the
    half-step grid, its first point and spacing (xi0, dxi) [m], and the number of intervals of a
    periodic table (0: not periodic). ``waves``: (amp, omega, phase) of the components, or a
    :class:`~stabflow.waves.synthesis.LineWaves` of them for the model's heading and speed (a
    record's chunks; :func:`line_waves`, whose ``decay_weights`` go with the table).

    The points cover ``centre`` +- ``reach`` [m] of the propagation coordinate at ``t0`` and move
    along it at ``drift`` [m/s] (the kernel's ``M_XI_RATE``; not for the periodic tables), spaced at the
    shortest component's wavelength / ``points_per_wavelength`` (cubic Hermite error about
    (k h)^4 / 384, 0.1 % at 8 points). A single regular wave is tabulated over one wavelength at 32
    points and calm water as zeros, both read periodically (any drift)."""
    lw = waves if isinstance(waves, LineWaves) else line_waves(model, waves)
    t_half = t0 + np.arange(2 * nsteps + 1) * 0.5 * dt
    if len(lw.amp) == 0:
        return np.zeros((len(t_half), 2, 3)), 0.0, 1.0, 1
    if len(lw.amp) == 1:
        lam = 2 * np.pi * float(model.p[K.P_G]) / float(lw.omega[0]) ** 2
        xi = np.arange(33) * lam / 32
        tab = lw.table(xi, t_half)
        return np.ascontiguousarray(tab), 0.0, float(xi[1]), 32
    kmax = float(np.max(lw.omega)) ** 2 / float(model.p[K.P_G])
    h = 2 * np.pi / kmax / points_per_wavelength
    n = int(np.ceil(2 * reach / h)) + 1
    xi = centre - reach + h * np.arange(n)
    tab = lw.table(xi, t_half, dtype, drift, uniform=True, spaced=True, spacing=h)
    return np.ascontiguousarray(tab), float(xi[0]), float(h), 0


def simulate_six_dof(model: SixDof, waves, duration: float, dt: float, *, phi_cap_deg: float = 90.0, s0=None,
                     points_per_wavelength: float = 8.0, ramp_s: float = 0.0, chunk_s: float = 10.0,
                     dtype=np.float32) -> xr.Dataset:
    """Simulate one 6-DOF record from the calm-water rest state (or ``s0``).

    Parameters
    ----------
    waves : tuple of arrays
        (amp [m], omega [rad/s], phase [rad]) of the wave components (empty: calm water).
    duration, dt : float
        Record length and RK4 step [s].
    phi_cap_deg : float
        Roll angle that ends the record as a capsize [degree].
    ramp_s : float
        The wave grows from zero over this time [s] (smoothstep), so that the ship enters it on the
        motion that continues the calm-water one (0: the full wave from the start).
    chunk_s : float
        Irregular waves are tabulated in chunks of this length [s] on a line of points that move
        with G's drift along the waves at its rate at the chunk's start, covering the hull,
        ``DRIFT_ALLOWANCE`` (0.5 m/s) of change of that rate and ``DRIFT_MARGIN`` (2 m) either way;
        a ship that leaves its table continues from its last step inside on a new chunk.
    dtype : numpy dtype
        Of the irregular-wave table (float32 halves its cost, as the 3-DOF ensembles' tables).

    Returns
    -------
    xarray.Dataset along ``time`` [s]: position of G in the frame moving with the commanded speed
    (``surge``, ``sway`` [m]), ``heave`` of G [m], ``roll``, ``pitch``, ``yaw`` and ``rudder``
    [degree], body surge and sway velocities ``u``, ``v`` [m/s], yaw rate [degree/s]; attributes
    ``status`` (0 ok, 1 capsized).
    """
    states, _, status = run_six_dof(model, waves, duration, dt, phi_cap_deg=phi_cap_deg, s0=s0,
                                    points_per_wavelength=points_per_wavelength, ramp_s=ramp_s, chunk_s=chunk_s,
                                    dtype=dtype)
    return six_dof_dataset(model, states, dt, status)


#: the largest |l| dt of a radiation memory pole l [-]: RK4's stability limit on the real axis is 2.785
#: (on the imaginary axis 2.83); beyond it the memory states would grow or lose their accuracy
MEMORY_STEP_LIMIT = 2.5


def _check_memory(model: SixDof, dt: float) -> None:
    """Refuse a record whose state vector and manoeuvring vector disagree on the memory states, or
    whose step is too long for the fastest memory pole (the kernel checks neither)."""
    n = int(model.m[K6.M_MEMORY]) if model.m.size > K6.M_MEMORY else 0
    if model.s0.size != K6.N_STATE6 + 4 * n:
        raise StabflowError(f"6-DOF model: {model.s0.size} states for {n} radiation memory poles "
                            f"(expected {K6.N_STATE6 + 4 * n})")
    if model.memory is not None:
        fast = float(np.max(np.abs(model.memory.poles)))
        if fast * dt > MEMORY_STEP_LIMIT:
            raise StabflowError(f"6-DOF model: step {dt:g} s too long for the heave-pitch memory model (its fastest "
                                f"pole |l| = {fast:.3g} 1/s needs dt <= {MEMORY_STEP_LIMIT / fast:.3g} s)")


#: allowance for the change of the ship's drift rate along the waves over a chunk [m/s] and a fixed
#: margin [m]: the wave line table covers the hull plus DRIFT_ALLOWANCE x the chunk's length plus
#: DRIFT_MARGIN either way around the drift at the chunk's starting rate; a ship that leaves it
#: continues from its last step inside on a new table centred on it (``run_six_dof``)
DRIFT_ALLOWANCE = 0.5
DRIFT_MARGIN = 2.0


def run_six_dof(model: SixDof, waves, duration: float, dt: float, *, phi_cap_deg: float = 90.0, s0=None,
                points_per_wavelength: float = 8.0, ramp_s: float = 0.0, chunk_s: float = 10.0, dtype=np.float32,
                t0: float = 0.0):
    """States (n + 1, state size: N_STATE6 and the memory states) of one 6-DOF record, the last step
    done n and the status (0 ok, 1 capsized); the arguments as :func:`simulate_six_dof`, the record
    starting at time ``t0`` [s] of the waves (a restart from a state inside a record)."""
    _check_memory(model, dt)
    nsteps = int(round(duration / dt))
    out = np.empty((nsteps + 1, model.s0.size))
    out[0] = model.s0 if s0 is None else np.asarray(s0, float)
    per = max(1, int(round(chunk_s / dt)))
    xg = float(model.p[K.P_XG])
    hull = float(np.max(np.abs(model.sec.x - xg)))
    cb, sb = np.cos(np.radians(model.heading_deg)), np.sin(np.radians(model.heading_deg))
    args = kernel_args(model.sec, model.tables)
    lw = line_waves(model, waves)
    weights = np.ascontiguousarray(lw.decay_weights)
    n0, status = 0, K6.OK
    with one_blas_thread():  # held for the record: the chunks' tables then skip its setting
        while n0 < nsteps and status == K6.OK:
            n1 = min(nsteps, n0 + per)
            s = out[n0]
            # the line table follows G's drift along xi in the moving frame at its present rate; the
            # points cover the hull plus an allowance for the change of that rate over the chunk
            span = (n1 - n0) * dt
            rate = s[K.S_RATE + K.S_X] * cb + s[K.S_RATE + K.S_Y] * sb
            centre = (s[K.S_X] + xg) * cb + s[K.S_Y] * sb
            reach = hull + DRIFT_ALLOWANCE * span + DRIFT_MARGIN
            while True:
                ltab, xi0, h, wrap = wave_line(model, lw, t0 + n0 * dt, n1 - n0, dt, centre, reach,
                                               points_per_wavelength, dtype, drift=rate)
                if ramp_s > 0:
                    r = np.clip((t0 + n0 * dt + np.arange(len(ltab)) * 0.5 * dt) / ramp_s, 0.0, 1.0)
                    ltab *= (r * r * (3.0 - 2.0 * r))[:, None, None]
                m = model.m.copy()
                m[K6.M_XI0], m[K6.M_DXI], m[K6.M_WRAP] = xi0, h, wrap
                m[K6.M_XI_RATE] = 0.0 if wrap else rate
                done, status = K6._simulate6(*args, model.p, m, model.foils, model.strips, ltab, weights, dt, n1 - n0, s,
                                             np.radians(phi_cap_deg), out[n0:n1 + 1])
                if status != K6.LEFT_TABLE:
                    break
                # a station left the table in the last step done: the steps before it saw the wave
                # everywhere, so the record continues from the last of them on a new table around the
                # ship (leaving in the first step: the same chunk on a table twice as wide)
                status = K6.OK
                done -= 1
                if done > 0:
                    break
                reach *= 2.0
            n0 += done
    return out[:n0 + 1], n0, status


def six_dof_dataset(model: SixDof, states: np.ndarray, dt: float, status: int) -> xr.Dataset:
    """Time histories of a 6-DOF record (see :func:`simulate_six_dof`)."""
    n = len(states)
    t = np.arange(n) * dt
    r = K.S_RATE
    psi = states[:, K.S_YAW]
    xd = model.speed + states[:, r + K.S_X]
    yd = states[:, r + K.S_Y]
    th0 = model.s0[K.S_PITCH]
    ds = xr.Dataset(
        {
            "surge": ("time", states[:, K.S_X]), "sway": ("time", states[:, K.S_Y]),
            "heave": ("time", states[:, K.S_Z] - model.s0[K.S_Z]),
            "roll": ("time", np.degrees(states[:, K.S_ROLL])),
            "pitch": ("time", np.degrees(states[:, K.S_PITCH] - th0)),
            "yaw": ("time", np.degrees(psi)), "rudder": ("time", np.degrees(states[:, K6.S_RUDDER])),
            "u": ("time", np.cos(psi) * xd + np.sin(psi) * yd), "v": ("time", -np.sin(psi) * xd + np.cos(psi) * yd),
            "yaw_rate": ("time", np.degrees(states[:, r + K.S_YAW])),
        },
        coords={"time": t},
    )
    ds.attrs.update(status=int(status), end_time=float(t[-1]), dt=dt, speed=model.speed,
                    heading_deg=model.heading_deg, course_deg=float(np.degrees(model.m[K6.M_PSID])),
                    max_rudder_deg=float(np.degrees(model.m[K6.M_MAX])))
    return annotate(ds)


def _linear_system(model: SixDof, eps: float = 1e-6):
    """(A (n, n), B (n,), rhs) of the 6-DOF right-hand side about the calm-water straight run in its
    n continuous states (q, q' and the radiation memory, :meth:`SixDof.continuous_index`): central
    differences in them and the rudder angle; ``rhs(s, delta, line)`` evaluates it."""
    args = kernel_args(model.sec, model.tables)
    m = model.m.copy()
    m[K6.M_XI0], m[K6.M_DXI], m[K6.M_WRAP] = 0.0, 1.0, 1.0
    nst = len(model.sec.x)
    # the foils' lift branches from their angles of attack (-1), as the kernel's modes at a step's start
    scratch = (np.zeros(6), np.zeros((nst, K6.WAVE_BUFFER)), np.zeros((nst, 5)), np.zeros((6, 6)),
               np.zeros(6),
               np.full(len(model.foils) + 2, -1, np.int64))

    idx = model.continuous_index()

    def rhs(s, delta, line=np.zeros((2, 3)), mm=m, decay=np.zeros((nst, 0))):
        ds = np.zeros(model.s0.size)
        K6._rhs6(*args, model.p, mm, model.foils, model.strips, line, decay, s, delta, ds, *scratch)
        return ds[idx]

    s0 = model.s0
    A = np.zeros((len(idx), len(idx)))
    for c, j in enumerate(idx):
        sp, sm = s0.copy(), s0.copy()
        sp[j] += eps
        sm[j] -= eps
        A[:, c] = (rhs(sp, 0.0) - rhs(sm, 0.0)) / (2 * eps)
    B = (rhs(s0, eps) - rhs(s0, -eps)) / (2 * eps)
    return A, B, rhs


def sway_yaw_eigenvalues(model: SixDof) -> np.ndarray:
    """The two eigenvalues [1/s] of the open-loop sway-yaw motion (rudder fixed) about the calm-water
    straight run: the linear system in the sway velocity y' across the mean course, the heading psi
    and the yaw rate r, rewritten in the body sway velocity v = y' - U psi (the loads depend on psi only
    through v), which removes the neutral mode of a course change. A positive real part is a
    directionally unstable hull."""
    A, _, _ = _linear_system(model)
    i = [K.S_RATE + K.S_Y, K.S_YAW, K.S_RATE + K.S_YAW]
    a = A[np.ix_(i, i)]
    U = model.speed
    return np.linalg.eigvals(np.array([[a[0, 0], a[0, 2] - U], [a[2, 0], a[2, 2]]]))


def _closed_loop(model: SixDof, A, B) -> np.ndarray:
    """The linear state matrix (n + 1, n + 1) of the continuous states (q, q', memory) and delta with
    the autopilot (eq 30) and the servo (eq 31) as a continuous lag."""
    ga, gb, tau = model.m[K6.M_GA], model.m[K6.M_GB], model.m[K6.M_TAU]
    n = A.shape[0]
    M = np.zeros((n + 1, n + 1))
    M[:n, :n] = A
    M[:n, n] = B
    M[n, K.S_YAW] = ga / tau
    M[n, K.S_RATE + K.S_YAW] = gb / tau
    M[n, n] = -1.0 / tau
    return M


def linearised_course_change(model: SixDof, step_deg: float, duration: float):
    """Heading response [degree] to a course change of ``step_deg`` in calm water by the linear theory of
    the same equations: the 6-DOF right-hand side differentiated about the straight run (central
    differences in q, q' and the rudder angle), closed by the autopilot of paper 004 eq 30 with the
    servo of eq 31 as a continuous first-order lag (no slew or angle limit). Returns (t [s], yaw [degree])."""
    from scipy.integrate import solve_ivp

    A, B, _ = _linear_system(model)
    M = _closed_loop(model, A, B)
    n = M.shape[0]
    c = np.zeros(n)
    c[-1] = -model.m[K6.M_GA] * np.radians(step_deg) / model.m[K6.M_TAU]
    t = np.linspace(0.0, duration, int(duration / 0.05) + 1)
    sol = solve_ivp(lambda _, x: M @ x + c, (0.0, duration), np.zeros(n), t_eval=t, rtol=1e-9, atol=1e-12)
    return sol.t, np.degrees(sol.y[K.S_YAW])


def linear_regular_response(model: SixDof, wavelength: float, amplitude: float = 1.0) -> np.ndarray:
    """Complex amplitudes (6,) of (surge, sway, heave [m], roll, pitch, yaw [rad]) of the steady state in
    a regular wave of ``wavelength`` [m] and ``amplitude`` [m], autopilot on, by the linear frequency-
    domain solution of the same equations: (i w_e - M) X = F with M the closed loop (with the
    radiation memory states when the model has them) and F
    the wave forcing per unit amplitude (the right-hand side's derivative in the wave amplitude at
    two phases), so that x(t) = Re[X exp(i w_e t)] for the wave a cos(k (xi - xi_G) - w_e t) (its
    crest at G's station at t = 0)."""
    A, B, rhs = _linear_system(model)
    M = _closed_loop(model, A, B)
    k = 2 * np.pi / wavelength
    w = np.sqrt(float(model.p[K.P_G]) * k)
    we = w - k * model.speed * np.cos(np.radians(model.heading_deg))
    xi_g = float(model.p[K.P_XG]) * np.cos(np.radians(model.heading_deg))
    eps = 1e-3
    f = []
    for t in (0.0, 0.5 * np.pi / we):
        lines = []
        for a in (eps, -eps):
            lw = line_waves(model, (np.array([a]), np.array([w]), np.array([-k * xi_g])))
            tab, _, _, _ = wave_line(model, lw, t, 0, 1.0, 0.0, 0.0)
            lines.append((np.ascontiguousarray(tab[0]), np.ascontiguousarray(lw.decay_weights)))
        mm = model.m.copy()
        mm[K6.M_XI0], mm[K6.M_DXI], mm[K6.M_WRAP] = 0.0, wavelength / 32, 32
        f.append((rhs(model.s0, 0.0, lines[0][0], mm, lines[0][1])
                  - rhs(model.s0, 0.0, lines[1][0], mm, lines[1][1])) / (2 * eps))
    # forcing f_c cos(w_e t) + f_s sin(w_e t) = Re[(f_c - i f_s) exp(i w_e t)]
    n = M.shape[0]
    F = np.zeros(n, complex)
    F[:n - 1] = f[0] - 1j * f[1]
    X = np.linalg.solve(1j * we * np.eye(n) - M, F * amplitude)
    return X[:6]


def first_harmonic(ds: xr.Dataset, omega: float, start: float) -> dict:
    """Amplitudes of the first harmonic at ``omega`` [rad/s] of each motion from ``start`` [s] on
    (least squares with a mean and a linear trend): surge, sway, heave [m], roll, pitch, yaw [degree]."""
    t = ds["time"].values
    sel = t >= start
    tt = t[sel]
    G_ = np.column_stack([np.ones_like(tt), tt - tt.mean(), np.cos(omega * tt), np.sin(omega * tt)])
    out = {}
    for v in ("surge", "sway", "heave", "roll", "pitch", "yaw"):
        c, *_ = np.linalg.lstsq(G_, ds[v].values[sel], rcond=None)
        out[v] = float(np.hypot(c[2], c[3]))
    return out
