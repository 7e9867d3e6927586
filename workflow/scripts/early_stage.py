"""Snakemake script for the early_stage rule (same as `stabflow early-stage`)."""
from stabflow.steps import run_early_stage

run_early_stage(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, dict(snakemake.params.cfg),
                snakemake.output.nc, snakemake.output.csv)
