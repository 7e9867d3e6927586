"""Checks of the derivative model (paper 001) against the full volume-based model it is fitted from.

| check | reference | tolerance | kind |
|---|---|---|---|
| calm-water restoring polynomial, RMS residual per force | the sampled FK + HS forces over the hull-position grid | 5 % of their RMS | consistency |
| wave excitation (constant term's transfer function) at three wave frequencies, heave and pitch | first harmonic of the FK loads on the ship held at equilibrium in a regular wave at speed, exact section clipping (:func:`stabflow.dynamics.linear.fk_excitation`) | 3 % of its modulus | consistency |
| small regular waves: steady heave and pitch amplitudes | the full model in the same waves | 3 % | consistency |
| regular-wave map: steady parametric-roll amplitude per cell where both models are steady above 5 deg | the full model | 10 % (issue 18) | consistency |
| regular-wave map: cells classified alike (no roll above 5 deg / steady parametric roll / unsteady or capsized) | the full model | share >= 0.8 (stabflow's criterion) | consistency |
| irregular seas (two ensembles of one sea): roll sigma; P(largest roll of a record > 25 deg); mean frequency of the roll spectrum | the full model's ensemble | 10 %; inside its 95 % interval; 5 % | consistency |
| no self-repetition: envelope of the wave autocorrelation from 10 min to the record length | 0 | 0.1 (stabflow's criterion) | independent |
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.constants import G, KNOT
from stabflow.dynamics import _kernels as K
from stabflow.dynamics.derivative import WAVE_TERMS, DerivativeModel, run_derivative, run_full
from stabflow.dynamics.linear import fk_excitation
from stabflow.validation import Check
from stabflow.waves.synthesis import encounter_frequency

#: roll amplitude [deg] above which a map cell counts as parametric roll
PARAMETRIC_DEG = 5.0


def _first_harmonic_amplitude(t, x, we):
    from stabflow.dynamics.rao import first_harmonic

    return first_harmonic(t, x, we)[0]


def derivative_checks(model, dm: DerivativeModel, ds: xr.Dataset, small_height: float = 0.5,
                      wavelengths=(0.8, 1.2, 2.0)) -> list[Check]:
    """Rows of the module table for the ensemble-style ``model`` (:func:`stabflow.statistics.ensemble.build_model`),
    its fitted derivative model ``dm`` and the study dataset ``ds`` (fit + regular-wave map)."""
    from stabflow.validation.dynamics import KernelLoads

    rows = []
    for i, f in enumerate(("heave", "roll", "pitch")):
        rel = float(ds["calm_residual"][i] / ds["calm_rms"][i])
        rows.append(Check(f"derivative model: calm-water {f} restoring polynomial, RMS residual / RMS", rel, 0.05, "1",
                          "sampled FK + HS restoring forces over the hull-position grid", "consistency"))
    lwl = float(model.st["lwl"])
    lcg, kg = float(model.st["lcg"]), float(model.st["kg"])
    th0 = float(model.s0[K.S_PITCH])
    h0 = K._origin_height(model.s0[K.S_Z], 0.0, th0, lcg, kg)
    j0 = WAVE_TERMS.index((0, 0, 0))
    for r in wavelengths:
        lam = r * lwl
        w = np.sqrt(2 * np.pi * G / lam)
        # at the fit's own amplitude: the first harmonic depends on the amplitude (odd orders)
        a = float(np.interp(w, dm.frequency, ds["fit_amplitude"].values))
        we = abs(float(encounter_frequency(w, model.speed, dm.heading_deg)))
        loads = KernelLoads(model.sec, model.ship.rho, lcg, kg, (np.array([a]), np.array([w]), np.array([0.0])),
                            dm.heading_deg, model.speed, model.decay)
        F = fk_excitation(loads, h0, th0, we)
        for k, f in ((0, "heave"), (2, "pitch")):
            T = np.interp(w, dm.frequency, dm.tf[:, k, j0].real) + 1j * np.interp(w, dm.frequency, dm.tf[:, k, j0].imag)
            if not (dm.frequency[0] <= w <= dm.frequency[-1]):
                rows.append(Check(f"derivative model: {f} wave excitation at lambda/L = {r:g}", np.nan, 0.03, "1",
                                  "FK loads on the ship held at equilibrium", "consistency",
                                  reason=f"wave frequency {w:.3f} rad/s outside the fitted range"))
                continue
            # the time-domain first harmonic is Re[F e^{i we t}]; the transfer function's Re[a T e^{-i we t}]
            dev = abs(F[k] - a * np.conj(T)) / abs(F[k])
            rows.append(Check(f"derivative model: {f} wave excitation at lambda/L = {r:g}, |difference| / |F|", dev, 0.03,
                              "1", "first harmonic of the FK loads on the ship held at equilibrium in a regular wave at "
                              "speed, exact section clipping (linear.fk_excitation)", "consistency"))
    # small regular waves: steady heave and pitch, both models
    for r in wavelengths:
        lam = r * lwl
        w = np.sqrt(2 * np.pi * G / lam)
        we = abs(float(encounter_frequency(w, model.speed, dm.heading_deg)))
        te = 2 * np.pi / we
        dt = min(0.1, te / 40)
        dur = max(40 * te, 400.0)
        n = int(round(dur / dt))
        waves = (np.array([0.5 * small_height]), np.array([w]), np.array([0.0]))
        out, _ = run_full(model, waves, dm.heading_deg, n * dt, dt)
        od, _ = run_derivative(dm, waves, n * dt, dt)
        t = np.arange(n + 1) * dt
        sel = t >= t[-1] - 10 * te
        for k, f in ((K.S_Z, "heave"), (K.S_PITCH, "pitch")):
            full = _first_harmonic_amplitude(t[sel], out[sel, k], we)
            der = _first_harmonic_amplitude(t[sel], od[sel, k], we)
            rows.append(Check(f"derivative model: {f} amplitude in a {small_height:g} m regular wave, lambda/L = {r:g}, "
                              "relative to the full model", der / full - 1, 0.03, "1",
                              "full volume-based model in the same wave", "consistency"))
    # the regular-wave map
    both = (ds["steady_full"] == 1) & (ds["steady_derivative"] == 1) & (ds["roll_full"] > PARAMETRIC_DEG) & (
        ds["roll_derivative"] > PARAMETRIC_DEG)
    ref = "full volume-based model in the same regular wave (paper 001's verification in regular waves)"
    cells = [(float(x), float(h)) for x in ds["frequency_ratio"].values for h in ds["wave_height"].values
             if bool(both.sel(frequency_ratio=x, wave_height=h))]
    for x, h in cells:
        c = ds.sel(frequency_ratio=x, wave_height=h)
        rows.append(Check(f"derivative model: steady parametric roll at omega_e/omega_roll = {x:.2f}, H = {h:g} m, "
                          "relative to the full model", float(c["roll_derivative"] / c["roll_full"] - 1), 0.10, "1", ref,
                          "consistency"))
    cls = {m: xr.where(ds[f"roll_{m}"] <= PARAMETRIC_DEG, 0,
                       xr.where((ds[f"capsized_{m}"] == 1) | (ds[f"steady_{m}"] == 0), 2, 1)) for m in ("full", "derivative")}
    pf, pd = cls["full"] > 0, cls["derivative"] > 0
    if not cells:
        # no parametric roll anywhere in the map: nothing to compare (SKIPPED); in one model only: FAIL
        none = not bool(pf.any()) and not bool(pd.any())
        rows.append(Check("derivative model: steady parametric roll in the regular-wave map", np.nan, 0.10, "1", ref,
                          "consistency", skipped=none,
                          reason=("neither model reaches" if none else "no cell where both models reach")
                          + f" a steady roll above {PARAMETRIC_DEG:g} deg in the map"))
    share = float((cls["full"] == cls["derivative"]).mean())
    counts = {m: [int((cls[m] == k).sum()) for k in (1, 2)] for m in cls}
    rows.append(Check(f"derivative model: map cells classified alike (none / steady parametric roll above "
                      f"{PARAMETRIC_DEG:g} deg / unsteady or capsized; full {counts['full'][0]} / {counts['full'][1]}, "
                      f"derivative {counts['derivative'][0]} / {counts['derivative'][1]} of {pf.size})", share, 0.0, "1",
                      ref, "consistency", lower=0.8, upper=1.0))
    return rows


def irregular_checks(full: xr.Dataset, der: xr.Dataset, level: float = 25.0, seaway=None, seed: int = 0) -> list[Check]:
    """Irregular seas, the two ensembles of the same sea (volume and derivative model): roll sigma
    within 10 % (issue 18's criterion), the derivative model's P(largest roll of a record > level)
    inside the full model's 95 % Clopper-Pearson interval, the roll spectra's mean frequency within
    5 %, and (with ``seaway``) no self-repetition of the records' sea: the envelope of the wave
    autocorrelation below 0.1 at every lag from 10 min to the record length (stabflow's criterion)."""
    from stabflow.dynamics.derivative import exceedance_probability, wave_autocorrelation

    rows = []
    ref = f"the same sea with the full volume-based model ({full.attrs['n_records']} records of {full.attrs['duration']:g} s)"
    hours = float(full["exposure_hours"])
    rows.append(Check(f"derivative model, irregular seas ({hours:.0f} h): roll sigma relative to the full model",
                      float(der["roll_std"] / full["roll_std"] - 1), 0.10, "1", ref, "consistency"))
    pf, lo, hi = exceedance_probability(full["roll_max"].values, level)
    pd, _, _ = exceedance_probability(der["roll_max"].values, level)
    rows.append(Check(f"derivative model, irregular seas: P(largest roll of a record > {level:g} deg) = {pd:.2f}, "
                      f"full model {pf:.2f} [{lo:.2f}, {hi:.2f}]", pd, 0.0, "1", ref, "consistency", lower=lo, upper=hi))
    # the spectra's mean frequency m1 / m0 (their Welch resolution, 2 pi / segment, is too coarse for
    # the peak of a narrow roll spectrum: the largest bin flips between neighbours)
    w = full["frequency"].values
    mean_w = [float(np.sum(w * e["roll_psd"].values) / np.sum(e["roll_psd"].values)) for e in (full, der)]
    rows.append(Check(f"derivative model, irregular seas: mean frequency m1/m0 of the roll spectrum "
                      f"({mean_w[1]:.3f} rad/s) relative to the full model's ({mean_w[0]:.3f})",
                      mean_w[1] / mean_w[0] - 1, 0.05, "1", ref, "consistency"))
    if seaway is not None:
        dur = float(full.attrs["duration"])
        lags = np.arange(600.0, dur, 1.0)
        amp, w, ph = seaway.components(seed, 0)
        we = encounter_frequency(w, float(full.attrs["speed_kn"]) * KNOT, float(full.attrs["heading_deg"]))
        r = float(np.max(wave_autocorrelation((amp, we, ph), lags, envelope=True)))  # as the ship meets it
        rows.append(Check(f"seaway of the ensembles: largest envelope of the encountered wave's autocorrelation at lags "
                          f"600 s to {dur:g} s "
                          f"({seaway.n_components} components, {seaway.method}, random frequencies "
                          f"{'on' if seaway.randomise else 'off'}): no self-repetition", r, 0.1, "1",
                          "0 for a non-repeating sea (paper 001: 3100 components against the self-repeating effect)",
                          "independent"))
    return rows
