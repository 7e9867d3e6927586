rule waves:
    """Quasi-static wave pass: GM(x_c) and GZ(phi; x_c) over wave length, steepness and crest position."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
    output:
        nc=f"{RESULTS}/waves/{{ship}}.nc",
        gm=f"{RESULTS}/waves/{{ship}}_gm.png",
        gz=f"{RESULTS}/waves/{{ship}}_gz_waves.png",
    params:
        cfg=config["wave_pass"],
    log:
        f"{RESULTS}/logs/waves/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/waves/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/waves.py"


rule early_stage:
    """Early-stage metric C (paper 002): GM_cr, mean time below GM_cr, C per sea state."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
    output:
        nc=f"{RESULTS}/waves/{{ship}}_metric.nc",
        csv=f"{RESULTS}/waves/{{ship}}_metric.csv",
    params:
        cfg=config["early_stage"],
    log:
        f"{RESULTS}/logs/early_stage/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/early_stage/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/early_stage.py"


rule early_stage_summary:
    """Table and bar chart of C for every ship and sea state (paper 002, Table 1 / Figure 6)."""
    input:
        per_ship(f"{RESULTS}/waves/{{ship}}_metric.nc"),
    output:
        csv=f"{RESULTS}/waves/early_stage_C.csv",
        png=f"{RESULTS}/waves/early_stage_C.png",
    log:
        f"{RESULTS}/logs/early_stage_summary.log",
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/early_stage_summary.py"
