"""The criteria data: every value sourced, null values explained, overrides validated."""

import numpy as np
import pytest

from stabflow import StabflowError
from stabflow.criteria.standards import Standards


def test_every_entry_has_provenance():
    std = Standards()
    assert len(std.entries) > 30
    for key, e in std.entries.items():
        assert e["source"], key
        assert e["value"] is not None or e["missing"], key
        assert e["value"] is None or e.get("read_at"), key


def test_missing_source_is_an_error(tmp_path):
    import shutil

    from stabflow.criteria.standards import DATA_DIR, FILES

    for f in FILES:
        shutil.copy(DATA_DIR / f"{f}.yaml", tmp_path / f"{f}.yaml")
    text = (tmp_path / "is_code_2008.yaml").read_text().replace(
        'source: "IMO Res. MSC.267(85) 2008 IS Code, Part A, 2.2.1 (area under GZ curve up to 30 deg)"', "")
    (tmp_path / "is_code_2008.yaml").write_text(text)
    with pytest.raises(StabflowError, match="area_0_to_30.source"):
        Standards(data_dir=tmp_path)


@pytest.mark.parametrize("item, match", [
    ("{key: no.such.entry, value: 1.0, source: x}", "criteria_overrides.0.key"),
    ("{key: is_code_2008.general_criteria.gm0_min, value: abc, source: x}", "criteria_overrides.0.value"),
    ("{key: is_code_2008.general_criteria.gm0_min, value: 0.2}", "criteria_overrides.0"),
    ("{key: is_code_2008.general_criteria.gm0_min, value: 0.2, source: ' '}", "criteria_overrides.0.source"),
    ("{key: is_code_2008.general_criteria.gm0_min, value: 0.2, source: x, unit: ft}", "criteria_overrides.0.unit"),
])
def test_bad_override_names_file_and_field(tmp_path, item, match):
    p = tmp_path / "o.yaml"
    p.write_text(f"criteria_overrides:\n  - {item}\n")
    with pytest.raises(StabflowError, match=match) as e:
        Standards(p)
    assert str(p) in str(e.value)


def test_override_replaces_value_and_records_source(tmp_path):
    p = tmp_path / "o.yaml"
    p.write_text("criteria_overrides:\n  - {key: is_code_2008.general_criteria.gm0_min, value: 0.35, source: 'owner rule 4.1'}\n")
    std = Standards(p)
    s = std.get("is_code_2008.general_criteria.gm0_min")
    assert s.value == 0.35 and s.source == "owner rule 4.1" and str(p) in s.read_at
    assert std.overrides_summary() and "owner rule 4.1" in std.overrides_summary()[0]


def test_tables_are_entries_and_can_be_overridden(tmp_path):
    """A table (pairs) is checked for provenance like a value and is overridden as a whole; rows
    must be [x, y] pairs with x ascending."""
    key = "is_code_2008.weather_criterion.roll_back_angle_phi1.X2_table"
    std = Standards()
    x, y, s = std.table(key)
    assert x[0] == 0.45 and y[-1] == 1.00 and "2.3.4" in s.source
    p = tmp_path / "o.yaml"
    p.write_text(f"criteria_overrides:\n  - {{key: {key}, value: [[0.4, 0.7], [0.8, 1.0]], source: 'owner table 7'}}\n")
    x, y, s = Standards(p).table(key)
    assert list(x) == [0.4, 0.8] and s.source == "owner table 7"
    p.write_text(f"criteria_overrides:\n  - {{key: {key}, value: [[0.8, 0.7], [0.4, 1.0]], source: 'x'}}\n")
    with pytest.raises(StabflowError, match="criteria_overrides.0.value"):
        Standards(p)


def test_round_off_meets_the_limit():
    """A value equal to its limit up to round-off passes; one just beyond it fails."""
    from stabflow.criteria.verdicts import Row

    assert Row("r", "l", 1.0 - 1e-15, "-", 1.0, ">=", "s").verdict == "PASS"
    assert Row("r", "l", 1.0 - 1e-6, "-", 1.0, ">=", "s").verdict == "FAIL"
    assert Row("r", "l", 16.0 + 1e-12, "deg", 16.0, "<=", "s").verdict == "PASS"
    assert Row("r", "l", float("inf"), "deg", 16.0, "<=", "s").verdict == "FAIL"
    assert Row("r", "l", float("nan"), "deg", 16.0, "<=", "s").verdict == "NOT EVALUATED"


def _copy_data(tmp_path):
    import shutil

    from stabflow.criteria.standards import DATA_DIR, FILES

    for f in FILES:
        shutil.copy(DATA_DIR / f"{f}.yaml", tmp_path / f"{f}.yaml")
    return tmp_path / "sgisc.yaml"


def test_drafts_are_checked(tmp_path):
    """A draft sits only beside a null value, with a number, its source, where it was read and the
    words printed; each shipped draft names an ISSW paper's file."""
    std = Standards()
    drafts = {k: e["draft"] for k, e in std.entries.items() if "draft" in e}
    fm = "sgisc.failure_modes."
    wc = "sgisc.wave_data.pure_loss_and_parametric_roll_level2_wave_cases."
    table = drafts.pop(wc + "cases")
    assert {k: d["value"] for k, d in drafts.items()} == {
        fm + "pure_loss_of_stability.level_2.RPL0": 0.06, fm + "pure_loss_of_stability.level_2.RPL2_heel_angle_deg": 25,
        fm + "parametric_rolling.level_2.RPR0": 0.06, fm + "parametric_rolling.level_2.roll_angle_threshold_deg": 25,
        fm + "surf_riding_broaching.level_1.length_limit_m": 200, fm + "surf_riding_broaching.level_1.froude_number_limit": 0.3,
        fm + "surf_riding_broaching.level_2.R_SR": 0.005, wc + "count": 16}
    for k, d in drafts.items():
        assert std.get(k).value is None and std.get(k).draft["value"] == d["value"], k
        assert "PDF_STAB_ISSW" in d["read_at"] and f"{d['value']:g}" in d["quote"], k
    # the 2013 draft's Table 3-A-1: 16 waves (W, lambda, H), its first and last rows quoted; the
    # weights are the Rec. 34 table's column sums over Hs / 100,000 (Tz 3.5 ... 18.5)
    assert table["columns"] == ["W", "lambda_m", "H_m"] and len(table["value"]) == 16
    assert table["value"][0] == [1.3e-05, 22.574, 0.35] and table["value"][-1] == [7e-06, 630.684, 5.95]
    assert "1 1.300E-05 22.574 0.35" in table["quote"] and "16 7.000E-06 630.684 5.95" in table["quote"]
    rec = std.raw["iacs_rec34_scatter"]
    cols = np.sum([r["counts"] for r in rec["hs_rows"]], axis=0)[2:] / 1e5
    # to the table's four printed digits (largest 1.2e-4); W_12 = 2.473E-03 is the Tz 14.5 column with
    # 0.3 at Hs 15.5 (247.3; 247.1 with the 0.1 of the Snoopy array): a fifth copy of that cell
    np.testing.assert_allclose([r[0] for r in table["value"]], cols, rtol=2e-4, atol=0)
    import yaml

    p = _copy_data(tmp_path)
    data = yaml.safe_load(p.read_text())
    entry = data["failure_modes"]["surf_riding_broaching"]["level_2"]["R_SR"]
    for change, match in (({"value": 0.01, "read_at": "x"}, "R_SR.draft: a draft is kept only where the adopted value is missing"),
                          ({"draft": {**entry["draft"], "value": "abc"}}, "R_SR.draft.value"),
                          ({"draft": {k: v for k, v in entry["draft"].items() if k != "quote"}}, "R_SR.draft: give value"),
                          ({"draft": {**entry["draft"], "columns": ["a"]}}, "R_SR.draft.columns: only a table"),
                          ({"draft": {**entry["draft"], "value": [[1.0, 2.0]], "columns": ["a"]}}, "R_SR.draft.value: a table"),
                          ({"draft": {**entry["draft"], "value": [[1.0, "x"]], "columns": ["a", "b"]}}, "R_SR.draft.value: a table"),
                          ({"draft": {**entry["draft"], "value": [[1.0]]}}, "R_SR.draft.value: a table")):
        data["failure_modes"]["surf_riding_broaching"]["level_2"]["R_SR"] = {**entry, **change}
        p.write_text(yaml.safe_dump(data))
        with pytest.raises(StabflowError, match=match):
            Standards(data_dir=tmp_path)


def test_an_override_replaces_the_draft(tmp_path):
    """A user's value for a drafted entry: the Standard has its value and no draft."""
    key = "sgisc.failure_modes.surf_riding_broaching.level_2.R_SR"
    p = tmp_path / "o.yaml"
    p.write_text(f"criteria_overrides:\n  - {{key: {key}, value: 0.004, source: 'owner copy 2.12.3'}}\n")
    s = Standards(p).get(key)
    assert s.value == 0.004 and s.draft is None and s.cite_draft() == ""


def test_indicative_verdict_only_where_drafts_cover_every_missing_item():
    """The row stays NOT EVALUATED; the indicative verdict needs every missing item drafted and a value."""
    from stabflow.criteria.standards import Standard
    from stabflow.criteria.verdicts import against

    d = {"value": 0.3, "source": "draft", "read_at": "here", "quote": "0.3"}
    s = Standard("k", None, "-", "doc 1", "", "not read", d)
    r = against("c", "l", 0.2, "-", s, "<=")
    assert r.verdict == "NOT EVALUATED" and r.draft_verdict == "PASS" and "Indicative" in r.reason
    assert against("c", "l", 0.4, "-", s, "<=").draft_verdict == "FAIL"
    assert against("c", "l", float("nan"), "-", s, "<=").draft_verdict == ""
    assert against("c", "l", 0.2, "-", s, "<=", missing=["the wave cases"]).draft_verdict == ""
    undrafted = Standard("k2", None, "-", "doc 2", "", "not read")
    assert against("c", "l", 0.2, "-", undrafted, "<=").draft_verdict == ""
    # another needed standard missing: covered only if it is drafted
    other = Standard("k3", None, "m", "doc 3", "", "not read", {**d, "value": 200})
    m = [f"{other.key} ({other.source})"]
    assert against("c", "l", 0.2, "-", s, "<=", missing=m, drafted=[other]).draft_verdict == "PASS"
    assert against("c", "l", 0.2, "-", s, "<=", missing=m).draft_verdict == ""
