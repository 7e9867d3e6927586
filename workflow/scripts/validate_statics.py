"""Snakemake script for validate_statics (same as `stabflow validate`)."""
from stabflow.steps import run_validate_statics

run_validate_statics(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, snakemake.output.nc)
