"""Wave spectra S(omega) [m^2 s] (one-sided, per rad/s) and their moments.

Bretschneider is paper 004 eq. 20: S = 486.0 H^2 T0^-4 w^-5 exp(-1948.18 T0^-4 w^-4), i.e.
(5/16) Hs^2 wm^4 w^-5 exp(-5/4 (wm/w)^4) with the modal frequency wm = 2 pi / T0.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

from stabflow.constants import G


def bretschneider(omega, hs: float, tm: float):
    """Two-parameter Bretschneider spectrum [m^2 s] for Hs [m] and modal period Tm [s]."""
    w = np.asarray(omega, dtype=float)
    wm = 2 * np.pi / tm
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        s = 5.0 / 16.0 * hs**2 * wm**4 / w**5 * np.exp(-1.25 * (wm / w) ** 4)
    return np.where(w > 0, s, 0.0)


def pierson_moskowitz_modal_frequency(hs: float) -> float:
    """Modal frequency [rad/s] of the Pierson-Moskowitz spectrum for Hs [m] (paper 004 eq. 22):
    Hs = 4 sqrt(m0) with m0 = alpha g^2 / (5 wm^4), alpha = 0.0081."""
    return (16 * 0.0081 * G**2 / (5 * hs**2)) ** 0.25


def pierson_moskowitz(omega, hs: float):
    """Pierson-Moskowitz spectrum alpha g^2 w^-5 exp(-5/4 (wm/w)^4), alpha = 0.0081 (paper 004
    eqs 21-22)."""
    return bretschneider(omega, hs, 2 * np.pi / pierson_moskowitz_modal_frequency(hs))


def _jonswap_shape(w, tm, gamma):
    wm = 2 * np.pi / tm
    sig = np.where(w <= wm, 0.07, 0.09)
    return bretschneider(w, 1.0, tm) * gamma ** np.exp(-((w - wm) ** 2) / (2 * sig**2 * wm**2))


def jonswap(omega, hs: float, tm: float, gamma: float = 3.3):
    """JONSWAP spectrum: Bretschneider shape times gamma^r (sigma 0.07 / 0.09), rescaled so that
    4 sqrt(m0) = Hs (m0 integrated on a fine grid from 0.2 to 10 times the peak frequency)."""
    wm = 2 * np.pi / tm
    grid = np.linspace(0.2 * wm, 10 * wm, 20001)
    m0 = np.trapezoid(_jonswap_shape(grid, tm, gamma), grid)
    return _jonswap_shape(np.asarray(omega, dtype=float), tm, gamma) * hs**2 / (16 * m0)


def spectrum(kind: str, hs: float, tm: float | None = None, gamma: float = 3.3):
    """Return S(omega) as a callable for ``kind`` in {bretschneider, pierson_moskowitz, jonswap}."""
    if kind == "bretschneider":
        return lambda w: bretschneider(w, hs, tm)
    if kind == "pierson_moskowitz":
        return lambda w: pierson_moskowitz(w, hs)
    if kind == "jonswap":
        return lambda w: jonswap(w, hs, tm, gamma)
    raise ValueError(f"unknown spectrum {kind!r}")


def cutoff_frequencies(S, w_peak: float, ratio: float = 1e-3) -> tuple[float, float]:
    """Lowest and highest frequencies where S falls to ``ratio`` of its peak (paper 004 eqs 23, 28)."""
    s0 = float(S(w_peak))
    lo = brentq(lambda w: float(S(w)) - ratio * s0, 1e-3 * w_peak, w_peak)
    hi = brentq(lambda w: float(S(w)) - ratio * s0, w_peak, 100 * w_peak)
    return lo, hi


def spectral_moments(S, w_lo: float, w_hi: float, orders=(0, 1, 2, 4)) -> dict[int, float]:
    """m_n = int w^n S(w) dw over [w_lo, w_hi]."""
    return {n: quad(lambda w: w**n * float(S(w)), w_lo, w_hi, limit=400)[0] for n in orders}
