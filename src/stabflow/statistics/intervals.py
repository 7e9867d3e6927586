"""Interval building blocks shared by the extremes and split-time steps."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np


def record_bootstrap(rng: np.random.Generator, records, values: np.ndarray, value_records: np.ndarray,
                     n_boot: int) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Bootstrap over records: ``n_boot`` times, draw ``len(records)`` records with replacement and
    yield (the drawn records, the concatenation of their ``values``), where ``value_records[i]`` is
    the record of ``values[i]``. Records are the independent units (each starts from rest in its
    own seaway), so resampling them keeps the dependence between events within a record."""
    records = np.asarray(records)
    by_record = {r: values[value_records == r] for r in np.unique(value_records)}
    empty = np.zeros(0)
    for _ in range(n_boot):
        pick = rng.choice(records, size=len(records), replace=True)
        yield pick, np.concatenate([by_record.get(r, empty) for r in pick])
