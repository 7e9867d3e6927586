"""Second-generation level-2 physics sea state by sea state of the IACS Rec. 34 scatter table, and
the rows of the levels they serve (pure loss of stability and parametric rolling on Grim's effective
wave; dead ship and excessive acceleration in beam seas without way).

What the circular weights and compares (its wave cases, exposure time, indices C and standards) was
not read: the rows are NOT EVALUATED and name what is missing; every quantity is computed and written
(``ew_*``: :mod:`stabflow.criteria.effective_wave`; ``ds_*``, ``ea_*``: :mod:`stabflow.criteria.beam_seas`).
The sea states are weighted with the Rec. 34 probabilities, which the circular's own table may or may
not equal (``sgisc.wave_data.level2_wave_scatter_table`` is null).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.criteria import dsa
from stabflow.criteria.beam_seas import beam_sea_cells, beam_sea_model
from stabflow.criteria.effective_wave import effective_wave_heights, stability_on_effective_waves
from stabflow.criteria.sgisc import CIRC, SG
from stabflow.criteria.standards import Standards
from stabflow.criteria.verdicts import Row, against

#: seconds per year (365.25 d), as the DSA's long-term rate
YEAR = dsa.SECONDS_PER_YEAR


def crew_height(ship, depth: float) -> tuple[float, str]:
    """Height above the baseline of the highest crew location [m] from the ship config's
    ``criteria.crew_location``, or the weather deck at the centreline amidships (the hull's deck
    height ``depth``) with that stated."""
    c = ship.data.get("criteria", {}).get("crew_location")
    if c:
        return float(c["z"]), f"crew location {float(c['z']):.2f} m above the baseline ({c.get('source', 'ship config')})"
    return depth, (f"crew location: the weather deck amidships, {depth:.2f} m above the baseline (the ship config gives "
                   "no criteria.crew_location, e.g. the bridge)")


def _weighted(p: xr.DataArray, x: xr.DataArray) -> float:
    """sum p x over the sea states read (p NaN: not read), per second -> per year by the caller."""
    ok = np.isfinite(p.values) & np.isfinite(x.values)
    return float((p.values[ok] * x.values[ok]).sum())


def sea_states(ship, sec, st: xr.Dataset, stab, wq: dict, cfg: dict, std: Standards, r_pr: float,
               depth: float, phi_f: tuple[float, str], hydro: xr.Dataset | None = None) -> tuple[list[Row], xr.Dataset]:
    """Rows and quantities of the level-2 sea-state physics of one ship.

    Parameters
    ----------
    stab : :class:`stabflow.criteria.is_code.Stability` (GZ curve, GM, KG).
    wq : the weather criterion's quantities (``wc_phi0``: heel under the steady wind, when a windage is given).
    cfg : the criteria section's ``sea_states`` settings (stations, acceleration_levels, heights, crest_positions).
    r_pr : level 1's R_PR (the parametric-rolling ratio the effective-wave variation is set against).
    depth : deck height amidships [m] (the default crew location).
    phi_f : (failure angle [degree], what governs it) (:func:`stabflow.criteria.dsa_run.failure_angle`).
    """
    from stabflow.config import _fill_defaults, schema
    from stabflow.statistics.ensemble import build_model

    p = dsa.scatter_probabilities(std.raw["iacs_rec34_scatter"])
    scatter_src = str(std.raw["iacs_rec34_scatter"]["meta"]["document"])
    V, lcg, kg = float(st["volume"]), float(st["lcg"]), float(st["kg"])
    # ---- Grim's effective wave: pure loss and parametric rolling ----
    # sea states that never occur (count 0) or were not read are left out (NaN), never weighted
    occurs = np.isfinite(p.values) & (p.values > 0)
    heff = effective_wave_heights(p, stab.lwl).where(occurs)
    ew = stability_on_effective_waves(sec, V, lcg, kg, stab.lwl, heff, stab.gm0, int(cfg["heights"]),
                                      int(cfg["crest_positions"]))
    # ---- beam seas without way: dead ship and lateral acceleration ----
    cond = _fill_defaults(schema("config")["properties"]["ensembles"]["items"],
                          {"name": "dead_ship", "ship": ship.name, "speed_kn": 0.0, "heading_deg": 90.0, "records": 1,
                           "stations": int(cfg["stations"]), "duration": 60.0, "dt": 0.1})
    model = build_model(ship, cond, hydro)
    bsm = beam_sea_model(model)
    phi_w = float(wq.get("wc_phi0", 0.0)) if math.isfinite(wq.get("wc_phi0", math.nan)) else 0.0
    wind = "wc_phi0" in wq
    slope = np.gradient(stab.gz, np.radians(stab.heel))
    c44 = bsm.stiffness[1, 1] * float(np.interp(phi_w, stab.heel, slope)) / float(slope[0])
    z_crew, crew_note = crew_height(ship, depth)
    h = z_crew - kg
    bs = beam_sea_cells(bsm, p.where(occurs), phi_f[0], phi_w, c44, h, cfg["acceleration_levels"])
    ds = ew.merge(bs)
    # ---- long-term figures over the scatter table ----
    pr_exceeds = (ds["ew_delta_gm_ratio"] > r_pr).astype(float).where(ds["ew_delta_gm_ratio"].notnull())
    frac_pr = _weighted(p, pr_exceeds)
    gm_neg = (ds["ew_gm_min"] < 0).astype(float).where(ds["ew_gm_min"].notnull())
    frac_gm = _weighted(p, gm_neg)
    ds_rate = _weighted(p, ds["ds_failure_rate"]) * YEAR
    ea = np.array([_weighted(p, ds["ea_exceedance_rate"].isel(ea_level=i)) for i in range(ds.sizes["ea_level"])]) * YEAR
    ds["ds_long_term_rate"] = ((), ds_rate)
    ds["ea_long_term_rate"] = ("ea_level", ea)
    ds["ew_probability_gm_negative"] = ((), frac_gm)
    ds["ew_probability_delta_gm_above_rpr"] = ((), frac_pr)
    ds["ds_heel_wind"] = ((), phi_w)
    ds["ds_failure_angle"] = ((), phi_f[0])
    ds["ea_crew_height"] = ((), z_crew)
    ds["ea_height_above_g"] = ((), h)
    ds["ea_roll_period"] = ((), bsm.roll_period)
    ds["ea_acceleration_per_roll"] = ((), G + 4 * math.pi**2 * h / bsm.roll_period**2)
    ds["sea_probability"] = (("hs", "tz"), p.values)
    ds.attrs.update(sea_states_scatter=scatter_src, ds_wind="IS Code 2.3 steady wind lever (phi0)" if wind else
                    "none: no windage in the ship config (waves only)", ea_crew=crew_note,
                    ds_failure_angle_governed_by=phi_f[1])

    # ---- rows ----
    rows = []
    big = ds["ew_effective_height"]
    imax = np.unravel_index(int(np.nanargmax(ds["ew_delta_gm_ratio"].values)), p.shape)
    wc = std.get("sgisc.wave_data.pure_loss_and_parametric_roll_level2_wave_cases.cases")
    wave_miss = [] if wc.available else [f"{wc.key} (the circular's wave cases; stabflow weights Rec. 34 sea states)"]
    pl = f"{SG}.pure_loss_of_stability.level_2"
    miss = wave_miss + [f"{s.key} ({s.source})" for s in (std.get(f"{pl}.RPL1_angle_of_vanishing_stability_deg"),
                                                          std.get(f"{pl}.RPL2_heel_angle_deg"),
                                                          std.get(f"{pl}.RPL3_heel_lever_coefficient")) if not s.available]
    rows.append(against("pure loss of stability: max(CR1, CR2) on the effective waves", "SGISC pure loss, level 2",
                        math.nan, "-", std.get_or_missing(f"{pl}.RPL0", f"{CIRC}, pure loss level 2"), "<=", missing=miss,
                        note=f"Grim effective wave lambda = L of each Rec. 34 sea state (largest H_eff {float(big.max()):.2f} m): "
                             f"smallest angle of vanishing stability on it {float(ds['ew_heel_vanishing'].min()):.1f} deg, "
                             f"smallest GZmax {float(ds['ew_gz_max'].min()):.3f} m; probability of sea states with GMmin < 0 "
                             f"on the effective wave {frac_gm:.3g}"))
    pr = f"{SG}.parametric_rolling.level_2"
    rows.append(against("parametric rolling: C1 (GM variation on the effective waves)", "SGISC parametric rolling, level 2",
                        math.nan, "-", std.get_or_missing(f"{pr}.RPR0", f"{CIRC}, parametric rolling level 2"), "<=",
                        missing=wave_miss + ["the circular's speed condition of C1 (not read)"],
                        note=f"largest delta GM / GM on the effective wave {float(ds['ew_delta_gm_ratio'].values[imax]):.3f} "
                             f"(Hs {float(p.hs[imax[0]]):g} m, Tz {float(p.tz[imax[1]]):g} s); probability of sea states where it "
                             f"exceeds level 1's R_PR {r_pr:.3f}: {frac_pr:.3g}"))
    dl1 = std.get_or_missing(f"{SG}.dead_ship.level_1.standard", f"{CIRC}, dead ship level 1")
    area = (f"the IS Code weather criterion's areas a = {wq['wc_area_a']:.4f}, b = {wq['wc_area_b']:.4f} m rad"
            if "wc_area_a" in wq else "no windage in the ship config: the weather criterion's areas are not computed")
    rows.append(against("dead ship condition: weather-criterion type check", "SGISC dead ship, level 1", math.nan, "-", dl1,
                        ">=", missing=["the circular's level-1 steepness and roll-back tables (not read)"],
                        note=f"the level-1 check is of the weather criterion's kind; {area}"))
    rds = std.get_or_missing(f"{SG}.dead_ship.level_2.RDS0", f"{CIRC}, dead ship level 2")
    worst = np.unravel_index(int(np.nanargmax(ds["ds_roll_std"].values)), p.shape)
    rows.append(against("dead ship condition: long-term failure index C", "SGISC dead ship, level 2", math.nan, "-", rds, "<=",
                        missing=["the circular's exposure time and index C (not read)"],
                        note=f"beam seas without way, linear roll with stochastically linearised damping: failure (roll "
                             f"beyond {phi_f[0]:.1f} deg, {phi_f[1]}) rate over the Rec. 34 table {ds_rate:.4g} per year; "
                             f"wind heel {phi_w:.2f} deg ({ds.attrs['ds_wind']}); largest roll sigma "
                             f"{float(ds['ds_roll_std'].values[worst]):.2f} deg (Hs {float(p.hs[worst[0]]):g} m, "
                             f"Tz {float(p.tz[worst[1]]):g} s)"))
    rows.append(against("excessive acceleration: lateral acceleration at the crew location", "SGISC excessive acceleration, level 1",
                        math.nan, "m/s2", std.get_or_missing(f"{SG}.excessive_acceleration.level_1.REA1", f"{CIRC}, level 1"),
                        "<=", missing=["the circular's level-1 roll amplitude (not read)"],
                        note=f"{crew_note}, {h:.2f} m above G; natural roll period {bsm.roll_period:.2f} s; lateral "
                             f"acceleration per radian of roll g + 4 pi^2 h / T^2 = {float(ds['ea_acceleration_per_roll']):.3f} m/s2"))
    lv = ds["ea_level"].values
    worst = np.unravel_index(int(np.nanargmax(ds["ea_acceleration_std"].values)), p.shape)
    rows.append(against("excessive acceleration: long-term index C", "SGISC excessive acceleration, level 2", math.nan, "-",
                        std.get_or_missing(f"{SG}.excessive_acceleration.level_2.REA2", f"{CIRC}, level 2"), "<=",
                        missing=[f"{std.get(f'{SG}.excessive_acceleration.level_1.lateral_acceleration_limit').key} (the "
                                 "acceleration limit)", "the circular's index C (not read)"],
                        note="beam seas without way at the crew location: rate of |a_y| above "
                             + ", ".join(f"{a:g} m/s2 {r:.3g}" for a, r in zip(lv, ea)) + " per year over the Rec. 34 table; "
                             f"largest sigma {float(ds['ea_acceleration_std'].values[worst]):.2f} m/s2 "
                             f"(Hs {float(p.hs[worst[0]]):g} m, Tz {float(p.tz[worst[1]]):g} s)"))
    return rows, ds
