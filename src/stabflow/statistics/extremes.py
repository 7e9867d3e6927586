"""Extreme roll: peaks of |roll| over a threshold, Poisson-GPD fit, rates of roll beyond x.

The ensemble step stores, for every record, the peaks of roll and the troughs (local extremes of
roll beyond a floor), with their times, and whether and when the record capsized. This step works on
|roll| peaks, the roll process itself (the Hilbert-envelope peaks the ensemble also stores were the
basis before: they run above the roll peaks, and on the default condition their intervals covered the
brute-force rate of roll > 50 deg in 76 % of samples; they are no longer used):

1. Decorrelation time tau: the lag after which the envelope of the ensemble roll autocorrelation
   stays below 0.05 (paper 003, section 5; ``signals.decorrelation_time``).
2. Threshold u = ``threshold_sigma`` x the sample's own roll sigma (documented rule); the estimate is
   repeated at every one of ``threshold_sigmas`` to show the consistency across thresholds, and the
   first sample's threshold diagnostics (mean residual life, parameter stability; pyextremes) are
   drawn.
3. Declustering (``decluster``): runs within each record, window tau (same clusters as pyextremes'
   POT with r = tau, tested); a capsized record's last cluster is a right-censored maximum (roll
   beyond the capsize angle), its peaks within tau before the capsize join it.
4. Poisson-GPD maximum likelihood and profile-likelihood intervals (``statistics.tail``): rate of
   cluster maxima beyond x, lambda(x) = lambda_u S(x - u), with the Poisson count, the exceedance
   probability and both GPD parameters in the interval. The same interval with the shape fixed gives
   the share of the uncertainty due to the shape (the extrapolation).

Validation: the sample is a block of records (e.g. 100 h); the brute-force rate counts the clusters
with maxima beyond x (capsizes included) among all other records of the same ensemble (same
threshold and declustering). Repeating over independent blocks gives the coverage of the interval.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from stabflow.statistics.signals import decorrelation_time
from stabflow.io import annotate
from stabflow.statistics.tail import consistent_with, shape_share

EPOCH = pd.Timestamp("2000-01-01")


def timeline(record: np.ndarray, time: np.ndarray, duration: float, gap: float) -> pd.DatetimeIndex:
    """Map (record, time [s]) onto pyextremes' datetime axis (records separated by ``gap`` [s])."""
    sec = record.astype(float) * (duration + gap) + time
    return EPOCH + pd.to_timedelta(np.round(sec * 1000).astype(np.int64), unit="ms")


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


def record_maxima(rec, t, v, u: float, tau: float, cap_rec, cap_t):
    """Cluster maxima of |roll| peaks ``v`` above ``u`` (runs declustering, window ``tau`` [s], within
    records); records ``cap_rec`` capsized at ``cap_t``: the run of exceedances that ends at the
    capsize (each closer than tau to the next, the last closer than tau to the capsize) is the
    capsize's cluster, which is not among the returned maxima. Returns (maxima, records, times)."""
    rec, t, v = np.asarray(rec), np.asarray(t, float), np.asarray(v, float)
    keep = np.ones(len(v), bool)
    for r, tc in zip(np.asarray(cap_rec).tolist(), np.asarray(cap_t, float).tolist()):
        # walk back from the capsize along the run of exceedances closer than tau to each other
        idx = np.nonzero((rec == r) & (v > u) & (t <= tc))[0]
        idx = idx[np.argsort(t[idx])][::-1]
        edge = tc
        for i in idx:
            if edge - t[i] > tau:
                break
            keep[i] = False
            edge = t[i]
    return decluster(rec[keep], t[keep], v[keep], u, tau)


#: fewest exceedances for a GPD fit
MIN_EXCEEDANCES = 3
#: roll beyond this is a capsize (the ensemble's capsize angle) [deg]
CAPSIZE_DEG = 90.0


def block_estimates(data_rec, data_t, data_v, cap_rec, cap_t, recs, hours, u_list, targets, tau, alpha, report):
    """Rates at ``targets`` [deg] for each threshold of ``u_list`` from the block ``recs``: (rates,
    lowers, uppers, shapes, exceedances) each of shape (thresholds, targets), and the fixed-shape
    (lower, upper) at threshold index ``report`` (None: not computed, NaN). NaN where a target lies below the threshold or fewer
    than MIN_EXCEEDANCES exceed it."""
    from stabflow.statistics.tail import TailData, fit, rate_estimate

    inb = np.isin(data_rec, recs)
    cb = np.isin(cap_rec, recs)
    nu, nt = len(u_list), len(targets)
    R, LO, HI, XI = (np.full((nu, nt), np.nan) for _ in range(4))
    NU = np.zeros(nu, np.int64)
    fixed = np.full((2, nt), np.nan)
    for i, u in enumerate(u_list):
        mx, _, _ = record_maxima(data_rec[inb], data_t[inb], data_v[inb], u, tau, cap_rec[cb], cap_t[cb])
        data = TailData(mx, hours, right=np.full(int(cb.sum()), CAPSIZE_DEG))
        NU[i] = len(mx) + int(cb.sum())
        if NU[i] < MIN_EXCEEDANCES:
            continue
        f0 = fit(data, u)  # one fit per threshold, shared by the targets
        for j, x in enumerate(targets):
            if x < u:  # the tail model says nothing below its threshold: NaN, not the rate of u
                continue
            r = rate_estimate(data, u, x, alpha, fixed_shape=i == report, fitted=f0)
            R[i, j], LO[i, j], HI[i, j], XI[i, j] = r["rate"], r["lower"], r["upper"], r["xi"]
            fixed[:, j] = (r["lower_fixed"], r["upper_fixed"]) if i == report else fixed[:, j]
    return R, LO, HI, XI, NU, fixed


def block_sigma(ens: xr.Dataset, records: np.ndarray) -> float:
    """Roll standard deviation [degree] of a set of records, from the streamed sums."""
    sel = ens["moment_sums"].sel(record=records, dof="roll")
    from stabflow.statistics.ensemble import record_samples

    n = float(record_samples(ens).sel(record=records).sum())
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
    sigmas = sorted(set([float(x) for x in cfg["threshold_sigmas"]] + [float(cfg["threshold_sigma"])]))
    rep = sigmas.index(float(cfg["threshold_sigma"]))
    alpha = float(cfg["alpha"])
    pr, pt = ens["peak_record"].values, ens["peak_time"].values.astype(float)
    pv = np.abs(ens["peak_value"].values.astype(float))
    capd = ens["capsized"].values.astype(bool)
    cap_rec, cap_t = rec_all[capd], ens["capsize_time"].values[capd]
    rows = []
    extra = {}
    for b in tqdm(range(nblocks), desc="extremes blocks", disable=not progress):
        recs = rec_all[b * per_block: (b + 1) * per_block]
        hours = float(hours_rec[np.isin(rec_all, recs)].sum())
        sig = block_sigma(ens, recs)
        u_list = [k * sig for k in sigmas]
        R, LO, HI, XI, NU, fixed = block_estimates(pr, pt, pv, cap_rec, cap_t, recs, hours, u_list, targets, tau,
                                                   alpha, rep)
        # brute force: same threshold and declustering on every other record; capsizes beyond every target
        out = ~np.isin(pr, recs)
        oc = ~np.isin(cap_rec, recs)
        bmx, _, _ = record_maxima(pr[out], pt[out], pv[out], u_list[rep], tau, cap_rec[oc], cap_t[oc])
        bf_hours = float(hours_rec[~np.isin(rec_all, recs)].sum())
        bf = np.array([(bmx > x).sum() + oc.sum() for x in targets]) / bf_hours
        rows.append(dict(u=u_list[rep], u_all=np.array(u_list), sigma=sig, xi=next((v for v in XI[rep] if np.isfinite(v)), np.nan), n_u=NU[rep], hours=hours,
                         rate=R[rep], lo=LO[rep], hi=HI[rep], rate_all=R, lo_all=LO, hi_all=HI, fixed_lo=fixed[0],
                         fixed_hi=fixed[1], bf=bf, bf_hours=bf_hours, capsizes=int(np.isin(cap_rec, recs).sum())))
        if b == 0:
            from stabflow.statistics.tail import TailData, profile_interval

            u = u_list[rep]
            inb = np.isin(pr, recs)
            cb = np.isin(cap_rec, recs)
            mx, _, _ = record_maxima(pr[inb], pt[inb], pv[inb], u, tau, cap_rec[cb], cap_t[cb])
            xg = np.linspace(u, max(targets.max(), u) * 1.15, 40)
            curve = np.full((3, len(xg)), np.nan)
            if len(mx) + cb.sum() >= MIN_EXCEEDANCES:
                data = TailData(mx, hours, right=np.full(int(cb.sum()), CAPSIZE_DEG))
                for j, x in enumerate(xg):
                    r = profile_interval(data, u, x, alpha)
                    curve[:, j] = r.rate, r.lower, r.upper
            allmx, _, _ = record_maxima(pr, pt, pv, u, tau, cap_rec, cap_t)
            gap = 2 * tau + 60.0
            sample = pd.Series(pv[inb], index=timeline(pr[inb], pt[inb], duration, gap)).sort_index()
            extra = dict(x=xg, rate=curve[0], lo=curve[1], hi=curve[2],
                         bf_maxima=np.sort(np.concatenate([allmx, np.full(int(capd.sum()), CAPSIZE_DEG)])),
                         bf_hours_all=float(hours_rec.sum()), sample_series=sample[~sample.index.duplicated()], u=u,
                         tau=tau, hours=hours)
    R = {k: np.array([r[k] for r in rows]) for k in rows[0]}
    inside = (R["lo"] <= R["bf"]) & (R["bf"] <= R["hi"])
    # consistency: the other thresholds' estimates inside the reported threshold's interval
    ra = R["rate_all"]
    # (thresholds above a target have no estimate there and are left out)
    consistent = consistent_with(ra, R["lo"][:, None, :], R["hi"][:, None, :], axis=1) & np.isfinite(R["rate"])
    share = shape_share(R["lo"], R["hi"], R["fixed_lo"], R["fixed_hi"])
    ds = xr.Dataset(
        {
            "decorrelation_time": ((), tau),
            "threshold": ("block", R["u"]),
            "thresholds": (("block", "threshold_sigma"), R["u_all"]),
            "sample_roll_std": ("block", R["sigma"]),
            "gpd_shape": ("block", R["xi"]),
            "n_exceedances": ("block", R["n_u"]),
            "sample_hours": ("block", R["hours"]),
            "sample_capsizes": ("block", R["capsizes"]),
            "rate_estimate": (("block", "target"), R["rate"]),
            "rate_lower": (("block", "target"), R["lo"]),
            "rate_upper": (("block", "target"), R["hi"]),
            "rate_estimate_by_threshold": (("block", "threshold_sigma", "target"), ra),
            "rate_lower_by_threshold": (("block", "threshold_sigma", "target"), R["lo_all"]),
            "rate_upper_by_threshold": (("block", "threshold_sigma", "target"), R["hi_all"]),
            "rate_lower_fixed_shape": (("block", "target"), R["fixed_lo"]),
            "rate_upper_fixed_shape": (("block", "target"), R["fixed_hi"]),
            "extrapolation_share": (("block", "target"), share),
            "rate_bruteforce": (("block", "target"), R["bf"]),
            "bruteforce_hours": ("block", R["bf_hours"]),
            "inside": (("block", "target"), inside.astype(np.int8)),
            "coverage": ("target", inside.mean(axis=0)),
            "threshold_consistency": ("target", consistent.mean(axis=0)),
            "rate_ratio": (("block", "target"), np.where(R["bf"] > 0, R["rate"] / np.where(R["bf"] > 0, R["bf"], 1), np.nan)),
        },
        coords={"block": np.arange(nblocks), "target": targets, "threshold_sigma": sigmas},
    )
    ds.attrs.update(ship=ens.attrs["ship"], condition=ens.attrs["condition"],
                    peaks="|roll| peaks (maxima of roll and of -roll) stored by the ensemble; capsizes right-censored "
                          f"at {CAPSIZE_DEG:g} deg",
                    declustering="runs within each record, window = decorrelation time (stabflow.statistics.extremes.decluster, "
                                 "tested equal to pyextremes' POT declustering)",
                    fit="Poisson-GPD maximum likelihood, threshold at threshold_sigma x the sample's roll sigma "
                        "(stabflow.statistics.tail); pyextremes draws the threshold diagnostics",
                    interval=f"profile likelihood {100 * (1 - alpha):g} %",
                    threshold_sigma=float(cfg["threshold_sigma"]), records_per_block=per_block,
                    ensemble_hours=float(hours_rec.sum()))
    return annotate(ds), extra
