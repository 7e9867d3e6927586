"""``stabflow`` command line: every pipeline step runs outside Snakemake too.

The commands are a table (:data:`COMMANDS`): name, help, arguments, and the call of the step
function in :mod:`stabflow.steps` that the Snakemake rule of the same name also uses.

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
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from stabflow import StabflowError, __version__
from stabflow import steps


def _pipeline(args) -> dict:
    from stabflow.config import load_pipeline

    return load_pipeline(args.config)


def _ensemble_condition(config_path, key):
    """(condition dict with its ``<ship>_<name>`` key as name, ship YAML path) of an ensembles entry."""
    from stabflow.config import load_pipeline

    cfg = load_pipeline(config_path)
    conds = {f"{c['ship']}_{c['name']}": c for c in cfg.get("ensembles", [])}
    if key not in conds:
        raise StabflowError(f"{config_path}: ensembles: no condition {key!r} (have {sorted(conds)})")
    return dict(conds[key], name=key), Path(cfg.get("ships_dir", "config/ships")) / f"{conds[key]['ship']}.yaml"


def _gz(args):
    """Print the particulars and the GZ table of a ship."""
    from stabflow.config import load_ship
    from stabflow.geometry import build_hull
    from stabflow.hydrostatics.statics import compute_statics

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


def _report(args):
    from stabflow.report import build_report

    cfg = _pipeline(args)
    build_report(args.results, cfg["ships"], cfg, args.source, args.output)


def _compare(args) -> int:
    """Print how the NetCDF files of two results folders compare; non-zero exit if any differs by
    more than ``--rtol``."""
    from stabflow.io import compare_results

    rows = compare_results(args.a, args.b)
    bad = 0
    for r in rows:
        worse = not r["max_rel"] <= args.rtol
        bad += worse
        extra = f" max rel. diff {r['max_rel']:.3g} in {', '.join(r['variables'])}" if r["variables"] else ""
        print(f"{'DIFF ' if worse else 'ok   '}{r['file']}: {r['status']}{extra}")
    print(f"{len(rows)} files, {sum(r['status'] == 'identical bytes' for r in rows)} byte-identical, "
          f"{bad} beyond rtol {args.rtol:g}")
    if bad:
        raise SystemExit(1)


def _ensemble_merge(args):
    f = Path(args.figures) if args.figures else None
    figs = (f / "roll_distribution.png", f / "spectra.png", f / "time_histories.png") if f else ()
    steps.run_ensemble_merge(args.shards, args.output, *figs)


def _with_condition(fn):
    """Resolve ``args.condition`` (``<ship>_<name>``) to (condition, ship YAML) before calling ``fn``."""
    def run(args):
        cond, ship_yaml = _ensemble_condition(args.config, args.condition)
        fn(args, cond, ship_yaml)
    return run


# argument specs: (flags, keyword arguments of ArgumentParser.add_argument)
SHIP = (("ship",), {"help": "ship configuration, config/ships/<name>.yaml"})
OUT = (("-o", "--output"), {"required": True})
CONFIG = (("--config",), {"default": "config/config.yaml", "help": "pipeline configuration"})
HULL = (("--hull",), {"required": True, "help": "hull step NetCDF"})
STATICS = (("--statics",), {"required": True, "help": "statics step NetCDF"})
FIGURE = (("--figure",), {"help": "figure path (PNG)"})
CONDITION = (("condition",), {"help": "<ship>_<name> of an ensembles entry"})
RAO_CONDITION = (("--condition",), {"required": True, "help": "name of a rao condition"})
THREADS = (("--threads",), {"type": int, "default": 1})
HYDRO = (("--hydro",), {"help": "Capytaine coefficients NetCDF (hydro step), for ships that use them"})
RADIATION = (("--radiation",), {"help": "heave-pitch memory model NetCDF (radiation step), for ships whose 6-DOF model "
                                        "uses one (computed when not given)"})


@dataclass(frozen=True)
class Command:
    """One CLI command: its help line, its arguments and what it runs."""

    help: str
    args: tuple
    run: Callable


def _section_and_figures(a, step: str, names) -> tuple[dict, dict | None]:
    """The pipeline config (its ``step`` section required) and {figure stem: path in --figures}."""
    cfg = _pipeline(a)
    if step not in cfg:
        raise StabflowError(f"{a.config}: {step}: the section is missing: nothing to run")
    if not a.figures:
        return cfg, None
    s = cfg[step]["ship"]
    return cfg, {n: str(Path(a.figures) / f"{s}_{n}.png") for n in names(cfg)}


def _broaching(a):
    cfg, figs = _section_and_figures(a, "broaching", steps.broaching_figure_names)
    return steps.run_broaching(cfg, cfg.get("ships_dir", "config/ships"), a.output, a.validation, figs,
                               radiation_nc=a.radiation)


def _derivative(a):
    from stabflow.dynamics.derivative import compared_ensembles

    cfg, figs = _section_and_figures(a, "derivative", steps.derivative_figure_names)
    pair = compared_ensembles(cfg)
    res = Path(cfg.get("results", "results"))
    ens = {k: str(res / "ensemble" / v / "ensemble.nc") for k, v in pair.items()} if pair else None
    return steps.run_derivative(cfg, cfg.get("ships_dir", "config/ships"), a.output, a.validation, figs, ens,
                                cpu_tsv=a.cpu)


COMMANDS: dict[str, Command] = {
    "hull": Command("cut stations and Bonjean tables", (SHIP, OUT, FIGURE),
                    lambda a: steps.run_hull(a.ship, a.output, a.figure)),
    "statics": Command("hydrostatics and calm-water GZ", (SHIP, HULL, OUT, FIGURE),
                       lambda a: steps.run_statics(a.ship, a.hull, a.output, a.figure)),
    "waves": Command("wave-pass GM/GZ", (SHIP, HULL, STATICS, CONFIG, OUT),
                     lambda a: steps.run_waves(a.ship, a.hull, a.statics, _pipeline(a)["wave_pass"], a.output)),
    "early-stage": Command("early-stage metric C", (SHIP, HULL, STATICS, CONFIG, OUT, (("--csv",), {})),
                           lambda a: steps.run_early_stage(a.ship, a.hull, a.statics, _pipeline(a)["early_stage"],
                                                           a.output, a.csv)),
    "early-stage-summary": Command("metric C of every ship in one CSV table and bar chart",
                                   ((("metrics",), {"nargs": "+", "help": "early-stage NetCDF files"}), OUT,
                                    (("--figure",), {"required": True})),
                                   lambda a: steps.run_early_stage_summary(a.metrics, a.output, a.figure)),
    "hydro": Command("Capytaine added mass and damping at the natural frequencies, linear peer RAOs",
                     (SHIP, HULL, STATICS, CONFIG, RAO_CONDITION, OUT),
                     lambda a: steps.run_hydro(a.ship, a.hull, a.statics, _pipeline(a)["rao"], a.condition, a.output)),
    "radiation": Command("heave-pitch added mass and damping over frequency (Capytaine) and the fitted memory model "
                         "of the 6-DOF Cummins equation", (SHIP, OUT, FIGURE),
                         lambda a: steps.run_radiation(a.ship, a.output, a.figure)),
    "roll-decay": Command("calm-water roll decay with the ship's damping (Ikeda components where selected)",
                          (SHIP, HULL, STATICS, OUT, FIGURE, HYDRO),
                          lambda a: steps.run_roll_decay(a.ship, a.hull, a.statics, a.output, a.figure, a.hydro)),
    "rao": Command("regular-wave sweep of the time-domain model", (SHIP, HULL, STATICS, CONFIG, RAO_CONDITION, OUT, FIGURE, HYDRO),
                   lambda a: steps.run_rao(a.ship, a.hull, a.statics, _pipeline(a)["rao"], a.condition, a.output, a.figure,
                                           a.hydro)),
    "criteria": Command("IS Code 2008 and second-generation criteria of one ship → NetCDF (with --figure, also "
                        "<ship>_sea_states.png beside it)",
                        (SHIP, HULL, STATICS, CONFIG, OUT, FIGURE, HYDRO, RADIATION),
                        lambda a: steps.run_criteria(a.ship, a.hull, a.statics, _pipeline(a)["criteria"], a.output,
                                                     a.figure, a.hydro, a.radiation)),
    "dsa": Command("direct stability assessment of one ship over the scatter table → NetCDF",
                   (SHIP, (("--criteria",), {"required": True, "help": "criteria step NetCDF"}), CONFIG, OUT,
                    (("--figures",), {"help": "folder for <ship>_dsa_map.png and <ship>_dsa_polar.png"}), HYDRO),
                   lambda a: steps.run_dsa(a.ship, a.criteria, _pipeline(a)["dsa"], a.output,
                                           {k: str(Path(a.figures) / f"{Path(a.ship).stem}_dsa_{k}.png")
                                            for k in ("map", "polar")} if a.figures else None, a.hydro,
                                           overrides=_pipeline(a)["criteria"].get("overrides"))),
    "validate-criteria": Command("criteria validation checks (box barge closed forms) → NetCDF",
                                 (SHIP, (("--criteria",), {"required": True, "help": "criteria step NetCDF"}),
                                  (("--dsa",), {"help": "the ship's DSA NetCDF (its screening is checked)"}), OUT),
                                 lambda a: steps.run_validate_criteria(a.ship, a.criteria, a.output, a.dsa)),
    "validate-dsa": Command("DSA aggregation against Rice's exact rate (linear 1-DOF roll) → NetCDF", (OUT,),
                            lambda a: steps.run_validate_dsa(a.output)),
    "validate": Command("statics validation checks → NetCDF", (SHIP, HULL, STATICS, OUT),
                        lambda a: steps.run_validate_statics(a.ship, a.hull, a.statics, a.output)),
    "validate-waves": Command("wave-pass and metric C validation checks → NetCDF",
                              (SHIP, HULL, STATICS, (("--waves",), {"required": True}), (("--metric",), {"required": True}),
                               CONFIG, OUT),
                              lambda a: steps.run_validate_waves(a.ship, a.hull, a.statics, a.waves, a.metric,
                                                                 _pipeline(a)["early_stage"], a.output)),
    "validate-dynamics": Command("time-domain validation checks → NetCDF", (SHIP, HULL, STATICS, OUT),
                                 lambda a: steps.run_validate_dynamics(a.ship, a.hull, a.statics, a.output)),
    "validate-ensemble": Command("seaway, step-size, extremes and split-time checks → NetCDF",
                                 (CONDITION, (("--ensemble",), {"required": True}), (("--extremes",), {}),
                                  (("--splittime",), {}), HYDRO, RADIATION, CONFIG, THREADS, OUT),
                                 _with_condition(lambda a, c, s: steps.run_validate_ensemble(
                                     s, c, a.ensemble, a.output, a.extremes, a.splittime, a.hydro, a.radiation,
                                     a.threads))),
    "ensemble-shard": Command("simulate one shard of an irregular-sea ensemble",
                              (CONDITION, (("--shard",), {"type": int, "required": True}), CONFIG, THREADS, HYDRO,
                               RADIATION, OUT),
                              _with_condition(lambda a, c, s: steps.run_ensemble_shard(s, c, a.shard, a.output, a.threads,
                                                                                       a.hydro, radiation_nc=a.radiation))),
    "ensemble-merge": Command("merge ensemble shards and draw the figures",
                              ((("shards",), {"nargs": "+"}), OUT,
                               (("--figures",), {"help": "folder for roll_distribution.png, spectra.png, time_histories.png"})),
                              _ensemble_merge),
    "extremes": Command("GPD extrapolation of roll from an ensemble, validated by brute force",
                        ((("ensemble",), {"help": "ensemble.nc of a condition"}), CONFIG, OUT),
                        lambda a: steps.run_extremes(a.ensemble, _pipeline(a)["extremes"], a.output)),
    "splittime": Command("split-time capsize rate from an ensemble (motion perturbations)",
                         (CONDITION, (("--ensemble",), {"required": True}), CONFIG, THREADS, HYDRO, RADIATION, OUT),
                         _with_condition(lambda a, c, s: steps.run_splittime(s, c, a.ensemble, _pipeline(a)["splittime"],
                                                                             a.output, threads=a.threads, hydro_nc=a.hydro,
                                                                             radiation_nc=a.radiation))),
    "capsize-1dof": Command("1-DOF box-barge capsize rates: split-time and extremes against brute force",
                            (CONFIG, THREADS, OUT, (("--validation",), {"required": True, "help": "validation rows NetCDF"}),
                             FIGURE),
                            lambda a: steps.run_capsize_1dof(_pipeline(a)["capsize_1dof"], a.output, a.validation,
                                                             a.figure, a.threads)),
    "broaching": Command("paper 004's stern-quartering cases (6-DOF), calm-water manoeuvres, surf-riding thresholds",
                         (CONFIG, OUT, (("--validation",), {"required": True, "help": "validation rows NetCDF"}),
                          (("--figures",), {"help": "folder for the figures (<ship>_motions_<loading>.png, "
                                                    "<ship>_strip.png, <ship>_manoeuvres.png)"}), RADIATION),
                         _broaching),
    "derivative": Command("derivative model of heave-roll-pitch (paper 001): fit, regular-wave parametric-roll map",
                          (CONFIG, OUT, (("--validation",), {"required": True, "help": "validation rows NetCDF"}),
                           (("--figures",), {"help": "folder for <ship>_fit.png, <ship>_transfer_functions.png, "
                                                     "<ship>_map.png (and the irregular-sea figures); the "
                                                     "ensembles are read from the config's results folder"}),
                           (("--cpu",), {"help": "TSV file for the measured CPU seconds of both models' runs"})),
                          _derivative),
    "report": Command("build the HTML report from a results folder",
                      (CONFIG, (("--results",), {"default": "results"}), (("--source",), {"default": "report"}),
                       (("-o", "--output"), {"default": "results/report/html/index.html"})),
                      _report),
    "compare": Command("compare the NetCDF files of two results folders (bit-identical reruns)",
                       ((("a",), {}), (("b",), {}), (("--rtol",), {"type": float, "default": 0.0,
                                                                   "help": "accepted relative difference"})),
                       _compare),
    "gz": Command("print particulars and the GZ table of a ship",
                  (SHIP, (("--every",), {"type": float, "default": 10.0, "help": "print every N degrees"})), _gz),
}


def parser() -> argparse.ArgumentParser:
    """The argument parser built from :data:`COMMANDS`."""
    p = argparse.ArgumentParser(prog="stabflow", description=__doc__.split("\n\n")[0])
    p.add_argument("--version", action="version", version=__version__)
    sub = p.add_subparsers(dest="cmd", required=True)
    for name, cmd in COMMANDS.items():
        s = sub.add_parser(name, help=cmd.help)
        for flags, kw in cmd.args:
            s.add_argument(*flags, **kw)
    return p


def main(argv=None) -> int:
    """Run one command; a :class:`StabflowError` prints one line and returns 2."""
    args = parser().parse_args(argv)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("always")
            COMMANDS[args.cmd].run(args)
    except StabflowError as exc:
        print(f"stabflow: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
