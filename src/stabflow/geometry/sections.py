"""Half contours of hull sections and their Bonjean tables.

A half contour is an (n, 2) array of (y, z) points, y >= 0, starting on the centreline at the
lowest point of the section, running up the port side and ending on the centreline at the deck.
The closing segment down the centreline is implicit.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow import StabflowError
from stabflow.geometry._kernels import _clip_half
from stabflow.io import annotate


def envelope_contour(segments: np.ndarray, tol: float) -> np.ndarray | None:
    """Half contour from the outer half-breadth envelope of a cut through a mesh.

    Parameters
    ----------
    segments : ndarray, shape (m, 2, 2)
        Section line segments as (y, z) end points [m].
    tol : float
        Simplification tolerance [m] (Douglas-Peucker on the contour).

    Returns
    -------
    ndarray (n, 2) or None if the cut is empty.
    The envelope y(z) = max(0, max y over the cut at height z) is piecewise linear between
    the vertex heights; it is sampled just below and just above each vertex height so the
    contour is exact (gaps between a bulb and the hull give y = 0).
    """
    if segments.shape[0] == 0:
        return None
    ya, za = segments[:, 0, 0], segments[:, 0, 1]
    yb, zb = segments[:, 1, 0], segments[:, 1, 1]
    levels = np.unique(np.round(np.concatenate([za, zb]), 9))
    if levels.size < 2:
        return None
    zlo = np.minimum(za, zb)
    zhi = np.maximum(za, zb)
    span = levels[-1] - levels[0]
    eps = 1e-7 * max(span, 1e-3)

    def ymax(z):
        inside = (zlo[None, :] < z[:, None]) & (zhi[None, :] > z[:, None])
        with np.errstate(invalid="ignore", divide="ignore"):
            t = (z[:, None] - za[None, :]) / (zb - za)[None, :]
        y = np.where(inside, ya[None, :] + t * (yb - ya)[None, :], -np.inf)
        return np.maximum(y.max(axis=1), 0.0)

    below = ymax(levels - eps)
    above = ymax(levels + eps)
    pts = [(0.0, levels[0])]
    for k, z in enumerate(levels):
        if k > 0:
            pts.append((below[k], z))
        if k < levels.size - 1 and (k == 0 or abs(above[k] - below[k]) > 1e-9):
            pts.append((above[k], z))
    pts.append((0.0, levels[-1]))
    return simplify(np.array(pts), tol)


def _clip_y_positive(p: np.ndarray) -> np.ndarray:
    """Sutherland-Hodgman clip of a closed polygon (k, 2) to y >= 0."""
    out = []
    n = len(p)
    for k in range(n):
        a, b = p[k - 1], p[k]
        ina, inb = a[0] >= 0, b[0] >= 0
        if ina != inb:
            t = a[0] / (a[0] - b[0])
            out.append((0.0, a[1] + t * (b[1] - a[1])))
        if inb:
            out.append((max(b[0], 0.0), b[1]))
    return np.array(out) if out else np.zeros((0, 2))


def loop_contour(loops: list[np.ndarray], tol: float) -> np.ndarray | None:
    """Half contour that follows the true section boundary (cambered decks, bulbs, domes).

    Parameters
    ----------
    loops : list of ndarray (k, 2)
        Section polylines as (y, z); open ones (open-deck meshes) are closed by the straight
        deck line joining their ends.
    tol : float
        Douglas-Peucker tolerance [m].

    Each loop that reaches the centreline is clipped to y >= 0, oriented counter-clockwise and
    started at its lowest centreline point, so it runs keel → side → deck → centreline. Several
    such loops (e.g. a dome below the hull) are chained in height order: the joins run along the
    centreline, where they add no area or moment. Returns None if no loop reaches the centreline.
    """
    halves = []
    for lp in loops:
        lp = np.asarray(lp, dtype=np.float64)
        if len(lp) > 1 and np.allclose(lp[0], lp[-1]):
            lp = lp[:-1]
        if len(lp) < 3 or lp[:, 0].min() > 0 or lp[:, 0].max() <= 0:
            continue
        h = _clip_y_positive(lp)
        if len(h) < 3:
            continue
        area2 = np.sum(h[:, 0] * np.roll(h[:, 1], -1) - np.roll(h[:, 0], -1) * h[:, 1])
        if area2 < 0:
            h = h[::-1]
        on_cl = np.abs(h[:, 0]) < 1e-9
        # start at the lowest point on the centreline
        cand = np.flatnonzero(on_cl)
        start = cand[np.argmin(h[cand, 1])]
        h = np.roll(h, -start, axis=0)
        # the contour ends at the highest centreline point reached going round
        on_cl = np.abs(h[:, 0]) < 1e-9
        cand = np.flatnonzero(on_cl)
        end = cand[np.argmax(h[cand, 1])]
        h = h[: end + 1]
        if len(h) >= 3 and abs(area2) > 0:
            halves.append(h)
    if not halves:
        return None
    halves.sort(key=lambda c: c[0, 1])
    return simplify(np.vstack(halves), tol)


def simplify(pts: np.ndarray, tol: float) -> np.ndarray:
    """Douglas-Peucker simplification keeping the end points; drops duplicate points."""
    keep = np.zeros(len(pts), bool)
    keep[[0, -1]] = True
    stack = [(0, len(pts) - 1)]
    while stack:
        i, j = stack.pop()
        if j <= i + 1:
            continue
        p, q = pts[i], pts[j]
        d = q - p
        nrm = np.hypot(*d)
        seg = pts[i + 1 : j] - p
        if nrm > 0:
            dist = np.abs(seg[:, 0] * d[1] - seg[:, 1] * d[0]) / nrm
        else:
            dist = np.hypot(seg[:, 0], seg[:, 1])
        k = int(np.argmax(dist))
        if dist[k] > tol:
            keep[i + 1 + k] = True
            stack += [(i, i + 1 + k), (i + 1 + k, j)]
    out = pts[keep]
    dup = np.r_[False, np.all(np.abs(np.diff(out, axis=0)) < 1e-12, axis=1)]
    return out[~dup]


def apply_topside(contour: np.ndarray, z_start: float, angle_deg: float) -> np.ndarray:
    """Replace the side above ``z_start`` by a straight topside at ``angle_deg`` from vertical.

    Above z_start the half-breadth is y(z) = y(z_start) + (z - z_start) tan(angle), >= 0, up to the
    section's own deck height: positive angles flare outward, negative give tumblehome. A section
    that does not reach down to z_start (overhangs at the ends) has y(z_start) = 0, so the rule is
    continuous along the ship.
    """
    y, z = contour[:, 0], contour[:, 1]
    ztop = z[-1]
    if z_start >= ztop:
        return contour
    t = np.tan(np.radians(angle_deg))
    side_y, side_z = y[:-1], z[:-1]  # exclude the closing centreline deck point
    if z_start <= z[0]:
        y0 = 0.0
        lower = np.array([[0.0, z_start]])
    else:
        k = int(np.searchsorted(side_z, z_start, side="right"))
        y0 = float(np.interp(z_start, side_z, side_y)) if k < len(side_z) else float(side_y[-1])
        lower = np.vstack([contour[:k][contour[:k, 1] < z_start], [[y0, z_start]]])
    ydeck = max(y0 + (ztop - z_start) * t, 0.0)
    if ydeck == 0.0 and y0 == 0.0:  # tumblehome on a section with no breadth at z_start: nothing above
        new = lower if len(lower) > 1 else np.array([[0.0, z_start], [0.0, z_start + 1e-9]])
        return simplify(new, 0.0) if len(new) > 2 else new
    new = np.vstack([lower, [[ydeck, ztop], [0.0, ztop]]])
    return simplify(new, 0.0)


def bonjean(contour: np.ndarray) -> np.ndarray:
    """Bonjean table of a half contour: (n, 3) area, moment about CL, moment about baseline.

    Row j is the y > 0 half-section below the horizontal waterline through point j [m^2, m^3, m^3].
    """
    ys = np.ascontiguousarray(contour[:, 0])
    zs = np.ascontiguousarray(contour[:, 1])
    return np.array([_clip_half(ys, zs, len(ys), 0.0, 1.0, zj) for zj in zs])


def check_contour(contour: np.ndarray, where: str) -> None:
    """Raise :class:`StabflowError` for a contour that cannot describe a half section."""
    if not np.all(np.isfinite(contour)):
        raise StabflowError(f"{where}: NaN or infinite offsets")
    if np.any(contour[:, 0] < 0):
        raise StabflowError(f"{where}: negative half-breadth")


def sections_dataset(xs: np.ndarray, dx: np.ndarray, contours: list[np.ndarray], attrs: dict) -> xr.Dataset:
    """Assemble the hull NetCDF content: padded contours and Bonjean tables per station."""
    n = np.array([len(c) for c in contours], dtype=np.int32)
    npmax = int(n.max())
    Y = np.full((len(xs), npmax), np.nan)
    Z = np.full((len(xs), npmax), np.nan)
    B = np.full((len(xs), npmax, 3), np.nan)
    full = np.zeros(len(xs))
    for i, c in enumerate(contours):
        Y[i, : n[i]] = c[:, 0]
        Z[i, : n[i]] = c[:, 1]
        B[i, : n[i]] = bonjean(c)
        full[i] = 2.0 * B[i, n[i] - 1, 0]
    ds = xr.Dataset(
        {
            "dx": ("station", dx),
            "n_points": ("station", n),
            "y": (("station", "point"), Y),
            "z": (("station", "point"), Z),
            "bonjean_area": (("station", "point"), B[..., 0]),
            "bonjean_moment_y": (("station", "point"), B[..., 1]),
            "bonjean_moment_z": (("station", "point"), B[..., 2]),
            "section_area_full": ("station", full),
        },
        coords={"x": ("station", xs)},
        attrs=attrs,
    )
    ds["hull_volume"] = float((full * dx).sum())
    return annotate(ds)


class Sections:
    """Kernel-ready arrays of a hull dataset (contours padded, float64, contiguous)."""

    def __init__(self, ds: xr.Dataset):
        self.x = np.ascontiguousarray(ds["x"].values, dtype=np.float64)
        self.dx = np.ascontiguousarray(ds["dx"].values, dtype=np.float64)
        self.n = np.ascontiguousarray(ds["n_points"].values, dtype=np.int64)
        self.y = np.ascontiguousarray(np.nan_to_num(ds["y"].values), dtype=np.float64)
        self.z = np.ascontiguousarray(np.nan_to_num(ds["z"].values), dtype=np.float64)
        self.hull_volume = float(ds["hull_volume"])
        self.length = float(self.x[-1] - self.x[0] + 0.5 * (self.dx[0] + self.dx[-1]))
        self.breadth = 2.0 * float(np.nanmax(ds["y"].values))
        self.depth = float(np.nanmax(ds["z"].values))

    def args(self):
        return self.x, self.dx, self.y, self.z, self.n

    def half_breadth(self, i: int, zw: float) -> float:
        """Half-breadth of station ``i`` at height ``zw`` (outermost crossing) [m]."""
        n = self.n[i]
        y, z = self.y[i, :n], self.z[i, :n]
        best = 0.0
        for k in range(n - 1):
            z0, z1 = z[k], z[k + 1]
            if (z0 - zw) * (z1 - zw) <= 0 and z0 != z1:
                t = (zw - z0) / (z1 - z0)
                best = max(best, y[k] + t * (y[k + 1] - y[k]))
        return best
