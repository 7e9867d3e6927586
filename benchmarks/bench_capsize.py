"""Time to answer a capsize rate (issue 16).

Run: ``python benchmarks/bench_capsize.py [--severity narrow_2]`` (1-DOF box barge) or
``python benchmarks/bench_capsize.py --condition dtmb5415_sq`` (3-DOF ensemble condition).

For one case of the 1-DOF box-barge validation model (config/config.yaml, capsize_1dof):

1. Split-time and extremes from one 100-h sample: wall time of the sample simulation, the motion
   perturbations and the profile-likelihood fits, with the estimate and its 95 % interval.
2. Brute force in the same process: wall time per simulated hour (2 threads), and the hours (and
   wall time) brute force would need for an interval as narrow as split-time's: the Garwood 95 %
   interval of a Poisson count k has log-width log(hi/lo) decreasing with k; the k whose width
   matches split-time's, over the true rate (the configured brute-force count), gives the hours.
   Where split-time's lower bound is 0 the comparison is with the hours after which a brute force
   that saw no capsize would have an upper bound as low (Garwood upper bound of 0 events / hours).

For a 3-DOF ensemble condition (``--condition``, config ``ensembles`` and ``splittime``): the split-time
sample (``splittime.sample_hours``) is simulated in this process (2 threads), its crossings are
perturbed and the metric fitted exactly as the pipeline's splittime step does; then ``--bf-hours``
of brute force are simulated to measure the wall time per simulated hour, and the brute-force hours
for an interval as narrow as split-time's are sized with the brute-force rate of
``--bruteforce-nc`` (the pipeline's ensemble) when given, else with split-time's own estimate.

Prints the figures and the ratio brute-force time / split-time time (target: an answer for a rate
of 1e-5 /h within 10 minutes on this 2-core machine).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from stabflow.config import load_pipeline
from stabflow.dynamics.one_dof import record_seeds
from stabflow.statistics.signals import decorrelation_time
from stabflow.statistics.splittime import poisson_interval
from stabflow.validation.capsize_1dof import (analyse_sample, box_model, bruteforce, cases,
                                              roll_autocorrelation)


def garwood_width(k: int) -> float:
    _, lo, hi = poisson_interval(k, 1.0)
    return np.log(hi / lo) if lo > 0 else np.inf


def brute_force_hours(rate: float, lo: float, hi: float) -> tuple[float, str]:
    """Brute-force hours for a Garwood interval as narrow as [lo, hi] at the true rate ``rate``
    (or, where lo is 0, for a capsize-free brute force to reach the upper bound hi)."""
    if lo > 0 and np.isfinite(hi):
        width = np.log(hi / lo)
        k = 1
        while garwood_width(k) > width and k < 10**7:
            k += 1
        return (k / rate if rate > 0 else np.inf), f"Garwood log-width {width:.2f} needs {k} capsizes"
    return (poisson_interval(0, 1.0)[2] / hi,
            f"lower bound 0: a capsize-free brute force reaches the upper bound {hi:.3g} /h")


def compare(method: str, lo: float, hi: float, rate: float, per_hour: float, t_answer: float) -> None:
    if not hi > 0:
        print(f"  {method}: interval [0, 0] rules out every positive rate (brute force {rate:.3g} /h): no answer")
        return
    need, why = brute_force_hours(rate, lo, hi)
    print(f"  {method}: brute force for the same interval {need:.3g} h ({why}) = {need * per_hour:.1f} s; "
          f"ratio brute-force time / estimate time {need * per_hour / t_answer:.1f}")


def three_dof(a) -> None:
    """Split-time on a 3-DOF ensemble condition, timed in one process against brute force."""
    import numba
    import xarray as xr

    from stabflow.config import load_ship
    from stabflow.statistics.ensemble import build_model, merge, run_shard
    from stabflow.statistics.splittime import analyse

    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    cfg = load_pipeline(a.config)
    conds = {f"{c['ship']}_{c['name']}": c for c in cfg["ensembles"]}
    cond = conds[a.condition]
    st_cfg = cfg["splittime"]
    t0 = time.perf_counter()
    model = build_model(load_ship(Path(a.config).parent / "ships" / f"{cond['ship']}.yaml"), cond)
    t_model = time.perf_counter() - t0
    nrec = max(1, int(round(st_cfg["sample_hours"] * 3600.0 / model.cond["duration"])))
    t0 = time.perf_counter()
    sample = merge([run_shard(model, range(nrec), progress=False)])
    t_sample = time.perf_counter() - t0
    t0 = time.perf_counter()
    ds = analyse(model, sample, st_cfg, threads=2)
    t_fit = time.perf_counter() - t0
    t_answer = t_model + t_sample + t_fit
    rep = int(np.argmax(ds["reported"].values))
    st = [float(ds[v][rep]) for v in ("capsize_rate_splittime", "capsize_rate_lower", "capsize_rate_upper")]
    thr = float(ds["split_threshold"][rep])
    print(f"condition {a.condition}: split-time sample {float(ds['sample_hours']):.0f} h, reported threshold {thr:g} deg, "
          f"{int(ds['clusters'][rep])} clusters")
    print(f"  split-time: {st[0]:.3g} /h [{st[1]:.3g}, {st[2]:.3g}]")
    print(f"  wall time: model {t_model:.1f} s + sample {t_sample:.1f} s + perturbations and fits {t_fit:.1f} s "
          f"= {t_answer:.1f} s")
    t0 = time.perf_counter()
    n_bf = max(1, int(round(a.bf_hours * 3600.0 / model.cond["duration"])))
    bf = merge([run_shard(model, range(nrec, nrec + n_bf), progress=False)])
    t_bf = time.perf_counter() - t0
    h = float(bf["steps"].sum()) * model.dt / 3600.0
    per_hour = t_bf / h
    print(f"  brute force: {int(bf['capsized'].sum())} capsizes in {h:.0f} h, {t_bf:.1f} s "
          f"({per_hour * 1e3:.2f} ms per simulated hour, 2 threads)")
    if a.bruteforce_nc:
        with xr.open_dataset(a.bruteforce_nc) as e:
            k, hours = int(e["capsized"].sum()), float(e["steps"].sum()) * float(e.attrs["dt"]) / 3600.0
        rate, src = k / hours, f"{a.bruteforce_nc}: {k} capsizes in {hours:.0f} h"
    else:
        rate, src = st[0], "split-time's own estimate"
    print(f"  rate used to size the brute force: {rate:.3g} /h ({src})")
    compare("split-time", st[1], st[2], rate, per_hour, t_answer)
    if rate > 0:
        # the same interval width at a rarer rate: brute-force hours scale as 1 / rate, split-time's cost does not
        need, _ = brute_force_hours(rate, st[1], st[2])
        print(f"  at 1e-5 /h the same relative interval needs {need * rate / 1e-5:.3g} brute-force hours "
              f"= {need * rate / 1e-5 * per_hour / 3600.0:.1f} h of wall time")


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--severity", default="narrow_2", help="1-DOF case name, e.g. narrow_1, broad_2")
    ap.add_argument("--condition", help="3-DOF ensemble key <ship>_<name> (instead of a 1-DOF case)")
    ap.add_argument("--bf-hours", type=float, default=500.0, help="3-DOF: brute-force hours simulated for the timing")
    ap.add_argument("--bruteforce-nc", help="3-DOF: the condition's ensemble NetCDF (brute-force rate)")
    ap.add_argument("--config", default="config/config.yaml")
    a = ap.parse_args(argv)
    if a.condition:
        three_dof(a)
        return
    cfg = load_pipeline(a.config)["capsize_1dof"]
    C = {c[0]: (i, c) for i, c in enumerate(cases(cfg))}
    ci, (name, band, sigma, bf_hours) = C[a.severity]
    model = box_model(cfg, band, sigma)
    seed = int(cfg["seed"]) + 7919 * ci
    t0 = time.perf_counter()
    tau = decorrelation_time(roll_autocorrelation(model, record_seeds(seed, 2, range(20)), 600.0))
    nrec = int(round(float(cfg["sample_hours"]) * 3600.0 / model.duration))
    res = analyse_sample(model, record_seeds(seed, 1, range(nrec)), tau, cfg)
    t_split = time.perf_counter() - t0
    rep = res["st_report"]
    st_rate, st_lo, st_hi = res["st"][rep]
    kr = [int(k) for k in cfg["extremes"]["exceedances"]].index(int(cfg["extremes"]["report"]))
    ex_rate, ex_lo, ex_hi = res["ext"][kr]
    print(f"case {name}: excitation sigma {np.degrees(sigma):.3g} deg, sample {res['hours']:.0f} h")
    print(f"  split-time: {st_rate:.3g} /h [{st_lo:.3g}, {st_hi:.3g}]; extremes: {ex_rate:.3g} /h [{ex_lo:.3g}, {ex_hi:.3g}]")
    print(f"  wall time, sample + perturbations + fits (both methods): {t_split:.1f} s")
    t0 = time.perf_counter()
    r, lo, hi, k, h, _ = bruteforce(model, bf_hours, int(cfg["seed"]) + 7919 * ci, threads=2)
    t_bf = time.perf_counter() - t0
    per_hour = t_bf / h
    print(f"  brute force: {k} capsizes in {h:.0f} h = {r:.3g} /h [{lo:.3g}, {hi:.3g}], {t_bf:.1f} s "
          f"({per_hour * 1e3:.3f} ms per simulated hour, 2 threads)")
    for method, lo_, hi_ in (("split-time", st_lo, st_hi), ("extremes", ex_lo, ex_hi)):
        compare(method, lo_, hi_, r, per_hour, t_split)

if __name__ == "__main__":
    main()
