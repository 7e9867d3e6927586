"""Snakemake script for the early_stage_summary rule."""
from stabflow.steps import run_early_stage_summary

run_early_stage_summary(list(snakemake.input), snakemake.output.csv, snakemake.output.png)
