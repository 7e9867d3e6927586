"""Snakemake script for validate_criteria (same as `stabflow validate-criteria`)."""
from stabflow.steps import run_validate_criteria

run_validate_criteria(snakemake.input.ship, snakemake.input.criteria, snakemake.output.nc)
