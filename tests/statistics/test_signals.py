"""Signal tools: crossings, envelope, decorrelation time, peaks against exact answers."""

import numpy as np
import pytest
import xarray as xr

from stabflow.statistics.signals import crossings, decorrelation_time, envelope, local_peaks


def test_parabolic_peak_of_a_sampled_parabola_is_exact():
    """A sampled parabola's peak (off the sample grid) is recovered exactly; the floor filters."""
    t = np.arange(0.0, 10.0, 0.5)
    x = 3.0 - (t - 4.2) ** 2
    tp, vp = local_peaks(t, x, -np.inf)
    assert tp == pytest.approx([4.2]) and vp == pytest.approx([3.0])
    assert len(local_peaks(t, x, 3.5)[0]) == 0


def test_crossing_of_a_sinusoid_is_exact():
    """x = A sin(w t): up-crossing of level c at t* = asin(c / A) / w with rate A w cos(w t*); linear
    interpolation on a fine grid recovers both to O(dt^2)."""
    A, w, c = 10.0, 0.5, 5.0
    t = np.arange(0, 40.0, 0.001)
    tc, rc, n = crossings(t, A * np.sin(w * t), A * w * np.cos(w * t), c)
    ts = np.arcsin(c / A) / w
    assert tc[0] == pytest.approx(ts, abs=1e-7)
    assert rc[0] == pytest.approx(A * w * np.cos(w * ts), rel=1e-6)
    assert len(tc) == 4 and np.diff(tc) == pytest.approx(2 * np.pi / w, abs=1e-7)


def test_envelope_of_sinusoid_is_its_amplitude():
    """100 whole periods: the Hilbert envelope is the amplitude to round-off."""
    t = np.arange(0, 2000.0, 0.5)
    x = 7.0 * np.cos(2 * np.pi / 20.0 * t + 0.3)
    assert np.max(np.abs(envelope(x) - 7.0)) < 1e-9


def test_decorrelation_time_of_damped_cosine():
    """acf = exp(-a t) cos(w t): envelope exp(-a t) falls below 0.05 at ln(20) / a."""
    lag = np.arange(0, 300.0, 0.5)
    a = 0.05
    acf = xr.DataArray(np.exp(-a * lag) * np.cos(0.5 * lag), coords={"lag": lag}, dims="lag")
    assert decorrelation_time(acf) == pytest.approx(np.log(20) / a, abs=1.5)
