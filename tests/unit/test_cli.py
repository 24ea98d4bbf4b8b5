"""The ``acphys`` command (README "The command line"): run, check and diff, and their errors.

``acphys.cli.main(argv)`` is called in-process and returns the exit code (argument
errors included), and the real command is run as a subprocess too. Nothing in acphys
is mocked.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from acphys.cli import main

SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
BAD = SCENARIOS / "bad"
VALID = SCENARIOS / "valid_minimal.toml"
BAD_FILES = sorted(BAD.glob("*.toml"))
DEFAULT_BODIES = ("skydiver", "ball", "spinner", "drifter", "sitter", "walker", "runner")


def invoke(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    """Run ``main(argv)``: its exit code, then stdout and stderr."""
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def one_line(text: str) -> str:
    """Rich wraps long stdout lines at the console width; undo that for matching."""
    return " ".join(text.split())


def assert_one_error_line(code: int, out: str, err: str) -> str:
    assert code == 2, (code, out, err)
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("acphys: error: "), err
    assert "Traceback" not in out + err
    return lines[0]


def bad_expectation(path: Path) -> tuple[str | None, str]:
    header = dict(re.findall(r"^# (key|problem): (.+)$", path.read_text(encoding="utf-8"), re.MULTILINE))
    return header.get("key"), header["problem"]


@pytest.fixture(scope="module")
def trace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A 0.5-s trace of the default scenario, written by the command."""
    path = tmp_path_factory.mktemp("cli") / "default.jsonl"
    assert main(["run", "--trace", str(path), "--until", "0.5"]) == 0
    return path


def planted(trace: Path, tmp_path: Path, index: int = 37, delta: float = 1e-3) -> Path:
    records = [json.loads(line) for line in trace.read_text(encoding="utf-8").splitlines()]
    records[index]["origin"][2] += delta
    path = tmp_path / "planted.jsonl"
    path.write_text("".join(json.dumps(record) + "\n" for record in records), encoding="utf-8")
    return path


# -- run --------------------------------------------------------------------------------------


def test_run_without_a_scenario_summarises_the_default(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(["run"], capsys)
    assert code == 0, err
    assert err == ""
    assert "default: 8 s simulated, 7 bodies" in one_line(out)
    for name in DEFAULT_BODIES:
        assert name in out


def test_run_writes_the_trace(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "out.jsonl"
    code, out, err = invoke(["run", "--trace", str(path), "--until", "0.5"], capsys)
    assert code == 0, err
    assert "0.5 s simulated" in one_line(out)
    assert "trace:" in out
    header, *records = [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]
    assert header["schema"] == "acphys.trace/2" and header["scenario"]["name"] == "default"
    assert len(records) == 7 + 105  # where the 7 bodies start, then 15 steps each at 30 Hz
    assert {record["body"] for record in records} == set(DEFAULT_BODIES)


def test_run_a_scenario_file_and_a_built_in_name(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(["run", str(VALID)], capsys)
    assert code == 0, err
    assert "minimal: 2 s simulated, 2 bodies" in one_line(out)
    assert "walker" in out and "rock" in out
    code, out, err = invoke(["run", "default", "--until", "0.1"], capsys)
    assert code == 0, err
    assert "default: 0.1 s simulated, 7 bodies" in one_line(out)


@pytest.mark.parametrize("until", ["-1", "nan", "inf"])
def test_run_refuses_an_impossible_until(until: str, capsys: pytest.CaptureFixture[str]) -> None:
    line = assert_one_error_line(*invoke(["run", f"--until={until}"], capsys))
    assert "--until" in line


def test_run_a_missing_scenario_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    missing = tmp_path / "missing.toml"
    line = assert_one_error_line(*invoke(["run", str(missing)], capsys))
    assert str(missing) in line


def test_run_with_an_unwritable_trace_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    target = tmp_path / "no-such-folder" / "out.jsonl"
    line = assert_one_error_line(*invoke(["run", "--trace", str(target), "--until", "0.1"], capsys))
    assert str(target) in line


# -- check ------------------------------------------------------------------------------------


@pytest.mark.parametrize("path", BAD_FILES, ids=[path.stem for path in BAD_FILES])
def test_check_reports_a_malformed_scenario_in_one_line(
    path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = invoke(["check", str(path)], capsys)
    line = assert_one_error_line(code, out, err)
    assert out == ""
    key, problem = bad_expectation(path)
    assert line.startswith(f"acphys: error: {path}: ")
    if key is not None:
        assert f"{path}: {key}: " in line
    assert problem in line


def test_check_the_default_scenario_by_name(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(["check", "default"], capsys)
    assert code == 0, err
    assert err == ""
    assert one_line(out) == "ok: default: 7 bodies, 6 events, 8 s at 60 Hz"


def test_check_a_valid_file(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(["check", str(VALID)], capsys)
    assert code == 0, err
    assert one_line(out) == "ok: minimal: 2 bodies, 3 events, 2 s at 60 Hz"


def test_check_a_missing_file_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    missing = tmp_path / "missing.toml"
    line = assert_one_error_line(*invoke(["check", str(missing)], capsys))
    assert f"{missing}: no such file" in line


def test_check_needs_a_scenario(capsys: pytest.CaptureFixture[str]) -> None:
    assert_one_error_line(*invoke(["check"], capsys))


# -- diff -------------------------------------------------------------------------------------


def test_diff_of_identical_traces_exits_0(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    copy = tmp_path / "copy.jsonl"
    shutil.copyfile(trace, copy)
    code, out, err = invoke(["diff", str(trace), str(copy)], capsys)
    assert code == 0, err
    assert err == ""
    assert "identical" in out


def test_diff_of_a_planted_divergence_exits_1_and_prints_it(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    changed = planted(trace, tmp_path, index=37)
    code, out, err = invoke(["diff", str(trace), str(changed)], capsys)
    assert code == 1, err
    assert err == ""
    text = one_line(out)
    assert "first divergence at line 38" in text
    assert "origin[2]" in text
    assert "differs by 0.001" in text


def test_diff_within_tolerance_exits_0(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    changed = planted(trace, tmp_path)
    code, out, err = invoke(["diff", str(trace), str(changed), "--tol", "1e-2"], capsys)
    assert code == 0, err
    assert "identical within 0.01" in out


def test_diff_of_a_truncated_trace_exits_1(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    short = tmp_path / "short.jsonl"
    short.write_text(
        "".join(trace.read_text(encoding="utf-8").splitlines(keepends=True)[:40]), encoding="utf-8"
    )
    code, out, _ = invoke(["diff", str(trace), str(short)], capsys)
    assert code == 1
    assert "line 41" in one_line(out) and "<end of trace>" in out


def test_diff_of_a_missing_file_is_one_line(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    missing = tmp_path / "missing.jsonl"
    line = assert_one_error_line(*invoke(["diff", str(trace), str(missing)], capsys))
    assert str(missing) in line


def test_diff_of_a_malformed_trace_names_file_and_line(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "bad.jsonl"
    first_two = trace.read_text(encoding="utf-8").splitlines(keepends=True)[:2]
    bad.write_text("".join(first_two) + "{oops\n", encoding="utf-8")
    line = assert_one_error_line(*invoke(["diff", str(trace), str(bad)], capsys))
    assert f"{bad}:3: not JSON" in line


@pytest.mark.parametrize("tol", ["-1", "nan"])
def test_diff_refuses_a_negative_tolerance(trace: Path, tol: str, capsys: pytest.CaptureFixture[str]) -> None:
    line = assert_one_error_line(*invoke(["diff", str(trace), str(trace), f"--tol={tol}"], capsys))
    assert "--tol" in line


# -- bad arguments --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv",
    [
        ["frobnicate"],
        [],
        ["run", "--until", "abc"],
        ["run", "--speed", "2"],
        ["diff", "only-one.jsonl"],
        ["diff", "a.jsonl", "b.jsonl", "--tol", "tiny"],
    ],
    ids=["unknown-command", "no-command", "until-abc", "unknown-option", "diff-one-file", "tol-word"],
)
def test_bad_arguments_exit_2_with_one_line(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(argv, capsys)
    assert_one_error_line(code, out, err)
    assert out == ""


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = invoke(["--version"], capsys)
    assert code == 0
    assert out.strip() == "acphys 0.1.0"


# -- the real command -------------------------------------------------------------------------


def _command(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "acphys.cli", *args], capture_output=True, text=True, cwd=cwd, timeout=120
    )


def test_the_module_entry_point_checks_and_fails_in_one_line(tmp_path: Path) -> None:
    bad = BAD / "velocity_nan.toml"
    done = _command("check", str(bad), cwd=tmp_path)
    assert done.returncode == 2
    assert done.stdout == ""
    assert done.stderr.splitlines() == [
        f"acphys: error: {bad}: body[0].velocity[1]: expected a finite number, got nan (line 7, body 'a')"
    ]

    done = _command("run", "--until", "abc", cwd=tmp_path)
    assert done.returncode == 2
    assert len(done.stderr.splitlines()) == 1 and "Traceback" not in done.stderr


def test_the_module_entry_point_runs_and_diffs(tmp_path: Path) -> None:
    done = _command("run", "--trace", "a.jsonl", "--until", "0.5", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert len((tmp_path / "a.jsonl").read_text(encoding="utf-8").splitlines()) == 1 + 7 + 105
    shutil.copyfile(tmp_path / "a.jsonl", tmp_path / "b.jsonl")
    done = _command("diff", "a.jsonl", "b.jsonl", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    planted(tmp_path / "a.jsonl", tmp_path, index=3, delta=0.5)
    done = _command("diff", "a.jsonl", "planted.jsonl", cwd=tmp_path)
    assert done.returncode == 1
    assert "line 4" in one_line(done.stdout) and "origin[2]" in done.stdout


def test_the_installed_console_script(tmp_path: Path) -> None:
    script = shutil.which("acphys", path=str(Path(sys.executable).parent))
    if script is None:
        pytest.skip("the acphys console script is not installed next to this interpreter")
    done = subprocess.run(
        [script, "check", "default"], capture_output=True, text=True, cwd=tmp_path, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("ok: default: 7 bodies")
    done = subprocess.run(
        [script, "check", str(BAD / "no_body.toml")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert done.returncode == 2
    assert done.stderr.splitlines() == [
        f"acphys: error: {BAD / 'no_body.toml'}: body: missing: a scenario needs at least one [[body]]"
    ]


def test_the_run_summary_lists_the_first_bodies_and_says_so(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A summary of 10,000 rows took rich longer than the run: past ``SUMMARY_ROWS`` it stops."""
    monkeypatch.setattr("acphys.cli.SUMMARY_ROWS", 3)
    code, out, err = invoke(["run", "--until", "0.1"], capsys)  # the default's 7 bodies
    assert (code, err) == (0, "")
    assert "7 bodies" in out and "the first 3 bodies; --trace records them all" in out
    rows = [line for line in out.splitlines() if re.match(r"│ \S.* │ 0x[0-9A-F]{8} │", line)]
    assert len(rows) == 3
