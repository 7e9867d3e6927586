"""``stabflow`` command line: every pipeline step runs outside Snakemake too.

Examples
--------
stabflow hull config/ships/dtmb5415.yaml -o results/hull/dtmb5415.nc --figure results/hull/dtmb5415_bodyplan.png
stabflow statics config/ships/dtmb5415.yaml --hull results/hull/dtmb5415.nc -o results/statics/dtmb5415.nc
stabflow gz config/ships/dtmb5415.yaml          # prints particulars and the GZ table
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

import xarray as xr

from . import StabflowError, __version__
from .config import load_ship


def run_hull(ship_yaml, out_nc, figure=None) -> xr.Dataset:
    """hull step: stations and Bonjean tables → NetCDF (+ body plan figure)."""
    from .hull import build_hull
    from .io import write_netcdf
    from .plots import body_plan

    ship = load_ship(ship_yaml)
    ds = build_hull(ship)
    if figure:
        body_plan(ds, figure)
    write_netcdf(ds, out_nc)
    return ds


def run_statics(ship_yaml, hull_nc, out_nc, figure=None) -> xr.Dataset:
    """statics step: particulars and calm-water GZ → NetCDF (+ GZ figure)."""
    from .io import write_netcdf
    from .plots import gz_curves
    from .statics import compute_statics

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

    from .hull import Sections
    from .io import write_netcdf
    from .plots import gm_wave_pass, gz_curves
    from .wavepass import crest_trough_calm, wave_pass

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
    from .early_stage import assess
    from .hull import Sections
    from .io import atomic_text, write_netcdf

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    ds = assess(Sections(hull), *(float(st[k]) for k in ("volume", "lcg", "kg", "km", "lwl", "bwl")), cfg["sea_states"], cfg)
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

    from .io import atomic_text
    from .plots import metric_bars

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
    from .dynamics import coefficients
    from .dynamics.hydro import bem_mesh, hydro_dataset
    from .dynamics.linear import stiffness_matrix
    from .dynamics.model import equilibrium
    from .hull import Sections
    from .io import write_netcdf

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    cond = {c["name"]: c for c in rao_cfg["conditions"]}[condition]
    sec = Sections(hull)
    co = coefficients(ship, sec, st)
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    C = stiffness_matrix(sec, ship.rho, float(st["lcg"]), float(st["kg"]), h0, th0)
    ds = hydro_dataset(bem_mesh(ship), st, co, ship.rho, cond["heading"], float(st["lwl"]), rao_cfg["wavelength_ratios"], C, h0, th0)
    ds.attrs.update(ship=ship.name, condition=condition, note="zero speed (Capytaine without forward speed)")
    write_netcdf(ds, out_nc)
    return ds


def run_rao(ship_yaml, hull_nc, statics_nc, rao_cfg: dict, condition: str, out_nc, fig=None, hydro_nc=None) -> xr.Dataset:
    """rao step: regular-wave sweep of the time-domain model for one condition → NetCDF + figure.

    With ``hydro_nc`` (Capytaine) the added mass and damping come from it and its linear RAOs are
    plotted beside the time-domain ones."""
    from .dynamics import coefficients
    from .dynamics.rao import rao_sweep
    from .early_stage import KNOT
    from .hull import Sections
    from .io import write_netcdf
    from .plots import rao_curves

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    cond = {c["name"]: c for c in rao_cfg["conditions"]}[condition]
    sec = Sections(hull)
    hydro = None
    if hydro_nc:
        with xr.open_dataset(hydro_nc) as h:
            hydro = h.load()
    co = coefficients(ship, sec, st, hydro if ship.data["dynamics"]["hydro"] == "capytaine" else None)
    ds = rao_sweep(sec, st, co, ship.rho, float(st["lwl"]), rao_cfg["wavelength_ratios"], rao_cfg["steepness"],
                   cond["heading"], cond["speed_kn"] * KNOT, rao_cfg["dt"])
    ds.attrs.update(ship=ship.name, condition=condition, roll_period=co.natural_period("roll"),
                    heave_period=co.natural_period("heave"), pitch_period=co.natural_period("pitch"),
                    hydro=ship.data["dynamics"]["hydro"])
    if fig:
        rao_curves(ds, fig, peer=hydro, title=f"{ship.name}, {condition}: heading {cond['heading']:g}°, {cond['speed_kn']:g} kn, "
                   f"H/λ = {rao_cfg['steepness']:g}")
    write_netcdf(ds, out_nc)
    return ds


def run_validate_statics(ship_yaml, hull_nc, statics_nc, out_nc) -> xr.Dataset:
    """validation of the statics step → NetCDF rows (check, value, tolerance, PASS/FAIL)."""
    from .io import write_netcdf
    from .validation import checks_dataset
    from .validation.statics import statics_checks

    ship = load_ship(ship_yaml)
    with xr.open_dataset(hull_nc) as h, xr.open_dataset(statics_nc) as s:
        hull, st = h.load(), s.load()
    ds = checks_dataset(ship.name, "statics", statics_checks(ship, hull, st))
    write_netcdf(ds, out_nc)
    return ds


def run_validate_waves(ship_yaml, hull_nc, statics_nc, waves_nc, metric_nc, es_cfg: dict, out_nc) -> xr.Dataset:
    """validation of the waves and early-stage steps → NetCDF rows."""
    from .io import write_netcdf
    from .validation import checks_dataset
    from .validation.waves import waves_checks

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    with xr.open_dataset(waves_nc) as w, xr.open_dataset(metric_nc) as m:
        waves, metric = w.load(), m.load()
    ds = checks_dataset(ship.name, "waves", waves_checks(ship, hull, st, waves, metric, es_cfg))
    write_netcdf(ds, out_nc)
    return ds


def run_validate_dynamics(ship_yaml, hull_nc, statics_nc, out_nc) -> xr.Dataset:
    """validation of the 3-DOF time-domain model → NetCDF rows."""
    from .io import write_netcdf
    from .validation import checks_dataset
    from .validation.dynamics import dynamics_checks

    ship, hull, st = _load_statics(ship_yaml, hull_nc, statics_nc)
    ds = checks_dataset(ship.name, "dynamics", dynamics_checks(ship, hull, st))
    write_netcdf(ds, out_nc)
    return ds


def _open_optional(path):
    if not path:
        return None
    with xr.open_dataset(path) as d:
        return d.load()


def run_validate_ensemble(ship_yaml, cond: dict, ensemble_nc, out_nc, extremes_nc=None, splittime_nc=None,
                          hydro_nc=None) -> xr.Dataset:
    """validation of an ensemble condition (seaway, step size) and of its extremes and split-time
    estimates against the brute force → NetCDF rows (key ``<ship>_<condition>``)."""
    from .ensemble import build_model
    from .io import write_netcdf
    from .validation import checks_dataset
    from .validation.ensemble import ensemble_checks

    model = build_model(load_ship(ship_yaml), cond, _open_optional(hydro_nc))
    ens = _open_optional(ensemble_nc)
    rows = ensemble_checks(model, ens, _open_optional(extremes_nc), _open_optional(splittime_nc))
    ds = checks_dataset(model.ship.name, "ensemble", rows)
    ds.attrs["condition"] = cond["name"]
    write_netcdf(ds, out_nc)
    return ds


def run_ensemble_shard(ship_yaml, cond: dict, shard: int, out_nc, threads: int = 1, hydro_nc=None, progress=True):
    """ensemble step, one shard: records [shard * shard_records, ...) of condition ``cond`` → NetCDF."""
    import numba

    from .ensemble import build_model, run_shard
    from .io import write_netcdf

    ship = load_ship(ship_yaml)
    hydro = None
    if hydro_nc:
        with xr.open_dataset(hydro_nc) as h:
            hydro = h.load()
    numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    model = build_model(ship, cond, hydro)
    n = int(cond["shard_records"])
    recs = range(shard * n, min((shard + 1) * n, int(cond["records"])))
    if len(recs) == 0:
        raise StabflowError(f"ensemble {cond['name']}: shard {shard} is beyond records = {cond['records']}")
    ds = run_shard(model, recs, progress=progress)
    write_netcdf(ds, out_nc)
    return ds


def run_ensemble_merge(shard_ncs, out_nc, fig_distribution=None, fig_spectra=None, fig_samples=None):
    """ensemble step, merge: shards → ensemble NetCDF + figures."""
    from .ensemble import merge
    from .io import write_netcdf
    from .plots import response_spectra, roll_distribution, time_histories

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


def run_extremes(ensemble_nc, cfg: dict, out_nc, fig_threshold=None, fig_rate=None, fig_validation=None):
    """extremes step: envelope POT + GPD rates from sample blocks, validated against the ensemble."""
    from .extremes import analyse
    from .io import write_netcdf
    from .plots import exceedance_rate_curve, extremes_validation, threshold_diagnostics

    with xr.open_dataset(ensemble_nc) as e:
        ens = e.load()
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
                  hydro_nc=None):
    """splittime step: crossings, motion perturbations, GPD of the metric → capsize rate + figures."""
    import numba

    from .ensemble import build_model
    from .io import write_netcdf
    from .plots import splittime_figures
    from .splittime import analyse

    hydro = None
    if hydro_nc:
        with xr.open_dataset(hydro_nc) as h:
            hydro = h.load()
    numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    model = build_model(load_ship(ship_yaml), cond, hydro)
    with xr.open_dataset(ensemble_nc) as e:
        ens = e.load()
    ds = analyse(model, ens, cfg, threads=threads, progress=True)
    if figures:
        a = ens.attrs
        splittime_figures(model, ds, figures, f"Split-time vs brute force: {a['condition']}, Hs {a['hs']:g} m, "
                          f"{a['speed_kn']:g} kn, heading {a['heading_deg']:g}°")
    write_netcdf(ds, out_nc)
    return ds


def _ensemble_condition(config_path, key):
    from .config import load_pipeline

    cfg = load_pipeline(config_path)
    conds = {f"{c['ship']}_{c['name']}": c for c in cfg.get("ensembles", [])}
    if key not in conds:
        raise StabflowError(f"{config_path}: ensembles: no condition {key!r} (have {sorted(conds)})")
    return dict(conds[key], name=key), Path(cfg.get("ships_dir", "config/ships")) / f"{conds[key]['ship']}.yaml"


def _cmd_gz(args):
    from .hull import build_hull
    from .statics import compute_statics

    ship = load_ship(args.ship)
    ds = compute_statics(ship, build_hull(ship))
    keys = ["volume", "mass", "draft_mid", "trim_upright", "lcb", "lcg", "kb", "bm", "km", "kg", "gm", "waterplane_area",
            "gz_max", "heel_gz_max", "heel_vanishing"]
    for k in keys:
        print(f"{k:16s} {float(ds[k]):14.4f} {ds[k].attrs.get('units', '')}")
    print("heel [deg]   GZ [m]")
    step = max(1, int(round(args.every / float(ds.heel[1] - ds.heel[0]))))
    for h, g in zip(ds.heel.values[::step], ds.gz.values[::step]):
        print(f"{h:9.1f} {g:9.4f}")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="stabflow", description=__doc__.split("\n\n")[0])
    p.add_argument("--version", action="version", version=__version__)
    sub = p.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("hull", help="cut stations and Bonjean tables")
    s.add_argument("ship")
    s.add_argument("-o", "--output", required=True)
    s.add_argument("--figure")
    s = sub.add_parser("statics", help="hydrostatics and calm-water GZ")
    s.add_argument("ship")
    s.add_argument("--hull", required=True)
    s.add_argument("-o", "--output", required=True)
    s.add_argument("--figure")
    s = sub.add_parser("validate", help="statics validation checks → NetCDF")
    s.add_argument("ship")
    s.add_argument("--hull", required=True)
    s.add_argument("--statics", required=True)
    s.add_argument("-o", "--output", required=True)
    s = sub.add_parser("validate-waves", help="wave-pass and metric C validation checks → NetCDF")
    s.add_argument("ship")
    for a in ("--hull", "--statics", "--waves", "--metric", "-o"):
        s.add_argument(a, required=True, **({"dest": "output"} if a == "-o" else {}))
    s.add_argument("--config", default="config/config.yaml")
    s = sub.add_parser("validate-dynamics", help="time-domain validation checks → NetCDF")
    s.add_argument("ship")
    s.add_argument("--hull", required=True)
    s.add_argument("--statics", required=True)
    s.add_argument("-o", "--output", required=True)
    s = sub.add_parser("validate-ensemble", help="seaway, step-size, extremes and split-time checks → NetCDF")
    s.add_argument("condition", help="<ship>_<name> of an ensembles entry")
    s.add_argument("--ensemble", required=True)
    s.add_argument("--extremes")
    s.add_argument("--splittime")
    s.add_argument("--hydro")
    s.add_argument("--config", default="config/config.yaml")
    s.add_argument("-o", "--output", required=True)
    s = sub.add_parser("report", help="build the HTML report from a results folder")
    s.add_argument("--config", default="config/config.yaml")
    s.add_argument("--results", default="results")
    s.add_argument("--source", default="report")
    s.add_argument("-o", "--output", default="results/report/html/index.html")
    for name, hlp in [("waves", "wave-pass GM/GZ"), ("early-stage", "early-stage metric C"),
                      ("rao", "regular-wave sweep of the time-domain model")]:
        s = sub.add_parser(name, help=hlp)
        s.add_argument("ship")
        s.add_argument("--hull", required=True)
        s.add_argument("--statics", required=True)
        s.add_argument("--config", default="config/config.yaml")
        s.add_argument("-o", "--output", required=True)
        if name == "rao":
            s.add_argument("--condition", required=True)
    s = sub.add_parser("ensemble-shard", help="simulate one shard of an irregular-sea ensemble")
    s.add_argument("condition", help="<ship>_<name> of an ensembles entry")
    s.add_argument("--shard", type=int, required=True)
    s.add_argument("--config", default="config/config.yaml")
    s.add_argument("--threads", type=int, default=1)
    s.add_argument("--hydro")
    s.add_argument("-o", "--output", required=True)
    s = sub.add_parser("ensemble-merge", help="merge ensemble shards and draw the figures")
    s.add_argument("shards", nargs="+")
    s.add_argument("-o", "--output", required=True)
    s.add_argument("--figures", help="folder for roll_distribution.png, spectra.png, time_histories.png")
    s = sub.add_parser("extremes", help="GPD extrapolation of roll from an ensemble, validated by brute force")
    s.add_argument("ensemble", help="ensemble.nc of a condition")
    s.add_argument("--config", default="config/config.yaml")
    s.add_argument("-o", "--output", required=True)
    s = sub.add_parser("splittime", help="split-time capsize rate from an ensemble (motion perturbations)")
    s.add_argument("condition", help="<ship>_<name> of an ensembles entry")
    s.add_argument("--ensemble", required=True)
    s.add_argument("--config", default="config/config.yaml")
    s.add_argument("--threads", type=int, default=1)
    s.add_argument("-o", "--output", required=True)
    s = sub.add_parser("gz", help="print particulars and the GZ table of a ship")
    s.add_argument("ship")
    s.add_argument("--every", type=float, default=10.0, help="print every N degrees")
    args = p.parse_args(argv)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("always")
            if args.cmd == "hull":
                run_hull(args.ship, args.output, args.figure)
            elif args.cmd == "statics":
                run_statics(args.ship, args.hull, args.output, args.figure)
            elif args.cmd in ("waves", "early-stage"):
                from .config import load_pipeline

                cfg = load_pipeline(args.config)
                if args.cmd == "waves":
                    run_waves(args.ship, args.hull, args.statics, cfg["wave_pass"], args.output)
                else:
                    run_early_stage(args.ship, args.hull, args.statics, cfg["early_stage"], args.output)
            elif args.cmd == "rao":
                from .config import load_pipeline

                run_rao(args.ship, args.hull, args.statics, load_pipeline(args.config)["rao"], args.condition, args.output)
            elif args.cmd == "validate":
                run_validate_statics(args.ship, args.hull, args.statics, args.output)
            elif args.cmd == "validate-waves":
                from .config import load_pipeline

                run_validate_waves(args.ship, args.hull, args.statics, args.waves, args.metric,
                                   load_pipeline(args.config)["early_stage"], args.output)
            elif args.cmd == "validate-dynamics":
                run_validate_dynamics(args.ship, args.hull, args.statics, args.output)
            elif args.cmd == "validate-ensemble":
                cond, ship_yaml = _ensemble_condition(args.config, args.condition)
                run_validate_ensemble(ship_yaml, cond, args.ensemble, args.output, args.extremes, args.splittime,
                                      args.hydro)
            elif args.cmd == "report":
                from .config import load_pipeline
                from .report import build_report

                cfg = load_pipeline(args.config)
                build_report(args.results, cfg["ships"], cfg, args.source, args.output)
            elif args.cmd == "ensemble-shard":
                cond, ship_yaml = _ensemble_condition(args.config, args.condition)
                run_ensemble_shard(ship_yaml, cond, args.shard, args.output, args.threads, args.hydro)
            elif args.cmd == "ensemble-merge":
                f = Path(args.figures) if args.figures else None
                run_ensemble_merge(args.shards, args.output, *((f / "roll_distribution.png", f / "spectra.png",
                                                                 f / "time_histories.png") if f else ()))
            elif args.cmd == "extremes":
                from .config import load_pipeline

                run_extremes(args.ensemble, load_pipeline(args.config)["extremes"], args.output)
            elif args.cmd == "splittime":
                from .config import load_pipeline

                cond, ship_yaml = _ensemble_condition(args.config, args.condition)
                run_splittime(ship_yaml, cond, args.ensemble, load_pipeline(args.config)["splittime"], args.output,
                              threads=args.threads)
            elif args.cmd == "gz":
                _cmd_gz(args)
    except StabflowError as exc:
        print(f"stabflow: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
