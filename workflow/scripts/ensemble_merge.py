"""Snakemake script for the ensemble_merge rule (same as `stabflow ensemble-merge`)."""
from stabflow.steps import run_ensemble_merge

run_ensemble_merge(list(snakemake.input.shards), snakemake.output.nc, snakemake.output.distribution,
                   snakemake.output.spectra, snakemake.output.samples)
