"""Irregular-sea checks: the seaway, the RK4 step, the extremes and the split-time estimates.

| check | reference | tolerance | kind |
|---|---|---|---|
| seaway: elevation variance | analytic m0 = Hs^2 / 16 of the target spectrum | 3 % | independent |
| seaway: Welch spectral density over the energetic band (S > 0.3 max) | analytic target S(w) | 15 % | independent |
| seaway: skewness, excess kurtosis of the elevation | Gaussian sea (0, 0) | 0.05, 0.1 | independent |
| seaway: largest distance of the elevation's CDF from the normal CDF (-3 to 3 sigma) | standard normal | 0.01 | independent |
| ensemble records regenerated from (seed, record) at dt | the ensemble's stored per-record moment sums | 1e-9 (relative) | consistency |
| step size: roll (6-DOF: and yaw) trajectory over the first 30 s of 10 records at dt vs dt / 5, largest difference / largest value (at least 1 degree) | the same records at dt / 5 | 1 % | consistency |
| step size: roll standard deviation at dt vs dt / 5 | the same records (same seaways) at dt / 5 | 0.5 % | consistency |
| step size: 0.999 quantile of abs(roll) at dt vs dt / 5 | the same records (same seaways) at dt / 5 | 1 % | consistency |
| step size, sigma and q0.999: paired-bootstrap 95 % interval of the effect (its largest bound; at least 10 records) | the same records at dt / 5, resampled by record together | 0.5 %, 1 % | consistency |
| extremes, per target angle: coverage of the brute-force rate by the interval over the samples | brute-force count of the declustered |roll| maxima (capsizes included) in the rest of the ensemble | >= 0.90 | independent |
| extremes, per target angle: median over the samples of estimate / brute force | the same brute-force count | 0.7 to 1.4 | independent |
| split-time, per threshold: brute-force rate inside the interval (1 / 0) | capsized records among the other records (Garwood interval) | = 1 | independent |
| split-time, per threshold: split-time rate / brute-force rate | the same brute-force count | 0.7 to 1.4 | independent |

Seaway
    The elevation of the condition's own seaway (``Seaway.components(seed, r)``, records
    0, 1, ...) is synthesised by ``station_wave_table`` at a fixed point (no forward speed, so the
    frequencies are the absolute ones of the target spectrum), sampled every 0.5 s (finer if the
    spectrum reaches beyond 0.8 pi / 0.5 s), over at least 40 records and at least 20 hours: the
    method and the tolerances of ``tests/waves/test_seaway.py`` (Welch segments of 256 s = 512
    samples, Hann window, averaged over records). Measured: DTMB 5415 condition (Bretschneider
    Hs 8.5 m, Tp 15 s, 220 components, 40 x 1800 s): variance -1.7 %, density 8.1 %, skewness
    0.002, excess kurtosis -0.025, CDF distance 0.002; barge beam sea (Hs 3.5 m, Tp 10 s, 120
    components, 80 x 900 s): +0.6 %, 10.4 %, -0.0005, -0.030, 0.002.
Step size
    The first ``CONVERGENCE_RECORDS`` records of the ensemble are simulated again through
    ``run_shard`` at the condition's step dt and at dt / 5. Roll standard deviation and the 0.999
    quantile of abs(roll) (roll histogram folded about 0, ``quantile_from_histogram``) at dt are
    compared with those at dt / 5, over the records that capsize at neither step: whether a record
    that comes close to capsizing does capsize depends on any perturbation (barge beam sea, 200
    records: 19 capsizes at dt = 0.5, 0.25, 0.1 and 0.05 s each, not all the same records), and one
    such record moves the 0.999 quantile by several percent. The capsize counts at both steps are in
    the row's reference. Measured (100 records, dt = 0.5 s vs 0.1 s): DTMB 5415 stern-quartering
    Hs 8.5 m, 10 kn: sigma -0.003 %, q0.999 +0.05 % (200 and 400 records: -0.09 %, -0.19 %); barge
    beam sea Hs 3.5 m: sigma -0.23 %, q0.999 -0.59 % (the test profile's 24 records: +0.02 %,
    +0.82 %; the 178 of 200 records that capsize at none of 0.5, 0.25, 0.1, 0.05 s: -0.27 %,
    -0.83 %, and 0.1 s vs 0.05 s: -0.00 %, -0.07 %). In chaotic records (steep stern-quartering
    seas with the 6-DOF model, parametric roll) two records of different steps part after a minute
    or so however small the steps, and the statistics of 100 records then compare two realisations:
    the trajectory row measures the step where the records are still predictable, the first
    ``TRAJECTORY_S`` seconds of the first ``TRAJECTORY_RECORDS`` records (roll, and yaw for 6-DOF,
    each relative to its largest value there: ``benchmarks/bench_six_dof.py``'s criterion of a
    converged step). Beside the sigma and quantile rows, their sampling interval (``paired_step_effect``):
    a row passes when the whole interval lies within the tolerance, and its name says whether the
    interval holds 0, which separates a step effect from two realisations' scatter. Under
    ``BOOTSTRAP_MIN_RECORDS`` records kept the two rows FAIL with that reason (the interval still in
    their names), and an effect that is undefined in any resample (a statistic of 0) FAILs them. The run at dt is also
    compared with the ensemble's own per-record moment sums: ``model`` must be the model of ``ens``
    (records regenerate bit for bit), otherwise none of these rows would describe ``ens``.
Extremes, split-time
    Taken from the datasets of those steps (``extremes.analyse``, ``splittime.analyse``). A target
    or threshold whose brute-force count is zero has nothing to be compared with: its rows are FAIL
    with that reason, never NaN. A step that does not run for the condition (dataset ``None``) gives
    SKIPPED rows with that reason.
"""

from __future__ import annotations

import dataclasses
import re
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import xarray as xr
from scipy import signal, stats

from stabflow.statistics.ensemble import merge, run_shard
from stabflow.statistics.signals import quantile_from_histogram
from stabflow.waves.synthesis import one_blas_thread, station_wave_table
from stabflow.validation import Check, run_check

#: seaway: records and hours of elevation at least (tests/waves/test_seaway.py: 40 x 30 min)
SEAWAY_RECORDS = 40
SEAWAY_HOURS = 20.0
SEAWAY_DT = 0.5  # sampling step of the elevation [s] (smaller if the spectrum reaches beyond 0.8 pi / dt)
SEAWAY_SEGMENT_S = 256.0  # Welch segment [s] (512 samples at 0.5 s)
TOL_VARIANCE = 3.0  # %
TOL_DENSITY = 15.0  # % over S > 0.3 max S
ENERGETIC = 0.3  # fraction of the spectral peak that defines the energetic band
TOL_SKEWNESS = 0.05
TOL_EXCESS_KURTOSIS = 0.1
TOL_CDF = 0.01  # largest |F_n(q) - Phi(q)|, q = -3 ... 3 sigma

#: step size: records, refinement, tolerances (measured values in the module docstring;
#: benchmarks/bench_ensemble.py, DTMB 5415 SS8: sigma and q0.999 within 0.5 % at 0.5 s vs 0.1 s).
#: 100 records, not fewer: over 20 records of DTMB 5415 q0.999 (the tail of 72,000 samples) moves by 1.1 %.
CONVERGENCE_RECORDS = 100
REFINE = 5
TOL_SIGMA = 0.5  # %
TOL_Q999 = 1.0  # %
TOL_REGENERATION = 1e-9  # relative, per (dof, moment order)
#: step size, trajectory: the first TRAJECTORY_S seconds of the first TRAJECTORY_RECORDS records
TRAJECTORY_S = 30.0
TRAJECTORY_RECORDS = 10
TOL_TRAJECTORY = 1.0  # % of the largest value (benchmarks/bench_six_dof.py's converged step)
#: step size, sampling interval of the step's effect on sigma and q0.999: records resampled with
#: replacement, the same draw at both steps (paired), percentile interval (Efron & Tibshirani 1993,
#: ch. 13); a fixed seed, so that the rows are the same at every run
BOOTSTRAP_RESAMPLES = 2000
BOOTSTRAP_LEVEL = 0.95
BOOTSTRAP_SEED = 20261202
#: fewest records for a verdict from the interval (stabflow's choice): with fewer, the percentile
#: interval over records is too coarse to show a step adequate (8 records give 6,435 distinct
#: resamples, and the bootstrap's spread falls short of the sampling spread by about sqrt((n-1)/n)
#: and more for a tail quantile); the rows then FAIL with the reason, the interval still in the name
BOOTSTRAP_MIN_RECORDS = 10
#: the two step-size statistics: key of paired_step_effect -> (name in the rows, tolerance [%])
STEP_STATISTICS = {"sig": ("roll standard deviation", TOL_SIGMA), "q": ("0.999 quantile of |roll|", TOL_Q999)}
#: the trajectory's scale is at least this [rad]: a record whose roll stays below a degree (head seas)
#: would otherwise judge the step by differences of thousandths of a degree
TRAJECTORY_FLOOR = np.radians(1.0)

#: extremes and split-time acceptance (the criterion set for the statistics of the project)
MIN_COVERAGE = 0.90
RATIO_BAND = (0.7, 1.4)


def _pct(text: str, default: str = "95 %") -> str:
    """The confidence level written in an ``interval`` attribute ('..., 95 %'), or ``default``."""
    m = re.search(r"(\d+(?:\.\d+)?)\s*%", text or "")
    return f"{m.group(1)} %" if m else default


# --------------------------------------------------------------------------------------------
# seaway


def seaway_elevation(model, records: int | None = None, dt: float | None = None) -> tuple[np.ndarray, float]:
    """Elevation [m] of the condition's seaway at a fixed point, records 0, 1, ... of its master seed.

    Parameters
    ----------
    model : stabflow.statistics.ensemble.Model
        The condition (``model.sea``, ``model.cond['seed']``, ``model.cond['duration']``).
    records : int, optional
        Number of records; default: at least ``SEAWAY_RECORDS`` and ``SEAWAY_HOURS`` hours.
    dt : float, optional
        Sampling step [s]; default ``SEAWAY_DT``, reduced so that the Nyquist frequency pi / dt is at
        least 1.25 times the highest component frequency.

    Returns
    -------
    eta : ndarray, shape (records, samples)
        Elevation, one row per record.
    dt : float
        The sampling step used [s].
    """
    duration = float(model.cond["duration"])
    if records is None:
        records = max(SEAWAY_RECORDS, int(np.ceil(SEAWAY_HOURS * 3600.0 / duration)))
    if dt is None:
        wmax = float(model.sea.edges()[-1])
        dt = min(SEAWAY_DT, np.pi / (1.25 * wmax))
    t = np.arange(0.0, duration, dt)
    seed = int(model.cond["seed"])
    rows = []
    for r in range(records):
        a, w, p = model.sea.components(seed, r)
        rows.append(station_wave_table(a, w, p, np.array([0.0]), 0.0, 0.0, t)[:, 0, 0])
    return np.array(rows), dt


def seaway_checks(model) -> list[Check]:
    """Variance, spectral density and Gaussian marginal of the condition's seaway against the
    analytic target spectrum.

    Parameters
    ----------
    model : stabflow.statistics.ensemble.Model
        The condition.

    Returns
    -------
    list of Check
        Five independent rows (variance, density, skewness, excess kurtosis, CDF distance); all FAIL
        with the reason if the seaway cannot be synthesised.
    """
    sea = model.sea
    spec = f"{sea.kind} Hs {sea.hs:g} m" + (f", Tp {sea.tp:g} s" if sea.tp is not None else "")
    names = {
        "var": ("seaway: elevation variance vs Hs^2/16", "%", f"analytic m0 = Hs^2/16 ({spec})",
                dict(tolerance=TOL_VARIANCE)),
        "psd": (f"seaway: Welch spectral density vs S(w), largest deviation over S > {ENERGETIC:g} max", "%",
                f"analytic target spectrum S(w) ({spec})", dict(tolerance=TOL_DENSITY)),
        "skew": ("seaway: elevation skewness", "-", "Gaussian sea: 0", dict(tolerance=TOL_SKEWNESS)),
        "kurt": ("seaway: elevation excess kurtosis", "-", "Gaussian sea: 0", dict(tolerance=TOL_EXCESS_KURTOSIS)),
        "cdf": ("seaway: largest distance of the elevation CDF from the normal CDF (-3 to 3 sigma)", "-",
                "standard normal CDF (scipy.stats.norm)", dict(tolerance=TOL_CDF)),
    }
    try:
        eta, dt = seaway_elevation(model)
    except Exception as exc:  # noqa: BLE001 - every row says why it could not run
        return [Check.failed(n, f"seaway synthesis failed: {type(exc).__name__}: {exc}", u, ref, **band)
                for n, u, ref, band in names.values()]
    nrec, nsamp = eta.shape
    what = f" ({nrec} records x {nsamp * dt:g} s, sampled every {dt:g} s)"
    x = eta.ravel()

    def variance():
        return 100.0 * (x.var() / (sea.hs**2 / 16.0) - 1.0)

    def density():
        nseg = min(1 << int(round(np.log2(SEAWAY_SEGMENT_S / dt))), 1 << int(np.log2(nsamp)))
        f, p = signal.welch(eta, fs=1.0 / dt, nperseg=nseg)
        w, S = 2 * np.pi * f, p.mean(axis=0) / (2 * np.pi)
        target = sea.density(w)
        band = target > ENERGETIC * target.max()
        if not band.any():
            raise ValueError("no frequency of the Welch estimate lies in the energetic band")
        return 100.0 * np.max(np.abs(S[band] / target[band] - 1.0))

    z = (x - x.mean()) / x.std()

    def cdf_distance():
        q = np.linspace(-3.0, 3.0, 61)
        return np.max(np.abs(np.searchsorted(np.sort(z), q) / len(z) - stats.norm.cdf(q)))

    fns = {"var": variance, "psd": density, "skew": lambda: stats.skew(z), "kurt": lambda: stats.kurtosis(z),
           "cdf": cdf_distance}
    return [run_check(fns[k], n + what, u, ref, "independent", **band) for k, (n, u, ref, band) in names.items()]


# --------------------------------------------------------------------------------------------
# step size


def roll_q999(ens: xr.Dataset) -> float:
    """0.999 quantile of abs(roll) [degree] from the ensemble's roll histogram folded about 0.

    Parameters
    ----------
    ens : xarray.Dataset
        Merged ensemble (``hist_roll`` on the symmetric bins ``roll_bin``).

    Returns
    -------
    float
        The quantile [degree], interpolated in the cumulative histogram.
    """
    h = ens["hist_roll"].values
    c = ens["roll_bin"].values
    half = len(h) // 2
    if len(h) % 2 or not np.allclose(c[half:], -c[:half][::-1]):
        raise ValueError("roll histogram bins are not symmetric about 0")
    return quantile_from_histogram(h[half:] + h[:half][::-1], c[half:], 0.999)


def record_arrays(shards: list[xr.Dataset]) -> dict[str, np.ndarray]:
    """Per-record roll sums of one-record shard datasets (``_rerun``): samples ``n`` (R,), sums of
    roll and roll^2 ``s1``, ``s2`` (R,) [degree, degree^2], the roll histogram folded about 0
    ``hist`` (R, nbins) on the bin centres ``bins`` (nbins,) [degree]."""
    first = shards[0]
    c = first["roll_bin"].values
    half = len(c) // 2
    if len(c) % 2 or not np.allclose(c[half:], -c[:half][::-1]):
        raise ValueError("roll histogram bins are not symmetric about 0")
    n, s1, s2, hist = [], [], [], []
    for d in shards:
        ms = d["moment_sums"].sel(dof="roll")
        n.append(float(d["steps"].values.sum()) + d.sizes["record"])
        s1.append(float(ms.sel(order=1).sum()))
        s2.append(float(ms.sel(order=2).sum()))
        h = d["hist_roll"].values
        hist.append(h[half:] + h[:half][::-1])
    return dict(n=np.array(n), s1=np.array(s1), s2=np.array(s2), hist=np.array(hist, float), bins=c[half:])


def paired_step_effect(a: dict, b: dict, resamples: int = BOOTSTRAP_RESAMPLES, level: float = BOOTSTRAP_LEVEL,
                       seed: int = BOOTSTRAP_SEED) -> dict[str, tuple[float, float, float]]:
    """The step's effect on roll sigma and on the 0.999 quantile of abs(roll) with its sampling
    interval, by a paired bootstrap over records.

    Parameters
    ----------
    a, b : dict
        :func:`record_arrays` of the same records at the two steps (same order).
    resamples, level, seed : int, float, int
        Bootstrap resamples, confidence level of the interval, seed of the resampling.

    Returns
    -------
    dict
        ``"sig"`` and ``"q"``: (effect, lower, upper) [%], the effect 100 (x_a / x_b - 1) over all
        records and the percentile interval of its bootstrap distribution.

    Notes
    -----
    Each resample draws the records with replacement and sums the same records' moment sums and
    histograms at both steps, so that what the records share (their seaways, and their first minute
    or so before chaotic records part) cancels as it does in the effect itself. The interval is the
    spread that a new set of as many records would give the effect: in records that stay predictable
    it is narrow about the effect, and in chaotic records it is the two realisations' sampling scatter.
    """
    R = len(a["n"])
    if len(b["n"]) != R:
        raise ValueError(f"paired bootstrap needs the same records at both steps ({R} and {len(b['n'])})")
    if R < 2:
        raise ValueError(f"paired bootstrap needs at least 2 records ({R} kept): one record resamples to itself")
    rng = np.random.default_rng(seed)
    W = np.zeros((resamples + 1, R))
    W[0] = 1.0  # row 0: all records once (the effect itself)
    idx = rng.integers(0, R, size=(resamples, R))
    np.add.at(W, (np.repeat(np.arange(1, resamples + 1), R), idx.ravel()), 1.0)

    def stats(x):
        N = W @ x["n"]
        m = (W @ x["s1"]) / N
        sig = np.sqrt(np.maximum((W @ x["s2"]) / N - m * m, 0.0))
        H = W @ x["hist"]
        q = np.array([quantile_from_histogram(h, x["bins"], 0.999) for h in H])
        return sig, q

    (sa, qa), (sb, qb) = stats(a), stats(b)
    out = {}
    tail = 50.0 * (1.0 - level)
    for key, xa, xb in (("sig", sa, sb), ("q", qa, qb)):
        with np.errstate(divide="ignore", invalid="ignore"):
            d = 100.0 * (xa / xb - 1.0)
        bad = int(np.count_nonzero(~np.isfinite(d)))
        if bad:
            raise ValueError(f"the {STEP_STATISTICS[key][0]} is zero or not finite at the reference step in {bad} of the "
                             f"{resamples + 1} (re)samples: the effect is undefined there")
        lo, hi = np.percentile(d[1:], [tail, 100.0 - tail])
        out[key] = (float(d[0]), float(lo), float(hi))
    return out


def _rerun(model, dt: float, records, threads: int = 1) -> dict[int, xr.Dataset]:
    """``records`` simulated again at step ``dt``, one shard dataset per record (no time histories
    kept), so that any subset merges without simulating it again.

    With ``threads`` > 1 the records of the 6-DOF and derivative models run in a thread pool (their
    kernels release the GIL); 3-DOF records run one after the other (their batch kernel uses numba's
    own threads, which must not be entered from several Python threads at once)."""
    m = dataclasses.replace(model, cond=dict(model.cond, dt=dt, samples=0))
    recs = [int(r) for r in records]

    def one(r):
        return run_shard(m, [r], progress=False)

    if threads > 1 and (m.six is not None or m.derivative is not None):
        with one_blas_thread(), ThreadPoolExecutor(max_workers=threads) as ex:
            return dict(zip(recs, ex.map(one, recs)))
    return {r: one(r) for r in recs}


def trajectory_error(model, records, dt: float, fine: float, seconds: float = TRAJECTORY_S) -> float:
    """Largest difference [%] between the first ``seconds`` of each of ``records`` simulated at ``dt``
    and at ``fine`` (a divisor of dt), at the steps of dt, of roll (and yaw for 6-DOF models), each
    relative to its largest absolute value at ``fine`` over those seconds of that record, or to
    ``TRAJECTORY_FLOOR`` (1 degree) where that is smaller."""
    from stabflow.dynamics._kernels import S_ROLL, S_YAW
    from stabflow.statistics.ensemble import simulate_record

    k = int(round(dt / fine))
    # the first seconds from rest: no warm-up (with one, the records would run warmup_s + seconds)
    short = dict(model.cond, duration=seconds, samples=0, warmup_s=0.0)
    coarse = dataclasses.replace(model, cond=dict(short, dt=dt))
    refined = dataclasses.replace(model, cond=dict(short, dt=fine))
    dofs = (S_ROLL, S_YAW) if model.six is not None else (S_ROLL,)
    worst = 0.0
    for r in records:
        sa, na = simulate_record(coarse, int(r))
        sb, nb = simulate_record(refined, int(r))
        worst = max(worst, relative_trajectory_error(sa[:na + 1, dofs], sb[:nb + 1, dofs], k))
    return worst


def relative_trajectory_error(coarse: np.ndarray, fine: np.ndarray, k: int) -> float:
    """Largest difference [%] between the columns (angles [rad]) of ``coarse`` (steps of dt, rows 0 ...)
    and ``fine`` (steps of dt / ``k``) at the coarse steps both reach, each column relative to its
    largest absolute value at ``fine`` there, or to ``TRAJECTORY_FLOOR`` (1 degree) where that is
    smaller (:func:`trajectory_error`; the broaching map's step row)."""
    n = min(len(coarse), (len(fine) - 1) // k + 1)
    ref = fine[:(n - 1) * k + 1:k]
    scale = np.maximum(np.max(np.abs(ref), axis=0), TRAJECTORY_FLOOR)
    return 100.0 * float(np.max(np.max(np.abs(coarse[:n] - ref), axis=0) / scale))


def step_checks(model, ens: xr.Dataset, records: int = CONVERGENCE_RECORDS, threads: int = 1) -> list[Check]:
    """Regeneration and step-size convergence rows (consistency).

    Parameters
    ----------
    model : stabflow.statistics.ensemble.Model
        The condition's model.
    ens : xarray.Dataset
        The condition's merged ensemble.
    records : int
        Records to simulate again (the first ones of ``ens``).
    threads : int
        Threads for the re-simulation (6-DOF and derivative models; results do not depend on it).

    Returns
    -------
    list of Check
        Regeneration at dt, the trajectory over the first ``TRAJECTORY_S`` seconds
        (:func:`trajectory_error`), roll standard deviation and 0.999 quantile of abs(roll) at dt vs
        dt / ``REFINE`` (percent), and the paired-bootstrap intervals of those two effects
        (:func:`bootstrap_rows`); FAIL rows with the reason when they cannot be computed.

    Notes
    -----
    The first ``records`` records of ``ens`` are simulated again at the condition's dt and at
    dt / ``REFINE``. Whether a record that comes close to capsizing does capsize depends on any
    perturbation, round-off included (barge beam sea, 200 records: 19 capsizes at dt = 0.5, 0.25,
    0.1 and 0.05 s, but not all the same records), so the statistics are compared over the records
    that capsize at neither step; the capsize counts at both steps are written in the reference.
    """
    dt = model.dt
    fine = dt / REFINE
    rows_spec = {
        "reg": ("ensemble records regenerated from (seed, record) at dt = {dt:g} s ({n} records): largest relative "
                "difference of the moment sums", "-", "per-record moment sums stored in the ensemble dataset",
                dict(tolerance=TOL_REGENERATION)),
        "traj": ("step size: {what} trajectory over the first {ts:g} s of {nt} records at dt = {dt:g} s vs dt = {fine:g} s: "
                 "largest difference / largest value (at least 1 deg)", "%", "the same records at dt / {r} = {fine:g} s",
                 dict(tolerance=TOL_TRAJECTORY)),
        **{key: (f"step size: {w} at dt = {{dt:g}} s vs dt = {{fine:g}} s ({{n}} records)", "%",
                 "the same records (same seaways) at dt / {r} = {fine:g} s", dict(tolerance=tol))
           for key, (w, tol) in STEP_STATISTICS.items()},
    }

    what = "roll and yaw" if model.six is not None else "roll"

    def spec(key, n, extra=""):
        name, unit, ref, band = rows_spec[key]
        nt = min(TRAJECTORY_RECORDS, n) if isinstance(n, int) else n
        return (name.format(dt=dt, fine=fine, n=n, what=what, ts=TRAJECTORY_S, nt=nt), unit,
                ref.format(r=REFINE, fine=fine) + extra, band)

    n = "?"
    try:
        recs = ens["record"].values[:records]
        n = len(recs)
        if n == 0:
            raise ValueError("the ensemble has no record")
        pa, pb = _rerun(model, dt, recs, threads), _rerun(model, fine, recs, threads)
        a, b = merge(list(pa.values())), merge(list(pb.values()))
    except Exception as exc:  # noqa: BLE001 - every row says why it could not run
        why = f"re-simulation failed: {type(exc).__name__}: {exc}"
        return [Check.failed(nm, why, u, ref, "consistency", **band) for nm, u, ref, band in
                (spec(k, n) for k in rows_spec)] + bootstrap_rows({}, {}, [], dt, fine, why=why, n=n)

    def regeneration():
        mine = a["moment_sums"].values
        stored = ens["moment_sums"].sel(record=recs).values
        scale = np.abs(stored).max(axis=0)
        return float(np.max(np.abs(mine - stored).max(axis=0) / np.where(scale > 0, scale, 1.0)))

    nm, u, ref, band = spec("reg", n)
    rows = [run_check(regeneration, nm, u, ref, "consistency", **band)]
    nm, u, ref, band = spec("traj", n)
    rows.append(run_check(lambda: trajectory_error(model, recs[:TRAJECTORY_RECORDS], dt, fine), nm, u, ref,
                          "consistency", **band))

    ca, cb = a["capsized"].values != 0, b["capsized"].values != 0
    keep = recs[~ca & ~cb]
    extra = (f"; capsized records: {int(ca.sum())} at dt = {dt:g} s, {int(cb.sum())} at dt = {fine:g} s, "
             f"{int((ca | cb).sum())} left out")
    try:
        if len(keep) == 0:
            raise ValueError(f"all {n} records capsized at dt = {dt:g} s or at dt = {fine:g} s")
        if len(keep) < n:
            a, b = merge([pa[int(r)] for r in keep]), merge([pb[int(r)] for r in keep])
        sa, sb = float(a["roll_std"]), float(b["roll_std"])
        qa, qb = roll_q999(a), roll_q999(b)
    except Exception as exc:  # noqa: BLE001
        why = f"{type(exc).__name__}: {exc}"
        return rows + [Check.failed(nm, why, u, ref, "consistency", **band) for nm, u, ref, band in
                       (spec(k, len(keep), extra) for k in ("sig", "q"))] + bootstrap_rows({}, {}, keep, dt, fine, why=why)
    for key, v, v_ref in (("sig", sa, sb), ("q", qa, qb)):
        nm, u, ref, band = spec(key, len(keep), extra + f": {v_ref:.4g} degree (at dt = {dt:g} s: {v:.4g} degree)")
        rows.append(run_check(lambda v=v, v_ref=v_ref: 100.0 * (v / v_ref - 1.0), nm, u, ref, "consistency", **band))
    return rows + bootstrap_rows(pa, pb, keep, dt, fine)


def bootstrap_rows(pa: dict, pb: dict, keep, dt: float, fine: float, why: str = "", n=None) -> list[Check]:
    """Two rows: the sampling interval of the step's effect on roll sigma and q0.999
    (:func:`paired_step_effect` over the records ``keep`` of the re-runs ``pa``, ``pb`` at dt and
    dt / REFINE), judged by :func:`bootstrap_checks`. With ``why`` (the re-runs failed) both rows are
    FAIL with that reason, over ``n`` records (default: ``len(keep)``)."""
    n = len(keep) if n is None else n
    try:
        if why:
            raise RuntimeError(why)
        eff = paired_step_effect(record_arrays([pa[int(r)] for r in keep]), record_arrays([pb[int(r)] for r in keep]))
    except Exception as exc:  # noqa: BLE001 - every row says why it could not run
        return bootstrap_checks(None, n, dt, fine, reason=why or f"{type(exc).__name__}: {exc}")
    return bootstrap_checks(eff, n, dt, fine)


def bootstrap_checks(eff: dict | None, n: int, dt: float, fine: float, reason: str = "") -> list[Check]:
    """The two bootstrap rows from :func:`paired_step_effect`'s ``eff`` over ``n`` records: PASS when
    the whole interval lies within the tolerance of the effect's own row (the step is shown adequate
    at the sample's resolution); FAIL when it reaches beyond, and the name says whether the interval
    holds 0 (the records cannot tell the step's effect from their sampling scatter) or not (a step
    effect). FAIL with the reason, value NaN, for ``eff`` None (``reason`` says why) and for fewer
    than ``BOOTSTRAP_MIN_RECORDS`` records (the interval stays in the name)."""
    pct = f"{100 * BOOTSTRAP_LEVEL:g} %"
    head = (f"step size: {{w}} at dt = {dt:g} s vs dt = {fine:g} s ({n} records): {pct} paired-bootstrap "
            "interval of the effect")
    ref = (f"the same records at dt / {REFINE} = {fine:g} s, resampled with replacement by record at both steps "
           f"({BOOTSTRAP_RESAMPLES} resamples, seed {BOOTSTRAP_SEED}, percentile interval, at least "
           f"{BOOTSTRAP_MIN_RECORDS} records); value: its largest |bound|, within the tolerance when the step is "
           "shown adequate at the sample's resolution")
    if eff is None:
        return [Check.failed(head.format(w=w), reason, "%", ref, "consistency", tolerance=tol)
                for w, tol in STEP_STATISTICS.values()]
    rows = []
    for key, (w, tol) in STEP_STATISTICS.items():
        d, lo, hi = eff[key]
        verdict = ("holds 0: the step's effect is within the sampling scatter of the records" if lo <= 0.0 <= hi
                   else "excludes 0: a step effect")
        name = head.format(w=w) + f" {d:+.2f} % in [{lo:+.2f}, {hi:+.2f}] % ({verdict})"
        if n < BOOTSTRAP_MIN_RECORDS:
            rows.append(Check.failed(name, f"{n} records, fewer than {BOOTSTRAP_MIN_RECORDS}: a percentile interval "
                                     "over so few records is too coarse to show the step adequate", "%", ref,
                                     "consistency", tolerance=tol))
        else:
            # NaN-propagating: a bound that is not finite makes the row FAIL (paired_step_effect refuses it first)
            rows.append(Check(name, float(np.max(np.abs([lo, hi]))), tol, "%", ref, kind="consistency"))
    return rows


# --------------------------------------------------------------------------------------------
# extremes and split-time


def extremes_checks(extremes: xr.Dataset | None) -> list[Check]:
    """Per target roll angle: coverage of the brute-force rate and median ratio estimate / brute force.

    Parameters
    ----------
    extremes : xarray.Dataset or None
        Dataset of ``stabflow.statistics.extremes.analyse``; ``None`` when the step does not run.

    Returns
    -------
    list of Check
        Two independent rows per target (coverage >= ``MIN_COVERAGE``, median ratio in
        ``RATIO_BAND``); FAIL with the reason where the brute force is zero in every sample or a
        value cannot be computed; two SKIPPED rows for ``None``.
    """
    lo, hi = RATIO_BAND
    cov_name = "extremes: coverage of the brute-force rate by the {pct} interval over {n} samples"
    rat_name = "extremes: median over the samples of estimate / brute-force rate"
    ref = "brute-force count of declustered |roll| maxima (capsizes included) in the rest of the ensemble"
    if extremes is None:
        why = "the extremes step does not run for this condition (not in extremes.conditions)"
        return [Check.not_applicable(cov_name.format(pct="95 %", n="N"), why, "-", ref),
                Check.not_applicable(rat_name, why, "-", ref)]
    try:
        targets = np.atleast_1d(extremes["target"].values).astype(float)
        nblk = int(extremes.sizes["block"])
        pct = _pct(extremes.attrs.get("interval", ""))
        hours = float(np.mean(extremes["bruteforce_hours"].values)) if "bruteforce_hours" in extremes else np.nan
    except Exception as exc:  # noqa: BLE001
        why = f"extremes dataset unreadable: {type(exc).__name__}: {exc}"
        return [Check.failed(cov_name.format(pct="95 %", n="N"), why, "-", ref, lower=MIN_COVERAGE),
                Check.failed(rat_name, why, "-", ref, lower=lo, upper=hi)]
    if np.isfinite(hours):
        ref = (f"brute-force count of declustered |roll| maxima (capsizes included) in the records outside each sample "
               f"({hours:.1f} h on average)")
    rows = []
    for x in targets:
        tag = f"extremes {x:g} deg: "
        cname = tag + cov_name.split(": ", 1)[1].format(pct=pct, n=nblk)
        rname = tag + rat_name.split(": ", 1)[1]

        def both_failed(why):
            return [Check.failed(cname, why, "-", ref, lower=MIN_COVERAGE),
                    Check.failed(rname, why, "-", ref, lower=lo, upper=hi)]

        try:
            sel = extremes.sel(target=x)
            bf = np.asarray(sel["rate_bruteforce"].values, float)
            est = np.asarray(sel["rate_estimate"].values, float)
            cov = float(sel["coverage"])
        except Exception as exc:  # noqa: BLE001
            rows += both_failed(f"{type(exc).__name__}: {exc}")
            continue
        if not np.any(bf > 0):
            rows += both_failed(f"the brute force counted no exceedance of {x:g} deg in any of the {nblk} samples: "
                                "no rate to compare with")
            continue
        if np.isfinite(cov):
            rows.append(Check(cname, cov, np.nan, "-", ref, lower=MIN_COVERAGE))
        else:
            rows.append(Check.failed(cname, "the coverage is NaN", "-", ref, lower=MIN_COVERAGE))
        ok = bf > 0
        ratio = np.where(ok, est / np.where(ok, bf, 1.0), np.nan)
        fin = np.isfinite(ratio)
        if fin.sum() < nblk:
            rname += f" (median over {fin.sum()} of {nblk} samples: brute force 0 or estimate NaN in the others)"
        if not fin.any():
            rows.append(Check.failed(rname, "estimate / brute force is NaN in every sample with a brute-force count",
                                     "-", ref, lower=lo, upper=hi))
        else:
            rows.append(Check(rname, float(np.median(ratio[fin])), np.nan, "-", ref, lower=lo, upper=hi))
        if "threshold_consistency" in extremes:
            sig = ", ".join(f"{v:g}" for v in extremes["threshold_sigma"].values)
            rows.append(Check(tag + f"share of samples whose estimates at the other thresholds ({sig} sigma) lie in "
                            "the reported interval", float(sel["threshold_consistency"]), np.nan, "-",
                            "the same samples at the other thresholds", kind="consistency", lower=MIN_COVERAGE))
    return rows


def splittime_checks(splittime: xr.Dataset | None) -> list[Check]:
    """Two independent rows per threshold of the split-time dataset ``splittime`` (the result of
    ``stabflow.statistics.splittime.analyse``, or ``None`` when the step does not run for this
    condition, which gives two SKIPPED rows): the brute-force rate inside the split-time interval
    (1 or 0, band [1, 1]) and split-time / brute-force rate in ``RATIO_BAND``. A brute force that
    counted no capsize, or a NaN value, gives FAIL rows with the reason.
    """
    lo, hi = RATIO_BAND
    in_name = "split-time: brute-force capsize rate inside the {pct} interval (1 yes, 0 no)"
    rat_name = "split-time: capsize rate / brute-force rate"
    ref = "brute force: capsized records among the other records of the ensemble"
    if splittime is None:
        why = "the split-time step does not run for this condition (not in splittime.conditions)"
        return [Check.not_applicable(in_name.format(pct="95 %"), why, "-", ref),
                Check.not_applicable(rat_name, why, "-", ref)]
    try:
        thresholds = np.atleast_1d(splittime["split_threshold"].values).astype(float)
        pct = _pct(splittime.attrs.get("interval", ""))
        k = int(splittime["bruteforce_capsizes"])
        bf = float(splittime["capsize_rate_bruteforce"])
        bf_h = float(splittime["bruteforce_hours"]) if "bruteforce_hours" in splittime else np.nan
        bf_lo, bf_hi = (float(splittime[v]) if v in splittime else np.nan
                        for v in ("capsize_rate_bruteforce_lower", "capsize_rate_bruteforce_upper"))
    except Exception as exc:  # noqa: BLE001
        why = f"split-time dataset unreadable: {type(exc).__name__}: {exc}"
        return [Check.failed(in_name.format(pct="95 %"), why, "-", ref, lower=1.0, upper=1.0),
                Check.failed(rat_name, why, "-", ref, lower=lo, upper=hi)]
    ref = (f"brute force: {k} capsized records in {bf_h:.1f} h of the other records, {bf:.3g} /h "
           f"(Garwood {pct} [{bf_lo:.3g}, {bf_hi:.3g}] /h)")
    rows = []
    for thr in thresholds:
        tag = f"split-time {thr:g} deg: "
        iname = tag + in_name.split(": ", 1)[1].format(pct=pct)
        rname = tag + rat_name.split(": ", 1)[1]
        def both_failed(why):
            return [Check.failed(iname, why, "-", ref, lower=1.0, upper=1.0),
                    Check.failed(rname, why, "-", ref, lower=lo, upper=hi)]

        if k == 0 or not bf > 0:
            rows += both_failed(f"the brute force counted no capsize in {bf_h:.1f} h of the other records: "
                                "no rate to compare with")
            continue
        try:
            s = splittime.sel(split_threshold=thr)
            lam = float(s["capsize_rate_splittime"])
            lam_lo, lam_hi = float(s["capsize_rate_lower"]), float(s["capsize_rate_upper"])
        except Exception as exc:  # noqa: BLE001
            rows += both_failed(f"{type(exc).__name__}: {exc}")
            continue
        iname += f" [{lam_lo:.3g}, {lam_hi:.3g}] /h"
        if np.isfinite(lam_lo) and np.isfinite(lam_hi):
            rows.append(Check(iname, float(lam_lo <= bf <= lam_hi), np.nan, "-", ref, lower=1.0, upper=1.0))
        else:
            rows.append(Check.failed(iname, "the split-time interval is NaN", "-", ref, lower=1.0, upper=1.0))
        rname += f" ({lam:.3g} /h vs {bf:.3g} /h)"
        if np.isfinite(lam):
            rows.append(Check(rname, lam / bf, np.nan, "-", ref, lower=lo, upper=hi))
        else:
            rows.append(Check.failed(rname, "the split-time capsize rate is NaN", "-", ref, lower=lo, upper=hi))
    if "reported" in splittime and "threshold_consistent" in splittime:
        rep = float(thresholds[np.argmax(splittime["reported"].values)])
        ok = splittime["threshold_consistent"].values.astype(bool)
        rows.append(Check(f"split-time: thresholds whose estimate lies in the reported {rep:g} deg interval "
                          f"({int(ok.sum())} of {len(ok)})", float(ok.mean()), np.nan, "-",
                          f"{splittime.attrs.get('threshold_rule', 'reported threshold')}", kind="consistency",
                          lower=1.0, upper=1.0))
    return rows


def ensemble_checks(model, ens: xr.Dataset, extremes: xr.Dataset | None = None,
                    splittime: xr.Dataset | None = None, threads: int = 1) -> list[Check]:
    """All irregular-sea validation rows of one condition.

    Parameters
    ----------
    model : stabflow.statistics.ensemble.Model
        ``build_model(ship, cond)`` of the condition.
    ens : xarray.Dataset
        The condition's merged ensemble (``results/ensemble/<ship>_<cond>/ensemble.nc``).
    extremes : xarray.Dataset, optional
        The extremes step's dataset (``stabflow.statistics.extremes.analyse``); ``None`` when that step does
        not run for the condition (its rows are SKIPPED with that reason).
    splittime : xarray.Dataset, optional
        The split-time step's dataset (``stabflow.statistics.splittime.analyse``); ``None`` likewise.
    threads : int
        Threads for the step-size re-simulation (:func:`step_checks`).

    Returns
    -------
    list of Check
        Seaway rows, regeneration and step-size rows, then extremes rows (two per target angle) and
        split-time rows (two per threshold); see the module docstring for references, tolerances and
        kinds. A row that cannot be computed is a FAIL row with the reason.
    """
    records = int(model.cond.get("validation_records", CONVERGENCE_RECORDS))
    return (seaway_checks(model) + step_checks(model, ens, records, threads) + extremes_checks(extremes)
            + splittime_checks(splittime))
