"""Sectional property tables for fast time-domain simulation.

The FK + HS kernel needs, per station and time step, the area and first moments of the section
below an inclined waterline. Exact clipping costs O(contour points); for long ensembles stabflow
tabulates them once per station over the waterline's normal angle psi (effective heel, 0-180 deg,
symmetry gives negative angles) and its distance d from the section origin (between fully dry and
fully wet), and reads them by bilinear interpolation. The tables are built by the same exact
clipping, so they converge to it as the grid is refined (tests compare both).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stabflow.geometry import Sections
from stabflow.dynamics._kernels import _build_tables


@dataclass(frozen=True)
class SectionTables:
    """``tab`` (nst, npsi, nu, 3): area [m^2], int y dA, int z dA [m^3]; ``lim`` (nst, npsi, 3): the
    waterline distances [m] where each section starts and stops being wet, and (nu - 1) / span [1/m]."""

    tab: np.ndarray
    lim: np.ndarray

    @classmethod
    def none(cls) -> "SectionTables":
        """No tables: the kernels clip the sections exactly."""
        return cls(np.zeros((0, 2, 2, 3)), np.zeros((0, 2, 3)))


def section_tables(sec: Sections, npsi: int = 361, nu: int = 161) -> SectionTables:
    """Build the tables for ``sec`` on ``npsi`` heel angles (0-180 deg) and ``nu`` waterline levels."""
    nst = len(sec.x)
    tab = np.empty((nst, npsi, nu, 3))
    lim = np.empty((nst, npsi, 3))
    _build_tables(sec.y, sec.z, sec.n, tab, lim)
    return SectionTables(tab, lim)


def kernel_args(sec: Sections, tables: SectionTables | None = None) -> tuple:
    """Geometry arguments of the dynamics kernels: stations, contours and (optional) tables."""
    t = tables or SectionTables.none()
    return (*sec.args(), t.tab, t.lim)
