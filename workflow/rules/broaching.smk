rule broaching:
    """Paper 004's stern-quartering cases with the 6-DOF model, calm-water manoeuvres, surf-riding thresholds."""
    priority: 20
    wildcard_constraints:
        ship=broaching_ship(),
    input:
        ship=ship_yaml,
        hull=hull_source,
        radiation=broaching_radiation,
    output:
        nc=f"{RESULTS}/broaching/{{ship}}.nc",
        validation=f"{RESULTS}/validation/{{ship}}_manoeuvring.nc",
        figures=[f"{RESULTS}/broaching/{{ship}}_{f}.png" for f in BROACHING_FIGURES],
    params:
        config={k: config[k] for k in ("broaching",) if k in config},
        ships_dir=SHIPS_DIR,
        names=BROACHING_FIGURES,
    log:
        f"{RESULTS}/logs/broaching_{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/broaching_{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/broaching.py"


rule radiation:
    """Heave-pitch added mass and damping over frequency (Capytaine) and the fitted memory model of the 6-DOF Cummins equation."""
    # head of the 6-DOF chain (ensemble, split-time, step-size validation)
    priority: 40
    wildcard_constraints:
        ship="|".join(radiation_ships()) or "none",
    input:
        ship=ship_yaml,
        hull=hull_source,
    output:
        nc=f"{RESULTS}/hydro/{{ship}}_radiation.nc",
        figure=f"{RESULTS}/hydro/{{ship}}_radiation.png",
    log:
        f"{RESULTS}/logs/hydro/{{ship}}_radiation.log",
    benchmark:
        f"{RESULTS}/benchmarks/hydro/{{ship}}_radiation.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/radiation.py"
