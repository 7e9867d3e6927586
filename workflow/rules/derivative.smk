rule derivative:
    """Derivative model (paper 001) fitted from the volume-based forces; regular-wave map of both models."""
    priority: 10
    wildcard_constraints:
        ship=derivative_ship(),
    input:
        unpack(derivative_ensembles),
        ship=ship_yaml,
        hull=hull_source,
    output:
        nc=f"{RESULTS}/derivative/{{ship}}.nc",
        validation=f"{RESULTS}/validation/{{ship}}_derivative.nc",
        figures=[f"{RESULTS}/derivative/{{ship}}_{f}.png" for f in DERIVATIVE_FIGURES],
        cpu=f"{RESULTS}/derivative/{{ship}}_cpu.tsv",
    params:
        config={k: config[k] for k in ("derivative", "ensembles") if k in config},
        ships_dir=SHIPS_DIR,
        names=DERIVATIVE_FIGURES,
    log:
        f"{RESULTS}/logs/derivative_{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/derivative_{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/derivative.py"
