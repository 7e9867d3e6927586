"""Extreme roll: threshold diagnostics, exceedance rate, validation against brute force."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


def threshold_diagnostics(series, tau: float, u: float, sigma: float, path, title: str = ""):
    """Mean residual life and GPD parameter stability (pyextremes) of the first sample's |roll|
    peaks, thresholds 1.5-5 sigma; the chosen threshold dashed."""
    from pyextremes import plot_mean_residual_life, plot_parameter_stability

    thr = np.linspace(1.5 * sigma, min(5.0 * sigma, float(series.max()) * 0.95), 25)
    fig = plt.figure(figsize=(11, 4.2))
    ax0 = fig.add_subplot(1, 3, 1)
    plot_mean_residual_life(series, thresholds=thr, ax=ax0)
    ax0.set_xlabel("threshold [deg]")
    ax0.set_ylabel("mean excess [deg]")
    ax1 = fig.add_subplot(1, 3, 2)
    ax2 = fig.add_subplot(1, 3, 3)
    plot_parameter_stability(series, thresholds=thr, r=f"{tau}s", alpha=None, axes=(ax1, ax2))
    ax1.set_title("")
    ax2.set_xlabel("threshold [deg]")
    ax2.set_ylabel("modified scale [deg]")
    ax1.set_ylabel("shape ξ [-]")
    for ax in (ax0, ax1, ax2):
        ax.axvline(u, color="k", ls="--", lw=0.8)
    fig.suptitle(title or "Threshold selection")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def exceedance_rate_curve(extra: dict, targets, path, title: str = ""):
    """GPD exceedance rate of the first sample with its bootstrap band, against the rate counted in
    the whole ensemble (same threshold and declustering)."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.fill_between(extra["x"], np.maximum(extra["lo"], 1e-9), np.maximum(extra["hi"], 1e-9), alpha=0.3,
                    label=f"95 % interval ({extra['hours']:.0f} h sample)")
    ax.semilogy(extra["x"], np.maximum(extra["rate"], 1e-9), label="GPD extrapolation")
    m = extra["bf_maxima"]
    xs = np.sort(m)[::-1]
    rate = np.arange(1, len(xs) + 1) / extra["bf_hours_all"]
    ax.semilogy(xs, rate, "k.", ms=2, label=f"counted, {extra['bf_hours_all']:.0f} h ensemble")
    for x in targets:
        ax.axvline(x, color="0.6", lw=0.6)
    ax.set_xlim(extra["u"], extra["x"][-1])
    ax.set_ylim(max(0.3 / extra["bf_hours_all"], 1e-6), None)
    ax.set_xlabel("|roll| cluster maximum x [deg]")
    ax.set_ylabel("rate of independent exceedances λ(x) [1/h]")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    ax.set_title(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def extremes_validation(ds: xr.Dataset, path, title: str = ""):
    """Per-sample estimates with intervals against the brute-force rate, one panel per target."""
    n = ds.sizes["target"]
    fig, axs = plt.subplots(1, n, figsize=(4 * n, 4), squeeze=False)
    b = ds["block"].values
    for ax, x in zip(axs[0], ds["target"].values):
        d = ds.sel(target=x)
        est, lo, hi = d["rate_estimate"].values, d["rate_lower"].values, d["rate_upper"].values
        ok = d["inside"].values.astype(bool)
        for sel, col in ((ok, "C0"), (~ok, "C3")):
            ax.errorbar(b[sel], est[sel], yerr=[est[sel] - lo[sel], hi[sel] - est[sel]], fmt="o", ms=3, color=col, lw=0.8)
        ax.plot(b, d["rate_bruteforce"].values, "k-", lw=1, label="brute force (other records)")
        ax.set_yscale("log")
        ax.set_xlabel("sample")
        ax.set_title(f"roll > {x:g}°: coverage {float(d['coverage']):.0%}")
        ax.grid(alpha=0.3, which="both")
    axs[0][0].set_ylabel("exceedance rate [1/h]")
    axs[0][0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
