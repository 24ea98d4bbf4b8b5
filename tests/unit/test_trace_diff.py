"""``acphys diff`` for a port (issue 15): records paired per body, fields and bodies chosen, every
divergence counted, context, a JSON report, and v1 traces against v2.

The traces are real: the built-in default scenario, run for half a second, then copies edited.
"""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys import trace_diff
from acphys.cli import main
from acphys.trace_diff import END_OF_TRACE, NO_SUCH_BODY, DiffError, Divergence, compare_traces, diff_traces

Record = dict[str, Any]


@pytest.fixture(scope="module")
def trace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("diff") / "default.jsonl"
    acphys.load_scenario("default").run(until=0.5, trace=path)
    return path


@pytest.fixture
def header(trace: Path) -> Record:
    return json.loads(trace.read_text(encoding="utf-8").partition("\n")[0])


@pytest.fixture
def records(trace: Path) -> list[Record]:
    """The body records (line ``i + 2`` holds ``records[i]``: line 1 is the header)."""
    return [json.loads(line) for line in trace.read_text(encoding="utf-8").splitlines()[1:]]


def write(path: Path, records: list[Record], header: Record | None = None) -> Path:
    lines = ([header] if header is not None else []) + records
    path.write_text("".join(json.dumps(line) + "\n" for line in lines), encoding="utf-8")
    return path


def index_of(records: list[Record], body: str, k: int) -> int:
    """The index of the ``k``-th record (from 0) of ``body``."""
    return [i for i, record in enumerate(records) if record["body"] == body][k]


def invoke(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def one_error_line(code: int, err: str) -> str:
    assert code == 2, err
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("acphys: error: "), err
    return lines[0]


def test_the_trace_is_v2_with_start_records(header: Record, records: list[Record]) -> None:
    assert header["schema"] == "acphys.trace/2"
    assert [record["quantum"] for record in records[:7]] == [0.0] * 7
    assert {"id", "heading", "motion"} <= records[0].keys()


def test_a_trace_is_identical_to_a_copy(trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    copy = tmp_path / "copy.jsonl"
    shutil.copyfile(trace, copy)
    report = compare_traces(trace, copy, all_bodies=True)
    assert report.identical and report.first is None
    assert (report.records_compared, report.bodies_compared) == (112, 7)
    assert report.missing_bodies == {"a": [], "b": []}
    assert invoke(["diff", str(trace), str(copy)], capsys) == (0, "identical within 1e-06\n", "")


# -- pairing per body --------------------------------------------------------------------------


def test_bodies_written_in_another_order_pair_up(
    trace: Path, header: Record, records: list[Record], tmp_path: Path
) -> None:
    steps = [records[i : i + 7] for i in range(0, len(records), 7)]
    reordered = write(tmp_path / "b.jsonl", [r for step in steps for r in reversed(step)], header)
    assert diff_traces(trace, reordered, tol=0.0) is None


def test_an_extra_record_diverges_only_its_body(
    trace: Path, header: Record, records: list[Record], tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    changed = [*records]
    last_ball = index_of(records, "ball", -1)
    changed.insert(last_ball + 1, dict(records[last_ball]))
    b = write(tmp_path / "b.jsonl", changed, header)
    report = compare_traces(trace, b, all_bodies=True)
    assert [d.body for d in report.divergences] == ["ball"]
    found = report.divergences[0]
    assert (found.field, found.a, found.b) == ("record", END_OF_TRACE, "record 17")
    assert (found.line, found.line_a, found.line_b) == (last_ball + 3, None, last_ball + 3)
    assert dict(report.field_counts) == {"record": 1}
    assert report.records_compared == len(records)
    code, out, _ = invoke(["diff", str(trace), str(b)], capsys)
    assert code == 1 and f"line {last_ball + 3}" in out and "<end of trace>" in out


def test_a_missing_record_shifts_only_its_body(
    trace: Path, header: Record, records: list[Record], tmp_path: Path
) -> None:
    gone = index_of(records, "drifter", 5)
    b = write(tmp_path / "b.jsonl", records[:gone] + records[gone + 1 :], header)
    report = compare_traces(trace, b, all_bodies=True)
    assert [d.body for d in report.divergences] == ["drifter"]
    first = report.divergences[0]
    assert (first.line, first.line_b) == (gone + 2, index_of(records, "drifter", 6) + 1)
    assert "record" in report.field_counts  # a has one drifter record more


def test_a_body_one_trace_lacks_is_reported(
    trace: Path, header: Record, records: list[Record], tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    b = write(tmp_path / "b.jsonl", [r for r in records if r["body"] != "sitter"], header)
    report = compare_traces(trace, b, all_bodies=True)
    assert report.missing_bodies == {"a": [], "b": ["sitter"]}
    found = report.first
    assert found is not None
    assert (found.body, found.field, found.a, found.b) == ("sitter", "record", "record 1", NO_SUCH_BODY)
    assert report.body_counts["sitter"] == 16
    code, out, _ = invoke(["diff", str(b), str(trace), "--all"], capsys)
    assert code == 1 and "body 'sitter' is not in a" in out


def test_a_trace_far_ahead_stops_the_comparison(
    trace: Path, header: Record, records: list[Record], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(trace_diff, "MAX_UNPAIRED", 5)
    b = write(tmp_path / "b.jsonl", [r for r in records if r["body"] != "ball"], header)
    report = compare_traces(trace, b, all_bodies=True)
    assert (
        report.stopped is not None
        and "a has 6 records of body 'ball' that b has not matched" in report.stopped
    )
    assert report.missing_bodies is None
    assert [(d.body, d.field) for d in report.divergences] == [("ball", "record")]


# -- choosing what is compared -----------------------------------------------------------------


def test_fields_and_bodies_restrict_the_comparison(
    trace: Path, header: Record, records: list[Record], tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    changed = json.loads(json.dumps(records))
    changed[index_of(records, "ball", 4)]["velocity"][0] += 1.0  # another field of the body
    changed[index_of(records, "drifter", 4)]["origin"][1] += 1.0  # the field, in another body
    b = write(tmp_path / "b.jsonl", changed, header)
    assert invoke(["diff", str(trace), str(b), "--fields", "origin", "--bodies", "ball"], capsys)[0] == 0
    assert compare_traces(trace, b, fields=["origin"], bodies=["ball"]).identical
    assert compare_traces(trace, b, ignore=["velocity"], bodies=["ball"]).identical
    found = compare_traces(trace, b, fields=["origin"]).first
    assert found is not None and (found.body, found.field) == ("drifter", "origin[1]")
    found = compare_traces(trace, b, bodies=["ball", "sitter"]).first
    assert found is not None and (found.body, found.field) == ("ball", "velocity[0]")


def test_motion_sub_fields_are_compared_one_by_one(
    trace: Path, header: Record, records: list[Record], tmp_path: Path
) -> None:
    changed = json.loads(json.dumps(records))
    walker = index_of(records, "walker", 3)
    assert changed[walker]["motion"]["forward_speed"] is not None
    changed[walker]["motion"]["forward_speed"] += 0.5
    changed[walker]["motion"]["hold_key"] = "other"
    b = write(tmp_path / "b.jsonl", changed, header)
    report = compare_traces(trace, b, all_bodies=True)
    assert dict(report.field_counts) == {"motion.forward_speed": 1, "motion.hold_key": 1}
    found = report.first
    assert found is not None and found.field == "motion.forward_speed" and found.difference == 0.5
    assert compare_traces(trace, b, fields=["motion.forward", "origin"]).identical
    assert compare_traces(trace, b, ignore=["motion"]).identical
    only = compare_traces(trace, b, fields=["motion.hold_key"]).first
    assert only is not None and (only.field, only.b) == ("motion.hold_key", "other")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ["--bodies", "ball,nobody"],
            "--bodies: no body named 'nobody' in either trace (they have: 'skydiver',",
        ),
        (["--bodies", ","], "--bodies needs at least one name"),
        (["--fields", "origin,colour"], "--fields: unknown field 'colour'"),
        (["--ignore", "motion.mood"], "--ignore: unknown field 'motion.mood'"),
        (["--fields", "body"], "--fields: body names the records compared"),
        (["--context", "-1"], "--context must be between 0 and"),
    ],
    ids=["unknown-body", "no-body", "unknown-field", "unknown-sub-field", "body-field", "context"],
)
def test_a_bad_choice_is_one_error_line(
    trace: Path,
    header: Record,
    records: list[Record],
    tmp_path: Path,
    capsys: pytest.CaptureFixture,
    args: list[str],
    message: str,
) -> None:
    changed = json.loads(json.dumps(records))
    changed[index_of(records, "ball", 1)]["origin"][0] += 1.0  # a divergence before the end
    b = write(tmp_path / "b.jsonl", changed, header)
    code, out, err = invoke(["diff", str(trace), str(b), *args], capsys)
    assert message in one_error_line(code, err) and out == ""


def test_a_bad_choice_is_a_diff_error() -> None:
    with pytest.raises(DiffError, match="unknown field 'colour'"):
        compare_traces("a.jsonl", "b.jsonl", fields=["colour"])


# -- --all, context, JSON ----------------------------------------------------------------------


@pytest.fixture
def planted(header: Record, records: list[Record], tmp_path: Path) -> Path:
    """ball's origin off in its records 3 and 9, drifter's velocity and omega in its record 6."""
    changed = json.loads(json.dumps(records))
    for k in (3, 9):
        changed[index_of(records, "ball", k)]["origin"][2] += 0.01
    drifter = changed[index_of(records, "drifter", 6)]
    drifter["velocity"][1] += 0.5
    drifter["omega"][2] += 0.25
    return write(tmp_path / "planted.jsonl", changed, header)


def test_all_reports_every_diverging_body_and_the_counts_per_field(
    trace: Path, records: list[Record], planted: Path, capsys: pytest.CaptureFixture
) -> None:
    report = compare_traces(trace, planted, all_bodies=True)
    assert [(d.body, d.field, d.line) for d in report.divergences] == [
        ("ball", "origin[2]", index_of(records, "ball", 3) + 2),
        ("drifter", "velocity[1]", index_of(records, "drifter", 6) + 2),
    ]
    assert dict(report.field_counts) == {"origin": 2, "velocity": 1, "omega": 1}
    assert dict(report.body_counts) == {"ball": 2, "drifter": 1}
    code, out, _ = invoke(["diff", str(trace), str(planted), "--all"], capsys)
    assert code == 1
    assert out.count("first divergence at") == 2
    assert "2 of 7 bodies diverge; 112 record pairs compared" in out
    assert re.search(r"origin\s+2\n", out) and re.search(r"omega\s+1\n", out)


def test_without_all_the_first_divergence_alone_is_reported(trace: Path, planted: Path) -> None:
    report = compare_traces(trace, planted)
    assert [d.body for d in report.divergences] == ["ball"]
    assert report.missing_bodies is None  # it stopped there


def test_context_shows_the_records_of_the_body_before_the_divergence(
    trace: Path, records: list[Record], planted: Path, capsys: pytest.CaptureFixture
) -> None:
    found = compare_traces(trace, planted, context=2).first
    assert found is not None
    lines = [index_of(records, "ball", k) + 2 for k in (1, 2)]
    assert [(row.line_a, row.line_b) for row in found.context] == [(line, line) for line in lines]
    assert [row.a for row in found.context] == [records[line - 2]["origin"][2] for line in lines]
    assert all(row.a == row.b and row.difference == 0.0 for row in found.context)
    code, out, _ = invoke(["diff", str(trace), str(planted)], capsys)
    text = out.splitlines()
    assert code == 1 and text[0].startswith(f"first divergence at line {found.line}, ")
    assert "origin[2] in a" in text[1] and "origin[2] in b" in text[1]
    assert [row.split()[0] for row in text[2:4]] == [str(line) for line in lines]
    assert text[4].split()[:3] == [">", str(found.line), str(found.line)] and text[4].endswith("0.01")
    _, out, _ = invoke(["diff", str(trace), str(planted), "--context", "0"], capsys)
    assert len(out.splitlines()) == 1
    early = compare_traces(trace, planted, context=10).first
    assert early is not None and len(early.context) == 3  # records 0, 1 and 2 of the ball


def test_the_json_report(
    trace: Path, planted: Path, header: Record, tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    path = tmp_path / "report.json"
    code, out, _ = invoke(["diff", str(trace), str(planted), "--all", "--json", str(path)], capsys)
    assert code == 1 and f"report: {path}" in out
    report = json.loads(path.read_text(encoding="utf-8"))
    assert report.keys() >= {
        "identical", "tolerance", "a", "b", "records_compared", "bodies_compared",
        "divergences", "field_counts", "missing_bodies",
    }  # fmt: skip
    assert (report["identical"], report["tolerance"]) == (False, 1e-6)
    assert report["a"] == {"path": str(trace), "header": header}
    assert report["b"]["header"] == header
    assert (report["records_compared"], report["bodies_compared"]) == (112, 7)
    assert report["field_counts"] == {"origin": 2, "velocity": 1, "omega": 1}
    assert report["missing_bodies"] == {"a": [], "b": []}
    first = report["divergences"][0]
    assert first.keys() >= {"body", "line_a", "line_b", "t", "field", "a", "b", "difference"}
    assert (first["body"], first["field"], first["line_a"]) == ("ball", "origin[2]", first["line_b"])
    assert first["difference"] == pytest.approx(0.01)
    assert len(first["context"]) == 2
    code, out, _ = invoke(["diff", str(trace), str(trace), "--json", "-"], capsys)
    assert code == 0 and json.loads(out)["identical"] is True and json.loads(out)["divergences"] == []


def test_the_json_report_spells_non_finite_numbers_as_strings(
    records: list[Record], tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    changed = json.loads(json.dumps(records))
    changed[0]["velocity"][0] = float("nan")
    a = write(tmp_path / "a.jsonl", records)
    b = write(tmp_path / "b.jsonl", changed)
    code, out, _ = invoke(["diff", str(a), str(b), "--json", "-"], capsys)
    report = json.loads(out, parse_constant=lambda name: pytest.fail(f"{name} in the report"))
    assert code == 1 and report["divergences"][0]["b"] == "NaN"


# -- headers, v1 against v2 --------------------------------------------------------------------


def v1(records: list[Record]) -> list[Record]:
    """A v1 trace of the same run: no start records, no id, heading or motion (nor a header)."""
    return [
        {key: value for key, value in record.items() if key not in ("id", "heading", "motion")}
        for record in records
        if record["quantum"] != 0.0
    ]


def test_a_v1_trace_of_the_same_run_compares_clean(
    trace: Path, records: list[Record], tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    old = write(tmp_path / "v1.jsonl", v1(records))
    for a, b in ((trace, old), (old, trace)):
        report = compare_traces(a, b, all_bodies=True)
        assert report.identical and report.records_compared == 105 and report.warnings == []
        assert invoke(["diff", str(a), str(b)], capsys) == (0, "identical within 1e-06\n", "")


def test_a_v1_trace_still_diverges_where_it_differs(
    records: list[Record], trace: Path, tmp_path: Path
) -> None:
    changed = v1(records)
    changed[20]["cell"] = "0xA9B40001"
    found = diff_traces(write(tmp_path / "v1.jsonl", changed), trace)
    assert isinstance(found, Divergence)
    assert (found.field, found.line, found.line_b) == ("cell", 21, 29)  # the header, 7 start records
    assert "first divergence at line 21 (b: line 29), " in found.describe()


def test_headers_of_other_scenarios_are_a_warning_not_a_divergence(
    trace: Path, header: Record, records: list[Record], tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    other = dict(header, engine="fast", acphys="9.9", scenario={"name": "elsewhere", "sha256": "0" * 64})
    b = write(tmp_path / "b.jsonl", records, other)
    assert compare_traces(trace, b).identical
    code, out, err = invoke(["diff", str(trace), str(b), "--json", "-"], capsys)
    assert code == 0
    assert err.startswith("acphys: warning: the traces are of different scenarios: a ran 'default'")
    assert len(err.splitlines()) == 1
    assert json.loads(out)["warnings"] == [err.removeprefix("acphys: warning: ").rstrip("\n")]
    same = write(tmp_path / "c.jsonl", records, dict(header, engine="fast", acphys="9.9"))
    assert invoke(["diff", str(trace), str(same)], capsys) == (0, "identical within 1e-06\n", "")
