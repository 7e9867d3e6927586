rule splittime:
    """Split-time: crossings, motion perturbations in the regenerated seaways, GPD of the metric."""
    priority: 30
    input:
        ship=ensemble_ship_yaml,
        ensemble=f"{RESULTS}/ensemble/{{ens}}/ensemble.nc",
        hydro=ensemble_hydro,
        radiation=ensemble_radiation,
    output:
        nc=f"{RESULTS}/splittime/{{ens}}.nc",
        crossings=f"{RESULTS}/splittime/{{ens}}_crossings.png",
        perturbation=f"{RESULTS}/splittime/{{ens}}_perturbation.png",
        metric=f"{RESULTS}/splittime/{{ens}}_metric.png",
        rate=f"{RESULTS}/splittime/{{ens}}_rate.png",
    params:
        cond=ensemble_condition,
        cfg=config["splittime"],
    threads: config["ensemble_threads"]
    log:
        f"{RESULTS}/logs/splittime/{{ens}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/splittime/{{ens}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/splittime.py"
