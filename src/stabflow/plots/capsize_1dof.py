"""Figure of the 1-DOF capsize-rate validation: every sample's estimate and interval against brute force."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


def capsize_1dof_figure(ds: xr.Dataset, path) -> None:
    """One panel per case: split-time and extremes estimates (dots) with their intervals (bars) per
    sample, the brute-force rate and its interval (band); zeros drawn at the panel's floor."""
    cases = list(ds["case"].values)
    fig, axes = plt.subplots(len(cases), 1, figsize=(9, 2.4 * len(cases)), squeeze=False)
    for ax, case in zip(axes[:, 0], cases):
        c = ds.sel(case=case)
        bf = float(c["capsize_rate_bruteforce"])
        floor = max(bf, 1e-9) * 1e-3
        ax.axhspan(float(c["capsize_rate_bruteforce_lower"]), float(c["capsize_rate_bruteforce_upper"]),
                   color="0.85", label="brute force 95 %")
        ax.axhline(bf, color="k", lw=1, label=f"brute force {bf:.2g} /h")
        rep_k = list(ds["exceedances"].values).index(int(ds.attrs["extremes_reported_exceedances"]))
        sets = [("split-time", c["splittime_rate"].values, c["splittime_rate_lower"].values,
                 c["splittime_rate_upper"].values, c["splittime_reported_threshold_sigma"].values, "C0", -0.15),
                ("extremes", c["extremes_rate"].values[:, rep_k], c["extremes_rate_lower"].values[:, rep_k],
                 c["extremes_rate_upper"].values[:, rep_k], None, "C3", 0.15)]
        x = np.arange(ds.sizes["sample"])
        for name, r, lo, hi, frac, col, off in sets:
            if frac is not None:
                j = np.array([list(ds["threshold_sigma"].values).index(f) for f in frac])
                r, lo, hi = (np.take_along_axis(a, j[:, None], axis=1)[:, 0] for a in (r, lo, hi))
            rr = np.where(r > floor, r, floor)
            ax.errorbar(x + off, rr, yerr=[rr - np.maximum(lo, floor), np.maximum(hi, floor) - rr], fmt="o", ms=3,
                        color=col, lw=0.8, label=name)
        ax.set_yscale("log")
        ax.set_ylim(floor * 0.5, None)
        ax.set_ylabel("capsize rate [1/h]")
        ax.set_title(f"{case}: excitation σ {float(c['excitation_std']):.3g}°", fontsize=9)
    axes[-1, 0].set_xlabel("independent sample")
    axes[0, 0].legend(fontsize=7, ncol=4, loc="upper right")
    fig.tight_layout()
    atomic_savefig(fig, path)
    plt.close(fig)
