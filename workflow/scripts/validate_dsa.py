"""Snakemake script for validate_dsa (same as `stabflow validate-dsa`)."""
from stabflow.steps import run_validate_dsa

run_validate_dsa(snakemake.output.nc)
