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


rule validate_dynamics:
    """3-DOF time domain: roll decay vs linear theory, pressure integration, linear frequency domain."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
    output:
        nc=f"{RESULTS}/validation/{{ship}}_dynamics.nc",
    log:
        f"{RESULTS}/logs/validation/{{ship}}_dynamics.log",
    benchmark:
        f"{RESULTS}/benchmarks/validate_dynamics/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/validate_dynamics.py"


rule validate_ensemble:
    """Seaway statistics, step-size convergence, extremes coverage and split-time vs brute force."""
    priority: 30
    input:
        ship=ensemble_ship_yaml,
        ensemble=f"{RESULTS}/ensemble/{{ens}}/ensemble.nc",
        extremes=ensemble_extremes,
        splittime=ensemble_splittime,
        hydro=ensemble_hydro,
        radiation=ensemble_radiation,
    output:
        nc=f"{RESULTS}/validation/{{ens}}_ensemble.nc",
    params:
        cond=ensemble_condition,
    threads: validation_threads
    log:
        f"{RESULTS}/logs/validation/{{ens}}_ensemble.log",
    benchmark:
        f"{RESULTS}/benchmarks/validate_ensemble/{{ens}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/validate_ensemble.py"
