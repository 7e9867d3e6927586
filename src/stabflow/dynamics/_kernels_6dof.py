"""Numba kernels (private): 6-DOF manoeuvring in waves (issue 17, paper 004).

The rigid-body equations about G and the FK + HS loads are those of :mod:`._kernels`; this module
adds what a free course needs:

* the incident wave at the stations' *instantaneous* positions: long-crested waves depend on the
  horizontal position only through xi = X cos(beta) + Y sin(beta), so one table on a line of xi
  points (``waves.synthesis.line_wave_table``: eta, S, dS/dxi on the half-step grid) is
  interpolated at each station by cubic Hermite polynomials (eta with its slope S, S with dS/dxi);
  the wave heading relative to the ship is beta - psi;
* calm-water resistance and a constant thrust, linear hull manoeuvring forces, foils (rudder,
  skeg) as lifting surfaces with their eddy-making normal force (paper 004 eqs 1-16), the inertia
  of the horizontal added mass in body axes, and the PD autopilot with the first-order rudder servo (paper 004 eqs 30-34);
* optionally, heave and pitch radiation with memory (Cummins' equation as states,
  :mod:`stabflow.dynamics.radiation`): the added mass of ``p`` is then A(inf) in heave and pitch, their
  constant damping zero, and the convolution a tail of ``m`` with states after the rudder's.

Parameters: ``p`` as in :mod:`._kernels` (its cos/sin beta are the wave heading relative to the
mean course), ``m`` (``M_*`` positions below), ``foils`` (nf, F_N) rows and the cross-flow drag
``strips`` (nst, 2).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from stabflow.waves._kernels import _crossbeam_node
from stabflow.waves.synthesis import DECAY_BLOCKS
from stabflow.dynamics._kernels import (DECAY_COLUMNS, N_STATE, P_ADDED_MASS, P_COS_BETA, P_G, P_RHO, P_SIN_BETA,
                                        P_XG, P_ZG, S_PITCH, S_RATE, S_ROLL, S_X, S_Y, S_YAW, S_Z, _fkhs,
                                        _generalized_system, _origin_height, _rotate, _solve_free, _update_amplitude)

#: columns of the stations' wave buffer (``_station_wave``): ``_kernels``'s layouts (at most
#: DECAY_COLUMNS + 1) and the stations' coordinate in the line table
WAVE_BUFFER = DECAY_COLUMNS + 2
U_COLUMN = DECAY_COLUMNS + 1

# manoeuvring parameter vector ``m``
M_SPEED = 0        # commanded speed U [m/s]: the frame of q moves with U along the mean course
M_XI0 = 1          # first point of the wave line table [m]
M_DXI = 2          # spacing of the wave line table [m]
M_YV = 3           # hull sway force per (u v) [kg/m]: Y = u (Yv v + Yr r)
M_YR = 4           # [kg]
M_NV = 5           # hull yaw moment about midships per (u v) [kg]: N = u (Nv v + Nr r)
M_NR = 6           # [kg m]
M_ZH = 7           # height of the hull side force above G [m] (negative: below G)
M_RES = 8          # 1/2 rho S_w (1 + k) [kg/m]: resistance = M_RES C_F(Re) u |u|
M_LNU = 9          # L / nu [s/m]: Re = |u| L / nu
M_THRUST = 10      # constant thrust [N] (the calm-water resistance at U)
M_GA = 11          # autopilot proportional gain [-] (paper 004 eq 30)
M_GB = 12          # autopilot derivative gain [s]
M_TAU = 13         # servo time constant P_B / R_m [s] (eq 31)
M_SLEW = 14        # slew rate R_m [rad/s] (eq 33)
M_MAX = 15         # maximum rudder angle A_m [rad] (eq 34)
M_PSID = 16        # desired heading [rad]
M_STEERING = 17    # STEER_FIXED, STEER_AUTOPILOT or STEER_ZIGZAG
M_HELM = 18        # commanded rudder angle of the fixed and zig-zag modes [rad]
M_ZIGZAG = 19      # heading deviation that reverses the zig-zag helm [rad]
M_WRAP = 20        # > 0: the line table is periodic with this many intervals (one regular wave)
M_AB = 21          # 3 x 3 added mass of (u, v, r) in body axes, row-major [kg, kg m, kg m^2]
M_XI_RATE = 30     # the line table's points move along xi at this rate [m/s] (a table in the frame of the ship's drift)
M_XI_TIME = 31     # time since the line table's first row [s] (set by the RK4 stage by stage)
M_CURVED = 32      # 1: the curved waterline across the sections (``_kernels._curved_sections``), 0: planar
M_KEEL_LINE = 33   # 1: the stations where the rolled, pitched and yawed hull puts them (``_station_wave``)
#                    and the tilted sections' horizontal loads (``_tilt_loads``); 0: the 3-DOF model's
#                    placement, on G's axis (the constrained-case comparison)
M_WL_HEIGHT = 34   # calm-water waterline height above the body origin at G's station [m] (``_station_wave``)
M_TRIM = 35        # calm-water trim theta_0 [rad]: the manoeuvring loads' attitude is the pitch from it
M_RR_DU = 36       # spacing of the resistance table [m/s] (0: no table, the friction line alone)
M_RR = 37          # the resistance beyond the friction line at u = 0, du, 2 du, ... [N] (``_resistance``)
N_RR = 121         # its points (stabflow.dynamics.resistance.TABLE_POINTS reads it)
N_M = M_RR + N_RR
# optional tail of ``m`` (longer than N_M): the heave-pitch radiation memory of
# :mod:`stabflow.dynamics.radiation` (``memory_parameters``): m[M_MEMORY] = number of poles n, then
# the poles (re, im) and the residues (re, im) in (pole, i, j) order, then the forward-speed flag
# (1: strip theory's speed terms, ``_memory``), the calm-water trim theta_0 [rad], the transom's
# position x_T from G [m] and its sectional heave added mass a_T [kg/m]; its states follow S_HELM
M_MEMORY = N_M

# foil rows: position from G (x forward, z up) [m], area S C [m^2], lift slope [1/rad], stall and
# trailing-edge stall angles [rad] (paper 004 eq 9), 1 for the rudder (turns with delta), effective
# aspect ratio 2 S / C (eq 6), coefficient of normal pressure C_N (eq 14)
F_X = 0
F_Z = 1
F_AREA = 2
F_CLA = 3
F_STALL = 4
F_TRAIL = 5
F_RUDDER = 6
F_AR = 7
F_CN = 8
F_N = 9

# steering modes: the servo follows a constant command, the PD autopilot, or a zig-zag manoeuvre
STEER_FIXED = 0.0
STEER_AUTOPILOT = 1.0
STEER_ZIGZAG = 2.0

# state: the 3-DOF state, the rudder angle delta [rad] (positive: trailing edge to starboard,
# turning the ship to starboard, psi decreasing), integrated with the motions, and the sign of the
# zig-zag helm, held within a step like the roll amplitude
S_RUDDER = N_STATE
S_HELM = N_STATE + 1
N_STATE6 = N_STATE + 2
# the radiation memory states (4 n reals: w_jp = (re, im) for input j in (heave, pitch), pole p) follow
S_MEMORY = N_STATE6

# lift branches of a foil (paper 004 eq 9), held within a step (event location, ``_simulate6``)
FOIL_ATTACHED = 0
FOIL_STALLED = 1
FOIL_REVERSED = 2
#: the most switches of the discrete modes (foils' lift branches, rudder slew limit and stop) located
#: within one step; beyond it the step is accepted with the modes of its end
MAX_EVENTS = 4
#: hysteresis of the modes' switches [rad, rad/s] (``_modes``)
MODE_BAND = 1e-6
#: a span whose modes are the same at both ends is searched for a switch and back at the points
#: dividing it into this many equal parts (``_simulate6``, ``_first_change``)
EVENT_SAMPLES = 8

# record status
OK = 0
CAPSIZED = 1
LEFT_TABLE = 2


@njit(cache=True, inline="always")
def _hermite(y0, d0, y1, d1, t, h):
    """Cubic Hermite interpolation on [0, 1] with derivatives d0, d1 per unit length and spacing h."""
    t2 = t * t
    t3 = t2 * t
    return ((2.0 * t3 - 3.0 * t2 + 1.0) * y0 + (t3 - 2.0 * t2 + t) * h * d0
            + (-2.0 * t3 + 3.0 * t2) * y1 + (t3 - t2) * h * d1)


@njit(cache=True, inline="always")
def _hermite_slope(y0, d0, y1, d1, t, h):
    """Derivative per unit length of :func:`_hermite`'s interpolant at t."""
    t2 = t * t
    return (6.0 * t2 - 6.0 * t) * (y0 - y1) / h + (3.0 * t2 - 4.0 * t + 1.0) * d0 + (3.0 * t2 - 2.0 * t) * d1


@njit(cache=True, inline="always")
def _crossbeam_weights(p, m, s):
    """(l_a, l_b): the weights of the cross-beam terms' two nodes (``waves.synthesis.crossbeam_node``:
    u_a and 1 in u = sin^2 of the relative heading; the terms vanish at u = 0) at the relative
    heading beta - psi: quadratic interpolation in u, exact at the course's heading. (0, 0) with
    the curved waterline, whose parabola carries a part of the cross-beam phase (``_kernels._fkhs``)."""
    if m[M_CURVED] != 0.0:
        return 0.0, 0.0
    sb = p[P_SIN_BETA]
    ua = _crossbeam_node(sb)
    u = math.sin(math.atan2(sb, p[P_COS_BETA]) - s[S_YAW]) ** 2
    return u * (u - 1.0) / (ua * (ua - 1.0)), u * (u - ua) / (1.0 - ua)


@njit(cache=True, inline="always")
def _remainder_weight(decay, i, j, nr, base, block, la, lb):
    """Station i's weight of factor j for a block ``base`` (0 WF, 1 WZ, 2 WY, 4 W_2, 5 W_3) with its
    cross-beam remainder's two nodes (blocks ``block`` and ``block + 1``, weighted ``la``, ``lb``)."""
    return decay[i, base * nr + j] + la * decay[i, block * nr + j] + lb * decay[i, (block + 1) * nr + j]


@njit(cache=True)
def _station_wave(xs, p, m, s, line, decay, la, lb, wave):
    """Fill ``wave`` (nst, ``WAVE_BUFFER``) with the stations' wave in ``_kernels``'s layout
    (``_wave_columns``) and u (eta_xixi = dS/dxi, the slope of S's Hermite interpolant: 0.4 % at 8 points per wavelength where a linear one of the tabulated dS/dxi is 7.6 %
    low), at the stations' instantaneous positions from the line
    table ``line`` (npoints, 3 + 4 r) at one time, whose points then lie at xi = m[M_XI0] + m[M_XI_RATE]
    m[M_XI_TIME] + k m[M_DXI] (a table on a grid moving with the ship's drift). Returns False if a station lies outside the table (its
    value is then taken at the nearest end); a periodic table (``M_WRAP`` intervals, one regular
    wave, last point = first) is read modulo its period and never left.

    Where a station is (``M_KEEL_LINE`` 1): across the beam the sections' waterline planes are
    referred to the body origin, so the station lies at the body origin's lateral position, z_G sin(phi)
    to the side of G's vertical (1.7 m at 30 degree of roll for the trawler's KG 3.47 m). Along the
    ship it lies where the pitched section meets the water: the body point (x_i, 0, z_w), z_w =
    ``M_WL_HEIGHT`` the calm waterline's height above the keel, at (z_w - z_G) sin(theta) cos(phi)
    along G's axis. A pitched section is a tilted slab whose points at height z lie z sin(theta)
    along the ship from its keel; the plane takes the wave as constant along the slab, so it is
    read where the slab's waterline is. Read at the keel (z = 0) instead, on the trawler surging in a
    following wave (lambda 42.7 m, H 1.8 m, 2 m/s, 8 degree of pitch; stabflow measurement,
    2026-12-04) the mean vertical force was +0.85 % of pressure integration's on the exact surface,
    the heave force's first harmonic +25 % and the mean surge force +12.6 %; at
    z_w -0.04 %, -1.3 % and, with ``_tilt_loads``, +0.2 % (validation rows of the broaching step).
    With R = Rz(psi) Ry(theta) Rx(phi), the station's offset from G before the yaw is
    (cos(theta) (x_i - x_G) + (z_w - z_G) sin(theta) cos(phi), z_G sin(phi)): the ship-axis component
    of R (x_i - x_G, 0, z_w - z_G) and the lateral one of R (x_i - x_G, 0, -z_G).
    ``M_KEEL_LINE`` 0 puts the stations on G's axis turned by the yaw, where the 3-DOF model's
    fixed stations are (paper 000 section 3: the body origin held, its horizontal shift with the
    rotations left out), for the constrained-case comparison.

    ``wave`` (nst, ``WAVE_BUFFER``) receives (eta, S) in its first columns, then with the pressure
    decay (``decay`` (nst, ``DECAY_BLOCKS`` r), r > 0: the station weights (WF, WZ, WY, W_1 ...
    W_6, WX_a, WX_b) of ``waves.synthesis.decay_factors``) dphi_zt = sum_j WF_ij P_j,
    S_h = sum_j WF'_ij Q_j, S_hz = sum_j WZ'_ij Q_j, T_yy = -sum_j WY_r,ij Q_j and
    U_yy = sum_j WY_y,ij P_j / g in columns 2-6, the heeled section's H_1 ... H_6 in 7-12, the
    cross-beam correction W = -sum_j (l_a WX_a,ij + l_b WX_b,ij) P_j / g in 13 (``la``, ``lb``:
    :func:`_crossbeam_weights`), the primed weights with their cross-beam remainders
    (WF' = WF + l_a WdF_a + l_b WdF_b, ``waves.synthesis.LineWaves``)
    (P_j, Q_j in the table's columns 3 + 4 j and 5 + 4 j, their slopes after each, Hermite as eta),
    and with the curved waterline (``M_CURVED``) eta_xixi in column 3, or 14 with the decay: the
    first ``_wave_columns`` columns are ``_kernels._fkhs``'s layout. Column ``U_COLUMN`` receives
    u, the station's coordinate in the table [intervals] (``_tilt_loads``). Columns not written are
    left as they were."""
    xg = p[P_XG]
    cb = p[P_COS_BETA]
    sb = p[P_SIN_BETA]
    cy = math.cos(s[S_YAW])
    sy = math.sin(s[S_YAW])
    x0 = s[S_X] + xg
    y0 = s[S_Y]
    # station - G before the yaw: (ct d + ox, oy) with d = x_i - x_G
    ct = 1.0
    ox = 0.0
    oy = 0.0
    if m[M_KEEL_LINE] != 0.0:
        zg = p[P_ZG]
        cp = math.cos(s[S_ROLL])
        ct = math.cos(s[S_PITCH])
        ox = (m[M_WL_HEIGHT] - zg) * math.sin(s[S_PITCH]) * cp
        oy = zg * math.sin(s[S_ROLL])
    x0 += -sy * oy
    y0 += cy * oy
    xi0 = m[M_XI0] + m[M_XI_RATE] * m[M_XI_TIME]
    h = m[M_DXI]
    npt = line.shape[0]
    wrap = m[M_WRAP]
    curved = m[M_CURVED] != 0.0
    nr = decay.shape[1] // DECAY_BLOCKS
    ic = DECAY_COLUMNS if nr > 0 else 3
    ig = 1.0 / p[P_G]
    if curved and nr == 0:
        for i in range(xs.shape[0]):
            wave[i, 2] = 0.0
    inside = True
    for i in range(xs.shape[0]):
        d = ct * (xs[i] - xg) + ox
        xi = (x0 + cy * d) * cb + (y0 + sy * d) * sb
        u = (xi - xi0) / h
        if wrap > 0.0:
            u -= wrap * math.floor(u / wrap)
        if u < 0.0:
            u = 0.0
            inside = False
        elif u > npt - 1.0:
            u = npt - 1.0
            inside = False
        k = min(int(u), npt - 2)
        t = u - k
        wave[i, 0] = _hermite(line[k, 0], line[k, 1], line[k + 1, 0], line[k + 1, 1], t, h)
        wave[i, 1] = _hermite(line[k, 1], line[k, 2], line[k + 1, 1], line[k + 1, 2], t, h)
        if nr > 0:
            dz = 0.0
            sh = 0.0
            shz = 0.0
            tyy = 0.0
            uyy = 0.0
            # the heeled section's H_1, H_2, H_3 = -sum_j W_ij P_j / g and H_4, H_5, H_6 = -sum_j W_ij Q_j
            h1 = 0.0
            h2 = 0.0
            h3 = 0.0
            h4 = 0.0
            h5 = 0.0
            h6 = 0.0
            cw = 0.0  # the cross-beam correction W = -sum_j (l_a WX_a,ij + l_b WX_b,ij) P_j / g
            for j in range(nr):
                c = 3 + 4 * j
                pj = _hermite(line[k, c], line[k, c + 1], line[k + 1, c], line[k + 1, c + 1], t, h)
                qj = _hermite(line[k, c + 2], line[k, c + 3], line[k + 1, c + 2], line[k + 1, c + 3], t, h)
                dz += decay[i, j] * pj
                sh += _remainder_weight(decay, i, j, nr, 0, 11, la, lb) * qj
                shz += _remainder_weight(decay, i, j, nr, 1, 13, la, lb) * qj
                tyy -= _remainder_weight(decay, i, j, nr, 2, 15, la, lb) * qj
                uyy += _remainder_weight(decay, i, j, nr, 2, 17, la, lb) * pj
                h1 -= decay[i, 3 * nr + j] * pj
                h2 -= _remainder_weight(decay, i, j, nr, 4, 19, la, lb) * pj
                h3 -= _remainder_weight(decay, i, j, nr, 5, 21, la, lb) * pj
                h4 -= decay[i, 6 * nr + j] * qj
                h5 -= decay[i, 7 * nr + j] * qj
                h6 -= decay[i, 8 * nr + j] * qj
                cw -= (la * decay[i, 9 * nr + j] + lb * decay[i, 10 * nr + j]) * pj
            wave[i, 2] = dz
            wave[i, 3] = sh
            wave[i, 4] = shz
            wave[i, 5] = tyy
            wave[i, 6] = uyy * ig
            wave[i, 7] = h1 * ig
            wave[i, 8] = h2 * ig
            wave[i, 9] = h3 * ig
            wave[i, 10] = h4
            wave[i, 11] = h5
            wave[i, 12] = h6
            wave[i, 13] = cw * ig
        if curved:
            wave[i, ic] = _hermite_slope(line[k, 1], line[k, 2], line[k + 1, 1], line[k + 1, 2], t, h)
        wave[i, U_COLUMN] = u
    return inside


@njit(cache=True, inline="always")
def _line_cell(line, m, u):
    """The interval k and fraction t in it of the coordinate ``u`` of the line table ``line`` (in
    intervals from its first point, as ``wave[:, U_COLUMN]``): periodic tables read modulo their
    period, others at the nearest end beyond it."""
    npt = line.shape[0]
    wrap = m[M_WRAP]
    if wrap > 0.0:
        u -= wrap * math.floor(u / wrap)
    u = min(max(u, 0.0), npt - 1.0)
    k = min(int(u), npt - 2)
    return k, u - k


@njit(cache=True, inline="always")
def _line_value(line, m, u, c):
    """Column ``c`` of the line table (its slope along xi in ``c + 1``) at the coordinate ``u``
    (:func:`_line_cell`): cubic Hermite. Column 1 is S."""
    k, t = _line_cell(line, m, u)
    return _hermite(line[k, c], line[k, c + 1], line[k + 1, c], line[k + 1, c + 1], t, m[M_DXI])


@njit(cache=True)
def _tilt_loads(xs, dx, rho, g, xg, zg, zw, phi, theta, cb, sb, line, m, decay, la, lb, wave, work, out):
    """Add to ``out`` (6,) the horizontal FK force of the pitched sections' tilt and its moment
    about G (heading frame), after ``_fkhs`` left each section's area and first moments (body axes,
    about the body origin) in ``work[:, 2:5]``.

    The volume-based force on a section is rho g dV times the wave slope (paper 000 eq 9, decay
    off: grad p = rho g grad eta; with the pressure decay the area-averaged slope S_h, both here and
    at the centroid, plus the change of S_h over the lift Z / F of the decaying gradient's
    resultant above the centroid, from dS_hz/dxi), taken at the station. A pitched section is a tilted slab: its
    point (y, z) lies sin(theta) (sin(phi) y + cos(phi) (z - z_w)) along the ship from the station
    (read at the waterline's height z_w, ``_station_wave``). To second order the force is rho g dV
    times the slope S_c at the section's centroid, read from the line table ``line`` where the
    centroid lies along xi (cos(beta - psi) of the distance along the ship): the force changes by
    rho g dV (S_c - S). (Read there by the table's cubic Hermite interpolant, smooth through the
    table's points; the linear extrapolation eta_xixi times the distance, with eta_xixi the slope
    of that interpolant, has a kink at each point, and took the records' step convergence from
    RK4's order to about first.) Its moment takes the section's centroid as the lever, as
    ``_fkhs`` does; the spread of the force over the section's height is left out. Second order in
    wave slope times pitch; it is the mean surge force that, with the resistance, sets the
    surf-riding threshold (trawler, lambda 42.7 m, 2 m/s, 7.7 degree of pitch: +0.5 % of
    pressure integration's; the station's slope alone, read on the keel line as before 2026-12-04,
    +12.6 %: validation rows of the broaching step)."""
    st = math.sin(theta)
    cp = math.cos(phi)
    sp = math.sin(phi)
    ct = math.cos(theta)
    h = m[M_DXI]
    nr = decay.shape[1] // DECAY_BLOCKS
    vs = 0.0
    px = 0.0
    py = 0.0
    pz = 0.0
    for i in range(xs.shape[0]):
        A = work[i, 2]
        if A == 0.0:
            continue
        # the centroid's distance along xi from the station, then dV (S_c - S)
        d = cb * st * (sp * work[i, 3] + cp * (work[i, 4] - zw * A)) / A
        if nr > 0:
            # the pressure decay: the area-averaged slope S_h = sum_j WF'_ij Q_j there and here, and
            # since the decaying gradient's resultant lies Z / F above the centroid, where the slab is
            # cos(beta) sin(theta) cos(phi) Z / F further along xi, its change there: dS_hz/dxi
            # (S_hz = sum_j WZ'_ij Q_j) times that factor (primed: with the cross-beam remainders,
            # ``_station_wave``)
            sc = 0.0
            lift = cb * st * cp
            kc, tc = _line_cell(line, m, wave[i, U_COLUMN] + d / h)  # the centroid's
            ks, ts = _line_cell(line, m, wave[i, U_COLUMN])  # the station's
            for j in range(nr):
                c = 5 + 4 * j
                sc += _remainder_weight(decay, i, j, nr, 0, 11, la, lb) * _hermite(
                    line[kc, c], line[kc, c + 1], line[kc + 1, c], line[kc + 1, c + 1], tc, h)
                sc += lift * _remainder_weight(decay, i, j, nr, 1, 13, la, lb) * _hermite_slope(
                    line[ks, c], line[ks, c + 1], line[ks + 1, c], line[ks + 1, c + 1], ts, h)
            e = (sc - wave[i, 3]) * A * dx[i]
        else:
            e = (_line_value(line, m, wave[i, U_COLUMN] + d / h, 1) - wave[i, 1]) * A * dx[i]
        vs += e
        px += (xs[i] - xg) * e
        py += work[i, 3] / A * e
        pz += (work[i, 4] / A - zg) * e
    f = rho * g
    ux = -cb
    uy = -sb
    out[0] += f * ux * vs
    out[1] += f * uy * vs
    rpx, rpy, rpz = _rotate(px, py, pz, cp, sp, ct, st)
    out[3] += f * (-rpz * uy)
    out[4] += f * (rpz * ux)
    out[5] += f * (rpx * uy - rpy * ux)


@njit(cache=True, inline="always")
def _lift_mode(alpha, stall, trail):
    """The foil's lift branch at the angle of attack ``alpha`` [rad] (paper 004 eq 9): FOIL_ATTACHED
    below the stall angle, FOIL_REVERSED within the trailing-edge stall angle of reversed flow,
    else FOIL_STALLED."""
    if abs(alpha) < stall:
        return FOIL_ATTACHED
    if math.pi - abs(alpha) < trail:
        return FOIL_REVERSED
    return FOIL_STALLED


@njit(cache=True, inline="always")
def _attack(uf, vf, delta):
    """Angle of attack [rad] of a foil moving at (uf, vf) [m/s], chord turned by ``delta``: from the
    upstream direction to the chord (0 without flow)."""
    v2 = uf * uf + vf * vf
    if v2 <= 1e-12:
        return 0.0
    vv = math.sqrt(v2)
    dx = uf / vv
    dy = vf / vv
    cx = math.cos(delta)
    cy = math.sin(delta)
    return math.atan2(dx * cy - dy * cx, dx * cx + dy * cy)


@njit(cache=True, inline="always")
def _foil_force(uf, vf, delta, rho, area, cla, stall, trail, ar, cn, mode=-1):
    """Force (Fx, Fy) [N] in body axes of a foil whose span lies along body z, moving at (uf, vf) [m/s]
    (body axes, ``_body_flow``) through still water, chord turned by ``delta`` (nose to port for
    delta > 0); the spanwise flow gives no force.

    Lift (paper 004 eqs 5, 9, 11): the angle of attack is measured from the upstream direction to
    the chord; lift is normal to the flow, C_L = C_La alpha below the stall angle, C_La (alpha -+ pi)
    within the trailing-edge stall angle of reversed flow, else zero; with the induced drag of the
    same lifting line, C_Di = C_L^2 / (pi A_R) (Prandtl), along the flow (without it a lifting
    rudder in a turn would propel the ship). Eddy making (eqs 12, 16): the flat-plate normal force
    1/2 C_N rho V_n |V_n| S C along the chord normal, V_n the flow's normal component (C_A = C_K =
    C_S = 1 at full-scale Reynolds numbers, eq 15): the force a stalled rudder still gives.

    ``mode``: the lift branch (FOIL_*), held through a step by the RK4 (the branch's formula
    continued beyond its angles, so that the step sees a smooth force and the switch is located,
    ``_simulate6``); -1: the branch of the angle of attack (``_lift_mode``)."""
    v2 = uf * uf + vf * vf
    if v2 <= 1e-12:
        return 0.0, 0.0
    vv = math.sqrt(v2)
    dx = uf / vv
    dy = vf / vv
    cx = math.cos(delta)
    cy = math.sin(delta)
    alpha = _attack(uf, vf, delta)
    if mode < 0:
        mode = _lift_mode(alpha, stall, trail)
    if mode == FOIL_ATTACHED:
        cl = cla * alpha
    elif mode == FOIL_REVERSED:
        cl = cla * (alpha - math.copysign(math.pi, alpha))
    else:
        cl = 0.0
    q = 0.5 * rho * v2 * area
    cd = cl * cl / (math.pi * ar)
    # normal n = c x e_z = (cy, -cx); the water moves at (-uf, -vf) relative to the foil
    vn = -(uf * cy - vf * cx)
    e = 0.5 * rho * cn * vn * abs(vn) * area
    # lift along (-dy, dx), drag against the foil's motion (-dx, -dy)
    return q * (-dy * cl - dx * cd) + e * cy, q * (dx * cl - dy * cd) - e * cx


@njit(cache=True, inline="always")
def _heading_velocities(m, s):
    """(cos psi, sin psi, u, v): the surge and sway velocities of G in the heading frame, the frame
    of q moving with the commanded speed along x."""
    psi = s[S_YAW]
    c = math.cos(psi)
    sn = math.sin(psi)
    xd = m[M_SPEED] + s[S_RATE + S_X]
    yd = s[S_RATE + S_Y]
    return c, sn, c * xd + sn * yd, -sn * xd + c * yd


@njit(cache=True, inline="always")
def _flow_frame(m, s):
    """(cos phi, sin phi, cos th, sin th, w_x, w_y, w_z) of the manoeuvring loads: the roll phi and the
    pitch from the calm-water trim th = theta - theta_0 (the derivatives and foils refer to the ship at
    its trim), and the angular velocity [rad/s] in the heading frame from the Euler angles' rates,
    (phi' cos th, th', psi' - phi' sin th) for R = Rz(psi) Ry(th) Rx(phi). Found once per evaluation
    and passed to ``_body_flow`` for each point."""
    th = s[S_PITCH] - m[M_TRIM]
    ct = math.cos(th)
    st = math.sin(th)
    pr = s[S_RATE + S_ROLL]
    return (math.cos(s[S_ROLL]), math.sin(s[S_ROLL]), ct, st, ct * pr, s[S_RATE + S_PITCH],
            s[S_RATE + S_YAW] - st * pr)


@njit(cache=True, inline="always")
def _body_flow(m, s, fr, x, z):
    """Velocity (u_b, v_b) [m/s] of the body point (x, 0, z) from G [m] through still water, in body
    axes (paper 004 eq 1, whose fluid velocity leaves out the waves' particle velocities): the
    heading frame's (u, v, z') of G plus omega x R r (``fr`` = ``_flow_frame(m, s)``: R = Ry(theta -
    theta_0) Rx(phi) and omega), turned back by R^T. Heeled, the horizontal sway velocity meets a foil
    or the hull's centreplane at v cos(phi), and the heave velocity at z' sin(phi)."""
    c, sn, u, v = _heading_velocities(m, s)
    cp, sp, ct, st, wx, wy, wz = fr
    rx, ry, rz = _rotate(x, 0.0, z, cp, sp, ct, st)
    vx = u + wy * rz - wz * ry
    vy = v + wz * rx - wx * rz
    vz = s[S_RATE + S_Z] + wx * ry - wy * rx
    return ct * vx - st * vz, cp * vy + sp * (st * vx + ct * vz)


@njit(cache=True, inline="always")
def _add_body_load(fb_x, fb_y, mb_x, mb_z, x, z, cp, sp, ct, st, f):
    """Add to ``f`` (6,) (heading frame, about G) the load given in body axes: the force (fb_x, fb_y,
    0) [N] at the body point (x, 0, z) [m] and the moment (mb_x, 0, mb_z) [N m]."""
    fx, fy, fz = _rotate(fb_x, fb_y, 0.0, cp, sp, ct, st)
    rx, ry, rz = _rotate(x, 0.0, z, cp, sp, ct, st)
    mx, my, mz = _rotate(mb_x, 0.0, mb_z, cp, sp, ct, st)
    f[0] += fx
    f[1] += fy
    f[2] += fz
    f[3] += mx + ry * fz - rz * fy
    f[4] += my + rz * fx - rx * fz
    f[5] += mz + rx * fy - ry * fx


@njit(cache=True)
def _resistance(m, u):
    """Calm-water resistance [N] at surge velocity ``u`` [m/s], odd in u: the ITTC-57 friction line
    M_RES C_F(Re) u^2 plus the table (M_RR_DU, M_RR) of the rest, linear between its points and
    growing as u^2 from its last (:func:`stabflow.dynamics.resistance.kernel_resistance`)."""
    au = abs(u)
    cf = 0.075 / (math.log10(max(au * m[M_LNU], 1e3)) - 2.0) ** 2  # ITTC 1957 model-ship correlation line
    r = m[M_RES] * cf * au * au
    du = m[M_RR_DU]
    if du > 0.0:
        t = au / du
        i = int(t)
        if i < N_RR - 1:
            w = t - i
            r += (1.0 - w) * m[M_RR + i] + w * m[M_RR + i + 1]
        else:
            r += m[M_RR + N_RR - 1] * (t / (N_RR - 1)) ** 2
    return r if u >= 0.0 else -r


@njit(cache=True)
def _manoeuvring_loads(p, m, foils, strips, s, delta, f, modes):
    """Add resistance, thrust, hull manoeuvring forces (linear derivatives and cross-flow drag of
    the ``strips`` (nst, 2): x from G [m] and 1/2 rho T C_D dx [kg/m]) and foil forces to the loads
    ``f`` (6,) (force and moment about G in the heading frame). ``modes`` (nf + 2,): the foils' lift
    branches first (``_foil_force``; -1: from the angle of attack).

    The hull's side force and yaw moment and the foils' forces are found in body axes, from the
    flow's body-axis velocities (``_body_flow``), and turned into the heading frame with their
    moments about G: heeled by phi, a foil meets the sway velocity at v cos(phi) and its force,
    normal to its span, has the horizontal part cos(phi) of it, so its lift's horizontal part goes
    as cos^2(phi) (taken in the heading frame with the span vertical, it was overstated by 1/cos(phi)
    to 1/cos^2(phi): 15-33 % at 30 degree of roll, 41-100 % at 45), with a vertical part sin(phi) and
    the foil's pitch moment."""
    rho = p[P_RHO]
    c, sn, u, v = _heading_velocities(m, s)
    fr = _flow_frame(m, s)
    cp, sp, ct, st, wx, wy, wz = fr
    # calm-water resistance and the constant thrust
    fx = m[M_THRUST] - _resistance(m, u)
    # the surge row of the added mass's -C_A nu (Fossen): (A22 v + A26 r) r, quadratic, so not in
    # the linear derivatives (the inertia term is -A_b d(u, v, r)/dt, ``_horizontal_added_mass``)
    r = s[S_RATE + S_YAW]
    ab = m[M_AB:M_AB + 9]
    fx += (ab[4] * v + 0.5 * (ab[5] + ab[7]) * r) * r
    f[0] += fx
    # linear hull manoeuvring forces about midships (x = 0) in body axes, with midships' sway
    # velocity v_b - x_G r_b, scaled by the surge velocity; r_b the body yaw rate, (R^T omega)_z
    ub, vb = _body_flow(m, s, fr, 0.0, 0.0)
    rb = -sp * wy + cp * (st * wx + ct * wz)
    vm = vb - p[P_XG] * rb
    fy = ub * (m[M_YV] * vm + m[M_YR] * rb)
    nz = ub * (m[M_NV] * vm + m[M_NR] * rb) - p[P_XG] * fy
    # cross-flow drag: each strip's lateral velocity v_b + r_b x meets the drag of a 2-D section
    for i in range(strips.shape[0]):
        vl = vb + rb * strips[i, 0]
        dy = -strips[i, 1] * vl * abs(vl)
        fy += dy
        nz += strips[i, 0] * dy
    # the side force acts M_ZH above G, the yaw moment about G's body z axis
    _add_body_load(0.0, fy, 0.0, nz, 0.0, m[M_ZH], cp, sp, ct, st, f)
    for j in range(foils.shape[0]):
        xf = foils[j, F_X]
        zf = foils[j, F_Z]
        dl = delta if foils[j, F_RUDDER] != 0.0 else 0.0
        uf, vf = _body_flow(m, s, fr, xf, zf)
        lx, ly = _foil_force(uf, vf, dl, rho, foils[j, F_AREA], foils[j, F_CLA], foils[j, F_STALL],
                             foils[j, F_TRAIL], foils[j, F_AR], foils[j, F_CN], modes[j])
        _add_body_load(lx, ly, 0.0, 0.0, xf, zf, cp, sp, ct, st, f)


@njit(cache=True)
def _horizontal_added_mass(m, s, mq, r):
    """Add the inertia of the body-axis added mass of (u, v, r), -A_b nu', to the generalized
    system of (x, y, psi): with u = cos psi (U + x') + sin psi y', v = -sin psi (U + x') + cos psi y',
    r = psi', nu' = J q'' + r (v, -u, 0) (J the rotation to the heading frame), so
    J^T A_b J q'' = Q - J^T A_b r (v, -u, 0). The velocity-dependent ideal-fluid forces (added-mass
    Coriolis terms, Munk moment) linear in the velocities are part of the hull derivatives (measured
    on rotating arms and planar-motion mechanisms, Clarke et al. 1983; in slender-body theory, the
    Munk moment's -U int m dx in N_v) and are not added again; the
    quadratic surge term is added with the loads (``_manoeuvring_loads``)."""
    c, sn, u, v = _heading_velocities(m, s)
    rr = s[S_RATE + S_YAW]
    A = m[M_AB:M_AB + 9]
    # J rows: u <- (c, s, 0), v <- (-s, c, 0), r <- (0, 0, 1) over (x, y, psi)
    J = ((c, sn, 0.0), (-sn, c, 0.0), (0.0, 0.0, 1.0))
    idx = (S_X, S_Y, S_YAW)
    for a in range(3):
        for b in range(3):
            acc = 0.0
            for k in range(3):
                for l in range(3):
                    acc += J[k][a] * A[3 * k + l] * J[l][b]
            mq[idx[a], idx[b]] += acc
    e0 = (A[0] * v - A[1] * u) * rr
    e1 = (A[3] * v - A[4] * u) * rr
    e2 = (A[6] * v - A[7] * u) * rr
    for a in range(3):
        r[idx[a]] -= J[0][a] * e0 + J[1][a] * e1 + J[2][a] * e2


@njit(cache=True, inline="always")
def _memory(p, m, s, r, ds, u):
    """Heave-pitch radiation memory (Cummins' convolution as states, :mod:`stabflow.dynamics.radiation`):
    subtracts mu_i = sum_jp Re(c_ijp w_jp) from the generalized forces ``r`` of heave and pitch and
    writes the states' rates w_jp' = l_p w_jp + v_j into ``ds``. Nothing without the tail of ``m``.

    Forward speed (the flag after the residues; ``u`` the surge velocity [m/s]): the time-domain
    form of strip theory (Salvesen, Tuck & Faltinsen 1970, with the transom's added-mass terms, its
    damping b^A left out; the A(inf) terms assume A35(inf) = A53(inf), as strip theory has). A section at x
    moves through the water with the relative vertical velocity w = z' - x theta' + u (theta -
    theta_0) (the fluid slice sees d/dt - u d/dx), and its force is -(d/dt - u d/dx) of its
    momentum, a(inf) w plus the memory's. So the heave input is v_z = z' + u (theta - theta_0), the
    heave force gains -u A33(inf) theta' and the pitch moment (the u d/dx part integrated by parts)
    u [A33(inf) v_z + mu~_3], mu~_3 = sum_jp Re(c_3jp w_jp / l_p) the heave row's memory of the
    displacement (its transfer K^(iw) / (iw), finite since K^(0) = 0). The flow leaves a transom
    stern at x_T with its momentum a_T w_T (the boundary term of the u d/dx part, w_T the transom's
    relative velocity; a_T its section's added mass at infinite frequency): heave -u a_T w_T, pitch
    u x_T a_T w_T. For harmonic motions this is STF's table with the transom's a^A (its b^A left
    out): A35 - U B33 / w^2 - U^2 a_T / w^2, B35 + U A33 - U x_T a_T, A53 + U B33 / w^2,
    B53 - U A33 - U x_T a_T, A55 + U^2 (A33 + x_T a_T) / w^2, B55 + U^2 B33 / w^2 + U x_T^2 a_T,
    B33 + U a_T (:func:`stabflow.dynamics.radiation.forward_speed_coefficients`)."""
    if m.shape[0] <= M_MEMORY:
        return
    n = int(m[M_MEMORY])
    b = M_MEMORY + 1
    c0 = b + 2 * n
    e = c0 + 8 * n
    fwd = m.shape[0] > e and m[e] != 0.0
    vz = s[S_RATE + S_Z]
    if fwd:
        vz += u * (s[S_PITCH] - m[e + 1])
    tilde = 0.0
    for j in range(2):
        v = vz if j == 0 else s[S_RATE + S_PITCH]
        for q in range(n):
            lr = m[b + 2 * q]
            li = m[b + 2 * q + 1]
            k = S_MEMORY + 2 * (n * j + q)
            wr = s[k]
            wi = s[k + 1]
            ds[k] = lr * wr - li * wi + v
            ds[k + 1] = li * wr + lr * wi
            for i in range(2):
                o = c0 + 2 * (4 * q + 2 * i + j)
                r[S_Z if i == 0 else S_PITCH] -= m[o] * wr - m[o + 1] * wi
            if fwd:
                # Re(c w / l) of the heave row, c / l = c conj(l) / |l|^2
                o = c0 + 2 * (4 * q + j)
                cr = m[o]
                ci = m[o + 1]
                l2 = lr * lr + li * li
                tilde += ((cr * lr + ci * li) * wr - (ci * lr - cr * li) * wi) / l2
    if fwd:
        a33 = p[P_ADDED_MASS + 6 * S_Z + S_Z]
        xt = m[e + 2]
        mt = m[e + 3] * (vz - xt * s[S_RATE + S_PITCH])  # the transom's momentum a_T w_T
        r[S_Z] -= u * (a33 * s[S_RATE + S_PITCH] + mt)
        r[S_PITCH] += u * (a33 * vz + tilde + xt * mt)


@njit(cache=True, inline="always")
def _wave_columns(m, decay):
    """Columns of ``_kernels``'s station-wave layout: 2, 4 with the curved waterline,
    ``DECAY_COLUMNS`` (14) with the pressure decay, one more with both."""
    if decay.shape[1] > 0:
        return DECAY_COLUMNS + (1 if m[M_CURVED] != 0.0 else 0)
    return 4 if m[M_CURVED] != 0.0 else 2


@njit(cache=True)
def _wave_loads(xs, dx, ys, zs, npts, tab, lim, p, m, line, decay, s, f, wave, work):
    """FK + HS loads ``f`` (6,) about G in the heading frame for the wave line ``line`` at this time:
    the stations' wave (``_station_wave``), the sections (``_fkhs``, the wave heading relative to the
    ship beta - psi) and their tilt (``_tilt_loads``). Returns False if a station left the table."""
    la, lb = _crossbeam_weights(p, m, s) if decay.shape[1] > 0 else (0.0, 0.0)
    inside = _station_wave(xs, p, m, s, line, decay, la, lb, wave)
    rel = math.atan2(p[P_SIN_BETA], p[P_COS_BETA]) - s[S_YAW]
    cb = math.cos(rel)
    sb = math.sin(rel)
    h = _origin_height(s[S_Z], s[S_ROLL], s[S_PITCH], p[P_XG], p[P_ZG])
    _fkhs(xs, dx, ys, zs, npts, tab, lim, p[P_RHO], p[P_G], p[P_XG], p[P_ZG], h, s[S_ROLL], s[S_PITCH],
          cb, sb, wave[:, :_wave_columns(m, decay)], f, work)
    if m[M_KEEL_LINE] != 0.0:
        _tilt_loads(xs, dx, p[P_RHO], p[P_G], p[P_XG], p[P_ZG], m[M_WL_HEIGHT], s[S_ROLL], s[S_PITCH], cb, sb, line,
                    m, decay, la, lb, wave, work, f)
    return inside


@njit(cache=True)
def _rhs6(xs, dx, ys, zs, npts, tab, lim, p, m, foils, strips, line, decay, s, delta, ds, f, wave, work, mq, r,
          modes):
    """State derivative of the 6-DOF state for the wave line ``line`` (npoints, 3 + 4 r) at this time and
    the rudder angle ``delta``; the FK + HS loads see the wave heading relative to the ship,
    beta - psi; ``modes`` the discrete modes (``_modes``; the rudder rate is not written here). Returns
    False if a station left the wave table."""
    inside = _wave_loads(xs, dx, ys, zs, npts, tab, lim, p, m, line, decay, s, f, wave, work)
    _manoeuvring_loads(p, m, foils, strips, s, delta, f, modes)
    for j in range(6):
        ds[j] = s[S_RATE + j]
    _generalized_system(p, s, f, mq, r)
    _horizontal_added_mass(m, s, mq, r)
    _memory(p, m, s, r, ds, _heading_velocities(m, s)[2])
    _solve_free(p, mq, r, ds[S_RATE:S_RATE + 6])
    for j in range(S_RATE + 6, N_STATE6):
        ds[j] = 0.0
    return inside


@njit(cache=True)
def _helm(m, psi, helm):
    """The zig-zag helm sign after a step: positive helm turns to starboard (psi decreasing) until
    psi <= -M_ZIGZAG, then reverses, and back when psi >= M_ZIGZAG (other modes: unchanged)."""
    if m[M_STEERING] == STEER_ZIGZAG:
        if helm > 0.0 and psi <= -m[M_ZIGZAG]:
            return -1.0
        if helm < 0.0 and psi >= m[M_ZIGZAG]:
            return 1.0
    return helm


@njit(cache=True, inline="always")
def _servo_rate(m, s, helm):
    """(delta_c - delta) / tau [rad/s]: the servo's rate before its limits (``_gear_rate``)."""
    mode = m[M_STEERING]
    if mode == STEER_AUTOPILOT:
        err = s[S_YAW] - m[M_PSID]
        err -= 2.0 * math.pi * math.floor((err + math.pi) / (2.0 * math.pi))  # to [-pi, pi)
        dc = m[M_GA] * err + m[M_GB] * s[S_RATE + S_YAW]
    elif mode == STEER_ZIGZAG:
        dc = helm * m[M_HELM]
    else:
        dc = m[M_HELM]
    return (dc - s[S_RUDDER]) / m[M_TAU]


@njit(cache=True, inline="always")
def _gear_rate(m, s, helm, slew, stop):
    """The rudder rate [rad/s] with the steering gear's modes held (``_modes``): zero at a stop, the
    slew rate +-R_m on the slew limit, else the servo's unlimited (delta_c - delta) / tau. The command: a constant (fixed
    mode), the PD autopilot of paper 004 eq 30, delta_c = G_a (psi - psi_d) + G_b psi', or the
    zig-zag helm +-M_HELM. The servo (eqs 31-34): tau delta' + delta = delta_c, the rate limited
    to the slew rate R_m (eq 33) and zero at the stop A_m when it pushes beyond (eq 34).

    Paper 004 writes eq 30's derivative as (psi - psi_0) / dt with psi_0 at the previous time step
    and solves eq 31 over a step with the command held (eq 32): both are first order in the step.
    Their limit dt -> 0, written here, is integrated with the motions by RK4, so that the records
    converge with the step (the closed loop of ``linearised_course_change`` is the same)."""
    if stop != 0:
        return 0.0
    if slew != 0:
        return slew * m[M_SLEW]
    return _servo_rate(m, s, helm)


@njit(cache=True, inline="always")
def _lift_margin(alpha, stall, trail, mode):
    """How far [rad] the angle of attack lies inside lift branch ``mode`` (negative: outside)."""
    a = abs(alpha)
    b = math.pi - a
    if mode == FOIL_ATTACHED:
        return stall - a
    if mode == FOIL_REVERSED:
        return trail - b
    return min(a - stall, b - trail)


@njit(cache=True)
def _modes(m, foils, s, helm, cur, out):
    """The discrete modes of state ``s`` into ``out`` (nf + 2,): each foil's lift branch
    (``_lift_mode``), then the steering gear's slew limit (+1, -1: the servo's rate beyond +-R_m;
    0) and stop (+1, -1: the rudder at +-A_m with the servo pushing beyond, or past it; 0). A mode
    of ``cur`` (the modes held so far; entries < -1: none) is kept while its margin (radians, or
    radians per second for the servo's rate) exceeds -MODE_BAND, so that a switch once located is
    not undone by the round-off between the interpolant it was located on and the RK4 state."""
    d = s[S_RUDDER]
    nf = foils.shape[0]
    fr = _flow_frame(m, s)
    for j in range(nf):
        dl = d if foils[j, F_RUDDER] != 0.0 else 0.0
        uf, vf = _body_flow(m, s, fr, foils[j, F_X], foils[j, F_Z])
        a = _attack(uf, vf, dl)
        if cur[j] >= 0 and _lift_margin(a, foils[j, F_STALL], foils[j, F_TRAIL], cur[j]) > -MODE_BAND:
            out[j] = cur[j]
        else:
            out[j] = _lift_mode(a, foils[j, F_STALL], foils[j, F_TRAIL])
    rn = _servo_rate(m, s, helm)
    dm = m[M_MAX]
    rm = m[M_SLEW]
    sc = cur[nf + 1]
    if sc == 1:
        keep = d >= dm - MODE_BAND and rn > -MODE_BAND
    elif sc == -1:
        keep = d <= -dm + MODE_BAND and rn < MODE_BAND
    elif sc == 0:
        keep = max(dm - d, -rn) > -MODE_BAND and max(dm + d, rn) > -MODE_BAND
    else:
        keep = False
    if keep:
        stop = sc
    elif d >= dm and (rn > 0.0 or d > dm):
        stop = 1
    elif d <= -dm and (rn < 0.0 or d < -dm):
        stop = -1
    else:
        stop = 0
    slew = 0
    if stop == 0:
        sl = cur[nf]
        if sc == 0 and ((sl == 0 and rm - abs(rn) > -MODE_BAND) or (sl == 1 and rn - rm > -MODE_BAND)
                        or (sl == -1 and -rn - rm > -MODE_BAND)):
            slew = sl
        elif rn > rm:
            slew = 1
        elif rn < -rm:
            slew = -1
    out[nf] = slew
    out[nf + 1] = stop


@njit(cache=True, inline="always")
def _stop(m, d):
    """The rudder angle held within +-A_m (eq 34)."""
    return min(max(d, -m[M_MAX]), m[M_MAX])


@njit(cache=True, inline="always")
def _same(a, b):
    for i in range(a.shape[0]):
        if a[i] != b[i]:
            return False
    return True


@njit(cache=True)
def _stage(a, j, n, dt, theta, sub, s, helm, modes, ds, f, wave, work, mq, r):
    """Right-hand side ``ds`` at the fraction ``theta`` of step ``n`` (line table rows j = 2 n, j + 1,
    j + 2 at 0, 1/2, 1; between them the rows' quadratic interpolation in time, written into
    ``sub``) with the modes held: the rudder rate of ``_gear_rate``. Returns False if a station left
    the wave table. ``a``: the arguments of ``_simulate6`` up to ``ltab``."""
    xs, dx, ys, zs, npts, tab, lim, p, m, foils, strips, ltab, decay = a
    m[M_XI_TIME] = (n + theta) * dt
    if theta == 0.0:
        line = ltab[j]
    elif theta == 0.5:
        line = ltab[j + 1]
    elif theta == 1.0:
        line = ltab[j + 2]
    else:
        # Lagrange weights of the rows at 0, 1/2, 1
        l0 = 2.0 * (theta - 0.5) * (theta - 1.0)
        l1 = -4.0 * theta * (theta - 1.0)
        l2 = 2.0 * theta * (theta - 0.5)
        for a in range(sub.shape[0]):
            for b in range(sub.shape[1]):
                sub[a, b] = l0 * ltab[j, a, b] + l1 * ltab[j + 1, a, b] + l2 * ltab[j + 2, a, b]
        line = sub
    nf = foils.shape[0]
    ok = _rhs6(xs, dx, ys, zs, npts, tab, lim, p, m, foils, strips, line, decay, s, s[S_RUDDER], ds, f, wave, work,
               mq, r, modes)
    ds[S_RUDDER] = _gear_rate(m, s, helm, modes[nf], modes[nf + 1])
    return ok


@njit(cache=True, inline="always")
def _rk4_span(a, j, n, dt, t0, t1, sub, sa, helm, modes, k1, k2, k3, k4, tmp, out, f, wave, work, mq, r, have_k1):
    """One RK4 step from ``sa`` at the fraction ``t0`` of step ``n`` to ``t1``, the modes held: the
    state into ``out`` (may be ``sa``), the first stage's rate stays in ``k1`` (``have_k1``: it is
    there already, from a span that started at the same state, time and modes). Returns False if a
    station left the wave table."""
    ns = sa.shape[0]
    h = (t1 - t0) * dt
    tm = 0.5 * (t0 + t1)
    ok = True
    if not have_k1:
        ok = _stage(a, j, n, dt, t0, sub, sa, helm, modes, k1, f, wave, work, mq, r)
    for q in range(ns):
        tmp[q] = sa[q] + 0.5 * h * k1[q]
    ok &= _stage(a, j, n, dt, tm, sub, tmp, helm, modes, k2, f, wave, work, mq, r)
    for q in range(ns):
        tmp[q] = sa[q] + 0.5 * h * k2[q]
    ok &= _stage(a, j, n, dt, tm, sub, tmp, helm, modes, k3, f, wave, work, mq, r)
    for q in range(ns):
        tmp[q] = sa[q] + h * k3[q]
    ok &= _stage(a, j, n, dt, t1, sub, tmp, helm, modes, k4, f, wave, work, mq, r)
    for q in range(ns):
        out[q] = sa[q] + h / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
    return ok


@njit(cache=True, inline="always")
def _hermite_state(c, h, sa, ka, sb, kb, out):
    """The cubic Hermite interpolant at the fraction ``c`` of a span of length ``h`` [s] between the
    states ``sa``, ``sb`` with their rates ``ka``, ``kb``, into ``out``."""
    c2 = c * c
    c3 = c2 * c
    h00 = 2.0 * c3 - 3.0 * c2 + 1.0
    h10 = (c3 - 2.0 * c2 + c) * h
    h01 = -2.0 * c3 + 3.0 * c2
    h11 = (c3 - c2) * h
    for q in range(sa.shape[0]):
        out[q] = h00 * sa[q] + h10 * ka[q] + h01 * sb[q] + h11 * kb[q]


@njit(cache=True, inline="always")
def _first_change(m, foils, helm, modes, nat, h, sa, k1, k2, k3, k4, s, kb, tmp, hermite):
    """The first of the EVENT_SAMPLES - 1 interior points c = q / EVENT_SAMPLES of the RK4 span of
    length ``h`` [s] from ``sa`` (stages ``k1`` ... ``k4``) to ``s`` (rate ``kb``) where the modes
    differ from ``modes`` (1.0: at none). ``hermite``: on the span's cubic Hermite interpolant (from
    the states and rates at both ends), else on the method's continuous extension of order 3 (its
    stages only; Hairer, Norsett & Wanner, Solving ODEs I, II.6: weights b1 = c - 3 c^2 / 2 +
    2 c^3 / 3, b2 = b3 = c^2 - 2 c^3 / 3, b4 = -c^2 / 2 + 2 c^3 / 3, the step's own at c = 1; ``kb``
    unread). ``nat`` and ``tmp`` are work arrays."""
    for q in range(1, EVENT_SAMPLES):
        c = q / EVENT_SAMPLES
        if hermite:
            _hermite_state(c, h, sa, k1, s, kb, tmp)
        else:
            c2 = c * c
            c3 = c2 * c
            b1 = h * (c - 1.5 * c2 + 2.0 * c3 / 3.0)
            b2 = h * (c2 - 2.0 * c3 / 3.0)
            b4 = h * (2.0 * c3 / 3.0 - 0.5 * c2)
            for i in range(sa.shape[0]):
                tmp[i] = sa[i] + b1 * k1[i] + b2 * (k2[i] + k3[i]) + b4 * k4[i]
        _modes(m, foils, tmp, helm, modes, nat)
        if not _same(nat, modes):
            return c
    return 1.0


@njit(cache=True, nogil=True)
def _simulate6(xs, dx, ys, zs, npts, tab, lim, p, m, foils, strips, ltab, decay, dt, nsteps, s0, phi_cap, out):
    """Fixed-step RK4 of the 6-DOF state from ``s0`` (N_STATE6 + the memory states,); ``ltab`` (2 nsteps + 1, npoints,
    3 + 4 r) the wave line table (eta, S, dS/dxi[, the pressure-decay terms' groups of four]) on the
    half-step grid and ``decay`` (nst, 3 r) its station weights (``_station_wave``). The rudder angle is a state of the
    RK4; the zig-zag helm switches at the steps. ``out`` (nsteps + 1, state size) receives the
    states; ``m[M_XI_TIME]`` is set stage by stage (``m`` is the caller's working copy). Returns
    (index of the last step done, status: OK, CAPSIZED (|roll| > phi_cap) or LEFT_TABLE).

    Event location: the foils' lift branches (stall, paper 004 eq 9) and the steering gear's slew
    limit and stop (eqs 33, 34) switch the right-hand side, which RK4 resolves only to the step.
    So the modes (``_modes``) are held within a step, each branch's formula continued beyond its
    switch; if the modes at the step's end differ, the switch is located on the step's cubic Hermite
    interpolant (from the states and rates at both ends, fourth order like RK4), bracketed by its
    first change among ``EVENT_SAMPLES`` - 1 interior points and bisected there, the
    step is integrated to it, the modes change (a rudder reaching its stop is set there) and the
    rest of the step follows, at most ``MAX_EVENTS`` times a step. Where the modes at both ends
    agree, a branch left and re-entered inside the step (the rudder's angle of attack carried past
    its stall angle and back) is looked for at those points on RK4's continuous extension
    (``_first_change``; from its stages, no right-hand side more), and a switch found there is
    located as above (unless the Hermite interpolant shows none: a borderline graze). Between the
    line table's half-step rows, the wave is their quadratic interpolation in time."""
    ns = s0.shape[0]
    s = np.empty(ns)
    sa = np.empty(ns)
    k1 = np.empty(ns)
    k2 = np.empty(ns)
    k3 = np.empty(ns)
    k4 = np.empty(ns)
    kb = np.empty(ns)
    tmp = np.empty(ns)
    f = np.empty(6)
    mq = np.empty((6, 6))
    r = np.empty(6)
    nst = xs.shape[0]
    work = np.empty((nst, 5))
    wave = np.empty((nst, WAVE_BUFFER))
    sub = np.empty_like(ltab[0])
    nf = foils.shape[0]
    modes = np.empty(nf + 2, np.int64)
    nat = np.empty(nf + 2, np.int64)
    for q in range(ns):
        s[q] = s0[q]
        out[0, q] = s0[q]
    none = np.full(nf + 2, -9, np.int64)
    _modes(m, foils, s, s[S_HELM], none, modes)
    a = (xs, dx, ys, zs, npts, tab, lim, p, m, foils, strips, ltab, decay)
    for n in range(nsteps):
        j = 2 * n
        helm = _helm(m, s[S_YAW], s[S_HELM])
        if helm != s[S_HELM]:
            _modes(m, foils, s, helm, none, modes)  # the command jumps: the gear's modes with it
        s[S_HELM] = helm
        prev = s[S_ROLL]
        ok = True
        for q in range(ns):
            sa[q] = s[q]
        ta = 0.0
        events = 0
        while True:
            # RK4 from sa at the fraction ta of the step to its end, the modes held
            h = (1.0 - ta) * dt
            ok &= _rk4_span(a, j, n, dt, ta, 1.0, sub, sa, helm, modes, k1, k2, k3, k4, tmp, s, f, wave, work, mq, r,
                            False)
            _modes(m, foils, s, helm, modes, nat)
            same = _same(nat, modes)
            # the same modes at both ends: a branch left and re-entered within the span (an angle of
            # attack grazing the stall angle) is looked for at EVENT_SAMPLES - 1 interior points of
            # RK4's own continuous extension (its stages: no right-hand side more)
            if same and (events == MAX_EVENTS or _first_change(m, foils, helm, modes, nat, h, sa, k1, k2, k3, k4, s,
                                                                 kb, tmp, False) == 1.0):
                break
            if events == MAX_EVENTS:
                for q in range(nf + 2):
                    modes[q] = nat[q]
                break
            # the first switch on the Hermite interpolant of (sa, k1) and (s, kb): bracketed by the
            # same interior points (so that of several crossings the first is taken), then bisected
            ok &= _stage(a, j, n, dt, 1.0, sub, s, helm, modes, kb, f, wave, work, mq, r)
            hi = _first_change(m, foils, helm, modes, nat, h, sa, k1, k2, k3, k4, s, kb, tmp, True)
            lo = hi - 1.0 / EVENT_SAMPLES if hi < 1.0 else 1.0 - 1.0 / EVENT_SAMPLES  # the sample before
            if same and hi == 1.0:
                break  # the Hermite interpolant shows none (the extension's switch was borderline)
            for _ in range(40):
                c = 0.5 * (lo + hi)
                _hermite_state(c, h, sa, k1, s, kb, tmp)
                _modes(m, foils, tmp, helm, modes, nat)
                if _same(nat, modes):
                    lo = c
                else:
                    hi = c
            # the modes just past the switch
            _hermite_state(hi, h, sa, k1, s, kb, tmp)
            _modes(m, foils, tmp, helm, modes, nat)
            # RK4 from sa to the switch with the old modes (its first stage is the span's above, in k1)
            tb = ta + hi * (1.0 - ta)
            ok &= _rk4_span(a, j, n, dt, ta, tb, sub, sa, helm, modes, k1, k2, k3, k4, tmp, sa, f, wave, work, mq, r,
                            True)
            for q in range(nf + 2):
                modes[q] = nat[q]
            if modes[nf + 1] != 0:
                sa[S_RUDDER] = math.copysign(m[M_MAX], float(modes[nf + 1]))
            ta = tb
            events += 1
        if modes[nf + 1] != 0:
            s[S_RUDDER] = math.copysign(m[M_MAX], float(modes[nf + 1]))
        else:
            s[S_RUDDER] = _stop(m, s[S_RUDDER])
        _update_amplitude(prev, s)
        for q in range(ns):
            out[n + 1, q] = s[q]
        if abs(s[S_ROLL]) > phi_cap:
            return n + 1, CAPSIZED
        if not ok:
            return n + 1, LEFT_TABLE
    return nsteps, OK
