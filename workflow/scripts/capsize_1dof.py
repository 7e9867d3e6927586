"""Snakemake script for the capsize_1dof rule (same as `stabflow capsize-1dof`)."""
from stabflow.steps import run_capsize_1dof

o = snakemake.output
run_capsize_1dof(dict(snakemake.params.cfg), o.nc, o.validation, o.figure, threads=snakemake.threads)
