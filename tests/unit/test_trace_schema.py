"""The published trace schema (``acphys schema trace``, ``acphys/data/trace.schema.json``): every
line of every bundled scenario's trace validates against it, and it names exactly the keys
acphys writes."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import jsonschema
import pytest

import acphys
from acphys.cli import main
from acphys.flags import TransientState
from acphys.scenario import builtin_scenarios
from acphys.trace import MOTION_KEYS, RECORD_KEYS, trace_schema

VALIDATOR = jsonschema.Draft202012Validator(trace_schema())


def lines(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]


def test_the_schema_is_a_valid_draft_2020_12_schema() -> None:
    jsonschema.Draft202012Validator.check_schema(trace_schema())


@pytest.mark.parametrize("name", builtin_scenarios())
def test_every_line_of_a_bundled_scenarios_trace_validates(name: str, tmp_path: Path) -> None:
    path = tmp_path / f"{name}.jsonl"
    acphys.load_scenario(name).run(trace=path)
    header, *records = lines(path)
    assert header["schema"] == "acphys.trace/2" and records
    for number, line in enumerate([header, *records], start=1):
        errors = [error.message for error in VALIDATOR.iter_errors(line)]
        assert not errors, f"{name}.jsonl:{number}: {errors[:3]}"


def test_the_schema_names_the_keys_acphys_writes_and_the_flags() -> None:
    definitions = trace_schema()["$defs"]
    assert definitions["record"]["required"] == list(RECORD_KEYS)
    assert list(definitions["record"]["properties"]) == list(RECORD_KEYS)
    assert definitions["motion"]["required"] == list(MOTION_KEYS)
    flags = definitions["record"]["properties"]["transient"]["items"]["enum"]
    assert flags == [member.name.lower() for member in TransientState]


def test_a_record_that_breaks_the_schema_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "t.jsonl"
    acphys.load_scenario().run(until=0.1, trace=path)
    header, first, *_ = lines(path)
    broken = [
        {key: value for key, value in first.items() if key != "id"},  # a key missing
        dict(first, spin=1.0),  # a key acphys does not write
        dict(first, origin=[1.0, 2.0]),  # a vector of two
        dict(first, transient=["flying"]),  # no such flag
        dict(first, cell="0xa9b40024"),  # lower-case hex
        dict(first, heading=360.0),  # a heading is below 360
        dict(header, schema="acphys.trace/1"),
    ]
    for line in broken:
        assert not VALIDATOR.is_valid(line), line


def test_acphys_schema_trace_prints_the_shipped_schema(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["schema", "trace"]) == 0
    assert json.loads(capsys.readouterr().out) == trace_schema()
