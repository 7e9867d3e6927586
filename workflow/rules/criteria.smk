rule criteria:
    """IS Code 2008 (general and weather criteria) and second-generation levels, from the ship's own GZ and wave GM."""
    input:
        ship=ship_yaml,
        hull=f"{RESULTS}/hull/{{ship}}.nc",
        statics=f"{RESULTS}/statics/{{ship}}.nc",
        data=criteria_data(),
        hydro=hydro_first,
        radiation=criteria_radiation,
    output:
        nc=f"{RESULTS}/criteria/{{ship}}.nc",
        fig=f"{RESULTS}/criteria/{{ship}}_criteria.png",
        seas=f"{RESULTS}/criteria/{{ship}}_sea_states.png",
    params:
        cfg=config["criteria"],
    log:
        f"{RESULTS}/logs/criteria/{{ship}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/criteria/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/criteria.py"


rule validate_criteria:
    """Criteria of the box barge against closed forms and exact integration (other hulls: SKIPPED with the reason), the level-1 routes, the beam-sea model, the DSA screening against simulation."""
    input:
        ship=ship_yaml,
        criteria=f"{RESULTS}/criteria/{{ship}}.nc",
        dsa=dsa_of,
    output:
        nc=f"{RESULTS}/validation/{{ship}}_criteria.nc",
    log:
        f"{RESULTS}/logs/validation/{{ship}}_criteria.log",
    benchmark:
        f"{RESULTS}/benchmarks/validate_criteria/{{ship}}.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/validate_criteria.py"


rule validate_dsa:
    """The DSA aggregation against an exact answer: linear 1-DOF roll, Rice's formula over the scatter table."""
    input:
        data=criteria_data(),
    output:
        nc=f"{RESULTS}/validation/dsa_linear_criteria.nc",
    log:
        f"{RESULTS}/logs/validation/dsa_linear_criteria.log",
    benchmark:
        f"{RESULTS}/benchmarks/validate_dsa/dsa_linear.tsv"
    conda:
        "../envs/stabflow.yaml"
    script:
        "../scripts/validate_dsa.py"
