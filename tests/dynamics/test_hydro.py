"""Capytaine coefficients and linear peer RAOs (barge)."""

import numpy as np
import pytest

from stabflow.dynamics import coefficients
from stabflow.dynamics.hydro import bem_mesh, hydro_dataset
from stabflow.dynamics.linear import stiffness_matrix
from stabflow.hydrostatics.statics import equilibrium


@pytest.fixture(scope="module")
def hydro(barge):
    ship, sec, st, co = barge
    h0, th0, _ = equilibrium(sec, float(st.volume), 0.0, float(st.kg))
    C = stiffness_matrix(sec, ship.rho, 0.0, float(st.kg), h0, th0)
    return hydro_dataset(bem_mesh(ship), st, co, ship.rho, 45.0, 100.0, [1.0, 10.0], C, h0, th0), C


def test_coefficients_at_natural_frequencies(barge, hydro):
    ship, sec, st, co = barge
    ds, C = hydro
    for mode, j, m in [("heave", 0, co.mass), ("roll", 1, co.i44), ("pitch", 2, co.i55)]:
        a, b, w = float(ds[f"added_{mode}"]), float(ds[f"damping_{mode}"]), float(ds[f"omega_{mode}"])
        assert a > 0 and b >= 0 and np.isfinite(a + b)
        assert w == pytest.approx(np.sqrt(C[j, j] / (m + a)), rel=0.02)  # fixed point converged
    # a wide flat barge: heave added mass of the order of its mass (strip theory ~0.8-1.5)
    assert 0.5 < float(ds.added_heave) / co.mass < 2.0
    cc = coefficients(ship, sec, st, ds)
    assert cc.a33 == float(ds.added_heave) and cc.b44 > float(ds.damping_roll)  # + viscous roll damping


def test_long_wave_limit(barge, hydro):
    """lambda = 10 L: the linear BEM heave follows the wave (heave/a -> 1 times the small dynamic
    amplification)."""
    ds, _ = hydro
    assert float(ds.heave_rao.sel(wavelength_ratio=10.0)) == pytest.approx(1.0, abs=0.15)
