"""NetCDF output: one table of CF attributes and atomic writing."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

#: name -> (units, long_name). Every variable stabflow writes takes its attributes from here.
CF_ATTRS: dict[str, tuple[str, str]] = {
    # hull
    "station": ("1", "station index"),
    "point": ("1", "contour point index"),
    "x": ("m", "station longitudinal position from midships, positive forward"),
    "dx": ("m", "station slab length"),
    "n_points": ("1", "number of points in the half contour"),
    "y": ("m", "half-contour transverse offset (half-breadth), positive to port"),
    "z": ("m", "half-contour height above baseline"),
    "bonjean_area": ("m2", "half-section area below the horizontal waterline through the point"),
    "bonjean_moment_y": ("m3", "first moment of that half-section area about the centreline"),
    "bonjean_moment_z": ("m3", "first moment of that half-section area about the baseline"),
    "section_area_full": ("m2", "full section area to the deck"),
    # statics
    "heel": ("degree", "heel angle, positive starboard down"),
    "gz": ("m", "righting arm GZ, free trim"),
    "draft_mid": ("m", "draft at midships, earth-vertical, from the baseline"),
    "trim": ("rad", "trim angle at each heel (free trim), positive bow down"),
    "trim_upright": ("rad", "trim angle of the upright equilibrium, positive bow down"),
    "heave": ("m", "earth height of the body origin (midships, baseline) above calm water"),
    "volume": ("m3", "displaced volume"),
    "mass": ("kg", "displacement mass"),
    "lcb": ("m", "longitudinal centre of buoyancy from midships, positive forward"),
    "lcg": ("m", "longitudinal centre of gravity from midships, positive forward"),
    "kb": ("m", "vertical centre of buoyancy above baseline"),
    "kg": ("m", "vertical centre of gravity above baseline"),
    "bm": ("m", "transverse metacentric radius"),
    "km": ("m", "transverse metacentre above baseline"),
    "gm": ("m", "transverse metacentric height, fluid-free"),
    "gm_from_gz_slope": ("m", "GM from the slope of the computed GZ curve at zero heel"),
    "waterplane_area": ("m2", "waterplane area"),
    "gz_max": ("m", "maximum righting arm"),
    "heel_gz_max": ("degree", "heel angle of the maximum righting arm"),
    "heel_vanishing": ("degree", "angle of vanishing stability"),
    "hull_volume": ("m3", "total enclosed hull volume to the deck"),
}


def cf(da: xr.DataArray, name: str | None = None) -> xr.DataArray:
    """Attach ``units`` and ``long_name`` from :data:`CF_ATTRS` to ``da``."""
    key = name or da.name
    units, long_name = CF_ATTRS[key]
    da.attrs.update(units=units, long_name=long_name)
    return da


def annotate(ds: xr.Dataset) -> xr.Dataset:
    """Attach CF attributes to every variable and coordinate of ``ds`` found in the table."""
    for name in list(ds.variables):
        if name in CF_ATTRS:
            units, long_name = CF_ATTRS[name]
            ds[name].attrs.update(units=units, long_name=long_name)
    return ds


def write_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file in the same folder, then rename).

    The history/date attributes are left out so the same inputs give bit-identical files.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4")
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def atomic_savefig(fig, path: str | Path, **kw) -> Path:
    """Save a matplotlib figure atomically; metadata stripped for reproducible files."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        meta = {"Software": None} if path.suffix == ".png" else {"Date": None}
        fig.savefig(tmp, metadata=meta, **kw)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def as_float(a) -> np.ndarray:
    """Contiguous float64 copy of ``a``."""
    return np.ascontiguousarray(a, dtype=np.float64)
