"""Ship axes and their rotation into earth axes (x forward, y to port, z up; heel phi positive
starboard down, trim theta positive bow down). The one rotation of the package: the numba kernels
call ``_rotate`` directly, Python code calls :func:`earth_vertices`."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def _rotate(bx, by, bz, cp, sp, ct, st):
    """Body → earth axes, R = Ry(theta) Rx(phi), with cp, sp = cos, sin(phi) and ct, st =
    cos, sin(theta); scalars or arrays."""
    y1 = cp * by - sp * bz
    z1 = sp * by + cp * bz
    return ct * bx + st * z1, y1, -st * bx + ct * z1


def earth_vertices(vertices: np.ndarray, phi: float, theta: float, h: float) -> np.ndarray:
    """Body → earth coordinates [m] of points (n, 3), rotation R = Ry(theta) Rx(phi), body origin at
    height h [m] above the calm water; angles [rad]."""
    x, y, z = np.ascontiguousarray(np.asarray(vertices, dtype=np.float64).T)
    ex, ey, ez = _rotate(x, y, z, np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta))
    return np.column_stack([ex, ey, ez + h])
