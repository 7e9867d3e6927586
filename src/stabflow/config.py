"""Ship and pipeline configuration: YAML files validated against the JSON schemas.

The schemas live in ``workflow/schemas`` (shipped in the package as ``stabflow/schemas``); they hold
every key's description, unit and default. Validation errors name the file and the field.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import jsonschema
import yaml

from stabflow import StabflowError

SCHEMA_DIR = Path(__file__).parent / "schemas"


@cache
def schema(name: str) -> dict:
    """Return the parsed JSON schema ``<name>.schema.yaml``."""
    with open(SCHEMA_DIR / f"{name}.schema.yaml") as fh:
        return yaml.safe_load(fh)


def _fill_defaults(sch: dict, data: Any) -> Any:
    """Insert schema defaults for missing object keys (recursively, also inside array items)."""
    if isinstance(data, list) and sch.get("type") == "array" and isinstance(sch.get("items"), dict):
        return [_fill_defaults(sch["items"], d) for d in data]
    if not isinstance(data, dict) or sch.get("type") != "object":
        return data
    for key, sub in sch.get("properties", {}).items():
        if key not in data and "default" in sub:
            data[key] = copy.deepcopy(sub["default"])
        if key in data:
            data[key] = _fill_defaults(sub, data[key])
    return data


# YAML 1.2 core-schema float (PyYAML implements YAML 1.1, which reads 8.6e6 and 1e-3 as strings
# because it wants a decimal point and a signed exponent)
_FLOAT_12 = re.compile(r"^[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?$")


def _types(sch: dict) -> set:
    t = sch.get("type", [])
    return set([t] if isinstance(t, str) else t)


def coerce_numbers(sch: dict, data: Any) -> Any:
    """Read YAML 1.2 numbers that PyYAML left as strings (``8.6e6``, ``1E-3``), where the schema
    wants a number: the config then means what a user typed, whichever YAML loader read it
    (stabflow's or Snakemake's). Strings elsewhere are untouched."""
    if isinstance(data, str) and _types(sch) & {"number", "integer"} and _FLOAT_12.match(data.strip()):
        v = float(data)
        return int(v) if "integer" in _types(sch) and "number" not in _types(sch) and v.is_integer() else v
    if isinstance(data, list) and isinstance(sch.get("items"), dict):
        return [coerce_numbers(sch["items"], d) for d in data]
    if isinstance(data, dict):
        props = sch.get("properties", {})
        extra = sch.get("additionalProperties")
        for k, v in data.items():
            sub = props.get(k, extra if isinstance(extra, dict) else None)
            if sub is not None:
                data[k] = coerce_numbers(sub, v)
    return data


def validate(data: Any, name: str, source: str | Path) -> dict:
    """Validate ``data`` against schema ``name``; fill defaults.

    Raises
    ------
    StabflowError
        ``"<source>: <field.path>: <reason>"`` for the first error found.
    """
    sch = schema(name)
    data = coerce_numbers(sch, copy.deepcopy(data))
    validator = jsonschema.Draft202012Validator(sch)
    errors = sorted(validator.iter_errors(data), key=lambda e: (len(e.path), list(map(str, e.path))))
    if errors:
        err = errors[0]
        field = ".".join(str(p) for p in err.absolute_path) or "(top level)"
        msg = err.message
        if err.validator == "not" and list(err.validator_value) == ["required"]:
            # an absolute value and its fraction given together (ship schema, dynamics)
            field = " and ".join(f"{field}.{k}" for k in err.validator_value["required"])
            msg = "give one, not both"
        elif err.validator == "oneOf":
            msg = "give exactly one of " + " / ".join(
                "+".join(s.get("required", [])) for s in err.validator_value
            )
        raise StabflowError(f"{source}: {field}: {msg}")
    return _fill_defaults(sch, data)


def load_yaml(path: str | Path) -> Any:
    """Read a YAML file, turning I/O and syntax errors into :class:`StabflowError`."""
    path = Path(path)
    if not path.is_file():
        raise StabflowError(f"{path}: file not found")
    try:
        with open(path) as fh:
            return yaml.safe_load(fh)
    except yaml.YAMLError as exc:
        raise StabflowError(f"{path}: not valid YAML: {exc}") from exc


@dataclass(frozen=True)
class Ship:
    """A validated ship configuration.

    Attributes
    ----------
    name : str
        Ship identifier.
    path : Path
        The YAML file it came from (hull files resolve relative to its folder).
    data : dict
        The validated configuration with defaults filled in.
    """

    name: str
    path: Path
    data: dict

    @property
    def hull(self) -> dict:
        return self.data["hull"]

    @property
    def loading(self) -> dict:
        return self.data["loading"]

    @property
    def rho(self) -> float:
        """Water density [kg/m^3]."""
        return float(self.data["water_density"])

    def modified(self, stations: int | None = None, kg: float | None = None, dynamics: dict | None = None) -> "Ship":
        """A copy cut at ``stations``, loaded to ``kg`` [m] and/or with ``dynamics`` entries
        overridden (the ensemble conditions and the convergence checks use this)."""
        data = copy.deepcopy(self.data)
        if stations is not None:
            data["hull"]["stations"] = int(stations)
        if kg is not None:
            data["loading"]["kg"] = float(kg)
        data["dynamics"].update(dynamics or {})
        return Ship(self.name, self.path, data)

    def hull_file(self) -> Path:
        """Absolute path of the hull file named in ``hull.file``."""
        if "file" not in self.hull:
            raise StabflowError(f"{self.path}: hull.file: required for source {self.hull['source']!r}")
        return (self.path.parent / self.hull["file"]).resolve()


def load_ship(path: str | Path) -> Ship:
    """Load and validate ``config/ships/<name>.yaml``."""
    path = Path(path)
    data = validate(load_yaml(path), "ship", path)
    if data["name"] != path.stem:
        raise StabflowError(f"{path}: name: {data['name']!r} must equal the file name {path.stem!r}")
    src = data["hull"]["source"]
    need = {"box": ["length", "breadth", "depth"], "wigley": ["length", "breadth", "depth", "design_draft"],
            "mesh": ["file"], "offsets": ["file"]}[src]
    for key in need:
        if key not in data["hull"]:
            raise StabflowError(f"{path}: hull.{key}: required for source {src!r}")
    return Ship(name=data["name"], path=path, data=data)


def load_pipeline(path: str | Path) -> dict:
    """Load and validate the pipeline configuration (``config/config.yaml``)."""
    return validate(load_yaml(path), "config", path)


def step_settings(cfg: dict, step: str, key: str) -> dict:
    """The settings of pipeline section ``step`` (``extremes``, ``splittime``) for ensemble condition
    ``key`` (``<ship>_<name>``): the section's ``overrides[key]`` over its settings, validated like the
    section (a bad override raises ``StabflowError`` naming ``<step>.overrides.<key>``)."""
    over = dict(cfg.get("overrides", {}).get(key, {}))
    sch = schema("config")["properties"][step]
    merged = {k: v for k, v in cfg.items() if k not in ("conditions", "overrides")}
    merged.update(over)
    bad = sorted(set(over) - set(sch["properties"]) | set(over) & {"conditions", "overrides"})
    if bad:
        raise StabflowError(f"config: {step}.overrides.{key}: unknown setting(s) {', '.join(bad)}")
    err = next(iter(jsonschema.Draft202012Validator(sch).iter_errors(merged)), None)
    if err is not None:
        field = ".".join(str(p) for p in err.absolute_path)
        raise StabflowError(f"config: {step}.overrides.{key}.{field}: {err.message}")
    return merged


def derivative_fit_settings(fit: dict) -> dict:
    """The derivative model's fit settings (``derivative.fit`` of the config schema, also an ensemble
    condition's ``derivative_fit``) with defaults filled; validated like that section."""
    sch = schema("config")["properties"]["derivative"]["properties"]["fit"]
    err = next(iter(jsonschema.Draft202012Validator(sch).iter_errors(dict(fit))), None)
    if err is not None:
        field = ".".join(str(p) for p in err.absolute_path)
        raise StabflowError(f"config: derivative_fit.{field}: {err.message}")
    return _fill_defaults(sch, dict(fit))
