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


def run_validate_statics(ship_yaml, hull_nc, statics_nc, out_nc) -> xr.Dataset:
    """validation of the statics step → NetCDF rows (check, value, tolerance, PASS/FAIL)."""
    from .io import write_netcdf
    from .validation import checks_dataset, statics_checks

    ship = load_ship(ship_yaml)
    with xr.open_dataset(hull_nc) as h, xr.open_dataset(statics_nc) as s:
        hull, st = h.load(), s.load()
    ds = checks_dataset(ship.name, "statics", statics_checks(ship, hull, st))
    write_netcdf(ds, out_nc)
    return ds


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
    s = sub.add_parser("report", help="build the HTML report from a results folder")
    s.add_argument("--config", default="config/config.yaml")
    s.add_argument("--results", default="results")
    s.add_argument("--source", default="report")
    s.add_argument("-o", "--output", default="results/report/html/index.html")
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
            elif args.cmd == "validate":
                run_validate_statics(args.ship, args.hull, args.statics, args.output)
            elif args.cmd == "report":
                from .config import load_pipeline
                from .report import build_report

                cfg = load_pipeline(args.config)
                build_report(args.results, cfg["ships"], cfg, args.source, args.output)
            elif args.cmd == "gz":
                _cmd_gz(args)
    except StabflowError as exc:
        print(f"stabflow: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
