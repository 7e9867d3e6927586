"""The HTML validation report (Jupyter Book 1.x) built from the NetCDF results: page builders in
:mod:`.book`; the hand-written pages and styles live in the repository's ``report/`` folder."""

from stabflow.report.book import build_report

__all__ = ["build_report"]
