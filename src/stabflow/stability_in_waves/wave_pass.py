"""Quasi-static stability in regular waves: GM and GZ as a wave crest passes (paper 002, App. 2).

For each crest position x_c the ship's sinkage and trim are solved so that the displaced volume
and the centre of buoyancy stay those of calm water (eq. A20; free trim at every heel for GZ), with
the same sectional volumes as calm water, the waterline at each station following the wave
profile (eqs A12, A18-A19). GM(x_c) = KB(x_c) + I_X(x_c)/V - KG (eqs A22-A24).
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from stabflow import StabflowError
from stabflow.hydrostatics._kernels import WORK_COLUMNS, _equilibrium, _gz_curve, _hydro_state
from stabflow.geometry import Sections
from stabflow.io import annotate
from stabflow.hydrostatics.statics import TOL, StabilityWarning


def wave_equilibrium(sec: Sections, volume, lcg, kg, amp, k, xc, guess=(None, None), heel=0.0):
    """Free-floating equilibrium on the wave eta = amp cos(k (x - xc)): (h [m], theta [rad]).

    Newton from ``guess`` (or the calm-water draft); if that stalls (very steep or long waves
    need large trims), continuation in wave amplitude from calm water in steps of 1/8.
    """
    work = np.empty((len(sec.x), WORK_COLUMNS))

    def solve(a, h0, th0):
        h, th, _, _ = _equilibrium(*sec.args(), heel, volume, lcg, kg, h0, th0, TOL, work, a, k, xc)
        V, ex, _ = _hydro_state(*sec.args(), heel, th, h, lcg, kg, work, a, k, xc)
        return h, th, abs(V - volume) <= 1e-6 * volume and abs(ex) <= 1e-5 * sec.length

    from stabflow.hydrostatics.statics import _draft_guess

    calm = _draft_guess(sec, volume)
    h0, th0 = guess if guess[0] is not None else calm
    h, th, ok = solve(amp, h0, th0)
    if not ok:
        h, th = calm
        for a in amp * np.arange(1, 9) / 8.0:
            h, th, ok = solve(a, h, th)
            if not ok:
                break
    if not ok:
        raise StabflowError(f"no equilibrium on the wave (amplitude {amp:.2f} m, k {k:.4f} rad/m, crest {xc:.1f} m)")
    return h, th


def wave_gm(sec: Sections, volume, lcg, kg, amp, k, xc, guess=(None, None)):
    """GM(x_c), KB(x_c), BM(x_c) [m] on the wave (paper 002 eqs A22-A24), and (h, theta)."""
    h, th = wave_equilibrium(sec, volume, lcg, kg, amp, k, xc, guess)
    work = np.empty((len(sec.x), WORK_COLUMNS))
    V, _, _ = _hydro_state(*sec.args(), 0.0, th, h, lcg, kg, work, amp, k, xc)
    ct, st = np.cos(th), np.sin(th)
    kb = float((work[:, 2] * sec.dx).sum() / V)
    eta = amp * np.cos(k * (sec.x * ct - xc))
    zw = (eta + st * sec.x - h) / ct  # body height of the local waterline at each station
    yw = np.array([sec.half_breadth(i, zw[i]) for i in range(len(sec.x))])
    bm = float((2.0 / 3.0 * yw**3 * sec.dx).sum()) / V
    return kb + bm - kg, kb, bm, (h, th)


def wave_gz(sec: Sections, volume, lcg, kg, amp, k, xc, heel_deg, guess=(None, None)) -> np.ndarray:
    """GZ(phi; x_c) [m] with free trim on the wave, at heels ``heel_deg`` [degree] (NaN where no
    equilibrium was found)."""
    heels = np.radians(np.asarray(heel_deg, dtype=np.float64))
    h0, th0 = wave_equilibrium(sec, volume, lcg, kg, amp, k, xc, guess, heel=float(heels[0]))
    out = np.empty((len(heels), 4))
    _gz_curve(*sec.args(), heels, volume, lcg, kg, h0, th0, TOL, out, amp, k, xc)
    # a heel whose Newton iteration ran out (99 iterations) is reported as NaN, never as a number
    return np.where(out[:, 3] < 99, out[:, 0], np.nan)


def wave_pass(sec: Sections, volume, lcg, kg, lwl, ratios, steepness, n_crest, heel_deg) -> xr.Dataset:
    """The wave-pass sweep: GM(x_c) and GZ(phi; x_c) over wave length, steepness and crest position.

    Parameters
    ----------
    sec : Sections
    volume, lcg, kg : float
        Loading [m^3, m, m].
    lwl : float
        Ship length L for lambda / L [m].
    ratios, steepness : sequence of float
        lambda / L [-] and H / lambda [-].
    n_crest : int
        Crest positions, equally spaced from the aft to the forward end of L (crest amidships in the
        middle when odd).
    heel_deg : array
        Heels of the GZ curves [degree].
    """
    xc = np.linspace(-0.5 * lwl, 0.5 * lwl, n_crest)
    gm = np.empty((len(ratios), len(steepness), n_crest, 3))
    gz = np.empty((len(ratios), len(steepness), n_crest, len(heel_deg)))
    for a, r in enumerate(ratios):
        lam = r * lwl
        k = 2 * np.pi / lam
        for b, s in enumerate(steepness):
            amp = 0.5 * s * lam
            guess = (None, None)
            for c, x in enumerate(xc):
                g, kb, bm, guess = wave_gm(sec, volume, lcg, kg, amp, k, x, guess)
                gm[a, b, c] = g, kb, bm
                gz[a, b, c] = wave_gz(sec, volume, lcg, kg, amp, k, x, heel_deg, guess)
    ds = xr.Dataset(
        {
            "gm_wave": (("wavelength_ratio", "steepness", "crest_position"), gm[..., 0]),
            "kb_wave": (("wavelength_ratio", "steepness", "crest_position"), gm[..., 1]),
            "bm_wave": (("wavelength_ratio", "steepness", "crest_position"), gm[..., 2]),
            "gz_wave": (("wavelength_ratio", "steepness", "crest_position", "heel"), gz),
        },
        coords={"wavelength_ratio": np.asarray(ratios, float), "steepness": np.asarray(steepness, float),
                "crest_position": xc, "heel": np.asarray(heel_deg, float)},
    )
    _flag_unconverged(ds, ["gz_wave"])
    return annotate(ds)


def _flag_unconverged(ds: xr.Dataset, names) -> None:
    """Count GZ points without an equilibrium (NaN), store the count as ``unconverged_points`` and
    warn: such points are never silent (the validation rows that read them FAIL)."""
    bad = sum(int(ds[n].isnull().sum()) for n in names)
    ds.attrs["unconverged_points"] = bad
    if bad:
        warnings.warn(f"no equilibrium on the wave at {bad} GZ points ({', '.join(names)} are NaN there)",
                      StabilityWarning, stacklevel=3)


def crest_trough_calm(sec: Sections, volume, lcg, kg, lwl, steepness, heel_deg) -> xr.Dataset:
    """GZ on a crest amidships, a trough amidships and calm water, for lambda = L at ``steepness``."""
    lam = lwl
    k = 2 * np.pi / lam
    amp = 0.5 * steepness * lam
    ds = xr.Dataset(
        {
            "gz_crest": ("heel", wave_gz(sec, volume, lcg, kg, amp, k, 0.0, heel_deg)),
            "gz_trough": ("heel", wave_gz(sec, volume, lcg, kg, amp, k, 0.5 * lam, heel_deg)),
            "gz_calm": ("heel", wave_gz(sec, volume, lcg, kg, 0.0, k, 0.0, heel_deg)),
        },
        coords={"heel": np.asarray(heel_deg, float)},
        attrs={"crest_trough_steepness": steepness},
    )
    _flag_unconverged(ds, ["gz_crest", "gz_trough", "gz_calm"])
    return annotate(ds)
