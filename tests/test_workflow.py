"""End-to-end: `snakemake -j2` on the small test profile builds the NetCDF files and the report."""

import os
import shutil
import subprocess
import sys

import pytest
import xarray as xr

from .cluster.background import slurm_runs  # noqa: F401  (session fixture: SLURM runs started at session start)
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


GM_EXACT_VARIATION = ("GM in quartering waves lambda = L, H = T/3, ship held: first-harmonic variation vs pressure "
                      "integration (exact wave surface)")
HEEL_EXACT_10 = ("pressure decay, beam waves at twice the roll frequency, ship held at +-10 deg: heel's part of the "
                 "roll moment vs pressure integration with decay on the exact wave surface")
BEAM_HEAVE = ("d2phi/dzdt option, beam waves at twice the roll frequency, H/lambda = 1/500: heave vs pressure "
              "integration with decay")
HYBRID = [f"diffraction option, beam waves, ship held: {label}, kernel FK with decay + Capytaine diffraction vs "
          "Capytaine FK + diffraction" for label in ("roll at the roll frequency", "heave at twice the roll frequency")]


def test_netcdf_outputs(pipeline):
    for ship in ["barge", "wigley"]:
        with xr.open_dataset(pipeline / "statics" / f"{ship}.nc") as ds:
            assert ds.gz.attrs["units"] == "m" and ds.heel.size == 181
        for step in ("statics", "waves", "dynamics"):
            with xr.open_dataset(pipeline / "validation" / f"{ship}_{step}.nc") as ds:
                status = list(ds.status.values)
                fails = [str(n) for n, s in zip(ds.name.values, status) if s == "FAIL"]
                # the expected FAIL: the planar waterline's GM variation against the exact surface
                # (barge +24.8 %), README time-domain model; its heave in short beam waves, +12 % and
                # +11.7 % with the diffraction option before the cross-beam correction (2026-12-07),
                # passes now (README: within 0.1 %); and the heel's part of the roll moment in beam waves
                # at +-10 deg against the exact surface (7.8 %: the heeled section's cross-beam terms are
                # of the first order in the heel; at +-2 deg 0.8 %, PASS)
                expected = [GM_EXACT_VARIATION, HEEL_EXACT_10] if (ship, step) == ("barge", "dynamics") else []
                assert fails == expected, (ship, step, fails)
                if (ship, step) == ("barge", "dynamics"):
                    names = [str(n) for n in ds.name.values]
                    for row in (BEAM_HEAVE, *HYBRID):
                        assert status[names.index(row)] == "PASS", row
                assert status.count("PASS") >= 3
                assert set(ds.kind.values) <= {"independent", "consistency"}
                skipped = ds.status.values == "SKIPPED"
                assert all(len(str(r)) > 0 for r in ds.reason.values[skipped])
        assert (pipeline / "hull" / f"{ship}_bodyplan.png").exists()
        with xr.open_dataset(pipeline / "waves" / f"{ship}.nc") as ds:
            assert ds.gm_wave.attrs["units"] == "m" and "gz_crest" in ds
        with xr.open_dataset(pipeline / "rao" / f"{ship}_sq.nc") as ds:
            assert ds.roll_rao.attrs["units"] == "1" and ds.wavelength_ratio.size == 2
            assert float(ds.heave_rao.max()) > 0.2
    table = (pipeline / "waves" / "early_stage_C.csv").read_text().splitlines()
    assert table[0].startswith("ship,sea_state") and len(table) == 1 + 2 * 2


def test_ensemble_validation_rows(pipeline):
    """The ensemble condition has rows for the seaway, the step size, extremes per target and
    split-time per threshold; each row is PASS, FAIL or SKIPPED with a reason, never absent."""
    with xr.open_dataset(pipeline / "validation" / "barge_beam_ensemble.nc") as ds:
        names = " ".join(str(n) for n in ds.name.values).lower()
        for word in ("variance", "spectr", "skew", "step", "coverage", "split-time"):
            assert word in names, word
        assert set(ds.status.values) <= {"PASS", "FAIL", "SKIPPED"}
        bad = (ds.status.values != "PASS")
        assert all(len(str(r)) > 0 or s == "FAIL" for r, s in zip(ds.reason.values[bad], ds.status.values[bad]))


def test_report_has_chapters_and_validation_table(pipeline):
    html = pipeline / "report" / "html"
    for page in ["index", "ship_barge", "ship_wigley", "waves", "validation", "methods"]:
        assert (html / f"{page}.html").exists(), page
    val = (html / "validation.html").read_text()
    assert "<table" in val and "PASS" in val and "exact polygon clipping" in val
    # one table per step, each with its summary line; kinds shown
    assert val.count("<table") >= 5
    for title in ("Calm-water statics", "Stability in waves", "Time domain", "Irregular seas"):
        assert title in val, title
    assert "independent" in val and "consistency" in val
    index = (html / "index.html").read_text()
    assert "Validation at a glance" in index and "pass" in index
    assert "WARNING" not in (html / "build.log").read_text()
    # every image the pages reference exists
    import re

    for page in html.glob("*.html"):
        for src in re.findall(r'<img [^>]*src="([^"]+)"', page.read_text()):
            assert (html / src).exists(), (page.name, src)


def test_broaching_chapter_tabulates_both_hull_derivative_sets(pipeline):
    """The broaching chapter lists Clarke's and the slender-body derivatives, marks the set in use
    and gives each set's sway-yaw eigenvalue as the results file holds it."""

    with xr.open_dataset(pipeline / "broaching" / "barge.nc") as d:
        md = (pipeline / "report" / "html" / "_sources" / "broaching.md").read_text()
        assert d.attrs["hull_derivatives"] == "clarke"
        assert "| Clarke et al. (1983) (used) |" in md and "| slender body, hull profile |" in md
        for k in ("clarke", "slender_body"):
            assert f"{float(d[f'{k}_yv']):.4f}" in md
            assert f"{float(d[f'sway_yaw_eigenvalue_{k}']):+.3f}" in md
        assert float(d["derivative_yv"]) == float(d["clarke_yv"])


def test_criteria_results_and_chapters(pipeline):
    """Every ship has its criteria file and chapter: IS Code rows with verdicts (the barge and the
    Wigley hull carry their own windage), unsourced standards NOT EVALUATED with the item named."""
    html = pipeline / "report" / "html"
    for ship in ["barge", "wigley"]:
        with xr.open_dataset(pipeline / "criteria" / f"{ship}.nc") as ds:
            verdicts = dict(zip((str(n) for n in ds.criterion_name.values), (str(v) for v in ds.verdict.values)))
            assert set(verdicts.values()) <= {"PASS", "FAIL", "NOT EVALUATED"}
            assert verdicts["area under GZ, 0 to 30 deg"] == "PASS"
            assert verdicts["weather criterion: area b / area a"] in ("PASS", "FAIL")
            ne = ds.verdict.values == "NOT EVALUATED"
            assert ne.any() and all("missing:" in str(r) for r in ds.verdict_reason.values[ne])
            assert all(len(str(s)) > 0 for s in ds.criterion_source.values)
        page = (html / f"criteria_{ship}.html").read_text()
        assert "NOT EVALUATED" in page and "PASS" in page and "<table" in page
        # the (reduced) direct stability assessment: a long-term rate with its interval, never a bare 0
        with xr.open_dataset(pipeline / "criteria" / f"{ship}_dsa.nc") as d:
            assert float(d.rate_lo) <= float(d.rate) <= float(d.rate_hi) and float(d.rate_hi) > 0
            assert set(d.method.values.astype(str)) <= {"screened", "counted", "extrapolated"}
            assert (d.cell_rate_hi.values > 0).all()  # every cell's upper bound too
        assert "Direct stability assessment" in page
        # the screening checked by simulating the screened cells (their verdict in the chapter)
        assert "checked by simulation" in page and f"<strong>{d.attrs['screen_recheck_verdict']}</strong>:" in page
    with xr.open_dataset(pipeline / "validation" / "dsa_linear_criteria.nc") as ds:
        status = dict(zip((str(n) for n in ds.name.values), (str(s) for s in ds.status.values)))
        assert list(status.values())[0] == "PASS"
        assert [v for k, v in status.items() if k.startswith("Grim's effective wave")] == ["PASS"]
    with xr.open_dataset(pipeline / "validation" / "barge_criteria.nc") as ds:
        status = dict(zip((str(n) for n in ds.name.values), (str(s) for s in ds.status.values)))
        # closed forms of the box and the linear beam-sea model in small waves pass; at 5 deg roll
        # the barge's time domain (the DSA's kernel, with the pressure-decay term) rolls about a
        # fifth more than the linear model: a recorded FAIL
        beam = [k for k in status if k.startswith("beam seas without way")]
        assert len(beam) == 2 and status[beam[0]] == "PASS" and status[beam[1]] == "FAIL"
        value = dict(zip((str(n) for n in ds.name.values), ds.value.values.astype(float)))
        # the README's +34.9 % at roll sigma 5 deg with the complete pressure decay (+22.5 % with its
        # vertical term alone)
        assert 0.28 < value[beam[1]] < 0.42
        # the level-1 routes against each other: the box's waterplane route has delta GM 0 (its
        # inertia does not change with draft), the wave pass the second-order change: -100 %, FAIL
        routes = [k for k in status if k.startswith(("level-1 parametric rolling", "level-1 pure loss"))]
        assert len(routes) == 2 and {status[k] for k in routes} == {"FAIL"}
        assert value[routes[0]] == -1.0
        # the DSA screening against the screened cells' own simulation (a consistency row)
        screening = [k for k in status if k.startswith("DSA screening")]
        with xr.open_dataset(pipeline / "criteria" / "barge_dsa.nc") as d:
            verdict = d.attrs["screen_recheck_verdict"]
        assert len(screening) == 1 and status[screening[0]] == ("PASS" if verdict == "PASS" else "FAIL")
        assert {v for k, v in status.items() if k not in beam + routes + screening} == {"PASS"} and len(status) >= 13
    with xr.open_dataset(pipeline / "validation" / "wigley_criteria.nc") as ds:
        # the Wigley hull's linear beam-sea model against the time domain in the same beam sea:
        # 0.5 deg within 3 % and 5 deg within 10 % (measured -0.44 % and +1.9 % with the complete
        # pressure decay of the DSA's runs; -0.44 % and -0.26 % without it)
        rows = [(str(s), str(k), float(v)) for n, s, k, v in zip(ds.name.values, ds.status.values, ds.kind.values,
                                                                  ds.value.values) if str(n).startswith("beam seas")]
        assert [r[:2] for r in rows] == [("PASS", "consistency")] * 2, rows
        assert abs(rows[0][2]) < 0.01 and 0.01 < rows[1][2] < 0.03, rows


def test_criteria_chapter_names_the_acceleration_failure(pipeline, tmp_path):
    """The DSA paragraph names the sourced lateral-acceleration limit (Circ.1627 3.2.1.2) and the crew
    location's height above G; a DSA file without them (no limit) says that side is not assessed.
    The DSA row has a verdict against the sourced standard (3.1.2)."""
    import shutil

    from stabflow.report.book import criteria_page

    res = tmp_path / "results"
    (res / "criteria").mkdir(parents=True)
    for f in (pipeline / "criteria").glob("barge*"):
        shutil.copy(f, res / "criteria")
    (tmp_path / "fig").mkdir()
    page = criteria_page("barge", res, tmp_path / "fig")
    assert "lateral acceleration beyond **9.81 m/s²** at the crew location" in page and "3.2.1.2" in page
    with xr.open_dataset(res / "criteria" / "barge_dsa.nc") as d:
        d = d.load()
    # the row's verdict follows the interval against the standard (Circ.1627 3.1.2, 2.6e-3 per year):
    # FAIL above it, PASS below it, NOT EVALUATED when it straddles it (the test run's 5-min records
    # counted a failure on the barge with the complete pressure decay, 0.057 per year at least: FAIL;
    # with the vertical term alone none: NOT EVALUATED)
    lo, hi = float(d.rate_lo), float(d.rate_hi)
    expected = "FAIL" if lo > 2.6e-3 else "PASS" if hi <= 2.6e-3 else "NOT EVALUATED"
    assert d.attrs["row_verdict"] == expected and d.attrs["row_limit"] == 2.6e-3
    if expected == "NOT EVALUATED":
        assert "straddles the standard" in d.attrs["row_reason"]
    for k in ("lateral_acceleration_limit", "crew_height_above_g", "lateral_acceleration_source"):
        del d.attrs[k]
    d.to_netcdf(res / "criteria" / "barge_dsa.nc")
    assert "lateral-acceleration failure is not assessed" in criteria_page("barge", res, tmp_path / "fig")


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


def test_validation_tables_fit_a_1400px_window(pipeline, tmp_path):
    """In a 1400 px wide browser window no validation table runs past the right edge (long
    references and reasons wrap): measured in headless Chromium from the laid-out page."""
    import re

    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        if os.environ.get("CI"):
            pytest.fail("chromium missing in CI (.ci/run installs it)")
        pytest.skip("chromium not installed")
    html = pipeline / "report" / "html"
    probe = html / "_fit_probe.html"
    js = ("<script>window.addEventListener('load', () => { const r = [...document.querySelectorAll('table')]"
          ".map(t => Math.ceil(t.getBoundingClientRect().right)); document.body.setAttribute('data-fit', "
          "document.documentElement.scrollWidth + ',' + window.innerWidth + ',' + r.length + ',' + Math.max(0, ...r)); });"
          "</script></body>")
    probe.write_text((html / "validation.html").read_text().replace("</body>", js))
    try:
        r = subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                            "--disable-background-networking", "--disable-component-update", "--disable-sync",
                            f"--user-data-dir={tmp_path / 'profile'}", "--window-size=1400,900",
                            "--virtual-time-budget=10000", "--dump-dom", probe.as_uri()],
                           capture_output=True, text=True, timeout=120)
    finally:
        probe.unlink()
    m = re.search(r'data-fit="(\d+),(\d+),(\d+),(\d+)"', r.stdout)
    assert m, r.stderr[-2000:]
    scroll, inner, ntab, right = map(int, m.groups())
    assert ntab >= 5
    assert right <= inner and scroll <= inner, (scroll, inner, right)


ENS = "ensemble/barge_beam"


def _ensemble_run(out, *extra, jobs="-j1"):
    cmd = [sys.executable, "-m", "snakemake", jobs, "--configfile", "config/test.yaml", "--config", f"results={out}",
           "-q", "--nolock", *extra, f"{out}/{ENS}/ensemble.nc"]
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)


def _ensemble_files(out):
    return {p.name: p.read_bytes() for p in sorted((out / ENS).glob("*")) if p.suffix in (".nc", ".png")}


def test_ensemble_outputs(pipeline):
    with xr.open_dataset(pipeline / ENS / "ensemble.nc") as e:
        assert e.sizes["record"] == 24 and e["roll_std"].attrs["long_name"].startswith("standard deviation") and e["roll_std"].attrs["units"] == "degree"
        assert float(e["exposure_hours"]) > 0 and e.sizes["sample"] == 2
        assert float(e["roll_std"]) > 1.0
    for f in ["roll_distribution.png", "spectra.png", "time_histories.png"]:
        assert (pipeline / ENS / f).stat().st_size > 10_000


def test_extremes_and_splittime_outputs(pipeline):
    with xr.open_dataset(pipeline / "extremes" / "barge_beam.nc") as x:
        assert x.sizes["block"] == 6 and x["rate_estimate"].attrs["units"] == "1/h"
        assert ((x["coverage"] >= 0) & (x["coverage"] <= 1)).all()
    with xr.open_dataset(pipeline / "splittime" / "barge_beam.nc") as st:
        assert st.sizes["split_threshold"] == 2 and int(st["crossings"].min()) > 0
        assert (st["perturbed_runs"] > st["crossings"]).all()
        assert (st["capsize_rate_lower"] <= st["capsize_rate_upper"]).all()
    for f in ["extremes/barge_beam_validation.png", "splittime/barge_beam_perturbation.png", "splittime/barge_beam_rate.png"]:
        assert (pipeline / f).stat().st_size > 10_000, f
    page = (pipeline / "report" / "html" / "rare_events.html").read_text()
    assert "Split-time capsize rate" in page and "coverage" in page


def test_ensemble_j1_j2_identical(pipeline, tmp_path):
    """-j1 and the default -j2 run write bit-identical ensemble files (the SLURM executor: below)."""
    ref = _ensemble_files(pipeline)
    r = _ensemble_run(tmp_path / "j1")
    assert r.returncode == 0, r.stderr[-3000:]
    assert _ensemble_files(tmp_path / "j1") == ref


def test_ensemble_killed_and_rerun_is_bit_identical(pipeline, tmp_path):
    """Kill the workflow (SIGKILL to its process group) once the first shard exists, rerun: the
    finished files equal those of the uninterrupted run."""
    import signal
    import time

    out = tmp_path / "killed"
    cmd = [sys.executable, "-m", "snakemake", "-j1", "--configfile", "config/test.yaml", "--config",
           f"results={out}", "-q", "--nolock", f"{out}/{ENS}/ensemble.nc"]
    p = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    t0 = time.time()
    while not (out / ENS / "shard_0.nc").exists() and p.poll() is None and time.time() - t0 < 120:
        time.sleep(0.05)
    assert p.poll() is None, "workflow finished before it could be killed"
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    assert not (out / ENS / "ensemble.nc").exists()
    r = _ensemble_run(out, "--rerun-incomplete")
    assert r.returncode == 0, r.stderr[-3000:]
    assert _ensemble_files(out) == _ensemble_files(pipeline)


def _netcdf_files(out):
    return {str(p.relative_to(out)): p for p in sorted(out.rglob("*.nc"))}


@pytest.mark.slurm
def test_slurm_executor_dag_bit_identical(pipeline, slurm_runs):  # noqa: F811
    """The whole test DAG through the SLURM executor (`snakemake --workflow-profile
    workflow/profiles/slurm` on the throwaway cluster of tests/cluster/slurm.py, every rule a SLURM
    job, shards with the profile's threads capped to the node) writes every NetCDF file of the local
    -j2 run, bit-identical."""
    run = slurm_runs.wait("dag")
    assert run.returncode == 0, run.tail()
    assert run.output.count("submitted with SLURM jobid") >= 25, run.tail()  # every rule a SLURM job
    ref, got = _netcdf_files(pipeline), _netcdf_files(run.out)
    assert len(ref) >= 25 and sorted(got) == sorted(ref), (sorted(set(ref) ^ set(got)), run.tail(2000))
    differ = [f for f in ref if ref[f].read_bytes() != got[f].read_bytes()]
    assert not differ, differ


@pytest.mark.slurm
def test_slurm_cancelled_shard_reported_and_rerun_bit_identical(pipeline, slurm_runs):  # noqa: F811
    """scancel of a running shard's SLURM job: the workflow stops with an error naming the job and
    its CANCELLED state, the shard has no output; the same command again completes, keeps the shards
    that had finished and writes ensemble files bit-identical to the local run."""
    kill = slurm_runs.wait("kill")
    assert "jobid" in kill.notes, ("no shard job was cancelled while running", kill.notes, kill.tail())
    jobid, shard = kill.notes["jobid"], kill.notes["shard"]
    assert kill.returncode not in (0, None), kill.tail()
    assert "Error in rule ensemble_shard" in kill.output and f"SLURM-job '{jobid}' failed" in kill.output, kill.tail()
    assert "CANCELLED" in kill.output, kill.tail()
    rerun = slurm_runs.wait("rerun")
    assert f"shard_{shard}.nc" not in rerun.notes["kept_before"]
    assert rerun.returncode == 0, rerun.tail()
    out = rerun.out / ENS
    for name, mtime in rerun.notes["kept_before"].items():
        assert (out / name).stat().st_mtime_ns == mtime, f"{name} finished before the cancel but was redone"
    assert _ensemble_files(rerun.out) == _ensemble_files(pipeline)
