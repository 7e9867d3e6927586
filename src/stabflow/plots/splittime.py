"""Split-time method (paper 003): crossings, perturbations, metric tail, capsize rate."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.dynamics._kernels import S_ROLL
from stabflow.plots._style import atomic_savefig, plt


def splittime_figures(model, ds: xr.Dataset, paths: dict, title: str = ""):
    """Paper 003 Figs 3 and 4, the metric tail with its GPD, and capsize rate vs threshold."""
    from scipy import stats

    from stabflow.statistics.ensemble import simulate_record
    from stabflow.statistics.splittime import perturbed_histories

    thr0 = float(ds["split_threshold"][0])
    ev = ds.where(ds["crossing_threshold_deg"] == thr0, drop=True)
    # Fig. 3: crossings on the sample record with the most crossings
    recs, counts = np.unique(ev["crossing_record"].values.astype(int), return_counts=True)
    r = int(recs[np.argmax(counts)])
    states, last = simulate_record(model, r)
    t = np.arange(last + 1) * model.dt
    fig, ax = plt.subplots(figsize=(9, 3.6))
    ax.plot(t, np.degrees(states[: last + 1, S_ROLL]), lw=0.8)
    m = ev["crossing_record"].values.astype(int) == r
    ax.plot(ev["crossing_time"].values[m], thr0 * ev["crossing_side"].values[m], "ro", ms=4, label="crossings")
    for s in (1, -1):
        ax.axhline(s * thr0, color="r", lw=0.6, ls="--")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("roll [deg]")
    ax.set_title(f"Non-rare problem: crossings of ±{thr0:g}° in record {r}")
    ax.legend(loc="upper right")
    fig.tight_layout()
    atomic_savefig(fig, paths["crossings"], dpi=120)
    plt.close(fig)
    # Fig. 4: perturbed runs at the crossing with the largest finite metric below 1
    y = ev["metric"].values
    d = ev["critical_perturbation"].values
    ok = np.isfinite(d) & (d > 0)
    k = int(np.nonzero(ok)[0][np.argmax(y[ok])]) if ok.any() else 0
    rk, sk, tk = int(ev["crossing_record"].values[k]), int(ev["crossing_side"].values[k]), float(ev["crossing_time"].values[k])
    step = int(np.floor(tk / model.dt))  # the step before the crossing instant
    dc = float(d[k]) if np.isfinite(d[k]) else 10.0
    deltas = [0.25 * dc, 0.5 * dc, 0.9 * dc, dc, 1.5 * dc]
    tt, base, runs = perturbed_histories(model, rk, step, sk, deltas, int(ds.attrs["window_steps"]), thr0)
    fig, ax = plt.subplots(figsize=(8, 4))
    for dd, rr in zip(deltas, runs):
        ax.plot(tt, rr, lw=1, label=f"+{dd:.2f} deg/s" + (" (critical)" if dd == dc else ""))
    ax.plot(tt, base, "k--", lw=1.2, label="unperturbed")
    ax.axhline(90 * sk, color="r", lw=0.6)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("roll [deg]")
    ax.set_title(f"Motion perturbation at a {thr0:g}° crossing (record {rk}, t = {tk:.1f} s), y = {y[k]:.3f}")
    ax.legend(fontsize=8)
    fig.tight_layout()
    atomic_savefig(fig, paths["perturbation"], dpi=120)
    plt.close(fig)
    # metric tail and GPD per threshold
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, thr in enumerate(ds["split_threshold"].values):
        e = ds.where(ds["crossing_threshold_deg"] == thr, drop=True)
        # declustered metric is not stored per event; show the exceedance curve of all metrics
        yy = np.sort(e["metric"].values)[::-1]
        ax.semilogy(yy, np.arange(1, len(yy) + 1) / len(yy), ".", ms=3, color=f"C{i}", label=f"{thr:g}°: metrics")
        u, xi, sc = (float(ds[v].sel(split_threshold=thr)) for v in ("metric_threshold", "metric_gpd_shape", "metric_gpd_scale"))
        if np.isfinite(xi):
            frac = float(ds["metric_exceedances"].sel(split_threshold=thr)) / float(ds["clusters"].sel(split_threshold=thr))
            yg = np.linspace(u, 1.0, 100)
            ax.semilogy(yg, frac * stats.genpareto.sf(yg - u, xi, scale=sc), color=f"C{i}", lw=1,
                        label=f"{thr:g}°: GPD (clusters), P(y≥1) = {float(ds['capsize_probability'].sel(split_threshold=thr)):.2g}")
    ax.axvline(1.0, color="k", lw=0.6)
    ax.set_xlabel("metric y = φ̇_U / φ̇_Cr [-]")
    ax.set_ylabel("exceedance probability [-]")
    ax.set_ylim(1e-5, 1.2)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both")
    ax.set_title("Rare problem: metric tail")
    fig.tight_layout()
    atomic_savefig(fig, paths["metric"], dpi=120)
    plt.close(fig)
    # capsize rate vs threshold
    fig, ax = plt.subplots(figsize=(7, 4.2))
    th = ds["split_threshold"].values
    lam, lo, hi = (ds[v].values for v in ("capsize_rate_splittime", "capsize_rate_lower", "capsize_rate_upper"))
    ax.errorbar(th, np.maximum(lam, 1e-7), yerr=[np.maximum(lam, 1e-7) - np.maximum(lo, 1e-7), np.maximum(hi - lam, 0)],
                fmt="o", capsize=4, label=f"split-time ({float(ds['sample_hours']):.0f} h sample)")
    bf, bl, bh = (float(ds[v]) for v in ("capsize_rate_bruteforce", "capsize_rate_bruteforce_lower", "capsize_rate_bruteforce_upper"))
    ax.axhspan(bl, bh, color="0.85", label=f"brute force {int(ds['bruteforce_capsizes'])} capsizes / {float(ds['bruteforce_hours']):.0f} h")
    ax.axhline(bf, color="k", lw=1)
    ax.set_yscale("log")
    ax.set_xlabel("intermediate threshold [deg]")
    ax.set_ylabel("capsize rate [1/h]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    ax.set_title(title)
    fig.tight_layout()
    atomic_savefig(fig, paths["rate"], dpi=120)
    plt.close(fig)
