rule broaching:
    """Paper 004's stern-quartering cases with the 6-DOF model, calm-water manoeuvres, surf-riding thresholds."""
    wildcard_constraints:
        ship=broaching_ship(),
    input:
        ship=ship_yaml,
        hull=hull_source,
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
