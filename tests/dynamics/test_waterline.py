"""The curved waterline across each section (``waterline="curved"``, stabflow.dynamics._kernels)."""

import numpy as np
import pytest

from stabflow.dynamics import simulate
from stabflow.dynamics.linear import KernelLoads, fk_excitation
from stabflow.hydrostatics.statics import equilibrium
from stabflow.waves.synthesis import regular


def _rest(sec, st):
    h0, th0, _ = equilibrium(sec, float(st.volume), float(st.lcg), float(st.kg))
    return h0, th0


@pytest.mark.parametrize("beta", [45.0, 90.0])
def test_box_heave_force_is_the_quadratic_cross_beam_integral(barge, beta):
    """Wall-sided box held upright: the curved waterline's layer is int C2 y^2 / 2 dy over the
    beam, so the vertical FK force is the planar one times 1 - u^2 / 6, u = k_y B / 2, to round-off
    (the same stations carry both); the exact surface's factor is sinc(u), u^4 / 120 away."""
    ship, sec, st, co = barge
    h0, th0 = _rest(sec, st)
    lam = 150.0
    W = regular(1.0, lam)
    we = float(W[1][0])
    k = 2 * np.pi / lam
    u = k * np.sin(np.radians(beta)) * 0.5 * sec.breadth
    f = {wl: fk_excitation(KernelLoads(sec, ship.rho, float(st.lcg), float(st.kg), W, beta, waterline=wl), h0, th0, we)
         for wl in ("planar", "curved")}
    assert abs(f["curved"][0]) / abs(f["planar"][0]) == pytest.approx(1 - u**2 / 6, rel=1e-9)


def test_head_and_following_seas_equal_the_planar_waterline(barge):
    """k_y = 0: no curvature across the beam, the same loads (heeled, trimmed, any instant)."""
    ship, sec, st, co = barge
    h0, th0 = _rest(sec, st)
    W = regular(3.0, 80.0)
    for beta in (0.0, 180.0):
        a = KernelLoads(sec, ship.rho, float(st.lcg), float(st.kg), W, beta)
        b = KernelLoads(sec, ship.rho, float(st.lcg), float(st.kg), W, beta, waterline="curved")
        for t, phi in ((0.0, 0.0), (2.5, 0.2), (4.0, -0.4)):
            fa, fb = a.loads(t, h0, phi, th0 + 0.01), b.loads(t, h0, phi, th0 + 0.01)
            assert np.allclose(fa, fb, rtol=1e-12, atol=1e-12 * np.abs(fa).max())


def test_records_carry_the_option(barge):
    """A record states its waterline, the curved one moves heave in a quartering wave (its vertical
    force is 1 - u^2 / 6 of the planar one), and an unknown waterline is refused."""
    ship, sec, st, co = barge
    W = regular(2.0, 100.0)
    rec = {wl: simulate(sec, st, co, ship.rho, W, 45.0, 0.0, 60.0, 0.1, waterline=wl) for wl in ("planar", "curved")}
    assert rec["curved"].attrs["waterline"] == "curved" and rec["planar"].attrs["waterline"] == "planar"
    hp, hc = (float(np.ptp(rec[w]["heave"].values[300:])) for w in ("planar", "curved"))
    assert 0.9 < hc / hp < 0.99
    with pytest.raises(ValueError, match="waterline"):
        simulate(sec, st, co, ship.rho, W, 45.0, 0.0, 1.0, 0.1, waterline="exact")
