"""Linear frequency-domain solution of the same 3-DOF equations (verification of the time domain).

[-we^2 (M + A) + i we B + C] X = F_FK in the generalized coordinates of the time domain (heave of
G, roll, pitch; :mod:`stabflow.dynamics.rigid_body`), with C the restoring matrix (central
differences of the generalized FK + HS forces in calm water, so couplings C35/C53 included) and
F_FK the generalized forces of the first harmonic of the Froude-Krylov loads on the ship held at
equilibrium in the wave (the kernel's or the pressure-integration reference's).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from stabflow.constants import G
from stabflow.dynamics import _kernels as K
from stabflow.dynamics.rigid_body import coordinates_from_origin, generalized_loads, generalized_system
from stabflow.dynamics.tables import kernel_args
from stabflow.waves.synthesis import station_wave_table
from stabflow.dynamics.rao import first_harmonic

if TYPE_CHECKING:
    from stabflow.geometry import Sections


class KernelLoads:
    """FK + HS loads of the volume-based kernel (``_fkhs``) on the ship held in the waves.

    Same ``loads(t, h, phi, theta)`` interface as :class:`stabflow.dynamics.pressure.PressureModel`,
    so :func:`stabflow.dynamics.linear.fk_excitation` takes either.

    Parameters
    ----------
    sec : Sections
        The ship's sections.
    rho, xg, zg : float
        Water density [kg/m^3] and centre of gravity (body axes) [m].
    waves : tuple of arrays
        (amp [m], omega [rad/s], phase [rad]) of the components.
    heading_deg, speed : float
        Wave heading [degree] and ship speed [m/s].
    decay : SectionDecay, optional
        The sections' pressure decay for the d2phi/dzdt term
        (:class:`stabflow.dynamics.model.SectionDecay`); None leaves it out (the default model).
    waterline : {"planar", "curved"}
        The wave across each section (:func:`stabflow.dynamics.simulate`).
    """

    def __init__(self, sec: Sections, rho: float, xg: float, zg: float, waves, heading_deg: float,
                 speed: float = 0.0, decay=None, waterline: str = "planar"):
        from stabflow.dynamics.model import _check_waterline

        self.curved = _check_waterline(waterline)
        self.sec, self.rho, self.xg, self.zg = sec, rho, xg, zg
        self.waves, self.heading, self.speed, self.decay = waves, heading_deg, speed, decay
        b = np.radians(heading_deg)
        self.cb, self.sb = np.cos(b), np.sin(b)
        self.args = kernel_args(sec)
        self._out = np.empty(6)
        self._work = np.empty((len(sec.x), 5))

    def loads(self, t: float, h: float, phi: float, theta: float) -> np.ndarray:
        """(Fx, Fy, Fz, Mx, My, Mz) about G in earth axes [N, N m] at time ``t`` [s] for heave ``h``
        [m], roll ``phi`` and pitch ``theta`` [rad] (absolute, as the kernel's state)."""
        w = station_wave_table(*self.waves, self.sec.x, self.heading, self.speed, np.array([float(t)]), self.decay,
                               curvature=self.curved)
        K._fkhs(*self.args, self.rho, G, self.xg, self.zg, h, phi, theta, self.cb, self.sb,
              np.ascontiguousarray(w[0]), self._out, self._work)
        return self._out.copy()


def _rest_parameters(rho, xg, zg) -> np.ndarray:
    """Parameter vector for the generalized forces at rest: only rho, g and G matter there."""
    from stabflow.dynamics.model import ModelParameters

    return ModelParameters(rho=rho, g=G, xg=xg, zg=zg, mass=0.0, b44q=np.zeros(K.N_AMPLITUDES), cos_beta=1.0, sin_beta=0.0,
                           inertia=np.zeros((3, 3)), added_mass=np.zeros((6, 6)), damping=np.zeros((6, 6))).vector()


def stiffness_matrix(sec, rho, xg, zg, h0, th0, step: float = 1e-5) -> np.ndarray:
    """3x3 restoring matrix of the coordinates (heave of G, roll, pitch) about the calm-water
    equilibrium (body origin at h0 [m], trim th0 [rad]) by central differences of the generalized
    FK + HS forces with ``step`` [m or rad]; units N/m, N/rad, N m/m, N m/rad."""
    p = _rest_parameters(rho, xg, zg)
    w = np.zeros((len(sec.x), 2))
    f = np.empty(6)
    work = np.empty((len(sec.x), 5))
    C = np.empty((3, 3))
    base = coordinates_from_origin(h0, 0.0, th0, xg, zg)
    dofs = (K.S_Z, K.S_ROLL, K.S_PITCH)
    for j, d in enumerate(dofs):
        loads = []
        for sgn in (1, -1):
            s = np.zeros(K.N_STATE)
            s[:6] = base
            s[d] += sgn * step
            K._loads(*kernel_args(sec), p, w, s, f, work)
            _, r = generalized_system(p, s, f)
            loads.append(r[list(dofs)])
        C[:, j] = -(loads[0] - loads[1]) / (2 * step)
    return C


def fk_excitation(model, h0, th0, we, n=64) -> np.ndarray:
    """Complex amplitudes of the generalized FK forces (heave, roll, pitch) on the ship held at
    equilibrium (origin height h0 [m], trim th0 [rad]) over one encounter period; ``model`` has
    ``loads(t, h, phi, theta)`` and the centre of gravity ``xg``, ``zg`` [m]."""
    Te = 2 * np.pi / we
    t = np.arange(n) * Te / n
    p = _rest_parameters(1.0, model.xg, model.zg)
    q = coordinates_from_origin(h0, 0.0, th0, model.xg, model.zg)
    L = np.array([generalized_loads(p, q, model.loads(tt, h0, 0.0, th0))[[K.S_Z, K.S_ROLL, K.S_PITCH]] for tt in t])
    out = np.empty(3, complex)
    for j in range(3):
        amp, ph = first_harmonic(t, L[:, j], we)
        out[j] = amp * np.exp(1j * ph)
    return out


def linear_response(co, C, F, we) -> np.ndarray:
    """Complex (heave of G, roll, pitch) amplitudes; roll damping linear only (small amplitude).
    M is diagonal: the generalized mass at the upright equilibrium for a principal-axes inertia
    tensor (E^T I E has no roll-pitch term at zero heel)."""
    M = np.diag([co.mass + co.a33, co.i44 + co.a44, co.i55 + co.a55])
    B = np.diag([co.b33, co.b44, co.b55])
    return np.linalg.solve(-we**2 * M + 1j * we * B + C, F)
