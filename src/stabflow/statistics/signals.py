"""Signal tools for records: threshold crossings, peaks, envelope, spectra, autocorrelation time,
quantiles of histograms. Used by the ensemble statistics, the extremes and split-time steps and the
time-domain checks."""

from __future__ import annotations

import numpy as np
import xarray as xr
from scipy.signal import hilbert

SPECTRUM_SEGMENT = 512  # Welch segment length [samples]


def crossings(t, x, xdot, level: float, up: bool = True):
    """Times, rates and step indices where ``x`` crosses ``level`` upwards (or downwards), with
    linear interpolation of time and rate between the samples either side."""
    a, b = x[:-1], x[1:]
    n = np.nonzero((a < level) & (b >= level))[0] if up else np.nonzero((a > level) & (b <= level))[0]
    f = (level - a[n]) / (b[n] - a[n])
    return t[n] + f * (t[n + 1] - t[n]), xdot[n] + f * (xdot[n + 1] - xdot[n]), n


def local_peaks(t, x, floor: float):
    """Local maxima of ``x`` above ``floor``, refined by the parabola through the three samples."""
    m = np.nonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]) & (x[1:-1] > floor))[0] + 1
    y0, y1, y2 = x[m - 1], x[m], x[m + 1]
    den = y0 - 2 * y1 + y2
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.where(den != 0, 0.5 * (y0 - y2) / den, 0.0)
    dt = t[1] - t[0] if len(t) > 1 else 0.0
    return t[m] + d * dt, y1 - 0.25 * (y0 - y2) * d


def envelope(x):
    """Amplitude envelope |x + i H[x]| (Hilbert transform, scipy.signal.hilbert) of a zero-mean record."""
    return np.abs(hilbert(x - x.mean())) if len(x) > 1 else np.abs(x)


def welch_psd(x: np.ndarray, dt: float, nseg: int = SPECTRUM_SEGMENT) -> np.ndarray:
    """One-sided Welch spectra per rad/s of the rows of ``x`` (Hann window, 50 % overlap, mean
    removed per segment): the same estimate as scipy.signal.welch, vectorised over rows."""
    step = nseg // 2
    starts = np.arange(0, x.shape[1] - nseg + 1, step)
    win = np.hanning(nseg + 1)[:-1]  # periodic Hann, as scipy's default
    seg = np.stack([x[:, s: s + nseg] for s in starts], axis=1)
    seg = (seg - seg.mean(axis=-1, keepdims=True)) * win
    p = np.abs(np.fft.rfft(seg, axis=-1)) ** 2 / (np.sum(win**2) / dt)
    p[..., 1:-1] *= 2.0
    return p.mean(axis=1) / (2 * np.pi)


def quantile_from_histogram(hist: np.ndarray, centres: np.ndarray, q: float) -> float:
    """Quantile of a fixed-bin histogram by linear interpolation of its CDF."""
    w = centres[1] - centres[0]
    edges = np.concatenate([centres - 0.5 * w, [centres[-1] + 0.5 * w]])
    cdf = np.concatenate([[0.0], np.cumsum(hist)]) / max(hist.sum(), 1)
    return float(np.interp(q, cdf, edges))


def decorrelation_time(acf: xr.DataArray, level: float = 0.05) -> float:
    """Time after which the envelope of the autocorrelation stays below ``level`` (paper 003,
    section 5): the envelope is |acf + i H[acf]|; returns the first lag beyond its last exceedance."""
    a = np.nan_to_num(acf.values)
    env = np.abs(hilbert(np.concatenate([a[::-1][:-1], a])))[len(a) - 1:]
    above = np.nonzero(env >= level)[0]
    lag = acf["lag"].values
    k = min(above[-1] + 1, len(lag) - 1) if len(above) else 0
    return float(lag[k])
