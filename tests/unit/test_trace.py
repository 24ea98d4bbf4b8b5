"""Traces (README contract 2): what ``Simulation.run(trace=...)`` writes, and ``diff_traces``.

Every test runs the real simulation; no part of acphys is mocked.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import re
import shutil
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

import acphys
import acphys.scenario
from acphys.cli import main
from acphys.flags import TransientState
from acphys.trace import (
    MOTION_KEYS,
    RECORD_KEYS,
    SCHEMA,
    TraceError,
    read_header,
    read_trace,
)
from acphys.trace_diff import Divergence, diff_traces
from support import UNIT_TOL, step_records

#: The bodies of the built-in default scenario, in file order.
DEFAULT_BODIES = ("skydiver", "ball", "spinner", "drifter", "sitter", "walker", "runner")
#: A 60-Hz driver runs the bodies at 30 Hz: 0.5 s is 15 physics steps per body.
STEPS_IN_HALF_SECOND = 15
TRANSIENT_NAMES = {member.name.lower() for member in TransientState}
CELL_FORMAT = re.compile(r"^0x[0-9A-F]{8}$")


def _refuse_constant(name: str) -> Any:
    raise AssertionError(f"the trace holds the non-standard JSON constant {name}")


def read_records(path: Path) -> list[dict[str, Any]]:
    """Every line of a trace as strict JSON (NaN and Infinity are refused)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    return [json.loads(line, parse_constant=_refuse_constant) for line in lines]


def write_records(path: Path, records: list[dict[str, Any]]) -> Path:
    path.write_text("".join(json.dumps(record) + "\n" for record in records), encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def default_trace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("trace") / "default.jsonl"
    sim = acphys.load_scenario()
    sim.run(until=0.5, trace=path)
    return path


@pytest.fixture(scope="module")
def steps_trace(default_trace: Path) -> Path:
    """The step records of ``default_trace``, byte for byte, without its header and start records."""
    lines = default_trace.read_text(encoding="utf-8").splitlines(keepends=True)
    path = default_trace.with_name("steps.jsonl")
    path.write_text("".join(lines[1 + len(DEFAULT_BODIES) :]), encoding="utf-8")
    return path


@pytest.fixture
def records(steps_trace: Path) -> list[dict[str, Any]]:
    """The step records of the default scenario's first half second."""
    return read_records(steps_trace)


def by_body(records: list[dict[str, Any]]) -> dict[str, list[dict[str, Any]]]:
    grouped: dict[str, list[dict[str, Any]]] = {}
    for record in records:
        grouped.setdefault(record["body"], []).append(record)
    return grouped


# -- what run(trace=...) writes ---------------------------------------------------------------


def test_one_record_per_body_per_physics_step(records: list[dict[str, Any]]) -> None:
    assert len(records) == len(DEFAULT_BODIES) * STEPS_IN_HALF_SECOND == 105
    assert Counter(record["body"] for record in records) == dict.fromkeys(
        DEFAULT_BODIES, STEPS_IN_HALF_SECOND
    )


def test_each_step_writes_the_bodies_in_scenario_order(records: list[dict[str, Any]]) -> None:
    count = len(DEFAULT_BODIES)
    for step in range(STEPS_IN_HALF_SECOND):
        group = records[step * count : (step + 1) * count]
        assert tuple(record["body"] for record in group) == DEFAULT_BODIES
        assert len({record["t"] for record in group}) == 1, f"step {step} mixes times"


def test_every_record_has_exactly_the_record_keys_in_order(records: list[dict[str, Any]]) -> None:
    for number, record in enumerate(records, start=1):
        assert list(record) == list(RECORD_KEYS), f"line {number}"


def test_every_line_is_strict_json_with_finite_numbers(default_trace: Path) -> None:
    text = default_trace.read_text(encoding="utf-8")
    assert text.endswith("\n")
    header, *lines = text.splitlines()
    assert json.loads(header, parse_constant=_refuse_constant)["schema"] == SCHEMA
    for number, line in enumerate(lines, start=2):
        record = json.loads(line, parse_constant=_refuse_constant)
        assert isinstance(record, dict), f"line {number}"
        numbers = [record["t"], record["quantum"]]
        for key in ("origin", "orientation", "velocity", "cached_velocity", "omega"):
            numbers += record[key]
        assert all(isinstance(x, float | int) and math.isfinite(x) for x in numbers), f"line {number}"


def test_time_increases_per_body_in_steps_of_one_thirtieth(records: list[dict[str, Any]]) -> None:
    for body, body_records in by_body(records).items():
        times = [record["t"] for record in body_records]
        assert all(a < b for a, b in itertools.pairwise(times)), body
        for step, record in enumerate(body_records, start=1):
            assert record["quantum"] == pytest.approx(1.0 / 30.0, abs=1e-6), (body, step)
            assert record["t"] == pytest.approx(step / 30.0, abs=1e-6), (body, step)
        assert times[-1] == pytest.approx(0.5, abs=1e-6)


def test_cell_is_formatted_as_eight_hex_digits(records: list[dict[str, Any]]) -> None:
    for record in records:
        assert CELL_FORMAT.match(record["cell"]), record["cell"]
    first = by_body(records)
    # The skydiver falls straight down at (96, 96), the corner of cells 0x25, 0x1D, 0x1C and 0x24
    # of 0xA9B4, added in that order (the sphere's cell, then its boundary neighbours). All four
    # hold the corner (triangle edges count), and find_cell_list keeps the last that does as the
    # check cell (acclient.c:347049), which the sweep moves the body into: 0x24.
    assert {record["cell"] for record in first["skydiver"]} == {"0xA9B40024"}


def test_vectors_have_three_components_and_orientation_four(records: list[dict[str, Any]]) -> None:
    for record in records:
        for key in ("origin", "velocity", "cached_velocity", "omega"):
            assert isinstance(record[key], list) and len(record[key]) == 3, key
        orientation = record["orientation"]
        assert isinstance(orientation, list) and len(orientation) == 4
        # a float32 quaternion, normalised to float32 precision
        assert math.fsum(q * q for q in orientation) == pytest.approx(1.0, abs=UNIT_TOL)


def test_transient_is_a_list_of_lower_case_flag_names(records: list[dict[str, Any]]) -> None:
    for record in records:
        transient = record["transient"]
        assert isinstance(transient, list)
        for name in transient:
            assert isinstance(name, str) and name == name.lower() and name in TRANSIENT_NAMES, name
    # The falling skydiver is active and touches nothing; the sitter sits on walkable ground.
    grouped = by_body(records)
    assert grouped["skydiver"][0]["transient"] == ["active"]
    assert {"contact", "on_walkable"} <= set(grouped["sitter"][0]["transient"])


def test_contact_normal_is_null_unless_in_contact(records: list[dict[str, Any]]) -> None:
    in_contact = 0
    for record in records:
        if "contact" in record["transient"]:
            in_contact += 1
            assert record["contact_normal"] == pytest.approx([0.0, 0.0, 1.0])
        else:
            assert record["contact_normal"] is None, record["body"]
    # The sitter, the walker and the runner, every step: enter_world places them through
    # SetPosition onto the ground, which gives them the contact plane (acclient.c:323369); the
    # spinner is placed 2 m up and the others fly.
    assert in_contact == 3 * STEPS_IN_HALF_SECOND


def test_events_is_a_list_of_names(records: list[dict[str, Any]]) -> None:
    for record in records:
        assert isinstance(record["events"], list)
        assert all(isinstance(name, str) for name in record["events"])


def test_omega_is_written_in_radians_per_second(records: list[dict[str, Any]]) -> None:
    # The default spinner turns at 90 deg/s about z.
    for record in by_body(records)["spinner"]:
        assert record["omega"] == pytest.approx([0.0, 0.0, math.pi / 2])


def test_last_record_of_each_body_is_its_state_after_the_run(tmp_path: Path) -> None:
    sim = acphys.load_scenario()
    sim.run(until=0.5, trace=tmp_path / "t.jsonl")
    last = {record["body"]: record for _, record in read_trace(tmp_path / "t.jsonl")}
    assert set(last) == set(DEFAULT_BODIES)
    for body in sim.bodies:
        record = last[body.name]
        frame = body.position.frame
        assert record["origin"] == list(frame.origin)
        assert record["orientation"] == [frame.qw, frame.qx, frame.qy, frame.qz]
        assert record["velocity"] == list(body.velocity)
        assert record["omega"] == list(body.omega)
        assert record["cell"] == f"0x{body.position.objcell_id:08X}"


def test_tracing_does_not_change_the_physics(tmp_path: Path) -> None:
    traced = acphys.load_scenario()
    traced.run(until=0.5, trace=tmp_path / "t.jsonl")
    plain = acphys.load_scenario()
    plain.run(until=0.5)
    for a, b in zip(traced.bodies, plain.bodies, strict=True):
        assert list(a.position.frame.origin) == list(b.position.frame.origin), a.name
        assert list(a.velocity) == list(b.velocity), a.name
        assert a.transient_state == b.transient_state, a.name
        assert a.observer is None, "the trace writer stays attached after run()"


def test_a_long_driver_tick_writes_one_record_per_quantum(tmp_path: Path) -> None:
    # A 2-Hz driver: each 0.5-s tick runs as 0.2 + 0.2 + 0.1 (MAX_QUANTUM is 0.2 s).
    text = """
[scenario]
driver_hz = 2.0

[[body]]
name = "a"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]

[[body]]
name = "b"
landblock = "0xA9B4"
origin = [100.0, 96.0, 50.0]
"""
    sim = acphys.parse_scenario(text, source="two.toml")
    sim.run(until=1.0, trace=tmp_path / "t.jsonl")
    grouped = by_body(step_records(tmp_path / "t.jsonl"))
    assert set(grouped) == {"a", "b"}
    for body_records in grouped.values():
        quanta = [record["quantum"] for record in body_records]
        assert quanta == pytest.approx([0.2, 0.2, 0.1, 0.2, 0.2, 0.1])
        assert [record["t"] for record in body_records] == pytest.approx([0.2, 0.4, 0.5, 0.7, 0.9, 1.0])


# -- schema v2: the header, where the run starts, who and how it moves ----------------------------


def test_the_first_line_is_a_header_naming_schema_version_engine_and_scenario(default_trace: Path) -> None:
    header = json.loads(default_trace.read_text(encoding="utf-8").splitlines()[0])
    text = acphys.scenario.builtin_scenario_text("default").encode("utf-8")
    assert header == {
        "schema": "acphys.trace/2",
        "acphys": acphys.__version__,
        "engine": "reference",
        "driver_hz": 60.0,
        "scenario": {"name": "default", "sha256": hashlib.sha256(text).hexdigest()},
    }
    assert read_header(default_trace) == header
    assert next(line for line, _ in read_trace(default_trace)) == 2  # the reader skips the header


def test_each_body_has_a_record_where_the_run_starts(default_trace: Path) -> None:
    start = [record for _, record in itertools.islice(read_trace(default_trace), len(DEFAULT_BODIES))]
    # In the order the steps run them (the object table's: ids from 0x80000001 in file order).
    assert [record["body"] for record in start] == list(DEFAULT_BODIES)
    assert [record["id"] for record in start] == [f"0x{0x80000001 + k:08X}" for k in range(7)]
    for record in start:
        assert (record["t"], record["quantum"], record["events"]) == (0.0, 0.0, []), record["body"]
        assert list(record) == list(RECORD_KEYS)
    assert start[0]["origin"] == [96.0, 96.0, 400.0]  # the skydiver, where the scenario puts it
    assert start[0]["velocity"] == [0.0, 0.0, 0.0]


def test_heading_is_the_compass_heading_of_the_orientation(records: list[dict[str, Any]]) -> None:
    grouped = by_body(records)
    # The drifter faces east (heading = 90): the float32 quaternion (cos 45°, 0, 0, -sin 45°)
    # gives Frame::get_heading (acclient.c:357409) 90 to within its rounding.
    assert all(r["heading"] == pytest.approx(90.0, abs=1e-5) for r in grouped["drifter"])
    # The spinner turns 90°/s anticlockwise about z: 3° a step, the compass heading falling from
    # 360: 357 after the first step, 315 after fifteen.
    spinner = [r["heading"] for r in grouped["spinner"]]
    assert spinner[0] == pytest.approx(357.0, abs=1e-5)
    assert spinner[14] == pytest.approx(315.0, abs=1e-4)


def test_motion_is_the_interpreted_state_and_the_animation_playing(records: list[dict[str, Any]]) -> None:
    grouped = by_body(records)
    assert all(r["motion"] is None for name in ("ball", "spinner", "drifter") for r in grouped[name])
    walker, runner = grouped["walker"], grouped["runner"]
    for record in [*walker, *runner]:
        assert list(record["motion"]) == list(MOTION_KEYS)
    # Standing until the 0.5-s event: Ready, the motion table's first cycle.
    assert walker[0]["motion"]["forward"] == "Ready" and walker[0]["motion"]["hold_key"] == "none"
    assert walker[0]["motion"]["animation"] == "motion_table.humanoid.cycle[0]"
    # The event's tick: WalkForward; with the run key held the interpreter makes it RunForward
    # (CMotionInterp::adjust_motion), and each starts on its link animation.
    assert walker[-1]["motion"]["forward"] == "WalkForward"
    assert (runner[-1]["motion"]["forward"], runner[-1]["motion"]["hold_key"]) == ("RunForward", "run")
    assert walker[-1]["motion"]["animation"] == "motion_table.humanoid.link[0]"
    assert runner[-1]["motion"]["animation"] == "motion_table.humanoid.link[2]"
    assert walker[-1]["motion"]["turn"] is None and walker[-1]["motion"]["sidestep"] is None


def test_a_v1_trace_without_header_or_start_records_still_reads(
    records: list[dict[str, Any]], tmp_path: Path
) -> None:
    old = [{k: v for k, v in r.items() if k not in ("id", "heading", "motion")} for r in records]
    path = write_records(tmp_path / "v1.jsonl", old)
    assert read_header(path) is None
    assert [record for _, record in read_trace(path)] == old


def test_a_v1_trace_plots_and_views(
    records: list[dict[str, Any]], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    old = [{k: v for k, v in r.items() if k not in ("id", "heading", "motion")} for r in records]
    path = write_records(tmp_path / "v1.jsonl", old)
    assert main(["view", str(path), "--bodies", "drifter"]) == 0
    assert "drifter" in capsys.readouterr().out
    assert main(["plot", str(path), "-o", str(tmp_path / "v1.png")]) == 0
    assert (tmp_path / "v1.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_header_of_an_unknown_schema_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "future.jsonl"
    path.write_text('{"schema": "acphys.trace/9"}\n', encoding="utf-8")
    with pytest.raises(TraceError, match=r"future.jsonl:1: unknown trace schema 'acphys.trace/9'"):
        list(read_trace(path))


# -- diff_traces --------------------------------------------------------------------------------


def test_identical_traces_do_not_diverge(steps_trace: Path, tmp_path: Path) -> None:
    copy = tmp_path / "copy.jsonl"
    shutil.copyfile(steps_trace, copy)
    assert diff_traces(steps_trace, steps_trace) is None
    assert diff_traces(steps_trace, copy, tol=0.0) is None


def test_two_runs_of_the_default_scenario_are_identical(steps_trace: Path, tmp_path: Path) -> None:
    again = tmp_path / "again.jsonl"
    acphys.load_scenario().run(until=0.5, trace=again)
    assert diff_traces(steps_trace, again, tol=0.0) is None


def _planted(
    records: list[dict[str, Any]], index: int, key: str, component: int, delta: float
) -> list[dict[str, Any]]:
    changed = json.loads(json.dumps(records))
    changed[index][key][component] += delta
    return changed


@pytest.mark.parametrize("index", [0, 37, 74])
def test_a_planted_origin_divergence_is_found_at_its_line_and_field(
    records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path, index: int
) -> None:
    changed = write_records(tmp_path / "b.jsonl", _planted(records, index, "origin", 2, 1e-3))
    found = diff_traces(steps_trace, changed, tol=1e-6)
    assert isinstance(found, Divergence)
    assert found.line == index + 1
    assert found.field == "origin[2]"
    assert found.body == records[index]["body"]
    assert found.t == records[index]["t"]
    assert found.a == records[index]["origin"][2]
    assert found.b == pytest.approx(records[index]["origin"][2] + 1e-3)
    assert found.difference == pytest.approx(1e-3, rel=1e-6)
    description = found.describe()
    assert f"line {index + 1}" in description and "origin[2]" in description
    assert diff_traces(steps_trace, changed, tol=1e-2) is None


def test_the_first_of_two_divergences_is_reported(
    records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path
) -> None:
    changed = _planted(records, 50, "origin", 0, 1.0)
    changed = _planted(changed, 20, "velocity", 1, 1.0)
    found = diff_traces(steps_trace, write_records(tmp_path / "b.jsonl", changed))
    assert found is not None
    assert (found.line, found.field) == (21, "velocity[1]")


def test_within_a_record_fields_are_compared_in_record_key_order(
    records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path
) -> None:
    changed = _planted(records, 10, "omega", 0, 1.0)
    changed = _planted(changed, 10, "origin", 1, 1.0)
    found = diff_traces(steps_trace, write_records(tmp_path / "b.jsonl", changed))
    assert found is not None
    assert (found.line, found.field) == (11, "origin[1]")


def test_the_tolerance_is_exclusive(records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path) -> None:
    # 0.5 is exact in binary, and so is the difference 400.0 - 399.5.
    index = 0  # the skydiver at z = 400 on its first step
    assert records[index]["origin"][2] == 400.0
    changed = write_records(tmp_path / "b.jsonl", _planted(records, index, "origin", 2, -0.5))
    assert diff_traces(steps_trace, changed, tol=0.5) is None
    found = diff_traces(steps_trace, changed, tol=0.25)
    assert found is not None and found.field == "origin[2]"


def test_a_changed_cell_is_reported(records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path) -> None:
    changed = json.loads(json.dumps(records))
    changed[12]["cell"] = "0xA9B40001"
    assert records[12]["cell"] != "0xA9B40001"
    found = diff_traces(steps_trace, write_records(tmp_path / "b.jsonl", changed), tol=1.0)
    assert found is not None
    assert (found.line, found.field) == (13, "cell")
    assert (found.a, found.b) == (records[12]["cell"], "0xA9B40001")
    assert found.difference is None


def test_a_boolean_never_equals_a_number(
    records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path
) -> None:
    # JSON true and 1 are different values, whatever the tolerance.
    first = dict(records[0], quantum=1)
    second = dict(records[0], quantum=True)
    a = write_records(tmp_path / "a.jsonl", [first])
    b = write_records(tmp_path / "b.jsonl", [second])
    found = diff_traces(a, b, tol=1.0)
    assert found is not None and (found.field, found.a, found.b) == ("quantum", 1, True)


def test_a_changed_transient_list_is_reported(
    records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path
) -> None:
    changed = json.loads(json.dumps(records))
    changed[4]["transient"] = [*changed[4]["transient"], "sliding"]
    found = diff_traces(steps_trace, write_records(tmp_path / "b.jsonl", changed), tol=1.0)
    assert found is not None
    assert (found.line, found.field) == (5, "transient")


def test_a_truncated_trace_diverges_at_its_first_missing_record(
    records: list[dict[str, Any]], steps_trace: Path, tmp_path: Path
) -> None:
    short = write_records(tmp_path / "short.jsonl", records[:40])
    found = diff_traces(steps_trace, short)
    assert found is not None
    assert found.line == 41
    assert found.field == "record"
    assert found.body == records[40]["body"]
    assert found.t == records[40]["t"]
    assert found.b == "<end of trace>"

    reverse = diff_traces(short, steps_trace)
    assert reverse is not None
    assert (reverse.line, reverse.field, reverse.a) == (41, "record", "<end of trace>")


def test_an_empty_trace_diverges_at_line_one(steps_trace: Path, tmp_path: Path) -> None:
    empty = tmp_path / "empty.jsonl"
    empty.write_text("", encoding="utf-8")
    found = diff_traces(empty, steps_trace)
    assert found is not None and (found.line, found.field) == (1, "record")
    assert diff_traces(empty, empty) is None


@pytest.mark.parametrize(
    ("bad_line", "problem"),
    [
        ("{not json", "not JSON"),
        ("[1, 2, 3]", "JSON object"),
        ('"a string"', "JSON object"),
        ('{"body": "skydiver", "quantum": 0.03}', "no t"),
    ],
    ids=["not-json", "array", "string", "missing-t"],
)
@pytest.mark.parametrize("side", ["a", "b"])
def test_a_malformed_trace_raises_trace_error_naming_file_and_line(
    records: list[dict[str, Any]],
    steps_trace: Path,
    tmp_path: Path,
    bad_line: str,
    problem: str,
    side: str,
) -> None:
    bad = tmp_path / "bad.jsonl"
    good_lines = "".join(json.dumps(record) + "\n" for record in records[:3])
    bad.write_text(good_lines + bad_line + "\n", encoding="utf-8")
    paths = (bad, steps_trace) if side == "a" else (steps_trace, bad)
    with pytest.raises(TraceError) as caught:
        diff_traces(*paths)
    message = str(caught.value)
    assert f"{bad}:4:" in message
    assert problem in message
    assert "\n" not in message


def test_read_trace_yields_line_numbers_and_skips_blank_lines(
    records: list[dict[str, Any]], tmp_path: Path
) -> None:
    path = tmp_path / "gaps.jsonl"
    path.write_text(f"{json.dumps(records[0])}\n\n{json.dumps(records[1])}\n", encoding="utf-8")
    assert [(line, record["body"]) for line, record in read_trace(path)] == [
        (1, records[0]["body"]),
        (3, records[1]["body"]),
    ]


def test_a_missing_trace_file_raises_trace_error_naming_it(steps_trace: Path, tmp_path: Path) -> None:
    missing = tmp_path / "nowhere.jsonl"
    with pytest.raises(TraceError, match=re.escape(str(missing))):
        diff_traces(steps_trace, missing)


@pytest.mark.parametrize("tol", [-1e-9, -1.0, math.nan])
def test_a_negative_tolerance_is_a_value_error(steps_trace: Path, tol: float) -> None:
    with pytest.raises(ValueError, match="tolerance") as caught:
        diff_traces(steps_trace, steps_trace, tol=tol)
    assert not isinstance(caught.value, TraceError)


def test_state_bits_combine_as_plain_ints_and_keep_their_names() -> None:
    # The flag classes use int's operators (fast; acphys.flags._use_int_operators): results are plain
    # ints of the right value, and flag_names reads the names through the class.
    from acphys.flags import PhysicsState, TransientState, flag_names

    combined = TransientState.CONTACT | TransientState.ACTIVE
    assert type(combined) is int and combined == 0x81
    assert (combined & ~TransientState.ACTIVE) == TransientState.CONTACT
    assert flag_names(combined, TransientState) == ["contact", "active"]
    assert flag_names(PhysicsState.GRAVITY) == ["gravity"]
    with pytest.raises(TypeError, match="needs the flag class"):
        flag_names(combined)
