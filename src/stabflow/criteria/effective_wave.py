"""Grim's effective wave: the regular wave of the ship's length that stands for an irregular sea in
the stability-in-waves checks (second-generation level 2 of pure loss of stability and parametric
rolling), and what the ship's stability does on it, sea state by sea state of a scatter table.

The effective wave is the least-squares fit of a cosine of length L with its crest (or trough)
amidships to the wave profile over the ship's length, -L/2 <= x <= L/2:

    h(t) = (2 / L) int eta(x, t) cos(2 pi x / L) dx.

For one component a cos(k x - w t + e) this is a cos(w t - e) F(k), and the integral gives

    F = 2 u sin(u) / (pi^2 - u^2),   u = k L / 2 = w^2 L / (2 g)  (deep water),

with F = 1 at lambda = L (u = pi) and F -> 0 for long and short waves (deep water; the sine part
of the profile is odd about midships and drops out of the fit). The effective amplitude of a
Gaussian sea is Gaussian with variance sigma^2 = int S(w) F(w)^2 dw. This is derived here from the
fit's definition (the product-to-sum integral of cos k x cos 2 pi x / L over the ship's length); its
agreement with the circular's formula was not checked against the circular's text (not read). The
significant effective wave height is taken as H_eff = 4 sigma (the definition Hs = 4 sqrt(m0) of a
Gaussian sea, applied to h); the circular's multiplier was not read either.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from scipy.integrate import simpson

from stabflow.constants import G

#: the significant height of a Gaussian process as a multiple of its standard deviation (Hs = 4 sqrt(m0))
SIGNIFICANT = 4.0
#: steepness H / lambda beyond which a regular wave breaks (the config schema's limit, 1/7)
BREAKING_STEEPNESS = 1.0 / 7.0


def grim_transfer(omega, length: float) -> np.ndarray:
    """Effective-wave amplitude per unit amplitude of a deep-water component of frequency ``omega``
    [rad/s] for a ship of length ``length`` [m]: F = 2 u sin u / (pi^2 - u^2), u = w^2 L / (2 g)
    (the removable singularity at u = pi, lambda = L, is F = 1)."""
    u = np.asarray(omega, float) ** 2 * length / (2 * G)
    d = math.pi**2 - u**2
    near = np.abs(u - math.pi) < 1e-6
    # at u = pi + e: 2u sin u / (pi^2 - u^2) = (2 pi + 2e) / (2 pi + e) = 1 + e / (2 pi) + O(e^2)
    safe = np.where(near, 1.0, d)
    return np.where(near, 1.0 + (u - math.pi) / (2 * math.pi), 2 * u * np.sin(u) / safe)


def projection(x, eta, length: float) -> np.ndarray:
    """The effective wave by its definition, the least-squares amplitude (2 / L) int eta cos(2 pi x / L)
    dx of profiles ``eta`` (..., len(x)) [m] sampled at ``x`` [m] over -L/2..L/2 (Simpson's rule):
    the direct route, against which :func:`grim_transfer` is checked."""
    x = np.asarray(x, float)
    return 2.0 / length * simpson(np.asarray(eta, float) * np.cos(2 * math.pi * x / length), x=x, axis=-1)


def effective_wave_std(omega, spectrum, length: float) -> float:
    """Standard deviation [m] of the effective wave amplitude: sqrt(int S F^2 dw), ``spectrum`` the
    one-sided wave spectrum [m^2 s] on the grid ``omega`` [rad/s] (Simpson's rule)."""
    w = np.asarray(omega, float)
    return float(math.sqrt(simpson(np.asarray(spectrum, float) * grim_transfer(w, length) ** 2, x=w)))


def effective_wave_heights(p: xr.DataArray, length: float, n: int = 4001) -> xr.DataArray:
    """Significant effective wave height H_eff = 4 sigma [m] of every sea state (hs, tz) of the scatter
    table ``p`` (:func:`stabflow.criteria.dsa.scatter_probabilities`): Bretschneider spectrum in
    (Hs, Tz) on the band where it is above 1e-3 of its peak, as the ensembles' seaways
    (:func:`stabflow.criteria.dsa.band_spectrum`), ``n`` points; deep water."""
    from stabflow.criteria.dsa import bretschneider_tz, spectrum_band

    out = np.empty(p.shape)
    for i, hs in enumerate(p.hs.values):
        for j, tz in enumerate(p.tz.values):
            w = np.linspace(*spectrum_band(float(hs), float(tz)), n)
            out[i, j] = SIGNIFICANT * effective_wave_std(w, bretschneider_tz(w, hs, tz), length)
    return xr.DataArray(out, dims=("hs", "tz"), coords={"hs": p.hs, "tz": p.tz}, name="ew_effective_height")


def vanishing_angle(heel, gz) -> float:
    """Angle of vanishing stability [degree] of a GZ curve ``gz`` [m] at heels ``heel`` [degree]: the
    first heel where GZ falls back to zero after its first positive stretch (linear interpolation; an
    angle of loll before that stretch does not count), the last heel if GZ stays positive, 0 if GZ is
    nowhere positive. NaN values (no equilibrium found) end the curve."""
    gz = np.asarray(gz, float)
    ok = np.isfinite(gz)
    n = len(gz) if ok.all() else int(np.argmin(ok))
    gz, heel = gz[:n], np.asarray(heel, float)[:n]
    pos = np.flatnonzero(gz > 0)
    if not len(pos):
        return 0.0
    start = int(pos[0])
    down = np.flatnonzero(gz[start:] <= 0)
    if not len(down):
        return float(heel[-1])
    b = start + int(down[0])
    a = b - 1
    return float(heel[a] + (heel[b] - heel[a]) * gz[a] / (gz[a] - gz[b]))


def stability_on_effective_waves(sec, volume: float, lcg: float, kg: float, lwl: float, heff: xr.DataArray,
                                 gm0: float, n_heights: int = 9, n_crest: int = 12,
                                 heel_deg=np.arange(0.0, 90.01, 1.0)) -> xr.Dataset:
    """GM and GZ of the ship on a regular wave lambda = L of each sea state's effective height.

    The quantities are tabulated over ``n_heights`` wave heights from 0 to the largest effective
    height (at most the steepness 1/7, beyond which a regular wave breaks) and ``n_crest`` crest
    positions over one wave length (free sinkage and trim at every point), then interpolated
    linearly in height to each sea state's H_eff. Sea states whose H_eff exceeds L/7 get NaN.

    Returns
    -------
    Dataset over (hs, tz): ``ew_gm_min``, ``ew_gm_max`` [m] (over crest positions), ``ew_delta_gm_ratio``
    [-] ((GMmax - GMmin) / 2 / GM0, parametric rolling), ``ew_heel_vanishing`` [degree] (smallest
    angle of vanishing stability over crest positions, :func:`vanishing_angle`), ``ew_gz_max`` [m]
    (smallest over crest positions of the curve's maximum, pure loss of stability); and over
    ``ew_height`` the tables they come from, with the GZ curves ``ew_table_gz`` (ew_height, ew_crest,
    ew_heel) [m] (crest positions from -L/2 over one wave length, free sinkage and trim).
    """
    from stabflow.stability_in_waves.wave_pass import wave_gm, wave_gz

    lam = lwl
    k = 2 * math.pi / lam
    top = min(float(np.nanmax(heff.values)), BREAKING_STEEPNESS * lam)
    heights = np.linspace(0.0, top, n_heights)
    xc = np.arange(n_crest) * lam / n_crest - lam / 2
    heel = np.asarray(heel_deg, float)
    gm = np.empty((n_heights, n_crest))
    vanish = np.empty((n_heights, n_crest))
    gzmax = np.empty((n_heights, n_crest))
    gzs = np.empty((n_heights, n_crest, len(heel)))
    for i, H in enumerate(heights):
        guess = (None, None)
        for j, x in enumerate(xc):
            gm[i, j], _, _, guess = wave_gm(sec, volume, lcg, kg, 0.5 * H, k, x, guess)
            gz = gzs[i, j] = wave_gz(sec, volume, lcg, kg, 0.5 * H, k, x, heel)
            gzmax[i, j] = np.nanmax(gz)
            vanish[i, j] = vanishing_angle(heel, gz)
    tab = xr.Dataset({"ew_table_gm_min": ("ew_height", gm.min(1)), "ew_table_gm_max": ("ew_height", gm.max(1)),
                      "ew_table_heel_vanishing": ("ew_height", vanish.min(1)),
                      "ew_table_gz_max": ("ew_height", gzmax.min(1)),
                      "ew_table_gz": (("ew_height", "ew_crest", "ew_heel"), gzs)},
                     coords={"ew_height": heights, "ew_crest": xc, "ew_heel": heel})
    h = heff.where(heff <= BREAKING_STEEPNESS * lam)
    at = tab.drop_vars("ew_table_gz").interp(ew_height=h)
    ds = xr.Dataset({"ew_effective_height": heff,
                     "ew_gm_min": at["ew_table_gm_min"].drop_vars("ew_height"),
                     "ew_gm_max": at["ew_table_gm_max"].drop_vars("ew_height"),
                     "ew_heel_vanishing": at["ew_table_heel_vanishing"].drop_vars("ew_height"),
                     "ew_gz_max": at["ew_table_gz_max"].drop_vars("ew_height")})
    ds["ew_delta_gm_ratio"] = (ds["ew_gm_max"] - ds["ew_gm_min"]) / 2 / gm0
    ds = ds.merge(tab)
    ds.attrs.update(ew_wave_length=lam, ew_crest_positions=n_crest)
    return ds
