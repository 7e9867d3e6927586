"""Snakemake script for the broaching rule (same as `stabflow broaching`)."""
from stabflow.steps import run_broaching

o = snakemake.output
run_broaching(dict(snakemake.params.config), snakemake.params.ships_dir, o.nc, o.validation,
              dict(zip(snakemake.params.names, o.figures)),
              radiation_nc=snakemake.input.radiation[0] if snakemake.input.radiation else None)
