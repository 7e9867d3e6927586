"""The criteria figure: GZ with the weather criterion's levers and areas, and GM on a wave of the
ship's length against wave steepness (the level-1 quantities of pure loss and parametric rolling)."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


def criteria_figure(ds: xr.Dataset, path, title: str = ""):
    """Left: GZ [m] with lw1, lw2 and areas a, b (when the weather criterion was evaluated);
    right: GMmin / GMmax on the wave and delta GM by both routes against H/lambda."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    heel, gz = ds["heel"].values, ds["gz"].values
    h = np.r_[-heel[:0:-1], heel]
    g = np.r_[-gz[:0:-1], gz]
    a1.plot(h, g, "k", lw=1.2, label="GZ (free trim)")
    if "wc_lw2" in ds and math.isfinite(float(ds["wc_area_a"])):
        lw1, lw2 = float(ds.wc_lw1), float(ds.wc_lw2)
        lo = float(ds.wc_phi0) - float(ds.wc_phi1)
        p2, pl = float(ds.wc_phi2), float(ds.wc_phi_lw2)
        a1.axhline(lw1, color="C0", lw=0.8, label=f"lw1 = {lw1:.3f} m")
        a1.axhline(lw2, color="C3", lw=0.8, label=f"lw2 = {lw2:.3f} m")
        ma = (h >= lo) & (h <= pl)
        mb = (h >= pl) & (h <= p2)
        a1.fill_between(h[ma], g[ma], lw2, color="C3", alpha=0.3, label=f"a = {float(ds.wc_area_a):.4f} m rad")
        a1.fill_between(h[mb], g[mb], lw2, color="C2", alpha=0.3, label=f"b = {float(ds.wc_area_b):.4f} m rad")
        a1.set_xlim(min(lo - 5, -5), 90)
    else:
        a1.set_xlim(0, 90)
        why = ("no windage in the ship config" if "wc_lw1" not in ds else
               "the wind levers exceed GZmax: the weather criterion fails")
        a1.text(0.02, 0.95, f"weather criterion areas not drawn: {why}", transform=a1.transAxes, va="top", fontsize=8)
    a1.axhline(0, color="k", lw=0.5)
    a1.set_xlabel("heel φ [degree]")
    a1.set_ylabel("GZ [m]")
    a1.grid(alpha=0.3)
    a1.legend(fontsize=7, loc="lower right")
    s = ds["steepness"].values
    a2.plot(s, ds["gm_wave_min"], "C0", label="GMmin on the wave")
    a2.plot(s, ds["gm_wave_max"], "C0--", label="GMmax on the wave")
    a2.axhline(float(ds["gm"]), color="k", lw=0.6, ls=":", label="GM calm water")
    a2.plot(s, ds["delta_gm_wave"], "C1", label="δGM on the wave, (max − min)/2")
    a2.plot(s, ds["delta_gm_waterplane"], "C2", label="δGM by waterplane inertias, d ± H/2")
    a2.set_xlabel("wave steepness H/λ (λ = L)")
    a2.set_ylabel("[m]")
    a2.grid(alpha=0.3)
    a2.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def sea_state_figure(ds: xr.Dataset, path, title: str = ""):
    """Level-2 physics over the scatter table's sea states (Hs x Tz, states that never occur blank):
    Grim's effective wave height, delta GM / GM on it, the dead-ship roll sigma, and the long-term
    rate of the lateral acceleration at the crew location exceeding a level."""
    fig, axes = plt.subplots(1, 4, figsize=(16, 3.8))
    tz, hs = ds["tz"].values, ds["hs"].values
    for ax, (var, label) in zip(axes[:3], (("ew_effective_height", "H_eff [m] (Grim, λ = L)"),
                                             ("ew_delta_gm_ratio", "δGM / GM on the effective wave"),
                                             ("ds_roll_std", "dead-ship roll σ [°] (beam seas, no way)"))):
        m = ax.pcolormesh(tz, hs, np.ma.masked_invalid(ds[var].values), shading="nearest", cmap="viridis")
        fig.colorbar(m, ax=ax, shrink=0.85)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("Tz [s]")
        ax.set_ylabel("Hs [m]")
    a = axes[3]
    r = ds["ea_long_term_rate"].values
    a.semilogy(ds["ea_level"].values, np.where(r > 0, r, np.nan), "o-")
    a.set_xlabel("lateral acceleration level [m/s²]")
    a.set_ylabel("exceedances per year")
    a.set_title(f"crew location {float(ds.ea_height_above_g):.1f} m above G", fontsize=9)
    a.grid(alpha=0.3, which="both")
    fig.suptitle(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=110)
    plt.close(fig)


def dsa_figures(ds: xr.Dataset, paths: dict, name: str):
    """``paths['map']``: each (Hs, Tz) cell's contribution to the long-term rate (summed over headings
    and speeds; x marks cells whose every heading and speed was screened); ``paths['polar']``: the
    failure rate over heading x speed in the three sea states contributing most."""
    import pandas as pd
    from matplotlib.colors import LogNorm

    df = pd.DataFrame({"hs": ds.hs.values, "tz": ds.tz.values, "heading": ds.heading.values,
                       "speed": ds.speed_kn.values, "c": ds.contribution.values,
                       "rate": ds.cell_rate.values * 3600.0, "screened": ds.method.values == "screened"})
    df["zero"] = (ds.method.values == "counted") & (ds.failures.values == 0)
    g = df.groupby(["hs", "tz"]).agg(c=("c", "sum"), screened=("screened", "all"), zero=("zero", "any")).reset_index()
    hs, tz = np.sort(g.hs.unique()), np.sort(g.tz.unique())
    C = np.full((len(hs), len(tz)), np.nan)
    for r in g.itertuples():
        C[np.searchsorted(hs, r.hs), np.searchsorted(tz, r.tz)] = r.c
    fig, ax = plt.subplots(figsize=(7.5, 5))
    pos = C[np.isfinite(C) & (C > 0)]
    norm = LogNorm(vmin=max(pos.min(), pos.max() * 1e-8), vmax=pos.max()) if pos.size else None
    m = ax.pcolormesh(tz, hs, np.where(C > 0, C, np.nan), norm=norm, cmap="viridis", shading="nearest")
    if pos.size:
        fig.colorbar(m, ax=ax, label="contribution to the long-term rate [1/year]")
    s = g[g.screened]
    ax.plot(s.tz, s.hs, "x", color="0.4", ms=4, label="screened (bound only)")
    z = g[g.zero & (g.c <= 0)]
    ax.plot(z.tz, z.hs, "o", mfc="none", color="C3", ms=5, label="simulated, no failure counted (in the interval's upper bound)")
    ax.set_xlabel("zero-crossing period Tz [s]")
    ax.set_ylabel("significant wave height Hs [m]")
    ax.set_title(f"{name}: DSA, {float(ds.rate):.3g} /year [{float(ds.rate_lo):.3g}, {float(ds.rate_hi):.3g}]")
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    atomic_savefig(fig, paths["map"], dpi=120)
    plt.close(fig)
    top = g.sort_values("c", ascending=False).head(3)
    fig, axs = plt.subplots(1, len(top), subplot_kw={"projection": "polar"}, figsize=(4 * max(len(top), 1), 4), squeeze=False)
    for a, r in zip(axs[0], top.itertuples()):
        d = df[(df.hs == r.hs) & (df.tz == r.tz)]
        rate = np.where(d.rate > 0, d.rate, np.nan)
        sc = a.scatter(np.radians(d.heading), d.speed, c=rate, cmap="magma_r", s=80, norm=LogNorm() if np.isfinite(rate).any() else None)
        a.set_thetamin(0)
        a.set_thetamax(180)
        a.set_title(f"Hs {r.hs:g} m, Tz {r.tz:g} s", fontsize=9)
        a.set_xlabel("heading [degree] (0 following); radius: speed [kn]", fontsize=7)
        if np.isfinite(rate).any():
            fig.colorbar(sc, ax=a, shrink=0.6, label="failures per hour")
    fig.suptitle(f"{name}: failure rate over heading x speed (operational polar)")
    fig.tight_layout()
    atomic_savefig(fig, paths["polar"], dpi=120)
    plt.close(fig)
