"""Snakemake script for the ensemble_shard rule (same as `stabflow ensemble-shard`)."""
from stabflow.steps import run_ensemble_shard

run_ensemble_shard(snakemake.input.ship, dict(snakemake.params.cond), int(snakemake.wildcards.shard),
                   snakemake.output.nc, threads=snakemake.threads,
                   hydro_nc=snakemake.input.hydro[0] if snakemake.input.hydro else None,
                   radiation_nc=snakemake.input.radiation[0] if snakemake.input.radiation else None)
