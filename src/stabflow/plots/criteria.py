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
        a1.text(0.02, 0.95, "weather criterion not evaluated (no windage)", transform=a1.transAxes, va="top", fontsize=8)
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
