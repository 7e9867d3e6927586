rule statics:
    """Upright equilibrium, hydrostatic particulars and calm-water GZ 0-180 deg (free trim)."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
    output:
        nc=f"{RESULTS}/statics/{{ship}}.nc",
        fig=f"{RESULTS}/statics/{{ship}}_gz.png",
    log:
        f"{RESULTS}/logs/statics/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/statics/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/statics.py"
