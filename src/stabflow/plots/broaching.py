"""Figures of the 6-DOF step (issue 17): paper 004's scenario and the calm-water manoeuvres."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.plots._style import atomic_savefig, plt


def motions_figure(ds: xr.Dataset, loading: str, path) -> None:
    """Six motions and the rudder of every case of one loading (paper 004 Figs 8-14): one row per
    case; roll, yaw with the rudder, pitch with heave, sway."""
    d = ds.sel(loading=loading)
    cases = list(d.case.values)
    fig, axes = plt.subplots(len(cases), 4, figsize=(13, 1.9 * len(cases)), sharex="row", layout="constrained")
    t = d.time.values
    for i, c in enumerate(cases):
        r = d.sel(case=c)
        ax = axes[i]
        ax[0].plot(t, r["roll"], lw=0.8)
        ax[0].set_ylabel(f"{c}\nroll [°]")
        ax[1].plot(t, r["yaw"], lw=0.8, label="yaw")
        ax[1].plot(t, r["rudder"], lw=0.8, label="rudder")
        ax[1].set_ylabel("[°]")
        ax[2].plot(t, r["pitch"], lw=0.8, label="pitch [°]")
        ax[2].plot(t, r["heave"], lw=0.8, label="heave [m]")
        ax[3].plot(t, r["sway"], lw=0.8, label="sway [m]")
        ax[3].plot(t, r["surge"], lw=0.8, label="surge [m]")
        ev = []
        if int(r["capsized"]):
            ev.append(f"capsize {float(r['capsize_time']):.1f} s")
        if int(r["broach"]):
            ev.append(f"broach {float(r['broach_time']):.1f} s")
        if int(r["surf_riding"]):
            ev.append(f"surf-riding {float(r['surf_riding_longest']):.0f} s")
        ax[0].set_title(", ".join(ev) or "no event", fontsize=8, loc="left")
        for a in ax:
            a.grid(alpha=0.3)
        if i == 0:
            for a in ax[1:]:
                a.legend(fontsize=7, loc="upper right")
    for a in axes[-1]:
        a.set_xlabel("time [s]")
    fig.suptitle(f"{ds.attrs['ship']}, {loading} loading (KG {float(d['kg']):.3f} m): {ds.attrs['speed_kn']:g} kn, "
                 f"waves {ds.attrs['heading_deg']:g}° off the stern")
    atomic_savefig(fig, path)
    plt.close(fig)


def strip_figure(ds: xr.Dataset, loading: str, case: str, path, every: float = 1.0, span: float = 10.0) -> None:
    """Top view of the hull in the wave every ``every`` seconds over the first ``span`` seconds (paper 004
    Fig. 7), centred on G: the waterline outline turned by the yaw, and the crests of the regular
    wave (k xi - w_e t + phase = 2 pi n in the frame moving with the commanded speed)."""
    d = ds.sel(loading=loading, case=case)
    dt = float(d.time[1] - d.time[0])
    beta = np.radians(ds.attrs["heading_deg"])
    eb = np.array([np.cos(beta), np.sin(beta)])
    xg = float(ds.attrs["lcg"])
    xo, hb = ds["outline_x"].values - xg, ds["outline_halfbreadth"].values
    ring = np.concatenate([np.column_stack([xo, hb]), np.column_stack([xo[::-1], -hb[::-1]])])
    times = np.arange(0.0, min(span, float(d["end_time"])) + 1e-9, every)
    fig, axes = plt.subplots(1, len(times), figsize=(1.7 * len(times), 3.4), sharey=True)
    axes = np.atleast_1d(axes)
    k, we, ph = float(d["wave_number"]), float(d["encounter_frequency"]), float(d["wave_phase"])
    for ax, tt in zip(axes, times):
        n = int(round(tt / dt))
        G = np.array([float(d["surge"][n]) + xg, float(d["sway"][n])])
        psi = np.radians(float(d["yaw"][n]))
        R = np.array([[np.cos(psi), -np.sin(psi)], [np.sin(psi), np.cos(psi)]])
        pts = ring @ R.T
        # plotted with x (forward) up and y (port) to the left
        ax.fill(-pts[:, 1], pts[:, 0], color="0.3")
        if np.isfinite(k):
            xi_g = float(G @ eb)
            m0 = np.floor((k * (xi_g - 40.0) - we * tt + ph) / (2 * np.pi))
            for m in np.arange(m0, m0 + 2 + 80.0 * k / (2 * np.pi)):
                xi = (2 * np.pi * m + we * tt - ph) / k - xi_g
                line = xi * eb + np.outer([-60.0, 60.0], [-eb[1], eb[0]])
                ax.plot(-line[:, 1], line[:, 0], color="tab:blue", lw=0.8)
        ax.set_title(f"{tt:.0f} s\nroll {float(d['roll'][n]):.0f}°, yaw {float(d['yaw'][n]):.0f}°", fontsize=7)
        ax.set_xlim(-20, 20)
        ax.set_ylim(-20, 20)
        ax.set_aspect("equal")
        ax.set_xticks([])
    axes[0].set_ylabel("along the course [m]")
    fig.suptitle(f"{case}, {loading} loading: hull outline and wave crests, top view centred on G (port to the left)")
    atomic_savefig(fig, path)
    plt.close(fig)


def manoeuvres_figure(tracks: dict, zigzags: dict, path) -> None:
    """Turning-circle tracks and zig-zag headings with their rudder angles."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
    for name, (X, Y) in tracks.items():
        a.plot(-Y, X, label=name)
    a.set_xlabel("to starboard [m]")
    a.set_ylabel("along the approach course [m]")
    a.set_aspect("equal")
    a.legend(fontsize=8)
    a.grid(alpha=0.3)
    for name, (t, psi, rud) in zigzags.items():
        line, = b.plot(t, psi, label=f"{name} heading")
        b.plot(t, rud, ls="--", color=line.get_color(), label=f"{name} rudder")
    b.set_xlabel("time [s]")
    b.set_ylabel("[°]")
    b.legend(fontsize=8)
    b.grid(alpha=0.3)
    atomic_savefig(fig, path)
    plt.close(fig)


def resistance_figure(ds: xr.Dataset, path) -> None:
    """Calm-water resistance of the 6-DOF model against the surge velocity, the friction line alone
    beside it, and each regular wave's Froude-Krylov surge-force amplitude at its celerity."""
    fig, ax = plt.subplots(figsize=(8, 4.8), layout="constrained")
    u = ds["resistance_speed"].values
    L, U = float(ds.attrs["manoeuvre_length"]), float(ds.attrs["manoeuvre_speed"])
    ax.plot(u, ds["resistance"].values / 1e3, label=f"model: {ds.attrs['resistance_method']}")
    ax.plot(u, ds["resistance_friction_only"].values / 1e3, ls="--", label="ITTC-57 friction line alone")
    for lam, c, f in zip(ds["resistance_wave"].values, ds["resistance_wave_celerity"].values,
                         ds["resistance_wave_surge_amplitude"].values):
        ax.plot([c], [f / 1e3], "o")
        ax.annotate(f"λ {lam:g} m", (c, f / 1e3), textcoords="offset points", xytext=(5, 3), fontsize=8)
    ax.axvline(U, color="k", lw=0.8, ls=":")
    ax.annotate("commanded speed", (U, 0), textcoords="offset points", xytext=(3, 5), fontsize=8, rotation=90)
    fn_max = ds.attrs.get("resistance_froude_range_max")
    if fn_max is not None:
        ax.axvspan(fn_max * np.sqrt(G * L), u[-1], color="0.9", zorder=0,
                   label=f"Fn > {fn_max:g} (beyond the range tabulated for trawlers)")
    ax.set_xlim(0, u[-1])
    ax.set_ylim(bottom=0)
    ax.set_xlabel("surge velocity [m/s]")
    ax.set_ylabel("resistance; surge-force amplitude (points) [kN]")
    top = ax.secondary_xaxis("top", functions=(lambda x: x / np.sqrt(G * L), lambda f: f * np.sqrt(G * L)))
    top.set_xlabel("Froude number")
    ax.legend(fontsize=8, title=f"points: FK surge-force amplitude at the celerity, H {ds.attrs['resistance_wave_height']:g} m",
              title_fontsize=8)
    ax.grid(alpha=0.3)
    atomic_savefig(fig, path)
    plt.close(fig)


def map_figure(ds: xr.Dataset, path) -> None:
    """Capsize and broach probability per record over wave heading x speed, each cell annotated with
    its count and 95 % interval."""
    n = int(ds.attrs["map_records"])
    nh, nv = ds.sizes["map_heading"], ds.sizes["map_speed"]
    # each cell 0.85 in wide and 0.75 in high at least, so that its three lines stay inside it
    fig, axes = plt.subplots(1, 2, figsize=(max(12.0, 2 * (0.85 * nh + 1.6)), max(4.8, 0.75 * nv + 1.8)))
    for ax, name in zip(axes, ("capsize", "broach")):
        p = ds[f"map_{name}_probability"].values
        im = ax.imshow(p.T, origin="lower", vmin=0, vmax=1, cmap="Reds", aspect="auto")
        for i in range(p.shape[0]):
            for j in range(p.shape[1]):
                lo, hi = float(ds[f"map_{name}_lower"][i, j]), float(ds[f"map_{name}_upper"][i, j])
                ax.text(i, j, f"{int(ds[f'map_{name}_count'][i, j])}/{n}\n{lo:.2f}–\n{hi:.2f}", ha="center",
                        va="center", fontsize=6.5, linespacing=1.1, color="white" if p[i, j] > 0.6 else "black")
        ax.set_xticks(range(p.shape[0]), [f"{h:g}" for h in ds.map_heading.values])
        ax.set_yticks(range(p.shape[1]), [f"{v:g}" for v in ds.map_speed.values])
        ax.set_xlabel("wave heading off the stern [°] (0 following)")
        ax.set_ylabel("speed [kn]")
        ax.set_title(f"P({name} in {ds.attrs['map_duration']:g} s)")
        fig.colorbar(im, ax=ax)
    fig.suptitle(f"{ds.attrs['ship']}, {ds.attrs['map_loading']} loading, {ds.attrs['map_sea']}: {n} records per cell, "
                 f"{ds.attrs['map_interval']} {100 * (1 - ds.attrs['map_alpha']):g} % intervals")
    atomic_savefig(fig, path)
    plt.close(fig)


def radiation_figure(ds: xr.Dataset, path) -> None:
    """Heave-pitch radiation of the memory model (the ``radiation`` step's file): Capytaine's damping
    and added mass against the fitted state-space model's, and the retardation functions."""
    fig, ax = plt.subplots(2, 3, figsize=(13, 6.5))
    w = ds["radiation_omega"].values
    t = ds["time"].values
    for col, (e, name) in enumerate([("33", "heave-heave"), ("55", "pitch-pitch"), ("35", "heave-pitch")]):
        v = {q: ds[f"radiation_{q}_{e}"] for q in ("damping", "damping_fit", "added_mass", "added_mass_fit",
                                                  "added_mass_inf", "kernel", "kernel_fit")}
        a = ax[0, col]
        a.plot(w, v["damping"], "o", ms=3, label="B(ω) Capytaine")
        a.plot(w, v["damping_fit"], lw=1.0, label="B(ω) memory model")
        b = a.twinx()
        b.plot(w, v["added_mass"], "s", ms=3, color="C2", label="A(ω) Capytaine")
        b.plot(w, v["added_mass_fit"], lw=1.0, color="C3", label="A(ω) memory model")
        b.axhline(float(v["added_mass_inf"]), color="0.5", lw=0.6, ls=":")
        a.set_title(name)
        a.set_xlabel("ω [rad/s]")
        a.set_ylabel(f"B{e} [{v['damping'].attrs.get('units', '')}]")
        b.set_ylabel(f"A{e} [{v['added_mass'].attrs.get('units', '')}] (dotted: A(∞))")
        if col == 0:
            a.legend(loc="upper right", fontsize=7)
            b.legend(loc="center right", fontsize=7)
        k = ax[1, col]
        k.plot(t, v["kernel"], lw=1.2, label=f"K(t) from B(ω) ≤ {w[-1]:.1f} rad/s")
        k.plot(t, v["kernel_fit"], lw=0.8, ls="--", label=f"fitted ({ds.sizes['pole']} poles)")
        k.set_xlabel("t [s]")
        k.set_ylabel(f"K{e} [{v['kernel'].attrs.get('units', '')}]")
        k.legend(fontsize=7)
    fig.suptitle("Heave-pitch radiation with memory (Cummins' equation)")
    fig.tight_layout()
    atomic_savefig(fig, path)
    plt.close(fig)
