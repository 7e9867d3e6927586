"""Irregular-sea ensembles: roll distribution, response spectra, sample records."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


def roll_distribution(ens: xr.Dataset, path, title: str = ""):
    """Roll pdf normalised by sigma against the standard normal, both tails on a log scale
    (seed 000 Figs 11-13): left, negative roll folded; right, positive roll."""
    c = ens["roll_bin"].values
    h = ens["hist_roll"].values.astype(float)
    sig = float(ens["roll_std"])
    w = c[1] - c[0]
    pdf = h / (h.sum() * w) * sig  # density of roll / sigma
    x = c / sig
    fig, axs = plt.subplots(1, 2, figsize=(9, 3.8), sharey=True)
    xs = np.linspace(0, x.max(), 400)
    for ax, side, lab in ((axs[0], -1, "negative roll (starboard up)"), (axs[1], 1, "positive roll")):
        m = (side * x > 0) & (pdf > 0)
        ax.semilogy(side * x[m], pdf[m], ".", ms=3, label="ensemble")
        ax.semilogy(xs, np.exp(-0.5 * xs**2) / np.sqrt(2 * np.pi), "k-", lw=1, label="normal")
        ax.set_xlabel(f"|roll| / σ [-] ({lab})")
        ax.set_xlim(0, max(6.0, float(np.abs(x[h > 0]).max()) if h.any() else 6.0))
        ax.grid(alpha=0.3)
    axs[0].set_ylabel("probability density of roll / σ [-]")
    axs[0].set_ylim(1e-8, 1)
    axs[1].legend()
    fig.suptitle(title or f"Roll distribution, σ = {sig:.2f}°, kurtosis {float(ens['kurtosis'].sel(dof='roll')):.2f}")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def response_spectra(ens: xr.Dataset, path, title: str = ""):
    """Mean encounter spectra of wave (midship), heave, roll and pitch."""
    units = {"wave": "m² s", "heave": "m² s", "roll": "deg² s", "pitch": "deg² s"}
    fig, axs = plt.subplots(2, 2, figsize=(9, 6), sharex=True)
    for ax, s in zip(axs.flat, units):
        ax.plot(ens["frequency"], ens[f"{s}_psd"])
        ax.set_ylabel(f"S_{s}(ω_e) [{units[s]}]")
        ax.set_xlim(0, 2.0)
        ax.grid(alpha=0.3)
    for ax in axs[1]:
        ax.set_xlabel("encounter frequency ω_e [rad/s]")
    fig.suptitle(title or "Response spectra (Welch, mean over records)")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def time_histories(ens: xr.Dataset, path, title: str = "", span: float = 600.0):
    """Sample records: wave elevation at midships, heave, roll and pitch (seed 000 Fig. 10)."""
    names = [("sample_wave", "wave η [m]"), ("sample_heave", "heave [m]"), ("sample_roll", "roll [deg]"),
             ("sample_pitch", "pitch [deg]")]
    fig, axs = plt.subplots(4, 1, figsize=(9, 7), sharex=True)
    if "sample" in ens.dims:
        t = ens["time"].values
        m = t <= span
        for ax, (v, lab) in zip(axs, names):
            for k in range(min(ens.sizes["sample"], 2)):
                ax.plot(t[m], ens[v].values[k, m], lw=0.8, label=f"record {int(ens['sample'][k])}")
            ax.set_ylabel(lab)
            ax.grid(alpha=0.3)
        axs[0].legend(loc="upper right", fontsize=8)
    axs[-1].set_xlabel("time [s]")
    fig.suptitle(title or "Sample records")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
