"""Figures: one function per figure kind; every axis carries units."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from .io import atomic_savefig  # noqa: E402


def body_plan(hull: xr.Dataset, path, title: str | None = None):
    """Classic body plan: aft-body stations on the left (mirrored), fore-body on the right."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    x = hull["x"].values
    for i in range(len(x)):
        n = int(hull["n_points"][i])
        y, z = hull["y"].values[i, :n], hull["z"].values[i, :n]
        sgn = 1.0 if x[i] >= 0 else -1.0
        ax.plot(sgn * y, z, color="C0" if sgn > 0 else "C1", lw=0.8)
    ax.axvline(0, color="k", lw=0.5)
    ax.set_aspect("equal")
    ax.set_xlabel("half-breadth y [m] (aft body left, fore body right)")
    ax.set_ylabel("height above baseline z [m]")
    ax.set_title(title or f"Body plan: {hull.attrs.get('ship', '')} ({len(x)} stations)")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def gz_curves(curves: dict[str, xr.DataArray], path, title: str = "", gm: float | None = None):
    """GZ curves [m] against heel [degree]; ``curves`` maps a label to a ``gz`` DataArray."""
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for label, da in curves.items():
        ax.plot(da["heel"], da, label=label)
    if gm is not None:
        h = np.linspace(0, 30, 10)
        ax.plot(h, gm * np.radians(h), "k:", lw=0.8, label=f"GM·φ (GM = {gm:.3f} m)")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("heel φ [degree]")
    ax.set_ylabel("righting arm GZ [m]")
    ax.set_xlim(0, float(max(da["heel"].max() for da in curves.values())))
    ax.grid(alpha=0.3)
    ax.legend()
    ax.set_title(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


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


def rao_curves(ds: xr.Dataset, path, title: str = "", peer: xr.Dataset | None = None):
    """Heave/a, roll/(ka), pitch/(ka) against L/lambda (paper 000 Figures 7-9); ``peer``: Capytaine
    linear RAOs (FK + diffraction + radiation) on the same axes."""
    fig, axs = plt.subplots(1, 3, figsize=(11, 3.6))
    x = 1.0 / ds["wavelength_ratio"]
    for ax, v, lab in zip(axs, ["heave_rao", "roll_rao", "pitch_rao"], ["heave / a [-]", "roll / ka [-]", "pitch / ka [-]"]):
        ax.plot(x, ds[v], "o-", label="stabflow: volume FK+HS, time domain")
        if peer is not None:
            ax.plot(1.0 / peer["wavelength_ratio"], peer[v], "s--", label="Capytaine linear (FK+diffr.+rad.)")
        ax.set_xlabel("L / λ [-]")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    axs[0].legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
