"""Snakemake script for validate_criteria (same as `stabflow validate-criteria`)."""
from stabflow.steps import run_validate_criteria

dsa = snakemake.input.get("dsa", [])  # the ship's DSA file, or none when the DSA does not run for it
dsa = [dsa] if isinstance(dsa, str) else list(dsa)
run_validate_criteria(snakemake.input.ship, snakemake.input.criteria, snakemake.output.nc, dsa[0] if dsa else None)
