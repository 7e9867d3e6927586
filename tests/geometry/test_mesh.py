"""Mesh ingestion: gzip, transforms, open decks and bad files."""

import gzip

import numpy as np
import pytest
import trimesh

from stabflow import StabflowError
from stabflow.config import load_ship
from stabflow.geometry import build_hull
from stabflow.geometry.mesh import load_mesh
from stabflow.validation.references import submerged

from ..conftest import ROOT


def _box_stl(path, gz=False, open_deck=False, flip=False):
    m = trimesh.creation.box(extents=[100, 20, 12])
    m.apply_translation([0, 0, 6])
    if open_deck:
        keep = ~(m.triangles_center[:, 2] > 11.99)
        m = trimesh.Trimesh(m.vertices, m.faces[keep], process=False)
    if flip:
        m.vertices[:, 1:] *= -1
    data = trimesh.exchange.stl.export_stl(m)
    path.write_bytes(gzip.compress(data) if gz else data)
    return path


@pytest.mark.parametrize("gz,open_deck,flip", [(False, False, False), (True, False, False), (False, True, True)])
def test_box_mesh_equals_analytic_box(tmp_path, ship_file, gz, open_deck, flip):
    stl = _box_stl(tmp_path / ("box.stl.gz" if gz else "box.stl"), gz, open_deck, flip)
    p = ship_file("barge", name="meshbox", hull={"source": "mesh", "file": stl.name, "stations": 21,
                                                  "transform": {"flip_z": flip}})
    ds = build_hull(load_ship(p))
    assert float(ds.hull_volume) == pytest.approx(100 * 20 * 12, rel=1e-9)
    assert np.allclose(ds["section_area_full"], 240.0)


def test_mesh_reference_integration_box():
    m = trimesh.creation.box(extents=[100, 20, 12])
    m.apply_translation([0, 0, 6])
    V, c = submerged(m, 0.0, 0.0, -6.0)
    assert V == pytest.approx(12000.0)
    assert c == pytest.approx([0, 0, -3.0], abs=1e-9)


@pytest.mark.parametrize("content", [b"", b"solid x\nendsolid x\n", b"not a mesh at all"])
def test_bad_mesh_files(tmp_path, content):
    p = tmp_path / "bad.stl"
    p.write_bytes(content)
    with pytest.raises(StabflowError, match="bad.stl"):
        load_mesh(p)


def test_missing_mesh(tmp_path):
    with pytest.raises(StabflowError, match="not found"):
        load_mesh(tmp_path / "nothere.stl")


def test_trawler_open_deck_z_down():
    """The shipped open-deck, z-down trawler mesh is closed at the deck edge and flipped."""
    m = load_mesh(ROOT / "resources/hulls/trawler_25m.stl", flip_z=True)
    assert m.bounds[0, 2] == pytest.approx(-0.69, abs=0.01)
    assert m.bounds[1, 2] == pytest.approx(6.147, abs=0.01)


def test_mesh_gz_reference_finds_its_own_equilibrium():
    """The mesh reference solves its own free-trim equilibrium (bracketed height, then fsolve with
    its convergence flag read): on a box mesh it equals the exact polygon-clipping GZ, and a volume
    the hull cannot displace raises instead of returning a number."""
    import numpy as np
    import pytest
    import trimesh

    from stabflow.validation.references import mesh_gz
    from stabflow.validation.references import exact_box_gz

    m = trimesh.creation.box(extents=[100, 20, 12])
    m.apply_translation([0, 0, 6])
    heels = np.array([0.0, 20.0, 50.0, 90.0, 130.0, 180.0])
    ref = exact_box_gz(100.0, 20.0, 12.0, 12000.0, 7.0, heels)
    assert np.abs(mesh_gz(m, 12000.0, 0.0, 7.0, heels) - ref).max() < 1e-6
    with pytest.raises(ValueError):
        mesh_gz(m, 30000.0, 0.0, 7.0, [10.0])  # more than the hull's 24000 m3: no bracket


def test_inward_normals_are_reversed_with_a_warning(tmp_path):
    """A closed mesh stored with inward normals (negative enclosed volume, as the trawler STL) is
    turned outward with a warning, so surface integrals (mesh GZ, pressure, Capytaine) are right."""
    import pytest
    import trimesh

    from stabflow.geometry.mesh import load_mesh

    m = trimesh.creation.box(extents=[10, 4, 2])
    m.invert()
    assert m.volume < 0
    path = tmp_path / "inward.stl"
    m.export(path)
    with pytest.warns(UserWarning, match="normals point inward"):
        out = load_mesh(path)
    assert out.volume == pytest.approx(80.0)
