"""Derivative model against the full volume-based model: CPU per simulated hour in one run (issue 18).
Run: python benchmarks/bench_derivative.py [--components 3000] [--hours 1]

The DTC parametric-roll condition of config/config.yaml (KG 21.7 m, JONSWAP Hs 10 m, Tp 14.5 s,
12 kn, 175 deg, 21 stations, dt 0.2 s), one core: for each model the seconds to fit (derivative:
hull positions x regular waves), and per simulated hour the excitation table (wave table at the
stations / coefficient table) and the RK4 kernel, and their ratio. Same records, same seeds.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numba  # noqa: E402
import numpy as np  # noqa: E402

from stabflow.config import load_pipeline, load_ship  # noqa: E402
from stabflow.dynamics._kernels import S_ROLL  # noqa: E402
from stabflow.statistics.ensemble import advance, build_model, record_table, state_size  # noqa: E402


def per_hour(model, records, hours):
    """(table CPU-s, kernel CPU-s) per simulated hour and the roll sigma [deg] of ``records``."""
    t_tab = t_run = 0.0
    roll = []
    for r in records:
        t0 = time.process_time()
        tab = record_table(model, r)
        t1 = time.process_time()
        out = np.empty((model.nsteps + 1, state_size(model)))
        last = advance(model, r, tab, model.s0, 0, model.nsteps, out)
        t2 = time.process_time()
        t_tab += t1 - t0
        t_run += t2 - t1
        roll.append(np.degrees(out[: last + 1, S_ROLL]))
    h = len(records) * hours
    return t_tab / h, t_run / h, float(np.std(np.concatenate(roll)))


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--components", type=int, default=3000)
    ap.add_argument("--hours", type=float, default=1.0)
    ap.add_argument("--records", type=int, default=3)
    a = ap.parse_args(argv)
    numba.set_num_threads(1)
    cfg = load_pipeline("config/config.yaml")
    base = next(c for c in cfg["ensembles"] if c["name"] == "pr")
    ship = load_ship("config/ships/dtc.yaml")
    cond = dict(base, duration=3600.0 * a.hours, sea=dict(base["sea"], n_components=a.components))
    res = {}
    for kind in ("volume", "derivative"):
        t0 = time.process_time()
        model = build_model(ship, dict(cond, name=kind, model=kind))
        build = time.process_time() - t0
        per_hour(model, [0], 0.01 * a.hours)  # compile
        res[kind] = (build,) + per_hour(model, range(a.records), a.hours)
        b, tab, run, sig = res[kind]
        print(f"{kind:10s}: build {b:5.1f} s; per simulated hour: table {tab:6.3f} CPU-s, RK4 {run:6.3f} CPU-s, "
              f"total {tab + run:6.3f}; roll sigma {sig:.2f} deg")
    full, der = (res[k][1] + res[k][2] for k in ("volume", "derivative"))
    print(f"derivative / full CPU per simulated hour: {der / full:.2f} ({a.components} components, "
          f"{len(build_model(ship, dict(cond, name='x')).sec.x)} stations, dt {cond['dt']:g} s, one core)")


if __name__ == "__main__":
    main()
