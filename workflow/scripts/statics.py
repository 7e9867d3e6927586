"""Snakemake script for the statics rule (same as `stabflow statics`)."""
import logging

from stabflow.steps import run_statics

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
run_statics(snakemake.input.ship, snakemake.input.hull, snakemake.output.nc, snakemake.output.fig)
