"""Snakemake script for the criteria rule (same as `stabflow criteria`)."""
import logging

from stabflow.steps import run_criteria

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
run_criteria(snakemake.input.ship, snakemake.input.hull, snakemake.input.statics, snakemake.params.cfg,
             snakemake.output.nc, snakemake.output.fig, snakemake.input.hydro[0] if snakemake.input.hydro else None,
             snakemake.input.radiation[0] if snakemake.input.radiation else None)
