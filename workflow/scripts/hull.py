"""Snakemake script for the hull rule (same as `stabflow hull`)."""
import logging

from stabflow.steps import run_hull

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
run_hull(snakemake.input.ship, snakemake.output.nc, snakemake.output.fig)
