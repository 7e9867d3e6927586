"""Calm-water roll decay and Ikeda's roll-damping components."""

from __future__ import annotations

import xarray as xr

from stabflow.plots._style import atomic_savefig, plt

#: Ikeda components drawn (dataset variable, label)
COMPONENTS = (("friction", "skin friction"), ("eddy", "hull eddy making"), ("lift", "hull lift"),
              ("bilge_keel_lift", "bilge-keel lift"), ("bilge_keel_normal", "bilge-keel normal force"),
              ("bilge_keel_hull", "bilge-keel hull pressure"), ("wave", "wave (Capytaine)"))


def roll_decay_figure(ds: xr.Dataset, path, title: str = ""):
    """Roll decay record with its peaks and the equivalent damping per cycle; with Ikeda's damping,
    B44 of each component against roll amplitude and against speed, as naval architects draw them."""
    ikeda = "amp_total" in ds
    fig, axs = plt.subplots(1, 3 if ikeda else 2, figsize=(13 if ikeda else 9, 3.8))
    ax = axs[0]
    ax.plot(ds["time"], ds["roll"], lw=0.9)
    ax.plot(ds["peak_time"], ds["peak_roll"], "o", ms=3)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("roll [deg]")
    ax.grid(alpha=0.3)
    ax = axs[1]
    ax.plot(ds["cycle_amplitude"], ds["cycle_zeta"], "o-")
    ax.set_xlabel("mean roll amplitude of the cycle [deg]")
    ax.set_ylabel("equivalent damping ratio ζ [-]")
    ax.grid(alpha=0.3)
    if ikeda:
        for var, label in COMPONENTS:
            ax = axs[2]
            axs[2].plot(ds["speed"], ds[f"speed_{var}"] / 1e6, label=label)
        axs[2].plot(ds["speed"], ds["speed_total"] / 1e6, "k-", lw=2, label="total")
        axs[2].set_xlabel("ship speed [m/s]")
        axs[2].set_ylabel(f"B44 at {ds.attrs['ikeda_amplitude_deg']:g}° [MN m s/rad]")
        axs[2].grid(alpha=0.3)
        axs[2].legend(fontsize=6)
        ax1 = axs[1].twinx()
        ax1.stackplot(ds["roll_amplitude"], *[ds[f"amp_{v}"] / 1e6 for v, _ in COMPONENTS], alpha=0.25,
                      labels=[lab for _, lab in COMPONENTS])
        ax1.set_ylabel("Ikeda B44 at zero speed [MN m s/rad] (stacked)")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
