"""End-to-end: `snakemake -j2` on the small test profile builds the NetCDF files and the report."""

import os
import shutil
import subprocess
import sys

import pytest
import xarray as xr

from .conftest import ROOT


@pytest.fixture(scope="module")
def pipeline(tmp_path_factory):
    """Run the workflow on config/test.yaml into a temporary results folder."""
    out = tmp_path_factory.mktemp("wf") / "results"
    cmd = [sys.executable, "-m", "snakemake", "-j2", "--configfile", "config/test.yaml",
           "--config", f"results={out}", "-q", "--nolock"]
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-4000:]
    return out


def test_lint_clean():
    r = subprocess.run([sys.executable, "-m", "snakemake", "--lint"], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0 and "Lints for" not in r.stdout + r.stderr, r.stdout + r.stderr


def test_netcdf_outputs(pipeline):
    for ship in ["barge", "wigley"]:
        with xr.open_dataset(pipeline / "statics" / f"{ship}.nc") as ds:
            assert ds.gz.attrs["units"] == "m" and ds.heel.size == 181
        with xr.open_dataset(pipeline / "validation" / f"{ship}_statics.nc") as ds:
            assert ds.passed.all()
        assert (pipeline / "hull" / f"{ship}_bodyplan.png").exists()
        with xr.open_dataset(pipeline / "validation" / f"{ship}_waves.nc") as ds:
            assert ds.passed.all()
        with xr.open_dataset(pipeline / "waves" / f"{ship}.nc") as ds:
            assert ds.gm_wave.attrs["units"] == "m" and "gz_crest" in ds
        with xr.open_dataset(pipeline / "rao" / f"{ship}_sq.nc") as ds:
            assert ds.roll_rao.attrs["units"] == "1" and ds.wavelength_ratio.size == 2
            assert float(ds.heave_rao.max()) > 0.2
    table = (pipeline / "waves" / "early_stage_C.csv").read_text().splitlines()
    assert table[0].startswith("ship,sea_state") and len(table) == 1 + 2 * 2


def test_report_has_chapters_and_validation_table(pipeline):
    html = pipeline / "report" / "html"
    for page in ["index", "ship_barge", "ship_wigley", "waves", "validation", "methods"]:
        assert (html / f"{page}.html").exists(), page
    val = (html / "validation.html").read_text()
    assert "<table" in val and "PASS" in val and "exact polygon clipping" in val
    assert "WARNING" not in (html / "build.log").read_text()
    # every image the pages reference exists
    import re

    for page in html.glob("*.html"):
        for src in re.findall(r'<img [^>]*src="([^"]+)"', page.read_text()):
            assert (html / src).exists(), (page.name, src)


def test_rerun_is_bit_identical(pipeline, tmp_path):
    """Same config → bit-identical NetCDF files (hull, statics)."""
    out = tmp_path / "again"
    cmd = [sys.executable, "-m", "snakemake", "-j1", "--configfile", "config/test.yaml",
           "--config", f"results={out}", "-q", "--nolock", f"{out}/statics/barge.nc"]
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    for f in ["hull/barge.nc", "statics/barge.nc"]:
        assert (pipeline / f).read_bytes() == (out / f).read_bytes(), f


def test_report_in_headless_chromium(pipeline, tmp_path):
    """Open the built book in a real browser and save a screenshot."""
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        if os.environ.get("CI"):
            pytest.fail("chromium missing in CI (.ci/run installs it)")
        pytest.skip("chromium not installed")
    shot = tmp_path / "report.png"
    index = pipeline / "report" / "html" / "validation.html"
    r = subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                        "--disable-background-networking", "--disable-component-update", "--disable-sync",
                        f"--user-data-dir={tmp_path / 'profile'}", "--window-size=1200,900",
                        f"--screenshot={shot}", index.as_uri()], capture_output=True, text=True, timeout=120)
    assert shot.exists() and shot.stat().st_size > 10_000, r.stderr[-2000:]
    keep = os.environ.get("STABFLOW_SCREENSHOT")
    if keep:
        shutil.copy(shot, keep)
