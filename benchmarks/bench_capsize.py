"""Time to answer a capsize rate (issue 16). Run: python benchmarks/bench_capsize.py [--severity narrow_2]

For one case of the 1-DOF box-barge validation model (config/config.yaml, capsize_1dof):

1. Split-time and extremes from one 100-h sample: wall time of the sample simulation, the motion
   perturbations and the profile-likelihood fits, with the estimate and its 95 % interval.
2. Brute force in the same process: wall time per simulated hour (2 threads), and the hours (and
   wall time) brute force would need for an interval as narrow as split-time's: the Garwood 95 %
   interval of a Poisson count k has log-width log(hi/lo) decreasing with k; the k whose width
   matches split-time's, over the true rate (the configured brute-force count), gives the hours.
   Where split-time's lower bound is 0 the comparison is with the hours after which a brute force
   that saw no capsize would have an upper bound as low (Garwood upper bound of 0 events / hours).

Prints the figures and the ratio brute-force time / split-time time (target: an answer for a rate
of 1e-5 /h within 10 minutes on this 2-core machine).
"""

from __future__ import annotations

import argparse
import time

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


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--severity", default="narrow_2", help="case name, e.g. narrow_1, broad_2")
    ap.add_argument("--config", default="config/config.yaml")
    a = ap.parse_args(argv)
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
        if not hi_ > 0:
            print(f"  {method}: interval [0, 0] rules out every positive rate (brute force {r:.3g} /h): no answer")
            continue
        if lo_ > 0 and np.isfinite(hi_):
            width = np.log(hi_ / lo_)
            kk = 1
            while garwood_width(kk) > width and kk < 10**7:
                kk += 1
            need = kk / r if r > 0 else np.inf
            why = f"Garwood log-width {width:.2f} needs {kk} capsizes"
        else:
            need = poisson_interval(0, 1.0)[2] / hi_
            why = f"lower bound 0: a capsize-free brute force reaches the upper bound {hi_:.3g} /h"
        print(f"  {method}: brute force for the same interval {need:.3g} h ({why}) = {need * per_hour:.1f} s; "
              f"ratio brute-force time / estimate time {need * per_hour / t_split:.1f}")

if __name__ == "__main__":
    main()
