rule report:
    """Jupyter Book HTML report: overview, one chapter per ship, validation table, methods."""
    input:
        statics=per_ship(f"{RESULTS}/statics/{{ship}}.nc"),
        figures=per_ship(f"{RESULTS}/statics/{{ship}}_gz.png") + per_ship(f"{RESULTS}/hull/{{ship}}_bodyplan.png"),
        validation=per_ship(f"{RESULTS}/validation/{{ship}}_statics.nc"),
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
