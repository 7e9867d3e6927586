rule extremes:
    """Envelope peaks over threshold, GPD rates from samples, coverage against brute force."""
    priority: 30
    input:
        ensemble=f"{RESULTS}/ensemble/{{ens}}/ensemble.nc",
    output:
        nc=f"{RESULTS}/extremes/{{ens}}.nc",
        threshold=f"{RESULTS}/extremes/{{ens}}_threshold.png",
        rate=f"{RESULTS}/extremes/{{ens}}_rate.png",
        validation=f"{RESULTS}/extremes/{{ens}}_validation.png",
    params:
        cfg=config["extremes"],
    log:
        f"{RESULTS}/logs/extremes/{{ens}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/extremes/{{ens}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/extremes.py"
