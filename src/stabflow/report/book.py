"""Build the validation report (Jupyter Book 1.x) from the NetCDF results.

The pages are MyST markdown generated here from ``results/``; the book only renders them
(``execute_notebooks: off``), so building the report never re-runs a simulation.
"""

from __future__ import annotations

import csv
import os
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from stabflow import __version__

PARTICULARS = ["volume", "mass", "draft_mid", "trim_upright", "lcb", "lcg", "kb", "bm", "km", "kg", "gm",
               "waterplane_area", "gz_max", "heel_gz_max", "heel_vanishing"]


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _fmt(v) -> str:
    v = float(v)
    if not np.isfinite(v):
        return "–"
    return f"{v:.4g}" if abs(v) < 1e5 else f"{v:.4e}"


def _benchmarks(results: Path) -> list[tuple[str, float]]:
    rows = []
    for f in sorted((results / "benchmarks").rglob("*.tsv")):
        with open(f) as fh:
            rec = list(csv.DictReader(fh, delimiter="\t"))
        if rec:
            rows.append((str(f.relative_to(results / "benchmarks").with_suffix("")), float(rec[0]["s"])))
    return rows


def ship_page(name: str, results: Path, figdir: Path) -> str:
    """MyST page for one ship: body plan, particulars, GZ."""
    hull = _open(results / "hull" / f"{name}.nc")
    st = _open(results / "statics" / f"{name}.nc")
    for src in [results / "hull" / f"{name}_bodyplan.png", results / "statics" / f"{name}_gz.png"]:
        shutil.copy(src, figdir / src.name)
    lines = [f"# Ship: {name}", "", f"{hull.attrs.get('hull_source', '')} hull, {hull.sizes['station']} stations, "
             f"enclosed hull volume {float(hull.hull_volume):.1f} m³.", ""]
    lines += [
        f":::{{figure}} figures/{name}_bodyplan.png", f":name: fig-{name}-bodyplan", "",
        f"Body plan of {name}: the half contours of every station (aft body left, fore body right) as cut "
        "from the hull and used for the Bonjean tables. Look for smooth, closed sections from keel to deck; "
        "a missing or jagged section would point to a bad cut.", ":::", "",
        "## Hydrostatic particulars (upright, free trim)", "", "| quantity | value | unit |", "|---|---:|---|",
    ]
    for k in PARTICULARS:
        lines.append(f"| {st[k].attrs.get('long_name', k)} | {_fmt(st[k])} | {st[k].attrs.get('units', '')} |")
    lines += [
        "", "## Calm-water GZ", "",
        f":::{{figure}} figures/{name}_gz.png", f":name: fig-{name}-gz", "",
        f"Calm-water righting arm GZ of {name} from 0° to 180° heel with free trim (heave and trim in "
        "equilibrium at every heel); the dotted line is GM·φ. Look for the initial slope matching GM, the "
        "angle of maximum GZ and the angle of vanishing stability.", ":::", "",
    ]
    lines += waves_section(name, results, figdir)
    lines += rao_section(name, results, figdir)
    return "\n".join(lines)


def rao_section(name: str, results: Path, figdir: Path) -> list[str]:
    """Regular-wave response amplitudes of the time-domain model, one figure per condition."""
    lines = []
    for nc in sorted((results / "rao").glob(f"{name}_*.nc")):
        ds = _open(nc)
        if ds.attrs.get("ship") != name:
            continue
        cond = ds.attrs["condition"]
        shutil.copy(nc.with_suffix(".png"), figdir / nc.with_suffix(".png").name)
        if not lines:
            lines += ["## Time-domain response in regular waves (3-DOF, volume-based FK + HS)", ""]
        lines += [
            f":::{{figure}} figures/{nc.with_suffix('.png').name}", f":name: fig-{name}-rao-{cond}", "",
            f"{name}, condition {cond}: steady-state first-harmonic heave / a, roll / ka and pitch / ka against "
            f"L/λ, heading {ds.attrs['heading_deg']:g}° (0 = following), speed {ds.attrs['speed']:.2f} m/s, "
            f"H/λ = {ds.attrs['steepness']:g}. Natural periods: heave {ds.attrs['heave_period']:.1f} s, roll "
            f"{ds.attrs['roll_period']:.1f} s, pitch {ds.attrs['pitch_period']:.1f} s; added mass and damping from "
            f"{'Capytaine (dashed: Capytaine linear RAOs with full FK + diffraction + radiation, zero speed)' if ds.attrs.get('hydro') == 'capytaine' else 'the ship config'}. "
            "Look for heave/a → 1 in long waves and the roll peak where the encounter period meets the roll period; "
            "where the dashed curves depart, the simplified hydrodynamics (no diffraction) matter.", ":::", "",
        ]
    return lines


def waves_section(name: str, results: Path, figdir: Path) -> list[str]:
    """Wave-pass figures and the early-stage metric table for one ship (if computed)."""
    wnc, mnc = results / "waves" / f"{name}.nc", results / "waves" / f"{name}_metric.nc"
    if not (wnc.exists() and mnc.exists()):
        return []
    for src in [results / "waves" / f"{name}_gm.png", results / "waves" / f"{name}_gz_waves.png"]:
        shutil.copy(src, figdir / src.name)
    w = _open(wnc)
    m = _open(mnc)
    s = w.attrs["crest_trough_steepness"]
    lines = [
        "## Stability in waves (quasi-static wave pass)", "",
        f":::{{figure}} figures/{name}_gm.png", f":name: fig-{name}-gm", "",
        f"GM of {name} as a regular wave crest passes along the ship (free sinkage and trim, same displacement "
        f"and LCB as in calm water), one line per wave length at the steepest wave of the sweep (H/λ = "
        f"{float(w.steepness.max()):g}); dashed: calm water. Look for the drop of GM with the crest near "
        "amidships and its rise with a trough amidships.", ":::", "",
        f":::{{figure}} figures/{name}_gz_waves.png", f":name: fig-{name}-gzwaves", "",
        f"GZ of {name} with the crest amidships, the trough amidships (λ = L, H/λ = {s:g}) and in calm water. "
        "Look for the loss of righting arm on the crest and the gain in the trough.", ":::", "",
        "## Early-stage assessment metric C (paper 002)", "",
        f"Critical GM {float(m.gm_cr):.3f} m (calm-water GZ maximum at {m.attrs['critical_angle_deg']:g}°, not below "
        f"the minimum), KG_cr {float(m.kg_cr):.3f} m, roll period T_φ = {float(m.roll_period):.2f} s; "
        f"{m.attrs['speed_kn']:g} kn in following seas, {m.attrs['spectrum']} spectrum, wave pass at the "
        f"{m.attrs['loading_kg']} KG.", "",
        "| sea state | Hs [m] | Tm [s] | σ_ζ [m] | k1 [rad/m] | k2 [rad/m] | Σ W_ij (grid) | m(tbc) [s] | C [-] |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for i, ss in enumerate(m.sea_state.values):
        lines.append(f"| {ss} | {_fmt(m.hs[i])} | {_fmt(m.tm[i])} | {_fmt(m.sigma_zeta[i])} | {_fmt(m.k1[i])} | "
                     f"{_fmt(m.k2[i])} | {_fmt(m.weight_sum[i])} | {_fmt(m.mean_tbc[i])} | {_fmt(m.metric_c[i])} |")
    lines.append("")
    return lines


def waves_page(results: Path, figdir: Path) -> str | None:
    """Cross-ship page: table and bar chart of C (paper 002 Table 1 / Figure 6)."""
    csv_path = results / "waves" / "early_stage_C.csv"
    if not csv_path.exists():
        return None
    shutil.copy(results / "waves" / "early_stage_C.png", figdir / "early_stage_C.png")
    with open(csv_path) as fh:
        rec = list(csv.DictReader(fh))
    states = list(dict.fromkeys(r["sea_state"] for r in rec))
    ships = list(dict.fromkeys(r["ship"] for r in rec))
    lines = ["# Stability change in waves: metric C", "",
             ":::{figure} figures/early_stage_C.png", ":name: fig-metric-c", "",
             "Early-stage assessment metric C = m(tbc)/T_φ for every ship and sea state (paper 002, Figure 6). "
             "Larger C means longer exposure to GM below its critical level relative to the roll period; compare "
             "the tumblehome and flared topside variants of the same underwater hull.", ":::", "",
             "| ship | GM_cr [m] | " + " | ".join(states) + " |", "|---|---:|" + "---:|" * len(states)]
    for sh in ships:
        rr = [r for r in rec if r["ship"] == sh]
        lines.append(f"| {sh} | {_fmt(rr[0]['gm_cr'])} | " + " | ".join(_fmt(r["metric_c"]) for r in rr) + " |")
    lines.append("")
    return "\n".join(lines)


def _fig(results: Path, figdir: Path, rel: str, caption: str) -> list[str]:
    src = results / rel
    if not src.exists():
        return []
    name = rel.replace("/", "_")
    shutil.copy(src, figdir / name)
    return [f":::{{figure}} figures/{name}", "", caption, ":::", ""]


def _figs(results: Path, figdir: Path, pattern: str, items) -> list[str]:
    """Figure blocks for (name, caption) pairs, file ``pattern.format(name)``."""
    return [line for name, cap in items for line in _fig(results, figdir, pattern.format(name), cap)]


def rare_events_page(results: Path, config: dict, figdir: Path) -> str | None:
    """Irregular seas: ensemble statistics, extreme roll (GPD vs brute force), split-time capsize rate."""
    ens = [f"{c['ship']}_{c['name']}" for c in config.get("ensembles", [])]
    if not ens:
        return None
    L = ["# Irregular seas: ensembles, extreme roll and capsizing", "",
         "Each ensemble is many independent 30-minute records (record r from master seed and r), simulated with the "
         "volume-based FK + hydrostatic model on tabulated sectional properties; only statistics are kept.", "",
         "| condition | Hs [m] | Tp [s] | speed [kn] | heading [deg] | hours | roll σ [deg] | roll kurtosis | capsizes |",
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for k in ens:
        p = results / "ensemble" / k / "ensemble.nc"
        if not p.exists():
            continue
        e = _open(p)
        a = e.attrs
        L.append(f"| {k} | {a['hs']:g} | {a['tp']:g} | {a['speed_kn']:g} | {a['heading_deg']:g} | "
                 f"{float(e['exposure_hours']):.0f} | {float(e['roll_std']):.2f} | "
                 f"{float(e['kurtosis'].sel(dof='roll')):.2f} | {int(e['capsize_count'])} |")
    L.append("")
    for k in ens:
        L += [f"## {k}", ""]
        L += _figs(results, figdir, f"ensemble/{k}/{{}}.png", (
            ("roll_distribution", "Roll distribution normalised by σ against the normal distribution, both tails "
                                  "(seed 000 Figs 11-13)."),
            ("spectra", "Mean encounter spectra (Welch) of wave, heave, roll, pitch."),
            ("time_histories", "Sample records (seed 000 Fig. 10).")))
        px = results / "extremes" / f"{k}.nc"
        if px.exists():
            x = _open(px)
            L += ["### Extreme roll: GPD extrapolation against brute force", "",
                  f"Envelope: {x.attrs['envelope']}; declustering: {x.attrs['declustering']} "
                  f"({float(x['decorrelation_time']):.1f} s); fit: {x.attrs['fit']}; interval: {x.attrs['interval']}. "
                  f"Each sample is {float(x['sample_hours'][0]):.0f} h; brute force counts the rest of the "
                  f"{x.attrs['ensemble_hours']:.0f}-h ensemble.", "",
                  "| target [deg] | rate, first sample [1/h] | 95 % interval | brute force [1/h] | median ratio | coverage |",
                  "|---:|---:|---|---:|---:|---:|"]
            for tg in x["target"].values:
                d = x.sel(target=tg)
                L.append(f"| {tg:g} | {float(d['rate_estimate'][0]):.4g} | [{float(d['rate_lower'][0]):.3g}, "
                         f"{float(d['rate_upper'][0]):.3g}] | {float(d['rate_bruteforce'][0]):.4g} | "
                         f"{float(d['rate_ratio'].median()):.2f} | {float(d['coverage']):.0%} of {x.sizes['block']} |")
            L.append("")
            L += _figs(results, figdir, f"extremes/{k}_{{}}.png", (
                ("threshold", "Threshold selection: mean residual life and parameter stability (pyextremes)."),
                ("rate", "Exceedance rate from the first sample with its interval, and counted in the ensemble."),
                ("validation", "Every independent sample's estimate and interval against the brute-force rate.")))
        ps = results / "splittime" / f"{k}.nc"
        if ps.exists():
            st = _open(ps)
            L += ["### Split-time capsize rate against brute force", "",
                  f"Sample {float(st['sample_hours']):.0f} h; brute force {int(st['bruteforce_capsizes'])} capsizes in "
                  f"{float(st['bruteforce_hours']):.0f} h: {float(st['capsize_rate_bruteforce']):.3g} /h "
                  f"[{float(st['capsize_rate_bruteforce_lower']):.3g}, {float(st['capsize_rate_bruteforce_upper']):.3g}].", "",
                  "| threshold [deg] | crossings | clusters | P(capsize / cluster) | split-time rate [1/h] | 95 % interval | brute force inside |",
                  "|---:|---:|---:|---:|---:|---|---|"]
            for th in st["split_threshold"].values:
                d = st.sel(split_threshold=th)
                L.append(f"| {th:g} | {int(d['crossings'])} | {int(d['clusters'])} | {float(d['capsize_probability']):.3g} | "
                         f"{float(d['capsize_rate_splittime']):.3g} | [{float(d['capsize_rate_lower']):.3g}, "
                         f"{float(d['capsize_rate_upper']):.3g}] | {'yes' if int(d['inside']) else 'no'} |")
            L.append("")
            L += _figs(results, figdir, f"splittime/{k}_{{}}.png", (
                ("crossings", "Non-rare problem: threshold crossings on a sample record (paper 003 Fig. 3)."),
                ("perturbation", "Motion perturbation at one crossing (paper 003 Fig. 4)."),
                ("metric", "Metric tail and fitted GPD, extrapolated to y = 1."),
                ("rate", "Capsize rate against the intermediate threshold, with the brute-force interval.")))
    return "\n".join(L)


#: validation steps in report order: (step attribute, title, file suffix)
STEPS = [("statics", "Calm-water statics", "statics"), ("waves", "Stability in waves and metric C", "waves"),
         ("dynamics", "Time domain (3-DOF)", "dynamics"),
         ("ensemble", "Irregular seas: seaways, step size, extremes, split-time", "ensemble")]


def validation_rows(results: Path, expected: dict[str, list[tuple[str, str]]]) -> dict[str, list[dict]]:
    """Rows per step from ``results/validation/<key>_<step>.nc``. ``expected`` maps each step to the
    (key, ship) pairs that must have a file; a missing file is a FAIL row, never a silent gap."""
    out: dict[str, list[dict]] = {step: [] for step, _, _ in STEPS}
    for step, _, suffix in STEPS:
        for key, ship in expected.get(step, []):
            f = results / "validation" / f"{key}_{suffix}.nc"
            if not f.exists():
                out[step].append(dict(ship=key, check="(validation file)", value=np.nan, criterion="present", unit="",
                                      kind="independent", reference=str(f.relative_to(results.parent) if results.parent in f.parents else f),
                                      status="FAIL", reason="validation results missing: the step did not run"))
                continue
            ds = _open(f)
            for i in range(ds.sizes["check"]):
                out[step].append(dict(ship=key, check=str(ds["name"].values[i]), value=float(ds["value"][i]),
                                      criterion=str(ds["criterion"].values[i]), unit=str(ds["unit"].values[i]),
                                      kind=str(ds["kind"].values[i]), reference=str(ds["reference"].values[i]),
                                      status=str(ds["status"].values[i]), reason=str(ds["reason"].values[i])))
    return out


def step_summary(rows: list[dict]) -> str:
    """'independent 12 / 14 pass, consistency 5 / 5 pass, 2 skipped' for one step's rows."""
    parts = []
    for kind in ("independent", "consistency"):
        k = [r for r in rows if r["kind"] == kind and r["status"] != "SKIPPED"]
        if k:
            parts.append(f"{kind} {sum(r['status'] == 'PASS' for r in k)} / {len(k)} pass")
    skipped = sum(r["status"] == "SKIPPED" for r in rows)
    if skipped:
        parts.append(f"{skipped} skipped")
    return ", ".join(parts) or "no checks"


def _unit(unit: str) -> str:
    """' m' after a number, nothing for dimensionless values."""
    return "" if unit in ("", "-", "1") else f" {unit}"


def _cell(text: str) -> str:
    return str(text).replace("|", "/").replace("\n", " ")


def validation_page(results: Path, expected: dict) -> tuple[str, dict]:
    """MyST page: a summary line per step, every FAIL listed first, then one table per step.
    Returns (page, counts) with counts[step] = {PASS, FAIL, SKIPPED, summary}."""
    rows = validation_rows(results, expected)
    counts = {}
    page = ["# Validation", "",
            "Every row is read from `results/validation/*.nc`, written by the pipeline's validation rules. The "
            "measured value is a deviation from the reference (or a statistic such as a coverage) and the row "
            "passes when it meets the criterion. **Kind**: *independent* — exact or analytic, a peer library, "
            "published data or a different method; *consistency* — the same code path another way (a limit of the "
            "same equations, a second route through the same kernel, self-convergence). A check that could not "
            "run is a FAIL with the reason; a check that does not apply is SKIPPED with the reason.", ""]
    summary = ["| step | independent | consistency | skipped | FAIL |", "|---|---|---|---:|---:|"]
    fails = []
    for step, title, _ in STEPS:
        r = rows[step]
        c = {st: sum(x["status"] == st for x in r) for st in ("PASS", "FAIL", "SKIPPED")}
        c["summary"] = step_summary(r)
        counts[step] = c

        def frac(kind):
            k = [x for x in r if x["kind"] == kind and x["status"] != "SKIPPED"]
            return f"{sum(x['status'] == 'PASS' for x in k)} / {len(k)} pass" if k else "–"

        summary.append(f"| {{ref}}`{title} <val-{step}>` | {frac('independent')} | {frac('consistency')} | {c['SKIPPED']} | "
                       f"{c['FAIL']} |")
        fails += [(title, x) for x in r if x["status"] == "FAIL"]
    page += summary + [""]
    if fails:
        page += ["## Failing checks", "",
                 "These checks miss their reference; each is explained in the closing note of the session that "
                 "measured it and stays FAIL until the method is fixed.", ""]
        page += [f"- {x['ship']} ({t.lower()}): {_cell(x['check'])} — measured {_fmt(x['value'])}{_unit(x['unit'])}, "
                 f"criterion {_cell(x['criterion'])}{_unit(x['unit'])}{' — ' + _cell(x['reason']) if x['reason'] else ''}"
                 for t, x in fails]
        page.append("")
    for step, title, _ in STEPS:
        r = rows[step]
        page += [f"(val-{step})=", f"## {title}", "", f"{step_summary(r)}.", ""]
        if not r:
            page += ["No ship or condition of this run has this step.", ""]
            continue
        page += ["| ship / condition | check — *kind*, reference | measured | criterion | result |",
                 "|---|---|---:|---|---|"]
        for x in r:
            res = {"PASS": "PASS", "FAIL": "**FAIL**", "SKIPPED": "SKIPPED"}[x["status"]]
            if x["reason"]:
                res += f" ({_cell(x['reason'])})"
            unit = _unit(x["unit"])
            page.append(f"| {x['ship']} | {_cell(x['check'])} — *{x['kind']}*, {_cell(x['reference'])} | "
                        f"{_fmt(x['value'])}{unit} | {_cell(x['criterion'])}{unit} | {res} |")
        page.append("")
    return "\n".join(page), counts


def overview_page(results: Path, ships: list[str], config: dict, counts: dict) -> str:
    import numba
    import scipy

    versions = {"stabflow": __version__, "python": platform.python_version(), "numpy": np.__version__,
                "scipy": scipy.__version__, "numba": numba.__version__, "xarray": xr.__version__}
    lines = ["# stabflow validation report", "",
             "Ship stability from hull geometry to calm-water GZ, stability in waves (wave-pass GM/GZ and the "
             "early-stage metric C, paper 002) and 3-DOF time-domain response in regular waves, all computed "
             "with the sectional (Bonjean) machinery of the volume-based Froude-Krylov and hydrostatic method "
             "(paper 000).", "",
             "## Validation at a glance", "",
             f"**{sum(c['PASS'] for c in counts.values())} PASS, {sum(c['FAIL'] for c in counts.values())} FAIL, "
             f"{sum(c['SKIPPED'] for c in counts.values())} SKIPPED** — details and every failing check on the "
             "[validation page](validation.md).", ""]
    for step, title, _ in STEPS:
        c = counts[step]
        lines.append(f"- {title}: {c['summary']}" + (f" — **{c['FAIL']} FAIL**" if c["FAIL"] else "") + ".")
    lines += ["", "## What was run", "", f"Ships: {', '.join(ships)}.", "", "Pipeline configuration:", "", "```yaml",
              yaml.safe_dump(_plain(config), sort_keys=False, default_flow_style=None, width=110).rstrip()]
    lines += ["```", "", "## Software", "", "| package | version |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in versions.items()]
    bench = _benchmarks(results)
    if bench:
        lines += ["", "## Run time per job (Snakemake benchmark files)", "", "| job | wall time [s] |", "|---|---:|"]
        lines += [f"| {k} | {v:.2f} |" for k, v in bench]
    lines.append("")
    return "\n".join(lines)


def _plain(obj):
    """Config as plain Python containers (Snakemake's config holds its own mapping types)."""
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    return obj


def expected_validation(ships: list[str], config: dict) -> dict:
    """The validation files a run must have: statics, waves and dynamics per ship, ensemble per
    ensemble condition."""
    ens = [(f"{c['ship']}_{c['name']}", c["ship"]) for c in config.get("ensembles", [])]
    return {"statics": [(s, s) for s in ships], "waves": [(s, s) for s in ships], "dynamics": [(s, s) for s in ships],
            "ensemble": ens}


def build_report(results: str | Path, ships: list[str], config: dict, source: str | Path, out_html: str | Path) -> Path:
    """Generate the pages and build the HTML book; ``out_html`` is the final ``index.html`` path.

    The book is built in a temporary folder and moved into place, so a failed build leaves nothing.
    """
    results = Path(results)
    out_dir = Path(out_html).parent
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=out_dir.parent) as tmp:
        book = Path(tmp) / "book"
        shutil.copytree(source, book, ignore=shutil.ignore_patterns("_build"))
        figdir = book / "figures"
        figdir.mkdir(exist_ok=True)
        val, counts = validation_page(results, expected_validation(ships, config))
        (book / "validation.md").write_text(val)
        (book / "index.md").write_text(overview_page(results, ships, config, counts))
        for s in ships:
            (book / f"ship_{s}.md").write_text(ship_page(s, results, figdir))
        toc = ["format: jb-book", "root: index", "parts:", "  - caption: Results", "    chapters:"]
        toc += [f"      - file: ship_{s}" for s in ships]
        wp = waves_page(results, figdir)
        if wp:
            (book / "waves.md").write_text(wp)
            toc.append("      - file: waves")
        rp = rare_events_page(results, config, figdir)
        if rp:
            (book / "rare_events.md").write_text(rp)
            toc.append("      - file: rare_events")
        toc += ["  - caption: Validation and methods", "    chapters:", "      - file: validation", "      - file: methods"]
        (book / "_toc.yml").write_text("\n".join(toc) + "\n")
        env = dict(os.environ, PYTHONHASHSEED="0")
        r = subprocess.run([sys.executable, "-c", "from jupyter_book.cli.main import main; main()", "build", str(book), "--builder", "html"],
                           capture_output=True, text=True, env=env)
        if r.returncode != 0 or not (book / "_build" / "html" / "index.html").exists():
            raise RuntimeError(f"jupyter-book build failed:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
        (book / "_build" / "build.log").write_text(r.stdout + r.stderr)
        if out_dir.exists():
            shutil.rmtree(out_dir)
        shutil.move(str(book / "_build" / "html"), out_dir)
        shutil.move(str(book / "_build" / "build.log"), out_dir / "build.log")
    return Path(out_html)
