"""Criteria results as rows: criterion, level, value, standard with its source, verdict.

A verdict is PASS or FAIL only when the computed value and every standard it needs are available;
otherwise NOT EVALUATED with the missing items named. Rows are never dropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from stabflow.criteria.standards import Standard

VERDICTS = ("PASS", "FAIL", "NOT EVALUATED")
#: relative round-off within which a value meets its limit
ROUND_OFF = 1e-9


@dataclass
class Row:
    """One criterion.

    Attributes
    ----------
    criterion : what is checked (e.g. "area under GZ 0-30 deg").
    level : the rule it belongs to (e.g. "IS Code 2008 A 2.2.1", "SGISC pure loss, level 1").
    value : the ship's computed value (NaN when it could not be computed; then NOT EVALUATED).
    unit : unit of value and limit.
    limit : the standard (None when missing).
    sense : ">=" (value must be at least the limit) or "<=".
    source : the standard's citation.
    missing : names of the missing items (standards or inputs); non-empty -> NOT EVALUATED.
    note : how the value was obtained, or why it is not evaluated beyond the missing items.
    """

    criterion: str
    level: str
    value: float
    unit: str
    limit: float | None
    sense: str
    source: str
    missing: list[str] = field(default_factory=list)
    note: str = ""

    @property
    def verdict(self) -> str:
        # an infinite value is a result (e.g. no steady-wind equilibrium: phi0 = inf fails); NaN is not
        if self.missing or self.limit is None or math.isnan(self.value):
            return "NOT EVALUATED"
        # a value within round-off (ROUND_OFF relative) of its limit meets it: a wall-sided hull's
        # freeboard-volume ratio is exactly 1 in theory and 1 - 1e-16 in floating point
        slack = ROUND_OFF * max(abs(self.limit), abs(self.value) if math.isfinite(self.value) else 0.0)
        ok = self.value >= self.limit - slack if self.sense == ">=" else self.value <= self.limit + slack
        return "PASS" if ok else "FAIL"

    @property
    def reason(self) -> str:
        if self.verdict != "NOT EVALUATED":
            return self.note
        why = list(self.missing)
        if math.isnan(self.value) and not why:
            why = ["the value could not be computed"]
        if self.limit is None and not self.missing:
            why.append("no standard value")
        return "missing: " + "; ".join(why) + (f". {self.note}" if self.note else "")


def against(criterion: str, level: str, value: float, unit: str, std: Standard, sense: str,
            note: str = "", missing: list[str] | None = None) -> Row:
    """A row comparing ``value`` with the standard ``std`` (NOT EVALUATED when std has no value)."""
    miss = list(missing or [])
    if not std.available:
        miss.append(f"{std.key} ({std.source})")
    limit = float(std.value) if std.available else None
    return Row(criterion, level, float(value), unit, limit, sense, std.cite(), miss, note)


def rows_dataset(rows: list[Row], ship: str) -> xr.Dataset:
    """The rows as a Dataset along ``criterion`` (strings for text, NaN for missing limits)."""
    n = np.arange(len(rows))
    ds = xr.Dataset(
        {
            "criterion_name": ("criterion", [r.criterion for r in rows]),
            "criterion_level": ("criterion", [r.level for r in rows]),
            "criterion_value": ("criterion", np.array([r.value for r in rows], float)),
            "criterion_unit": ("criterion", [r.unit for r in rows]),
            "criterion_limit": ("criterion", np.array([np.nan if r.limit is None else r.limit for r in rows], float)),
            "criterion_sense": ("criterion", [r.sense for r in rows]),
            "criterion_source": ("criterion", [r.source for r in rows]),
            "verdict": ("criterion", [r.verdict for r in rows]),
            "verdict_reason": ("criterion", [r.reason for r in rows]),
        },
        coords={"criterion": n},
    )
    ds.attrs["ship"] = ship
    return ds
