"""Snakemake script for the waves rule (same as `stabflow waves`)."""
from stabflow.steps import run_waves

run_waves(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, dict(snakemake.params.cfg),
          snakemake.output.nc, snakemake.output.gm, snakemake.output.gz)
