"""Snakemake script for the report rule (same as `stabflow report`)."""
from pathlib import Path

from stabflow.report import build_report

results = Path(snakemake.input.statics[0]).parents[1]
build_report(results, snakemake.params.ships, dict(snakemake.params.config), "report",
             snakemake.output.html)
