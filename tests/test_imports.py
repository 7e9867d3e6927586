"""Every module of the package and every workflow script imports in this environment.

CI runs the suite in a brand-new virtual environment made from pyproject.toml alone, so an import
that only works because a package was once installed by hand fails here."""

import ast
import importlib
import pkgutil

import pytest

import stabflow

from .conftest import ROOT

MODULES = sorted(m.name for m in pkgutil.walk_packages(stabflow.__path__, "stabflow."))
SCRIPTS = sorted((ROOT / "workflow" / "scripts").glob("*.py"))


def test_found_the_code():
    assert len(MODULES) > 20 and len(SCRIPTS) > 10


@pytest.mark.parametrize("name", MODULES)
def test_module_imports(name):
    importlib.import_module(name)


def _imports(tree: ast.AST) -> set[str]:
    """Every module named by an import statement anywhere in the tree (also inside functions, where
    stabflow keeps its heavy optional imports)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out.add(node.module)
    return out


@pytest.mark.parametrize("name", MODULES)
def test_lazy_imports_of_module_resolve(name):
    """Imports inside functions (pyextremes, capytaine, navaltoolbox, networkx through trimesh...)
    resolve too: a missing dependency would otherwise surface only when that step runs."""
    spec = importlib.util.find_spec(name)
    tree = ast.parse(open(spec.origin).read())
    for mod in sorted(_imports(tree)):
        importlib.import_module(mod)


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_workflow_script_imports(script):
    """The scripts run inside Snakemake (which injects ``snakemake``); compile them and import
    everything they import."""
    tree = ast.parse(script.read_text(), filename=str(script))
    compile(tree, str(script), "exec")
    mods = _imports(tree)
    assert mods, script
    for mod in sorted(mods):
        importlib.import_module(mod)


def test_trimesh_section_traversal_dependency():
    """trimesh's mesh sections (used to cut stations) need networkx at call time."""
    import trimesh

    box = trimesh.creation.box(extents=[2, 2, 2])
    assert box.section(plane_origin=[0, 0, 0], plane_normal=[1, 0, 0]) is not None
