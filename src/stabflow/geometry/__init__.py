"""Hull ingestion: analytic forms, offsets tables and meshes → stations and Bonjean tables."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow import StabflowError
from stabflow.config import Ship
from stabflow.geometry.analytic import box_contour, wigley_contour
from stabflow.geometry.mesh import cut_loops, cut_segments, ship_mesh
from stabflow.geometry.offsets import offsets_contour, read_offsets
from stabflow.geometry.sections import Sections, apply_topside, check_contour, envelope_contour, loop_contour, sections_dataset

__all__ = ["build_hull", "Sections"]


def _stations(x0: float, x1: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Station positions at the centres of ``n`` equal slabs between x0 and x1."""
    dx = (x1 - x0) / n
    return x0 + dx * (np.arange(n) + 0.5), np.full(n, dx)


#: allowed distance of the keel (lowest point of the middle half of the length) from the
#: baseline z = 0, as a fraction of the hull depth (keel drag, rounding of the midship section)
KEEL_TOLERANCE = 0.05


def check_frame(ship: Ship, lo, hi, keel: float) -> None:
    """Check that the transformed hull lies in ship axes (origin midships on the baseline, z up).

    ``lo``, ``hi`` are the hull's bounds (x, y, z) [m]; ``keel`` the lowest z [m] over the middle
    half of its length (a sonar dome or a skeg may reach below the baseline, the keel amidships
    may not).

    A mesh in millimetres, a missing or wrong ``flip_z`` or a forgotten ``translate`` give a hull
    whose keel is not on z = 0, whose x range misses midships, or whose depth makes the loading
    absurd (a 6 m draft on a 13,000 m deep "hull"). Such a hull would still float numerically
    (KB = -225 m, GM = -180 m), so it is rejected here with what was found.

    Raises
    ------
    StabflowError
        ``"<ship file>: hull.transform: ..."``.
    """
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    depth = hi[2] - lo[2]
    where = f"{ship.path}: hull.transform"
    found = (f"after the transform the hull spans x {lo[0]:.4g} to {hi[0]:.4g} m, z {lo[2]:.4g} to {hi[2]:.4g} m "
             "(check scale, flip_z and translate: ship axes have z up, the keel on z = 0, x = 0 midships)")
    if depth <= 0:
        raise StabflowError(f"{where}: the hull has no height; {found}")
    if abs(keel) > KEEL_TOLERANCE * depth:
        raise StabflowError(f"{where}: the keel amidships (lowest point of the middle half of the length) is at "
                            f"z = {keel:.4g} m, not on the baseline z = 0; {found}")
    if not lo[0] < 0.0 < hi[0]:
        raise StabflowError(f"{where}: x = 0 (midships) is outside the hull; {found}")
    # a loading that no ship of this depth has means the hull is mis-scaled (or the loading belongs
    # to another hull): a draft under 2 % of the depth, a KG outside 5-150 % of it
    ld = ship.loading
    odd = []
    if "draft" in ld and ld["draft"] < 0.02 * depth:
        odd.append(f"loading.draft {ld['draft']:g} m is {100 * ld['draft'] / depth:.2g} % of it")
    if not 0.05 * depth <= ld["kg"] <= 1.5 * depth:
        odd.append(f"loading.kg {ld['kg']:g} m is {100 * ld['kg'] / depth:.2g} % of it")
    if odd:
        raise StabflowError(f"{where}: a hull {depth:.4g} m deep makes the loading implausible ({'; '.join(odd)}); {found}")


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
        zall = np.concatenate([r[:, 0] for r in rows])
        mid = np.abs(ox - 0.5 * (ox[0] + ox[-1])) <= 0.25 * (ox[-1] - ox[0])
        keel = min(r[:, 0].min() for r, m in zip(rows, mid) if m) if mid.any() else zall.min()
        check_frame(ship, [ox[0], 0.0, zall.min()], [ox[-1], 0.0, zall.max()], keel)
        xs, dx = _stations(ox[0], ox[-1], n)
        contours = [offsets_contour(x, ox, rows) for x in xs]
        attrs["hull_file"] = path.name
    else:  # mesh
        path = ship.hull_file()
        mesh = ship_mesh(ship)
        lo, hi = mesh.bounds
        v = mesh.vertices
        mid = np.abs(v[:, 0] - 0.5 * (lo[0] + hi[0])) <= 0.25 * (hi[0] - lo[0])
        check_frame(ship, lo, hi, float(v[mid, 2].min()) if mid.any() else float(lo[2]))
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
