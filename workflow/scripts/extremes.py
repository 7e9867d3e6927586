"""Snakemake script for the extremes rule (same as `stabflow extremes`)."""
from stabflow.steps import run_extremes

run_extremes(snakemake.input.ensemble, dict(snakemake.params.cfg), snakemake.output.nc, snakemake.output.threshold,
             snakemake.output.rate, snakemake.output.validation)
