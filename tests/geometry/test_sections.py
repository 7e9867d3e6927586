"""Sections and Bonjean tables against exact geometry."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stabflow.geometry._kernels import _clip_half, _section
from stabflow.config import load_ship
from stabflow.geometry import build_hull
from stabflow.geometry.sections import apply_topside, bonjean, loop_contour, simplify

from ..conftest import SHIPS

BOX = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 12.0], [0.0, 12.0]])


def test_bonjean_box_exact():
    """Half-box Bonjean table: area 10 z, moment about CL 50 z, about baseline 5 z^2."""
    b = bonjean(BOX)
    z = BOX[:, 1]
    assert np.allclose(b[:, 0], 10 * z)
    assert np.allclose(b[:, 1], 50 * z)
    assert np.allclose(b[:, 2], 5 * z * z)


@settings(max_examples=200, deadline=None)
@given(phi=st.floats(-np.pi, np.pi), c=st.floats(-15, 15))
def test_clip_matches_shapely(phi, c):
    """Clipped section area and centroid equal shapely's polygon intersection for any heel."""
    from shapely.geometry import Polygon

    full = Polygon([(-10, 0), (10, 0), (10, 12), (-10, 12)])
    a, b = np.sin(phi), np.cos(phi)
    ys, zs = BOX[:, 0].copy(), BOX[:, 1].copy()
    A, Sy, Sz = _section(ys, zs, 4, a, b, c)
    # half plane a y + b z <= c as a big polygon
    d = np.array([b, -a]) * 1e3
    p0 = np.array([a, b]) * c
    n = np.array([a, b])
    half = Polygon([p0 + d, p0 + d - 1e3 * n, p0 - d - 1e3 * n, p0 - d])
    ref = full.intersection(half)
    assert A == pytest.approx(ref.area, abs=1e-9)
    if ref.area > 1e-6:
        assert Sy / A == pytest.approx(ref.centroid.x, abs=1e-7)
        assert Sz / A == pytest.approx(ref.centroid.y, abs=1e-7)


def test_loop_contour_cambered_deck_and_open_section():
    """A closed loop with a cambered deck is followed exactly; an open U is closed by its deck line."""
    loop = np.array([[0, 0], [5, 0], [5, 4], [0, 4.5], [-5, 4], [-5, 0]], float)
    c = loop_contour([loop], 0.0)
    assert c[0].tolist() == [0, 0] and c[-1].tolist() == [0, 4.5]
    area = _clip_half(np.ascontiguousarray(c[:, 0]), np.ascontiguousarray(c[:, 1]), len(c), 0.0, 1.0, 100.0)[0]
    assert area == pytest.approx(5 * 4 + 0.5 * 5 * 0.5)
    open_u = np.array([[-5, 4], [-5, 0], [5, 0], [5, 4]], float)
    c = loop_contour([open_u], 0.0)
    area = _clip_half(np.ascontiguousarray(c[:, 0]), np.ascontiguousarray(c[:, 1]), len(c), 0.0, 1.0, 100.0)[0]
    assert area == pytest.approx(20.0)


def test_simplify_keeps_corners():
    pts = np.array([[0, 0], [1, 0], [2, 0], [2, 1], [2, 2]], float)
    assert simplify(pts, 1e-9).tolist() == [[0, 0], [2, 0], [2, 2]]


def test_topside_flare_and_tumblehome():
    c = np.array([[0, 0], [5, 0], [5, 10], [0, 10]], float)
    fl = apply_topside(c, 6.0, 10.0)
    th = apply_topside(c, 6.0, -10.0)
    assert fl[-2, 0] == pytest.approx(5 + 4 * np.tan(np.radians(10)))
    assert th[-2, 0] == pytest.approx(5 - 4 * np.tan(np.radians(10)))
    assert fl[-1].tolist() == [0, 10]


def test_wigley_sections_converge_to_analytic_volume():
    ds = build_hull(load_ship(SHIPS / "wigley.yaml"))
    L, B, D, T = 100.0, 10.0, 10.0, 6.25
    # hull to the deck: underwater 4/9 LBT plus wall-sided part (D - T) * B * 2L/3
    ref = 4 / 9 * L * B * T + (D - T) * B * 2 * L / 3
    assert float(ds.hull_volume) == pytest.approx(ref, rel=5e-4)  # README: Wigley within 0.05 % (measured -0.011 %)
    assert ds["bonjean_area"].attrs["units"] == "m2"


def _ring_moments(c):
    """Shoelace area, first and second moments of a closed ring (counter-clockwise), written out
    independently of the clipping kernel."""
    y, z, y1, z1 = c[:-1, 0], c[:-1, 1], c[1:, 0], c[1:, 1]
    cr = y * z1 - y1 * z
    return np.array([cr.sum() / 2, ((y + y1) * cr).sum() / 6, ((z + z1) * cr).sum() / 6,
                     ((y * y + y * y1 + y1 * y1) * cr).sum() / 12,
                     ((y * z1 + 2 * y * z + 2 * y1 * z1 + y1 * z) * cr).sum() / 24,
                     ((z * z + z * z1 + z1 * z1) * cr).sum() / 12])


def test_section_moments_against_shapely_clipping():
    """_section_moments (area, first and second moments of the wet section and int s^k ds over the
    waterline's wet chords) against shapely's clip of the full section polygon and its cut of the
    line: DTMB 5415 stations and the trawler's stern stations, whose waterline crosses the hull four
    times at large heel (the gap between the chords is left out), heel up to 57 deg."""
    from shapely.geometry import LineString, Polygon
    from shapely.geometry.polygon import orient

    from stabflow.geometry import Sections
    from stabflow.geometry._kernels import _section_moments

    rng = np.random.default_rng(5)
    multi = 0
    checked = 0
    for name, stations, heel in (("dtmb5415", (10, 50, 90), 1.0), ("trawler", (6, 9, 12), 1.0)):
        sec = Sections(build_hull(load_ship(SHIPS / f"{name}.yaml")))
        for i in stations:
            n = sec.n[i]
            y, z = sec.y[i, :n], sec.z[i, :n]
            full = Polygon(np.concatenate([np.column_stack([y, z]), np.column_stack([-y[::-1], z[::-1]])])).buffer(0)
            # random lines, and (trawler) low heeled ones through the deadwood and the bottom apart
            lines = [(rng.uniform(-heel, heel), rng.uniform(0.2, 0.8)) for _ in range(8)]
            if name == "trawler":
                lines += [(0.35, 0.25), (0.35, 0.3), (0.4, 0.2), (-0.35, 0.25)]
            for psi, f in lines:
                a, b = np.sin(psi), np.cos(psi)
                c = f * (abs(a) * y.max() + b * z.max())
                tdir, nvec = np.array([b, -a]), np.array([a, b])
                base = c * nvec
                half = Polygon([base + 1e3 * tdir, base - 1e3 * tdir, base - 1e3 * (tdir + nvec),
                                base + 1e3 * (tdir - nvec)])
                wet = full.intersection(half)
                pieces = [orient(g, 1.0) for g in getattr(wet, "geoms", [wet]) if g.geom_type == "Polygon" and g.area > 0]
                if not pieces:
                    continue
                ref = sum(_ring_moments(np.asarray(g.exterior.coords)) for g in pieces)
                got = _section_moments(y, z, n, a, b, c)
                assert np.allclose(got[:6], ref, rtol=1e-9, atol=1e-9 * abs(ref[3])), (name, i, psi)
                chords = LineString([base + 1e3 * tdir, base - 1e3 * tdir]).intersection(full)
                parts = [g for g in getattr(chords, "geoms", [chords]) if g.length > 0]
                multi += len(parts) > 1
                J = np.zeros(4)
                for g in parts:
                    s0, s1 = sorted(b * p[0] - a * p[1] for p in g.coords)
                    J += [(s1 ** (k + 1) - s0 ** (k + 1)) / (k + 1) for k in range(4)]
                assert np.allclose(got[6:], J, rtol=1e-9, atol=1e-9 * max(1.0, abs(J).max())), (name, i, psi)
                checked += 1
    assert checked >= 40 and multi >= 1
