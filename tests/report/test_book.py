"""The report's number formats (``stabflow.report.book``)."""

import math
from pathlib import Path

from stabflow.report.book import _fmt, _rate


def test_rate_prints_an_underflowed_rate_from_log_space():
    """A rate that underflowed to 0 prints its order of magnitude from its log10, never a bare 0; a
    representable rate prints as every other number; a rate with no finite log10 stays as it is."""
    assert _rate(0.0, -412.5).startswith("3.2e-413 ")
    assert "log space" in _rate(0.0, -412.5)
    assert _rate(2.5e-3, math.log10(2.5e-3)) == _fmt(2.5e-3) == "0.0025"
    assert _rate(0.0, -math.inf) == "0"
    assert _rate(math.inf, math.inf) == "–"


def test_rate_text_rounds_the_mantissa_into_its_decade():
    """A mantissa that rounds up to 10 moves to the next decade (1e-300, not 10e-301); Rice's log10
    rate keeps NaN as NaN and a process without up-crossings at -inf."""
    from stabflow.criteria.dsa import rice_log10_rate
    from stabflow.criteria.sea_states import rate_text

    assert rate_text(0.0, -300.0001).startswith("1e-300 ")
    assert math.isnan(rice_log10_rate(math.nan, 1.0, 1.0)) and rice_log10_rate(1.0, 0.0, 1.0) == -math.inf


def test_criteria_table_rows_have_one_cell_per_column():
    """The criteria chapter's verdict table (the template's own block): a row with a draft's limit and
    an indicative verdict, one without, and the DSA's row keep seven cells each."""
    import re

    from stabflow.report.book import _env

    text = (Path(__file__).resolve().parents[2] / "src/stabflow/report/templates/criteria.md.j2").read_text()
    block = re.search(r"{% call\(r\) m\.table.*?{% endcall %}\n", text, re.S).group(0)
    base = {"name": "c", "level": "l", "value": 0.35, "unit": "-", "limit": None, "sense": "<=", "verdict": "NOT EVALUATED",
            "reason": "missing: x", "source": "doc", "draft_limit": None, "draft_source": "", "draft_verdict": ""}
    rows = [base, {**base, "draft_limit": 0.3, "draft_source": "draft doc", "draft_verdict": "FAIL"},
            {**base, "limit": 0.0026, "verdict": "FAIL", "unit": "1/year"}]
    out = _env().from_string('{% import "_macros.md.j2" as m %}' + block).render(rows=rows)
    lines = [x for x in out.splitlines() if x.startswith("| ")]
    assert len(lines) == 4  # header and three rows
    for x in lines:
        assert x.count(" | ") == 6, x
    assert "(indicative against the draft: FAIL) | missing: x" in lines[2] and "(draft: <= 0.3)" in lines[2]
    assert "draft: draft doc" in lines[2] and "draft" not in lines[1]


def test_criteria_c1_table_one_cell_per_column():
    """The criteria chapter's C1 section (the template's own block): C1, the speed requirement's state,
    and one row of eight cells per wave (a NaN V_PR printed, not dropped)."""
    import re

    from stabflow.report.book import _env

    text = (Path(__file__).resolve().parents[2] / "src/stabflow/report/templates/criteria.md.j2").read_text()
    block = re.search(r"{% if c1 %}.*?{% endif %}\n", text, re.S).group(0)
    row = {"i": 1, "w": 0.25, "lam": 100.0, "h": 2.0, "gm": 1.9, "ratio": 0.05, "vpr": 3.2, "fails": 0.0}
    c1 = {"value": 0.125, "speed": "evaluated", "tphi": 11.5, "rpr": 0.477, "vd": 15.41, "crests": 10,
          "rows": [row, {**row, "i": 2, "vpr": math.nan, "fails": 1.0}]}
    out = _env().from_string('{% import "_macros.md.j2" as m %}' + block).render(c1=c1)
    assert "**C1 = 0.125**" in out and "speed requirement evaluated" in out and "V_D = 15.41 m/s" in out
    lines = [x for x in out.splitlines() if x.startswith("| ")]
    assert len(lines) == 3 and all(x.count(" | ") == 7 for x in lines), lines
    assert "| 2 | 0.25 | 100.0 | 2.000 | 1.900 | 0.050 |" in lines[2]


def test_criteria_c2_section_renders():
    """The C2 section: its value, the speeds it misses, one row of three cells per speed and heading."""
    import re

    from stabflow.report.book import _env

    text = (Path(__file__).resolve().parents[2] / "src/stabflow/report/templates/criteria.md.j2").read_text()
    block = re.search(r"{% if c2 %}.*?{% endif %}\n{% endif %}\n", text, re.S).group(0)
    c2 = {"value": 0.0123, "threshold": 25.0, "left_out": 0.0, "missing": "none", "headings": "none", "breaking": 0.001,
          "service": 0.41,
          "rows": [{"heading": 0.0, "fn": 0.1, "c2": 0.02}, {"heading": 180.0, "fn": 0.1, "c2": 0.0046}]}
    out = _env().from_string('{% import "_macros.md.j2" as m %}' + block).render(c2=c2)
    assert "**C2 = 0.0123**" in out and "exceeds 25°" in out and "NaN" not in out
    lines = [x for x in out.splitlines() if x.startswith("| ")]
    assert len(lines) == 3 and all(x.count(" | ") == 2 for x in lines), lines
    miss = _env().from_string('{% import "_macros.md.j2" as m %}' + block).render(c2={**c2, "missing": "0.4", "rows": []})
    assert "no 1-DOF coefficients at Fn 0.4" in miss and "| " not in miss
    nospeed = _env().from_string('{% import "_macros.md.j2" as m %}' + block).render(
        c2={**c2, "value": math.nan, "service": math.nan, "rows": []})
    assert "no service speed in the ship config" in nospeed


def test_paper_004_comparison_matches_cases_by_their_wave():
    """Each heavy-loading case gets paper 004's outcome by its wave (regular wavelength with H 1.8 m,
    or Hs), and capsize-or-not is compared where the paper states it (not IR-3)."""
    import numpy as np
    import xarray as xr

    from stabflow.report.book import paper_004_comparison

    cases = ["R-1", "R-2", "R-3", "R-4", "IR-1", "IR-2", "IR-3"]
    lam = [21.3, 30.5, 42.7, 85.3, np.nan, np.nan, np.nan]
    height = [1.8] * 4 + [3.1, 4.0, 4.6]
    cap = [[0, 1, 1, 0, 1, 1, 1], [0] * 7]
    d = xr.Dataset({"capsized": (("loading", "case"), np.array(cap)), "wavelength": ("case", lam),
                    "wave_height": ("case", height)}, coords={"loading": ["heavy", "tank_test"], "case": cases})
    texts, versus = paper_004_comparison(d)
    assert texts["R-2"].startswith("broach and capsize") and texts["IR-3"].startswith("not stated")
    assert versus["compared"] == 6
    assert versus["agree"] == ["R-2", "R-3", "R-4", "IR-2"] and versus["differ"] == ["R-1", "IR-1"]
    # a wave the paper did not run is not compared
    d2 = d.assign(wave_height=("case", [2.0] * 4 + [3.1, 4.0, 4.6]))
    assert paper_004_comparison(d2)[1]["compared"] == 2


def test_scenario_ensembles_find_the_paper_case_and_give_the_rate_interval(tmp_path):
    """A 6-DOF ensemble of the broaching ship is reported with its capsize rate and Garwood
    interval, and matched to paper 004's irregular case of the same loading's KG and Hs."""
    import numpy as np
    import xarray as xr
    from scipy import stats

    from stabflow.report.book import _scenario_ensembles

    cases = ["IR-1", "IR-2"]
    d = xr.Dataset({"wavelength": ("case", [np.nan, np.nan]), "wave_height": ("case", [3.1, 4.0]),
                    "kg": ("loading", [3.8873, 3.468])}, coords={"loading": ["heavy", "tank_test"], "case": cases})
    folder = tmp_path / "ensemble" / "trawler_sq6"
    folder.mkdir(parents=True)
    xr.Dataset({"capsize_count": 18, "exposure_hours": 90.0, "warmup_lost_count": 3, "broach_count": 500},
               attrs={"n_records": 600}).to_netcdf(folder / "ensemble.nc")
    config = {"broaching": {"heading_deg": 45.0, "speed_kn": 10.0},
              "ensembles": [{"name": "sq6", "ship": "trawler", "dof": 6, "kg": 3.8873, "heading_deg": 45.0,
                             "speed_kn": 10.0, "duration": 600.0, "warmup_s": 100.0,
                             "sea": {"spectrum": "pierson_moskowitz", "hs": 4.0}},
                            {"name": "sq", "ship": "trawler", "sea": {"hs": 4.0}}]}
    (e,) = _scenario_ensembles(tmp_path, config, "trawler", d)
    assert e["case"] == "IR-2, heavy loading" and e["k"] == 18 and e["lost"] == 3 and e["records"] == 600
    assert e["rate"] == 18 / 90.0
    assert e["lo"] == stats.chi2.ppf(0.025, 36) / 2 / 90.0 and e["hi"] == stats.chi2.ppf(0.975, 38) / 2 / 90.0
    config["ensembles"][0]["kg"] = 3.5
    assert _scenario_ensembles(tmp_path, config, "trawler", d)[0]["case"] is None
