"""Wave-pass and early-stage checks (paper 002).

| check | reference | kind |
|---|---|---|
| GM(x_c), GZ(phi; x_c) for H -> 0 | calm-water statics through the same kernel | consistency |
| GM(x_c) eq. A24 vs GZ slope on the wave | second route through the same kernel | consistency |
| GM(x_c), GZ on the wave with stations doubled | self-convergence | consistency |
| DTMB 5415 crest below / trough above calm GZ | paper 002 finding for a flared hull | independent |
| angle of GZ max at KG_cr | definition of GM_cr, re-check of the metric file | consistency |
| weights of the (A, k) grid sum to 1; Rayleigh marginal | exact properties of the joint density | independent |

A GZ on the wave that has no equilibrium (NaN) makes its row FAIL with the count; it is never
skipped by a NaN-ignoring maximum.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.config import Ship
from stabflow.validation import Check


def _gz_check(name: str, diff, gzmax: float, tol: float, reference: str, kind: str = "consistency") -> Check:
    """max |diff| / GZmax [%]; FAIL naming the count if any point has no equilibrium (NaN)."""
    diff = np.asarray(diff, float)
    bad = int((~np.isfinite(diff)).sum())
    if bad:
        return Check.failed(name, f"no equilibrium on the wave at {bad} of {diff.size} points", "%", reference, kind,
                            tolerance=tol)
    return Check(name, 100 * float(np.abs(diff).max()) / gzmax, tol, "%", reference, kind=kind)


def waves_checks(ship: Ship, hull: xr.Dataset, st: xr.Dataset, waves: xr.Dataset, metric: xr.Dataset, es_cfg: dict) -> list[Check]:
    """Wave-pass and early-stage checks: H → 0 limit, two GM routes, station convergence, weights."""
    from stabflow.stability_in_waves.early_stage import heel_of_gz_max, joint_pdf, wave_statistics, weights
    from stabflow.geometry import Sections, build_hull
    from stabflow.hydrostatics.statics import gz_curve
    from stabflow.waves.spectra import spectrum
    from stabflow.stability_in_waves.wave_pass import wave_gm, wave_gz

    sec = Sections(hull)
    V, lcg, kg, L = (float(st[k]) for k in ("volume", "lcg", "kg", "lwl"))
    k = 2 * np.pi / L
    gzmax = float(st["gz_max"])
    checks = []
    tiny = 1e-9 * L  # GM(x_c) is linear in the amplitude: keep the wave negligible
    g0 = max(abs(wave_gm(sec, V, lcg, kg, tiny, k, x)[0] - float(st["gm"])) for x in (0.0, 0.25 * L, 0.5 * L))
    checks.append(Check("GM(x_c) for H -> 0 vs calm-water GM", g0, 1e-4, "m", "calm-water statics (same kernel, zero wave)",
                        kind="consistency"))
    heel = np.arange(0.0, 91.0, 5.0)
    gzt = wave_gz(sec, V, lcg, kg, tiny, k, 0.0, heel)
    checks.append(_gz_check("GZ(phi; x_c) for H -> 0 vs calm-water GZ, / GZmax", gzt - st["gz"].sel(heel=heel).values, gzmax,
                            0.1, "calm-water statics (same kernel, zero wave)"))
    # GM from the waterplane (eqs A22-A24) vs the slope of the wave GZ curve, crest amidships
    s = float(waves["steepness"].max())
    amp = 0.5 * s * L
    gm_c = wave_gm(sec, V, lcg, kg, amp, k, 0.0)[0]
    d = 0.05
    slope = wave_gz(sec, V, lcg, kg, amp, k, 0.0, np.array([0.0, d]))[1] / np.sin(np.radians(d))
    checks.append(Check(f"GM(x_c=0) eq. A24 vs GZ slope on the wave (lambda = L, H/lambda = {s:g})", gm_c - slope, 0.01, "m",
                        "second route: slope of GZ(phi; x_c)", kind="consistency"))
    # station convergence of GM(x_c), lambda = L at the steepest wave
    ship2 = ship.modified(stations=2 * int(ship.hull["stations"]))
    sec2 = Sections(build_hull(ship2))
    xs = waves["crest_position"].values[:: max(1, len(waves["crest_position"]) // 5)]
    a = np.array([wave_gm(sec, V, lcg, kg, amp, k, x)[0] for x in xs])
    b = np.array([wave_gm(sec2, V, lcg, kg, amp, k, x)[0] for x in xs])
    checks.append(Check("GM(x_c) change with stations doubled (lambda = L), / calm GM", 100 * np.abs(a - b).max() / abs(float(st["gm"])),
                        2.0, "%", "self-convergence", kind="consistency"))
    heel = np.arange(0.0, 61.0, 10.0)
    ga = np.array([wave_gz(sec, V, lcg, kg, amp, k, x, heel) for x in (0.0, 0.5 * L)])
    gb = np.array([wave_gz(sec2, V, lcg, kg, amp, k, x, heel) for x in (0.0, 0.5 * L)])
    checks.append(_gz_check("GZ(phi; x_c) change with stations doubled (crest / trough amidships, 0-60 deg), / GZmax",
                            ga - gb, gzmax, 2.0, "self-convergence", kind="consistency"))
    if ship.name == "dtmb5415":
        # paper 002: for a flared hull the crest amidships lowers GZ and the trough raises it;
        # measured as the largest violation (0 when the ordering holds at every heel 5-90 deg)
        ct = waves[["gz_crest", "gz_trough", "gz_calm"]].sel(heel_full=np.arange(5.0, 91.0, 5.0))
        for name, d in (("crest amidships GZ below calm, 5-90 deg: violation max(GZ_crest - GZ_calm, 0)", ct["gz_crest"] - ct["gz_calm"]),
                        ("trough amidships GZ above calm, 5-90 deg: violation max(GZ_calm - GZ_trough, 0)", ct["gz_calm"] - ct["gz_trough"])):
            d = d.values
            if not np.all(np.isfinite(d)):
                checks.append(Check.failed(name, f"no equilibrium on the wave at {int((~np.isfinite(d)).sum())} heels", "m",
                                           "paper 002 (flared hull)", tolerance=0.0))
            else:
                checks.append(Check(name, max(float(d.max()), 0.0), 0.0, "m", "paper 002 (flared hull)"))
    # the critical KG of the metric file puts the calm-water GZ maximum at the critical angle
    hh = np.arange(0.0, 90.01, 0.5)
    phi = heel_of_gz_max(gz_curve(sec, V, lcg, float(metric["kg_cr"]), hh)["gz"].values, hh)
    if float(metric["gm_cr"]) > es_cfg["gm_min"] + 1e-9:
        checks.append(Check("angle of GZ max at KG_cr vs critical angle", phi - es_cfg["critical_angle"], 0.1, "degree",
                            "paper 002 definition of GM_cr (re-check of the metric file)", kind="consistency"))
    else:  # floored: even at GM = gm_min the GZ maximum lies at or beyond the critical angle
        checks.append(Check("GM_cr floored: critical angle minus angle of GZ max at GM_min (violation if > 0)",
                            max(es_cfg["critical_angle"] - phi, 0.0), 0.1, "degree",
                            "paper 002 definition of GM_cr (re-check of the metric file)", kind="consistency"))
    # statistical weights: the full (A, k) plane integrates to 1; the marginal of A is Rayleigh
    # (exact: a probability density integrates to 1 and its amplitude marginal is Rayleigh)
    for ss in es_cfg["sea_states"]:
        S = spectrum(es_cfg["spectrum"], ss["hs"], ss["tm"])
        sigma, k1, k2 = wave_statistics(S, 2 * np.pi / ss["tm"])
        W = weights(np.linspace(0, 8 * sigma, 33), np.linspace(0, k1 + 40 * k2, 161), sigma, k1, k2)
        checks.append(Check(f"{ss['name']}: weights of the full (A, k) grid sum to 1", float(W.sum()) - 1.0, 5e-3, "-",
                            "eq. 4 normalisation (exact: 1)"))
        A = np.linspace(0.2, 3.0, 8) * sigma
        kk = np.linspace(0, k1 + 60 * k2, 200001)
        marg = np.trapezoid(joint_pdf(A[:, None], kk[None, :], sigma, k1, k2), kk, axis=1)
        ray = A / sigma**2 * np.exp(-A * A / (2 * sigma**2))
        checks.append(Check(f"{ss['name']}: marginal of f(A, k) over k vs Rayleigh, max relative error",
                            float(np.abs(marg / ray - 1).max()), 1e-3, "-", "eq. A4 (exact: Rayleigh)"))
    return checks
