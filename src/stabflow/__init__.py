"""stabflow: ship dynamic stability in irregular seas.

Volume-based Froude-Krylov + hydrostatic forces on sectional (Bonjean) hull tables, calm-water and
in-wave statics, and time-domain simulation, following the NSWCCD papers in ``shared/seeds``.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("stabflow")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0"


class StabflowError(Exception):
    """Bad input: the message names the file and the field at fault."""
