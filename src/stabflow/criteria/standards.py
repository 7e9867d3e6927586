"""The criteria standards: one place for every regulatory number, each with its source.

``resources/criteria/*.yaml`` hold the numbers (2008 IS Code, second-generation criteria, the IACS
Rec. 34 scatter table). A *numeric entry* is a mapping with ``value`` (a number, a list of pairs or
null), ``unit``, ``source`` (document and paragraph) and ``read_at`` (where it was actually read);
null values carry ``missing`` (what was searched). A user holding the documents supplies missing
values in an override file (``criteria_overrides``), validated here, its source kept in the results.

A null entry may carry a ``draft``: the value a readable draft of the document printed (``value``,
``source``: the draft and paragraph, ``read_at``, ``quote``: the sentence as printed). A draft
never makes a verdict: the row stays NOT EVALUATED and shows, beside it, the verdict it would have
against the draft's value ("indicative"), so that a reader sees where the ship stands while the
adopted text is unread.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from stabflow import StabflowError
from stabflow.config import load_yaml

#: the shipped data files, by the name used in keys ("is_code_2008.general_criteria.gm0_min")
DATA_DIR = Path(__file__).resolve().parents[3] / "resources" / "criteria"
FILES = ("is_code_2008", "sgisc", "iacs_rec34_scatter")


@dataclass(frozen=True)
class Standard:
    """One standard value and where it comes from.

    Attributes
    ----------
    key : dotted key, e.g. ``is_code_2008.general_criteria.gm0_min``.
    value : the number (or table) or None when no readable source gave it.
    unit : its unit.
    source : the document and paragraph/table it belongs to.
    read_at : where it was read (page or repository file), or the override file.
    missing : why it is None (what was searched), else "".
    draft : for a missing value, the value a readable draft printed: a mapping with ``value`` (a
        number, or a table: rows with ``columns``), ``source``, ``read_at`` and ``quote`` (see the
        module's docstring), else None.
    """

    key: str
    value: Any
    unit: str
    source: str
    read_at: str
    missing: str = ""
    draft: dict | None = None

    @property
    def available(self) -> bool:
        return self.value is not None

    def cite(self) -> str:
        """Short citation for a results row: the source, and where it was read."""
        return f"{self.source} [read at: {self.read_at}]" if self.read_at else self.source

    def cite_draft(self) -> str:
        """Citation of the draft's value ("" without a draft)."""
        if self.draft is None:
            return ""
        return f"{self.draft['source']} [read at: {self.draft['read_at']}; printed: \"{self.draft['quote']}\"]"


def _as_text(v) -> str:
    if v is None:
        return ""
    if isinstance(v, (list, tuple)):
        return "; ".join(str(x) for x in v)
    return str(v)


def _entries(node, prefix: str, out: dict, where: Path) -> None:
    """Collect every numeric entry (a mapping with ``value``, or a table with ``pairs``) under
    ``node``; check its provenance."""
    if isinstance(node, dict):
        if "pairs" in node and "value" not in node:
            # a table: its pairs are its value (tables are overridden as a whole)
            node = {**node, "value": node["pairs"]}
        if "value" in node:
            if not node.get("source"):
                raise StabflowError(f"{where}: {prefix}.source: every value needs its source")
            if node["value"] is None and not node.get("missing"):
                raise StabflowError(f"{where}: {prefix}.missing: a null value must say what was searched")
            if node["value"] is not None and not node.get("read_at"):
                raise StabflowError(f"{where}: {prefix}.read_at: a value must say where it was read")
            if "draft" in node:
                _check_draft(node, prefix, where)
            out[prefix] = node
        for k, v in node.items():
            if isinstance(v, (dict, list)) and k not in ("value", "draft"):
                _entries(v, f"{prefix}.{k}", out, where)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            if isinstance(v, dict):
                _entries(v, f"{prefix}.{i}", out, where)


def _check_draft(node: dict, prefix: str, where: Path) -> None:
    """A draft's value: only beside a null value, a number (or a table: rows of numbers, with its
    ``columns``), with its source, where it was read and the words printed."""
    d = node["draft"]
    field = f"{prefix}.draft"
    if node["value"] is not None:
        raise StabflowError(f"{where}: {field}: a draft is kept only where the adopted value is missing (null)")
    keys = {"value", "source", "read_at", "quote"}
    if not isinstance(d, dict) or not keys <= set(d) or set(d) - keys - {"columns"}:
        raise StabflowError(f"{where}: {field}: give value, source, read_at and quote (and columns for a table), "
                            "nothing else")

    def number(v):
        return isinstance(v, (int, float)) and not isinstance(v, bool)

    v = d["value"]
    if isinstance(v, list):
        cols = d.get("columns")
        if not isinstance(cols, list) or not cols or not v or any(
                not isinstance(r, list) or len(r) != len(cols) or not all(number(x) for x in r) for r in v):
            raise StabflowError(f"{where}: {field}.value: a table's rows must each hold one number per column "
                                f"({cols!r})")
    elif not number(v):
        raise StabflowError(f"{where}: {field}.value: {v!r} is not a number")
    elif "columns" in d:
        raise StabflowError(f"{where}: {field}.columns: only a table has columns")
    for k in ("source", "read_at", "quote"):
        if not str(d[k]).strip():
            raise StabflowError(f"{where}: {field}.{k}: empty")


class Standards:
    """All criteria data, with optional user overrides.

    Parameters
    ----------
    overrides : path of a YAML file ``{criteria_overrides: [{key, value, source}, ...]}``, or None.
    data_dir : folder of the data files (default: the shipped ``resources/criteria``).
    """

    def __init__(self, overrides: str | Path | None = None, data_dir: str | Path | None = None):
        self.data_dir = Path(data_dir) if data_dir else DATA_DIR
        self.raw: dict[str, Any] = {}
        self.entries: dict[str, dict] = {}
        for name in FILES:
            path = self.data_dir / f"{name}.yaml"
            self.raw[name] = load_yaml(path)
            _entries(self.raw[name], name, self.entries, path)
        self.overridden: dict[str, dict] = {}
        if overrides:
            self._apply(Path(overrides))

    def _apply(self, path: Path) -> None:
        data = load_yaml(path)
        if not isinstance(data, dict) or set(data) != {"criteria_overrides"} or not isinstance(data["criteria_overrides"], list):
            raise StabflowError(f"{path}: criteria_overrides: the file must hold one list 'criteria_overrides'")
        for i, item in enumerate(data["criteria_overrides"]):
            field = f"criteria_overrides.{i}"
            if not isinstance(item, dict) or not {"key", "value", "source"} <= set(item) or set(item) - {"key", "value", "source", "unit"}:
                raise StabflowError(f"{path}: {field}: give key, value and source (unit optional), nothing else")
            key = item["key"]
            if key not in self.entries:
                raise StabflowError(f"{path}: {field}.key: '{key}' is not a criteria entry")
            old = self.entries[key]
            v = item["value"]
            if isinstance(old.get("value"), list):
                ok = (isinstance(v, list) and len(v) >= 2 and all(isinstance(r, list) and len(r) == 2 and all(
                    isinstance(x, (int, float)) and not isinstance(x, bool) for x in r) for r in v)
                      and all(a[0] < b[0] for a, b in zip(v, v[1:])))
            else:
                ok = isinstance(v, (int, float)) and not isinstance(v, bool)
            if not ok:
                raise StabflowError(f"{path}: {field}.value: {v!r} is not a value of the kind '{key}' holds")
            if not str(item["source"]).strip():
                raise StabflowError(f"{path}: {field}.source: say which document and paragraph the value is from")
            if "unit" in item and old.get("unit") and item["unit"] != old["unit"]:
                raise StabflowError(f"{path}: {field}.unit: '{item['unit']}' but '{key}' is in '{old['unit']}'")
            self.entries[key] = {**old, "value": v, "source": str(item["source"]), "read_at": f"override file {path}",
                                 "missing": ""}
            self.overridden[key] = self.entries[key]

    def get(self, key: str) -> Standard:
        """The standard at ``key`` (``<file>.<path>``); a StabflowError if there is no such entry."""
        if key not in self.entries:
            raise StabflowError(f"criteria data: no entry '{key}'")
        e = self.entries[key]
        return Standard(key, e["value"], str(e.get("unit", "")), str(e["source"]), _as_text(e.get("read_at")),
                        "" if e["value"] is not None else str(e.get("missing", "")),
                        e.get("draft") if e["value"] is None else None)

    def get_or_missing(self, key: str, source: str) -> Standard:
        """The standard at ``key``, or a missing Standard (value None) when the data files hold no
        such entry: for standards whose place in the data is not settled yet."""
        if key in self.entries:
            return self.get(key)
        return Standard(key, None, "", source, "", f"no entry '{key}' in resources/criteria")

    def value(self, key: str):
        """The value at ``key``; a StabflowError naming it if the value is missing (for values the
        computation itself needs and which are always sourced, e.g. the weather-criterion tables)."""
        s = self.get(key)
        if s.value is None:
            raise StabflowError(f"criteria data: '{key}' has no value ({s.missing})")
        return s.value

    def table(self, key: str):
        """(x, y) arrays of a table entry (``pairs``), with its Standard."""
        import numpy as np

        node = self.entries.get(key)
        if node is None:
            raise StabflowError(f"criteria data: no entry '{key}'")
        pairs = node["value"]
        if pairs is None:
            raise StabflowError(f"criteria data: '{key}' has no table")
        a = np.asarray(pairs, float)
        return a[:, 0], a[:, 1], Standard(key, pairs, f"{node.get('y', '')}", str(node.get("source", "")),
                                          _as_text(node.get("read_at")))

    def _node(self, key: str) -> dict:
        name, *path = key.split(".")
        node = self.raw.get(name)
        for p in path:
            node = node.get(p) if isinstance(node, dict) else None
        if not isinstance(node, dict):
            raise StabflowError(f"criteria data: no entry '{key}'")
        if not node.get("source"):
            raise StabflowError(f"criteria data: '{key}' has no source")
        return node

    def overrides_summary(self) -> list[str]:
        """One line per overridden entry: key = value (source), for the results' attributes."""
        return [f"{k} = {e['value']} ({e['source']}; {e['read_at']})" for k, e in self.overridden.items()]
