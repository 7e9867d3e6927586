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
