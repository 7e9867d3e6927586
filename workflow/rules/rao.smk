rule rao:
    """Regular-wave sweep of the 3-DOF time-domain model: heave/a, roll/ka, pitch/ka vs lambda/L."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
        hydro=hydro_input,
    output:
        nc=f"{RESULTS}/rao/{{ship}}_{{condition}}.nc",
        fig=f"{RESULTS}/rao/{{ship}}_{{condition}}.png",
    params:
        cfg=config["rao"],
    log:
        f"{RESULTS}/logs/rao/{{ship}}_{{condition}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/rao/{{ship}}_{{condition}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/rao.py"


rule hydro:
    """Capytaine BEM: added mass and damping at the natural frequencies, linear peer RAOs."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
    output:
        nc=f"{RESULTS}/hydro/{{ship}}_{{condition}}.nc",
    params:
        cfg=config["rao"],
    log:
        f"{RESULTS}/logs/hydro/{{ship}}_{{condition}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/hydro/{{ship}}_{{condition}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/hydro.py"
