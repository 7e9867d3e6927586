"""Snakemake script for the radiation rule (same as `stabflow radiation`)."""
from stabflow.steps import run_radiation

run_radiation(snakemake.input.ship, snakemake.output.nc, snakemake.output.figure)
