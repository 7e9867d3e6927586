"""Split-time method (paper 003): capsize rate = crossing rate x P(capsize | crossing).

Non-rare problem
    Up-crossings of +phi_thr and down-crossings of -phi_thr in the ensemble records (stored by the
    ensemble step with the roll rate by linear interpolation). Crossing rate, eq. 2:
    lambda = N_U / (N_T dt), with a binomial (Clopper-Pearson) interval on N_U out of N_T samples.
Rare problem (motion perturbation method)
    For each crossing the record's seaway is regenerated from (master seed, record) and the record
    re-simulated (bit-identical to the ensemble run) up to the RK4 step just before the crossing; an
    RK4 sub-step (Newton-refined length, waves synthesized off the grid) carries that state to the
    crossing instant (:func:`crossing_state`). There the roll rate is changed by delta (in the
    direction of the crossing), a sub-step of the rest of the step returns to the time grid and the
    motion is followed in the same waves until it capsizes (90 deg) or returns to the unperturbed
    solution (paper 003: "truncated as soon as a roll angle of 90 degrees is reached or the motion
    converges to the unperturbed solution"), at most ``follow_periods`` roll periods. The critical
    delta is found by bisection to ``tolerance`` deg/s: in [0, max_perturbation] when the unperturbed
    motion survives the crossing, in [-phidot_U, 0] when it capsizes before the next crossing (the
    critical rate is then below the crossing's). Metric: y = phidot_U / phidot_Cr with
    phidot_Cr = phidot_U + delta, so y = 1 at the boundary of capsizing, y > 1 for crossings that
    capsize, and the distribution is extrapolated to y = 1 as the seed's text describes (eq. 1 as
    printed, 1 - phidot_U / phidot_Cr, is 0 at capsize; its complement is used).
6-DOF conditions
    The records of ``dof: 6`` conditions are regenerated with the 6-DOF model; the perturbation is
    applied to the grid state just after the crossing (the roll amplitude of the damping is a
    state updated at the steps, which an off-grid sub-step would not have) and the run continues
    from there
    (waves restarted at that time, tabulated around the ship chunk by chunk).
Declustering
    Crossings of the same threshold in the same record closer than the decorrelation time (roll
    autocorrelation envelope below 0.05) form a cluster; the largest metric is kept.
Extrapolation and intervals
    Poisson-GPD maximum likelihood of the declustered metric above its ``metric_quantile``
    (``statistics.tail``): crossings whose bracket never capsized are left-censored (y below the value
    at the largest perturbation), not values. Capsize rate = cluster rate x P(y >= 1), with its
    profile-likelihood interval (cluster count, exceedance probability, GPD scale and shape) and the
    same interval with the shape fixed (the share of the uncertainty due to the extrapolation).
Thresholds
    Every configured threshold is estimated; the reported one is the highest with at least
    ``min_clusters`` declustered crossings in the sample (documented rule), and the others'
    estimates are checked against its interval.
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
from stabflow.statistics.ensemble import Model, advance, force_table, record_table, simulate_record
from stabflow.waves.synthesis import one_blas_thread, station_wave_table
from stabflow.statistics.extremes import decluster
from stabflow.statistics.tail import shape_share
from stabflow.io import annotate
from stabflow.statistics.signals import decorrelation_time


def bisect_critical(capsizes, dmax: float, tol: float, dmin: float = 0.0) -> tuple[float, int]:
    """Critical perturbation: the smallest delta in [dmin, dmax] for which ``capsizes(delta)`` is
    True, to ``tol`` (bisection, capsizing assumed monotonic in delta over the bracket).

    If the unperturbed motion (delta = 0) does not capsize the bracket is [0, dmax]: inf if even dmax
    does not capsize. If it does, the critical rate lies below the unperturbed one and the bracket is
    [dmin, 0] (``dmin`` < 0, e.g. minus the roll rate at the crossing): a negative delta, so the
    metric exceeds 1 and is continuous across capsizing (paper 003: extrapolate the metric to 1);
    dmin itself when even dmin capsizes. Returns (delta, runs)."""
    runs = 1
    if capsizes(0.0):
        if dmin >= 0.0:
            return 0.0, runs
        runs += 1
        if capsizes(dmin):
            return dmin, runs
        lo, hi = dmin, 0.0
    else:
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
    t0 + tau / 2 and t0 + tau (the same float32 tables as the ensemble's; the derivative model's
    coefficients likewise). Returns the new state."""
    times = np.array([t0, t0 + 0.5 * tau, t0 + tau])
    out = np.empty((2, N_STATE))
    if model.derivative is not None:
        from stabflow.dynamics.derivative import step_derivative

        step_derivative(model.derivative, model.derivative.coefficient_table(components, times, dtype=np.float32), tau,
                        0, 1, s, np.inf, out)
        return out[1]
    amp, w, ph = components
    tab = station_wave_table(amp, w, ph, model.sec.x, model.cond["heading_deg"], model.speed, times, model.decay,
                             dtype=np.float32, curvature=model.curved)
    ftab = force_table(model, components, times)
    _simulate(*kernel_args(model.sec, model.tables), model.p, tab, ftab, tau, 0, 1, np.asarray(s, float), np.inf, out,
              np.empty((0, 6)))
    return out[1]


def crossing_state(model: Model, components, states: np.ndarray, n0: int, level: float,
                   iterations: int = 6) -> tuple[float, np.ndarray]:
    """The state at the instant roll crosses ``level`` [rad] between steps ``n0`` and ``n0 + 1``:
    RK4 sub-steps from the step before the crossing, the sub-step length refined by Newton's method
    on roll(tau) - level (start: linear interpolation). Returns (time [s], state). 6-DOF conditions:
    the state at step ``n0 + 1``, the first beyond the level."""
    dt = model.dt
    if model.six is not None:
        # 6-DOF: the first grid state beyond the level (the damping's roll amplitude is updated at
        # the steps; an off-grid sub-step would not have it)
        return (n0 + 1) * dt, states[n0 + 1].copy()
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
                  side: int, delta_deg: float, buf: np.ndarray, base: np.ndarray | None = None, base_last: int = -1,
                  ret: float = 0.0) -> tuple[int, int]:
    """Follow the record from the crossing state ``s_c`` at ``t_c`` [s] (between steps n0 and n0 + 1)
    with the roll rate increased by ``side * delta_deg`` [deg/s]: a sub-step of the rest of step n0,
    then the grid up to step ``n1`` at most; ``buf`` (nsteps + 1, N_STATE) receives the grid states
    from n0 + 1.

    With the unperturbed states ``base`` (valid up to ``base_last``) the run stops as soon as it has
    returned to them: sqrt(droll^2 + (droll_rate / w_roll)^2) below ``ret`` [rad] at a check (every
    quarter roll period; paper 003: perturbed runs are truncated at 90 deg or when the motion
    converges to the unperturbed solution). Returns (outcome, last step done): 1 capsized (roll
    beyond 90 deg), 0 returned, -1 neither by step n1.

    ``wtab`` is the record's table (:func:`stabflow.statistics.ensemble.record_table`). 6-DOF
    conditions: ``s_c`` is the grid state at step n0 + 1 (:func:`crossing_state`), perturbed there."""
    cap = np.radians(90.0)
    s = s_c.copy()
    s[S_RATE + S_ROLL] += side * np.radians(delta_deg)
    if model.six is None:
        s = sub_step(model, components, s, t_c, (n0 + 1) * model.dt - t_c)
    buf[n0 + 1] = s
    k = n0 + 1
    w = 2 * np.pi / model.roll_period
    chunk = max(1, int(round(0.25 * model.roll_period / model.dt)))
    while True:
        if abs(buf[k, S_ROLL]) > cap:
            return 1, k
        if base is not None and k <= base_last:
            d = np.hypot(buf[k, S_ROLL] - base[k, S_ROLL], (buf[k, S_RATE + S_ROLL] - base[k, S_RATE + S_ROLL]) / w)
            if d < ret:
                return 0, k
        if k >= n1:
            return -1, k
        k1 = min(k + chunk, n1)
        last = advance(model, -1, wtab, buf[k], k, k1, buf, cap, components=components)
        if last < k1:
            return 1, last
        k = k1


def crossing_metric(rate: np.ndarray, delta: np.ndarray, dmax: float) -> tuple[np.ndarray, np.ndarray]:
    """Metric y = rate / (rate + delta) of crossings (roll rate at the crossing and critical
    perturbation, same units; paper 003 eq. 1 in the form that is 1 at capsize) and its kind:
    0 exact (y > 1 where the unperturbed motion capsizes and the critical rate lies below the
    crossing's); -1 left-censored at rate / (rate + dmax) (no capsize within the bracket); +1 where
    even zero roll rate at the crossing capsizes (y = inf: at least 1)."""
    rate = np.abs(np.asarray(rate, float))
    delta = np.asarray(delta, float)
    if np.isnan(delta).any() or np.isnan(rate).any():
        raise ValueError("crossing_metric: a crossing without a critical perturbation (NaN)")
    y = np.full(len(rate), np.inf)
    kind = np.zeros(len(rate), np.int8)
    fin = np.isfinite(delta) & (rate + delta > 0)
    y[fin] = rate[fin] / (rate[fin] + delta[fin])
    cens = np.isposinf(delta)
    y[cens] = rate[cens] / (rate[cens] + dmax)
    kind[cens] = -1
    kind[np.isfinite(delta) & ~fin] = 1
    return y, kind


def decluster_metric(rec, t, y, kind, tau: float):
    """Cluster maxima of crossing metrics (same record, closer than ``tau`` [s]); a cluster takes the
    kind of its maximum. Returns (y, kind, record, time)."""
    order = np.lexsort((np.asarray(t, float), np.asarray(rec)))
    rec, t, y, kind = (np.asarray(a)[order] for a in (rec, t, y, kind))
    yc, rc, tcl = decluster(rec, t, np.where(np.isinf(y), np.finfo(float).max, y) + 1.0, 0.0, tau)
    idx = np.array([np.nonzero((rec == r) & (t == tt))[0][0] for r, tt in zip(rc, tcl)], np.int64)
    return y[idx], kind[idx], rc, tcl


def metric_rate(y, kind, hours: float, quantile: float, alpha: float, fixed_shape: bool = True):
    """Capsize rate from declustered metrics: Poisson-GPD above the metric's ``quantile``
    (``statistics.tail``; left-censored metrics as such, y = inf right-censored at max(1, u)),
    rate = cluster rate x P(y >= 1) with its profile-likelihood interval and the interval with the
    GPD shape fixed (unless ``fixed_shape`` is False: NaN). Returns dict(rate, lower, upper,
    lower_fixed, upper_fixed, xi, sigma, u, n_u);
    NaN entries when fewer than 3 metrics exceed u."""
    from stabflow.statistics.tail import TailData, rate_estimate

    y, kind = np.asarray(y, float), np.asarray(kind)
    if len(y) == 0:
        return rate_estimate(TailData([], hours), np.nan, 1.0, alpha, fixed_shape)
    # the GPD threshold: the metric's quantile, kept below 1 (the model must reach y = 1; above a
    # threshold at 1 the rate is the counted share of clusters at or beyond 1)
    u = min(float(np.quantile(np.where(np.isinf(y), np.finfo(float).max, y), quantile)), 1.0 - 1e-9)
    data = TailData(y[kind == 0], hours, left=y[kind == -1], right=np.full(int(np.sum(kind == 1)), max(1.0, u)))
    return rate_estimate(data, u, 1.0, alpha, fixed_shape)


def critical_perturbations(model: Model, records, steps, sides, levels, follow: int, dmax_deg: float,
                           tol_deg: float, ret: float, threads: int = 1, progress: bool = False):
    """Critical roll-rate perturbation [deg/s] for each crossing (record, step before the crossing,
    side +1/-1) of one threshold. Crossings of one record share its regenerated seaway; records run
    in parallel threads (the RK4 kernel releases the GIL).

    ``levels`` is the crossed roll angle of each crossing [deg] (signed). The perturbation is applied
    to the exact state at the crossing instant (:func:`crossing_state`); each perturbed run is
    followed until it capsizes or returns to the unperturbed solution (distance below ``ret`` times
    the perturbation's, :func:`perturbed_run`), at most ``follow`` steps (then it counts as not
    capsized; such runs are counted). A run that returns shares the unperturbed outcome: capsized
    when the unperturbed record capsizes before its next crossing of the threshold, which is also
    the outcome at delta = 0. The bisection (:func:`bisect_critical`) searches [0, dmax] when the
    unperturbed record survives the crossing and [-rate, 0] when it capsizes. Returns (delta [deg/s],
    bisection runs, roll rate at the crossing [deg/s], crossing time [s], undecided runs) per
    crossing."""
    from tqdm import tqdm

    records = np.asarray(records)
    steps = np.asarray(steps)
    sides = np.asarray(sides)
    levels = np.asarray(levels, float)
    delta = np.full(len(records), np.nan)
    runs = np.zeros(len(records), np.int64)
    undecided = np.zeros(len(records), np.int64)
    rate_at = np.full(len(records), np.nan)
    t_at = np.full(len(records), np.nan)
    w = 2 * np.pi / model.roll_period

    def one_record(r):
        idx = np.nonzero(records == r)[0]
        idx = idx[np.argsort(steps[idx], kind="stable")]
        wtab = record_table(model, int(r))
        comps = model.sea.components(model.cond["seed"], int(r))
        states, last = simulate_record(model, int(r), wtab=wtab)
        buf = np.empty_like(states)
        for j, c in enumerate(idx):
            n0 = int(steps[c])
            n1 = min(n0 + follow, model.nsteps)
            nxt = int(steps[idx[j + 1]]) if j + 1 < len(idx) else np.iinfo(np.int64).max
            base_caps = bool(last < model.nsteps and last <= nxt)
            tc, s0 = crossing_state(model, comps, states, n0, np.radians(levels[c]))
            rate_at[c], t_at[c] = abs(np.degrees(s0[S_RATE + S_ROLL])), tc

            def capsizes(d, s0=s0, n0=n0, n1=n1, side=sides[c], tc=tc, base_caps=base_caps, c=c):
                if d == 0.0:
                    return base_caps
                out, _ = perturbed_run(model, comps, wtab, s0, tc, n0, n1, side, d, buf, states, last,
                                       ret * np.radians(abs(d)) / w)
                undecided[c] += out < 0
                return out > 0 or (out == 0 and base_caps)

            delta[c], runs[c] = bisect_critical(capsizes, dmax_deg, tol_deg, dmin=-rate_at[c])
        return len(idx)

    todo = np.unique(records)
    # BLAS on one thread for the whole pool, set here in the calling thread: the worker threads'
    # wave tables then never change the process-wide limit (bit-identical files, any job threads)
    with one_blas_thread(), ThreadPoolExecutor(max_workers=max(1, threads)) as ex:
        for _ in tqdm(ex.map(one_record, todo), total=len(todo), desc="perturbations (records)",
                      disable=not progress, mininterval=10):
            pass
    return delta, runs, rate_at, t_at, undecided


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
    from stabflow.statistics.ensemble import record_samples

    n_samples = int(record_samples(ens).values[in_s].sum())
    hours = float(ens["steps"].values[in_s].sum()) * dt / 3600.0
    bf_k = int(ens["capsized"].values[~in_s].sum())
    bf_hours = float(ens["steps"].values[~in_s].sum()) * dt / 3600.0
    bf, bf_lo, bf_hi = poisson_interval(bf_k, bf_hours, cfg["alpha"]) if bf_hours > 0 else (np.nan,) * 3
    follow = int(round(cfg["follow_periods"] * model.roll_period / dt))
    thresholds = list(ens["threshold"].values)
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
        delta, runs, rate_u, t, und = critical_perturbations(model, rec, step, side, side * float(thr), follow,
                                                             cfg["max_perturbation"], cfg["tolerance"],
                                                             cfg["return_fraction"], threads, progress)
        y, kind = crossing_metric(rate_u, delta, cfg["max_perturbation"])
        # declustering: same threshold, same record, closer than tau; the largest metric is kept
        yc, kc, rc, tc = decluster_metric(rec, t, y, kind, tau)
        est = metric_rate(yc, kc, hours, cfg["metric_quantile"], cfg["alpha"])
        lam_cl = len(yc) / hours
        raw, raw_lo, raw_hi = crossing_rate(len(rec), n_samples, dt, cfg["alpha"])
        res.append(dict(thr=thr, n_cross=len(rec), raw=raw, raw_lo=raw_lo, raw_hi=raw_hi, n_cl=len(yc), lam_cl=lam_cl,
                        u=est["u"], xi=est["xi"], sig=est["sigma"], n_u=est["n_u"],
                        p=est["rate"] / lam_cl if lam_cl > 0 else np.nan, lam=est["rate"], lo=est["lower"],
                        hi=est["upper"], lo_f=est["lower_fixed"], hi_f=est["upper_fixed"], runs=int(runs.sum()),
                        undecided=int(und.sum()), inside=int(est["lower"] <= bf <= est["upper"]),
                        capsized_crossings=int(np.sum(y >= 1.0)), censored=int(np.sum(kind == -1))))
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
            "capsize_rate_lower_fixed_shape": ("split_threshold", R["lo_f"]),
            "capsize_rate_upper_fixed_shape": ("split_threshold", R["hi_f"]),
            "perturbed_runs": ("split_threshold", R["runs"]),
            "undecided_runs": ("split_threshold", R["undecided"]),
            "censored_crossings": ("split_threshold", R["censored"]),
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
    # documented threshold rule: the highest threshold with at least min_clusters clusters in the sample
    ok = [k for k, n in enumerate(R["n_cl"]) if n >= int(cfg["min_clusters"])]
    rep = max(ok, key=lambda k: R["thr"][k]) if ok else int(np.argmin(R["thr"]))
    ds["reported"] = ("split_threshold", (np.arange(len(R["thr"])) == rep).astype(np.int8))
    ds["threshold_consistent"] = ("split_threshold", ((R["lam"] >= R["lo"][rep]) & (R["lam"] <= R["hi"][rep])).astype(np.int8))
    ds["extrapolation_share"] = ("split_threshold", shape_share(R["lo"], R["hi"], R["lo_f"], R["hi_f"]))
    ds.attrs.update(ship=ens.attrs["ship"], condition=ens.attrs["condition"], window_steps=follow,
                    tolerance=float(cfg["tolerance"]), max_perturbation=float(cfg["max_perturbation"]),
                    return_fraction=float(cfg["return_fraction"]),
                    interval=f"profile likelihood {100 * (1 - cfg['alpha']):g} % (cluster count, exceedance "
                             "probability, GPD scale and shape)",
                    fit="Poisson-GPD maximum likelihood of the declustered metric, never-capsizing brackets "
                        "left-censored (stabflow.statistics.tail)",
                    metric="y = phidot_U / (phidot_U + delta_cr); > 1 where the unperturbed motion capsizes",
                    threshold_rule=f"reported: the highest threshold with at least {int(cfg['min_clusters'])} "
                                   "declustered crossings in the sample")
    return annotate(ds)


def perturbed_histories(model: Model, record: int, step: int, side: int, deltas, window: int, level_deg: float):
    """Roll [deg] of the unperturbed record and of perturbed runs (roll rate + side * delta [deg/s]
    at the exact crossing of ``side * level_deg`` after ``step``, as in :func:`critical_perturbations`)
    over ``window`` steps (paper 003 Fig. 4). Returns (t [s], unperturbed, list of runs), starting at
    the crossing instant."""
    wtab = record_table(model, int(record))
    comps = model.sea.components(model.cond["seed"], int(record))
    states, last = simulate_record(model, int(record), wtab=wtab)
    tc, sc = crossing_state(model, comps, states, step, np.radians(side * level_deg))
    n1 = min(step + window, model.nsteps)
    t = np.concatenate([[tc], np.arange(step + 1, n1 + 1) * model.dt])
    runs = []
    for d in deltas:
        buf = np.full(states.shape, np.nan)
        perturbed_run(model, comps, wtab, sc, tc, step, n1, side, d, buf)
        runs.append(np.degrees(np.concatenate([[sc[S_ROLL]], buf[step + 1: n1 + 1, S_ROLL]])))
    base = np.full(len(t), np.nan)
    base[0] = np.degrees(sc[S_ROLL])
    m = min(last, n1)
    base[1: m - step + 1] = np.degrees(states[step + 1: m + 1, S_ROLL])
    if model.six is not None:  # the crossing state is the grid state at step + 1: drop the repeated instant
        return t[1:], base[1:], [r[1:] for r in runs]
    return t, base, runs
