"""Tabulated sectional properties against exact clipping (same kernel, two geometry routes)."""

import copy

import numpy as np
import pytest

from stabflow.geometry._kernels import _section
from stabflow.config import Ship, load_ship
from stabflow.dynamics import coefficients, simulate
from stabflow.dynamics._kernels import _section_tab
from stabflow.dynamics.tables import section_tables
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics
from stabflow.waves.seaway import Seaway

from ..conftest import SHIPS


@pytest.fixture(scope="module")
def dtmb21():
    base = load_ship(SHIPS / "dtmb5415.yaml")
    d = copy.deepcopy(base.data)
    d["hull"]["stations"] = 21
    d["dynamics"]["hydro"] = "config"
    d["dynamics"]["roll_damping"] = "coefficients"
    ship = Ship(base.name, base.path, d)
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    sec = Sections(hull)
    return ship, sec, st, coefficients(ship, sec, st)


def test_table_matches_clipping(dtmb21):
    """Random waterlines (heel -120..120 deg, any level): area within 0.3 % of the full section area,
    centroid within 2 cm, DTMB 5415 sections (bulb, transom, flare)."""
    _, sec, _, _ = dtmb21
    tb = section_tables(sec)
    rng = np.random.default_rng(0)
    worst_a = worst_c = 0.0
    for i in range(len(sec.x)):
        full = _section(sec.y[i], sec.z[i], sec.n[i], 0.0, 1.0, 1e3)[0]
        if full <= 0:
            continue
        for _ in range(200):
            psi = rng.uniform(-2.1, 2.1)
            d = rng.uniform(-5.0, 15.0)
            a, b = np.sin(psi), np.cos(psi)
            A, Sy, Sz = _section(sec.y[i], sec.z[i], sec.n[i], a, b, d)
            At, Syt, Szt = _section_tab(tb.tab, tb.lim, i, psi, d)
            worst_a = max(worst_a, abs(At - A) / full)
            if A > 0.05 * full:
                worst_c = max(worst_c, abs(Syt / At - Sy / A), abs(Szt / At - Sz / A))
    assert worst_a < 3e-3, worst_a
    assert worst_c < 0.02, worst_c


def test_tabulated_simulation_matches_exact(dtmb21):
    """30-min irregular record (SS7 stern quartering, 10 kn): roll, heave, pitch standard deviations
    from the tables within 0.2 % of exact clipping, roll extreme within 0.5 deg."""
    ship, sec, st, co = dtmb21
    W = Seaway("bretschneider", 7.0, 15.0).components(1, 0)
    a = simulate(sec, st, co, ship.rho, W, 30.0, 5.0, 1800.0, 0.25)
    b = simulate(sec, st, co, ship.rho, W, 30.0, 5.0, 1800.0, 0.25, tables=section_tables(sec))
    assert a.attrs["capsized"] == b.attrs["capsized"] == 0
    for v in ("roll", "heave", "pitch"):
        assert float(b[v].std()) == pytest.approx(float(a[v].std()), rel=2e-3)
    assert abs(float(np.abs(b["roll"]).max() - np.abs(a["roll"]).max())) < 0.5
