"""Split-time method (paper 003): capsize rate = crossing rate x P(capsize | crossing).

Non-rare problem
    Up-crossings of +phi_thr and down-crossings of -phi_thr in the ensemble records (stored by the
    ensemble step with the roll rate by linear interpolation). Crossing rate, eq. 2:
    lambda = N_U / (N_T dt), with a binomial (Clopper-Pearson) interval on N_U out of N_T samples.
Rare problem (motion perturbation method)
    For each crossing the record's seaway is regenerated from (master seed, record) and the record
    re-simulated (bit-identical to the ensemble run) up to the RK4 step just before the crossing; an
    RK4 sub-step (Newton-refined length, waves synthesized off the grid) carries that state to the
    crossing instant (:func:`crossing_state`). There the roll rate is increased by delta (in the
    direction of the crossing), a sub-step of the rest of the step returns to the time grid
    and the motion followed in the same waves for ``window_periods`` roll periods; it stops at
    once if roll passes 90 deg (capsize). The smallest capsizing delta is found by bisection to
    ``tolerance`` deg/s. Metric: y = phidot_U / phidot_Cr with phidot_Cr = phidot_U + delta, so
    y = 1 at capsize and the distribution is extrapolated to y = 1 as the seed's text describes
    (eq. 1 as printed, 1 - phidot_U / phidot_Cr, is 0 at capsize; its complement is used).
Declustering
    Crossings of the same threshold in the same record closer than the decorrelation time (roll
    autocorrelation envelope below 0.05) form a cluster; the largest metric is kept.
Extrapolation
    GPD fit (maximum likelihood, scipy.stats.genpareto as in the extremes step) to the declustered
    metric above its ``metric_quantile``; P(capsize | cluster) = (n_u / n) * GPD survival(1 - u)
    (zero when the fitted upper bound u - sigma / xi lies below 1). Capsize rate
    lambda_c = (clusters / hours) * P, with a bootstrap-over-records percentile interval.
Validation
    The sample is the first ``sample_hours`` of the ensemble; the brute-force rate is the number of
    capsized records among all other records over their exposure (Garwood Poisson interval).
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import xarray as xr
from scipy import stats

from stabflow.dynamics._kernels import N_STATE, S_RATE, S_ROLL, _simulate
from stabflow.dynamics.tables import kernel_args
from stabflow.statistics.ensemble import Model, simulate_record, wave_table
from stabflow.waves.synthesis import station_wave_table
from stabflow.statistics.extremes import decluster, gpd_mle
from stabflow.io import annotate
from stabflow.statistics.intervals import record_bootstrap
from stabflow.statistics.signals import decorrelation_time


def bisect_critical(capsizes, dmax: float, tol: float) -> tuple[float, int]:
    """Smallest perturbation in [0, dmax] for which ``capsizes(delta)`` is True, to ``tol``.

    Returns (delta, runs); delta = 0 if the unperturbed motion capsizes, inf if even ``dmax`` does
    not. Assumes capsizing is monotonic in delta over the bracket (checked at both ends).
    """
    runs = 1
    if capsizes(0.0):
        return 0.0, runs
    runs += 1
    if not capsizes(dmax):
        return np.inf, runs
    lo, hi = 0.0, dmax
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        runs += 1
        if capsizes(mid):
            hi = mid
        else:
            lo = mid
    return hi, runs


def crossing_rate(n_cross: int, n_samples: int, dt: float, alpha: float = 0.05):
    """Eq. 2, lambda = N_U / (N_T dt) [1/h], with the Clopper-Pearson binomial interval."""
    lam = n_cross / (n_samples * dt) * 3600.0
    lo = stats.beta.ppf(alpha / 2, n_cross, n_samples - n_cross + 1) if n_cross > 0 else 0.0
    hi = stats.beta.ppf(1 - alpha / 2, n_cross + 1, n_samples - n_cross)
    return lam, lo / dt * 3600.0, hi / dt * 3600.0


def poisson_interval(k: int, hours: float, alpha: float = 0.05):
    """Garwood exact interval of a Poisson rate k / hours [1/h]."""
    lo = stats.chi2.ppf(alpha / 2, 2 * k) / 2 if k > 0 else 0.0
    hi = stats.chi2.ppf(1 - alpha / 2, 2 * k + 2) / 2
    return k / hours, lo / hours, hi / hours


def sub_step(model: Model, components, s: np.ndarray, t0: float, tau: float) -> np.ndarray:
    """One RK4 step of length ``tau`` [s] from state ``s`` at time ``t0`` [s], off the record's time
    grid: the waves of the record's ``components`` (amp, omega, phase) are synthesized at t0,
    t0 + tau / 2 and t0 + tau (the same float32 tables as the ensemble's). Returns the new state."""
    amp, w, ph = components
    tab = station_wave_table(amp, w, ph, model.sec.x, model.cond["heading_deg"], model.speed,
                             np.array([t0, t0 + 0.5 * tau, t0 + tau]), model.depth, dtype=np.float32)
    out = np.empty((2, N_STATE))
    _simulate(*kernel_args(model.sec, model.tables), model.p, tab, tau, 0, 1, np.asarray(s, float), np.inf, out,
              np.empty((0, 6)))
    return out[1]


def crossing_state(model: Model, components, states: np.ndarray, n0: int, level: float,
                   iterations: int = 6) -> tuple[float, np.ndarray]:
    """The state at the instant roll crosses ``level`` [rad] between steps ``n0`` and ``n0 + 1``:
    RK4 sub-steps from the step before the crossing, the sub-step length refined by Newton's method
    on roll(tau) - level (start: linear interpolation). Returns (time [s], state)."""
    dt = model.dt
    s0 = states[n0]
    r0, r1 = s0[S_ROLL], states[n0 + 1, S_ROLL]
    tau = dt * (level - r0) / (r1 - r0) if r1 != r0 else 0.0
    s = s0
    for _ in range(iterations):
        tau = min(max(tau, 0.0), dt)
        s = sub_step(model, components, s0, n0 * dt, tau)
        err = s[S_ROLL] - level
        rate = s[S_RATE + S_ROLL]
        if abs(err) <= 1e-12 or rate == 0.0:
            break
        tau -= err / rate
    return n0 * dt + tau, s


def perturbed_run(model: Model, components, wtab: np.ndarray, s_c: np.ndarray, t_c: float, n0: int, n1: int,
                  side: int, delta_deg: float, buf: np.ndarray) -> tuple[bool, int]:
    """Follow the record from the crossing state ``s_c`` at ``t_c`` [s] (between steps n0 and n0 + 1)
    with the roll rate increased by ``side * delta_deg`` [deg/s]: a sub-step of the rest of step n0,
    then the grid up to step ``n1``; ``buf`` (nsteps + 1, N_STATE) receives the grid states from
    n0 + 1. Returns (capsized: roll beyond 90 deg, last step done)."""
    cap = np.radians(90.0)
    s = s_c.copy()
    s[S_RATE + S_ROLL] += side * np.radians(delta_deg)
    s = sub_step(model, components, s, t_c, (n0 + 1) * model.dt - t_c)
    buf[n0 + 1] = s
    if abs(s[S_ROLL]) > cap:
        return True, n0 + 1
    if n0 + 1 >= n1:
        return False, n0 + 1
    last = _simulate(*kernel_args(model.sec, model.tables), model.p, wtab, model.dt, n0 + 1, n1, s, cap, buf,
                     np.empty((0, 6)))
    return bool(last < n1 or abs(buf[last, S_ROLL]) > cap), last


def critical_perturbations(model: Model, records, steps, sides, levels, window: int, dmax_deg: float,
                           tol_deg: float, threads: int = 1, progress: bool = False):
    """Critical roll-rate perturbation [deg/s] for each crossing (record, step before the crossing,
    side +1/-1). Crossings of one record share its regenerated seaway; records run in parallel
    threads (the RK4 kernel releases the GIL).

    ``levels`` is the crossed roll angle of each crossing [deg] (signed). The perturbation is applied
    to the exact state at the crossing instant (:func:`crossing_state`) and the perturbed run returns
    to the time grid with a sub-step of the rest of that step (:func:`perturbed_run`). Returns
    (delta [deg/s], bisection runs, roll rate at the crossing [deg/s], crossing time [s]) per
    crossing."""
    from tqdm import tqdm

    records = np.asarray(records)
    steps = np.asarray(steps)
    sides = np.asarray(sides)
    levels = np.asarray(levels, float)
    delta = np.full(len(records), np.nan)
    runs = np.zeros(len(records), np.int64)
    rate_at = np.full(len(records), np.nan)
    t_at = np.full(len(records), np.nan)

    def one_record(r):
        idx = np.nonzero(records == r)[0]
        wtab = wave_table(model, int(r))
        comps = model.sea.components(model.cond["seed"], int(r))
        states, _ = simulate_record(model, int(r), wtab=wtab)
        buf = np.empty((model.nsteps + 1, N_STATE))
        for c in idx:
            n0 = int(steps[c])
            n1 = min(n0 + window, model.nsteps)
            tc, s0 = crossing_state(model, comps, states, n0, np.radians(levels[c]))
            rate_at[c], t_at[c] = abs(np.degrees(s0[S_RATE + S_ROLL])), tc

            def capsizes(d, s0=s0, n0=n0, n1=n1, side=sides[c], tc=tc):
                return perturbed_run(model, comps, wtab, s0, tc, n0, n1, side, d, buf)[0]

            delta[c], runs[c] = bisect_critical(capsizes, dmax_deg, tol_deg)
        return len(idx)

    todo = np.unique(records)
    with ThreadPoolExecutor(max_workers=max(1, threads)) as ex:
        for _ in tqdm(ex.map(one_record, todo), total=len(todo), desc="perturbations (records)",
                      disable=not progress, mininterval=10):
            pass
    return delta, runs, rate_at, t_at


def capsize_probability(y, u: float):
    """(P(Y >= 1), xi, sigma, n_u) from declustered metrics ``y``: GPD fitted to the excesses over
    ``u`` and evaluated at y = 1 (empirical fraction if fewer than 3 excesses or u >= 1)."""
    y = np.asarray(y, float)
    if len(y) == 0:
        return 0.0, np.nan, np.nan, 0
    exc = y[y > u] - u
    if len(exc) < 3 or u >= 1.0:
        return float(np.mean(y >= 1.0)), np.nan, np.nan, len(exc)
    xi, sig = gpd_mle(exc)
    return float(len(exc) / len(y) * stats.genpareto.sf(1.0 - u, xi, scale=sig)), xi, sig, len(exc)


def analyse(model: Model, ens: xr.Dataset, cfg: dict, threads: int = 1, progress: bool = False) -> xr.Dataset:
    """Split-time capsize rate from the first ``sample_hours`` of the ensemble at each threshold,
    against the brute-force rate of the other records."""
    dt = float(ens.attrs["dt"])
    duration = float(ens.attrs["duration"])
    tau = decorrelation_time(ens["roll_autocorrelation"])
    nrec = max(1, int(round(cfg["sample_hours"] * 3600.0 / duration)))
    rec_all = ens["record"].values
    sample = rec_all[:nrec]
    in_s = np.isin(rec_all, sample)
    n_samples = int((ens["steps"].values[in_s] + 1).sum())
    hours = float(ens["steps"].values[in_s].sum()) * dt / 3600.0
    bf_k = int(ens["capsized"].values[~in_s].sum())
    bf_hours = float(ens["steps"].values[~in_s].sum()) * dt / 3600.0
    bf, bf_lo, bf_hi = poisson_interval(bf_k, bf_hours, cfg["alpha"]) if bf_hours > 0 else (np.nan,) * 3
    window = int(round(cfg["window_periods"] * model.roll_period / dt))
    thresholds = list(ens["threshold"].values)
    rng = np.random.default_rng(int(cfg["seed"]))
    res = []
    cross_rows = []
    for thr in cfg["thresholds_deg"]:
        if thr not in thresholds:
            raise ValueError(f"splittime threshold {thr} deg is not among the ensemble's thresholds {thresholds}")
        j = thresholds.index(thr)
        m = (ens["crossing_threshold"].values == j) & np.isin(ens["crossing_record"].values, sample)
        rec = ens["crossing_record"].values[m]
        side = ens["crossing_side"].values[m]
        step = ens["crossing_step"].values[m]
        # the metric uses the roll rate of the exact state at the crossing (the perturbed state)
        delta, runs, rate_u, t = critical_perturbations(model, rec, step, side, side * float(thr), window,
                                                        cfg["max_perturbation"], cfg["tolerance"], threads, progress)
        y = np.where(np.isfinite(delta), rate_u / (rate_u + delta), rate_u / (rate_u + cfg["max_perturbation"]))
        # declustering: same threshold, same record, closer than tau; keep the largest metric
        # (decluster() keeps cluster maxima of values above a level: use y + 1 > 0)
        yc, rc, tc = decluster(rec, t, y + 1.0, 0.0, tau)
        yc = yc - 1.0
        u = float(np.quantile(yc, cfg["metric_quantile"])) if len(yc) else 0.0
        p, xi, sig, n_u = capsize_probability(yc, u)
        lam_cl = len(yc) / hours
        lam_c = lam_cl * p
        raw, raw_lo, raw_hi = crossing_rate(len(rec), n_samples, dt, cfg["alpha"])
        # bootstrap over records: clusters, GPD and P refitted
        boots = np.empty(int(cfg["n_boot"]))
        for b, (pick, yb) in enumerate(record_bootstrap(rng, sample, yc, rc, len(boots))):
            hb = float(ens["steps"].sel(record=pick).sum()) * dt / 3600.0
            ub = float(np.quantile(yb, cfg["metric_quantile"])) if len(yb) else 0.0
            boots[b] = len(yb) / hb * capsize_probability(yb, ub)[0]
        lo, hi = np.quantile(boots, [cfg["alpha"] / 2, 1 - cfg["alpha"] / 2])
        res.append(dict(thr=thr, n_cross=len(rec), raw=raw, raw_lo=raw_lo, raw_hi=raw_hi, n_cl=len(yc), lam_cl=lam_cl,
                        u=u, xi=xi, sig=sig, n_u=n_u, p=p, lam=lam_c, lo=lo, hi=hi, runs=int(runs.sum()),
                        inside=int(lo <= bf <= hi), capsized_crossings=int(np.sum(delta == 0))))
        cross_rows.append((np.full(len(rec), thr), rec, t, side, rate_u, delta, y))
    R = {k: np.array([r[k] for r in res]) for k in res[0]}
    C = [np.concatenate(c) for c in zip(*cross_rows)]
    ds = xr.Dataset(
        {
            "crossings": ("split_threshold", R["n_cross"]),
            "crossing_rate_raw": ("split_threshold", R["raw"]),
            "crossing_rate_lower": ("split_threshold", R["raw_lo"]),
            "crossing_rate_upper": ("split_threshold", R["raw_hi"]),
            "clusters": ("split_threshold", R["n_cl"]),
            "cluster_rate": ("split_threshold", R["lam_cl"]),
            "metric_threshold": ("split_threshold", R["u"]),
            "metric_gpd_shape": ("split_threshold", R["xi"]),
            "metric_gpd_scale": ("split_threshold", R["sig"]),
            "metric_exceedances": ("split_threshold", R["n_u"]),
            "capsize_probability": ("split_threshold", R["p"]),
            "capsize_rate_splittime": ("split_threshold", R["lam"]),
            "capsize_rate_lower": ("split_threshold", R["lo"]),
            "capsize_rate_upper": ("split_threshold", R["hi"]),
            "perturbed_runs": ("split_threshold", R["runs"]),
            "capsizing_crossings": ("split_threshold", R["capsized_crossings"]),
            "inside": ("split_threshold", R["inside"]),
            "capsize_rate_bruteforce": ((), bf),
            "capsize_rate_bruteforce_lower": ((), bf_lo),
            "capsize_rate_bruteforce_upper": ((), bf_hi),
            "bruteforce_capsizes": ((), bf_k),
            "bruteforce_hours": ((), bf_hours),
            "sample_hours": ((), hours),
            "decorrelation_time": ((), tau),
            "crossing_threshold_deg": ("event", C[0]),
            "crossing_record": ("event", C[1].astype(np.int64)),
            "crossing_time": ("event", C[2]),
            "crossing_side": ("event", C[3].astype(np.int8)),
            "crossing_roll_rate": ("event", C[4]),
            "critical_perturbation": ("event", C[5]),
            "metric": ("event", C[6]),
        },
        coords={"split_threshold": np.array(cfg["thresholds_deg"], float)},
    )
    ds.attrs.update(ship=ens.attrs["ship"], condition=ens.attrs["condition"], window_steps=window,
                    tolerance=float(cfg["tolerance"]), max_perturbation=float(cfg["max_perturbation"]),
                    interval=f"bootstrap over records, {int(cfg['n_boot'])} resamples", fit="GPD MLE (scipy)",
                    metric="y = phidot_U / (phidot_U + delta_cr)")
    return annotate(ds)


def perturbed_histories(model: Model, record: int, step: int, side: int, deltas, window: int, level_deg: float):
    """Roll [deg] of the unperturbed record and of perturbed runs (roll rate + side * delta [deg/s]
    at the exact crossing of ``side * level_deg`` after ``step``, as in :func:`critical_perturbations`)
    over ``window`` steps (paper 003 Fig. 4). Returns (t [s], unperturbed, list of runs), starting at
    the crossing instant."""
    wtab = wave_table(model, int(record))
    comps = model.sea.components(model.cond["seed"], int(record))
    states, last = simulate_record(model, int(record), wtab=wtab)
    tc, sc = crossing_state(model, comps, states, step, np.radians(side * level_deg))
    n1 = min(step + window, model.nsteps)
    t = np.concatenate([[tc], np.arange(step + 1, n1 + 1) * model.dt])
    runs = []
    for d in deltas:
        buf = np.full((model.nsteps + 1, N_STATE), np.nan)
        perturbed_run(model, comps, wtab, sc, tc, step, n1, side, d, buf)
        runs.append(np.degrees(np.concatenate([[sc[S_ROLL]], buf[step + 1: n1 + 1, S_ROLL]])))
    base = np.full(len(t), np.nan)
    base[0] = np.degrees(sc[S_ROLL])
    m = min(last, n1)
    base[1: m - step + 1] = np.degrees(states[step + 1: m + 1, S_ROLL])
    return t, base, runs
