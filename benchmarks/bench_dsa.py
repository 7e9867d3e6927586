"""Direct stability assessment of one ship: wall and CPU time of the whole assessment and of its
screening alone, on this machine (issue 21 target: DTMB 5415, scatter table x 7 headings x 3
speeds, <= 4 h on 2 cores with every cell's interval).
Run: python benchmarks/bench_dsa.py [--config config/dsa.yaml] [--ship dtmb5415] [--hs-max H]

One process on one core; the cells are independent, so two cores take half the time (the figure
printed for 2 cores is that half, not a measured parallel run). The reference in the same run is the
screening's share of the CPU. Prints cells per method, the long-term rate with its interval, CPU of
models / screening / simulation, and the wall time.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def main():
    import xarray as xr

    from stabflow.config import load_pipeline, load_ship, load_yaml, validate
    from stabflow.criteria.assess import assess
    from stabflow.criteria.dsa_run import assess_dsa
    from stabflow.geometry import build_hull
    from stabflow.hydrostatics.statics import compute_statics

    ap = argparse.ArgumentParser()
    ap.add_argument("--config", default="config/dsa.yaml")
    ap.add_argument("--ship", default="dtmb5415")
    ap.add_argument("--hs-max", type=float, default=None)
    ap.add_argument("--hydro", default=None, help="Capytaine NetCDF (hydro step) for ships that use it")
    a = ap.parse_args()
    # the profile extends config/config.yaml as Snakemake's --configfile does (its dsa keys replace)
    base = load_pipeline("config/config.yaml")
    extra = load_yaml(a.config).get("dsa", {}) if a.config != "config/config.yaml" else {}
    cfg = validate(dict(base, dsa=dict(base["dsa"], **extra)), "config", a.config)["dsa"]
    if a.hs_max is not None:
        cfg["hs_max"] = a.hs_max
    ship = load_ship(f"config/ships/{a.ship}.yaml")
    if ship.data["dynamics"].get("hydro") == "capytaine" and not a.hydro:
        # without the hydro step's file the config coefficients stand in (stated in the output)
        ship = ship.modified(dynamics={"hydro": "config", "roll_damping": "coefficients"})
        print("note: no --hydro file: config coefficients instead of Capytaine + Ikeda")
    hull = build_hull(ship)
    hydro = xr.open_dataset(a.hydro).load() if a.hydro else None
    crit = assess(ship, hull, compute_statics(ship, hull), base["criteria"], hydro=hydro)
    t0 = time.time()
    ds = assess_dsa(ship, crit, cfg, hydro, progress=True)
    wall = time.time() - t0
    m = ds.method.values.astype(str)
    print(f"{a.ship}: {ds.sizes['cell']} cells: " + ", ".join(f"{k} {int((m == k).sum())}" for k in ("screened", "counted", "extrapolated")))
    print(f"long-term rate {float(ds.rate):.4g} /year [{float(ds.rate_lo):.4g}, {float(ds.rate_hi):.4g}]; "
          f"screening bound {float(ds.screen_bound):.3g} /year vs interval width {float(ds.interval_width):.3g}")
    cpu = ds.encoding["cpu"]
    print(f"CPU: models {cpu['build']:.1f} s, screening {cpu['screen']:.1f} s, simulation "
          f"{cpu['simulate']:.1f} s, recheck of the screened cells {cpu.get('recheck', 0.0):.1f} s, total "
          f"{cpu['total']:.1f} s; wall {wall:.1f} s (one process)")
    print(f"recheck: {ds.attrs.get('screen_recheck_verdict')}: {ds.attrs.get('screen_recheck_reason', '')}")
    print(f"screening share of the CPU: {cpu['screen'] / cpu['total']:.2f}; "
          f"two cores (cells independent): about {wall / 2 / 3600:.2f} h")


if __name__ == "__main__":
    main()
