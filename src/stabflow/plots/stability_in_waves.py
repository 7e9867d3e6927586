"""Stability in waves: GM as the crest passes, metric C per ship and sea state (paper 002)."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


def gm_wave_pass(ds: xr.Dataset, path, gm_calm: float, title: str = ""):
    """GM(x_c) [m] against crest position [m], one line per lambda/L at the steepest wave."""
    s = float(ds["steepness"].max())
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for r in ds["wavelength_ratio"].values:
        ax.plot(ds["crest_position"], ds["gm_wave"].sel(wavelength_ratio=r, steepness=s), label=f"λ/L = {r:g}")
    ax.axhline(gm_calm, color="k", ls="--", lw=0.8, label="calm water")
    ax.set_xlabel("wave crest position x_c from midships [m] (+ forward)")
    ax.set_ylabel("GM in waves [m]")
    ax.set_title(title or f"GM as the crest passes, H/λ = {s:g}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def metric_bars(table, path):
    """Bar chart of metric C per ship and sea state (paper 002, Figure 6). ``table``: pandas frame
    with columns ship, sea_state, metric_c."""
    ships = list(dict.fromkeys(table["ship"]))
    states = list(dict.fromkeys(table["sea_state"]))
    fig, ax = plt.subplots(figsize=(8, 4.2))
    w = 0.8 / len(states)
    for j, s in enumerate(states):
        vals = [float(table[(table.ship == sh) & (table.sea_state == s)]["metric_c"].iloc[0]) for sh in ships]
        ax.bar(np.arange(len(ships)) + (j - (len(states) - 1) / 2) * w, vals, w, label=s)
    ax.set_xticks(np.arange(len(ships)), ships, rotation=20)
    ax.set_ylabel("assessment metric C = m(tbc) / T_φ [-]")
    ax.set_title("Early-stage assessment of stability change in waves (15 kn, following seas)")
    ax.legend(title="sea state")
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
