"""Offsets-table input and its errors."""

import numpy as np
import pytest

from stabflow import StabflowError
from stabflow.config import load_ship
from stabflow.geometry import build_hull
from stabflow.hydrostatics.statics import compute_statics


def _write(path, rows):
    path.write_text("# x, z1, y1, ...\n" + "\n".join(",".join(str(v) for v in r) for r in rows) + "\n")
    return path


def test_box_offsets_equal_analytic_box(tmp_path, ship_file):
    rows = [[x, 0, 10, 6, 10, 12, 10] for x in (-50, 0, 50)]
    _write(tmp_path / "box.csv", rows)
    p = ship_file("barge", name="offbox", hull={"source": "offsets", "file": "box.csv", "stations": 21})
    ship = load_ship(p)
    st = compute_statics(ship, build_hull(ship))
    barge = load_ship(ship_file("barge"))
    ref = compute_statics(barge, build_hull(barge))
    assert float(st.volume) == pytest.approx(12000.0)
    assert float(st.gm) == pytest.approx(3 + 400 / 72 - 7.0)
    assert np.allclose(st.gz, ref.gz, atol=1e-9)


@pytest.mark.parametrize(
    "rows,msg",
    [
        ([[0, 0, 1, 5, 2], [-1, 0, 1, 5, 2]], "stations must increase"),
        ([[0, 0, 1, 5, "nan"], [1, 0, 1, 5, 2]], "NaN"),
        ([[0, 0, -1, 5, 2], [1, 0, 1, 5, 2]], "negative half-breadth"),
        ([[0, 5, 1, 0, 2], [1, 0, 1, 5, 2]], "must not decrease"),
        ([[0, 0, 1, 5], [1, 0, 1, 5, 2]], "pairs"),
    ],
)
def test_malformed_offsets(tmp_path, ship_file, rows, msg):
    _write(tmp_path / "bad.csv", rows)
    p = ship_file("barge", name="bad", hull={"source": "offsets", "file": "bad.csv"})
    with pytest.raises(StabflowError, match=msg) as e:
        build_hull(load_ship(p))
    assert "bad.csv: line" in str(e.value)
