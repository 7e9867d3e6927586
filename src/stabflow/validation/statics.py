"""Statics checks: calm-water particulars and GZ against exact, independent and published references.

| check | reference | kind |
|---|---|---|
| GM from the GZ slope vs hydrostatic GM | BM = I_T / V of the same sections | consistency |
| box barge GZ 0-180 deg | shapely polygon clipping of the rectangle (exact) | independent |
| box barge BM | B^2 / (12 T) | independent |
| Wigley volume and BM | analytic 4/9 LBT, (2/3)(B/2)^3 L 16/35 / V | independent |
| mesh GZ 0-180 deg, free trim | divergence-theorem integration over the STL (no sections) | independent |
| mesh GZ 0-60 deg | navaltoolbox (peer library) | independent |
| volume, displacement, GMt, KMt | published particulars (PUBLISHED, with source) | independent |
| stations doubled | the same method at twice the stations | consistency |
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from stabflow.config import Ship
from stabflow.geometry.mesh import ship_mesh
from stabflow.validation import Check, run_check
from stabflow.validation.references import exact_box_gz, mesh_gz

#: published particulars used as references: (statics quantity, published value, tolerance, unit, source)
#: per ship; "volume" [m^3], "mass" [t], "gm" and "km" [m]. The hull file's README restates SIMMAN 2008's
#: volume and GMt; Ariffin, Mansor & Laurens, "Experimental study on the wind heeling arm of the
#: weather criterion", Proc. 15th International Ship Stability Workshop, Stockholm 2016, Table 2
#: ("5415 shape": "Draft, (m) 6.15", "Displacement, (tonnes) 8,635", "VCG, (m) 7.555",
#: "KM, (m) 9.493", "GM, (m) 1.938"), read at helenedartoisTNAH-M2/ShipStabResearchApp@f479b9ae:
#: app/static/PDF_STAB_ISSW/ISSW_2016_s08-p3.pdf, p. 247, give the same loading's displacement, KM and GM.
_ARIFFIN = "Ariffin, Mansor & Laurens, ISSW 2016, Table 2 (T = 6.15 m, VCG = 7.555 m)"
PUBLISHED = {
    "dtmb5415": [("volume", 8424.0, 1.0, "%", "SIMMAN 2008, T = 6.15 m (resources/hulls/README.md)"),
                 ("gm", 1.95, 0.05, "m", "SIMMAN 2008, KG = 7.555 m (resources/hulls/README.md)"),
                 ("mass", 8635.0, 1.0, "%", _ARIFFIN),
                 ("km", 9.493, 0.05, "m", _ARIFFIN),
                 ("gm", 1.938, 0.05, "m", _ARIFFIN)],
}
#: row name and unit of each published quantity
_PUBLISHED_LABELS = {"volume": ("displaced volume", "m3"), "mass": ("displacement", "t"), "gm": ("GMt", "m"),
                     "km": ("KMt", "m")}


#: largest heel [degree] of the navaltoolbox comparison: navaltoolbox departs from the exact mesh
#: integration beyond about 65-75 deg on the shipped hulls (deck deeply immersed)
NAVALTOOLBOX_MAX_HEEL = 60.0

#: acceptance bands claimed in the README (percent of GZmax or of the reference)
TOL_EXACT_BOX = 0.5  # % GZmax (measured: round-off, 1e-9 %)
TOL_WIGLEY = 0.05  # % (measured: volume -0.048 %, BM +0.048 % at 41 stations)
TOL_MESH = 0.5  # % GZmax (measured: DTMB 0.21 %, DTC 0.11 %)
TOL_NAVALTOOLBOX = 1.0  # % GZmax (measured: DTMB 0.26 %, DTC 0.65 %)
TOL_STATIONS = 0.5  # % GZmax


def navaltoolbox_gz(ship: Ship, volume, lcg, kg, heel_deg) -> np.ndarray:
    """GZ [m] from navaltoolbox (independent implementation) for a mesh ship.

    The mesh is handed over in ship axes (scale, flip and shift applied, written as a temporary
    STL), so G is given in ship axes as well. Raises if navaltoolbox is missing or fails.
    """
    import navaltoolbox as nt

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{ship.name}.stl"
        ship_mesh(ship).export(path)
        hull = nt.Hull(str(path))
    calc = nt.StabilityCalculator(nt.Vessel(hull), ship.rho)
    cur = calc.gz_curve(volume * ship.rho, (lcg, 0.0, kg), [float(x) for x in heel_deg])
    return np.array(cur.values())


def statics_checks(ship: Ship, hull: xr.Dataset, st: xr.Dataset) -> list[Check]:
    """All statics checks that apply to ``ship`` (see the module table). A check that cannot run is
    a FAIL row with the reason; a check that does not apply to this hull source is SKIPPED."""
    from stabflow.geometry import build_hull
    from stabflow.hydrostatics.statics import compute_statics

    checks: list[Check] = []
    gz = st["gz"]
    gzmax = float(st["gz_max"])
    vol, lcg, kg = float(st["volume"]), float(st["lcg"]), float(st["kg"])
    h = ship.hull
    checks.append(Check("GM from GZ slope vs hydrostatic GM", float(st["gm_from_gz_slope"] - st["gm"]), 1e-3, "m",
                        "BM = I_T/V from the waterplane of the same sections", kind="consistency"))
    if h["source"] == "box":
        ref = exact_box_gz(h["length"], h["breadth"], h["depth"], vol, kg, gz["heel"].values)
        err = np.abs(gz.values - ref).max() / np.abs(ref).max()
        checks.append(Check("GZ 0-180 deg vs exact polygon clipping, max abs. error / GZmax", 100 * err, TOL_EXACT_BOX, "%",
                            "shapely polygon clipping of the rectangle"))
        B, T = h["breadth"], float(st["draft_mid"])
        checks.append(Check("BM vs B^2/(12T)", float(st["bm"]) - B * B / (12 * T), 1e-9 * B, "m", "analytic"))
    if h["source"] == "wigley":
        L, B, T = h["length"], h["breadth"], h["design_draft"]
        vref = 4.0 / 9.0 * L * B * T
        checks.append(Check("volume vs analytic 4/9 LBT", 100 * (vol - vref) / vref, TOL_WIGLEY, "%", "analytic Wigley"))
        bmref = (2.0 / 3.0) * (B / 2) ** 3 * L * 16.0 / 35.0 / vref
        checks.append(Check("BM vs analytic", 100 * (float(st["bm"]) - bmref) / bmref, TOL_WIGLEY, "%", "analytic Wigley"))
    mesh_name = "GZ 0-180 deg vs exact mesh integration (free trim), max abs. error / GZmax"
    nt_name = f"GZ 0-{NAVALTOOLBOX_MAX_HEEL:.0f} deg vs navaltoolbox, max abs. error / GZmax"
    if h["source"] == "mesh" and "topside" not in h:  # references are of the untransformed mesh
        heels = np.arange(0.0, float(gz["heel"].max()) + 1e-9, 10.0)
        checks.append(run_check(
            lambda: 100 * np.abs(gz.sel(heel=heels).values - mesh_gz(ship_mesh(ship), vol, lcg, kg, heels)).max() / gzmax,
            mesh_name, "%", "divergence-theorem integration over the STL", tolerance=TOL_MESH))
        ntheel = np.arange(0.0, NAVALTOOLBOX_MAX_HEEL + 1e-9, 5.0)
        checks.append(run_check(
            lambda: 100 * np.abs(gz.sel(heel=ntheel).values - navaltoolbox_gz(ship, vol, lcg, kg, ntheel)).max() / gzmax,
            nt_name, "%", "navaltoolbox (independent code)", tolerance=TOL_NAVALTOOLBOX))
    else:
        why = ("the hull is not a mesh" if h["source"] != "mesh" else
               "the topside variant changes the hull above the waterline; the mesh file is the original hull")
        checks.append(Check.not_applicable(mesh_name, why, "%", "divergence-theorem integration over the STL"))
        checks.append(Check.not_applicable(nt_name, why, "%", "navaltoolbox (independent code)"))
    for quantity, ref, tol, unit, src in PUBLISHED.get(ship.name, []):
        value = {"volume": vol, "mass": float(st["mass"]) / 1000.0, "gm": float(st["gm"]), "km": float(st["gm"]) + kg}[quantity]
        dev = 100 * (value - ref) / ref if unit == "%" else value - ref
        label, ref_unit = _PUBLISHED_LABELS[quantity]
        checks.append(Check(f"{label} vs published {ref:g} {ref_unit}", dev, tol, unit, src))
    # station convergence: doubling the stations changes GZ by less than 0.5 % of GZmax
    ship2 = ship.modified(stations=2 * int(h["stations"]))
    st2 = compute_statics(ship2, build_hull(ship2))
    err = np.abs(st2["gz"].values - gz.values).max() / gzmax
    checks.append(Check(f"GZ change with stations doubled ({h['stations']} to {2 * h['stations']}), / GZmax", 100 * err,
                        TOL_STATIONS, "%", "self-convergence", kind="consistency"))
    return checks
