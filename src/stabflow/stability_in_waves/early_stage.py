"""Early-stage assessment of stability change in waves: metric C (paper 002, section 3).

Irregular sea → joint distribution of wave amplitude A and wave number k (eq. 4 / A11) →
statistical weights W_ij on a grid of amplitudes and wave numbers (eq. 6) → for each wave the
GM(x_c) wave pass and the time below the critical GM (eq. 7) → mean m(tbc) (eq. 10) →
C = m(tbc) / T_phi with T_phi = 0.8 B / sqrt(GM_cr) (eq. 11).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.geometry import Sections
from stabflow.io import annotate
from stabflow.constants import KNOT, G
from stabflow.hydrostatics.statics import Particulars, gz_curve
from stabflow.waves.spectra import cutoff_frequencies, spectral_moments, spectrum
from stabflow.stability_in_waves.wave_pass import wave_gm



def wave_statistics(S, w_peak: float) -> tuple[float, float, float]:
    """sigma_zeta [m], k1 and k2 [rad/m] of eq. 5, integrated between the 0.1 % cut-offs."""
    lo, hi = cutoff_frequencies(S, w_peak)
    m = spectral_moments(S, lo, hi, orders=(0, 2, 4))
    sigma = np.sqrt(m[0])
    return sigma, m[2] / G / m[0], np.sqrt(m[4]) / G / sigma


def joint_pdf(A, k, sigma, k1, k2):
    """f(A, k) of eq. 4 (A11) [1/(m rad/m)]: Rayleigh amplitude times a folded normal wave number
    with mean k1 and standard deviation sigma sqrt(k2^2 - k1^2) / A."""
    A = np.asarray(A, float)
    k = np.asarray(k, float)
    d = k2 * k2 - k1 * k1
    q = A * A / (2 * sigma * sigma)
    return (A * A / (sigma**3 * np.sqrt(d) * np.sqrt(2 * np.pi)) * np.exp(-q)
            * (np.exp(-q * (k - k1) ** 2 / d) + np.exp(-q * (k + k1) ** 2 / d)))


def weights(a_edges, k_edges, sigma, k1, k2, order: int = 12) -> np.ndarray:
    """W_ij of eq. 6: f(A, k) integrated over each (A, k) cell, Gauss-Legendre ``order`` per axis."""
    x, w = np.polynomial.legendre.leggauss(order)
    out = np.empty((len(a_edges) - 1, len(k_edges) - 1))
    for i in range(len(a_edges) - 1):
        a0, a1 = a_edges[i], a_edges[i + 1]
        A = 0.5 * (a0 + a1) + 0.5 * (a1 - a0) * x
        for j in range(len(k_edges) - 1):
            k0, kk1 = k_edges[j], k_edges[j + 1]
            K = 0.5 * (k0 + kk1) + 0.5 * (kk1 - k0) * x
            f = joint_pdf(A[:, None], K[None, :], sigma, k1, k2)
            out[i, j] = 0.25 * (a1 - a0) * (kk1 - k0) * (w[:, None] * w[None, :] * f).sum()
    return out


def heel_of_gz_max(gz: np.ndarray, heel_deg: np.ndarray) -> float:
    """Heel [degree] of the GZ maximum, refined by a parabola through the three best points."""
    j = int(np.argmax(gz))
    if 0 < j < len(gz) - 1:
        y0, y1, y2 = gz[j - 1], gz[j], gz[j + 1]
        den = y0 - 2 * y1 + y2
        off = 0.5 * (y0 - y2) / den if den != 0 else 0.0
        return float(heel_deg[j] + off * (heel_deg[1] - heel_deg[0]))
    return float(heel_deg[j])


def critical_gm(sec: Sections, volume, lcg, km, angle_deg=30.0, gm_min=0.2) -> tuple[float, float]:
    """(GM_cr, KG_cr): the KG that puts the calm-water GZ maximum at ``angle_deg``, but GM >= gm_min.

    The angle of maximum falls as KG rises, so the KG is found by bisection between KG = 0 and the
    KG giving GM = gm_min.
    """
    heel = np.arange(0.0, 90.01, 0.5)

    def phimax(kg):
        return heel_of_gz_max(gz_curve(sec, volume, lcg, kg, heel)["gz"].values, heel)

    hi = km - gm_min
    if phimax(hi) >= angle_deg:  # the 30 deg KG would give GM below the minimum
        return gm_min, hi
    lo = 0.0
    if phimax(lo) <= angle_deg:
        return km - lo, lo
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if phimax(mid) > angle_deg:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-4:
            break
    kg = 0.5 * (lo + hi)
    return km - kg, kg


def time_below(gm_samples: np.ndarray, level: float, wavelength: float, rel_speed: float) -> float:
    """Time [s] per wave passage with GM below ``level`` (eq. 7).

    ``gm_samples`` are GM at crest positions equally spaced over one wavelength (GM(x_c) is
    periodic in x_c with period lambda); the length of crest travel with GM < level is found by
    linear interpolation between samples, then divided by the crest's speed relative to the ship.
    """
    g = np.append(gm_samples, gm_samples[0]) - level
    n = len(gm_samples)
    frac = 0.0
    for m in range(n):
        a, b = g[m], g[m + 1]
        if a < 0 and b < 0:
            frac += 1.0
        elif a < 0 <= b:
            frac += a / (a - b)
        elif b < 0 <= a:
            frac += b / (b - a)
    return frac / n * wavelength / rel_speed


def assess(sec: Sections, ship: Particulars, sea_states, cfg) -> xr.Dataset:
    """Metric C for every sea state in ``sea_states`` (list of dicts name, hs, tm) for the ship's
    upright particulars ``ship``.

    ``cfg["loading_kg"]``: "critical" (the paper's Table 1: "the values of KG for all the ships
    were set for critical angle of the maximum of 30 degrees", so calm-water GM = GM_cr and every
    wave that lowers GM counts) or "actual" (GM(x_c) at the ship's own KG against GM_cr).

    ``cfg`` keys: speed_kn, critical_angle, gm_min, n_amplitudes, n_wavenumbers,
    min_wavelength_ratio, amplitude_max_sigma, breaking_steepness, crest_positions, spectrum,
    min_relative_speed.
    """
    volume, lcg, kg, km, lwl, bwl = ship.volume, ship.lcg, ship.kg, ship.km, ship.lwl, ship.bwl
    gm_cr, kg_cr = critical_gm(sec, volume, lcg, km, cfg["critical_angle"], cfg["gm_min"])
    t_phi = 0.8 * bwl / np.sqrt(gm_cr)
    kg_pass = kg_cr if cfg["loading_kg"] == "critical" else kg
    vs = cfg["speed_kn"] * KNOT
    kmax = 2 * np.pi / (cfg["min_wavelength_ratio"] * lwl)
    k_edges = np.linspace(0.0, kmax, cfg["n_wavenumbers"] + 1)
    kc = 0.5 * (k_edges[1:] + k_edges[:-1])
    nx = cfg["crest_positions"]
    rows = []
    for ss in sea_states:
        S = spectrum(cfg["spectrum"], ss["hs"], ss["tm"])
        sigma, k1, k2 = wave_statistics(S, 2 * np.pi / ss["tm"])
        a_edges = np.linspace(0.0, cfg["amplitude_max_sigma"] * sigma, cfg["n_amplitudes"] + 1)
        ac = 0.5 * (a_edges[1:] + a_edges[:-1])
        W = weights(a_edges, k_edges, sigma, k1, k2)
        tbc = np.zeros_like(W)
        for j, k in enumerate(kc):
            lam = 2 * np.pi / k
            c = np.sqrt(G / k)
            rel = max(abs(c - vs), cfg["min_relative_speed"])  # following seas
            guess = (None, None)
            for i, a in enumerate(ac):
                amp = min(a, 0.5 * cfg["breaking_steepness"] * lam)  # no wave steeper than breaking
                gms = []
                for x in np.arange(nx) * lam / nx:
                    g, _, _, guess = wave_gm(sec, volume, lcg, kg_pass, amp, k, x, guess)
                    gms.append(g)
                tbc[i, j] = time_below(np.array(gms), gm_cr, lam, rel)
        m_tbc = float((tbc * W).sum())
        rows.append(dict(hs=ss["hs"], tm=ss["tm"], sigma_zeta=sigma, k1=k1, k2=k2, weight_sum=float(W.sum()),
                         mean_tbc=m_tbc, metric_c=m_tbc / t_phi))
    ds = xr.Dataset(
        {key: ("sea_state", [r[key] for r in rows]) for key in rows[0]},
        coords={"sea_state": [s["name"] for s in sea_states]},
    )
    ds["gm_cr"] = gm_cr
    ds["kg_cr"] = kg_cr
    ds["roll_period"] = t_phi
    ds.attrs.update(loading_kg=cfg["loading_kg"], speed_kn=cfg["speed_kn"], critical_angle_deg=cfg["critical_angle"], heading="following seas",
                    spectrum=cfg["spectrum"])
    return annotate(ds)
