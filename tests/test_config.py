"""Bad configuration: one clear message naming the file and the field."""

import pytest

from stabflow import StabflowError
from stabflow.config import load_pipeline, load_ship

from .conftest import ROOT, SHIPS


@pytest.mark.parametrize("name", ["barge", "wigley", "dtmb5415", "dtc", "trawler"])
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


def test_validation_profile_merges_into_a_valid_config(tmp_path):
    """config/validation.yaml is an overlay (snakemake --configfile): merged over config.yaml as
    Snakemake merges (mappings recursively, lists replaced) it validates, analyses three DTMB 5415
    loadings and adds 1-DOF severities."""
    import yaml

    def merge(a, b):
        out = dict(a)
        for k, v in b.items():
            out[k] = merge(a[k], v) if isinstance(v, dict) and isinstance(a.get(k), dict) else v
        return out

    base = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    over = yaml.safe_load((ROOT / "config" / "validation.yaml").read_text())
    p = tmp_path / "merged.yaml"
    p.write_text(yaml.safe_dump(merge(base, over)))
    cfg = load_pipeline(p)
    keys = {f"{c['ship']}_{c['name']}" for c in cfg["ensembles"]}
    assert len(cfg["splittime"]["conditions"]) == 3 and set(cfg["splittime"]["conditions"]) <= keys
    assert set(cfg["extremes"]["conditions"]) <= keys
    assert all(len(b["sigma_deg"]) == 4 == len(b["bruteforce_hours"]) for b in cfg["capsize_1dof"]["bands"])


@pytest.mark.parametrize("text", ["8.6e6", "8.6E6", "8.6e+6", "86e5", "8600000.0"])
def test_scientific_notation_is_a_number(tmp_path, ship_file, text):
    """YAML 1.1 (PyYAML) reads 8.6e6 as a string; stabflow reads every config number as YAML 1.2
    does, as the README's own example writes it."""
    p = ship_file("dtmb5415")
    lines = [ln for ln in p.read_text().splitlines()]
    body = "\n".join(ln for ln in lines if not ln.strip().startswith("draft:"))
    body = body.replace("loading:", f"loading:\n  mass: {text}\n  lcg: 0.0", 1)
    p.write_text(body + "\n")
    ship = load_ship(p)
    assert ship.loading["mass"] == pytest.approx(8.6e6) and isinstance(ship.loading["mass"], float)


def test_scientific_notation_in_pipeline_config(tmp_path):
    """The same in the pipeline config, also through Snakemake's own loader (common.smk coerces)."""
    import yaml

    from stabflow.config import coerce_numbers, schema

    text = (ROOT / "config" / "test.yaml").read_text().replace("hs: 3.5, tp: 10.0", "hs: 35e-1, tp: 1E+1")
    raw = yaml.safe_load(text)
    assert raw["ensembles"][0]["sea"]["hs"] == "35e-1"  # what PyYAML gives
    (tmp_path / "c.yaml").write_text(text)
    cfg = load_pipeline(tmp_path / "c.yaml")
    assert cfg["ensembles"][0]["sea"]["hs"] == 3.5 and cfg["ensembles"][0]["sea"]["tp"] == 10.0
    coerced = coerce_numbers(schema("config"), raw)
    assert coerced["ensembles"][0]["sea"]["hs"] == 3.5
    assert coerce_numbers(schema("config"), {"ships": ["1e5"]})["ships"] == ["1e5"]  # strings stay strings


@pytest.mark.parametrize(
    "transform,what",
    [
        ({"scale": 1000.0, "flip_z": False, "translate": [-71.0, 0.0, 0.0]}, "loading implausible"),  # millimetres
        ({"scale": 1.0, "flip_z": True, "translate": [-71.0, 0.0, 0.0]}, "keel amidships"),  # wrong flip
        ({"scale": 1.0, "flip_z": False, "translate": [100.0, 0.0, 0.0]}, "midships"),  # origin not midships
        ({"scale": 1.0, "flip_z": False, "translate": [-71.0, 0.0, 4.0]}, "keel amidships"),  # keel off baseline
    ],
)
def test_hull_frame_checked_after_transform(ship_file, transform, what):
    """A mesh in millimetres, flipped, or shifted off the ship axes is rejected with one line naming
    hull.transform (or the loading it makes absurd) and what was found; nothing is computed."""
    from stabflow.geometry import build_hull

    p = ship_file("dtmb5415", hull__transform=transform)
    with pytest.raises(StabflowError) as e:
        build_hull(load_ship(p))
    msg = str(e.value)
    assert msg.startswith(f"{p}: hull.transform: ") and what in msg and "hull spans" in msg and "\n" not in msg


def test_absolute_and_fraction_together_is_one_clear_error(ship_file):
    """An absolute coefficient and its fraction for the same mode: one line naming both fields."""
    p = ship_file("barge", dynamics={"b44": 1.0e6, "roll_damping_linear": 0.05})
    with pytest.raises(StabflowError) as e:
        load_ship(p)
    assert str(e.value) == f"{p}: dynamics.b44 and dynamics.roll_damping_linear: give one, not both"


def test_step_overrides_per_condition():
    """extremes / splittime overrides replace the section's settings for one condition only, and are
    validated like the section (the error names <step>.overrides.<key>.<field>)."""
    from stabflow.config import step_settings

    cfg = load_pipeline(ROOT / "config" / "config.yaml")
    st = cfg["splittime"]
    for key in st["conditions"]:
        s = step_settings(st, "splittime", key)
        assert "conditions" not in s and "overrides" not in s
        want = dict({k: v for k, v in st.items() if k not in ("conditions", "overrides")}, **st["overrides"].get(key, {}))
        assert s == want
    base = dict(st, overrides={"a_b": {"sample_hours": 5.0}})
    assert step_settings(base, "splittime", "a_b")["sample_hours"] == 5.0
    assert step_settings(base, "splittime", "c_d")["sample_hours"] == st["sample_hours"]
    with pytest.raises(StabflowError, match=r"splittime\.overrides\.a_b\.sample_hours"):
        step_settings(dict(st, overrides={"a_b": {"sample_hours": -1.0}}), "splittime", "a_b")
    with pytest.raises(StabflowError, match=r"extremes\.overrides\.a_b: unknown setting\(s\) sample_hour"):
        step_settings(dict(cfg["extremes"], overrides={"a_b": {"sample_hour": 5.0}}), "extremes", "a_b")


def test_condition_key_of_pipeline_and_bare_names():
    """The overrides key of an ensemble: the pipeline names a condition by its key, the CLI by its name."""
    from stabflow.steps import condition_key

    assert condition_key({"ship": "trawler", "condition": "trawler_sq6"}) == "trawler_sq6"
    assert condition_key({"ship": "trawler", "condition": "sq6"}) == "trawler_sq6"
