"""Damaged traces never crash the trace commands: a record of a real trace with one field made
wrong (another type, NaN, missing, odd lists) or a line cut short makes ``acphys diff``,
``acphys view`` and ``acphys plot`` either work or print one error line and exit 2."""

from __future__ import annotations

import copy
import json
import math
import random
from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.cli import main

WRONG: list[Any] = [
    None,
    True,
    0,
    -1,
    1e300,
    "x",
    "0xZZ",
    "",
    [],
    [1.0],
    ["a", "b", "c"],
    {},
    [None, None, None],
]


@pytest.fixture(scope="module")
def trace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("trace") / "default.jsonl"
    acphys.load_scenario("default").run(until=0.5, trace=path)
    return path


def _damaged(lines: list[str], rng: random.Random) -> list[str]:
    lines = list(lines)
    index = rng.randrange(len(lines))
    if rng.random() < 0.2:
        lines[index] = lines[index][: rng.randrange(len(lines[index]))]
        return lines
    record = json.loads(lines[index])
    key = rng.choice(sorted(record))
    if rng.random() < 0.2:
        del record[key]
    else:
        record[key] = copy.deepcopy(rng.choice([*WRONG, math.nan] if key != "t" else WRONG))
    lines[index] = json.dumps(record)
    return lines


@pytest.mark.parametrize("command", ["diff", "view", "plot"])
def test_a_damaged_trace_works_or_is_a_one_line_error(
    trace: Path, tmp_path: Path, command: str, capsys: pytest.CaptureFixture[str]
) -> None:
    lines = trace.read_text(encoding="utf-8").splitlines()
    rng = random.Random(command)
    for trial in range(60 if command != "plot" else 12):
        damaged = tmp_path / f"damaged-{trial}.jsonl"
        damaged.write_text("\n".join(_damaged(lines, rng)) + "\n", encoding="utf-8")
        if command == "diff":
            args = ["diff", str(trace), str(damaged)]
        elif command == "view":
            args = ["view", str(damaged)]
        else:
            args = ["plot", str(damaged), "-o", str(tmp_path / "p.png")]
        code = main(args)
        err = capsys.readouterr().err
        assert code in (0, 1, 2), f"trial {trial}: exit {code}"
        if code == 2:
            assert err.startswith("acphys: error:") and len(err.strip().splitlines()) == 1, (
                f"trial {trial}: {err}"
            )
