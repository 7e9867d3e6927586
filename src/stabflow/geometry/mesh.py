"""Mesh (STL, optionally gzip-compressed) input: load, transform, cut stations."""

from __future__ import annotations

import gzip
import io
import warnings
from pathlib import Path

import numpy as np
import trimesh

from stabflow import StabflowError


def load_mesh(path: str | Path, scale: float = 1.0, flip_z: bool = False, translate=(0.0, 0.0, 0.0)) -> trimesh.Trimesh:
    """Load an STL (``.stl`` or ``.stl.gz``) and bring it to ship axes.

    ``flip_z`` turns a north-east-down mesh (z down) into x forward, y port, z up by negating
    y and z (a rotation of 180 deg about x, so the mesh keeps its handedness).
    """
    path = Path(path)
    if not path.is_file():
        raise StabflowError(f"{path}: mesh file not found")
    raw = path.read_bytes()
    if not raw:
        raise StabflowError(f"{path}: mesh file is empty")
    if path.suffix == ".gz":
        try:
            raw = gzip.decompress(raw)
        except OSError as exc:
            raise StabflowError(f"{path}: not a valid gzip file ({exc})") from exc
    try:
        mesh = trimesh.load(io.BytesIO(raw), file_type="stl", process=True)
    except Exception as exc:  # trimesh raises many kinds
        raise StabflowError(f"{path}: cannot read STL ({exc})") from exc
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise StabflowError(f"{path}: mesh has no triangles")
    v = np.array(mesh.vertices, dtype=np.float64)
    if not np.all(np.isfinite(v)):
        raise StabflowError(f"{path}: mesh has NaN or infinite vertices")
    if flip_z:
        v[:, 1:] *= -1.0
    v = v * scale + np.asarray(translate, dtype=np.float64)
    out = trimesh.Trimesh(vertices=v, faces=mesh.faces, process=False)
    # normals pointing into the hull give a negative enclosed volume: the references that integrate
    # over the surface (mesh GZ, pressure integration, Capytaine) need them outward (the stations
    # are cut from the surface and do not depend on it)
    if out.volume < 0:
        warnings.warn(f"{path}: mesh normals point inward (enclosed volume {out.volume:.4g} m3): faces reversed",
                      stacklevel=2)
        out.invert()
    return out


def ship_mesh(ship) -> trimesh.Trimesh:
    """The mesh of a ``source: mesh`` ship (``stabflow.config.Ship``) in ship axes, after the
    config's ``hull.transform`` (flip, scale, shift)."""
    tr = ship.hull.get("transform", {})
    return load_mesh(ship.hull_file(), tr.get("scale", 1.0), tr.get("flip_z", False), tr.get("translate", [0.0, 0.0, 0.0]))


def cut_segments(mesh: trimesh.Trimesh, x: float) -> np.ndarray:
    """(m, 2, 2) (y, z) segments of the mesh cut by the plane at ``x``."""
    segs = trimesh.intersections.mesh_plane(mesh, plane_normal=[1.0, 0.0, 0.0], plane_origin=[x, 0.0, 0.0])
    segs = np.asarray(segs, dtype=np.float64)
    if segs.size == 0:
        return np.zeros((0, 2, 2))
    return segs[:, :, 1:3]


def cut_loops(mesh: trimesh.Trimesh, x: float) -> list[np.ndarray]:
    """Section polylines (y, z) of the mesh cut by the plane at ``x`` (open ones left open)."""
    path = mesh.section(plane_origin=[x, 0.0, 0.0], plane_normal=[1.0, 0.0, 0.0])
    if path is None:
        return []
    return [np.asarray(d, dtype=np.float64)[:, 1:3] for d in path.discrete]
