"""Ensemble speed and step-size convergence (issue 6). Run: python benchmarks/bench_ensemble.py [--hours N]

1. Step-size convergence: the same records (DTMB 5415, 21 stations, 220 components, Bretschneider
   SS8 Hs 11.5 m / Tp 16.4 s, stern quartering 30 deg, 10 kn) at dt = 0.1 ... 1.0 s: roll standard
   deviation and the 0.999 quantile of |roll|, relative to dt = 0.1 s.
2. CPU-seconds per simulated hour on one core (numba and BLAS at one thread) at the converged step
   (largest dt whose sigma and q0.999 lie within 0.5 % of the dt = 0.1 s values) and at the
   pipeline default 0.5 s, split into wave synthesis, RK4 kernel and statistics.
3. A 10,000-hour ensemble through Snakemake at -j2 (20 shards): wall time and the peak memory of
   any job (the merge reads only per-record statistics, so memory does not grow with hours).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numba  # noqa: E402
import numpy as np  # noqa: E402
import yaml  # noqa: E402

from stabflow.config import load_pipeline, load_ship  # noqa: E402
from stabflow.statistics.ensemble import build_model, merge, run_shard  # noqa: E402
from stabflow.statistics.signals import quantile_from_histogram  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
COND = dict(name="bench", ship="dtmb5415", sea=dict(spectrum="bretschneider", hs=11.5, tp=16.4), speed_kn=10.0,
            heading_deg=30.0, dynamics={"hydro": "config"}, records=20000, samples=0)


def condition(**kw):
    """The benchmark condition with the schema defaults filled in."""
    cfg = load_pipeline_dict({"ships": ["dtmb5415"], "ensembles": [dict(COND, **kw)]})
    return dict(cfg["ensembles"][0], name="dtmb5415_bench")


def load_pipeline_dict(d):
    with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
        yaml.safe_dump(d, f)
    try:
        return load_pipeline(f.name)
    finally:
        os.unlink(f.name)


def q999(ens):
    h = ens["hist_roll"].values
    half = len(h) // 2
    fold = h[half:] + h[:half][::-1]
    c = ens["roll_bin"].values[half:]
    return quantile_from_histogram(fold, c, 0.999)


def convergence(records: int):
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    ship = load_ship(ROOT / "config/ships/dtmb5415.yaml")
    rows = []
    for dt in (0.1, 0.25, 0.5, 0.75, 1.0):
        m = build_model(ship, condition(dt=dt))
        e = merge([run_shard(m, range(records), progress=False)])
        rows.append((dt, float(e["roll_std"]), q999(e), int(e["capsize_count"])))
    ref = rows[0]
    print(f"\nStep-size convergence ({records} records x 30 min, same seaways):")
    print("  dt [s]   roll sigma [deg]   rel     |roll| q0.999 [deg]   rel     capsizes")
    ok = ref[0]
    for dt, s, q, c in rows:
        rs, rq = s / ref[1] - 1, q / ref[2] - 1
        print(f"  {dt:5.2f}   {s:12.4f}   {rs:+8.2%}   {q:14.3f}   {rq:+8.2%}   {c:6d}")
        if abs(rs) < 0.005 and abs(rq) < 0.005:
            ok = dt
    print(f"  converged step (sigma and q0.999 within 0.5 % of dt = 0.1 s): {ok} s")
    return ok


def cpu_per_hour(dt: float, records: int = 64):
    numba.set_num_threads(1)
    ship = load_ship(ROOT / "config/ships/dtmb5415.yaml")
    m = build_model(ship, condition(dt=dt))
    run_shard(m, range(4), progress=False)  # JIT warm-up
    from stabflow.statistics import ensemble as E

    parts = {"wave": 0.0, "kernel": 0.0, "stats": 0.0}
    orig = (E.wave_table, E._simulate_batch, E.record_statistics)

    def timed(name, f):
        def g(*a, **k):
            t = time.process_time()
            r = f(*a, **k)
            parts[name] += time.process_time() - t
            return r
        return g

    E.wave_table, E._simulate_batch, E.record_statistics = (timed("wave", orig[0]), timed("kernel", orig[1]),
                                                             timed("stats", orig[2]))
    try:
        t0 = time.process_time()
        run_shard(m, range(100, 100 + records), progress=False)
        cpu = time.process_time() - t0
    finally:
        E.wave_table, E._simulate_batch, E.record_statistics = orig
    hours = records * 0.5
    print(f"  dt {dt:4.2f} s: {cpu / hours:.4f} CPU-s per simulated hour (wave {parts['wave'] / hours:.4f}, "
          f"RK4 kernel {parts['kernel'] / hours:.4f}, statistics {parts['stats'] / hours:.4f}, "
          f"rest {(cpu - sum(parts.values())) / hours:.4f})")
    return cpu / hours


def ensemble_10k(hours: float, dt: float):
    records = int(round(hours * 2))
    with tempfile.TemporaryDirectory() as tmp:
        cfg = {"ships": ["dtmb5415"], "results": f"{tmp}/results",
               "ensembles": [dict(COND, records=records, shard_records=max(1, records // 20), dt=dt, name="bench")]}
        cf = Path(tmp) / "bench.yaml"
        cf.write_text(yaml.safe_dump(cfg))
        target = f"{tmp}/results/ensemble/dtmb5415_bench/ensemble.nc"
        t = time.time()
        r = subprocess.run([sys.executable, "-m", "snakemake", "-j2", "--configfile", str(cf), "--quiet", "all",
                            "--nolock", target], cwd=ROOT, capture_output=True, text=True)
        wall = time.time() - t
        if r.returncode:
            print(r.stdout[-3000:], r.stderr[-3000:])
            raise SystemExit(1)
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
        import xarray as xr

        with xr.open_dataset(target) as e:
            h, caps = float(e["exposure_hours"]), int(e["capsize_count"])
    print(f"\n{h:,.0f}-hour ensemble at -j2 (dt {dt} s, 20 shards): wall {wall:.0f} s "
          f"({wall / h * 1e6 / 3600:.1f} h per million simulated hours), peak job memory {peak:.0f} MB, "
          f"{caps} capsizes")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--records", type=int, default=100, help="records per step size in the convergence study")
    ap.add_argument("--hours", type=float, default=10000.0, help="hours of the -j2 ensemble (0 to skip)")
    a = ap.parse_args()
    ok = convergence(a.records)
    print("\nOne core (numba and BLAS single-threaded), 220 components, 21 stations:")
    for dt in sorted({ok, 0.5}):
        cpu_per_hour(dt)
    print("  target 0.035 CPU-s per simulated hour; SimpleCode (published) 0.7")
    if a.hours > 0:
        ensemble_10k(a.hours, 0.5)


if __name__ == "__main__":
    main()
