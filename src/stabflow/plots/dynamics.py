"""Regular-wave response of the time-domain model."""

from __future__ import annotations

import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


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
