"""Snakemake script for the hydro rule (Capytaine coefficients and peer RAOs)."""
from stabflow.steps import run_hydro

run_hydro(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, dict(snakemake.params.cfg),
          snakemake.wildcards.condition, snakemake.output.nc)
