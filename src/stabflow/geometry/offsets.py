"""Offsets-table input.

Format (CSV, ``#`` comments allowed): one row per station,

    x, z1, y1, z2, y2, ..., zn, yn

x: station position [m] (strictly increasing down the file); then pairs of height above baseline
z [m] and half-breadth y >= 0 [m] from the keel up to the deck edge, z non-decreasing. Rows may have
different numbers of pairs. The deck is closed horizontally from the last point to the centreline.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stabflow import StabflowError


def read_offsets(path: str | Path) -> tuple[np.ndarray, list[np.ndarray]]:
    """Read and check an offsets CSV; return station x and (z, y) pair arrays per station."""
    path = Path(path)
    if not path.is_file():
        raise StabflowError(f"{path}: offsets file not found")
    xs, rows = [], []
    for lineno, line in enumerate(path.read_text().splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        try:
            vals = [float(v) for v in line.replace(";", ",").split(",") if v.strip() != ""]
        except ValueError as exc:
            raise StabflowError(f"{path}: line {lineno}: not a number ({exc})") from exc
        where = f"{path}: line {lineno}"
        if len(vals) < 5 or (len(vals) - 1) % 2:
            raise StabflowError(f"{where}: need x then at least two (z, half-breadth) pairs")
        arr = np.array(vals)
        if not np.all(np.isfinite(arr)):
            raise StabflowError(f"{where}: NaN or infinite value")
        zy = arr[1:].reshape(-1, 2)
        if np.any(zy[:, 1] < 0):
            raise StabflowError(f"{where}: negative half-breadth")
        if np.any(np.diff(zy[:, 0]) < 0):
            raise StabflowError(f"{where}: heights z must not decrease from keel to deck")
        if xs and arr[0] <= xs[-1]:
            raise StabflowError(f"{where}: station x = {arr[0]} is not after the previous x = {xs[-1]} (stations must increase)")
        xs.append(arr[0])
        rows.append(zy)
    if len(xs) < 2:
        raise StabflowError(f"{path}: need at least two stations, found {len(xs)}")
    return np.array(xs), rows


def offsets_contour(x: float, xs: np.ndarray, rows: list[np.ndarray]) -> np.ndarray:
    """Half contour at ``x`` by linear interpolation in x of the tabulated half-breadths y(z)."""
    j = int(np.clip(np.searchsorted(xs, x) - 1, 0, len(xs) - 2))
    w = (x - xs[j]) / (xs[j + 1] - xs[j])
    r0, r1 = rows[j], rows[j + 1]
    z0 = (1 - w) * r0[0, 0] + w * r1[0, 0]
    z1 = (1 - w) * r0[-1, 0] + w * r1[-1, 0]

    def on(r, zq):
        # map onto each row's own keel-deck span so the profile morphs smoothly
        s = (zq - z0) / max(z1 - z0, 1e-12)
        zr = r[0, 0] + s * (r[-1, 0] - r[0, 0])
        return np.interp(zr, r[:, 0], r[:, 1])

    s0 = (r0[:, 0] - r0[0, 0]) / max(r0[-1, 0] - r0[0, 0], 1e-12)
    s1 = (r1[:, 0] - r1[0, 0]) / max(r1[-1, 0] - r1[0, 0], 1e-12)
    s = np.unique(np.concatenate([s0, s1]))
    z = z0 + s * (z1 - z0)
    y = (1 - w) * on(r0, z) + w * on(r1, z)
    pts = np.column_stack([y, z])
    return np.vstack([[[0.0, z0]], pts, [[0.0, z1]]])
