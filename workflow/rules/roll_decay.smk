rule roll_decay:
    """Calm-water roll decay with the ship's own damping; Ikeda's components where selected."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
        hydro=hydro_first,
    output:
        nc=f"{RESULTS}/roll_decay/{{ship}}.nc",
        fig=f"{RESULTS}/roll_decay/{{ship}}.png",
    log:
        f"{RESULTS}/logs/roll_decay/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/roll_decay/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/roll_decay.py"
