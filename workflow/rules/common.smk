# Config validation and helpers (no lambdas in rules).
from pathlib import Path

from snakemake.utils import validate

from stabflow.config import coerce_numbers, derivative_fit_settings, load_ship, schema, step_settings
from stabflow.dynamics.derivative import compared_ensembles
from stabflow.steps import broaching_figure_names, derivative_figure_names


# numbers typed as 8.6e6 reach us as strings from Snakemake's YAML 1.1 loader: read them as numbers
coerce_numbers(schema("config"), config)
validate(config, "../schemas/config.schema.yaml")

SHIPS_DIR = config.get("ships_dir", "config/ships")
RESULTS = config.get("results", "results")
SHIPS = {name: load_ship(Path(SHIPS_DIR) / f"{name}.yaml") for name in config["ships"]}


RAO_CONDITIONS = [c["name"] for c in config["rao"]["conditions"]]


ENSEMBLES = {f"{c['ship']}_{c['name']}": c for c in config["ensembles"]}
for _step in ("extremes", "splittime"):
    for _key in config[_step]["conditions"]:
        if _key not in ENSEMBLES:
            raise ValueError(f"config: {_step}: conditions: {_key!r} is not an ensemble (have {sorted(ENSEMBLES)})")
        # overrides of other conditions may come from the base config that a --configfile extends
        step_settings(config[_step], _step, _key)
for _step in ("broaching", "derivative"):
    if _step in config and config[_step]["ship"] not in SHIPS:
        raise ValueError(f"config: {_step}: ship {config[_step]['ship']!r} is not in ships")
for _key, _c in ENSEMBLES.items():
    if _c.get("model", "volume") == "derivative":
        # checked here, not first in a shard job
        if int(_c.get("dof", 3)) != 3:
            raise ValueError(f"config: ensembles: {_key}: model: derivative is a heave-roll-pitch model; it cannot "
                             "run with dof: 6")
        derivative_fit_settings(_c.get("derivative_fit", {}))
    if _c.get("compare_with"):
        _o = ENSEMBLES.get(f"{_c['ship']}_{_c['compare_with']}")
        if _o is None:
            raise ValueError(f"config: ensembles: {_key}: compare_with: {_c['compare_with']!r} is not a condition of "
                             f"ship {_c['ship']!r} (have {sorted(ENSEMBLES)})")
        # the comparison claims the same sea, records and ship: everything but the model must match
        _diff = [k for k in ("sea", "seed", "speed_kn", "heading_deg", "kg", "dynamics", "dt", "duration", "records",
                             "stations", "dphi_dzdt") if _c.get(k) != _o.get(k)]
        if _diff:
            raise ValueError(f"config: ensembles: {_key}: compare_with: {_c['compare_with']!r} differs in "
                             f"{', '.join(_diff)}; the two conditions must be the same sea and ship")
for _s in config["dsa"].get("ships") or []:
    if _s not in SHIPS:
        raise ValueError(f"config: dsa: ships: {_s!r} is not in ships")
for _key, _c in ENSEMBLES.items():
    if _c["ship"] not in SHIPS:
        raise ValueError(f"config: ensembles: {_key}: ship {_c['ship']!r} is not in ships")


wildcard_constraints:
    ship="|".join(SHIPS),
    condition="|".join(RAO_CONDITIONS),
    ens="|".join(ENSEMBLES) or "none",
    shard=r"\d+",


def ship_yaml(wildcards):
    """Path of the ship configuration file."""
    return str(Path(SHIPS_DIR) / f"{wildcards.ship}.yaml")


def hull_source(wildcards):
    """The ship's hull file (mesh or offsets), if any, so edits re-run the hull step."""
    ship = SHIPS[wildcards.ship]
    return [str(ship.hull_file())] if "file" in ship.hull else []


def per_ship(pattern):
    """Expand a results pattern over every configured ship."""
    return expand(pattern, ship=list(SHIPS))


def hydro_input(wildcards):
    """The Capytaine results for ships whose dynamics.hydro is capytaine (none otherwise)."""
    if SHIPS[wildcards.ship].data["dynamics"]["hydro"] == "capytaine":
        return [f"{RESULTS}/hydro/{wildcards.ship}_{wildcards.condition}.nc"]
    return []


def hydro_first(wildcards):
    """The Capytaine results of the first RAO condition, for ships that use them (the roll decay)."""
    if SHIPS[wildcards.ship].data["dynamics"]["hydro"] == "capytaine":
        return [f"{RESULTS}/hydro/{wildcards.ship}_{RAO_CONDITIONS[0]}.nc"]
    return []


def per_ship_condition(pattern):
    """Expand a results pattern over every ship and RAO condition."""
    return expand(pattern, ship=list(SHIPS), condition=RAO_CONDITIONS)


def ensemble_condition(wildcards):
    """The ensemble condition's config (with its key as name)."""
    return dict(ENSEMBLES[wildcards.ens], name=wildcards.ens)


def validation_threads(wildcards):
    """Threads of a validate_ensemble job: ``ensemble_threads`` for the 6-DOF and derivative
    conditions, whose step-size re-runs simulate records in parallel; 1 for 3-DOF conditions (their
    re-runs are serial)."""
    c = ENSEMBLES[wildcards.ens]
    return config["ensemble_threads"] if c.get("dof", 3) == 6 or c.get("model") == "derivative" else 1


def ensemble_ship_yaml(wildcards):
    """Ship file of an ensemble condition."""
    return str(Path(SHIPS_DIR) / f"{ENSEMBLES[wildcards.ens]['ship']}.yaml")


def ensemble_hull_source(wildcards):
    """Hull file of an ensemble condition's ship, if any."""
    ship = SHIPS[ENSEMBLES[wildcards.ens]["ship"]]
    return [str(ship.hull_file())] if "file" in ship.hull else []


def ensemble_hydro(wildcards):
    """Capytaine coefficients, when the condition's effective dynamics use them."""
    c = ENSEMBLES[wildcards.ens]
    dyn = dict(SHIPS[c["ship"]].data["dynamics"], **c.get("dynamics", {}))
    return [f"{RESULTS}/hydro/{c['ship']}_{RAO_CONDITIONS[0]}.nc"] if dyn.get("hydro") == "capytaine" else []


def uses_memory(ship):
    """True if the ship's 6-DOF model radiates in heave and pitch through the memory model."""
    return SHIPS[ship].data.get("manoeuvring", {}).get("heave_pitch_radiation", "constant") == "memory"


def radiation_ships():
    """Ships whose 6-DOF records run (broaching step, dof: 6 ensembles) with the heave-pitch memory model."""
    used = {c["ship"] for c in config["ensembles"] if int(c.get("dof", 3)) == 6}
    if "broaching" in config:
        used.add(config["broaching"]["ship"])
    return sorted(s for s in used if s in SHIPS and uses_memory(s))


def radiation_outputs():
    """The radiation step's files (heave-pitch BEM over frequency and the fitted memory model)."""
    return [f"{RESULTS}/hydro/{s}_radiation{x}" for s in radiation_ships() for x in (".nc", ".png")]


def broaching_radiation(wildcards):
    """The broaching ship's memory model, when it uses one."""
    return [f"{RESULTS}/hydro/{wildcards.ship}_radiation.nc"] if uses_memory(wildcards.ship) else []


def ensemble_radiation(wildcards):
    """The memory model of a dof: 6 condition's ship, when it uses one."""
    c = ENSEMBLES[wildcards.ens]
    return [f"{RESULTS}/hydro/{c['ship']}_radiation.nc"] if int(c.get("dof", 3)) == 6 and uses_memory(c["ship"]) else []


def ensemble_shards(wildcards):
    """All shard files of an ensemble condition."""
    c = ENSEMBLES[wildcards.ens]
    n = -(-c["records"] // c["shard_records"])
    return [f"{RESULTS}/ensemble/{wildcards.ens}/shard_{k}.nc" for k in range(n)]


def ensemble_extremes(wildcards):
    """The extremes result of an ensemble condition, if the extremes step analyses it."""
    return [f"{RESULTS}/extremes/{wildcards.ens}.nc"] if wildcards.ens in config["extremes"]["conditions"] else []


def ensemble_splittime(wildcards):
    """The split-time result of an ensemble condition, if the split-time step analyses it."""
    return [f"{RESULTS}/splittime/{wildcards.ens}.nc"] if wildcards.ens in config["splittime"]["conditions"] else []


def validation_files():
    """Every validation result: statics, waves and time domain per ship, one per ensemble condition."""
    return (
        per_ship(f"{RESULTS}/validation/{{ship}}_statics.nc")
        + per_ship(f"{RESULTS}/validation/{{ship}}_waves.nc")
        + per_ship(f"{RESULTS}/validation/{{ship}}_dynamics.nc")
        + [f"{RESULTS}/validation/{k}_ensemble.nc" for k in ENSEMBLES]
        + capsize_1dof_outputs("validation")
        + broaching_outputs("validation")
        + derivative_outputs("validation")
        + per_ship(f"{RESULTS}/validation/{{ship}}_criteria.nc")
        + [f"{RESULTS}/validation/dsa_linear_criteria.nc"]
    )


def derivative_outputs(which="nc"):
    """The derivative model's fit, map and checks when the config has a derivative section."""
    if "derivative" not in config:
        return []
    s = config["derivative"]["ship"]
    return {"nc": [f"{RESULTS}/derivative/{s}.nc"], "validation": [f"{RESULTS}/validation/{s}_derivative.nc"],
            "figures": [f"{RESULTS}/derivative/{s}_{f}.png" for f in DERIVATIVE_FIGURES]}[which]


def derivative_ship():
    """The ship of the derivative step (the rule's {ship} wildcard is constrained to it)."""
    return config["derivative"]["ship"] if "derivative" in config else "none"


DERIVATIVE_FIGURES = derivative_figure_names(config) if "derivative" in config else []


def derivative_ensembles(wildcards):
    """The two ensembles (model volume, model derivative) the derivative step compares, if any."""
    e = compared_ensembles(config) if "derivative" in config else None
    return {} if not e else {k: f"{RESULTS}/ensemble/{e[k]}/ensemble.nc" for k in ("full", "derivative")}


def broaching_outputs(which="nc"):
    """Paper 004's scenario and the manoeuvring checks when the config has a broaching section."""
    if "broaching" not in config:
        return []
    s = config["broaching"]["ship"]
    return {"nc": [f"{RESULTS}/broaching/{s}.nc"], "validation": [f"{RESULTS}/validation/{s}_manoeuvring.nc"],
            "figures": [f"{RESULTS}/broaching/{s}_{f}.png" for f in BROACHING_FIGURES]}[which]


def broaching_ship():
    """The ship of the broaching step (the rule's {ship} wildcard is constrained to it)."""
    return config["broaching"]["ship"] if "broaching" in config else "none"


BROACHING_FIGURES = broaching_figure_names(config)


def capsize_1dof_outputs(which="nc"):
    """The 1-DOF capsize case's results when capsize_1dof.bands is not empty (none otherwise)."""
    if not config["capsize_1dof"]["bands"]:
        return []
    return {"nc": [f"{RESULTS}/capsize_1dof/box1dof.nc"],
            "validation": [f"{RESULTS}/validation/box1dof_capsize.nc"]}[which]


def criteria_data():
    """The criteria data files and the override file, if any (edits re-run the criteria step)."""
    files = sorted(str(p) for p in Path("resources/criteria").glob("*.yaml"))
    return files + ([config["criteria"]["overrides"]] if config["criteria"].get("overrides") else [])


def dsa_ships():
    """Ships of the direct stability assessment (dsa.ships, or every ship)."""
    return config["dsa"]["ships"] if config["dsa"].get("ships") is not None else list(SHIPS)


def criteria_radiation(wildcards):
    """The radiation step's file for the criteria step's surf-riding with the mean wave force, for the
    memory-model ships whose radiation step runs (for others the chapter says it was not given)."""
    return [f"{RESULTS}/hydro/{wildcards.ship}_radiation.nc"] if wildcards.ship in radiation_ships() else []


def dsa_of(wildcards):
    """The ship's DSA file when the DSA runs for it (its screening is validated), else nothing."""
    return [f"{RESULTS}/criteria/{wildcards.ship}_dsa.nc"] if wildcards.ship in dsa_ships() else []


def dsa_hydro(wildcards):
    """Capytaine coefficients for a ship whose DSA dynamics use them."""
    dyn = dict(SHIPS[wildcards.ship].data["dynamics"], **config["dsa"].get("dynamics", {}))
    return [f"{RESULTS}/hydro/{wildcards.ship}_{RAO_CONDITIONS[0]}.nc"] if dyn.get("hydro") == "capytaine" else []


def report_sources():
    """Hand-written report pages and styles (report/*.md, report/_config.yml, report/_static/*)."""
    return sorted(str(p) for p in Path("report").rglob("*") if p.is_file() and "_build" not in p.parts)


def all_outputs():
    """Everything `snakemake -j2` builds."""
    return (
        per_ship(f"{RESULTS}/statics/{{ship}}.nc")
        + per_ship(f"{RESULTS}/waves/{{ship}}.nc")
        + per_ship_condition(f"{RESULTS}/rao/{{ship}}_{{condition}}.nc")
        + per_ship(f"{RESULTS}/roll_decay/{{ship}}.nc")
        + per_ship(f"{RESULTS}/criteria/{{ship}}.nc")
        + [f"{RESULTS}/criteria/{s}_dsa.nc" for s in dsa_ships()]
        + [f"{RESULTS}/ensemble/{k}/ensemble.nc" for k in ENSEMBLES]
        + [f"{RESULTS}/extremes/{k}.nc" for k in config["extremes"]["conditions"]]
        + [f"{RESULTS}/splittime/{k}.nc" for k in config["splittime"]["conditions"]]
        + capsize_1dof_outputs()
        + broaching_outputs()
        + radiation_outputs()
        + derivative_outputs()
        + [f"{RESULTS}/waves/early_stage_C.csv", f"{RESULTS}/report/html/index.html"]
    )
