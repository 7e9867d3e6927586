"""Calm-water and wave GZ curves."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


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
