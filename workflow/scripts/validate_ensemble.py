"""Snakemake script for validate_ensemble (same as `stabflow validate-ensemble`)."""
from stabflow.steps import run_validate_ensemble

i = snakemake.input


def first(files):
    return files[0] if files else None


run_validate_ensemble(i.ship, dict(snakemake.params.cond), i.ensemble, snakemake.output.nc, first(i.extremes),
                      first(i.splittime), first(i.hydro), first(i.radiation), threads=snakemake.threads)
