"""Criteria results as rows: criterion, level, value, standard with its source, verdict.

A verdict is PASS or FAIL only when the computed value and every standard it needs are available;
otherwise NOT EVALUATED with the missing items named. Rows are never dropped. Where the only missing
items are standards whose readable drafts printed a value (``Standard.draft``), the row also carries
the verdict it would have against the drafts ("indicative"): never the row's verdict.
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
    draft_limit : the limit of the indicative verdict: a draft's, where the adopted one is missing;
        the adopted one where only another standard the row needs is drafted.
    draft_source : the drafts' citations.
    blockers : the missing items no draft covers (an indicative verdict needs none).
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
    draft_limit: float | None = None
    draft_source: str = ""
    blockers: list[str] = field(default_factory=list)

    def _meets(self, limit: float) -> bool:
        # a value within round-off (ROUND_OFF relative) of its limit meets it: a wall-sided hull's
        # freeboard-volume ratio is exactly 1 in theory and 1 - 1e-16 in floating point
        slack = ROUND_OFF * max(abs(limit), abs(self.value) if math.isfinite(self.value) else 0.0)
        return self.value >= limit - slack if self.sense == ">=" else self.value <= limit + slack

    @property
    def verdict(self) -> str:
        # an infinite value is a result (e.g. no steady-wind equilibrium: phi0 = inf fails); NaN is not
        if self.missing or self.limit is None or math.isnan(self.value):
            return "NOT EVALUATED"
        return "PASS" if self._meets(self.limit) else "FAIL"

    @property
    def draft_verdict(self) -> str:
        """PASS or FAIL against the drafts' limit where only drafted standards are missing, else ""."""
        if (self.verdict != "NOT EVALUATED" or self.draft_limit is None or self.blockers
                or math.isnan(self.value)):
            return ""
        return "PASS" if self._meets(self.draft_limit) else "FAIL"

    @property
    def reason(self) -> str:
        if self.verdict != "NOT EVALUATED":
            return self.note
        why = list(self.missing)
        if math.isnan(self.value) and not why:
            why = ["the value could not be computed"]
        if self.limit is None and not self.missing:
            why.append("no standard value")
        text = "missing: " + "; ".join(why) + (f". {self.note}" if self.note else "")
        if self.draft_verdict:
            # without an adopted limit the indicative one is the draft's; with one, another standard was drafted
            which = ("the draft's limit" if self.limit is None else
                     "the limit, with the drafts' values of the other missing standards,")
            text += f". Indicative, against {which} {self.draft_limit:g} (not the adopted text): {self.draft_verdict}"
        return text


def against(criterion: str, level: str, value: float, unit: str, std: Standard, sense: str,
            note: str = "", missing: list[str] | None = None, drafted: list[Standard] | None = None) -> Row:
    """A row comparing ``value`` with the standard ``std`` (NOT EVALUATED when std has no value).

    ``missing`` names other missing items; ``drafted`` other missing standards the row needs (the
    caller's ``missing`` names them too) whose drafts count toward the indicative verdict."""
    miss = list(missing or [])
    covered = {f"{s.key} ({s.source})" for s in (drafted or []) if s.draft is not None}
    if not std.available:
        miss.append(f"{std.key} ({std.source})")
        if std.draft is not None:
            covered.add(miss[-1])
    draft_limit = float(std.draft["value"]) if not std.available and std.draft is not None else None
    limit = float(std.value) if std.available else None
    sources = [s.cite_draft() for s in [std, *(drafted or [])] if not s.available and s.draft is not None]
    return Row(criterion, level, float(value), unit, limit, sense, std.cite(), miss, note,
               draft_limit=draft_limit if draft_limit is not None else (limit if sources else None),
               draft_source="; ".join(sources), blockers=[m for m in miss if m not in covered])


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
            "verdict_draft": ("criterion", [r.draft_verdict for r in rows]),
            "criterion_draft_limit": ("criterion", np.array([np.nan if r.draft_limit is None else r.draft_limit
                                                             for r in rows], float)),
            "criterion_draft_source": ("criterion", [r.draft_source for r in rows]),
        },
        coords={"criterion": n},
    )
    ds.attrs["ship"] = ship
    return ds
