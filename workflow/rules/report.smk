rule report:
    """Jupyter Book HTML report: overview, one chapter per ship, validation table, methods."""
    input:
        statics=per_ship(f"{RESULTS}/statics/{{ship}}.nc"),
        figures=per_ship(f"{RESULTS}/statics/{{ship}}_gz.png") + per_ship(f"{RESULTS}/hull/{{ship}}_bodyplan.png"),
        waves=per_ship(f"{RESULTS}/waves/{{ship}}.nc"),
        wave_figures=per_ship(f"{RESULTS}/waves/{{ship}}_gm.png") + per_ship(f"{RESULTS}/waves/{{ship}}_gz_waves.png"),
        metric=f"{RESULTS}/waves/early_stage_C.csv",
        rao=per_ship_condition(f"{RESULTS}/rao/{{ship}}_{{condition}}.nc"),
        roll_decay=per_ship(f"{RESULTS}/roll_decay/{{ship}}.nc"),
        criteria=per_ship(f"{RESULTS}/criteria/{{ship}}.nc") + per_ship(f"{RESULTS}/criteria/{{ship}}_criteria.png")
        + per_ship(f"{RESULTS}/criteria/{{ship}}_sea_states.png"),
        dsa=[f"{RESULTS}/criteria/{s}_dsa{x}" for s in dsa_ships() for x in (".nc", "_map.png", "_polar.png")],
        validation=validation_files(),
        ensembles=[f"{RESULTS}/ensemble/{k}/ensemble.nc" for k in ENSEMBLES],
        extremes=[f"{RESULTS}/extremes/{k}.nc" for k in config["extremes"]["conditions"]],
        splittime=[f"{RESULTS}/splittime/{k}.nc" for k in config["splittime"]["conditions"]],
        capsize_1dof=capsize_1dof_outputs(),
        broaching=broaching_outputs() + broaching_outputs("figures"),
        radiation=radiation_outputs(),
        derivative=derivative_outputs() + derivative_outputs("figures"),
        source=report_sources(),
    output:
        html=f"{RESULTS}/report/html/index.html",
    params:
        ships=list(SHIPS),
        config=config,
    log:
        f"{RESULTS}/logs/report.log",
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/report.py"
