"""Spectra: closed forms and moments."""

import numpy as np
import pytest

from stabflow.waves.spectra import bretschneider, cutoff_frequencies, spectral_moments, spectrum


@pytest.mark.parametrize("hs,tm", [(1.25, 8.8), (5.0, 12.4), (11.5, 16.4)])
def test_bretschneider_matches_lamp_eq20_and_hs(hs, tm):
    w = np.linspace(0.2, 3.0, 50)
    lamp = 486.0 * hs**2 * tm**-4 * w**-5 * np.exp(-1948.18 * tm**-4 * w**-4)
    # LAMP rounds the coefficient (5/16)(2 pi)^4 = 487.05 to 486.0: 0.2 % apart
    assert np.allclose(bretschneider(w, hs, tm), lamp * 487.0454 / 486.0, rtol=1e-4)
    S = spectrum("bretschneider", hs, tm)
    m0 = spectral_moments(S, 1e-3, 50.0, orders=(0,))[0]
    assert 4 * np.sqrt(m0) == pytest.approx(hs, rel=1e-4)
    w = np.linspace(0.05, 3, 20001)
    assert 2 * np.pi / w[np.argmax(bretschneider(w, hs, tm))] == pytest.approx(tm, rel=1e-3)


def test_cutoffs_are_one_per_mille_of_peak():
    S = spectrum("bretschneider", 5.0, 12.4)
    wp = 2 * np.pi / 12.4
    lo, hi = cutoff_frequencies(S, wp)
    assert float(S(lo)) == pytest.approx(1e-3 * float(S(wp)))
    assert float(S(hi)) == pytest.approx(1e-3 * float(S(wp)))
    assert lo < wp < hi


def test_jonswap_and_pm():
    J = spectrum("jonswap", 5.0, 12.4, gamma=3.3)
    m0 = spectral_moments(J, 0.05, 20.0, orders=(0,))[0]
    assert 4 * np.sqrt(m0) == pytest.approx(5.0, rel=2e-3)
    wp = 2 * np.pi / 12.4
    assert float(J(wp)) / float(bretschneider(wp, 5.0, 12.4)) > 1.5  # peak enhancement
    P = spectrum("pierson_moskowitz", 11.5)
    m0 = spectral_moments(P, 0.01, 20.0, orders=(0,))[0]
    assert 4 * np.sqrt(m0) == pytest.approx(11.5, rel=1e-4)
    with pytest.raises(ValueError):
        spectrum("nope", 1.0, 1.0)
