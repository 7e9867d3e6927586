"""Hull ingestion: analytic forms, offsets tables and meshes → stations and Bonjean tables."""

from __future__ import annotations

import numpy as np
import xarray as xr

from .. import StabflowError
from ..config import Ship
from .analytic import box_contour, wigley_contour
from .mesh import cut_loops, cut_segments, load_mesh
from .offsets import offsets_contour, read_offsets
from .sections import Sections, apply_topside, check_contour, envelope_contour, loop_contour, sections_dataset

__all__ = ["build_hull", "Sections"]


def _stations(x0: float, x1: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Station positions at the centres of ``n`` equal slabs between x0 and x1."""
    dx = (x1 - x0) / n
    return x0 + dx * (np.arange(n) + 0.5), np.full(n, dx)


def build_hull(ship: Ship) -> xr.Dataset:
    """Cut the ship's hull into stations and tabulate each section.

    Parameters
    ----------
    ship : Ship
        Validated ship configuration.

    Returns
    -------
    xarray.Dataset
        Dimensions ``station`` and ``point``: half contours ``y``, ``z`` [m], Bonjean tables
        ``bonjean_area`` [m^2], ``bonjean_moment_y``/``bonjean_moment_z`` [m^3], slab lengths ``dx`` [m].
    """
    h = ship.hull
    n = int(h["stations"])
    src = h["source"]
    attrs = {"ship": ship.name, "hull_source": src, "stations": n}
    if src == "box":
        L = h["length"]
        xs, dx = _stations(-0.5 * L, 0.5 * L, n)
        contours = [box_contour(x, L, h["breadth"], h["depth"]) for x in xs]
    elif src == "wigley":
        L = h["length"]
        xs, dx = _stations(-0.5 * L, 0.5 * L, n)
        contours = [wigley_contour(x, L, h["breadth"], h["depth"], h["design_draft"]) for x in xs]
    elif src == "offsets":
        path = ship.hull_file()
        ox, rows = read_offsets(path)
        tr = h.get("transform", {})
        s = tr.get("scale", 1.0)
        t = tr.get("translate", [0.0, 0.0, 0.0])
        ox = ox * s + t[0]
        rows = [np.column_stack([r[:, 0] * s + t[2], r[:, 1] * s]) for r in rows]
        xs, dx = _stations(ox[0], ox[-1], n)
        contours = [offsets_contour(x, ox, rows) for x in xs]
        attrs["hull_file"] = path.name
    else:  # mesh
        path = ship.hull_file()
        tr = h.get("transform", {})
        mesh = load_mesh(path, tr.get("scale", 1.0), tr.get("flip_z", False), tr.get("translate", [0.0, 0.0, 0.0]))
        lo, hi = mesh.bounds
        xs, dx = _stations(lo[0], hi[0], n)
        tol = 1e-4 * (hi[1] - lo[1])
        contours = []
        for x in xs:
            c = loop_contour(cut_loops(mesh, x), tol)
            if c is None:  # no loop reaches the centreline: fall back to the half-breadth envelope
                c = envelope_contour(cut_segments(mesh, x), tol)
            if c is None:
                raise StabflowError(f"{path}: station at x = {x:.3f} m cuts no part of the mesh")
            contours.append(c)
        attrs["hull_file"] = path.name
        attrs["mesh_watertight"] = int(mesh.is_watertight)
    if "topside" in h:
        ts = h["topside"]
        contours = [apply_topside(c, ts["z_start"], ts["angle"]) for c in contours]
    for x, c in zip(xs, contours):
        check_contour(c, f"{ship.path}: hull station x = {x:.3f} m")
    ds = sections_dataset(xs, dx, contours, attrs)
    if not ds["hull_volume"] > 0:
        raise StabflowError(f"{ship.path}: hull: the sections enclose no volume")
    return ds
