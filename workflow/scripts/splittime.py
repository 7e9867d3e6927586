"""Snakemake script for the splittime rule (same as `stabflow splittime`)."""
from stabflow.steps import run_splittime

o = snakemake.output
run_splittime(snakemake.input.ship, dict(snakemake.params.cond), snakemake.input.ensemble, dict(snakemake.params.cfg),
              o.nc, {"crossings": o.crossings, "perturbation": o.perturbation, "metric": o.metric, "rate": o.rate},
              threads=snakemake.threads, hydro_nc=snakemake.input.hydro[0] if snakemake.input.hydro else None,
              radiation_nc=snakemake.input.radiation[0] if snakemake.input.radiation else None)
