rule dsa:
    """Direct stability assessment over the IACS Rec. 34 scatter table x headings x speeds (screened, simulated, extrapolated)."""
    priority: 10
    input:
        ship=ship_yaml,
        criteria=f"{RESULTS}/criteria/{{ship}}.nc",
        data=criteria_data(),
        hydro=dsa_hydro,
    output:
        nc=f"{RESULTS}/criteria/{{ship}}_dsa.nc",
        map=f"{RESULTS}/criteria/{{ship}}_dsa_map.png",
        polar=f"{RESULTS}/criteria/{{ship}}_dsa_polar.png",
    params:
        cfg=config["dsa"],
        overrides=config["criteria"].get("overrides"),
    log:
        f"{RESULTS}/logs/dsa/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/dsa/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/dsa.py"
