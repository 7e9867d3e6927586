"""Derivative model (paper 001): restoring fit, transfer functions, regular-wave parametric-roll map."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.plots._style import atomic_savefig, plt


def fit_figure(model, dm, path):
    """Calm-water roll moment and heave force over roll (z = theta = 0) and over heave (phi = theta
    = 0): sampled volume-based forces against the fitted polynomial."""
    from stabflow.dynamics import derivative as D
    from stabflow.dynamics.tables import kernel_args

    args = kernel_args(model.sec, model.tables)
    calm = D.calm_snapshot(len(model.sec.x), model.decay)
    rr = np.radians(float(dm.dataset.attrs["roll_range_deg"]))
    hr = float(dm.dataset.attrs["heave_range"])
    phi = np.linspace(-1.5 * rr, 1.5 * rr, 61)
    z = np.linspace(-1.5 * hr, 1.5 * hr, 61)
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
    for a, rel, k, x, lab, unit, scale in (
            (ax[0], np.column_stack([0 * phi, phi, 0 * phi]), 1, np.degrees(phi), "roll [deg]", "MN m", 1e-6),
            (ax[1], np.column_stack([z, 0 * z, 0 * z]), 0, z, "heave of G [m]", "MN", 1e-6)):
        R = D._sample(args, model.p, dm.q0, rel, calm)[0][:, k]
        A = np.column_stack([np.prod(rel ** np.array(e), axis=1) for e in D.CALM_TERMS])
        a.plot(x, scale * R, "k-", lw=1.5, label="volume-based FK + HS")
        a.plot(x, scale * (A @ dm.calm[k]), "r--", lw=1.2, label="third-order polynomial")
        lim = np.degrees(rr) if k == 1 else hr
        a.axvspan(-lim, lim, color="0.9", zorder=0, label="fit range")
        a.set_xlabel(lab)
        a.set_ylabel(f"generalized {('heave force', 'roll moment')[k]} [{unit}]")
        a.legend(fontsize=8)
    fig.suptitle("Calm-water restoring: sampled forces and the derivative model's polynomial")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def transfer_figure(ds: xr.Dataset, path):
    """Moduli of the transfer functions of the heave and pitch excitation and of the roll
    restoring coefficient K_zeta_phi (paper 001 Figs 3-5), per metre of wave amplitude."""
    w = ds["tf_frequency"].values
    T = ds["tf_real"].values + 1j * ds["tf_imag"].values
    terms = list(ds["wave_term"].values)
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    for a, (k, term, title, unit) in zip(ax, ((0, "1", "heave excitation Z_w", "MN/m"),
                                             (2, "1", "pitch excitation M_w", "MN m/m"),
                                             (1, "phi", "roll restoring K_zeta_phi", "MN m/rad/m"))):
        a.plot(w, np.abs(T[:, k, terms.index(term)]) * 1e-6, "b-")
        a.set_xlabel("wave frequency [rad/s]")
        a.set_ylabel(f"|T| [{unit}]")
        a.set_title(title, fontsize=10)
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def map_figure(ds: xr.Dataset, path):
    """Largest roll over the last window in regular waves over omega_e / omega_roll x wave height:
    full model and derivative model side by side (Ince-Strutt-shaped instability region)."""
    x = ds["frequency_ratio"].values
    h = ds["wave_height"].values
    vmax = float(max(ds["roll_full"].max(), ds["roll_derivative"].max(), 1.0))
    fig, ax = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for a, v, name in ((ax[0], "roll_full", "full volume-based model"), (ax[1], "roll_derivative", "derivative model")):
        m = a.pcolormesh(x, h, ds[v].values.T, shading="nearest", cmap="viridis", vmin=0, vmax=vmax)
        cap = ds[v.replace("roll", "capsized")].values.T
        for i in range(len(h)):
            for j in range(len(x)):
                if cap[i, j]:
                    a.text(x[j], h[i], "C", ha="center", va="center", color="w", fontsize=8)
        a.set_xlabel("encounter / roll natural frequency")
        a.set_title(name, fontsize=10)
    ax[0].set_ylabel("wave height [m]")
    fig.colorbar(m, ax=ax, label="largest |roll| over the last 10 roll periods [deg]")
    fig.suptitle(f"Parametric roll in regular waves (heading {ds.attrs['heading_deg']:g}°, "
                 f"{ds.attrs['speed'] / 0.514444:.0f} kn); C = capsized")
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def irregular_figure(full: xr.Dataset, der: xr.Dataset, path, level: float = 25.0):
    """Roll spectra of both models (paper 001 Fig. 18) and the distribution over records of each
    record's own roll standard deviation (non-ergodicity: paper 001 section 5), with pitch for contrast."""
    from stabflow.dynamics.derivative import record_variances

    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    for e, name, c in ((full, "full model", "k"), (der, "derivative model", "r")):
        ax[0].plot(e["frequency"].values, e["roll_psd"].values, color=c, label=name)
        ax[1].hist(np.sqrt(record_variances(e, "roll")), bins=15, histtype="step", color=c, lw=1.5, label=name)
        ax[2].hist(np.sqrt(record_variances(e, "pitch")), bins=15, histtype="step", color=c, lw=1.5, label=name)
    ax[0].set_xlim(0, 1.5)
    ax[0].set_xlabel("encounter frequency [rad/s]")
    ax[0].set_ylabel("roll spectrum [deg² s]")
    ax[0].legend(fontsize=8)
    ax[1].set_xlabel("roll standard deviation of one record [deg]")
    ax[1].set_ylabel("records")
    ax[2].set_xlabel("pitch standard deviation of one record [deg]")
    for a in ax[1:]:
        a.legend(fontsize=8)
    a = full.attrs
    fig.suptitle(f"Irregular head seas: JONSWAP Hs {a['hs']:g} m, Tp {a['tp']:g} s, {a['speed_kn']:g} kn, "
                 f"{a['heading_deg']:g}°; {a['n_records']} records of {a['duration'] / 3600:g} h")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def running_variance_figure(full: xr.Dataset, path):
    """Roll of the sample records and each record's running roll variance: time averages of single
    records settle at different values (non-ergodic), so one long record does not replace the ensemble."""
    t = full["time"].values
    fig, ax = plt.subplots(2, 1, figsize=(11, 6), sharex=True)
    for k in range(full.sizes["sample"]):
        x = full["sample_roll"].values[k]
        ok = np.isfinite(x)
        ax[0].plot(t[ok] / 3600, x[ok], lw=0.5)
        run = np.cumsum(x[ok] ** 2) / np.arange(1, ok.sum() + 1)
        ax[1].plot(t[ok] / 3600, np.sqrt(run), lw=1.2, label=f"record {int(full['sample'][k])}")
    ax[1].axhline(float(full["roll_std"]), color="k", ls="--", lw=1, label="ensemble")
    ax[0].set_ylabel("roll [deg]")
    ax[1].set_ylabel("running roll RMS [deg]")
    ax[1].set_xlabel("time [h]")
    ax[1].legend(fontsize=8, ncol=3)
    fig.suptitle("Sample records (full model): roll at half the encounter frequency, and their running RMS")
    fig.tight_layout()
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)


def irregular_map_figure(ds: xr.Dataset, path):
    """Roll sigma and P(largest roll of a record > level) over speed x peak period, both models."""
    fig, ax = plt.subplots(2, 2, figsize=(11, 7), sharex=True, sharey=True)
    x, y = ds["map_tp"].values, ds["map_speed"].values
    smax = float(max(ds["map_sigma_full"].max(), ds["map_sigma_derivative"].max(), 1.0))
    for j, kind in enumerate(("full", "derivative")):
        for i, (v, lab, vmax) in enumerate(((f"map_sigma_{kind}", "roll σ [deg]", smax),
                                            (f"map_p_{kind}", f"P(max roll > {ds.attrs['map_level_deg']:g}°)", 1.0))):
            a = ax[i, j]
            m = a.pcolormesh(x, y, ds[v].values, shading="nearest", vmin=0, vmax=vmax, cmap="viridis")
            for p in range(len(y)):
                for q in range(len(x)):
                    txt = f"{ds[v].values[p, q]:.1f}" if i == 0 else (
                        f"{ds[v].values[p, q]:.2f}\n[{ds[f'map_p_lower_{kind}'].values[p, q]:.2f}, "
                        f"{ds[f'map_p_upper_{kind}'].values[p, q]:.2f}]")
                    a.text(x[q], y[p], txt, ha="center", va="center", color="w", fontsize=7)
            fig.colorbar(m, ax=a, label=lab)
            a.set_title(f"{'full' if kind == 'full' else 'derivative'} model", fontsize=10)
    for a in ax[1]:
        a.set_xlabel("JONSWAP peak period [s]")
    for a in ax[:, 0]:
        a.set_ylabel("speed [kn]")
    fig.suptitle(f"Head seas, Hs {ds.attrs['map_hs']:g} m: {ds.attrs['map_records']} records of "
                 f"{ds.attrs['map_record_duration'] / 3600:g} h per cell (intervals: Clopper-Pearson 95 %)")
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
