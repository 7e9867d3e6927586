"""Dynamics coefficients as users have them: absolute SI values or fractions, one form per quantity.

The ``dynamics`` config takes, per quantity, the absolute value (tank-test report, BEM run) or the
fractional form (radius of gyration, ratio, fraction of critical damping); both is an error naming
the file and both fields; neither gives the documented default, so the shipped ships keep their
coefficients bit for bit.
"""

import numpy as np
import pytest
import xarray as xr

from stabflow import StabflowError
from stabflow.config import load_ship, schema
from stabflow.dynamics import coefficients

from ..conftest import SHIPS
from .conftest import ship_model

#: (absolute SI key, fractional key, a valid value of each) for every quantity of the config
PAIRS = [
    ("i44", "roll_gyradius", 8.0e8, 8.0),
    ("i55", "pitch_gyradius", 7.7e9, 25.0),
    ("i66", "yaw_gyradius", 7.7e9, 25.0),
    ("a33", "added_mass_heave", 1.2e7, 1.0),
    ("a44", "added_inertia_roll", 1.6e8, 0.2),
    ("a55", "added_inertia_pitch", 7.7e9, 1.0),
    ("b33", "damping_heave", 8.9e6, 0.2),
    ("b44", "roll_damping_linear", 4.2e7, 0.05),
    ("b55", "damping_pitch", 6.3e9, 0.2),
    ("b44q", "roll_damping_quadratic", 1.0e8, 0.1),
]

SHIPPED = ["barge", "wigley", "dtmb5415", "dtmb5415_flare", "dtmb5415_tumblehome", "dtc"]


def barge_with(ship_file, barge, **dynamics):
    """The barge with ``dynamics`` in its config file (loaded and validated), and its coefficients
    on the fixture's sections and statics (the hull and loading are unchanged)."""
    _, sec, st, _ = barge
    ship = load_ship(ship_file("barge", dynamics=dynamics))
    return ship, coefficients(ship, sec, st)


def fake_hydro(mass):
    """A stand-in for the Capytaine dataset at the natural frequencies."""
    return xr.Dataset({"added_heave": mass * 0.8731, "added_roll": mass * 3.17, "added_pitch": mass * 91.3,
                       "damping_heave": mass * 0.417, "damping_roll": mass * 0.0123, "damping_pitch": mass * 2.9})


# --- absolute values and fractions -------------------------------------------------------------

def test_absolute_values_reach_coefficients_exactly(ship_file, barge):
    given = {"i44": 8.123e8, "i55": 7.71e9, "i66": 7.9e9, "a33": 1.11e7, "a44": 1.234e8, "a55": 6.5e9,
             "b33": 8.8e6, "b44": 4.321e7, "b55": 6.1e9, "b44q": 9.87e7}
    ship, co = barge_with(ship_file, barge, **given)
    for key, value in given.items():
        assert getattr(co, key) == value, key
    # scientific notation as PyYAML leaves it (a string) is read as the number
    p = ship_file("barge")
    p.write_text(p.read_text() + "dynamics:\n  i44: 8.123e8\n  b44q: 9.87E7\n")
    co2 = coefficients(load_ship(p), barge[1], barge[2])
    assert co2.i44 == 8.123e8 and co2.b44q == 9.87e7


def test_inertia_from_gyradius(ship_file, barge):
    _, co = barge_with(ship_file, barge, roll_gyradius=7.9, pitch_gyradius=24.5, yaw_gyradius=26.0)
    assert co.i44 == co.mass * 7.9**2
    assert co.i55 == co.mass * 24.5**2
    assert co.i66 == co.mass * 26.0**2
    # the same inertia given as kg m^2 gives the same coefficients
    _, co2 = barge_with(ship_file, barge, i44=co.mass * 7.9**2, i55=co.mass * 24.5**2, i66=co.mass * 26.0**2)
    assert co2 == co


def test_added_mass_absolute_vs_fraction(ship_file, barge):
    _, frac = barge_with(ship_file, barge, added_mass_heave=0.8, added_inertia_roll=0.3, added_inertia_pitch=0.9)
    assert frac.a33 == 0.8 * frac.mass and frac.a44 == 0.3 * frac.i44 and frac.a55 == 0.9 * frac.i55
    _, ab = barge_with(ship_file, barge, a33=frac.a33, a44=frac.a44, a55=frac.a55)
    assert ab.a33 == frac.a33 and ab.a44 == frac.a44 and ab.a55 == frac.a55
    # the damping (fractions of critical by default) follows the added mass either way
    assert ab == frac
    _, ab2 = barge_with(ship_file, barge, a33=2.0e7)
    assert ab2.a33 == 2.0e7 and ab2.b33 == 2 * 0.2 * np.sqrt((ab2.mass + 2.0e7) * ab2.c33)


def test_damping_absolute_vs_fraction_of_critical(ship_file, barge):
    _, frac = barge_with(ship_file, barge, roll_damping_linear=0.07, damping_heave=0.15, damping_pitch=0.25,
                         roll_damping_quadratic=0.4)
    assert frac.b44 == 2 * 0.07 * np.sqrt((frac.i44 + frac.a44) * frac.c44)
    assert frac.b33 == 2 * 0.15 * np.sqrt((frac.mass + frac.a33) * frac.c33)
    assert frac.b55 == 2 * 0.25 * np.sqrt((frac.i55 + frac.a55) * frac.c55)
    assert frac.b44q == 0.4 * (frac.i44 + frac.a44)
    # fraction of critical: zeta = B / (2 sqrt((I + A) C)) recovers what was given
    assert frac.b44 / (2 * np.sqrt((frac.i44 + frac.a44) * frac.c44)) == pytest.approx(0.07, rel=1e-14)
    _, ab = barge_with(ship_file, barge, b44=float(frac.b44), b33=float(frac.b33), b55=float(frac.b55),
                       b44q=float(frac.b44q))
    assert ab == frac
    _, ab2 = barge_with(ship_file, barge, b44=3.0e7)
    assert ab2.b44 == 3.0e7 and ab2.b33 == 2 * 0.2 * np.sqrt((ab2.mass + ab2.a33) * ab2.c33)  # default


def test_capytaine_path_with_absolute_roll_damping(ship_file, barge):
    """With the Capytaine dataset the BEM values replace added mass and radiation damping; the
    linear roll damping given (absolute or fraction) is the viscous part added to it."""
    ship, sec, st, _ = barge
    hy = fake_hydro(float(st["mass"]))
    # a33 is accepted and not used with hydro: capytaine (BEM gives it), like the fractions
    ab = load_ship(ship_file("barge", dynamics={"hydro": "capytaine", "b44": 1.5e7, "b44q": 2.0e8, "a33": 1.0}))
    co = coefficients(ab, sec, st, hy)
    assert co.a33 == float(hy.added_heave) and co.a44 == float(hy.added_roll)
    assert co.b44 == float(hy.damping_roll) + 1.5e7 and co.b44q == 2.0e8
    fr = load_ship(ship_file("barge", dynamics={"hydro": "capytaine", "roll_damping_linear": 0.06}))
    cf = coefficients(fr, sec, st, hy)
    assert cf.b44 == float(hy.damping_roll) + 2 * 0.06 * np.sqrt((cf.i44 + float(hy.added_roll)) * cf.c44)


# --- one form per quantity ----------------------------------------------------------------------

@pytest.mark.parametrize("absolute,fraction,va,vf", PAIRS)
def test_both_given_is_an_error_at_load(ship_file, absolute, fraction, va, vf):
    p = ship_file("barge", dynamics={absolute: va, fraction: vf})
    with pytest.raises(StabflowError) as e:
        load_ship(p)
    msg = str(e.value)
    assert msg.startswith(f"{p}: dynamics")
    assert absolute in msg and fraction in msg


@pytest.mark.parametrize("absolute,fraction,va,vf", PAIRS)
def test_both_given_is_an_error_in_coefficients(barge, absolute, fraction, va, vf):
    """Overrides (ensemble conditions, Ship.modified) skip the schema: coefficients() checks."""
    ship, sec, st, _ = barge
    with pytest.raises(StabflowError) as e:
        coefficients(ship.modified(dynamics={absolute: va, fraction: vf}), sec, st)
    assert str(e.value) == f"{ship.path}: dynamics.{absolute} and dynamics.{fraction}: give one, not both"


def test_every_dynamics_key_documented():
    props = schema("ship")["properties"]["dynamics"]["properties"]
    paired = {k for a, f, _, _ in PAIRS for k in (a, f)}
    for key, sub in props.items():
        d = sub["description"]
        if sub.get("type") == "number":
            assert "[" in d and "]" in d, f"{key}: no unit"
        if key in paired:
            assert "default" not in sub, f"{key}: a schema default would hide a both-given config"
    for a, f, _, _ in PAIRS:
        assert a in props and f in props
        assert "Default (neither given)" in props[f]["description"]


# --- the trawler: the published tank-test numbers -----------------------------------------------

@pytest.fixture(scope="module")
def trawler():
    return ship_model("trawler")


def test_trawler_coefficients_are_the_published_ones(trawler):
    ship, sec, st, co = trawler
    assert co.mass == pytest.approx(253.31e3, rel=1e-12)  # mass = rho V after the equilibrium solve
    assert float(st.lcg) == -0.810 and float(st.kg) == 3.467986
    assert (co.i44, co.i55, co.i66) == (1.522e6, 8.279e6, 7.676e6)
    assert (co.a33, co.a44, co.a55) == (1.980e5, 3.189e5, 8.866e6)
    assert (co.b33, co.b44, co.b55, co.b44q) == (1.9e5, 1.74e4, 4.67e6, 1.45e6)
    # restoring from the statics: C44 = rho g V GM cos(trim), roll being about the trimmed body x-axis
    ct = np.cos(np.radians(float(st.trim_upright)))
    assert co.c44 == pytest.approx(ship.rho * 9.80665 * float(st.volume) * float(st.gm) * ct, rel=1e-6)
    assert 6.0 < co.natural_period("roll") < 6.6


# --- shipped ships: the documented defaults, bit for bit ------------------------------------------

@pytest.fixture(scope="module", params=SHIPPED)
def shipped(request):
    return ship_model(request.param)[:3]


def test_shipped_ships_keep_the_default_coefficients(shipped):
    ship, sec, st = shipped
    if ship.data["dynamics"]["roll_damping"] == "ikeda":  # dtmb5415: roll damping tested below
        ship = ship.modified(dynamics={"roll_damping": "coefficients"})
    co = coefficients(ship, sec, st)
    m, L, B = float(st["mass"]), float(st["lwl"]), float(st["bwl"])
    # no coefficient given but DTMB 5415's published roll radius of gyration: every default applies
    given = {"roll_gyradius"} if ship.name == "dtmb5415" else set()
    assert set(ship.data["dynamics"]) == {"hydro", "roll_damping", "ikeda_amplitude_deg", "ikeda_normal_force",
                                          "decay_heel_deg", "diffraction"} | given
    assert co.mass == m
    kxx = 7.363 if given else 0.40 * B  # Araki, Ohashi & Hirata, ISSW 2014, Table 1: 0.158 m x 46.6
    assert co.i44 == m * kxx ** 2 and co.i55 == m * (0.25 * L) ** 2 and co.i66 == m * (0.25 * L) ** 2
    assert co.a33 == 1.0 * m and co.a44 == 0.2 * co.i44 and co.a55 == 1.0 * co.i55
    assert co.b33 == 2 * 0.2 * np.sqrt((co.mass + co.a33) * co.c33)
    assert co.b44 == 2 * 0.05 * np.sqrt((co.i44 + co.a44) * co.c44)
    assert co.b55 == 2 * 0.2 * np.sqrt((co.i55 + co.a55) * co.c55)
    assert co.b44q == 0.0
    # Capytaine path: BEM added mass and radiation damping, default viscous roll damping on top
    hy = fake_hydro(m)
    ch = coefficients(ship, sec, st, hy)
    assert (ch.a33, ch.a44, ch.a55) == (float(hy.added_heave), float(hy.added_roll), float(hy.added_pitch))
    assert (ch.b33, ch.b55) == (float(hy.damping_heave), float(hy.damping_pitch))
    assert ch.b44 == float(hy.damping_roll) + 2 * 0.05 * np.sqrt((co.i44 + float(hy.added_roll)) * co.c44)
    assert ch.b44q == 0.0 and (ch.i44, ch.i55, ch.c44) == (co.i44, co.i55, co.c44)


# --- roll damping from the hull (dynamics.roll_damping: ikeda) ------------------------------------

def test_ikeda_roll_damping_coefficients(barge, ship_file):
    """roll_damping: ikeda with Capytaine: B44 = Ikeda's linear part (friction, lifts) + the
    radiation damping, B44q = the quadratic part at ikeda_amplitude_deg, and the table of B44q
    against the running amplitude for the time domain; errors name the file and field."""
    from stabflow.dynamics import _kernels as K
    from stabflow.dynamics.roll_damping import linear_quadratic

    _, sec, st, _ = barge
    keels = {"span": 0.5, "length": 40.0, "x_start": -20.0, "x_end": 20.0}
    p = ship_file("barge", dynamics={"hydro": "capytaine", "roll_damping": "ikeda", "ikeda_amplitude_deg": 15.0},
                  bilge_keels=keels)
    ship = load_ship(p)
    hy = fake_hydro(float(st["mass"]))
    co = coefficients(ship, sec, st, hy, speed=3.0)
    omega = np.sqrt(co.c44 / (co.i44 + co.a44))
    ref = linear_quadratic(sec, st, omega=omega, roll_amplitude_deg=15.0, speed=3.0, bilge_keels=keels,
                           wave=float(hy.damping_roll), rho=ship.rho)
    assert co.roll_damping == "ikeda"
    assert co.b44 == pytest.approx(float(ref.b1), rel=1e-12) and co.b44 > float(hy.damping_roll)
    assert co.b44q == pytest.approx(float(ref.b2), rel=1e-12) and co.b44q > 0
    grid = np.degrees(np.arange(K.N_AMPLITUDES) * K.AMPLITUDE_STEP)
    assert co.b44q_table.shape == grid.shape and np.all(co.b44q_table >= 0)
    j = int(np.argmin(np.abs(grid - 16.0)))
    at = linear_quadratic(sec, st, omega=omega, roll_amplitude_deg=grid[j], speed=3.0, bilge_keels=keels,
                          wave=float(hy.damping_roll), rho=ship.rho)
    assert co.b44q_table[j] == pytest.approx(float(at.b2), rel=1e-12)
    # Capytaine is needed for the wave part; config roll damping cannot be given as well
    with pytest.raises(StabflowError, match="roll_damping: ikeda needs dynamics.hydro: capytaine"):
        coefficients(ship, sec, st)
    with pytest.raises(StabflowError, match=r"dynamics.b44: roll damping is computed"):
        coefficients(ship.modified(dynamics={"b44": 1e6}), sec, st, hy)
    with pytest.raises(StabflowError, match="bilge_keels"):
        bad = load_ship(ship_file("barge", dynamics={"hydro": "capytaine", "roll_damping": "ikeda"},
                                  bilge_keels={"span": 0.5, "length": 10.0, "x_start": 0.0, "x_end": 20.0}))
        coefficients(bad, sec, st, hy)
    # the schema: ikeda without capytaine is rejected at load, naming the file
    with pytest.raises(StabflowError, match="barge.yaml"):
        load_ship(ship_file("barge", dynamics={"roll_damping": "ikeda"}))
