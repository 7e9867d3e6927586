rule hull:
    """Cut stations from the hull (mesh, offsets or analytic) and tabulate Bonjean curves."""
    input:
        ship=ship_yaml,
        source=hull_source,
    output:
        nc=f"{RESULTS}/hull/{{ship}}.nc",
        fig=f"{RESULTS}/hull/{{ship}}_bodyplan.png",
    log:
        f"{RESULTS}/logs/hull/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/hull/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/hull.py"
