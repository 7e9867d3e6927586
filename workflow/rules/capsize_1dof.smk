rule capsize_1dof:
    """1-DOF box-barge roll: split-time and extremes from independent samples against brute force."""
    # scheduling (see the Snakefile): no inputs and ~9 min on one core: it starts first
    priority: 50
    output:
        nc=f"{RESULTS}/capsize_1dof/box1dof.nc",
        validation=f"{RESULTS}/validation/box1dof_capsize.nc",
        figure=f"{RESULTS}/capsize_1dof/box1dof.png",
    params:
        cfg=config["capsize_1dof"],
    threads: config["ensemble_threads"]
    log:
        f"{RESULTS}/logs/capsize_1dof.log",
    benchmark:
        f"{RESULTS}/benchmarks/capsize_1dof.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/capsize_1dof.py"
