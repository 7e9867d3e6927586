"""Snakemake script for validate_waves."""
from stabflow.steps import run_validate_waves

i = snakemake.input
run_validate_waves(i.ship, i.hull, i.statics, i.waves, i.metric, dict(snakemake.params.cfg), snakemake.output.nc)
