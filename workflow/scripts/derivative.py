"""Snakemake script for the derivative rule (same as `stabflow derivative`)."""
from stabflow.steps import run_derivative

o = snakemake.output
run_derivative(dict(snakemake.params.config), snakemake.params.ships_dir, o.nc, o.validation,
               dict(zip(snakemake.params.names, o.figures)))
