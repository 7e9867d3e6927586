rule ensemble_shard:
    """One shard of an irregular-sea ensemble: records [k * shard_records, ...), statistics only."""
    priority: 30
    input:
        ship=ensemble_ship_yaml,
        hull=ensemble_hull_source,
        hydro=ensemble_hydro,
        radiation=ensemble_radiation,
    output:
        nc=f"{RESULTS}/ensemble/{{ens}}/shard_{{shard}}.nc",
    params:
        cond=ensemble_condition,
    threads: config["ensemble_threads"]
    log:
        f"{RESULTS}/logs/ensemble/{{ens}}_{{shard}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/ensemble/{{ens}}_{{shard}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/ensemble_shard.py"


rule ensemble_merge:
    """Merge the shards; roll distribution, response spectra and sample time histories."""
    priority: 30
    input:
        shards=ensemble_shards,
    output:
        nc=f"{RESULTS}/ensemble/{{ens}}/ensemble.nc",
        distribution=f"{RESULTS}/ensemble/{{ens}}/roll_distribution.png",
        spectra=f"{RESULTS}/ensemble/{{ens}}/spectra.png",
        samples=f"{RESULTS}/ensemble/{{ens}}/time_histories.png",
    log:
        f"{RESULTS}/logs/ensemble/{{ens}}_merge.log",
    benchmark:
        f"{RESULTS}/benchmarks/ensemble/{{ens}}_merge.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/ensemble_merge.py"
