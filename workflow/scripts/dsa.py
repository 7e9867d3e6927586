"""Snakemake script for the dsa rule (same as `stabflow dsa`)."""
import logging

from stabflow.steps import run_dsa

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
run_dsa(snakemake.input.ship, snakemake.input.criteria, snakemake.params.cfg, snakemake.output.nc,
        {"map": snakemake.output.map, "polar": snakemake.output.polar},
        snakemake.input.hydro[0] if snakemake.input.hydro else None, overrides=snakemake.params.overrides)
