"""Snakemake script for the roll_decay rule (same as `stabflow roll-decay`)."""
from stabflow.steps import run_roll_decay

run_roll_decay(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, snakemake.output.nc,
               snakemake.output.fig, snakemake.input.hydro[0] if snakemake.input.hydro else None)
