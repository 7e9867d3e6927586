"""Snakemake script for the derivative rule (same as `stabflow derivative`)."""
from stabflow.steps import run_derivative

i, o = snakemake.input, snakemake.output
ens = {"full": i.full, "derivative": i.derivative} if "full" in i.keys() else None
run_derivative(dict(snakemake.params.config), snakemake.params.ships_dir, o.nc, o.validation,
               dict(zip(snakemake.params.names, o.figures)), ens, cpu_tsv=o.cpu)
