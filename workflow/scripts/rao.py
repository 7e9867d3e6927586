"""Snakemake script for the rao rule (same as `stabflow rao`)."""
from stabflow.steps import run_rao

run_rao(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, dict(snakemake.params.cfg),
        snakemake.wildcards.condition, snakemake.output.nc, snakemake.output.fig,
        snakemake.input.hydro[0] if snakemake.input.hydro else None)
