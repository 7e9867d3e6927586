"""Linear frequency-domain solution of the same 3-DOF equations (verification of the time domain).

[-we^2 (M + A) + i we B + C] X = F_FK, with C the hydrostatic stiffness matrix (heave, roll,
pitch, by central differences of the FK+HS kernel in calm water, so couplings C35/C53 included)
and F_FK the first harmonic of the Froude-Krylov loads on the ship held at equilibrium in the
wave, from the pressure-integration reference with the decay switched off.
"""

from __future__ import annotations

import numpy as np

from stabflow.constants import G
from stabflow.dynamics._kernels import _fkhs
from stabflow.dynamics.tables import kernel_args
from stabflow.dynamics.rao import first_harmonic


def stiffness_matrix(sec, rho, xg, zg, h0, th0, step: float = 1e-5) -> np.ndarray:
    """3x3 restoring matrix of (heave, roll, pitch) about the calm-water equilibrium (h0 [m], th0
    [rad]) by central differences of the FK+HS kernel with ``step`` [m or rad]: rows (Fz, Mx, My),
    columns (h, phi, theta); units N/m, N/rad, N m/m, N m/rad."""
    w = np.zeros((len(sec.x), 2))
    f = np.empty(6)
    C = np.empty((3, 3))
    e = step
    base = np.array([h0, 0.0, th0])
    for j in range(3):
        loads = []
        for sgn in (1, -1):
            q = base.copy()
            q[j] += sgn * e
            _fkhs(*kernel_args(sec), rho, G, xg, zg, q[0], q[1], q[2], 1.0, 0.0, w, f, np.empty((len(sec.x), 5)))
            loads.append(np.array([f[2], f[3], f[4]]))
        C[:, j] = -(loads[0] - loads[1]) / (2 * e)
    return C


def fk_excitation(model, h0, th0, we, n=64) -> np.ndarray:
    """Complex FK amplitudes (Fz, Mx, My) on the fixed ship over one encounter period."""
    Te = 2 * np.pi / we
    t = np.arange(n) * Te / n
    L = np.array([model.loads(tt, h0, 0.0, th0)[[2, 3, 4]] for tt in t])
    out = np.empty(3, complex)
    for j in range(3):
        amp, ph = first_harmonic(t, L[:, j], we)
        out[j] = amp * np.exp(1j * ph)
    return out


def linear_response(co, C, F, we) -> np.ndarray:
    """Complex (heave, roll, pitch) amplitudes; roll damping linear only (small amplitude)."""
    M = np.diag([co.mass + co.a33, co.i44 + co.a44, co.i55 + co.a55])
    B = np.diag([co.b33, co.b44, co.b55])
    return np.linalg.solve(-we**2 * M + 1j * we * B + C, F)
