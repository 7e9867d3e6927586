"""Bad configuration: one clear message naming the file and the field."""

import pytest

from stabflow import StabflowError
from stabflow.config import load_pipeline, load_ship

from .conftest import ROOT, SHIPS


@pytest.mark.parametrize("name", ["barge", "wigley", "dtmb5415", "dtc"])
def test_shipped_configs_valid(name):
    ship = load_ship(SHIPS / f"{name}.yaml")
    assert ship.name == name
    assert ship.data["statics"]["heel_step"] == 1.0  # default filled


@pytest.mark.parametrize(
    "changes,field",
    [
        ({"hull__statoins": 41}, "hull"),  # mistyped key
        ({"colour": "red"}, "(top level)"),  # unknown key
        ({"loading__kg": -1.0}, "loading.kg"),
        ({"hull__stations": 2}, "hull.stations"),
        ({"water_density": 500}, "water_density"),
        ({"loading__mass": 1e7}, "loading"),  # both draft and mass
        ({"hull__length": None}, "hull.length"),
        ({"hull__source": "lofting"}, "hull.source"),
    ],
)
def test_bad_ship_config(ship_file, changes, field):
    p = ship_file("barge", **changes)
    with pytest.raises(StabflowError) as e:
        load_ship(p)
    msg = str(e.value)
    assert str(p) in msg and field in msg


def test_name_must_match_file(tmp_path, ship_file):
    p = ship_file("barge")
    q = tmp_path / "other.yaml"
    q.write_text(p.read_text())
    with pytest.raises(StabflowError, match="name"):
        load_ship(q)


def test_bad_yaml_and_missing(tmp_path):
    p = tmp_path / "x.yaml"
    p.write_text("name: [unclosed\n")
    with pytest.raises(StabflowError, match="not valid YAML"):
        load_ship(p)
    with pytest.raises(StabflowError, match="not found"):
        load_ship(tmp_path / "nothere.yaml")


def test_pipeline_configs_valid():
    for f in ["config.yaml", "test.yaml"]:
        assert load_pipeline(ROOT / "config" / f)["ships"]
