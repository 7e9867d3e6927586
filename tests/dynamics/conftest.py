import pytest

from stabflow.config import load_ship
from stabflow.dynamics.model import config_coefficients
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics

from ..conftest import SHIPS


def ship_model(name: str):
    """(ship, sections, statics, 3-DOF coefficients from the config alone) of a shipped ship config."""
    ship = load_ship(SHIPS / f"{name}.yaml")
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    sec = Sections(hull)
    return ship, sec, st, config_coefficients(ship, sec, st)


@pytest.fixture(scope="module")
def barge():
    """The shipped box barge with its statics and default 3-DOF coefficients."""
    return ship_model("barge")
