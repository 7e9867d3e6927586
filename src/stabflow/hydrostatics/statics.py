"""Calm-water statics: equilibrium, hydrostatic particulars and the GZ curve (free trim).

Uses the same sectional machinery (``_kernels``) as the time-domain model: the volume and volume
centre of every section up to an inclined waterline (paper 000, section 3 and section 4 "restoring
curve check").
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow import StabflowError
from stabflow.hydrostatics._kernels import WORK_COLUMNS, _equilibrium, _gz_curve, _hydro_state
from stabflow.config import Ship
from stabflow.geometry import Sections
from stabflow.io import annotate

TOL = 1e-11


@dataclass(frozen=True)
class Particulars:
    """The upright particulars that the later steps take together: displaced volume [m^3], LCG and
    KG [m], KM [m], waterline length and breadth [m] (from the statics step's dataset)."""

    volume: float
    lcg: float
    kg: float
    km: float
    lwl: float
    bwl: float

    @classmethod
    def from_statics(cls, st: xr.Dataset) -> "Particulars":
        return cls(*(float(st[k]) for k in ("volume", "lcg", "kg", "km", "lwl", "bwl")))


class StabilityWarning(UserWarning):
    """Legal but noteworthy loading, e.g. negative GM (a lolling ship)."""


def _volume_at(sec: Sections, h: float, theta: float = 0.0, phi: float = 0.0):
    work = np.empty((len(sec.x), WORK_COLUMNS))
    V, _, _ = _hydro_state(*sec.args(), phi, theta, h, 0.0, 0.0, work)
    # body-frame centroid from the sectional sums
    A = work[:, 0] * sec.dx
    xb = float((A * sec.x).sum() / V) if V > 0 else 0.0
    zb = float((work[:, 2] * sec.dx).sum() / V) if V > 0 else 0.0
    return V, xb, zb


def loading(ship: Ship, sec: Sections) -> dict:
    """Resolve the loading to volume [m^3], LCG [m] and KG [m]; check the hull can float it."""
    ld = ship.loading
    if "draft" in ld:
        T = float(ld["draft"])
        if T >= sec.depth:
            raise StabflowError(f"{ship.path}: loading.draft: {T} m is not below the deck ({sec.depth:.3f} m)")
        vol, lcb, _ = _volume_at(sec, -T)
        lcg = float(ld.get("lcg", lcb))
    else:
        vol = float(ld["mass"]) / ship.rho
        if vol >= sec.hull_volume:
            raise StabflowError(
                f"{ship.path}: loading.mass: {ld['mass']:.6g} kg needs {vol:.1f} m^3 but the hull "
                f"encloses only {sec.hull_volume:.1f} m^3 - it cannot float"
            )
        lcg = float(ld.get("lcg", 0.0))
    kg = float(ld["kg"])
    if kg > sec.depth * 3:
        raise StabflowError(f"{ship.path}: loading.kg: {kg} m is far above the deck ({sec.depth:.3f} m)")
    xmin, xmax = sec.x[0] - 0.5 * sec.dx[0], sec.x[-1] + 0.5 * sec.dx[-1]
    if not xmin < lcg < xmax:
        raise StabflowError(f"{ship.path}: loading.lcg: {lcg} m lies outside the hull ({xmin:.2f} to {xmax:.2f} m)")
    return {"volume": vol, "lcg": lcg, "kg": kg}


def equilibrium(sec: Sections, volume: float, lcg: float, kg: float, heel: float = 0.0, guess=None):
    """Free-floating equilibrium at a fixed heel [rad]: heave h [m], trim theta [rad], GZ [m].

    Raises :class:`StabflowError` if no equilibrium is found.
    """
    if guess is None:
        guess = _draft_guess(sec, volume)
    work = np.empty((len(sec.x), WORK_COLUMNS))
    h, th, gz, it = _equilibrium(*sec.args(), heel, volume, lcg, kg, guess[0], guess[1], TOL, work)
    V, ex, _ = _hydro_state(*sec.args(), heel, th, h, lcg, kg, work)
    if abs(V - volume) > 1e-6 * volume or abs(ex) > 1e-6 * sec.length:
        raise StabflowError(f"no equilibrium found for volume {volume:.1f} m^3 and LCG {lcg:.2f} m")
    return h, th, gz


def _draft_guess(sec: Sections, volume: float) -> tuple[float, float]:
    """Even-keel draft with the target volume (bisection), as (h, theta)."""
    lo, hi = float(np.nanmin(sec.z)), sec.depth
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _volume_at(sec, -mid)[0] < volume:
            lo = mid
        else:
            hi = mid
    return -0.5 * (lo + hi), 0.0


def particulars(sec: Sections, volume: float, lcg: float, kg: float, rho: float) -> dict:
    """Upright hydrostatic particulars at the free-trim equilibrium.

    Returns volume, mass, draft_mid, trim, lcb, kb, waterplane_area, bm, km, gm (SI units).
    BM = I_T / V with I_T = sum (2/3) y_wl^3 dx over the trimmed waterline.
    """
    h, th, _ = equilibrium(sec, volume, lcg, kg)
    V, xb, zb = _volume_at(sec, h, th)
    ct, st = np.cos(th), np.sin(th)
    # body height of the waterline at each station: cos(th) z = sin(th) x - h
    zw = (st * sec.x - h) / ct
    yw = np.array([sec.half_breadth(i, zw[i]) for i in range(len(sec.x))])
    awp = float((2 * yw * sec.dx).sum()) / ct
    it = float((2.0 / 3.0 * yw**3 * sec.dx).sum())
    bm = it / V
    km = zb + bm
    wet = yw > 0
    lwl = float(sec.dx[wet].sum()) if wet.any() else 0.0
    return {
        "volume": V, "mass": rho * V, "draft_mid": -h / ct, "trim_upright": th, "lwl": lwl, "bwl": 2 * float(yw.max()),
        "lcb": xb, "lcg": lcg, "kb": zb, "kg": kg, "waterplane_area": awp, "bm": bm, "km": km, "gm": km - kg,
    }


def gz_curve(sec: Sections, volume: float, lcg: float, kg: float, heel_deg: np.ndarray) -> xr.Dataset:
    """GZ with free trim at each heel [degree] (0 to 180, inverted ship included).

    Returns a Dataset with ``gz`` [m], ``heave`` [m] and ``trim`` [degree] along ``heel`` [degree].
    """
    heels = np.radians(np.asarray(heel_deg, dtype=np.float64))
    h0, th0, _ = equilibrium(sec, volume, lcg, kg, heel=float(heels[0]))
    out = np.empty((len(heels), 4))
    _gz_curve(*sec.args(), heels, volume, lcg, kg, h0, th0, TOL, out)
    # verify every point converged
    work = np.empty((len(sec.x), WORK_COLUMNS))
    for k, phi in enumerate(heels):
        V, ex, _ = _hydro_state(*sec.args(), phi, out[k, 2], out[k, 1], lcg, kg, work)
        if abs(V - volume) > 1e-6 * volume or abs(ex) > 1e-5 * sec.length:
            raise StabflowError(f"GZ: no equilibrium at heel {heel_deg[k]:.1f} deg")
    ds = xr.Dataset(
        {"gz": ("heel", out[:, 0]), "heave": ("heel", out[:, 1]), "trim": ("heel", np.degrees(out[:, 2]))},
        coords={"heel": np.asarray(heel_deg, dtype=np.float64)},
    )
    return annotate(ds)


def curve_summary(gz: xr.DataArray) -> dict:
    """GZ maximum, its angle and the angle of vanishing stability (first downward zero crossing)."""
    hd = gz["heel"].values
    # round-off zeros (e.g. GZ(180 deg) of a ship stable to 180) count as zero
    g = np.where(np.abs(gz.values) < 1e-9 * max(float(np.abs(gz.values).max()), 1e-12), 0.0, gz.values)
    k = int(np.argmax(g))
    vanish = np.nan
    for j in range(max(k, 1), len(g)):
        if g[j - 1] > 0 >= g[j]:
            vanish = hd[j - 1] + (hd[j] - hd[j - 1]) * g[j - 1] / (g[j - 1] - g[j])
            break
    return {"gz_max": float(g[k]), "heel_gz_max": float(hd[k]), "heel_vanishing": float(vanish)}


def compute_statics(ship: Ship, hull: xr.Dataset) -> xr.Dataset:
    """The statics step: particulars and the calm-water GZ curve for the ship's loading."""
    sec = Sections(hull)
    ld = loading(ship, sec)
    p = particulars(sec, ld["volume"], ld["lcg"], ld["kg"], ship.rho)
    if p["gm"] < 0:
        warnings.warn(f"{ship.path}: loading gives negative GM = {p['gm']:.3f} m (a lolling ship)", StabilityWarning, stacklevel=2)
    st = ship.data["statics"]
    heel = np.round(np.arange(0.0, st["heel_max"] + 1e-9, st["heel_step"]), 10)
    ds = gz_curve(sec, ld["volume"], ld["lcg"], ld["kg"], heel)
    for k, v in p.items():
        ds[k] = np.degrees(v) if k == "trim_upright" else v  # angles in degrees on disk
    for k, v in curve_summary(ds["gz"]).items():
        ds[k] = v
    # GM check from the GZ slope at zero heel (central difference on a small heel)
    d = np.radians(0.05)
    gzp = gz_curve(sec, ld["volume"], ld["lcg"], ld["kg"], np.array([0.0, np.degrees(d)]))["gz"].values[1]
    ds["gm_from_gz_slope"] = gzp / np.sin(d)
    ds["hull_volume"] = sec.hull_volume
    ds.attrs.update(ship=ship.name, water_density=ship.rho, gz_method="sectional volume clipping, free trim")
    return annotate(ds)
