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


def threshold_diagnostics(series, tau: float, u: float, sigma: float, path, title: str = ""):
    """Mean residual life and GPD parameter stability (pyextremes) of the first sample's envelope
    peaks, thresholds 1.5-5 sigma; the chosen threshold dashed."""
    from pyextremes import plot_mean_residual_life, plot_parameter_stability

    thr = np.linspace(1.5 * sigma, min(5.0 * sigma, float(series.max()) * 0.95), 25)
    fig = plt.figure(figsize=(11, 4.2))
    ax0 = fig.add_subplot(1, 3, 1)
    plot_mean_residual_life(series, thresholds=thr, ax=ax0)
    ax0.set_xlabel("threshold [deg]")
    ax0.set_ylabel("mean excess [deg]")
    ax1 = fig.add_subplot(1, 3, 2)
    ax2 = fig.add_subplot(1, 3, 3)
    plot_parameter_stability(series, thresholds=thr, r=f"{tau}s", alpha=None, axes=(ax1, ax2))
    ax1.set_title("")
    ax2.set_xlabel("threshold [deg]")
    ax2.set_ylabel("modified scale [deg]")
    ax1.set_ylabel("shape ξ [-]")
    for ax in (ax0, ax1, ax2):
        ax.axvline(u, color="k", ls="--", lw=0.8)
    fig.suptitle(title or "Threshold selection")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def exceedance_rate_curve(extra: dict, targets, path, title: str = ""):
    """GPD exceedance rate of the first sample with its bootstrap band, against the rate counted in
    the whole ensemble (same threshold and declustering)."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.fill_between(extra["x"], np.maximum(extra["lo"], 1e-9), np.maximum(extra["hi"], 1e-9), alpha=0.3,
                    label=f"95 % interval ({extra['hours']:.0f} h sample)")
    ax.semilogy(extra["x"], np.maximum(extra["rate"], 1e-9), label="GPD extrapolation")
    m = extra["bf_maxima"]
    xs = np.sort(m)[::-1]
    rate = np.arange(1, len(xs) + 1) / extra["bf_hours_all"]
    ax.semilogy(xs, rate, "k.", ms=2, label=f"counted, {extra['bf_hours_all']:.0f} h ensemble")
    for x in targets:
        ax.axvline(x, color="0.6", lw=0.6)
    ax.set_xlim(extra["u"], extra["x"][-1])
    ax.set_ylim(max(0.3 / extra["bf_hours_all"], 1e-6), None)
    ax.set_xlabel("roll envelope peak x [deg]")
    ax.set_ylabel("rate of independent exceedances λ(x) [1/h]")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    ax.set_title(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def extremes_validation(ds: xr.Dataset, path, title: str = ""):
    """Per-sample estimates with intervals against the brute-force rate, one panel per target."""
    n = ds.sizes["target"]
    fig, axs = plt.subplots(1, n, figsize=(4 * n, 4), squeeze=False)
    b = ds["block"].values
    for ax, x in zip(axs[0], ds["target"].values):
        d = ds.sel(target=x)
        est, lo, hi = d["rate_estimate"].values, d["rate_lower"].values, d["rate_upper"].values
        ok = d["inside"].values.astype(bool)
        for sel, col in ((ok, "C0"), (~ok, "C3")):
            ax.errorbar(b[sel], est[sel], yerr=[est[sel] - lo[sel], hi[sel] - est[sel]], fmt="o", ms=3, color=col, lw=0.8)
        ax.plot(b, d["rate_bruteforce"].values, "k-", lw=1, label="brute force (other records)")
        ax.set_yscale("log")
        ax.set_xlabel("sample")
        ax.set_title(f"roll > {x:g}°: coverage {float(d['coverage']):.0%}")
        ax.grid(alpha=0.3, which="both")
    axs[0][0].set_ylabel("exceedance rate [1/h]")
    axs[0][0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def splittime_figures(model, ds: xr.Dataset, paths: dict, title: str = ""):
    """Paper 003 Figs 3 and 4, the metric tail with its GPD, and capsize rate vs threshold."""
    from scipy import stats

    from .ensemble import simulate_record
    from .splittime import perturbed_histories

    thr0 = float(ds["split_threshold"][0])
    ev = ds.where(ds["crossing_threshold_deg"] == thr0, drop=True)
    # Fig. 3: crossings on the sample record with the most crossings
    recs, counts = np.unique(ev["crossing_record"].values.astype(int), return_counts=True)
    r = int(recs[np.argmax(counts)])
    states, last = simulate_record(model, r)
    t = np.arange(last + 1) * model.dt
    fig, ax = plt.subplots(figsize=(9, 3.6))
    ax.plot(t, np.degrees(states[: last + 1, 1]), lw=0.8)
    m = ev["crossing_record"].values.astype(int) == r
    ax.plot(ev["crossing_time"].values[m], thr0 * ev["crossing_side"].values[m], "ro", ms=4, label="crossings")
    for s in (1, -1):
        ax.axhline(s * thr0, color="r", lw=0.6, ls="--")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("roll [deg]")
    ax.set_title(f"Non-rare problem: crossings of ±{thr0:g}° in record {r}")
    ax.legend(loc="upper right")
    fig.tight_layout()
    atomic_savefig(fig, paths["crossings"], dpi=120)
    plt.close(fig)
    # Fig. 4: perturbed runs at the crossing with the largest finite metric below 1
    y = ev["metric"].values
    d = ev["critical_perturbation"].values
    ok = np.isfinite(d) & (d > 0)
    k = int(np.nonzero(ok)[0][np.argmax(y[ok])]) if ok.any() else 0
    rk, sk, tk = int(ev["crossing_record"].values[k]), int(ev["crossing_side"].values[k]), float(ev["crossing_time"].values[k])
    step = int(np.floor(tk / model.dt))
    dc = float(d[k]) if np.isfinite(d[k]) else 10.0
    deltas = [0.25 * dc, 0.5 * dc, 0.9 * dc, dc, 1.5 * dc]
    tt, base, runs = perturbed_histories(model, rk, step, sk, deltas, int(ds.attrs["window_steps"]))
    fig, ax = plt.subplots(figsize=(8, 4))
    for dd, rr in zip(deltas, runs):
        ax.plot(tt, rr, lw=1, label=f"+{dd:.2f} deg/s" + (" (critical)" if dd == dc else ""))
    ax.plot(tt, base, "k--", lw=1.2, label="unperturbed")
    ax.axhline(90 * sk, color="r", lw=0.6)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("roll [deg]")
    ax.set_title(f"Motion perturbation at a {thr0:g}° crossing (record {rk}, t = {tk:.1f} s), y = {y[k]:.3f}")
    ax.legend(fontsize=8)
    fig.tight_layout()
    atomic_savefig(fig, paths["perturbation"], dpi=120)
    plt.close(fig)
    # metric tail and GPD per threshold
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i, thr in enumerate(ds["split_threshold"].values):
        e = ds.where(ds["crossing_threshold_deg"] == thr, drop=True)
        # declustered metric is not stored per event; show the exceedance curve of all metrics
        yy = np.sort(e["metric"].values)[::-1]
        ax.semilogy(yy, np.arange(1, len(yy) + 1) / len(yy), ".", ms=3, color=f"C{i}", label=f"{thr:g}°: metrics")
        u, xi, sc = (float(ds[v].sel(split_threshold=thr)) for v in ("metric_threshold", "metric_gpd_shape", "metric_gpd_scale"))
        if np.isfinite(xi):
            frac = float(ds["metric_exceedances"].sel(split_threshold=thr)) / float(ds["clusters"].sel(split_threshold=thr))
            yg = np.linspace(u, 1.0, 100)
            ax.semilogy(yg, frac * stats.genpareto.sf(yg - u, xi, scale=sc), color=f"C{i}", lw=1,
                        label=f"{thr:g}°: GPD (clusters), P(y≥1) = {float(ds['capsize_probability'].sel(split_threshold=thr)):.2g}")
    ax.axvline(1.0, color="k", lw=0.6)
    ax.set_xlabel("metric y = φ̇_U / φ̇_Cr [-]")
    ax.set_ylabel("exceedance probability [-]")
    ax.set_ylim(1e-5, 1.2)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both")
    ax.set_title("Rare problem: metric tail")
    fig.tight_layout()
    atomic_savefig(fig, paths["metric"], dpi=120)
    plt.close(fig)
    # capsize rate vs threshold
    fig, ax = plt.subplots(figsize=(7, 4.2))
    th = ds["split_threshold"].values
    lam, lo, hi = (ds[v].values for v in ("capsize_rate_splittime", "capsize_rate_lower", "capsize_rate_upper"))
    ax.errorbar(th, np.maximum(lam, 1e-7), yerr=[np.maximum(lam, 1e-7) - np.maximum(lo, 1e-7), np.maximum(hi - lam, 0)],
                fmt="o", capsize=4, label=f"split-time ({float(ds['sample_hours']):.0f} h sample)")
    bf, bl, bh = (float(ds[v]) for v in ("capsize_rate_bruteforce", "capsize_rate_bruteforce_lower", "capsize_rate_bruteforce_upper"))
    ax.axhspan(bl, bh, color="0.85", label=f"brute force {int(ds['bruteforce_capsizes'])} capsizes / {float(ds['bruteforce_hours']):.0f} h")
    ax.axhline(bf, color="k", lw=1)
    ax.set_yscale("log")
    ax.set_xlabel("intermediate threshold [deg]")
    ax.set_ylabel("capsize rate [1/h]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    ax.set_title(title)
    fig.tight_layout()
    atomic_savefig(fig, paths["rate"], dpi=120)
    plt.close(fig)
