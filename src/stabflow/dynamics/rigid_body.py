"""Rigid-body equations of motion about G, for Python callers of the RK4 kernels.

The generalized coordinates are q = (x, y, z of G [m], in an earth frame moving with the mean speed
and course, z up; roll phi, pitch theta, yaw psi [rad], the Euler angles of R = Rz(psi) Ry(theta)
Rx(phi)); the state is (q, q'), positions ``S_*`` of :mod:`stabflow.dynamics._kernels`. Newton's
law for G and Euler's equations in body axes,

    m v_G' = F + m g,        I w' + w x (I w) = M_b,        w = E(phi, theta) (phi', theta', psi'),

projected on q (Kane's method) give M(q) q'' = r(q, q'): M = J^T diag(m 1, I) J + A and
r = J^T (tau - M_RB J' q' - (0, w x I w)) - B q' - B44q(phi_a) phi'|phi'| e_phi, with J = diag(1, 1, 1, E)
and phi_a the running roll amplitude (LAMP's quasi-steady form, paper 004 eqs 17-19).
The added mass A and linear damping B (6 x 6) act on q, as the seakeeping (equilibrium) axes of
the radiation forces; the inertia tensor I is about G in body axes. The state is (q, q', phi_a,
peak): two memory states, held within a step, carry the running roll amplitude. A coordinate may be held
(``free`` flag 0): its acceleration is zero and its row drops out. The 3-DOF model is the
constrained case with surge, sway and yaw held (``THREE_DOF``), so that G moves on a vertical line
and the heave equation is written for G, including its vertical acceleration relative to any
other body point (d^2/dt^2 (z_G cos(theta) cos(phi) - x_G sin(theta)) from the keel's view).

Energy: in calm water without damping the FK + HS loads of the sections are conservative, with
potential U = m g z_G - rho g sum_i dx_i int_{A_i} z_e dA (each wet section point carries the
buoyancy rho g dx dA at its earth height z_e < 0, zero at the waterline), so
E = 1/2 m |v_G|^2 + 1/2 w^T I w + 1/2 q'^T A q' + U is conserved (:func:`mechanical_energy`).
"""

from __future__ import annotations

import numpy as np

from stabflow.constants import G
from stabflow.dynamics import _kernels as K

#: free flags of the 3-DOF model: heave, roll, pitch free; surge, sway, yaw held
THREE_DOF = (0.0, 0.0, 1.0, 1.0, 1.0, 0.0)
#: all six degrees of freedom free
SIX_DOF = (1.0,) * 6
#: names of the generalized coordinates, in state order
COORDINATES = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def origin_height(p: np.ndarray, q) -> float:
    """Earth height [m] of the body origin (keel, midships) for coordinates ``q`` (6,) of G."""
    return float(K._origin_height(q[K.S_Z], q[K.S_ROLL], q[K.S_PITCH], p[K.P_XG], p[K.P_ZG]))


def coordinates_from_origin(h: float, phi: float, theta: float, xg: float, zg: float) -> np.ndarray:
    """Generalized coordinates (6,) for the body origin at earth height ``h`` [m], heel ``phi`` and
    trim ``theta`` [rad]: z_G = h - sin(theta) x_G + cos(theta) cos(phi) z_G,body (the inverse of
    :func:`origin_height`), G over the frame's origin, no yaw."""
    q = np.zeros(6)
    q[K.S_Z] = h - np.sin(theta) * xg + np.cos(theta) * np.cos(phi) * zg
    q[K.S_ROLL] = phi
    q[K.S_PITCH] = theta
    return q


def generalized_system(p: np.ndarray, state, loads) -> tuple[np.ndarray, np.ndarray]:
    """(M (6, 6) [kg, kg m^2], r (6,) [N, N m]) of M q'' = r at ``state`` (N_STATE,) with the FK + HS
    ``loads`` (6,) (force and moment about G in the heading frame), all coordinates free."""
    mq, r = np.empty((6, 6)), np.empty(6)
    K._generalized_system(p, np.asarray(state, float), np.asarray(loads, float), mq, r)
    return mq, r


def generalized_loads(p: np.ndarray, q, loads) -> np.ndarray:
    """Generalized forces (6,) [N, N m] of ``loads`` (6,) on coordinates ``q`` (6,) at rest:
    J^T (F, M_b), without gravity or damping."""
    s = np.zeros(K.N_STATE)
    s[:6] = q
    _, r1 = generalized_system(p, s, loads)
    _, r0 = generalized_system(p, s, np.zeros(6))
    return r1 - r0


def accelerations(p: np.ndarray, state, loads) -> np.ndarray:
    """q'' (6,) at ``state`` (N_STATE,) for ``loads`` (6,), held coordinates zero (``p``'s free flags)."""
    acc = np.empty(6)
    K._accelerations(p, np.asarray(state, float), np.asarray(loads, float), acc, np.empty((6, 6)), np.empty(6))
    return acc


def mechanical_energy(sec, p: np.ndarray, states: np.ndarray) -> np.ndarray:
    """Total mechanical energy [J] along ``states`` (n, N_STATE) in calm water: kinetic energy of the
    rigid body and the added mass, potential of G and the hydrostatic potential of the sections
    (module docstring). Exact clipping of the sections, as the kernel without tables."""
    from stabflow.hydrostatics._kernels import _station_sections

    states = np.atleast_2d(states)
    xs, dx, ys, zs, npts = sec.args()
    m, g, rho = p[K.P_MASS], p[K.P_G], p[K.P_RHO]
    inertia = p[K.P_INERTIA:K.P_INERTIA + 9].reshape(3, 3)
    added = p[K.P_ADDED_MASS:K.P_ADDED_MASS + 36].reshape(6, 6)
    zero = np.zeros(len(xs))
    work = np.empty((len(xs), 3))
    out = np.empty(len(states))
    for n, s in enumerate(states):
        phi, th = s[K.S_ROLL], s[K.S_PITCH]
        cp, sp, ct, st = np.cos(phi), np.sin(phi), np.cos(th), np.sin(th)
        h = origin_height(p, s[:6])
        _station_sections(xs, ys, zs, npts, ct, st, cp, sp, h, zero, zero, work)
        A, Sy, Sz = work.T
        # int z_e dA over each wet section, z_e = h - sin(theta) x + cos(theta) (sin(phi) y + cos(phi) z)
        zint = A * (h - st * xs) + ct * (sp * Sy + cp * Sz)
        potential = m * g * s[K.S_Z] - rho * g * float(np.sum(dx * zint))
        v = s[K.S_RATE:K.S_RATE + 6]
        pd, td, yd = v[3], v[4], v[5]
        w = np.array([pd - st * yd, cp * td + sp * ct * yd, -sp * td + cp * ct * yd])
        kinetic = 0.5 * m * float(v[:3] @ v[:3]) + 0.5 * float(w @ inertia @ w) + 0.5 * float(v @ added @ v)
        out[n] = kinetic + potential
    return out


def lateral_specific_force(states: np.ndarray, dt: float, height: float, g: float = G) -> np.ndarray:
    """Lateral specific force [m/s^2] (what a transverse accelerometer reads, body +y, to port) at a
    point on the centreline ``height`` [m] above G, along a 3-DOF record. Heeled starboard down
    (phi > 0) its gravity part points to the raised side; the pull the crew feels is its opposite.
    Sway is held in the 3-DOF records: a free ship's sway acceleration, which in long beam waves
    partly cancels the g sin(phi) term, is not in it (an overestimate at low encounter frequency; at
    the roll resonance the sign of the difference is not assured).

    With surge, sway and yaw held the body rate is (phi', theta' cos(phi), -theta' sin(phi)) and G
    moves vertically, so the body-y component of a_P - g at r = (0, 0, h) is

        f_y = (g + z'') cos(theta) sin(phi) - h phi'' - h theta'^2 sin(phi) cos(phi)

    (rigid-body kinematics a_P = a_G + w' x r + w x (w x r)); for small harmonic roll of frequency w
    this is (g + w^2 h) phi, the level-2 linear estimate. The accelerations phi'' and z'' are
    second-order central differences of the state's rates (one-sided at the ends).

    Parameters
    ----------
    states : array (n, N_STATE)
        States every ``dt`` [s] (``S_*`` positions of :mod:`stabflow.dynamics._kernels`).
    """
    phi = states[:, K.S_ROLL]
    theta = states[:, K.S_PITCH]
    rate = states[:, K.S_RATE:K.S_RATE + 6]
    if len(phi) < 2:
        return (g * np.cos(theta) * np.sin(phi)).astype(float)
    acc_roll = np.gradient(rate[:, K.S_ROLL], dt)
    acc_heave = np.gradient(rate[:, K.S_Z], dt)
    return ((g + acc_heave) * np.cos(theta) * np.sin(phi) - height * acc_roll
            - height * rate[:, K.S_PITCH] ** 2 * np.sin(phi) * np.cos(phi))
