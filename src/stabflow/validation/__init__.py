"""Validation checks: every result compared with a reference, as rows of the report's validation page.

Each row (:class:`Check`) carries the measured value, its acceptance band, the reference it was
compared with and the *kind* of reference:

``independent``
    exact or analytic, a peer library, published data, or a different method;
``consistency``
    the same code path another way (a limit of the same equations, a second route through the same
    kernel, self-convergence).

A check that cannot run is never dropped: it is a row with status ``FAIL`` (something that should
have worked did not) or ``SKIPPED`` (it does not apply here), with the reason. A NaN value is a FAIL.
Modules: :mod:`.statics`, :mod:`.waves`, :mod:`.dynamics` (time domain), :mod:`.ensemble`
(seaways, step size, extremes, split-time).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

KINDS = ("independent", "consistency")
STATUSES = ("PASS", "FAIL", "SKIPPED")


@dataclass
class Check:
    """One validation row.

    Attributes
    ----------
    check : str
        What is compared.
    value : float
        The measured value (a deviation from the reference, or a statistic such as a coverage).
    tolerance : float
        Passes when ``|value| <= tolerance`` (unless ``lower``/``upper`` are given).
    unit : str
        Unit of ``value`` and the bounds.
    reference : str
        What the value was compared with (document, method, library).
    kind : str
        ``"independent"`` or ``"consistency"`` (see the module docstring).
    lower, upper : float, optional
        Acceptance band ``lower <= value <= upper`` instead of ``|value| <= tolerance``.
    reason : str
        Why the check failed to run or was skipped (empty otherwise).
    skipped : bool
        The check does not apply (status SKIPPED, ``reason`` says why).
    """

    check: str
    value: float
    tolerance: float
    unit: str
    reference: str
    kind: str = "independent"
    lower: float | None = None
    upper: float | None = None
    reason: str = ""
    skipped: bool = False

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"check {self.check!r}: kind must be one of {KINDS}, not {self.kind!r}")
        self.value = float(self.value) if self.value is not None else np.nan

    @property
    def passed(self) -> bool:
        if self.skipped or not np.isfinite(self.value):
            return False
        if self.lower is not None or self.upper is not None:
            lo = -np.inf if self.lower is None else self.lower
            hi = np.inf if self.upper is None else self.upper
            return bool(lo <= self.value <= hi)
        return bool(abs(self.value) <= self.tolerance)

    @property
    def status(self) -> str:
        if self.skipped:
            return "SKIPPED"
        return "PASS" if self.passed else "FAIL"

    @property
    def criterion(self) -> str:
        """The acceptance band as text: 'within ±0.5', '≥ 0.9', 'in [0.7, 1.4]' (no '|': it is a table cell)."""
        if self.lower is not None and self.upper is not None:
            return f"in [{self.lower:.4g}, {self.upper:.4g}]"
        if self.lower is not None:
            return f"≥ {self.lower:.4g}"
        if self.upper is not None:
            return f"≤ {self.upper:.4g}"
        return f"within ±{self.tolerance:.4g}"

    @classmethod
    def failed(cls, check: str, reason: str, unit: str, reference: str, kind: str = "independent", **band) -> Check:
        """A check that could not be computed: status FAIL with ``reason`` (value NaN)."""
        band.setdefault("tolerance", np.nan)
        return cls(check, np.nan, unit=unit, reference=reference, kind=kind, reason=reason, **band)

    @classmethod
    def not_applicable(cls, check: str, reason: str, unit: str, reference: str, kind: str = "independent") -> Check:
        """A check that does not apply here: status SKIPPED with ``reason``."""
        return cls(check, np.nan, np.nan, unit, reference, kind=kind, reason=reason, skipped=True)


def run_check(fn, check: str, unit: str, reference: str, kind: str = "independent", **band) -> Check:
    """Call ``fn()`` for the value of a check; any exception becomes a FAIL row naming it."""
    try:
        value = fn()
    except Exception as exc:  # noqa: BLE001 - the row must show why it could not run
        return Check.failed(check, f"{type(exc).__name__}: {exc}", unit, reference, kind, **band)
    band.setdefault("tolerance", np.nan)
    return Check(check, value, unit=unit, reference=reference, kind=kind, **band)


def checks_dataset(ship: str, step: str, checks: list[Check]) -> xr.Dataset:
    """Rows as a NetCDF-friendly Dataset along dimension ``check``."""

    def opt(v):
        return np.nan if v is None else float(v)

    return xr.Dataset(
        {
            "value": ("check", [c.value for c in checks], {"long_name": "measured value (deviation from the reference or statistic)"}),
            "tolerance": ("check", [c.tolerance for c in checks], {"long_name": "allowed absolute value (NaN: a band is used)"}),
            "lower": ("check", [opt(c.lower) for c in checks], {"long_name": "lower bound of the acceptance band (NaN: none)"}),
            "upper": ("check", [opt(c.upper) for c in checks], {"long_name": "upper bound of the acceptance band (NaN: none)"}),
            "criterion": ("check", [c.criterion for c in checks], {"long_name": "acceptance criterion as text"}),
            "unit": ("check", [c.unit for c in checks]),
            "passed": ("check", np.array([c.passed for c in checks], dtype=np.int8), {"long_name": "1 = PASS, 0 = FAIL or SKIPPED"}),
            "status": ("check", [c.status for c in checks], {"long_name": "PASS, FAIL or SKIPPED"}),
            "kind": ("check", [c.kind for c in checks], {"long_name": "independent (exact, analytic, peer, published, other method) or consistency (same code path)"}),
            "reason": ("check", [c.reason for c in checks], {"long_name": "why the check failed to run or was skipped"}),
            "reference": ("check", [c.reference for c in checks]),
            "name": ("check", [c.check for c in checks]),
        },
        coords={"check": np.arange(len(checks))},
        attrs={"ship": ship, "step": step},
    )
