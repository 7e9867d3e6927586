"""Hull figures: the body plan of the cut stations."""

from __future__ import annotations

import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


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
