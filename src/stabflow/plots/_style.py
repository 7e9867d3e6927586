"""Matplotlib set-up shared by the figure modules (headless backend, atomic saving)."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from stabflow.io import atomic_savefig  # noqa: E402

__all__ = ["atomic_savefig", "plt"]
