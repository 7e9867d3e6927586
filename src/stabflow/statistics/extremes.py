"""Extreme roll: Hilbert-envelope peaks over a threshold, GPD fit (pyextremes), rates of exceedance.

The ensemble step stores, for every record, the peaks of the roll envelope |phi + i H[phi]|
(Hilbert transform, ``ensemble.envelope``) above a floor, with their times. This step:

1. Decorrelation time tau: the lag after which the envelope of the ensemble roll autocorrelation
   stays below 0.05 (paper 003, section 5; ``signals.decorrelation_time``).
2. Time axis for pyextremes: records are independent, so they are *not* joined into one continuous
   series. Record r, time t maps to ``EPOCH + r (T_rec + gap) + t`` with a gap of 2 tau + 60 s
   between records: pyextremes' declustering window (r = tau) can never join peaks of two records,
   and rates are computed with the simulated exposure (records x T_rec), never the span of that
   artificial axis.
3. Peaks over the threshold u (``threshold_sigma`` x the sample's own roll sigma), declustered by
   pyextremes (``get_extremes('POT', r=tau)``: one maximum per cluster), generalized Pareto fit by
   maximum likelihood (``fit_model('MLE', 'genpareto')``, location fixed at u).
4. Rate of exceeding x: lambda(x) = (n_u / hours) * GPD survival(x - u). Confidence intervals by
   bootstrap over records (resample the sample's records with replacement, refit the GPD with the
   same maximum likelihood — scipy.stats.genpareto, which pyextremes wraps — and recount n_u):
   this carries both the Poisson count and the parameter uncertainty.

Validation: the sample is a block of records (e.g. 100 h); the brute-force rate is counted directly
from the cluster maxima of all other records of the same ensemble (same threshold, same
declustering). Repeating over independent blocks gives the coverage of the interval.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr
from scipy import stats

from stabflow.statistics.signals import decorrelation_time
from stabflow.io import annotate
from stabflow.statistics.intervals import record_bootstrap

EPOCH = pd.Timestamp("2000-01-01")


def timeline(record: np.ndarray, time: np.ndarray, duration: float, gap: float) -> pd.DatetimeIndex:
    """Map (record, time [s]) onto pyextremes' datetime axis (records separated by ``gap`` [s])."""
    sec = record.astype(float) * (duration + gap) + time
    return EPOCH + pd.to_timedelta(np.round(sec * 1000).astype(np.int64), unit="ms")


def record_of(index: pd.DatetimeIndex, duration: float, gap: float) -> np.ndarray:
    """Inverse of ``timeline`` for the record index."""
    sec = (index - EPOCH).total_seconds().to_numpy()
    return np.floor(sec / (duration + gap)).astype(np.int64)


def decluster(rec, t, v, u: float, tau: float):
    """Runs declustering of the exceedances of ``u``: within a record, exceedances closer than
    ``tau`` [s] to the previous one belong to the same cluster; clusters never span records. Returns
    the cluster maxima (values, records, times). Same clusters as pyextremes' POT with r = tau on the
    ``timeline`` axis (tested); vectorised so the brute-force count over millions of peaks is fast."""
    rec = np.asarray(rec)
    t = np.asarray(t, float)
    v = np.asarray(v, float)
    m = v > u
    rec, t, v = rec[m], t[m], v[m]
    order = np.lexsort((t, rec))
    rec, t, v = rec[order], t[order], v[order]
    if len(v) == 0:
        return v, rec, t
    new = np.ones(len(v), bool)
    new[1:] = (rec[1:] != rec[:-1]) | (np.diff(t) > tau)
    cid = np.cumsum(new) - 1
    # index of the maximum within each cluster (first one on ties)
    best = np.lexsort((-v, cid))
    first = np.ones(len(best), bool)
    first[1:] = cid[best][1:] != cid[best][:-1]
    k = best[first]
    return v[k], rec[k], t[k]


def pyextremes_fit(values, records, times, u: float, tau: float, duration: float):
    """GPD fit by pyextremes (MLE, location fixed at u) of declustered maxima placed on the
    ``timeline`` axis; returns the EVA object (``eva.model.fit_parameters``: c = xi, scale)."""
    from pyextremes import EVA

    gap = 2 * tau + 60.0
    idx = timeline(np.asarray(records), np.asarray(times), duration, gap)
    ex = pd.Series(np.asarray(values, float), index=idx).sort_index()
    eva = EVA(ex)
    eva.set_extremes(ex, method="POT", extremes_type="high", threshold=u, r=pd.Timedelta(seconds=tau))
    eva.fit_model("MLE", distribution="genpareto")
    return eva


#: fewest exceedances for a GPD fit
MIN_EXCEEDANCES = 3


def gpd_mle(excess: np.ndarray) -> tuple[float, float]:
    """(shape xi, scale sigma) of the GPD of ``excess`` (> 0), maximum likelihood, location 0.
    (NaN, NaN) when there are fewer than ``MIN_EXCEEDANCES`` or the optimiser fails."""
    if len(excess) < MIN_EXCEEDANCES:
        return np.nan, np.nan
    try:
        c, _, scale = stats.genpareto.fit(excess, floc=0.0)
    except (RuntimeError, ValueError, FloatingPointError):
        return np.nan, np.nan
    if not (np.isfinite(c) and np.isfinite(scale) and scale > 0):
        return np.nan, np.nan
    return float(c), float(scale)


def exceedance_rate(x, u, n_u, hours, xi, sigma):
    """lambda(x) = n_u / hours * P(X > x | X > u) [1/h] for x >= u (exact counts below the
    threshold are not modelled). NaN where the GPD could not be fitted (``xi`` NaN): a failed fit
    is never a rate of zero."""
    x = np.asarray(x, float)
    if not np.isfinite(xi):
        return np.full_like(x, np.nan)
    return n_u / hours * stats.genpareto.sf(np.maximum(x - u, 0.0), xi, scale=sigma)


def bootstrap_interval(boots: np.ndarray, alpha: float):
    """Percentile interval of bootstrap rates, rows = resamples. Resamples with too few exceedances
    to fit (-inf) rank below every fitted one (fewer exceedances, lower rates): when they reach the
    alpha/2 quantile the lower bound is undetermined (NaN). Fits that failed otherwise (NaN) are
    left out. Returns (lower, upper, resamples too few, resamples failed)."""
    few = np.isneginf(boots[:, 0])
    failed = np.isnan(boots[:, 0])
    ok = boots[~failed]
    if len(ok) == 0:
        n = boots.shape[1]
        return np.full(n, np.nan), np.full(n, np.nan), int(few.sum()), int(failed.sum())
    with np.errstate(invalid="ignore"):  # interpolating next to -inf: undetermined, made NaN below
        lo, hi = np.quantile(ok, [alpha / 2, 1 - alpha / 2], axis=0)
    lo = np.where(np.isfinite(lo), lo, np.nan)
    hi = np.where(np.isfinite(hi), hi, np.nan)
    return lo, hi, int(few.sum()), int(failed.sum())


def estimate(maxima, recs, block_records, u, hours, xs, n_boot: int, alpha: float, rng):
    """Rates at ``xs`` from one sample's cluster maxima, with bootstrap-over-records intervals.
    Returns (xi, sigma, n_u, rate, lo, hi, resamples with too few exceedances, failed fits)."""
    exc = maxima - u
    xi, sig = gpd_mle(exc)
    rate = exceedance_rate(xs, u, len(exc), hours, xi, sig)
    boots = np.empty((n_boot, len(xs)))
    for b, (_, e) in enumerate(record_bootstrap(rng, block_records, exc, recs, n_boot)):
        if len(e) < MIN_EXCEEDANCES:
            boots[b] = -np.inf
            continue
        bx, bs = gpd_mle(e)
        boots[b] = exceedance_rate(xs, u, len(e), hours, bx, bs)
    lo, hi, few, failed = bootstrap_interval(boots, alpha)
    return xi, sig, len(exc), rate, lo, hi, few, failed


def block_sigma(ens: xr.Dataset, records: np.ndarray) -> float:
    """Roll standard deviation [degree] of a set of records, from the streamed sums."""
    sel = ens["moment_sums"].sel(record=records, dof="roll")
    n = float((ens["steps"].sel(record=records) + 1).sum())
    m1 = float(sel.sel(order=1).sum()) / n
    return float(np.sqrt(float(sel.sel(order=2).sum()) / n - m1**2))


def analyse(ens: xr.Dataset, cfg: dict, progress: bool = False) -> tuple[xr.Dataset, dict]:
    """Extreme-roll estimates from sample blocks of ``cfg['sample_hours']`` against the brute-force
    rate of the rest of the ensemble. Returns the dataset and the objects the figures need."""
    from tqdm import tqdm

    duration = float(ens.attrs["duration"])
    tau = decorrelation_time(ens["roll_autocorrelation"])
    rec_all = ens["record"].values
    hours_rec = (ens["steps"].values + 0.0) * float(ens.attrs["dt"]) / 3600.0
    per_block = max(1, int(round(cfg["sample_hours"] * 3600.0 / duration)))
    nblocks = min(int(cfg["max_blocks"]), len(rec_all) // per_block)
    if nblocks < 1:
        raise ValueError(f"ensemble has {len(rec_all)} records, fewer than one sample of {per_block}")
    targets = np.asarray(cfg["targets_deg"], float)
    rng = np.random.default_rng(int(cfg["seed"]))
    er, et, ev = (ens[f"envelope_peak_{k}"].values for k in ("record", "time", "value"))
    rows = []
    extra = {}
    it = tqdm(range(nblocks), desc="extremes blocks", disable=not progress)
    for b in it:
        recs = rec_all[b * per_block: (b + 1) * per_block]
        inb = np.isin(er, recs)
        hours = float(hours_rec[np.isin(rec_all, recs)].sum())
        sig = block_sigma(ens, recs)
        u = cfg["threshold_sigma"] * sig
        mx, mr, mt = decluster(er[inb], et[inb], ev[inb], u, tau)
        # the first sample also gets its curve on a grid for the figure (same bootstrap resamples)
        xg = np.linspace(u, max(targets.max(), u) * 1.15, 60) if b == 0 else np.zeros(0)
        xi, sc, n_u, rate, lo, hi, few, failed = estimate(mx, mr, recs, u, hours, np.concatenate([targets, xg]),
                                                          int(cfg["n_boot"]), cfg["alpha"], rng)
        nt = len(targets)
        r_g, lo_g, hi_g = rate[nt:], lo[nt:], hi[nt:]
        rate, lo, hi = rate[:nt], lo[:nt], hi[:nt]
        if b == 0 and n_u >= MIN_EXCEEDANCES:
            # the reported fit of the first sample is pyextremes' own (the bootstrap refits use
            # scipy.stats.genpareto, the same maximum likelihood)
            eva = pyextremes_fit(mx, mr, mt, u, tau, duration)
            xi, sc = (float(eva.model.fit_parameters[k]) for k in ("c", "scale"))
            rate = exceedance_rate(targets, u, n_u, hours, xi, sc)
        # brute force: same threshold and declustering on every other record
        out = ~inb
        bmx, _, _ = decluster(er[out], et[out], ev[out], u, tau)
        bf_hours = float(hours_rec[~np.isin(rec_all, recs)].sum())
        bf = np.array([(bmx > x).sum() for x in targets]) / bf_hours
        rows.append(dict(u=u, sigma=sig, xi=xi, scale=sc, n_u=n_u, hours=hours, rate=rate, lo=lo, hi=hi, bf=bf,
                         bf_hours=bf_hours, few=few, failed=failed))
        if b == 0:
            allmx, _, _ = decluster(er, et, ev, u, tau)
            gap = 2 * tau + 60.0
            sample = pd.Series(ev[inb], index=timeline(er[inb], et[inb], duration, gap)).sort_index()
            extra = dict(x=xg, rate=r_g, lo=lo_g, hi=hi_g, bf_maxima=np.sort(allmx), bf_hours_all=float(hours_rec.sum()),
                         sample_series=sample[~sample.index.duplicated()], u=u, tau=tau, hours=hours)
    R = {k: np.array([r[k] for r in rows]) for k in rows[0]}
    inside = (R["lo"] <= R["bf"]) & (R["bf"] <= R["hi"])
    ds = xr.Dataset(
        {
            "decorrelation_time": ((), tau),
            "threshold": ("block", R["u"]),
            "sample_roll_std": ("block", R["sigma"]),
            "gpd_shape": ("block", R["xi"]),
            "gpd_scale": ("block", R["scale"]),
            "n_exceedances": ("block", R["n_u"]),
            "sample_hours": ("block", R["hours"]),
            "rate_estimate": (("block", "target"), R["rate"]),
            "rate_lower": (("block", "target"), R["lo"]),
            "rate_upper": (("block", "target"), R["hi"]),
            "rate_bruteforce": (("block", "target"), R["bf"]),
            "bruteforce_hours": ("block", R["bf_hours"]),
            "bootstrap_too_few": ("block", R["few"]),
            "bootstrap_failed": ("block", R["failed"]),
            "inside": (("block", "target"), inside.astype(np.int8)),
            "coverage": ("target", inside.mean(axis=0)),
            "rate_ratio": (("block", "target"), np.where(R["bf"] > 0, R["rate"] / np.where(R["bf"] > 0, R["bf"], 1), np.nan)),
        },
        coords={"block": np.arange(nblocks), "target": targets},
    )
    ds.attrs.update(ship=ens.attrs["ship"], condition=ens.attrs["condition"], envelope="Hilbert transform",
                    declustering="runs within each record, window = decorrelation time (stabflow.statistics.extremes.decluster, "
                                 "tested equal to pyextremes' POT declustering)",
                    fit="GPD maximum likelihood, location fixed at the threshold: pyextremes (MLE) for the first "
                        "sample's reported fit, scipy.stats.genpareto (the same likelihood) for the other samples "
                        "and every bootstrap refit",
                    interval=f"bootstrap over records, {int(cfg['n_boot'])} resamples, {100 * (1 - cfg['alpha']):g} %",
                    threshold_sigma=float(cfg["threshold_sigma"]), records_per_block=per_block,
                    ensemble_hours=float(hours_rec.sum()))
    return annotate(ds), extra
