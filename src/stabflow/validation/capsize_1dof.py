"""Analytic-grade capsize-rate validation (issue 16, item 1): a 1-DOF roll model with the box
barge's exact GZ (softening beyond deck-edge immersion) in narrow- and broad-band Gaussian
excitation, cheap enough to count capsizes by brute force over 10^5 - 10^6 simulated hours.

For each band and severity (excitation sigma):

1. Brute force: records of ``record_s`` counted seconds after a warm-up from rest, each from its own
   seed stream; rate = capsizes / counted hours, Garwood interval.
2. ``samples`` independent samples of ``sample_hours`` (other seeds). On each:

   * extremes: cluster maxima of |roll| (peaks of roll and troughs, runs-declustered with the
     decorrelation time), capsized records as right-censored maxima at the capsize angle; Poisson-GPD
     fit above the threshold leaving ``exceedances`` maxima above it; rate of maxima beyond the
     capsize angle = capsize rate, profile-likelihood interval (``statistics.tail``);
   * split-time (paper 003): up-crossings of +phi_thr and down-crossings of -phi_thr; the exact
     state at each crossing perturbed in roll rate and followed until capsize or return to the
     unperturbed solution; bisection on the critical perturbation (below the crossing's rate when
     the record capsizes); metric y = rate / (rate + delta) declustered per record, brackets that
     never capsize are left-censored (y below the value at the largest perturbation); Poisson-GPD fit of the metric above its ``metric_quantile``; capsize
     rate = cluster rate x P(y >= 1) with the profile-likelihood interval.

3. Coverage (share of samples whose interval holds the brute-force rate) and median ratio
   estimate / brute force per band, severity and method.

Thresholds (documented rule): extremes use the thresholds leaving ``exceedances`` maxima above
them (``report`` is the reported one, the others show the consistency); split-time uses
``threshold_sigmas`` x the sample's own roll sigma and reports the highest whose sample holds at
least ``min_clusters`` declustered crossings, showing the others.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.dynamics.one_dof import OneDof, critical_perturbation, record_seeds, restoring_table
from stabflow.io import annotate
from stabflow.statistics.extremes import record_maxima
from stabflow.statistics.signals import crossings, decorrelation_time, local_peaks
from stabflow.statistics.splittime import crossing_metric, decluster_metric, metric_rate, poisson_interval
from stabflow.statistics.tail import TailData, consistent_with, rate_estimate, shape_share

#: seed streams: brute force and samples never share a record seed
BRUTE_STREAM, SAMPLE_STREAM = 0, 1


def box_model(cfg: dict, band: dict, sigma: float) -> OneDof:
    """The 1-DOF model of ``cfg`` (hull, damping, time step) for one band and excitation sigma [rad].

    GM = KB + BM - KG of the box at its draft (KB = T / 2, BM = B^2 / (12 T)); w0 = sqrt(g GM) / k
    with k the roll radius of gyration (added inertia included); GZ the exact box GZ by polygon
    clipping (``validation.references.exact_box_gz``)."""
    from stabflow.validation.references import exact_box_gz

    h = cfg["hull"]
    L, B, D, T, KG = (float(h[k]) for k in ("length", "breadth", "depth", "draft", "kg"))
    gm = T / 2 + B**2 / (12 * T) - KG
    if gm <= 0:
        raise ValueError(f"capsize_1dof.hull: GM = {gm:.3f} m <= 0")
    tab, dphi = restoring_table(lambda a: exact_box_gz(L, B, D, L * B * T, KG, a), gm, 90.0, 0.1)
    neg = np.nonzero(tab[1:] <= 0)[0]
    if not len(neg):
        raise ValueError("capsize_1dof.hull: GZ has no angle of vanishing stability below 90 deg")
    # angle of vanishing stability by linear interpolation of the table
    i = neg[0]
    avs = dphi * (i + tab[i] / (tab[i] - tab[i + 1]))
    w0 = np.sqrt(G * gm) / float(cfg["gyradius"])
    T0 = 2 * np.pi / w0
    return OneDof(w0=w0, zeta=float(cfg["damping_ratio"]), restoring=tab, dphi=dphi, cap=avs, wf=w0 * float(band["filter_frequency_ratio"]),
                  zf=float(band["filter_damping"]), sigma=float(sigma), dt=T0 / float(cfg["steps_per_period"]),
                  warmup=float(cfg["warmup_s"]), duration=float(cfg["record_s"]))


def counted(model: OneDof, last: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(counted hours, capsized after the warm-up) per record; records that capsize in the warm-up
    count no hours and no capsize (the brute force and the samples alike)."""
    last = np.asarray(last)
    hours = np.clip(np.minimum(last, model.nsteps) - model.nwarm, 0, None) * model.dt / 3600.0
    return hours, (last < model.nsteps) & (last > model.nwarm)


def bruteforce(model: OneDof, hours: float, seed: int, threads: int = 1, progress: bool = False):
    """Brute-force capsize rate over about ``hours`` counted hours: (rate, lower, upper [1/h],
    capsizes, hours, records lost in the warm-up)."""
    n = int(np.ceil(hours * 3600.0 / model.duration))
    last = model.bruteforce(record_seeds(seed, BRUTE_STREAM, range(n)), threads, progress)
    h, cap = counted(model, last)
    r, lo, hi = poisson_interval(int(cap.sum()), float(h.sum()))
    return r, lo, hi, int(cap.sum()), float(h.sum()), int(np.sum(last <= model.nwarm))


def roll_autocorrelation(model: OneDof, seeds, maxlag_s: float) -> xr.DataArray:
    """Ensemble roll autocorrelation of counted, non-capsized records (FFT, biased estimator)."""
    nlag = int(maxlag_s / model.dt) + 1
    acc = np.zeros(nlag)
    for s in seeds:
        st, last = model.record(int(s))
        if last < model.nsteps:
            continue
        x = st[model.nwarm:, 0] - st[model.nwarm:, 0].mean()
        f = np.fft.rfft(x, 2 * len(x))
        acc += np.fft.irfft(f * np.conj(f))[:nlag] / len(x)
    return xr.DataArray(acc / acc[0], dims="lag", coords={"lag": np.arange(nlag) * model.dt})


@dataclass
class SampleEvents:
    """Per-sample events: cluster maxima of |roll| and the split-time metric per threshold."""

    hours: float
    maxima: np.ndarray            # exact cluster maxima of |roll| [deg]
    capsizes: int                 # right-censored maxima (capsized records)
    metric: dict                  # threshold [roll sigma] -> (declustered y, kind, crossings, runs, undecided runs)
    roll_std: float               # the sample's roll standard deviation [deg]


def sample_events(model: OneDof, seeds, tau: float, sigmas, st_cfg: dict, peak_floor_deg: float) -> SampleEvents:
    """Simulate one sample's records and collect its extremes and split-time events; the split-time
    thresholds are ``sigmas`` x the sample's own roll standard deviation."""
    cap_deg = np.degrees(model.cap)
    dmax = np.radians(float(st_cfg["max_perturbation_deg_s"]))
    tol = np.radians(float(st_cfg["tolerance_deg_s"]))
    follow = int(round(float(st_cfg["follow_periods"]) * 2 * np.pi / model.w0 / model.dt))
    ret = float(st_cfg["return_fraction"])
    runs_ = []
    s1 = s2 = n = 0.0
    for s in seeds:
        exc = model.excitation(int(s))
        st, last = model.record(int(s), exc)
        h, capsized = counted(model, [last])
        if h[0] <= 0:
            continue
        x = np.degrees(st[model.nwarm:min(last, model.nsteps) + 1, 0])
        s1, s2, n = s1 + x.sum(), s2 + (x * x).sum(), n + len(x)
        runs_.append((exc, st, last, float(h[0]), bool(capsized[0])))
    roll_std = float(np.sqrt(max(s2 / n - (s1 / n) ** 2, 0.0))) if n else np.nan
    hours_all, maxima, caps = 0.0, [], 0
    acc = {f: dict(rec=[], t=[], rate=[], delta=[], runs=0, und=0) for f in sigmas}
    for r, (exc, st, last, h, capsized) in enumerate(runs_):
        hours_all += h
        n0 = model.nwarm
        end = min(last, model.nsteps)
        t = np.arange(n0, end + 1) * model.dt
        roll = np.degrees(st[n0:end + 1, 0])
        rate = np.degrees(st[n0:end + 1, 1])
        # |roll| peaks: maxima of roll and of -roll
        tp, vp = local_peaks(t, roll, peak_floor_deg)
        tm, vm = local_peaks(t, -roll, peak_floor_deg)
        pt, pv = np.concatenate([tp, tm]), np.concatenate([vp, vm])
        caps += capsized
        mx, _, _ = record_maxima(np.zeros(len(pv), int), pt, pv, 0.0, tau, [0] if capsized else [], [t[-1]])
        maxima.append(mx)
        for f in sigmas:
            thr = min(f * roll_std, 0.99 * cap_deg)
            ev = []
            for side in (1, -1):
                tc, _, idx = crossings(t, roll, rate, side * thr, up=side > 0)
                ev += [(float(a), int(b) + n0, side) for a, b in zip(tc, idx)]
            ev.sort()
            steps_all = [e[1] for e in ev] + [np.iinfo(np.int64).max // 2]
            a = acc[f]
            for j, (_, k, side) in enumerate(ev):
                d, runs, tc2, vc, und = critical_perturbation(model, exc, st, last, k, np.radians(side * thr), side,
                                                              int(steps_all[j + 1]), dmax, tol, ret, follow)
                a["runs"] += runs
                a["und"] += und
                a["rec"].append(r)
                a["t"].append(tc2)
                a["rate"].append(abs(vc))
                a["delta"].append(d)
    metric = {}
    for f, a in acc.items():
        y, kind = crossing_metric(np.array(a["rate"]), np.array(a["delta"], float), dmax)
        yc, kc, _, _ = decluster_metric(np.array(a["rec"], np.int64), np.array(a["t"]), y, kind, tau)
        metric[f] = (yc, kc, len(a["rec"]), a["runs"], a["und"])
    return SampleEvents(hours_all, np.concatenate(maxima) if maxima else np.zeros(0), caps, metric, roll_std)


def threshold_with(values: np.ndarray, k: int) -> float:
    """Threshold leaving the ``k`` largest ``values`` above it (midway to the next one)."""
    v = np.sort(values)[::-1]
    if len(v) <= k:
        return float(v[-1]) * 0.999 if len(v) else np.nan
    return float(0.5 * (v[k - 1] + v[k]))


def extremes_estimate(ev: SampleEvents, x_deg: float, k: int, alpha: float, fixed_shape: bool = True):
    """Capsize rate from the |roll| cluster maxima (right-censored capsizes) above the threshold with
    ``k`` exceedances: (rate, lower, upper, lower/upper with the shape fixed, xi, u)."""
    allv = np.concatenate([ev.maxima, np.full(ev.capsizes, x_deg)])
    u = threshold_with(allv, k)
    data = TailData(ev.maxima, ev.hours, right=np.full(ev.capsizes, x_deg))
    r = rate_estimate(data, u, x_deg, alpha, fixed_shape)
    return r["rate"], r["lower"], r["upper"], r["lower_fixed"], r["upper_fixed"], r["xi"], u


def reported_threshold(clusters: dict, sigmas, min_clusters: int) -> float:
    """Documented rule: the highest threshold whose sample holds at least ``min_clusters`` declustered
    crossings (the lowest when none does)."""
    ok = [f for f in sigmas if clusters[f] >= min_clusters]
    return max(ok) if ok else min(sigmas)


def analyse_sample(model: OneDof, seeds, tau: float, cfg: dict) -> dict:
    """Extremes and split-time estimates (with intervals) of one sample."""
    ex, st = cfg["extremes"], cfg["splittime"]
    alpha = float(cfg["alpha"])
    sigmas = [float(f) for f in st["threshold_sigmas"]]
    ev = sample_events(model, seeds, tau, sigmas, st, float(cfg["peak_floor_deg"]))
    cap_deg = float(np.degrees(model.cap))
    out = dict(hours=ev.hours, capsizes=ev.capsizes, maxima=len(ev.maxima), sample_roll_std=ev.roll_std)
    ks = [int(k) for k in ex["exceedances"]]
    kr = int(ex["report"])
    e = {k: extremes_estimate(ev, cap_deg, k, alpha, fixed_shape=k == kr) for k in ks}
    out["ext"] = np.array([e[k][:3] for k in ks])
    out["ext_xi"] = np.array([e[k][5] for k in ks])
    out["ext_u"] = np.array([e[k][6] for k in ks])
    out["ext_fixed"] = np.array(e[kr][3:5])
    q = float(st["metric_quantile"])
    clusters = {f: len(ev.metric[f][0]) for f in sigmas}
    fr = reported_threshold(clusters, sigmas, int(st["min_clusters"]))
    s = {}
    for f in sigmas:
        m = metric_rate(ev.metric[f][0], ev.metric[f][1], ev.hours, q, alpha, fixed_shape=f == fr)
        s[f] = (m["rate"], m["lower"], m["upper"], m["lower_fixed"], m["upper_fixed"], m["xi"], m["u"])
    out["st"] = np.array([s[f][:3] for f in sigmas])
    out["st_xi"] = np.array([s[f][5] for f in sigmas])
    out["st_fixed"] = np.array(s[fr][3:5])
    out["st_report"] = sigmas.index(fr)
    out["st_clusters"] = np.array([clusters[f] for f in sigmas])
    out["st_crossings"] = np.array([ev.metric[f][2] for f in sigmas])
    out["st_runs"] = np.array([ev.metric[f][3] for f in sigmas])
    out["st_undecided"] = np.array([ev.metric[f][4] for f in sigmas])
    out["st_capsizing"] = np.array([int(np.sum(ev.metric[f][0] >= 1.0)) for f in sigmas])
    return out


def _sample_job(args):
    model, seeds, tau, cfg = args
    return analyse_sample(model, seeds, tau, cfg)


def cases(cfg: dict) -> list[tuple[str, dict, float, float]]:
    """(name, band, sigma [rad], brute-force hours) of every band and severity."""
    out = []
    for band in cfg["bands"]:
        for i, (sd, h) in enumerate(zip(band["sigma_deg"], band["bruteforce_hours"])):
            out.append((f"{band['name']}_{i + 1}", band, float(np.radians(sd)), float(h)))
    return out


def analyse(cfg: dict, threads: int = 1, progress: bool = False) -> xr.Dataset:
    """Run every case of the ``capsize_1dof`` config: brute force, samples, estimates, coverage."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    from tqdm import tqdm

    seed = int(cfg["seed"])
    nsamp = int(cfg["samples"])
    ks = [int(k) for k in cfg["extremes"]["exceedances"]]
    sigmas = [float(f) for f in cfg["splittime"]["threshold_sigmas"]]
    C = cases(cfg)
    per_case, samples = [], []
    for ci, (name, band, sigma, bf_hours) in enumerate(C):
        model = box_model(cfg, band, sigma)
        bf = bruteforce(model, bf_hours, seed + 7919 * ci, threads, progress)
        nrec = max(1, int(round(float(cfg["sample_hours"]) * 3600.0 / model.duration)))
        # decorrelation time from records that are in no sample (stream 2)
        tau = decorrelation_time(roll_autocorrelation(model, record_seeds(seed + 7919 * ci, 2, range(20)), 600.0))
        jobs = [(model, record_seeds(seed + 7919 * ci, SAMPLE_STREAM, range(j * nrec, (j + 1) * nrec)), tau, cfg)
                for j in range(nsamp)]
        with ProcessPoolExecutor(max_workers=max(1, threads), mp_context=mp.get_context("fork")) as ex:
            res = list(tqdm(ex.map(_sample_job, jobs), total=nsamp, desc=f"1-DOF {name} samples", disable=not progress,
                            mininterval=10))
        st, _ = model.record(int(record_seeds(seed + 7919 * ci, 2, [0])[0]))
        per_case.append(dict(name=name, band=band["name"], sigma=np.degrees(sigma), bf=bf, tau=tau,
                             avs=np.degrees(model.cap), period=2 * np.pi / model.w0, dt=model.dt,
                             roll_std=float(np.degrees(np.nanstd(st[model.nwarm:, 0])))))
        samples.append(res)
    return _dataset(cfg, per_case, samples, ks, sigmas)


def _dataset(cfg, per_case, samples, ks, sigmas) -> xr.Dataset:
    def S(key):
        return np.array([[r[key] for r in res] for res in samples])

    bf = np.array([c["bf"] for c in per_case], float)
    ext, st = S("ext"), S("st")          # (case, sample, k|fraction, 3)
    rep_k = ks.index(int(cfg["extremes"]["report"]))
    rep_f = S("st_report")               # (case, sample)
    st_rep = np.take_along_axis(st, rep_f[:, :, None, None], axis=2)[:, :, 0]
    ds = xr.Dataset(
        {
            "band": ("case", [c["band"] for c in per_case]),
            "excitation_std": ("case", [c["sigma"] for c in per_case]),
            "roll_std": ("case", [c["roll_std"] for c in per_case]),
            "vanishing_angle": ((), per_case[0]["avs"]),
            "roll_period": ((), per_case[0]["period"]),
            "time_step": ((), per_case[0]["dt"]),
            "decorrelation_time": ("case", [c["tau"] for c in per_case]),
            "capsize_rate_bruteforce": ("case", bf[:, 0]),
            "capsize_rate_bruteforce_lower": ("case", bf[:, 1]),
            "capsize_rate_bruteforce_upper": ("case", bf[:, 2]),
            "bruteforce_capsizes": ("case", bf[:, 3].astype(np.int64)),
            "bruteforce_hours": ("case", bf[:, 4]),
            "bruteforce_warmup_capsizes": ("case", bf[:, 5].astype(np.int64)),
            "sample_hours": (("case", "sample"), S("hours")),
            "sample_capsizes": (("case", "sample"), S("capsizes")),
            "sample_roll_std": (("case", "sample"), S("sample_roll_std")),
            "extremes_rate": (("case", "sample", "exceedances"), ext[..., 0]),
            "extremes_rate_lower": (("case", "sample", "exceedances"), ext[..., 1]),
            "extremes_rate_upper": (("case", "sample", "exceedances"), ext[..., 2]),
            "extremes_gpd_shape": (("case", "sample", "exceedances"), S("ext_xi")),
            "extremes_threshold": (("case", "sample", "exceedances"), S("ext_u")),
            "extremes_rate_lower_fixed_shape": (("case", "sample"), S("ext_fixed")[..., 0]),
            "extremes_rate_upper_fixed_shape": (("case", "sample"), S("ext_fixed")[..., 1]),
            "splittime_rate": (("case", "sample", "threshold_sigma"), st[..., 0]),
            "splittime_rate_lower": (("case", "sample", "threshold_sigma"), st[..., 1]),
            "splittime_rate_upper": (("case", "sample", "threshold_sigma"), st[..., 2]),
            "splittime_gpd_shape": (("case", "sample", "threshold_sigma"), S("st_xi")),
            "splittime_clusters": (("case", "sample", "threshold_sigma"), S("st_clusters")),
            "splittime_crossings": (("case", "sample", "threshold_sigma"), S("st_crossings")),
            "splittime_capsizing_clusters": (("case", "sample", "threshold_sigma"), S("st_capsizing")),
            "perturbed_runs": (("case", "sample", "threshold_sigma"), S("st_runs")),
            "undecided_runs": (("case", "sample", "threshold_sigma"), S("st_undecided")),
            "splittime_reported_threshold_sigma": (("case", "sample"), np.array(sigmas)[rep_f]),
            "splittime_rate_lower_fixed_shape": (("case", "sample"), S("st_fixed")[..., 0]),
            "splittime_rate_upper_fixed_shape": (("case", "sample"), S("st_fixed")[..., 1]),
        },
        coords={"case": [c["name"] for c in per_case], "sample": np.arange(ext.shape[1]),
                "exceedances": ks, "threshold_sigma": sigmas},
    )
    for method, est in (("extremes", ext[:, :, rep_k]), ("splittime", st_rep)):
        truth = bf[:, 0][:, None]
        inside = (est[..., 1] <= truth) & (truth <= est[..., 2])
        ds[f"{method}_inside"] = (("case", "sample"), inside.astype(np.int8))
        ds[f"{method}_coverage"] = ("case", inside.mean(axis=1))
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = est[..., 0] / truth
        ds[f"{method}_median_ratio"] = ("case", np.nanmedian(np.where(np.isfinite(ratio), ratio, np.nan), axis=1))
        lo_f = ds[f"{method}_rate_lower_fixed_shape"].values
        hi_f = ds[f"{method}_rate_upper_fixed_shape"].values
        ds[f"{method}_extrapolation_share"] = (("case", "sample"), shape_share(est[..., 1], est[..., 2], lo_f, hi_f))
    # consistency across thresholds: every threshold's estimate inside the reported threshold's interval
    # (thresholds without an estimate are left out, as in the extremes step; the reported one must have one)
    ext_ok = (consistent_with(ext[..., 0], ext[:, :, rep_k:rep_k + 1, 1], ext[:, :, rep_k:rep_k + 1, 2], axis=2)
              & np.isfinite(ext[:, :, rep_k, 0]))
    st_ok = consistent_with(st[..., 0], st_rep[:, :, None, 1], st_rep[:, :, None, 2], axis=2) & np.isfinite(st_rep[..., 0])
    ds["extremes_threshold_consistency"] = ("case", ext_ok.mean(axis=1))
    ds["splittime_threshold_consistency"] = ("case", st_ok.mean(axis=1))
    ds.attrs.update(
        model="1-DOF roll, box barge exact GZ, linear damping, second-order filtered Gaussian excitation "
              "(stabflow.dynamics.one_dof)",
        hull=str(dict(cfg["hull"])), gyradius=float(cfg["gyradius"]), damping_ratio=float(cfg["damping_ratio"]),
        extremes="|roll| cluster maxima (runs declustering, decorrelation time), capsizes right-censored at the "
                 "angle of vanishing stability; Poisson-GPD maximum likelihood (stabflow.statistics.tail) above the "
                 f"threshold leaving {cfg['extremes']['report']} maxima (reported; others for consistency)",
        splittime="paper 003 motion perturbation: exact crossing state, run until capsize or return "
                  f"(distance below {cfg['splittime']['return_fraction']} of the perturbation, at most "
                  f"{cfg['splittime']['follow_periods']} periods), critical rate below the crossing's when the "
                  "record capsizes (metric > 1); Poisson-GPD of the declustered metric above its "
                  f"{cfg['splittime']['metric_quantile']} quantile, never-capsizing brackets left-censored; "
                  "thresholds at multiples of the sample's roll sigma, reported: the highest with at least "
                  f"{cfg['splittime']['min_clusters']} clusters in the sample",
        interval=f"profile likelihood {100 * (1 - float(cfg['alpha'])):g} % (counts, exceedance probability, "
                 "GPD scale and shape)",
        bruteforce="records from rest, counted after the warm-up; Garwood interval", seed=int(cfg["seed"]),
        sample_hours=float(cfg["sample_hours"]), samples=int(cfg["samples"]),
        extremes_reported_exceedances=int(cfg["extremes"]["report"]))
    return annotate(ds)


#: fewest brute-force capsizes for a reference rate (Garwood interval within about a factor 2)
MIN_BRUTEFORCE = 10


def capsize_1dof_checks(ds: xr.Dataset) -> list:
    """Validation rows per case: for extremes and split-time, coverage of the brute-force rate by the
    samples' intervals (>= MIN_COVERAGE) and the median ratio estimate / brute force (in RATIO_BAND);
    the consistency of the estimates across thresholds (share of samples whose other thresholds'
    estimates lie in the reported interval, >= MIN_COVERAGE); a brute-force count of at least
    MIN_BRUTEFORCE capsizes. FAIL rows name the reason; nothing is dropped."""
    from stabflow.validation import Check
    from stabflow.validation.ensemble import MIN_COVERAGE, RATIO_BAND

    rows = []
    lo, hi = RATIO_BAND
    for case in ds["case"].values:
        c = ds.sel(case=case)
        k, h, bf = int(c["bruteforce_capsizes"]), float(c["bruteforce_hours"]), float(c["capsize_rate_bruteforce"])
        ref = (f"brute force: {k} capsizes in {h:.3g} h = {bf:.3g} /h (Garwood 95 % "
               f"[{float(c['capsize_rate_bruteforce_lower']):.3g}, {float(c['capsize_rate_bruteforce_upper']):.3g}])")
        tag = f"1-DOF {case} (excitation {float(c['excitation_std']):.3g} deg): "
        rows.append(Check(tag + "brute-force capsizes", k, np.nan, "-", f"{h:.3g} h of independent records",
                          lower=MIN_BRUTEFORCE))
        n = int(ds.sizes["sample"])
        for method, title in (("splittime", "split-time"), ("extremes", "extremes (|roll| maxima)")):
            cov = float(c[f"{method}_coverage"])
            med = float(c[f"{method}_median_ratio"])
            cname = tag + f"{title}: share of {n} samples whose 95 % interval holds the brute-force rate"
            rname = tag + f"{title}: median estimate / brute force over {n} samples"
            if k == 0:
                why = "the brute force counted no capsize: no rate to compare with"
                rows += [Check.failed(cname, why, "-", ref, lower=MIN_COVERAGE),
                         Check.failed(rname, why, "-", ref, lower=lo, upper=hi)]
                continue
            rows.append(Check(cname, cov, np.nan, "-", ref, lower=MIN_COVERAGE) if np.isfinite(cov) else
                        Check.failed(cname, "coverage is NaN", "-", ref, lower=MIN_COVERAGE))
            rows.append(Check(rname, med, np.nan, "-", ref, lower=lo, upper=hi) if np.isfinite(med) else
                        Check.failed(rname, "no sample gave an estimate (too few exceedances above every threshold)",
                                     "-", ref, lower=lo, upper=hi))
            share = float(c[f"{method}_threshold_consistency"])
            sname = tag + f"{title}: share of samples whose other thresholds' estimates lie in the reported interval"
            rows.append(Check(sname, share, np.nan, "-", "the same sample at the other configured thresholds",
                              kind="consistency", lower=MIN_COVERAGE))
    return rows
