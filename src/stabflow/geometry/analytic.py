"""Analytic hull forms: rectangular barge and Wigley hull."""

from __future__ import annotations

import numpy as np


def box_contour(x: float, length: float, breadth: float, depth: float) -> np.ndarray:
    """Half contour of a rectangular barge section [m]."""
    h = 0.5 * breadth
    return np.array([[0.0, 0.0], [h, 0.0], [h, depth], [0.0, depth]])


def wigley_contour(x: float, length: float, breadth: float, depth: float, draft: float, nz: int = 24) -> np.ndarray:
    """Half contour of the Wigley hull at ``x`` (origin midships).

    y = B/2 (1 - (2x/L)^2) (1 - ((T - z)/T)^2) for 0 <= z <= T; wall-sided from T up to the deck.
    Points cluster near the keel where the section curves most.
    """
    xi = 2.0 * x / length
    yx = 0.5 * breadth * max(1.0 - xi * xi, 0.0)
    s = np.linspace(0.0, 1.0, nz)
    z = draft * (1.0 - np.cos(0.5 * np.pi * s))  # denser at the keel
    y = yx * (1.0 - ((draft - z) / draft) ** 2)
    pts = np.column_stack([y, z])
    pts = np.vstack([[[0.0, 0.0]], pts[1:], [[yx, depth], [0.0, depth]]])
    return pts
