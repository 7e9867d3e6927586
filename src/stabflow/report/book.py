"""Build the validation report (Jupyter Book 1.x) from the NetCDF results.

The pages are MyST markdown rendered from the Jinja2 templates in ``templates/`` with the values read here
from ``results/``; the book only renders them (``execute_notebooks: off``), so building the report never
re-runs a simulation. The Python side collects plain values (numbers, strings, lists, dicts) and copies
the figures; the words of the pages and every number format (the ``num`` filter, ``_fmt``) are in the
templates, except the one-line step summaries of ``step_summary`` (counts, also shared with callers).
"""

from __future__ import annotations

import csv
import functools
import os
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import jinja2
import numpy as np
import xarray as xr
import yaml

from stabflow import __version__
from stabflow.constants import G

PARTICULARS = ["volume", "mass", "draft_mid", "trim_upright", "lcb", "lcg", "kb", "bm", "km", "kg", "gm",
               "waterplane_area", "gz_max", "heel_gz_max", "heel_vanishing"]


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _fmt(v, spec: str | None = None) -> str:
    """The report's number format (the templates' ``num`` filter): ``format(v, spec)`` for a format spec
    such as ``".2f"``, ``"g"`` or ``".0%"``; without one four significant digits (exponent from 1e5);
    "–" for a value that is not finite."""
    v = float(v)
    if not np.isfinite(v):
        return "–"
    if spec is not None:
        return format(v, spec)
    return f"{v:.4g}" if abs(v) < 1e5 else f"{v:.4e}"


def _rate(v, log10) -> str:
    """A rate as the report prints it: :func:`_fmt` of ``v``, or, where ``v`` underflowed to 0 as a
    double and its ``log10`` is finite, that order of magnitude ("3.2e-412", from log space)."""
    from stabflow.criteria.sea_states import rate_text

    return rate_text(v, log10) if float(v) == 0.0 else _fmt(v)


def _cell(text) -> str:
    """Text safe inside a Markdown table cell (the templates' ``cell`` filter)."""
    return str(text).replace("|", "/").replace("\n", " ")


@functools.cache
def _env() -> jinja2.Environment:
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(Path(__file__).parent / "templates"),
                             undefined=jinja2.StrictUndefined, keep_trailing_newline=True, trim_blocks=True,
                             lstrip_blocks=True)
    env.filters["num"] = _fmt
    env.filters["cell"] = _cell
    return env


def _render(template: str, **context) -> str:
    """Render one template. Every block of a page ends with a blank line; the page ends with a single
    newline instead (and is empty when the template wrote nothing)."""
    text = _env().get_template(template).render(**context)
    return text.rstrip("\n") + "\n" if text.strip() else ""


def _copy(src: Path, figdir: Path, name: str | None = None) -> str:
    """Copy a result figure into the book; returns its file name there."""
    name = name or src.name
    shutil.copy(src, figdir / name)
    return name


def _optional_figures(results: Path, figdir: Path, pattern: str, stems: tuple[str, ...]) -> dict[str, str | None]:
    """{stem: file name in the book, or None where ``results/pattern.format(stem)`` does not exist}; the
    copy is named after its results path with "/" → "_"."""
    out = {}
    for stem in stems:
        rel = pattern.format(stem)
        out[stem] = _copy(results / rel, figdir, rel.replace("/", "_")) if (results / rel).exists() else None
    return out


def _benchmarks(results: Path) -> list[tuple[str, float]]:
    rows = []
    for f in sorted((results / "benchmarks").rglob("*.tsv")):
        with open(f) as fh:
            rec = list(csv.DictReader(fh, delimiter="\t"))
        if rec and "s" in rec[0]:  # Snakemake's benchmark files (wall seconds in column s)
            rows.append((str(f.relative_to(results / "benchmarks").with_suffix("")), float(rec[0]["s"])))
    return rows


def ship_page(name: str, results: Path, figdir: Path) -> str:
    """MyST page for one ship: body plan, particulars, GZ, stability in waves, regular-wave response."""
    hull = _open(results / "hull" / f"{name}.nc")
    st = _open(results / "statics" / f"{name}.nc")
    figures = {"bodyplan": _copy(results / "hull" / f"{name}_bodyplan.png", figdir),
               "gz": _copy(results / "statics" / f"{name}_gz.png", figdir)}
    particulars = [{"label": st[k].attrs.get("long_name", k), "value": float(st[k]),
                    "unit": st[k].attrs.get("units", "")} for k in PARTICULARS]
    return _render("ship.md.j2", name=name, hull_source=hull.attrs.get("hull_source", ""),
                   stations=hull.sizes["station"], hull_volume=float(hull.hull_volume), figures=figures,
                   particulars=particulars, waves=_waves_data(name, results, figdir),
                   raos=_rao_data(name, results, figdir), decay=_decay_data(name, results, figdir))


def _decay_data(name: str, results: Path, figdir: Path) -> dict | None:
    """The roll-decay figure (copied) and its numbers; None if the step did not run."""
    nc = results / "roll_decay" / f"{name}.nc"
    if not nc.exists():
        return None
    ds = _open(nc)
    a = ds.attrs
    return {"figure": _copy(nc.with_suffix(".png"), figdir), "heel": float(a["decay_heel_deg"]),
            "source": a["roll_damping"], "b44": float(a["b44"]), "b44q": float(a["b44q"]),
            "period": float(a["roll_period"]), "peaks": [float(v) for v in ds["peak_roll"].values[:6]],
            "ikeda": "amp_total" in ds}


def _rao_data(name: str, results: Path, figdir: Path) -> list[dict]:
    """One entry per regular-wave condition of ``name`` (figure copied)."""
    raos = []
    for nc in sorted((results / "rao").glob(f"{name}_*.nc")):
        ds = _open(nc)
        a = ds.attrs
        if a.get("ship") != name:
            continue
        raos.append({"condition": a["condition"], "figure": _copy(nc.with_suffix(".png"), figdir),
                     "capytaine": a.get("hydro") == "capytaine",
                     **{k: float(a[k]) for k in ("heading_deg", "speed", "steepness", "heave_period", "roll_period",
                                                  "pitch_period")}})
    return raos


def rao_section(name: str, results: Path, figdir: Path) -> list[str]:
    """Regular-wave response amplitudes of the time-domain model, one figure per condition (page lines)."""
    text = _render("ship_rao.md.j2", name=name, raos=_rao_data(name, results, figdir))
    return text.split("\n") if text else []


def _waves_data(name: str, results: Path, figdir: Path) -> dict | None:
    """Wave-pass figures (copied) and the early-stage metric of one ship; None if not computed."""
    wnc, mnc = results / "waves" / f"{name}.nc", results / "waves" / f"{name}_metric.nc"
    if not (wnc.exists() and mnc.exists()):
        return None
    figures = {"gm": _copy(results / "waves" / f"{name}_gm.png", figdir),
               "gz_waves": _copy(results / "waves" / f"{name}_gz_waves.png", figdir)}
    w = _open(wnc)
    m = _open(mnc)
    columns = ("hs", "tm", "sigma_zeta", "k1", "k2", "weight_sum", "mean_tbc", "metric_c")
    return {"figures": figures, "steepness_max": float(w.steepness.max()),
            "crest_trough_steepness": float(w.attrs["crest_trough_steepness"]),
            "gm_cr": float(m.gm_cr), "kg_cr": float(m.kg_cr), "roll_period": float(m.roll_period),
            "critical_angle_deg": float(m.attrs["critical_angle_deg"]), "speed_kn": float(m.attrs["speed_kn"]),
            "spectrum": m.attrs["spectrum"], "loading_kg": m.attrs["loading_kg"],
            "sea_states": [{"sea_state": str(ss), **{c: float(m[c][i]) for c in columns}}
                           for i, ss in enumerate(m.sea_state.values)]}


def waves_section(name: str, results: Path, figdir: Path) -> list[str]:
    """Wave-pass figures and the early-stage metric table for one ship (if computed), as page lines."""
    text = _render("ship_waves.md.j2", name=name, waves=_waves_data(name, results, figdir))
    return text.split("\n") if text else []


def waves_page(results: Path, figdir: Path) -> str | None:
    """Cross-ship page: table and bar chart of C (paper 002 Table 1 / Figure 6)."""
    csv_path = results / "waves" / "early_stage_C.csv"
    if not csv_path.exists():
        return None
    figure = _copy(results / "waves" / "early_stage_C.png", figdir)
    with open(csv_path) as fh:
        rec = list(csv.DictReader(fh))
    states = list(dict.fromkeys(r["sea_state"] for r in rec))
    ships = []
    for sh in dict.fromkeys(r["ship"] for r in rec):
        rr = [r for r in rec if r["ship"] == sh]
        ships.append({"ship": sh, "gm_cr": rr[0]["gm_cr"], "metric_c": [r["metric_c"] for r in rr]})
    return _render("waves.md.j2", figure=figure, sea_states=states, ships=ships)


def _extremes_data(results: Path, k: str, figdir: Path) -> dict | None:
    """GPD extrapolation against brute force for condition ``k``; None if not computed."""
    p = results / "extremes" / f"{k}.nc"
    if not p.exists():
        return None
    x = _open(p)
    first = x.isel(block=0)  # the "first sample" of the page; the others only count in ratio and coverage
    targets = []
    for tg in x.target.values:
        d, d0 = x.sel(target=tg), first.sel(target=tg)
        targets.append({"target": float(tg), "rate": float(d0.rate_estimate), "lower": float(d0.rate_lower),
                        "upper": float(d0.rate_upper), "bruteforce": float(d0.rate_bruteforce),
                        "median_ratio": float(d.rate_ratio.median()), "coverage": float(d.coverage),
                        "consistency": float(d.threshold_consistency) if "threshold_consistency" in d else np.nan,
                        "share": float(np.nanmedian(d.extrapolation_share.values))
                        if "extrapolation_share" in d and np.isfinite(d.extrapolation_share.values).any() else np.nan})
    return {**{a: x.attrs[a] for a in ("peaks", "declustering", "fit", "interval")},
            "decorrelation_time": float(x.decorrelation_time), "sample_hours": float(first.sample_hours),
            "ensemble_hours": float(x.attrs["ensemble_hours"]), "blocks": x.sizes["block"], "targets": targets,
            "figures": _optional_figures(results, figdir, f"extremes/{k}_{{}}.png",
                                         ("threshold", "rate", "validation"))}


def _splittime_data(results: Path, k: str, figdir: Path) -> dict | None:
    """Split-time capsize rate against brute force for condition ``k``; None if not computed."""
    p = results / "splittime" / f"{k}.nc"
    if not p.exists():
        return None
    st = _open(p)
    rows = []
    for th in st.split_threshold.values:
        d = st.sel(split_threshold=th)
        rows.append({"threshold": float(th), "crossings": int(d.crossings), "clusters": int(d.clusters),
                     "probability": float(d.capsize_probability), "rate": float(d.capsize_rate_splittime),
                     "lower": float(d.capsize_rate_lower), "upper": float(d.capsize_rate_upper),
                     "inside": bool(int(d.inside)), "reported": bool(int(d.reported)) if "reported" in d else False,
                     "share": float(d.extrapolation_share) if "extrapolation_share" in d else np.nan,
                     "undecided": int(d.undecided_runs) if "undecided_runs" in d else 0})
    return {"sample_hours": float(st.sample_hours), "bruteforce_capsizes": int(st.bruteforce_capsizes),
            "bruteforce_hours": float(st.bruteforce_hours), "bruteforce_rate": float(st.capsize_rate_bruteforce),
            "bruteforce_lower": float(st.capsize_rate_bruteforce_lower),
            "bruteforce_upper": float(st.capsize_rate_bruteforce_upper), "thresholds": rows,
            "figures": _optional_figures(results, figdir, f"splittime/{k}_{{}}.png",
                                         ("crossings", "perturbation", "metric", "rate"))}


def _capsize_1dof_data(results: Path, figdir: Path) -> dict | None:
    """The 1-DOF capsize case (brute force, coverage and median ratios per method); None if not run."""
    p = results / "capsize_1dof" / "box1dof.nc"
    if not p.exists():
        return None
    d = _open(p)
    rows = []
    for case in d.case.values:
        c = d.sel(case=case)
        rows.append({"case": str(case), "sigma": float(c.excitation_std), "roll_std": float(c.roll_std),
                     "bf": float(c.capsize_rate_bruteforce), "bf_lower": float(c.capsize_rate_bruteforce_lower),
                     "bf_upper": float(c.capsize_rate_bruteforce_upper), "bf_k": int(c.bruteforce_capsizes),
                     "bf_hours": float(c.bruteforce_hours),
                     "sample_capsizes": float(c.sample_capsizes.mean()),
                     **{f"{m}_{q}": float(c[f"{m}_{q}"]) for m in ("splittime", "extremes")
                        for q in ("coverage", "median_ratio", "threshold_consistency")},
                     **{f"{m}_share": float(np.nanmedian(c[f"{m}_extrapolation_share"].values))
                        if np.isfinite(c[f"{m}_extrapolation_share"].values).any() else np.nan
                        for m in ("splittime", "extremes")}})
    return {"rows": rows, "attrs": dict(d.attrs), "avs": float(d.vanishing_angle), "period": float(d.roll_period),
            "samples": int(d.sizes["sample"]),
            "figure": _optional_figures(results, figdir, "capsize_1dof/{}.png", ("box1dof",))["box1dof"]}


def rare_events_page(results: Path, config: dict, figdir: Path) -> str | None:
    """Irregular seas: ensemble statistics, extreme roll (GPD vs brute force), split-time capsize rate."""
    conditions = []
    for c in config.get("ensembles", []):
        k = f"{c['ship']}_{c['name']}"
        p = results / "ensemble" / k / "ensemble.nc"
        stats = None
        if p.exists():
            e = _open(p)
            stats = {**{a: float(e.attrs[a]) for a in ("hs", "tp", "speed_kn", "heading_deg")},
                     "hours": float(e.exposure_hours), "roll_std": float(e.roll_std),
                     "roll_kurtosis": float(e.kurtosis.sel(dof="roll")), "capsizes": int(e.capsize_count),
                     "dof": int(e.attrs.get("dof", 3)), "model": str(e.attrs.get("model", "volume")),
                     "broaches": f"{int(e.broach_count)} of {e.sizes['record']}" if "broach_count" in e else "—"}
        conditions.append({"key": k, "stats": stats, "extremes": _extremes_data(results, k, figdir),
                           "splittime": _splittime_data(results, k, figdir),
                           "figures": _optional_figures(results, figdir, f"ensemble/{k}/{{}}.png",
                                                        ("roll_distribution", "spectra", "time_histories"))})
    one_dof = _capsize_1dof_data(results, figdir)
    if not conditions and one_dof is None:
        return None
    return _render("rare_events.md.j2", conditions=conditions, one_dof=one_dof)


def criteria_page(name: str, results: Path, figdir: Path) -> str | None:
    """Criteria chapter of one ship (None when the criteria step has not written its file)."""
    p = results / "criteria" / f"{name}.nc"
    if not p.exists():
        return None
    d = _open(p)
    rows = [{"name": str(d.criterion_name[i].values), "level": str(d.criterion_level[i].values),
             "value": float(d.criterion_value[i]), "unit": str(d.criterion_unit[i].values),
             "limit": None if not np.isfinite(d.criterion_limit[i]) else float(d.criterion_limit[i]),
             "sense": str(d.criterion_sense[i].values), "verdict": str(d.verdict[i].values),
             "reason": str(d.verdict_reason[i].values), "source": str(d.criterion_source[i].values),
             # a draft's limit where the adopted one is missing (files before 2026-12-07 have none)
             "draft_limit": (float(d.criterion_draft_limit[i]) if "criterion_draft_limit" in d
                             and np.isfinite(d.criterion_draft_limit[i]) else None),
             "draft_source": str(d.criterion_draft_source[i].values) if "criterion_draft_source" in d else "",
             "draft_verdict": str(d.verdict_draft[i].values) if "verdict_draft" in d else ""}
            for i in range(d.sizes["criterion"])]
    dsa = _dsa_data(name, results, figdir)
    if dsa is not None:
        rows.append({"draft_limit": None, "draft_source": "", "draft_verdict": "", **dsa.pop("row")})
    counts = {v: sum(r["verdict"] == v for r in rows) for v in ("PASS", "FAIL", "NOT EVALUATED")}
    wc = {k[3:]: float(d[k]) for k in d.data_vars if k.startswith("wc_")}

    def route(name, a, b):
        return {"name": name, "a": a, "b": b, "ratio": a / b if b else float("nan")}
    routes, l1 = [], {"cm": float(d.midship_coefficient), "rpr": float(d.rpr)}
    if "l1_pure_loss_gm_min" in d:
        # the steepnesses the criteria step used (overrides included)
        s_pl, s_pr = float(d.attrs["sw_pure_loss"]), float(d.attrs["sw_parametric"])
        routes = [route("GMmin (pure loss)", float(d.l1_pure_loss_gm_min), float(d.gm_wave_min.interp(steepness=s_pl))),
                  route("δGM (parametric rolling)", float(d.l1_parametric_delta_gm1),
                        float(d.delta_gm_wave.interp(steepness=s_pr)))]
        l1.update(pl_dl=float(d.l1_pure_loss_d_L), pr_dh=float(d.l1_parametric_d_H), pr_dl=float(d.l1_parametric_d_L),
                  sw_pl=s_pl, sw_pr=s_pr)
    flooding = float(d.flooding_angle)
    wf = "sr_froude_critical_wave_force" in d
    sr = [{"ratio": float(r), **{f"s{j}": float(d.sr_froude_critical.sel(sr_wavelength_ratio=r).values[j])
                                 for j in range(d.sizes["sr_steepness"])},
           **{f"w{j}": (float(d.sr_froude_critical_wave_force.sel(sr_wavelength_ratio=r).values[j]) if wf else None)
              for j in range(d.sizes["sr_steepness"])}}
          for r in d.sr_wavelength_ratio.values] if "sr_froude_critical" in d else []
    sr_wf = {"on": wf, "why": d.attrs.get("sr_wave_force_not_computed", ""),
             "resistance": d.attrs.get("sr_resistance", ""),
             "beyond": int(d.attrs.get("sr_wave_force_exceeds_resistance", 0))}
    sr_steep = [float(x) for x in d.sr_steepness.values] if "sr_froude_critical" in d else []
    pr = [{"heading": float(h), "fn": float(f), "s": float(x), "ratio": float(d.pr_encounter_ratio.sel(pr_heading=h, pr_froude=f, pr_steepness=x)),
           "one": float(d.pr_roll_1dof.sel(pr_heading=h, pr_froude=f, pr_steepness=x)),
           "three": float(d.pr_roll_3dof.sel(pr_heading=h, pr_froude=f, pr_steepness=x))}
          for h in d.pr_heading.values for f in d.pr_froude.values for x in d.pr_steepness.values] if "pr_roll_1dof" in d else []
    c1 = None
    if "c1_fails" in d:
        c1 = {"value": float(d.c1), "speed": str(d.attrs.get("c1_speed_requirement", "")),
              "tphi": float(d.attrs.get("c1_roll_period", np.nan)), "rpr": float(d.attrs.get("c1_r_pr", np.nan)),
              "vd": float(d.attrs.get("c1_service_speed", np.nan)), "crests": int(d.attrs.get("c1_crest_positions", 0)),
              "rows": [{"i": int(i), "w": float(d.c1_weight.sel(c1_case=i)), "lam": float(d.c1_wave_length.sel(c1_case=i)),
                        "h": float(d.c1_wave_height.sel(c1_case=i)), "gm": float(d.c1_gm_wave.sel(c1_case=i)),
                        "ratio": float(d.c1_gm_ratio.sel(c1_case=i)), "vpr": float(d.c1_speed_resonance.sel(c1_case=i)),
                        "fails": float(d.c1_fails.sel(c1_case=i))} for i in d.c1_case.values]}
    c2 = None
    if "c2_by_speed" in d:
        c2 = {"value": float(d.c2), "threshold": float(d.attrs.get("c2_threshold_deg", np.nan)),
              "left_out": float(d.attrs.get("c2_probability_left_out", np.nan)),
              "missing": str(d.attrs.get("c2_missing_speeds", "none")),
              "headings": str(d.attrs.get("c2_missing_headings", "none")),
              "breaking": float(d.attrs.get("c2_probability_breaking", np.nan)),
              "service": float(d.attrs.get("c2_service_froude", np.nan)),
              "rows": [{"heading": float(h), "fn": float(f), "c2": float(d.c2_by_speed.sel(c2_heading=h, c2_froude=f))}
                       for h in d.c2_heading.values for f in d.c2_froude.values]}
    seas = None
    if "ew_effective_height" in d:
        occ = d.sea_probability.values > 0
        seas = {"n": int(occ.sum()), "lam": float(d.attrs.get("ew_wave_length", np.nan)),
                "crests": int(d.attrs.get("ew_crest_positions", 0)), "phi_w": float(d.ds_heel_wind),
                "wind": str(d.attrs.get("ds_wind", "")), "phi_f": float(d.ds_failure_angle),
                "governs": str(d.attrs.get("ds_failure_angle_governed_by", "")), "crew": str(d.attrs.get("ea_crew", "")),
                "h": float(d.ea_height_above_g), "heff": float(d.ew_effective_height.max()),
                "gm_min": float(d.ew_gm_min.min()), "p_gm": float(d.ew_probability_gm_negative),
                "dgm": float(d.ew_delta_gm_ratio.max()), "p_pr": float(d.ew_probability_delta_gm_above_rpr),
                "vanish": float(d.ew_heel_vanishing.min()), "gzmax": float(d.ew_gz_max.min()),
                "roll": float(d.ds_roll_std.max()), "roll1": float(d.ew_roll_1dof.max()),
                "p_break": float(d.ew_probability_breaking), "rate": _rate(d.ds_long_term_rate, d.ds_long_term_log10_rate), "tr": float(d.ea_roll_period),
                "kacc": float(d.ea_acceleration_per_roll),
                "acc": [(float(a), _rate(r, lr)) for a, r, lr in zip(d.ea_level.values, d.ea_long_term_rate.values,
                                                                      d.ea_long_term_log10_rate.values)],
                "figure": _copy(results / "criteria" / f"{name}_sea_states.png", figdir)}
    return _render("criteria.md.j2", name=name, rows=rows, counts=counts, overrides=d.attrs.get("standards_overridden", "none"),
                   seas=seas,
                   figure=_copy(results / "criteria" / f"{name}_criteria.png", figdir), wc=wc,
                   block=float(d.block_coefficient), deck_edge=float(d.deck_edge_immersion),
                   flooding=None if not np.isfinite(flooding) else flooding, routes=routes, l1=l1, dsa=dsa,
                   sr=sr, sr_steep=sr_steep, sr_wf=sr_wf, fn_service=float(d.froude_service),
                   pr=pr, pr_phi0=float(d.attrs.get("pr_phi0_deg", np.nan)), pr_duration=float(d.attrs.get("pr_duration", np.nan)),
                   c1=c1, c2=c2)


def _dsa_data(name: str, results: Path, figdir: Path) -> dict | None:
    """The direct stability assessment of one ship for its criteria chapter (None if not run)."""
    p = results / "criteria" / f"{name}_dsa.nc"
    if not p.exists():
        return None
    d = _open(p)
    a = d.attrs
    method = d.method.values.astype(str)
    parts = [{"part": str(k), "cells": int((method == k).sum()), "rate": float(d.part_rate[i]),
              "lo": float(d.part_rate_lo[i]), "hi": float(d.part_rate_hi[i]), "share": float(d.part_share[i])}
             for i, k in enumerate(d.part.values)]
    top = np.argsort(-np.nan_to_num(d.contribution.values))[:8]
    cells = [{"hs": float(d.hs[i]), "tz": float(d.tz[i]), "heading": float(d.heading[i]), "speed": float(d.speed_kn[i]),
              "method": str(method[i]), "failures": int(d.failures[i]), "hours": float(d.exposure[i]) / 3600.0,
              "rate": float(d.cell_rate[i]) * 3600.0, "lo": float(d.cell_rate_lo[i]) * 3600.0,
              "hi": float(d.cell_rate_hi[i]) * 3600.0, "share": float(d.share[i]), "sigma": float(d.roll_sigma[i])}
             for i in top]
    limit = float(a["row_limit"])
    row = {"name": a["row_criterion"], "level": "SGISC direct stability assessment", "value": float(a["row_value"]),
           "unit": "1/year", "limit": limit if np.isfinite(limit) else None, "sense": "<=", "verdict": a["row_verdict"],
           "reason": a["row_reason"], "source": a["row_source"]}
    return {"row": row, "rate": float(d.rate), "lo": float(d.rate_lo), "hi": float(d.rate_hi), "parts": parts,
            "cells": cells, "n": int(d.sizes["cell"]), "phi_f": float(d.failure_angle),
            "governs": a["failure_angle_governed_by"], "fsource": a["failure_angle_source"],
            "bound": float(d.screen_bound), "width": float(d.interval_width),
            "ok": bool(a["screening_changes_less_than_interval"]), "covered": float(a["scatter_covered_fraction"]),
            "recheck": ({"verdict": a["screen_recheck_verdict"], "reason": a["screen_recheck_reason"]}
                        if a.get("screen_recheck_verdict", "SKIPPED") != "SKIPPED" else None),
            "recheck_skipped": a.get("screen_recheck_reason", "the results predate the recheck")
            if a.get("screen_recheck_verdict", "SKIPPED") == "SKIPPED" else None,
            "used": float(a["probability_used"]), "alpha": float(a["alpha"]), "screening": a["screening"],
            "parametric_cells": a.get("parametric_cells", "no"),
            "dphi_dzdt": bool(a.get("dphi_dzdt", 0)),
            "disp": float(a["count_dispersion_estimate"]), "disp_dof": int(a["count_dispersion_dof"]),
            "disp_used": float(a["count_dispersion_used"]),
            "acc_limit": float(a.get("lateral_acceleration_limit", np.nan)),
            "crew_h": float(a.get("crew_height_above_g", np.nan)),
            "acc_source": str(a.get("lateral_acceleration_source", "")),
            "seconds": _benchmark_seconds(results, f"dsa/{name}.tsv"),
            "headings": sorted(set(float(x) for x in d.heading.values)),
            "heading_span": str(a.get("heading_span", "0-180 deg")),
            "warmup": str(a.get("warmup", "none: the records were counted from rest (results before 2026-12-07)")),
            "speeds": sorted(set(float(x) for x in d.speed_kn.values)),
            "map": _copy(results / "criteria" / f"{name}_dsa_map.png", figdir),
            "polar": _copy(results / "criteria" / f"{name}_dsa_polar.png", figdir)}


def _step_result(results: Path, config: dict, step: str):
    """(ship, dataset of results/<step>/<ship>.nc) of a one-ship step section, dataset None when the
    config has no such section or the step has not written its file."""
    if step not in config:
        return None, None
    ship = config[step]["ship"]
    p = results / step / f"{ship}.nc"
    return ship, (_open(p) if p.exists() else None)


#: Paper 004's outcomes for *Italian Gold* in its loading (G 0.08 m above the waterline), 10 kn, waves
#: 45 degree off the stern (its section 4): the text after Fig. 7, "when the wavelength is about 1 to 2
#: ship lengths, the ship will capsize even though the wave height is only 6 ft (1.8 m)" and R-4 "is
#: just riding on the wave and does not capsize", Fig. 7's R-2 broaching and capsizing; after Table
#: 4, "the ship can survive in 10 ft (3.1 m) random sea" and "capsized while the significant wave height
#: reached 13 ft (4.0 m)"; IR-3's (4.6 m) is not stated in the text. Keyed by the wave as the broaching
#: step writes it: (wavelength [m], H [m]) of a regular wave (Table 3), (None, Hs [m]) of a
#: Pierson-Moskowitz sea (Table 4); value (text, capsized: True / False / None).
PAPER_004_OUTCOMES = {(21.3, 1.8): ("capsize (λ/L ≈ 1-2)", True),
                      (30.5, 1.8): ("broach and capsize (Fig. 7)", True),
                      (42.7, 1.8): ("capsize (λ/L ≈ 1-2)", True),
                      (85.3, 1.8): ("rides the wave, no capsize", False),
                      (None, 3.1): ("survives", False),
                      (None, 4.0): ("capsize", True),
                      (None, 4.6): ("not stated (Fig. 14)", None)}


def paper_004_comparison(d: xr.Dataset, loading: str = "heavy") -> tuple[dict, dict]:
    """Paper 004's outcome beside each case of the broaching step's ``loading`` (the paper's: G 0.08 m
    above the waterline): ({case: paper's text}, summary with the cases compared, those agreeing on
    capsize or not, and those that do not). Cases whose wave the paper did not run, or whose outcome it
    does not state, are not compared."""
    texts, agree, differ = {}, [], []
    if loading not in d.loading.values:
        return texts, {"compared": 0, "agree": agree, "differ": differ}
    for c in d.case.values:
        r = d.sel(loading=loading, case=c)
        lam = float(r.wavelength)
        key = (round(lam, 1) if np.isfinite(lam) else None, round(float(r.wave_height), 1))
        if key not in PAPER_004_OUTCOMES:
            continue
        text, capsized = PAPER_004_OUTCOMES[key]
        texts[str(c)] = text
        if capsized is not None:
            (agree if bool(int(r.capsized)) == capsized else differ).append(str(c))
    return texts, {"compared": len(agree) + len(differ), "agree": agree, "differ": differ}


def broaching_page(results: Path, config: dict, figdir: Path) -> str | None:
    """Paper 004's scenario, the calm-water manoeuvres and the surf-riding thresholds; None if not run."""
    ship, d = _step_result(results, config, "broaching")
    if d is None:
        return None

    def when(flag, t):
        return f"{float(t):.1f}" if int(flag) else "no"

    paper, versus = paper_004_comparison(d)
    rows = []
    for lo in d.loading.values:
        for c in d.case.values:
            r = d.sel(loading=lo, case=c)
            wave = (f"regular λ {float(r.wavelength):g} m, H {float(r.wave_height):g} m" if np.isfinite(float(r.wavelength))
                    else f"PM Hs {float(r.wave_height):g} m")
            rows.append({"loading": str(lo), "kg": float(r.kg), "case": str(c), "wave": wave,
                         "paper": paper.get(str(c), "—") if str(lo) == "heavy" else "—",
                         "capsize": when(r.capsized, r.capsize_time), "broach": when(r.broach, r.broach_time),
                         "surf": when(r.surf_riding, r.surf_riding_longest),
                         "roll": float(np.nanmax(np.abs(r["roll"]))), "yaw": float(np.nanmax(np.abs(r["yaw"])))})

    def val(k, fmt=".1f", unit=""):
        v = float(d[k]) if k in d else np.nan
        return f"{v:{fmt}}{unit}" if np.isfinite(v) else "not completed"

    L = float(d.attrs.get("manoeuvre_length", np.nan))
    man_rows = []
    for helm in (35, 20):
        for k, title in (("advance", "advance"), ("transfer", "transfer"), ("tactical_diameter", "tactical diameter"),
                         ("steady_diameter", "steady turning diameter")):
            v = float(d[f"turning_{helm}_{k}"])
            man_rows.append((f"turning, rudder {helm}°: {title}", f"{v:.1f} m ({v / L:.2f} L)" if np.isfinite(v)
                             else "not completed"))
        man_rows.append((f"turning, rudder {helm}°: speed loss", val(f"turning_{helm}_speed_loss", ".0%")))
    for z in (10, 20):
        man_rows.append((f"zig-zag {z}°/{z}°: first overshoot", val(f"zigzag_{z}_first_overshoot", ".1f", "°")))
        man_rows.append((f"zig-zag {z}°/{z}°: second overshoot", val(f"zigzag_{z}_second_overshoot", ".1f", "°")))
    man_rows.append(("autopilot, 10° course change: overshoot", val("autopilot_step_overshoot", ".3f", "°")))
    surf = [{"lam": float(d.surf_riding_wavelength[i]), "melnikov": float(d.surf_riding_melnikov[i]),
             "surge": float(d.surf_riding_surge_only[i]), "six": float(d.surf_riding_six_dof[i]),
             "wave": float(d.surf_riding_melnikov_wave_force[i])}
            for i in range(d.sizes.get("surf_case", 0))]
    from stabflow.steps import broaching_figure_names

    figs = _optional_figures(results, figdir, f"broaching/{ship}_{{}}.png",
                             tuple(dict.fromkeys(broaching_figure_names(config) + ["map"])))
    figures = {"motions": [{"loading": str(lo), "file": figs.get(f"motions_{lo}")} for lo in d.loading.values],
               "strip": figs["strip"], "manoeuvres": figs["manoeuvres"], "map": figs["map"],
               "resistance": figs["resistance"]}
    pmap = None
    res = _resistance_summary(d)
    ens6 = _scenario_ensembles(results, config, ship, d)
    if "map_heading" in d.dims:
        mrows = [{"heading": float(h), "speed": float(v),
                  **{f"{t}{x}": (int if t == "k" else float)(d[f"map_{name}_{q}"].sel(map_heading=h, map_speed=v))
                     for name, x in (("capsize", "c"), ("broach", "b"))
                     for t, q in (("k", "count"), ("p", "probability"), ("l", "lower"), ("u", "upper"))}}
                 for h in d.map_heading.values for v in d.map_speed.values]
        pmap = {"rows": mrows, "loading": d.attrs["map_loading"], "kg": float(d.attrs["map_kg"]),
                "sea": d.attrs["map_sea"], "records": int(d.attrs["map_records"]),
                "duration": float(d.attrs["map_duration"]), "interval": d.attrs["map_interval"],
                "level": 100 * (1 - float(d.attrs["map_alpha"]))}
    from stabflow.config import load_ship
    from stabflow.dynamics.manoeuvring import HULL_DERIVATIVES, LINEAR_DERIVATIVES

    sh = load_ship(Path(config.get("ships_dir", "config/ships")) / f"{ship}.yaml")
    mcfg = sh.data.get("manoeuvring", {})
    foils = [{**f, "name": f.get("name", "foil"), "source": f.get("source", "source not given")} for f in mcfg.get("foils", [])]
    given = {k: v for k, v in mcfg.get("derivatives", {}).items() if k != "source"}
    hull_src = {"clarke": "Clarke, Gedling & Hine (1983), a regression of model tests on L, B, T and C_B",
                "slender_body": "slender-body theory on this hull's own lateral profile (its deadwood, keel rake "
                                "and trim; the flow leaves at the deepest aft station)"}
    hull_der = d.attrs["hull_derivatives"]
    derivatives = (f"given {', '.join(sorted(given))} ({mcfg['derivatives'].get('source', 'source not given')}), the rest "
                   if given else "") + hull_src[hull_der]
    der_rows = [[{"clarke": "Clarke et al. (1983)", "slender_body": "slender body, hull profile"}[k]
                 + (" (used)" if k == hull_der and not given else "")]
                + [f"{float(d[f'{k}_{c}']):.4f}" for c in LINEAR_DERIVATIVES]
                + [f"{float(d[f'sway_yaw_eigenvalue_{k}']):+.3f}"]
                for k in HULL_DERIVATIVES if f"{k}_yv" in d]
    der_rows += [[f"{k.replace('_', ' ')}: not available ({d.attrs[f'{k}_unavailable']})", "", "", "", "", ""]
                 for k in HULL_DERIVATIVES if f"{k}_unavailable" in d.attrs]
    if given and "derivative_yv" in d:
        der_rows.append(["used (with the given values)"] + [f"{float(d[f'derivative_{c}']):.4f}"
                                                            for c in LINEAR_DERIVATIVES]
                        + [f"{float(d['sway_yaw_eigenvalue']):+.3f}"])
    return _render("broaching.md.j2", ship=ship, a=config["broaching"], decay=bool(int(d.attrs.get("dphi_dzdt", 0))),
                   rows=rows, versus=versus, foils=foils, derivatives=derivatives,
                   der_rows=der_rows,
                   man={"rows": man_rows, "length": L, "b_l": float(d.attrs.get("manoeuvre_breadth", np.nan)) / L,
                        "form_factor": float(mcfg.get("form_factor", 0.0)), "ap": mcfg.get("autopilot", {}),
                        "eig": float(d["sway_yaw_eigenvalue"]) if "sway_yaw_eigenvalue" in d else np.nan,
                        "added_mass": {"capytaine": "Capytaine's zero-frequency limit of the hull mesh",
                                       "clarke": "Clarke et al. (1983)"}.get(str(mcfg.get("added_mass", "capytaine")),
                                                                             "given in the ship file")},
                   surf=surf, figures=figures, pmap=pmap, res=res, ens6=ens6, strip_case=d.attrs.get("strip_case", ""),
                   strip_loading=d.attrs.get("strip_loading", ""), radiation=_radiation_summary(results, figdir, ship, d))


def _scenario_ensembles(results: Path, config: dict, ship: str, d: xr.Dataset) -> list[dict]:
    """The config's 6-DOF ensembles of the broaching ship, each
    with its capsize count, exposure and rate (Garwood 95 % interval), and the paper 004 case it
    repeats as a statistic (the same loading's KG and the irregular case's Hs), if any."""
    from stabflow.statistics.splittime import poisson_interval

    b = config["broaching"]
    out = []
    for c in config.get("ensembles", []):
        if c.get("ship") != ship or int(c.get("dof", 3)) != 6:
            continue
        f = results / "ensemble" / f"{ship}_{c['name']}" / "ensemble.nc"
        if not f.exists():
            continue
        with xr.open_dataset(f) as e:
            k, hours = int(e["capsize_count"]), float(e["exposure_hours"])
            n = int(e.attrs["n_records"])
            lost = int(e["warmup_lost_count"]) if "warmup_lost_count" in e else 0
            broach = int(e["broach_count"]) if "broach_count" in e else None
        rate, lo, hi = poisson_interval(k, hours)
        case = None
        if (c.get("kg") is not None and float(c["heading_deg"]) == float(b["heading_deg"])
                and float(c["speed_kn"]) == float(b["speed_kn"])):
            for lname in d.loading.values:
                for cname in d.case.values:
                    r = d.sel(loading=lname, case=cname)
                    if (not np.isfinite(float(r.wavelength)) and abs(float(r.kg) - float(c["kg"])) < 1e-3
                            and float(r.wave_height) == float(c["sea"]["hs"])):
                        case = f"{cname}, {lname} loading"
        out.append({"name": c["name"], "hs": float(c["sea"]["hs"]), "spectrum": c["sea"]["spectrum"],
                    "heading": float(c["heading_deg"]), "speed": float(c["speed_kn"]), "kg": c.get("kg"),
                    "records": n, "lost": lost, "duration": float(c["duration"]), "warmup": float(c.get("warmup_s", 0.0)),
                    "k": k, "hours": hours, "rate": rate, "lo": lo, "hi": hi, "broach": broach, "case": case})
    return out


def _resistance_summary(d: xr.Dataset) -> dict | None:
    """The broaching chapter's account of the calm-water resistance (``broaching.resistance_curve``):
    the method and its particulars, R and the friction line alone at the commanded speed, and each
    regular wave's surge-force amplitude against R at its celerity."""
    if "resistance" not in d:
        return None
    u = d["resistance_speed"].values
    U = float(d.attrs["manoeuvre_speed"])

    def at(name, x):
        return float(np.interp(x, u, d[name].values)) / 1e3

    waves = [{"lam": float(lam), "c": float(c), "f": float(f) / 1e3, "r": at("resistance", float(c)),
              "line": at("resistance_friction_only", float(c))}
             for lam, c, f in zip(d["resistance_wave"].values, d["resistance_wave_celerity"].values,
                                  d["resistance_wave_surge_amplitude"].values)]
    a = d.attrs
    return {"method": a["resistance_method"], "holtrop": str(a["resistance_method"]).startswith("holtrop"),
            "curve": str(a["resistance_method"]) == "curve", "source": a.get("resistance_source", ""),
            "k1": float(a.get("resistance_form_factor", np.nan)), "area": float(a.get("resistance_wetted_area", np.nan)),
            "transom": float(a.get("resistance_transom_area", np.nan)), "bulb": float(a.get("resistance_bulb_area", np.nan)),
            "outside": a.get("resistance_outside_range", ""),
            "fn_max": float(a.get("resistance_froude_range_max", np.nan)), "speed": U,
            "fn": U / np.sqrt(G * float(a["manoeuvre_length"])), "r_u": at("resistance", U),
            "line_u": at("resistance_friction_only", U), "height": float(a["resistance_wave_height"]), "waves": waves}


def _radiation_summary(results: Path, figdir: Path, ship: str, d: xr.Dataset) -> dict:
    """The broaching chapter's account of the heave-pitch radiation: constant coefficients, or the
    memory model with its BEM frequency range, poles and figure (the radiation step's files)."""
    if d.attrs.get("heave_pitch_radiation", "constant") != "memory":
        return {"memory": False}
    f = results / "hydro" / f"{ship}_radiation.nc"
    fig = _optional_figures(results, figdir, f"hydro/{ship}_{{}}.png", ("radiation",))["radiation"]
    if not f.exists():
        return {"memory": True, "file": None, "figure": fig}
    with xr.open_dataset(f) as r:
        w = r["radiation_omega"].values
        return {"memory": True, "file": True, "figure": fig, "w0": float(w[0]), "w1": float(w[-1]), "n": len(w),
                "poles": int(r.sizes["pole"]), "panels": int(r.attrs["panels"]), "lid": int(r.attrs["lid_panels"]),
                "radius": float(r.attrs["max_panel_radius"]), "source": str(r.attrs["source"]),
                "a33": float(r["radiation_added_mass_inf_33"]), "a55": float(r["radiation_added_mass_inf_55"]),
                "order": int(r.attrs["order"])}


def parametric_roll_page(results: Path, config: dict, figdir: Path) -> str | None:
    """The derivative model (paper 001): fit, transfer functions, the regular-wave map of both models."""
    ship, d = _step_result(results, config, "derivative")
    if d is None:
        return None
    figs = _optional_figures(results, figdir, f"derivative/{ship}_{{}}.png", ("fit", "transfer_functions", "map"))
    rows = []
    for x in d["frequency_ratio"].values:
        for h in d["wave_height"].values:
            c = d.sel(frequency_ratio=x, wave_height=h)
            if float(c["roll_full"]) > 5 or float(c["roll_derivative"]) > 5:
                rows.append({"ratio": float(x), "height": float(h), "wavelength": float(c["wavelength"]),
                             "full": float(c["roll_full"]), "deriv": float(c["roll_derivative"]),
                             "steady": f"{'yes' if int(c['steady_full']) else 'no'} / "
                                       f"{'yes' if int(c['steady_derivative']) else 'no'}"})
    fit = {f: float(d["calm_residual"].sel(force=f) / d["calm_rms"].sel(force=f)) for f in ("heave", "roll", "pitch")}
    irregular = None
    from stabflow.dynamics.derivative import compared_ensembles

    ens = compared_ensembles(config)
    if ens:
        from stabflow.dynamics.derivative import ergodic_variance_cv, exceedance_probability, record_variances

        figs.update(_optional_figures(results, figdir, f"derivative/{ship}_{{}}.png", ("irregular", "running")))
        level = float(config["derivative"].get("level_deg", 25.0))
        irregular = {"level": level, "models": []}
        for kind in ("full", "derivative"):
            f = results / "ensemble" / ens[kind] / "ensemble.nc"
            if not f.exists():
                continue
            e = _open(f)
            rv, pv = record_variances(e, "roll"), record_variances(e, "pitch")
            p, lo, hi = exceedance_probability(e["roll_max"].values, level)
            irregular["models"].append({
                "name": {"full": "full volume-based", "derivative": "derivative"}[kind], "key": ens[kind],
                "hours": float(e["exposure_hours"]), "records": int(e.sizes["record"]),
                "roll_std": float(e["roll_std"]), "pitch_std": float(e["pitch_std"]), "p": p, "lo": lo, "hi": hi,
                "roll_cv": float(np.std(rv) / np.mean(rv)), "pitch_cv": float(np.std(pv) / np.mean(pv)),
                "roll_cv_ergodic": ergodic_variance_cv(e, "roll"), "pitch_cv_ergodic": ergodic_variance_cv(e, "pitch"),
                "roll_min": float(np.sqrt(rv.min())), "roll_maxsd": float(np.sqrt(rv.max())),
                "cpu": _benchmark_seconds(results, f"ensemble/{ens[kind]}_[0-9]*.tsv")})
            irregular.update(hs=float(e.attrs["hs"]), tp=float(e.attrs["tp"]), duration=float(e.attrs["duration"]),
                             n_components=int(e.attrs["n_components"]))
    if "map_speed" in d.coords:
        figs.update(_optional_figures(results, figdir, f"derivative/{ship}_{{}}.png", ("irregular_map",)))
    return _render("parametric_roll.md.j2", ship=ship, a=d.attrs, rows=rows, fit=fit, figures=figs,
                   cpu=_derivative_cpu(results, ship), cells=int(d["roll_full"].size),
                   irregular=irregular, has_map="map_speed" in d.coords)


def _derivative_cpu(results: Path, ship: str) -> dict | None:
    """{model: CPU seconds} of the derivative step's regular-wave map (results/derivative/<ship>_cpu.tsv), None if absent."""
    f = results / "derivative" / f"{ship}_cpu.tsv"
    if not f.exists():
        return None
    with open(f) as fh:
        return {r["model"]: float(r["cpu_s"]) for r in csv.DictReader(fh, delimiter="\t")}


def _benchmark_seconds(results: Path, pattern: str) -> float | None:
    """Summed CPU seconds of the Snakemake benchmark files ``results/benchmarks/<pattern>``, None if none."""
    total, found = 0.0, False
    for f in sorted((results / "benchmarks").glob(pattern)):
        with open(f) as fh:
            rec = list(csv.DictReader(fh, delimiter="\t"))
        if rec and "cpu_time" in rec[0]:
            total += float(rec[0]["cpu_time"])
            found = True
    return total if found else None


#: validation steps in report order: (step attribute, title, file suffix)
STEPS = [("statics", "Calm-water statics", "statics"), ("waves", "Stability in waves and metric C", "waves"),
         ("dynamics", "Time domain (3-DOF)", "dynamics"),
         ("ensemble", "Irregular seas: seaways, step size, extremes, split-time", "ensemble"),
         ("capsize", "Capsize-rate methods against brute force (1-DOF box barge)", "capsize"),
         ("manoeuvring", "6-DOF manoeuvring and surf-riding", "manoeuvring"),
         ("derivative", "Derivative model against the full model (parametric roll)", "derivative"),
         ("criteria", "Stability criteria and the direct stability assessment", "criteria")]


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


def _passes(rows: list[dict]) -> dict[str, str]:
    """{kind: 'PASS / checked pass'} for the kinds with checks that ran (SKIPPED rows left out)."""
    out = {}
    for kind in ("independent", "consistency"):
        k = [r for r in rows if r["kind"] == kind and r["status"] != "SKIPPED"]
        if k:
            out[kind] = f"{sum(r['status'] == 'PASS' for r in k)} / {len(k)} pass"
    return out


def step_summary(rows: list[dict]) -> str:
    """'independent 12 / 14 pass, consistency 5 / 5 pass, 2 skipped' for one step's rows."""
    parts = [f"{kind} {frac}" for kind, frac in _passes(rows).items()]
    skipped = sum(r["status"] == "SKIPPED" for r in rows)
    if skipped:
        parts.append(f"{skipped} skipped")
    return ", ".join(parts) or "no checks"


def validation_page(results: Path, expected: dict) -> tuple[str, dict]:
    """MyST page: a summary line per step, every FAIL listed first, then one table per step.
    Returns (page, counts) with counts[step] = {PASS, FAIL, SKIPPED, summary}."""
    rows = validation_rows(results, expected)
    counts, steps = {}, []
    for step, title, _ in STEPS:
        r = rows[step]
        counts[step] = {st: sum(x["status"] == st for x in r) for st in ("PASS", "FAIL", "SKIPPED")}
        counts[step]["summary"] = step_summary(r)
        steps.append({"key": step, "title": title, "rows": r, "counts": counts[step], "passes": _passes(r)})
    fails = [(s["title"], x) for s in steps for x in s["rows"] if x["status"] == "FAIL"]
    return _render("validation.md.j2", steps=steps, fails=fails), counts


def overview_page(results: Path, ships: list[str], config: dict, counts: dict) -> str:
    import numba
    import scipy

    versions = {"stabflow": __version__, "python": platform.python_version(), "numpy": np.__version__,
                "scipy": scipy.__version__, "numba": numba.__version__, "xarray": xr.__version__}
    return _render("index.md.j2", counts=counts, steps=[{"key": step, "title": title} for step, title, _ in STEPS],
                   ships=ships, versions=list(versions.items()), benchmarks=_benchmarks(results),
                   config_yaml=yaml.safe_dump(_plain(config), sort_keys=False, default_flow_style=None,
                                              width=110).rstrip())


def _plain(obj):
    """Config as plain Python containers (Snakemake's config holds its own mapping types)."""
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    return obj


def expected_validation(ships: list[str], config: dict) -> dict:
    """The validation files a run must have: statics, waves and dynamics per ship, ensemble per
    ensemble condition, the 1-DOF capsize case when configured."""
    ens = [(f"{c['ship']}_{c['name']}", c["ship"]) for c in config.get("ensembles", [])]
    one_dof = [("box1dof", "box1dof")] if config.get("capsize_1dof", {}).get("bands") else []
    six = [(config["broaching"]["ship"], config["broaching"]["ship"])] if "broaching" in config else []
    der = [(config["derivative"]["ship"], config["derivative"]["ship"])] if "derivative" in config else []
    return {"statics": [(s, s) for s in ships], "waves": [(s, s) for s in ships], "dynamics": [(s, s) for s in ships],
            "ensemble": ens, "capsize": one_dof, "manoeuvring": six, "derivative": der,
            "criteria": [(s, s) for s in ships] + [("dsa_linear", "dsa_linear")]}


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
        chapters = {f"ship_{s}": ship_page(s, results, figdir) for s in ships}
        chapters.update({f"criteria_{s}": criteria_page(s, results, figdir) for s in ships})
        chapters["waves"] = waves_page(results, figdir)
        chapters["rare_events"] = rare_events_page(results, config, figdir)
        chapters["broaching"] = broaching_page(results, config, figdir)
        chapters["parametric_roll"] = parametric_roll_page(results, config, figdir)
        chapters = {stem: page for stem, page in chapters.items() if page}
        for stem, page in chapters.items():
            (book / f"{stem}.md").write_text(page)
        (book / "_toc.yml").write_text(_render("_toc.yml.j2", chapters=list(chapters)))
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
