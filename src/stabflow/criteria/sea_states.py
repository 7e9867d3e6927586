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
from stabflow.criteria.effective_wave import BREAKING_STEEPNESS, effective_wave_heights, stability_on_effective_waves
from stabflow.criteria.sgisc import CIRC, SG
from stabflow.criteria.standards import Standards
from stabflow.criteria.verdicts import Row, against


def crew_height(ship, depth: float) -> tuple[float, str]:
    """Height above the baseline of the highest crew location [m] from the ship config's
    ``criteria.crew_location``, or the weather deck at the centreline amidships (the hull's deck
    height ``depth``) with that stated."""
    c = ship.data.get("criteria", {}).get("crew_location")
    if c:
        return float(c["z"]), f"crew location {float(c['z']):.2f} m above the baseline ({c.get('source', 'ship config')})"
    return depth, (f"crew location: the weather deck amidships, {depth:.2f} m above the baseline (the ship config gives "
                   "no criteria.crew_location, e.g. the bridge)")


def _occurs(p: xr.DataArray) -> np.ndarray:
    """The sea states that occur: probability read (not NaN) and positive."""
    return np.isfinite(p.values) & (p.values > 0)


def _long_term(p: xr.DataArray, x: xr.DataArray) -> float:
    """sum p x over the sea states that occur, e.g. a rate [1/s]: infinite when an occurring state's
    value is, NaN when one is NaN (never dropped)."""
    occ = _occurs(p)
    v = x.values[occ]
    if np.isnan(v).any():
        return math.nan
    return float((p.values[occ] * v).sum())


def _long_term_log10(p: xr.DataArray, log10_x: xr.DataArray) -> float:
    """log10 of sum p x from log10 x, summed in log space (scipy's logsumexp): the order of magnitude
    of a long-term rate whose every term underflows as a double; +inf, NaN as :func:`_long_term`."""
    from scipy.special import logsumexp

    occ = _occurs(p)
    v = log10_x.values[occ]
    if np.isnan(v).any():
        return math.nan
    if np.isposinf(v).any():
        return math.inf
    return float(logsumexp(v * math.log(10.0) + np.log(p.values[occ])) / math.log(10.0))


def rate_text(value: float, log10: float, spec: str = ".4g") -> str:
    """A rate as text: ``format(value, spec)``, or, where ``value`` underflowed to 0 as a double and
    its ``log10`` is finite, that order of magnitude ("4.6e-376", from log space): never a bare 0
    for a rate that is not 0."""
    value, log10 = float(value), float(log10)
    if value == 0.0 and math.isfinite(log10):
        e = math.floor(log10)
        m = round(10.0 ** (log10 - e), 1)
        if m >= 10.0:  # the mantissa rounds up to the next decade
            m, e = m / 10.0, e + 1
        return f"{m:.2g}e{e} (below the smallest double: from log space)"
    return format(value, spec)


def _fraction(p: xr.DataArray, flag: xr.DataArray) -> float:
    """Probability of the occurring sea states where ``flag`` is 1, over those where it is defined
    (NaN: e.g. an effective wave beyond the breaking steepness, reported separately)."""
    occ = _occurs(p) & np.isfinite(flag.values)
    return float((p.values[occ] * flag.values[occ]).sum())


def _extreme(x: xr.DataArray, p: xr.DataArray, fmt: str, unit: str, largest: bool) -> str:
    """'value unit (Hs, Tz)' of the largest or smallest finite value over the occurring sea states."""
    v = np.where(_occurs(p) & np.isfinite(x.values), x.values, np.nan)
    if not np.isfinite(v).any():
        return "not computed in any sea state"
    i, j = np.unravel_index(int(np.nanargmax(v) if largest else np.nanargmin(v)), v.shape)
    return f"{v[i, j]:{fmt}}{' ' + unit if unit else ''} (Hs {float(p.hs[i]):g} m, Tz {float(p.tz[j]):g} s)"


def _largest(x, p, fmt, unit=""):
    return _extreme(x, p, fmt, unit, True)


def _smallest(x, p, fmt, unit=""):
    return _extreme(x, p, fmt, unit, False)


def _gz_at_height(ew: xr.Dataset, height: float) -> np.ndarray:
    """GZ on the wave lambda = L of ``height`` [m] (ew_crest, ew_heel), linear in height between the
    effective-wave table's heights (``ew_height``, ``ew_table_gz``)."""
    heights, gz = ew["ew_height"].values, ew["ew_table_gz"].values
    m = min(max(int(np.searchsorted(heights, height)) - 1, 0), len(heights) - 2)
    f = (height - heights[m]) / (heights[m + 1] - heights[m])
    return (1.0 - f) * gz[m] + f * gz[m + 1]


def _roll_amplitude(tab: np.ndarray, ew: xr.Dataset, pr: xr.Dataset, lam: float, heading_deg: float, b: int) -> float:
    """Largest |roll| [degree] of the last quarter of a 1-DOF run (:func:`stabflow.criteria.sgisc.roll_1dof`)
    with GZ ``tab`` on the passing wave lambda = ``lam`` at ``heading_deg`` (0 following, 180 head) and
    the speed ``pr_froude[b]`` of the regular-wave cases ``pr`` (their coefficients, start heel,
    duration and step); 90 where it capsized."""
    from stabflow.criteria.sgisc import roll_1dof

    dur, dt, phi0 = float(pr.attrs["pr_duration"]), float(pr.attrs["pr_dt"]), float(pr.attrs["pr_phi0_deg"])
    keep = int(round(0.25 * dur / dt))
    c = math.sqrt(G / (2 * math.pi / lam))
    v_rel = c * math.cos(math.radians(float(heading_deg))) - float(pr["pr_froude"][b]) * math.sqrt(G * lam)
    roll = roll_1dof(tab, ew["ew_heel"].values, lam, v_rel, float(pr["pr_inertia"][b]), float(pr["pr_b44"][b]),
                     float(pr["pr_b44q"][b]), float(pr.attrs["pr_weight"]), phi0, dur, dt)
    return 90.0 if np.isnan(roll[-1]) else float(np.nanmax(np.abs(roll[-keep:])))


def parametric_roll_sea_states(ew: xr.Dataset, pr: xr.Dataset, lam: float) -> xr.DataArray:
    """Largest roll [degree] of the 1-DOF model with GZ on the passing wave
    (:func:`stabflow.criteria.sgisc.roll_1dof`) on each sea state's effective wave (lambda = L,
    height H_eff), over the regular-wave cases' headings and speeds (``pr``: their coefficients,
    start heel, duration and step), the largest |roll| of the run's last quarter (90: capsized);
    NaN for sea states without an effective wave (not occurring, or H_eff above L/7).

    The GZ curves on the wave are interpolated linearly in height between the effective-wave
    table's heights (``ew_table_gz``)."""
    h = ew["ew_effective_height"]
    out = np.full(h.shape, np.nan)
    for i, j in zip(*np.nonzero(np.isfinite(h.values) & (h.values <= BREAKING_STEEPNESS * lam))):
        tab = _gz_at_height(ew, float(h.values[i, j]))
        out[i, j] = max([0.0] + [_roll_amplitude(tab, ew, pr, lam, mu, b) for mu in pr["pr_heading"].values
                                 for b in range(pr.sizes["pr_froude"])])
    return xr.DataArray(out, dims=h.dims, coords=h.coords, name="ew_roll_1dof")


#: the 2013 draft's parametric-rolling C2 (SLF 55/WP.3 Annex 1, 2.11.3.3-2.11.3.4.1, read in Umeda,
#: ISSW 2013, pp. 13-14): the roll amplitude of the 1-DOF model in regular waves lambda = L of heights
#: h_i = 0.01 i L, i = 0 ... 10 (C2_HEIGHTS), for Froude numbers from 0 to the service Froude number in
#: steps of "[0.1]" (C2_FROUDE_STEP), head and following seas
C2_HEIGHTS = 0.01 * np.arange(11)
C2_FROUDE_STEP = 0.1


def parametric_c2(ew: xr.Dataset, pr: xr.Dataset, p: xr.DataArray, lam: float, fn_service: float | None,
                  threshold_deg: float) -> xr.Dataset:
    """Parametric rolling, level 2, second check as the 2013 draft states it: for each speed and
    heading, C2 = sum_i W_i C_i over the sea states of the scatter table (W_i their probability), C_i = 1
    where the roll amplitude on the sea state's effective wave (lambda = L, height H_i = ``ew``'s
    ``ew_effective_height``: stabflow's Grim wave; the draft leaves H_i's definition to an explanatory
    note "to be developed") exceeds ``threshold_deg``; the roll amplitude at H_i interpolated linearly
    from the amplitudes at the heights h = 0.01 i L (the largest |roll| of the last quarter of a 1-DOF run
    with GZ on the passing wave, :func:`stabflow.criteria.sgisc.roll_1dof`, the regular-wave cases' start
    heel, duration and step; 90 deg: capsized) below the effective-wave table's top (the largest
    effective wave, at most L/7) and at the top itself: no sea state needs more, none is extrapolated.
    C2 is the average over the speeds and headings.

    The speeds are Fn = 0, 0.1, ... up to ``fn_service`` (None: none, C2 NaN); the 1-DOF coefficients
    at each come from ``pr`` (its ``pr_froude``): a speed missing there is named in
    ``c2_missing_speeds`` and C2 is NaN; so is a heading (0 or 180 deg) missing from ``pr``
    (``c2_missing_headings``), and C2 is NaN without a finite ``threshold_deg``. A sea state whose effective
    wave would break (H_eff > L/7) counts as exceeding (on the safe side; ``c2_probability_breaking``); one
    without an effective wave is left out (``c2_probability_left_out``).

    Returns a Dataset: ``c2_roll`` (c2_heading, c2_froude, c2_height) [degree], ``c2_by_speed``
    (c2_heading, c2_froude), scalar ``c2``; attributes as named."""
    heights = ew["ew_height"].values
    # the draft's heights up to the effective-wave table's top, and the top itself (the largest effective
    # wave, at most L/7), so that no sea state's amplitude is extrapolated
    hgrid = C2_HEIGHTS * lam
    hgrid = hgrid[hgrid < heights[-1] - 1e-9]
    hgrid = np.append(hgrid, heights[-1]) if heights[-1] > 0 else hgrid
    fns = (np.round(np.arange(0.0, fn_service + 1e-9, C2_FROUDE_STEP), 10) if fn_service is not None
           else np.zeros(0))
    have = {round(float(f), 10): b for b, f in enumerate(pr["pr_froude"].values)}
    missing = [f for f in fns if round(float(f), 10) not in have]
    heads = pr["pr_heading"].values
    # the draft's head and following seas: a heading missing from the regular-wave cases is named, C2 NaN
    no_heads = [h for h in (0.0, 180.0) if not np.any(np.isclose(heads.astype(float), h))]
    roll = np.full((len(heads), len(fns), len(hgrid)), np.nan)
    for m, H in enumerate(hgrid):
        tab = _gz_at_height(ew, float(H))
        for a, mu in enumerate(heads):
            for v, fn in enumerate(fns):
                b = have.get(round(float(fn), 10))
                if b is not None:
                    roll[a, v, m] = _roll_amplitude(tab, ew, pr, lam, mu, b)
    heff = ew["ew_effective_height"].values
    occ = _occurs(p)
    use = occ & np.isfinite(heff) & (heff <= BREAKING_STEEPNESS * lam)
    # a sea state whose effective wave would break (H_eff > L/7) counts as exceeding the roll angle
    # (stabflow's choice, on the safe side: no regular wave of the table is that steep)
    breaking = occ & np.isfinite(heff) & (heff > BREAKING_STEEPNESS * lam)
    w = np.where(use, p.values, 0.0)
    by = np.full((len(heads), len(fns)), np.nan)
    for a in range(len(heads)):
        for v in range(len(fns)):
            if np.isfinite(roll[a, v]).all() and len(hgrid) > 1 and math.isfinite(threshold_deg):
                amp = np.interp(np.where(use, heff, 0.0), hgrid, roll[a, v])
                by[a, v] = float(np.sum(w * (amp > threshold_deg)) + np.sum(np.where(breaking, p.values, 0.0)))
    value = (float(np.mean(by)) if len(fns) and not missing and not no_heads and np.isfinite(by).all()
             else math.nan)
    ds = xr.Dataset({"c2_roll": (("c2_heading", "c2_froude", "c2_height"), roll),
                     "c2_by_speed": (("c2_heading", "c2_froude"), by), "c2": ((), value)},
                    coords={"c2_heading": heads, "c2_froude": fns, "c2_height": hgrid})
    ds.attrs.update(c2_threshold_deg=float(threshold_deg),
                    c2_missing_speeds=", ".join(f"{x:g}" for x in missing) or "none",
                    c2_missing_headings=", ".join(f"{x:g}" for x in no_heads) or "none",
                    c2_service_froude=math.nan if fn_service is None else float(fn_service),
                    c2_probability_breaking=float(np.sum(np.where(breaking, p.values, 0.0))),
                    c2_probability_left_out=float(np.nansum(np.where(occ & ~use & ~breaking, p.values, 0.0))))
    return ds


def sea_states(ship, sec, st: xr.Dataset, stab, wq: dict, cfg: dict, std: Standards, r_pr: float,
               depth: float, phi_f: tuple[float, str], pr: xr.Dataset, hydro: xr.Dataset | None = None,
               fn_service: float | None = None) -> tuple[list[Row], xr.Dataset]:
    """Rows and quantities of the level-2 sea-state physics of one ship.

    Parameters
    ----------
    stab : :class:`stabflow.criteria.is_code.Stability` (GZ curve, GM, KG).
    wq : the weather criterion's quantities (``wc_phi0``: heel under the steady wind, when a windage is given).
    cfg : the criteria section's ``sea_states`` settings (stations, acceleration_levels, heights, crest_positions).
    r_pr : level 1's R_PR (the parametric-rolling ratio the effective-wave variation is set against).
    depth : deck height amidships [m] (the default crew location).
    phi_f : (failure angle [degree], what governs it) (:func:`stabflow.criteria.dsa_run.failure_angle`).
    pr : the regular-wave parametric-roll cases (:func:`stabflow.criteria.sgisc.parametric_roll_cases`):
        headings, speeds and 1-DOF coefficients of the sea-state parametric-roll runs.
    fn_service : the service Froude number (None: not given), the top speed of C2 (:func:`parametric_c2`).
    """
    from stabflow.config import _fill_defaults, schema
    from stabflow.statistics.ensemble import build_model

    p = dsa.scatter_probabilities(std.raw["iacs_rec34_scatter"])
    scatter_src = str(std.raw["iacs_rec34_scatter"]["meta"]["document"])
    V, lcg, kg = float(st["volume"]), float(st["lcg"]), float(st["kg"])
    # ---- Grim's effective wave: pure loss and parametric rolling ----
    # sea states that never occur (count 0) or were not read are left out (NaN), never weighted
    occurs = _occurs(p)
    heff = effective_wave_heights(p, stab.lwl).where(occurs)
    ew = stability_on_effective_waves(sec, V, lcg, kg, stab.lwl, heff, stab.gm0, int(cfg["heights"]),
                                      int(cfg["crest_positions"]))
    ew["ew_roll_1dof"] = parametric_roll_sea_states(ew, pr, stab.lwl)
    # ---- beam seas without way: dead ship and lateral acceleration ----
    cond = _fill_defaults(schema("config")["properties"]["ensembles"]["items"],
                          {"name": "dead_ship", "ship": ship.name, "speed_kn": 0.0, "heading_deg": 90.0, "records": 1,
                           "stations": int(cfg["stations"]), "duration": 60.0, "dt": 0.1})
    model = build_model(ship, cond, hydro)
    bsm = beam_sea_model(model)
    # the steady wind heel: IS Code phi0 where a windage is given (infinite: no equilibrium under the
    # wind lever, the dead-ship rate is infinite), none without windage
    wind = "wc_phi0" in wq
    phi_w = float(wq["wc_phi0"]) if wind else 0.0
    c44 = None
    if wind and math.isfinite(phi_w) and phi_w != 0.0:
        # roll restoring about the heel: W GZ'(phi_w), the upright C44 (= W GM) scaled by GZ'(phi_w) / GM
        slope = np.gradient(stab.gz, np.radians(stab.heel))
        c44 = bsm.stiffness[1, 1] * float(np.interp(phi_w, stab.heel, slope)) / stab.gm0
    z_crew, crew_note = crew_height(ship, depth)
    h = z_crew - kg
    acc = std.get(f"{SG}.excessive_acceleration.level_1.lateral_acceleration_limit")
    levels = [float(a) for a in cfg["acceleration_levels"]]
    if acc.available and float(acc.value) not in levels:
        levels.append(float(acc.value))
    bs = beam_sea_cells(bsm, p.where(occurs), phi_f[0], phi_w, c44, h, sorted(levels))
    ds = ew.merge(bs)
    # ---- parametric rolling's C2 as the 2013 draft states it (roll angle: the standard, else its draft) ----
    thr = std.get(f"{SG}.parametric_rolling.level_2.roll_angle_threshold_deg")
    thr_deg = float(thr.value) if thr.available else float(thr.draft["value"]) if thr.draft else math.nan
    c2 = parametric_c2(ew, pr, p, stab.lwl, fn_service, thr_deg)
    ds = ds.merge(c2)
    ds.attrs.update(c2.attrs)
    # ---- long-term figures over the scatter table ----
    breaking = ds["ew_effective_height"] > BREAKING_STEEPNESS * stab.lwl
    p_break = _fraction(p, breaking.astype(float))
    pr_exceeds = (ds["ew_delta_gm_ratio"] > r_pr).astype(float).where(ds["ew_delta_gm_ratio"].notnull())
    frac_pr = _fraction(p, pr_exceeds)
    gm_neg = (ds["ew_gm_min"] < 0).astype(float).where(ds["ew_gm_min"].notnull())
    frac_gm = _fraction(p, gm_neg)
    ds_rate = _long_term(p, ds["ds_failure_rate"]) * dsa.SECONDS_PER_YEAR
    ea = np.array([_long_term(p, ds["ea_exceedance_rate"].isel(ea_level=i)) for i in range(ds.sizes["ea_level"])]) * dsa.SECONDS_PER_YEAR
    ds["ds_long_term_rate"] = ((), ds_rate)
    ds["ea_long_term_rate"] = ("ea_level", ea)
    # the same in log space: where every sea state's Gaussian tail underflows (rates far below 1e-308
    # per second) the plain sums are 0; their order of magnitude is kept here, never a bare 0
    year = math.log10(dsa.SECONDS_PER_YEAR)
    ds["ds_long_term_log10_rate"] = ((), _long_term_log10(p, ds["ds_failure_log10_rate"]) + year)
    ds["ea_long_term_log10_rate"] = ("ea_level", [_long_term_log10(p, ds["ea_exceedance_log10_rate"].isel(ea_level=i))
                                                  + year for i in range(ds.sizes["ea_level"])])
    ds["ew_probability_gm_negative"] = ((), frac_gm)
    ds["ew_probability_delta_gm_above_rpr"] = ((), frac_pr)
    ds["ew_probability_breaking"] = ((), p_break)
    ds["ds_heel_wind"] = ((), phi_w)
    ds["ds_failure_angle"] = ((), phi_f[0])
    ds["ea_crew_height"] = ((), z_crew)
    ds["ea_height_above_g"] = ((), h)
    ds["ea_roll_period"] = ((), bsm.roll_period)
    ds["ea_acceleration_per_roll"] = ((), G + 4 * math.pi**2 * h / bsm.roll_period**2)
    ds["sea_probability"] = (("hs", "tz"), p.values)
    ds.attrs.update(sea_states_scatter=scatter_src,
                    ds_wind=("none: no windage in the ship config (waves only)" if not wind else
                             "IS Code 2.3 steady wind lever (phi0)" if math.isfinite(phi_w) else
                             "IS Code 2.3 steady wind lever above GZmax: no equilibrium, failure rate infinite"),
                    ea_crew=crew_note,
                    ds_failure_angle_governed_by=phi_f[1])

    # ---- rows ----
    rows = []
    wc = std.get("sgisc.wave_data.pure_loss_and_parametric_roll_level2_wave_cases.cases")
    wave_miss = [] if wc.available else [f"{wc.key} (the circular's wave cases; stabflow weights Rec. 34 sea states)"]
    breaking_note = (f"; sea states whose effective wave would break (H_eff > L/7, left out of these probabilities) "
                     f"have probability {p_break:.3g}" if p_break > 0 else "")
    pl = f"{SG}.pure_loss_of_stability.level_2"
    miss = wave_miss + [f"{s.key} ({s.source})" for s in (std.get(f"{pl}.RPL1_angle_of_vanishing_stability_deg"),
                                                          std.get(f"{pl}.RPL2_heel_angle_deg"),
                                                          std.get(f"{pl}.RPL3_heel_lever_coefficient")) if not s.available]
    rows.append(against("pure loss of stability: max(CR1, CR2) on the effective waves", "SGISC pure loss, level 2",
                        math.nan, "-", std.get_or_missing(f"{pl}.RPL0", f"{CIRC}, pure loss level 2"), "<=", missing=miss,
                        note=f"Grim effective wave lambda = L of each Rec. 34 sea state (largest H_eff "
                             f"{_largest(ds['ew_effective_height'], p, '.2f', 'm')}): smallest angle of vanishing stability on it "
                             f"{_smallest(ds['ew_heel_vanishing'], p, '.1f', 'deg')}, smallest GZmax "
                             f"{_smallest(ds['ew_gz_max'], p, '.3f', 'm')}; probability of sea states with GMmin < 0 "
                             f"on the effective wave {frac_gm:.3g}" + breaking_note))
    pr_key = f"{SG}.parametric_rolling.level_2"
    rows.append(against("parametric rolling: C1 (GM variation on the effective waves)", "SGISC parametric rolling, level 2",
                        math.nan, "-", std.get_or_missing(f"{pr_key}.RPR0", f"{CIRC}, parametric rolling level 2"), "<=",
                        missing=wave_miss + ["the circular's speed condition of C1 (not read)"],
                        note=f"largest delta GM / GM on the effective wave {_largest(ds['ew_delta_gm_ratio'], p, '.3f')}; "
                             f"probability of sea states where it exceeds level 1's R_PR {r_pr:.3f}: {frac_pr:.3g}"
                             + breaking_note))
    c2_miss = list(wave_miss) + ["the effective wave height H_i of C2 (the 2013 draft leaves it to an explanatory note; "
                                 "stabflow's Grim wave here)"]
    if not thr.available:
        c2_miss.append(f"{thr.key} ({thr.source})")
    if fn_service is None:
        c2_miss.append("the ship's service speed (criteria.service_speed_kn): the top speed of C2")
    elif ds.attrs["c2_missing_speeds"] != "none":
        c2_miss.append(f"the 1-DOF coefficients at Fn {ds.attrs['c2_missing_speeds']} (criteria.parametric.froude_numbers)")
    if ds.attrs["c2_missing_headings"] != "none":
        c2_miss.append(f"the heading(s) {ds.attrs['c2_missing_headings']} deg of C2 (criteria.parametric.headings_deg: "
                       "the draft takes head and following seas)")
    if not math.isfinite(thr_deg):
        c2_miss.append("a roll angle for C2 (neither the standard nor a draft)")
    rows.append(against("parametric rolling: C2 (1-DOF roll on the effective waves)", "SGISC parametric rolling, level 2",
                        float(ds["c2"]), "-", std.get_or_missing(f"{pr_key}.RPR0", f"{CIRC}, parametric rolling level 2"), "<=",
                        missing=c2_miss, drafted=[thr],
                        note=f"the 2013 draft's C2 (SLF 55/WP.3 Annex 1, 2.11.3.3-2.11.3.4.1): per speed and heading the "
                             f"probability of the sea states whose roll amplitude on the effective wave exceeds "
                             f"{thr_deg:g} deg, averaged over Fn {', '.join(f'{x:g}' for x in ds.c2_froude.values) or 'none'} "
                             f"and headings {', '.join(f'{x:g}' for x in pr.pr_heading.values)} deg (the 2013 text compares C2 "
                             f"with RPR1, bracketed [0.15 or 0.25]); largest 1-DOF roll with GZ on the passing effective wave "
                             f"{_largest(ds['ew_roll_1dof'], p, '.1f', 'deg')} (from {float(pr.attrs['pr_phi0_deg']):g} deg heel); "
                             f"sea states whose effective wave would break, counted as exceeding: probability "
                             f"{ds.attrs['c2_probability_breaking']:.3g}"))
    dl1 = std.get_or_missing(f"{SG}.dead_ship.level_1.standard", f"{CIRC}, dead ship level 1")
    area = (f"the IS Code weather criterion's areas a = {wq['wc_area_a']:.4f}, b = {wq['wc_area_b']:.4f} m rad"
            if "wc_area_a" in wq else "no windage in the ship config: the weather criterion's areas are not computed")
    rows.append(against("dead ship condition: weather-criterion type check", "SGISC dead ship, level 1", math.nan, "-", dl1,
                        ">=", missing=["the circular's level-1 steepness and roll-back tables (not read)"],
                        note=f"the level-1 check is of the weather criterion's kind; {area}"))
    rds = std.get_or_missing(f"{SG}.dead_ship.level_2.RDS0", f"{CIRC}, dead ship level 2")
    rate_txt = ("not computed (no failure angle)" if math.isnan(ds_rate) else "infinite (the steady wind heel reaches the "
                "failure angle or has no equilibrium)" if math.isinf(ds_rate) else
                f"{rate_text(ds_rate, float(ds['ds_long_term_log10_rate']))} per year")
    rows.append(against("dead ship condition: long-term failure index C", "SGISC dead ship, level 2", math.nan, "-", rds, "<=",
                        missing=["the circular's exposure time and index C (not read)"],
                        note=f"beam seas without way, linear roll with stochastically linearised damping (a lower estimate: "
                             f"see the validation page): failure (roll beyond {phi_f[0]:.1f} deg, {phi_f[1]}) rate over the "
                             f"Rec. 34 table {rate_txt}; wind heel {phi_w:.2f} deg ({ds.attrs['ds_wind']}); largest roll "
                             f"sigma {_largest(ds['ds_roll_std'], p, '.2f', 'deg')}"))
    rows.append(against("excessive acceleration: lateral acceleration at the crew location", "SGISC excessive acceleration, level 1",
                        math.nan, "m/s2", std.get_or_missing(f"{SG}.excessive_acceleration.level_1.REA1", f"{CIRC}, level 1"),
                        "<=", missing=["the circular's level-1 roll amplitude (not read)"],
                        note=f"{crew_note}, {h:.2f} m above G; natural roll period {bsm.roll_period:.2f} s; lateral "
                             f"acceleration per radian of roll g + 4 pi^2 h / T^2 = {float(ds['ea_acceleration_per_roll']):.3f} m/s2"))
    lv = ds["ea_level"].values
    rows.append(against("excessive acceleration: long-term index C", "SGISC excessive acceleration, level 2", math.nan, "-",
                        std.get_or_missing(f"{SG}.excessive_acceleration.level_2.REA2", f"{CIRC}, level 2"), "<=",
                        missing=([] if acc.available else [f"{acc.key} (the acceleration limit)"])
                        + ["the circular's index C (not read)"],
                        note="beam seas without way, upright, at the crew location: rate of |a_y| above "
                             + ", ".join(f"{a:g} m/s2 {rate_text(r, lr, '.3g')}"
                                         for a, r, lr in zip(lv, ea, ds["ea_long_term_log10_rate"].values))
                             + " per year over the Rec. 34 table"
                             + (f" (the limit {float(acc.value):g} m/s2 from the standards)" if acc.available else "")
                             + f"; largest sigma {_largest(ds['ea_acceleration_std'], p, '.2f', 'm/s2')}"))
    return rows, ds
