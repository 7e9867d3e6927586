"""One function per pipeline step (Snakemake rule): read the inputs, call the library, write the
outputs atomically. The workflow scripts (``workflow/scripts/*.py``) and the command line
(:mod:`stabflow.cli`) both call these, so a step gives the same files either way."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from stabflow import StabflowError
from stabflow.config import load_ship, step_settings


def _open_optional(path) -> xr.Dataset | None:
    """The dataset at ``path`` loaded into memory, or None when no path is given."""
    if not path:
        return None
    with xr.open_dataset(path) as d:
        return d.load()


def run_hull(ship_yaml, out_nc, figure=None) -> xr.Dataset:
    """hull step: stations and Bonjean tables → NetCDF (+ body plan figure)."""
    from stabflow.geometry import build_hull
    from stabflow.io import write_netcdf
    from stabflow.plots.geometry import body_plan

    ship = load_ship(ship_yaml)
    ds = build_hull(ship)
    if figure:
        body_plan(ds, figure)
    write_netcdf(ds, out_nc)
    return ds


def run_statics(ship_yaml, hull_nc, out_nc, figure=None) -> xr.Dataset:
    """statics step: particulars and calm-water GZ → NetCDF (+ GZ figure)."""
    from stabflow.io import write_netcdf
    from stabflow.plots.hydrostatics import gz_curves
    from stabflow.hydrostatics.statics import compute_statics

    ship = load_ship(ship_yaml)
    with xr.open_dataset(hull_nc) as h:
        hull = h.load()
    ds = compute_statics(ship, hull)
    if figure:
        gz_curves({"calm water": ds["gz"]}, figure, title=f"{ship.name}: calm-water GZ, free trim", gm=float(ds["gm"]))
    write_netcdf(ds, out_nc)
    return ds


def _load_statics(ship_yaml, hull_nc, statics_nc):
    ship = load_ship(ship_yaml)
    with xr.open_dataset(hull_nc) as h, xr.open_dataset(statics_nc) as s:
        return ship, h.load(), s.load()


def run_waves(ship_yaml, hull_nc, statics_nc, cfg: dict, out_nc, fig_gm=None, fig_gz=None) -> xr.Dataset:
    """waves step: wave-pass GM(x_c), GZ(phi; x_c) and crest/trough/calm GZ → NetCDF + figures."""
    import numpy as np

    from stabflow.geometry import Sections
    from stabflow.io import write_netcdf
    from stabflow.plots.hydrostatics import gz_curves
    from stabflow.plots.stability_in_waves import gm_wave_pass
    from stabflow.stability_in_waves.wave_pass import crest_trough_calm, wave_pass

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    sec = Sections(hull)
    V, lcg, kg, L = (float(st[k]) for k in ("volume", "lcg", "kg", "lwl"))
    heel = np.round(np.arange(0.0, cfg["heel_max"] + 1e-9, cfg["heel_step"]), 10)
    ds = wave_pass(sec, V, lcg, kg, L, cfg["wavelength_ratios"], cfg["steepness"], cfg["crest_positions"], heel)
    ct = crest_trough_calm(sec, V, lcg, kg, L, cfg["crest_trough_steepness"], np.round(np.arange(0.0, 180.01, 1.0), 10))
    unconverged = ds.attrs["unconverged_points"] + ct.attrs["unconverged_points"]
    ds = xr.merge([ds, ct.rename(heel="heel_full")], compat="override")
    ds.attrs["unconverged_points"] = unconverged
    ds["heel_full"].attrs.update(units="degree", long_name="heel angle of the crest/trough/calm curves")
    ds.attrs.update(ship=ship.name, lwl=L, kg=kg, crest_trough_steepness=cfg["crest_trough_steepness"])
    if fig_gm:
        gm_wave_pass(ds, fig_gm, float(st["gm"]), title=f"{ship.name}: GM as the wave crest passes")
    if fig_gz:
        s = cfg["crest_trough_steepness"]
        gz_curves({"crest amidships": ct["gz_crest"], "trough amidships": ct["gz_trough"], "calm water": ct["gz_calm"]},
                  fig_gz, title=f"{ship.name}: GZ on a wave λ = L, H/λ = {s:g}")
    write_netcdf(ds, out_nc)
    return ds


def run_early_stage(ship_yaml, hull_nc, statics_nc, cfg: dict, out_nc, out_csv=None) -> xr.Dataset:
    """early_stage step: GM_cr and metric C per sea state → NetCDF (+ CSV)."""
    from stabflow.hydrostatics.statics import Particulars
    from stabflow.stability_in_waves.early_stage import assess
    from stabflow.geometry import Sections
    from stabflow.io import atomic_text, write_netcdf

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    ds = assess(Sections(hull), Particulars.from_statics(st), cfg["sea_states"], cfg)
    ds.attrs["ship"] = ship.name
    if out_csv:
        df = ds.to_dataframe().reset_index()
        df.insert(0, "ship", ship.name)
        atomic_text(df.to_csv(index=False, float_format="%.6g"), out_csv)
    write_netcdf(ds, out_nc)
    return ds


def run_early_stage_summary(metric_ncs, out_csv, out_png):
    """All ships' metric C in one CSV table and a bar chart (paper 002, Figure 6)."""
    import pandas as pd

    from stabflow.io import atomic_text
    from stabflow.plots.stability_in_waves import metric_bars

    frames = []
    for f in metric_ncs:
        with xr.open_dataset(f) as ds:
            df = ds[["hs", "tm", "metric_c", "mean_tbc"]].to_dataframe().reset_index()
            df.insert(0, "ship", ds.attrs["ship"])
            df["gm_cr"] = float(ds["gm_cr"])
            frames.append(df)
    table = pd.concat(frames, ignore_index=True)
    atomic_text(table.to_csv(index=False, float_format="%.6g"), out_csv)
    metric_bars(table, out_png)
    return table


def run_hydro(ship_yaml, hull_nc, statics_nc, rao_cfg: dict, condition: str, out_nc) -> xr.Dataset:
    """hydro step: Capytaine coefficients at the natural frequencies and linear peer RAOs → NetCDF."""
    from stabflow.dynamics.model import config_coefficients
    from stabflow.dynamics.hydro import bem_mesh, hydro_dataset
    from stabflow.dynamics.linear import stiffness_matrix
    from stabflow.dynamics.model import equilibrium
    from stabflow.geometry import Sections
    from stabflow.io import write_netcdf

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    cond = {c["name"]: c for c in rao_cfg["conditions"]}[condition]
    sec = Sections(hull)
    co = config_coefficients(ship, sec, st)
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    C = stiffness_matrix(sec, ship.rho, float(st["lcg"]), float(st["kg"]), h0, th0)
    ds = hydro_dataset(bem_mesh(ship), st, co, ship.rho, cond["heading"], float(st["lwl"]), rao_cfg["wavelength_ratios"], C, h0, th0)
    ds.attrs.update(ship=ship.name, condition=condition, note="zero speed (Capytaine without forward speed)")
    write_netcdf(ds, out_nc)
    return ds


def run_radiation(ship_yaml, out_nc, figure=None, progress: bool = True) -> xr.Dataset:
    """radiation step (issue 17): heave-pitch added mass and damping of the hull mesh over frequency
    (Capytaine), the fitted memory model of the 6-DOF Cummins equation → NetCDF + figure."""
    from stabflow.dynamics.radiation import ship_radiation, uses_memory
    from stabflow.io import write_netcdf
    from stabflow.plots.broaching import radiation_figure

    ship = load_ship(ship_yaml)
    if not uses_memory(ship):
        raise StabflowError(f"{ship_yaml}: manoeuvring.heave_pitch_radiation: the ship uses the constant coefficients "
                            "(set it to memory for the radiation step)")
    ds = ship_radiation(ship, progress=progress)  # its attributes name the ship
    if figure:
        radiation_figure(ds, figure)
    write_netcdf(ds, out_nc)
    return ds


def run_rao(ship_yaml, hull_nc, statics_nc, rao_cfg: dict, condition: str, out_nc, fig=None, hydro_nc=None) -> xr.Dataset:
    """rao step: regular-wave sweep of the time-domain model for one condition → NetCDF + figure.

    With ``hydro_nc`` (Capytaine) the added mass and damping come from it and its linear RAOs are
    plotted beside the time-domain ones."""
    from stabflow.dynamics import coefficients
    from stabflow.dynamics.rao import rao_sweep
    from stabflow.constants import KNOT
    from stabflow.geometry import Sections
    from stabflow.io import write_netcdf
    from stabflow.plots.dynamics import rao_curves

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    cond = {c["name"]: c for c in rao_cfg["conditions"]}[condition]
    sec = Sections(hull)
    hydro = _open_optional(hydro_nc)
    co = coefficients(ship, sec, st, hydro if ship.data["dynamics"]["hydro"] == "capytaine" else None,
                      speed=cond["speed_kn"] * KNOT)
    ds = rao_sweep(sec, st, co, ship.rho, float(st["lwl"]), rao_cfg["wavelength_ratios"], rao_cfg["steepness"],
                   cond["heading"], cond["speed_kn"] * KNOT, rao_cfg["dt"])
    ds.attrs.update(ship=ship.name, condition=condition, roll_period=co.natural_period("roll"),
                    heave_period=co.natural_period("heave"), pitch_period=co.natural_period("pitch"),
                    hydro=ship.data["dynamics"]["hydro"], roll_damping=co.roll_damping, b44=co.b44, b44q=co.b44q)
    if fig:
        rao_curves(ds, fig, peer=hydro, title=f"{ship.name}, {condition}: heading {cond['heading']:g}°, {cond['speed_kn']:g} kn, "
                   f"H/λ = {rao_cfg['steepness']:g}")
    write_netcdf(ds, out_nc)
    return ds


def run_roll_decay(ship_yaml, hull_nc, statics_nc, out_nc, fig=None, hydro_nc=None) -> xr.Dataset:
    """roll_decay step: calm-water free roll from ``dynamics.decay_heel_deg`` with the ship's own
    coefficients (zero speed), its peaks and equivalent damping per cycle, and with
    ``roll_damping: ikeda`` Ikeda's components against roll amplitude and speed → NetCDF + figure."""
    import numpy as np

    from stabflow.dynamics import coefficients, simulate
    from stabflow.geometry import Sections
    from stabflow.io import annotate, write_netcdf
    from stabflow.plots.roll_damping import roll_decay_figure
    from stabflow.statistics.signals import local_peaks

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    sec = Sections(hull)
    d = ship.data["dynamics"]
    hydro = _open_optional(hydro_nc) if d["hydro"] == "capytaine" else None
    co = coefficients(ship, sec, st, hydro, speed=0.0)
    heel = float(d["decay_heel_deg"])
    tn = co.natural_period("roll")
    dt = min(0.05, tn / 200)
    rec = simulate(sec, st, co, ship.rho, (np.array([]),) * 3, 0.0, 0.0, 15 * tn, dt, phi0_deg=heel)
    t, roll = rec["time"].values, rec["roll"].values
    tp, vp = local_peaks(t, roll, 0.0)
    # equivalent damping per cycle from successive positive peaks: zeta = delta / sqrt(4 pi^2 + delta^2)
    delta = np.log(vp[:-1] / vp[1:]) if len(vp) > 1 else np.zeros(0)
    ds = xr.Dataset(
        {"roll": ("time", roll), "peak_time": ("peak", tp), "peak_roll": ("peak", vp),
         "cycle_amplitude": ("cycle", 0.5 * (vp[:-1] + vp[1:]) if len(vp) > 1 else np.zeros(0)),
         "cycle_zeta": ("cycle", delta / np.sqrt(4 * np.pi**2 + delta**2))},
        coords={"time": t},
        attrs=dict(ship=ship.name, decay_heel_deg=heel, roll_damping=co.roll_damping, b44=co.b44, b44q=co.b44q,
                   roll_period=tn, dt=dt, capsized=int(rec.attrs["capsized"])),
    )
    if co.roll_damping == "ikeda":
        from stabflow.constants import G
        from stabflow.dynamics.model import ikeda_inputs
        from stabflow.dynamics.roll_damping import damping_vs_amplitude, damping_vs_speed, section_parameters

        sp = section_parameters(sec, st)
        omega = co.natural_frequency("roll")
        kw = dict(omega=omega, wave=float(hydro["damping_roll"]), **ikeda_inputs(ship))
        amp = damping_vs_amplitude(sp, amplitudes_deg=np.arange(1.0, 41.0), speed=0.0, **kw)
        spd = damping_vs_speed(sp, roll_amplitude_deg=float(d["ikeda_amplitude_deg"]),
                               speeds=np.linspace(0.0, 0.3 * np.sqrt(G * float(st["lwl"])), 13), **kw)
        for v in amp.data_vars:
            if "roll_amplitude" in amp[v].dims:
                ds[f"amp_{v}"] = amp[v]
        for v in spd.data_vars:
            ds[f"speed_{v}"] = spd[v]
        ds.attrs.update(ikeda_amplitude_deg=float(d["ikeda_amplitude_deg"]), ikeda_omega=omega)
    ds = annotate(ds)
    if fig:
        roll_decay_figure(ds, fig, title=f"{ship.name}: calm-water roll decay from {heel:g}° (B44 {co.b44:.3g} N m s/rad, "
                          f"B44q {co.b44q:.3g} N m s²/rad², roll damping from {co.roll_damping})")
    write_netcdf(ds, out_nc)
    return ds


def run_criteria(ship_yaml, hull_nc, statics_nc, cfg: dict, out_nc, figure=None, hydro_nc=None,
                 radiation_nc=None) -> xr.Dataset:
    """criteria step: IS Code and second-generation rows with every intermediate quantity → NetCDF
    (+ GZ / weather-criterion and GM-on-the-wave figure, and ``<ship>_sea_states.png`` beside it);
    ``radiation_nc``: the radiation step's file of a ship with the heave-pitch memory model."""
    from stabflow.criteria.assess import assess
    from stabflow.io import write_netcdf
    from stabflow.plots.criteria import criteria_figure, sea_state_figure

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    ds = assess(ship, hull, st, cfg, hydro=_open_optional(hydro_nc), radiation=_open_optional(radiation_nc))
    if figure:
        criteria_figure(ds, figure, title=f"{ship.name}: IS Code weather criterion and GM on a wave λ = L")
        # the level-2 sea-state figure beside it: <ship>_sea_states.png
        sea_state_figure(ds, Path(figure).parent / f"{ship.name}_sea_states.png",
                         title=f"{ship.name}: second-generation level-2 physics over the IACS Rec. 34 sea states")
    write_netcdf(ds, out_nc)
    return ds


def run_dsa(ship_yaml, criteria_nc, cfg: dict, out_nc, figures: dict | None = None, hydro_nc=None,
            progress: bool = True, overrides=None) -> xr.Dataset:
    """dsa step: direct stability assessment of one ship over the scatter table → NetCDF (+ the
    contribution map and the operational polar); ``overrides``: the criteria override file (the
    pipeline's ``criteria.overrides``), as the criteria step reads it."""
    from stabflow.criteria.dsa_run import assess_dsa
    from stabflow.criteria.standards import Standards
    from stabflow.io import write_netcdf
    from stabflow.plots.criteria import dsa_figures

    ship = load_ship(ship_yaml)
    crit = _open_optional(criteria_nc)
    ds = assess_dsa(ship, crit, cfg, _open_optional(hydro_nc), std=Standards(overrides), progress=progress)
    import logging

    logging.getLogger(__name__).info("dsa %s: CPU seconds %s", ship.name, ds.encoding.get("cpu"))
    if figures:
        dsa_figures(ds, figures, ship.name)
    write_netcdf(ds, out_nc)
    return ds


def run_validate_criteria(ship_yaml, criteria_nc, out_nc, dsa_nc=None) -> xr.Dataset:
    """validation of the criteria step (closed forms of the box barge, the level-1 routes, the beam-sea
    model) and of the DSA's screening (``dsa_nc``, the ship's ``_dsa.nc``; None: no DSA for the
    ship) → NetCDF rows."""
    from stabflow.io import write_netcdf
    from stabflow.validation import checks_dataset
    from stabflow.validation.criteria import criteria_checks

    ship = load_ship(ship_yaml)
    ds = checks_dataset(ship.name, "criteria", criteria_checks(ship, _open_optional(criteria_nc),
                                                                _open_optional(dsa_nc)))
    write_netcdf(ds, out_nc)
    return ds


def run_validate_dsa(out_nc) -> xr.Dataset:
    """validation of the DSA aggregation against Rice's exact rate (linear 1-DOF roll) and of Grim's
    effective wave against direct projection → NetCDF rows."""
    from stabflow.criteria.dsa import dsa_verification
    from stabflow.io import write_netcdf
    from stabflow.validation import checks_dataset
    from stabflow.validation.criteria import dsa_checks, grim_check

    ds = checks_dataset("dsa_linear", "criteria", dsa_checks(dsa_verification()) + [grim_check()])
    write_netcdf(ds, out_nc)
    return ds


def run_validate_statics(ship_yaml, hull_nc, statics_nc, out_nc) -> xr.Dataset:
    """validation of the statics step → NetCDF rows (check, value, tolerance, PASS/FAIL)."""
    from stabflow.io import write_netcdf
    from stabflow.validation import checks_dataset
    from stabflow.validation.statics import statics_checks

    ship = load_ship(ship_yaml)
    with xr.open_dataset(hull_nc) as h, xr.open_dataset(statics_nc) as s:
        hull, st = h.load(), s.load()
    ds = checks_dataset(ship.name, "statics", statics_checks(ship, hull, st))
    write_netcdf(ds, out_nc)
    return ds


def run_validate_waves(ship_yaml, hull_nc, statics_nc, waves_nc, metric_nc, es_cfg: dict, out_nc) -> xr.Dataset:
    """validation of the waves and early-stage steps → NetCDF rows."""
    from stabflow.io import write_netcdf
    from stabflow.validation import checks_dataset
    from stabflow.validation.waves import waves_checks

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    with xr.open_dataset(waves_nc) as w, xr.open_dataset(metric_nc) as m:
        waves, metric = w.load(), m.load()
    ds = checks_dataset(ship.name, "waves", waves_checks(ship, hull, st, waves, metric, es_cfg))
    write_netcdf(ds, out_nc)
    return ds


def run_validate_dynamics(ship_yaml, hull_nc, statics_nc, out_nc) -> xr.Dataset:
    """validation of the 3-DOF time-domain model → NetCDF rows."""
    from stabflow.io import write_netcdf
    from stabflow.validation import checks_dataset
    from stabflow.validation.dynamics import dynamics_checks

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    ds = checks_dataset(ship.name, "dynamics", dynamics_checks(ship, hull, st))
    write_netcdf(ds, out_nc)
    return ds


def run_validate_ensemble(ship_yaml, cond: dict, ensemble_nc, out_nc, extremes_nc=None, splittime_nc=None,
                          hydro_nc=None, radiation_nc=None, threads: int = 1) -> xr.Dataset:
    """validation of an ensemble condition (seaway, step size) and of its extremes and split-time
    estimates against the brute force → NetCDF rows (key ``<ship>_<condition>``); ``threads`` for
    the step-size re-simulation (the files do not depend on it)."""
    from stabflow.statistics.ensemble import build_model
    from stabflow.io import write_netcdf
    from stabflow.validation import checks_dataset
    from stabflow.validation.ensemble import ensemble_checks

    model = build_model(load_ship(ship_yaml), cond, _open_optional(hydro_nc), _open_optional(radiation_nc))
    ens = _open_optional(ensemble_nc)
    rows = ensemble_checks(model, ens, _open_optional(extremes_nc), _open_optional(splittime_nc), threads=threads)
    ds = checks_dataset(model.ship.name, "ensemble", rows)
    ds.attrs["condition"] = cond["name"]
    write_netcdf(ds, out_nc)
    return ds


def run_ensemble_shard(ship_yaml, cond: dict, shard: int, out_nc, threads: int = 1, hydro_nc=None, progress=True,
                       radiation_nc=None):
    """ensemble step, one shard: records [shard * shard_records, ...) of condition ``cond`` → NetCDF."""
    import numba

    from stabflow.statistics.ensemble import build_model, run_shard
    from stabflow.io import write_netcdf

    ship = load_ship(ship_yaml)
    hydro = _open_optional(hydro_nc)
    numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    model = build_model(ship, cond, hydro, _open_optional(radiation_nc))
    n = int(cond["shard_records"])
    recs = range(shard * n, min((shard + 1) * n, int(cond["records"])))
    if len(recs) == 0:
        raise StabflowError(f"ensemble {cond['name']}: shard {shard} is beyond records = {cond['records']}")
    ds = run_shard(model, recs, progress=progress)
    write_netcdf(ds, out_nc)
    return ds


def run_ensemble_merge(shard_ncs, out_nc, fig_distribution=None, fig_spectra=None, fig_samples=None):
    """ensemble step, merge: shards → ensemble NetCDF + figures."""
    from stabflow.statistics.ensemble import merge
    from stabflow.io import write_netcdf
    from stabflow.plots.ensemble import response_spectra, roll_distribution, time_histories

    shards = []
    for p in shard_ncs:
        with xr.open_dataset(p) as d:
            shards.append(d.load())
    ens = merge(shards)
    a = ens.attrs
    head = (f"{a['condition']}: Hs {a['hs']:g} m, Tp {a['tp']:g} s, {a['speed_kn']:g} kn, "
            f"heading {a['heading_deg']:g}°, {float(ens['exposure_hours']):.0f} h")
    if fig_distribution:
        roll_distribution(ens, fig_distribution, f"Roll distribution: {head}")
    if fig_spectra:
        response_spectra(ens, fig_spectra, f"Encounter spectra: {head}")
    if fig_samples:
        time_histories(ens, fig_samples, f"Sample records: {head}")
    write_netcdf(ens, out_nc)
    return ens


def condition_key(attrs) -> str:
    """The ensemble key <ship>_<name> of an ensemble dataset's attributes (the pipeline names its
    conditions by the key already; the CLI and the library may use the bare name)."""
    c, ship = str(attrs["condition"]), str(attrs["ship"])
    return c if c.startswith(f"{ship}_") else f"{ship}_{c}"


def run_extremes(ensemble_nc, cfg: dict, out_nc, fig_threshold=None, fig_rate=None, fig_validation=None):
    """extremes step: envelope POT + GPD rates from sample blocks, validated against the ensemble."""
    from stabflow.statistics.extremes import analyse
    from stabflow.io import write_netcdf
    from stabflow.plots.extremes import exceedance_rate_curve, extremes_validation, threshold_diagnostics

    with xr.open_dataset(ensemble_nc) as e:
        ens = e.load()
    cfg = step_settings(cfg, "extremes", condition_key(ens.attrs))
    ds, extra = analyse(ens, cfg, progress=True)
    a = ens.attrs
    head = f"{a['condition']}: Hs {a['hs']:g} m, {a['speed_kn']:g} kn, heading {a['heading_deg']:g}°"
    if fig_threshold:
        threshold_diagnostics(extra["sample_series"], extra["tau"], extra["u"], float(ds["sample_roll_std"][0]),
                              fig_threshold, f"Threshold selection ({extra['hours']:.0f} h sample): {head}")
    if fig_rate:
        exceedance_rate_curve(extra, ds["target"].values, fig_rate, f"Roll exceedance rate: {head}")
    if fig_validation:
        extremes_validation(ds, fig_validation, f"GPD from {extra['hours']:.0f} h samples vs brute force "
                            f"({ds.attrs['ensemble_hours']:.0f} h): {head}")
    write_netcdf(ds, out_nc)
    return ds


def run_splittime(ship_yaml, cond: dict, ensemble_nc, cfg: dict, out_nc, figures: dict | None = None, threads: int = 1,
                  hydro_nc=None, radiation_nc=None):
    """splittime step: crossings, motion perturbations, GPD of the metric → capsize rate + figures."""
    import numba

    from stabflow.statistics.ensemble import build_model
    from stabflow.io import write_netcdf
    from stabflow.plots.splittime import splittime_figures
    from stabflow.statistics.splittime import analyse

    hydro = _open_optional(hydro_nc)
    numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    model = build_model(load_ship(ship_yaml), cond, hydro, _open_optional(radiation_nc))
    with xr.open_dataset(ensemble_nc) as e:
        ens = e.load()
    cfg = step_settings(cfg, "splittime", condition_key(ens.attrs))
    ds = analyse(model, ens, cfg, threads=threads, progress=True)
    if figures:
        a = ens.attrs
        splittime_figures(model, ds, figures, f"Split-time vs brute force: {a['condition']}, Hs {a['hs']:g} m, "
                          f"{a['speed_kn']:g} kn, heading {a['heading_deg']:g}°")
    write_netcdf(ds, out_nc)
    return ds


#: key of the 1-DOF capsize case in results/validation/<key>_capsize.nc
CAPSIZE_1DOF_KEY = "box1dof"


def run_capsize_1dof(cfg: dict, out_nc, validation_nc, figure=None, threads: int = 1, progress: bool = True) -> xr.Dataset:
    """capsize_1dof step: 1-DOF box-barge roll, brute force and independent samples of split-time and
    extremes estimates → NetCDF, validation rows (coverage, median ratio, threshold consistency), figure."""
    from stabflow.io import write_netcdf
    from stabflow.plots.capsize_1dof import capsize_1dof_figure
    from stabflow.validation import checks_dataset
    from stabflow.validation.capsize_1dof import analyse, capsize_1dof_checks

    if not cfg.get("bands"):
        raise StabflowError("config: capsize_1dof: bands is empty: nothing to run")
    ds = analyse(cfg, threads=threads, progress=progress)
    rows = checks_dataset(CAPSIZE_1DOF_KEY, "capsize", capsize_1dof_checks(ds))
    if figure:
        capsize_1dof_figure(ds, figure)
    write_netcdf(ds, out_nc)
    write_netcdf(rows, validation_nc)
    return ds


def broaching_figure_names(config: dict) -> list[str]:
    """Figure stems of the broaching step: motions per loading, the snapshot strip, the manoeuvres,
    the resistance curve and, with a ``map`` section, the probability map."""
    if "broaching" not in config:
        return []
    b = config["broaching"]
    return [f"motions_{k}" for k in b["loadings"]] + ["strip", "manoeuvres", "resistance"] + (["map"] if "map" in b else [])


def run_broaching(config: dict, ships_dir, out_nc, validation_nc, figures: dict | None = None,
                  progress: bool = True, radiation_nc=None) -> xr.Dataset:
    """broaching step (issue 17): paper 004's stern-quartering cases with the 6-DOF model, calm-water
    manoeuvres, and the surf-riding threshold checks → NetCDF, validation rows, figures."""
    from pathlib import Path

    from stabflow.dynamics.broaching import (manoeuvre_checks, map_step_row, probability_map, scenario,
                                             scenario_step_row)
    from stabflow.io import write_netcdf
    from stabflow.plots.broaching import (manoeuvres_figure, map_figure, motions_figure, resistance_figure,
                                          strip_figure)
    from stabflow.validation import checks_dataset

    cfg = config["broaching"]
    ship = load_ship(Path(ships_dir) / f"{cfg['ship']}.yaml")
    rad = _open_optional(radiation_nc)
    from stabflow.dynamics.radiation import ship_radiation, uses_memory

    if rad is None and uses_memory(ship):  # computed once here rather than for every model
        rad = ship_radiation(ship, progress=progress)
    ds = scenario(ship, cfg, progress=progress, radiation=rad)
    man, rows, tracks, zigzags = manoeuvre_checks(ship, cfg, radiation=rad)
    rows.append(scenario_step_row(ds))
    ds = ds.merge(man)
    ds.attrs.update(man.attrs)
    if "map" in cfg:
        pm = probability_map(ship, cfg, progress=progress, radiation=rad)
        rows.append(map_step_row(pm))
        ds = ds.merge(pm)
        ds.attrs.update(pm.attrs)
    if figures:
        for lname in ds.loading.values:
            motions_figure(ds, str(lname), figures[f"motions_{lname}"])
        # paper 004 Fig. 7 is case R-2 (lambda 30.5 m); else the first regular case
        cases = [str(c) for c in ds.case.values]
        ds.attrs.update(strip_case="R-2" if "R-2" in cases else cases[0], strip_loading=str(ds.loading.values[0]))
        strip_figure(ds, ds.attrs["strip_loading"], ds.attrs["strip_case"], figures["strip"])
        manoeuvres_figure(tracks, zigzags, figures["manoeuvres"])
        resistance_figure(ds, figures["resistance"])
        if "map" in figures:
            map_figure(ds, figures["map"])
    write_netcdf(ds, out_nc)
    write_netcdf(checks_dataset(cfg["ship"], "manoeuvring", rows), validation_nc)
    return ds


def derivative_figure_names(config: dict) -> list[str]:
    """Figure stems of the derivative step (results/derivative/<ship>_<stem>.png) for the pipeline config."""
    from stabflow.dynamics.derivative import compared_ensembles

    cfg = config["derivative"]
    return (["fit", "transfer_functions", "map"] + (["irregular", "running"] if compared_ensembles(config) else [])
            + (["irregular_map"] if "irregular_map" in cfg else []))


def run_derivative(config: dict, ships_dir, out_nc, validation_nc, figures: dict | None = None,
                   ensembles: dict | None = None, progress: bool = True, cpu_tsv=None) -> xr.Dataset:
    """derivative step (issue 18): the derivative model (paper 001) fitted from the volume-based
    forces, its regular-wave parametric-roll map against the full model, the two models' ensembles
    of one sea compared (``ensembles`` {"full": path, "derivative": path} of the ensemble.nc files of
    :func:`stabflow.dynamics.derivative.compared_ensembles`), and the
    irregular-sea map over speed x peak period → NetCDF with the fit residuals, validation rows,
    figures."""
    from pathlib import Path

    from stabflow.dynamics.derivative import compared_ensembles, derivative_study, irregular_map
    from stabflow.io import write_netcdf
    from stabflow.plots import derivative as P
    from stabflow.validation import checks_dataset
    from stabflow.validation.derivative import derivative_checks, irregular_checks
    from stabflow.waves.seaway import Seaway

    cfg = config["derivative"]
    ship = load_ship(Path(ships_dir) / f"{cfg['ship']}.yaml")
    model, dm, ds = derivative_study(ship, cfg, progress=progress)
    cpu = ds.encoding.pop("cpu", {})
    rows = derivative_checks(model, dm, ds)
    pair = compared_ensembles(config)
    if pair:
        if not ensembles:
            raise StabflowError(f"derivative: ensembles {pair['full']} and {pair['derivative']} are compared; give "
                                "their ensemble.nc files")
        with xr.open_dataset(ensembles["full"]) as f, xr.open_dataset(ensembles["derivative"]) as d:
            full, der = f.load(), d.load()
        conds = {f"{c['ship']}_{c['name']}": c for c in config.get("ensembles", [])}
        sea = Seaway.from_config(conds[pair["full"]]["sea"])
        rows += irregular_checks(full, der, float(cfg["level_deg"]), sea, int(full.attrs["seed"]))
        if figures:
            P.irregular_figure(full, der, figures["irregular"], float(cfg["level_deg"]))
            P.running_variance_figure(full, figures["running"])
    if "irregular_map" in cfg:
        im = irregular_map(ship, cfg, progress=progress)
        ds = ds.merge(im)
        ds.attrs.update(im.attrs)
        if figures:
            P.irregular_map_figure(ds, figures["irregular_map"])
    if figures:
        P.fit_figure(model, dm, figures["fit"])
        P.transfer_figure(ds, figures["transfer_functions"])
        P.map_figure(ds, figures["map"])
    write_netcdf(ds, out_nc)
    write_netcdf(checks_dataset(cfg["ship"], "derivative", rows), validation_nc)
    if cpu_tsv:
        # measured CPU seconds of the regular-wave map (a benchmark, not a result: differs per run)
        from stabflow.io import atomic_path

        with atomic_path(cpu_tsv) as tmp, open(tmp, "w") as fh:
            fh.write("model\tcpu_s\tcells\n")
            for k in ("full", "derivative"):
                fh.write(f"{k}\t{cpu[k]:.3f}\t{cpu['cells']}\n")
    return ds
