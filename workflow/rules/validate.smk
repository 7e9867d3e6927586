rule validate_statics:
    """Statics against exact, independent and published references (rows of the validation table)."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
    output:
        nc=f"{RESULTS}/validation/{{ship}}_statics.nc",
    log:
        f"{RESULTS}/logs/validation/{{ship}}_statics.log",
    benchmark:
        f"{RESULTS}/benchmarks/validate_statics/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/validate_statics.py"


rule validate_waves:
    """Wave pass and metric C: H -> 0 limit, two GM routes, convergence, weights, Rayleigh marginal."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
        waves=f"{RESULTS}/waves/{{ship}}.nc",
        metric=f"{RESULTS}/waves/{{ship}}_metric.nc",
    output:
        nc=f"{RESULTS}/validation/{{ship}}_waves.nc",
    params:
        cfg=config["early_stage"],
    log:
        f"{RESULTS}/logs/validation/{{ship}}_waves.log",
    benchmark:
        f"{RESULTS}/benchmarks/validate_waves/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/validate_waves.py"
