"""``acphys run --engine fast`` writes the reference engine's trace, and says how it ran."""

from __future__ import annotations

from pathlib import Path

import pytest

from acphys.cli import main
from acphys.fast.differential import split_trace


@pytest.mark.parametrize("scenario", ["default", "hills"])
def test_run_with_the_fast_engine_writes_the_same_trace(
    scenario: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    traces = {}
    for engine in ("reference", "fast"):
        traces[engine] = tmp_path / f"{engine}.jsonl"
        args = ["run", scenario, "--until", "3", "--trace", str(traces[engine]), "--engine", engine]
        assert main(args) == 0
    out = capsys.readouterr().out
    header, records = split_trace(traces["reference"])
    assert header is not None and header["scenario"]["name"] == scenario
    assert (header, records) == split_trace(traces["fast"])
    assert b'"engine": "fast"' in traces["fast"].read_bytes().partition(b"\n")[0]
    assert out.count("fast engine:") == 1 and "on the reference path" in out


def test_an_unknown_engine_is_a_one_line_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["run", "--engine", "warp"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("acphys: error:") and "--engine" in err and len(err.splitlines()) == 1
