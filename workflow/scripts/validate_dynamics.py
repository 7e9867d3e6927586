"""Snakemake script for validate_dynamics (same as `stabflow validate-dynamics`)."""
from stabflow.steps import run_validate_dynamics

i = snakemake.input
run_validate_dynamics(i.ship, i.hull, i.statics, snakemake.output.nc)
