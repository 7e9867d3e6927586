rule criteria:
    """IS Code 2008 (general and weather criteria) and second-generation levels, from the ship's own GZ and wave GM."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
        data=criteria_data(),
    output:
        nc=f"{RESULTS}/criteria/{{ship}}.nc",
        fig=f"{RESULTS}/criteria/{{ship}}_criteria.png",
    params:
        cfg=config["criteria"],
    log:
        f"{RESULTS}/logs/criteria/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/criteria/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/criteria.py"
