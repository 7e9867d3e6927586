"""Surface-pressure-integration reference (stabflow.dynamics.pressure): the waterline options."""

import numpy as np
import pytest
import trimesh

from stabflow.constants import G
from stabflow.dynamics.pressure import PressureModel
from stabflow.waves.synthesis import regular

RHO = 1025.0
L, B, T = 100.0, 20.0, 6.0
# a box of length L, beam B and depth 12 m, keel on z = 0, panels of 1 m
_BOX = trimesh.creation.box(extents=[L, B, 12.0])
_BOX.apply_translation([0.0, 0.0, 6.0])
VERTS, FACES = trimesh.remesh.subdivide_to_size(_BOX.vertices, _BOX.faces, max_edge=1.0)


def heave_force_amplitude(model, we, n=32):
    """First-harmonic amplitude of Fz on the box held upright at draft T [N]."""
    t = np.arange(n) * (2 * np.pi / we) / n
    fz = np.array([model.loads(tt, -T, 0.0, 0.0)[2] for tt in t])
    return abs(2 * np.mean(fz * np.exp(1j * we * t)))


@pytest.mark.parametrize("beta", [45.0, 90.0])
def test_box_heave_force_exact_and_planar_in_closed_form(beta):
    """Wall-sided box, decay off: Fz = rho g int int eta dA over the waterplane, i.e.
    rho g a L B sinc(k_x L / 2) sinc(k_y B / 2) with the exact wave surface and without the second
    sinc with the planar waterline (the cross-beam integral of cos(psi0) - k_y y sin(psi0) is B cos(psi0))."""
    lam, H = 150.0, 1.0
    W = regular(H, lam)
    we = float(W[1][0])
    k = we**2 / G
    kx, ky = k * np.cos(np.radians(beta)), k * np.sin(np.radians(beta))
    sinc = lambda u: np.sinc(u / np.pi)  # noqa: E731 - sin(u) / u
    base = RHO * G * 0.5 * H * L * B * sinc(kx * L / 2)
    exact = PressureModel(VERTS, FACES, RHO, 0.0, 4.0, W, beta, 0.0)
    planar = PressureModel(VERTS, FACES, RHO, 0.0, 4.0, W, beta, 0.0, waterline="planar")
    # panels of 1 m: the pressure is linear between vertices, so the chord error is (k_y 1 m)^2 / 12
    assert heave_force_amplitude(exact, we) == pytest.approx(base * sinc(ky * B / 2), rel=2e-4)
    assert heave_force_amplitude(planar, we) == pytest.approx(base, rel=2e-4)


def test_planar_equals_exact_in_head_and_following_waves():
    """With k_y = 0 the planar waterline is the exact surface: the loads agree to round-off."""
    W = regular(2.0, 80.0)
    for beta in (0.0, 180.0):
        a = PressureModel(VERTS, FACES, RHO, 0.0, 4.0, W, beta, 0.0)
        b = PressureModel(VERTS, FACES, RHO, 0.0, 4.0, W, beta, 0.0, waterline="planar")
        for t, phi in ((0.0, 0.0), (3.1, 0.1), (5.0, -0.2)):
            fa, fb = a.loads(t, -T, phi, 0.02), b.loads(t, -T, phi, 0.02)
            assert np.allclose(fa, fb, rtol=1e-12, atol=1e-9 * np.abs(fa).max())


def test_unknown_waterline_is_refused():
    with pytest.raises(ValueError, match="waterline"):
        PressureModel(VERTS, FACES, RHO, 0.0, 4.0, regular(1.0, 50.0), 45.0, 0.0, waterline="curved")
