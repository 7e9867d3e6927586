"""All criteria of one loaded ship: the rows (criterion, level, value, standard, verdict) and every
intermediate quantity, as one Dataset (``results/criteria/{ship}.nc``)."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from stabflow.config import Ship
from stabflow.constants import G, KNOT
from stabflow.criteria import is_code, sea_states, sgisc
from stabflow.criteria.dsa_run import failure_angle
from stabflow.criteria.standards import Standards
from stabflow.criteria.verdicts import rows_dataset
from stabflow.geometry import Sections
from stabflow.hydrostatics.profile import deck_edge_immersion, deck_edges, lateral_areas
from stabflow.hydrostatics.statics import gz_curve
from stabflow.io import annotate


def stability(ship: Ship, sec: Sections, st: xr.Dataset, step_deg: float = 0.25, max_deg: float = 90.0) -> is_code.Stability:
    """The IS Code inputs of the ship at its loading: GZ on a fine grid (free trim) and particulars."""
    V, lcg, kg = (float(st[k]) for k in ("volume", "lcg", "kg"))
    heel = np.round(np.arange(0.0, max_deg + 1e-9, step_deg), 10)
    gz = gz_curve(sec, V, lcg, kg, heel)["gz"].values
    crit = ship.data.get("criteria", {})
    d, B, L = float(st["draft_mid"]), float(st["bwl"]), float(st["lwl"])
    return is_code.Stability(
        heel=heel, gz=gz, gm0=float(st["gm"]), kg=kg, draft=d, breadth=B, lwl=L, block=V / (L * B * d),
        displacement=float(st["mass"]) / 1000.0, deck_edge=deck_edge_immersion(sec, V, lcg, kg),
        flooding=float(crit.get("flooding_angle_deg", math.nan)))


def windage(ship: Ship, sec: Sections, st: xr.Dataset) -> is_code.Windage | None:
    """Windage area and lever (to the centre of the underwater lateral area) from the ship config."""
    w = ship.data.get("criteria", {}).get("windage")
    if w is None:
        return None
    la = lateral_areas(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    if w == "hull":
        return is_code.Windage(la["area_above"], la["z_above"] - la["z_below"],
                               "windage: the hull's side above the waterline only (ship config windage: hull)")
    return is_code.Windage(float(w["area"]), float(w["height"]) - la["z_below"], w.get("source", ""))


def keel_area(ship: Ship) -> float:
    """Total bilge-keel area Ak [m^2] (span x length x count) from the ship's ``bilge_keels``, 0 if none."""
    from stabflow.dynamics.roll_damping import BilgeKeels

    bk = ship.data.get("bilge_keels")
    if not bk:
        return 0.0
    k = BilgeKeels.from_config(bk)
    return float(k.span * k.length * k.count)


def assess(ship: Ship, hull: xr.Dataset, st: xr.Dataset, cfg: dict, std: Standards | None = None,
           hydro: xr.Dataset | None = None, radiation: xr.Dataset | None = None) -> xr.Dataset:
    """Every criterion of the ship: rows along ``criterion`` plus the GZ curve, the weather
    criterion's quantities and the level-1 curves over wave steepness.

    Parameters
    ----------
    cfg : the pipeline's ``criteria`` section (``steepness``: H/lambda grid of the level-1 curves,
        ``crest_positions``, ``overrides``: optional override file, ``parametric``: the regular-wave
        cases of :func:`stabflow.criteria.sgisc.parametric_roll_cases`).
    hydro : Capytaine coefficients for ships whose dynamics use them.
    radiation : the radiation step's heave-pitch coefficients for ships with the memory model (the
        surf-riding threshold with the mean wave force).
    """
    std = std or Standards(cfg.get("overrides"))
    sec = Sections(hull)
    stab = stability(ship, sec, st)
    crit = ship.data.get("criteria", {})
    rows = is_code.general_criteria(stab, std)
    wrows, wq = is_code.weather_criterion(stab, std, windage(ship, sec, st), crit.get("bilge", "round"), keel_area(ship))
    rows += wrows
    V = float(st["volume"])
    # the curves' grid plus the circular's steepnesses where sourced, so the verdicts are read at them
    sws = [std.get_or_missing(f"{sgisc.SG}.{m}.level_1.wave_steepness_SW", "") for m in
           ("pure_loss_of_stability", "parametric_rolling")]
    grid = sorted(set(float(x) for x in cfg["steepness"]) | {float(w.value) for w in sws if w.available})
    gw = sgisc.gm_on_wave(sec, V, float(st["lcg"]), stab.kg, stab.lwl, grid, cfg["crest_positions"], draft=stab.draft)
    speed = crit.get("service_speed_kn")
    fn = speed * KNOT / math.sqrt(G * stab.lwl) if speed is not None else None
    mid = int(np.argmin(np.abs(sec.x)))
    depth = float(deck_edges(sec)[mid, 2])
    zz = np.linspace(0.0, stab.draft, 401)
    cm = float(np.trapezoid([2 * sec.half_breadth(mid, z) for z in zz], zz)) / (stab.breadth * stab.draft)
    reserve = (sec.hull_volume - V) / (float(st["waterplane_area"]) * (depth - stab.draft))
    simple, q1 = {}, {}
    for mode, key in (("pure_loss", "pure_loss_of_stability"), ("parametric", "parametric_rolling")):
        sw = std.get_or_missing(f"{sgisc.SG}.{key}.level_1.wave_steepness_SW", "")
        frac = std.get_or_missing(f"{sgisc.SG}.{key}.level_1." + ("dL_draft_rule_min_fraction" if mode == "pure_loss"
                                                                  else "dH_dL_draft_rule_min_fraction"), "")
        if sw.available and frac.available:
            simple[mode] = sgisc.simplified_level1(sec, V, stab.kg, stab.draft, depth, stab.lwl, float(sw.value),
                                                   float(frac.value))
            q1.update({f"l1_{mode}_{k}": v for k, v in simple[mode].items()})
        else:
            simple[mode] = {k: math.nan for k in ("d_H", "d_L", "I_H", "I_L", "KB_L", "gm_min", "delta_gm1")}
    r_pr = sgisc.rpr(std, cm, keel_area(ship), stab.lwl, stab.breadth, crit.get("bilge", "round"))
    rows += sgisc.level1_rows(gw, simple, stab.gm0, stab.lwl, fn, std, r_pr, reserve)
    q1.update(midship_coefficient=cm, depth_midship=depth, freeboard_volume_ratio=reserve, rpr=r_pr[0])
    pr = sgisc.parametric_roll_cases(ship, cfg["parametric"], stab.lwl, hydro)
    rows.append(sgisc.parametric_level2_row(pr, std))
    # the first level-2 check (C1) over the draft's regular waves; T_phi from the 1-DOF model's inertia
    cases, cases_src = sgisc.c1_cases(std)
    t_phi = (2 * math.pi * math.sqrt(float(pr["pr_inertia"].values[0]) / (float(pr.attrs["pr_weight"]) * stab.gm0))
             if stab.gm0 > 0 else math.nan)
    c1 = sgisc.parametric_c1(sec, V, float(st["lcg"]), stab.kg, stab.gm0, cases, r_pr[0], t_phi,
                             None if speed is None else speed * KNOT)
    rows.append(sgisc.parametric_c1_row(c1, std, cases_src))
    sr = sgisc.surf_riding_thresholds(ship, cfg["surf_riding"], stab.lwl, radiation)
    rows.append(sgisc.surf_riding_level2_row(sr, fn, std))
    from stabflow.config import _fill_defaults, schema

    sea_cfg = _fill_defaults(schema("config")["properties"]["criteria"]["properties"]["sea_states"], cfg.get("sea_states", {}))
    srows, seas = sea_states.sea_states(ship, sec, st, stab, wq, sea_cfg, std, r_pr[0], depth,
                                        failure_angle(std, stab.vanishing, stab.flooding), pr, hydro, fn)
    rows += srows
    ds = rows_dataset(rows, ship.name)
    ds = ds.merge(gw).merge(pr).merge(seas).merge(c1)
    ds.attrs.update(seas.attrs)
    ds.attrs.update(pr.attrs)
    ds.attrs.update(c1.attrs)
    ds = ds.merge(sr)
    ds.attrs.update(sr.attrs)
    ds["gz"] = ("heel", stab.gz)
    ds = ds.assign_coords(heel=stab.heel)
    for k, v in {**wq, **q1, "deck_edge_immersion": stab.deck_edge, "flooding_angle": stab.flooding,
                 "heel_vanishing": stab.vanishing, "gm": stab.gm0, "lwl": stab.lwl, "block_coefficient": stab.block,
                 "froude_service": np.nan if fn is None else fn}.items():
        ds[k] = float(v)
    ds.attrs.update(sw_pure_loss=float(sws[0].value) if sws[0].available else np.nan,
                    sw_parametric=float(sws[1].value) if sws[1].available else np.nan)
    ds.attrs.update(ship=ship.name, standards_overridden="; ".join(std.overrides_summary()) or "none",
                    criteria_data="resources/criteria/is_code_2008.yaml, sgisc.yaml, iacs_rec34_scatter.yaml")
    return annotate(ds)
