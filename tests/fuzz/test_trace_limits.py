"""The trace readers' limits (issue 13): ``acphys view``, ``plot`` and ``diff`` given a hostile trace
(not UTF-8, a 5,000-digit number, 100,000-deep nesting, a 50 MB line, a FIFO, ``/dev/zero``,
origins of ±1e308, infinity or NaN) print one ``acphys: error:`` line naming the file, the line and
the limit, and exit 2; names that matplotlib would read as maths are drawn as written; ``diff`` takes
NaN as equal to NaN; and a long trace is read in bounded memory, each command within 30 s and 1 GiB.

Every trace is generated here in ``tmp_path``; the command line runs as a subprocess, timed and
measured with ``os.wait4``.
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from acphys.plot import MAX_MAGNITUDE, PathCollector, Points, make_figure, read_paths
from acphys.trace import MAX_DEPTH, MAX_INT_DIGITS, MAX_LINE_BYTES
from acphys.trace_diff import _first_difference, _same

#: The memory a command may use, and the seconds it may take: the issue's bounds.
MEMORY_LIMIT = 1 << 30
TIME_LIMIT = 30.0
#: Commands that read a trace, each with ``{trace}`` and ``{png}`` to fill in.
COMMANDS = {
    "view": ["view", "{trace}"],
    "plot": ["plot", "{trace}", "-o", "{png}"],
    "diff": ["diff", "{trace}", "{trace}"],
}
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def record(t: float = 0.1, body: str = "ball", origin: Any = (10.0, 20.0, 30.0), **more: Any) -> dict:
    """A trace record as acphys writes it, with ``more`` keys set."""
    values = {
        "t": t,
        "body": body,
        "quantum": 0.03333333507180214,
        "cell": "0xA9B4000A",
        "origin": list(origin),
        "orientation": [1.0, 0.0, 0.0, 0.0],
        "velocity": [6.0, 0.0, 8.5],
        "cached_velocity": [5.9, 0.0, 8.4],
        "omega": [0.0, 0.0, 0.0],
        "transient": ["active"],
        "contact_normal": None,
        "events": [],
    }
    values.update(more)
    return values


def write_trace(path: Path, *records: dict | str) -> Path:
    """``records`` one a line (a string is written as it is)."""
    lines = (item if isinstance(item, str) else json.dumps(item) for item in records)
    path.write_text("".join(f"{line}\n" for line in lines), encoding="utf-8")
    return path


@dataclass
class Run:
    code: int
    out: str
    err: str
    seconds: float
    #: The peak resident memory, in bytes.
    memory: int


#: Starts the command it is given and writes the command's peak memory (``ru_maxrss``, KiB) to
#: the file in ``ACPHYS_PEAK_FILE``, exiting with its exit status. Linux counts a process's peak
#: from before its ``exec``, that is the image of whatever forked it: a command forked from this
#: small launcher is measured as itself, not as the test process (which may hold a compiler).
_LAUNCHER = """
import os, sys
pid = os.posix_spawn(sys.argv[1], sys.argv[1:], os.environ)
_, status, usage = os.wait4(pid, 0)
with open(os.environ["ACPHYS_PEAK_FILE"], "w") as peak:
    peak.write(str(usage.ru_maxrss))
sys.exit(os.waitstatus_to_exitcode(status) % 256)
"""


def acphys(*args: str | Path, cwd: Path, code: str | None = None) -> Run:
    """``acphys ARGS`` (or ``python -c CODE ARGS``) as a subprocess, timed and its peak memory
    measured by ``os.wait4`` (through :data:`_LAUNCHER`); one that outlives :data:`TIME_LIMIT` is
    killed and fails the test."""
    command = [sys.executable, "-m", "acphys.cli"] if code is None else [sys.executable, "-c", code]
    out, err, peak = cwd / "stdout.txt", cwd / "stderr.txt", cwd / "peak.txt"
    start = time.monotonic()
    with out.open("wb") as stdout, err.open("wb") as stderr:
        process = subprocess.Popen(
            [sys.executable, "-c", _LAUNCHER, *command, *map(str, args)],
            stdout=stdout,
            stderr=stderr,
            cwd=cwd,
            env={**os.environ, "ACPHYS_PEAK_FILE": str(peak)},
            start_new_session=True,
        )
    while True:
        pid, status, _usage = os.wait4(process.pid, os.WNOHANG)
        seconds = time.monotonic() - start
        if pid:
            break
        if seconds > TIME_LIMIT:
            os.killpg(process.pid, signal.SIGKILL)
            os.wait4(process.pid, 0)
            pytest.fail(f"acphys {args} ran for more than {TIME_LIMIT} s")
        time.sleep(0.01)
    process.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
    memory = int(peak.read_text("utf-8")) * 1024
    run = Run(process.returncode, out.read_text("utf-8"), err.read_text("utf-8"), seconds, memory)
    assert run.memory < MEMORY_LIMIT, f"acphys {args}: {run.memory / 2**20:.0f} MiB"
    assert run.seconds < TIME_LIMIT
    return run


def run_command(command: str, trace: Path | str, tmp_path: Path) -> Run:
    args = [arg.format(trace=trace, png=tmp_path / "out.png") for arg in COMMANDS[command]]
    return acphys(*args, cwd=tmp_path)


def one_error_line(run: Run, expected: str) -> str:
    """The single ``acphys: error:`` line of a run that exited 2: ``expected`` after the prefix."""
    lines = run.err.splitlines()
    assert run.code == 2, run.err
    assert len(lines) == 1, lines
    assert lines[0] == f"acphys: error: {expected}", lines[0]
    return lines[0]


# -- what the reader refuses: every command, one line -------------------------------------------


@pytest.mark.parametrize("command", COMMANDS)
def test_a_trace_that_is_not_utf8(tmp_path: Path, command: str) -> None:
    trace = tmp_path / "latin1.jsonl"
    trace.write_bytes(json.dumps(record()).encode() + b'\n{"t": 0.1, "body": "caf\xe9"}\n')
    expected = f"{trace}:2: not UTF-8: byte 0xe9 at column 24"
    one_error_line(run_command(command, trace, tmp_path), expected)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_5000_digit_integer(tmp_path: Path, command: str) -> None:
    trace = write_trace(tmp_path / "digits.jsonl", record(), f'{{"t": {"9" * 5000}, "body": "ball"}}')
    expected = f"{trace}:2: an integer of 5000 digits; the limit is {MAX_INT_DIGITS}"
    one_error_line(run_command(command, trace, tmp_path), expected)


@pytest.mark.parametrize("command", ["view", "plot"])
def test_a_5000_digit_float_is_infinite_and_not_drawn(tmp_path: Path, command: str) -> None:
    trace = write_trace(tmp_path / "digits.jsonl", f'{{"t": {"9" * 5000}.5, "body": "ball"}}')
    expected = f"{trace}:1: t must be a number, finite and within ±3.4e+38 (the float32 range), got inf"
    one_error_line(run_command(command, trace, tmp_path), expected)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_record_nested_100000_deep(tmp_path: Path, command: str) -> None:
    deep = "[" * 100_000 + "]" * 100_000
    trace = write_trace(tmp_path / "deep.jsonl", record(), f'{{"t": 0.2, "body": "ball", "x": {deep}}}')
    expected = f"{trace}:2: values nest more than {MAX_DEPTH} deep, the limit for a record"
    one_error_line(run_command(command, trace, tmp_path), expected)


@pytest.mark.parametrize("command", COMMANDS)
def test_a_50_mb_line(tmp_path: Path, command: str) -> None:
    trace = tmp_path / "long.jsonl"
    with trace.open("wb") as file:  # sparse: one line of 50 MB, the rest of it NUL bytes
        file.write(json.dumps(record()).encode() + b'\n{"t": 0.2, "body": "')
        file.truncate(50_000_000)
    run = run_command(command, trace, tmp_path)
    one_error_line(run, f"{trace}:2: the line is longer than {MAX_LINE_BYTES} bytes, the limit for a record")
    assert run.memory < 200 * 2**20  # a line is read up to its limit, never whole


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("kind", ["fifo", "device"])
def test_a_fifo_or_a_device_is_refused_before_it_is_read(tmp_path: Path, command: str, kind: str) -> None:
    if kind == "fifo":
        trace, what = tmp_path / "pipe.jsonl", "a FIFO"
        os.mkfifo(trace)  # nothing writes to it: a reader that opened it would wait forever
    else:
        trace, what = Path("/dev/zero"), "a character device"  # endless NUL bytes, no newline
    one_error_line(
        run_command(command, trace, tmp_path), f"{trace}: cannot open: not a regular file ({what})"
    )


def test_a_file_name_holding_a_newline_stays_one_line(tmp_path: Path) -> None:
    trace = tmp_path / "two\nlines.jsonl"
    trace.write_bytes(b"\xff\n")
    label = str(trace).replace("\n", "\\n")
    one_error_line(run_command("view", trace, tmp_path), f"{label}:1: not UTF-8: byte 0xff at column 1")


# -- huge and non-finite values: refused by the pictures, compared by diff -----------------------


NOT_DRAWN = {
    "1e308": [1e308, -1e308, 0.0],
    "-1e308": [1.0, 2.0, -1e308],
    "Infinity": [math.inf, 0.0, 0.0],
    "NaN": [0.0, math.nan, 0.0],
}


@pytest.mark.parametrize(
    ("command", "origin"),
    [("plot", NOT_DRAWN["1e308"]), *(("view", origin) for origin in NOT_DRAWN.values())],
    ids=["plot-1e308", *(f"view-{name}" for name in NOT_DRAWN)],
)
def test_an_origin_past_the_float32_range_or_not_finite_is_refused(
    tmp_path: Path, command: str, origin: list[float]
) -> None:
    trace = write_trace(tmp_path / "huge.jsonl", record(), record(t=0.2, origin=origin))
    expected = (  # the JSON spelling (Infinity, NaN) is read as Python's inf and nan
        f"{trace}:2: origin must be 3 numbers, finite and within ±3.4e+38 (the float32 range), "
        f"got {[float(value) for value in origin]!r}"
    )
    one_error_line(run_command(command, trace, tmp_path), expected)


@pytest.mark.parametrize("command", ["view", "plot"])
def test_values_at_the_edge_of_the_float32_range_are_drawn(tmp_path: Path, command: str) -> None:
    edge = MAX_MAGNITUDE
    trace = write_trace(
        tmp_path / "edge.jsonl",
        record(t=-edge, origin=(edge, -edge, edge)),
        record(t=edge, origin=(-edge, edge, -edge)),
        record(t=edge, body="other", origin=(0.0, 0.0, 0.0)),
    )
    run = run_command(command, trace, tmp_path)
    assert (run.code, run.err) == (0, "")
    if command == "plot":
        assert (tmp_path / "out.png").read_bytes()[:8] == PNG_SIGNATURE


def test_diff_of_a_trace_with_itself_is_identical_whatever_it_holds(tmp_path: Path) -> None:
    odd = [record(t=0.1 * index, origin=origin) for index, origin in enumerate(NOT_DRAWN.values())]
    trace = write_trace(tmp_path / "odd.jsonl", *odd, record(t=math.nan, quantum=math.inf))
    run = run_command("diff", trace, tmp_path)
    assert (run.code, run.out, run.err) == (0, "identical within 1e-06\n", "")


def test_diff_takes_nan_as_nan_and_a_number_against_nan_as_a_divergence(tmp_path: Path) -> None:
    nan = write_trace(tmp_path / "nan.jsonl", record(), record(t=0.2, velocity=[0.0, math.nan, 1.0]))
    number = write_trace(tmp_path / "number.jsonl", record(), record(t=0.2, velocity=[0.0, 0.5, 1.0]))
    assert "NaN" in nan.read_text(encoding="utf-8")
    same = acphys("diff", nan, nan, cwd=tmp_path)
    assert (same.code, same.out, same.err) == (0, "identical within 1e-06\n", "")
    for a, b, shown in ((nan, number, "nan vs 0.5"), (number, nan, "0.5 vs nan")):
        run = acphys("diff", a, b, "--context", "0", cwd=tmp_path)
        assert (run.code, run.err) == (1, "")
        assert run.out == f"first divergence at line 2, t=0.2, body 'ball': velocity[1]: {shown}\n"


# -- names: drawn as written, one line in every message ------------------------------------------


MATHS = ["$x^$", "$\\frac{", "a$b$c"]


@pytest.mark.parametrize("name", MATHS)
def test_a_name_matplotlib_would_read_as_maths_is_drawn_as_written(tmp_path: Path, name: str) -> None:
    trace = write_trace(
        tmp_path / "maths.jsonl", record(body=name), record(t=0.2, body=name, origin=(11, 21, 29))
    )
    run = run_command("plot", trace, tmp_path)
    assert (run.code, run.err) == (0, "")  # no mathtext error, no warning
    png = (tmp_path / "out.png").read_bytes()
    assert png[:8] == PNG_SIGNATURE and len(png) > 10_000
    figure = make_figure(read_paths(trace))
    legend = figure.legends[0].get_texts()[0]
    assert (legend.get_text(), legend.get_parse_math()) == (name, False)
    view = run_command("view", trace, tmp_path)
    assert (view.code, view.err) == (0, "") and name in view.out


def test_a_name_holding_a_newline_is_shown_escaped_and_messages_stay_one_line(tmp_path: Path) -> None:
    name = "two\nlines"
    trace = write_trace(tmp_path / "newline.jsonl", record(body=name), record(t=0.2, body=name))
    view = run_command("view", trace, tmp_path)
    assert (view.code, view.err) == (0, "") and "two\\nlines" in view.out
    plot = run_command("plot", trace, tmp_path)
    assert (plot.code, plot.err) == (0, "")
    missing = acphys("view", trace, "--bodies", "nobody", cwd=tmp_path)
    one_error_line(missing, "no body named 'nobody' in the trace (it has: two\\nlines)")
    other = write_trace(tmp_path / "other.jsonl", record(body=name), record(t=0.2, body="one"))
    diff = acphys("diff", trace, other, "--context", "0", cwd=tmp_path)
    assert (diff.code, diff.err) == (1, "")
    # Records pair per body: the second record of 'two\nlines' has none to pair with in the other.
    expected = "first divergence at line 2, t=0.2, body 'two\\nlines': record: 'record 2' vs '<end of trace>'"
    expected += "\n"
    assert diff.out == expected


# -- long traces: bounded memory and time --------------------------------------------------------


def compact_trace(path: Path, records: int, bodies: int = 4) -> Path:
    """A trace of ``records`` records over ``bodies`` walking bodies, holding only the keys a
    picture reads (a third of a full record's length), written a thousand records at a time."""
    block = []
    for index in range(1000):
        t = index // bodies / 30
        x = 20.0 + 10.0 * math.sin(index / 50)
        events = '"hit_ground"' if index % 97 == 0 else ""
        block.append(
            f'{{"t": {t!r}, "body": "b{index % bodies}", "quantum": 0.0333, "cell": "0xA9B4000A", '
            f'"origin": [{x!r}, {index / 10!r}, 1.5], "transient": ["active", "contact"], '
            f'"events": [{events}]}}\n'
        )
    text = "".join(block).encode()
    with path.open("wb") as file:
        for _ in range(records // 1000):
            file.write(text)
    return path


#: ``acphys ARGS`` with the picture's sample budget cut to a thousand, so that thinning starts
#: early: what the memory of a longer trace would show past :data:`acphys.plot.MAX_POINTS`.
SMALL_BUDGET = (
    "import sys, acphys.plot, acphys.cli; acphys.plot.MAX_POINTS = 1000; sys.exit(acphys.cli.main())"
)


def test_past_the_sample_budget_memory_does_not_grow_with_the_trace(tmp_path: Path) -> None:
    short = compact_trace(tmp_path / "short.jsonl", 25_000)
    long = compact_trace(tmp_path / "long.jsonl", 100_000)
    runs = [
        acphys("plot", trace, "-o", tmp_path / "out.png", cwd=tmp_path, code=SMALL_BUDGET)
        for trace in (short, long)
    ]
    for run, records in zip(runs, ("6,250", "25,000"), strict=True):
        assert run.code == 0, run.err
        assert run.err.count("\n") == 1 and run.err.startswith("acphys: warning: "), run.err
        assert f"has {records} records); a picture keeps at most 1,000 samples" in run.err
    assert runs[1].memory - runs[0].memory < 4 * 2**20, [run.memory for run in runs]


def test_a_long_trace_is_drawn_and_viewed_within_the_bounds(tmp_path: Path) -> None:
    trace = compact_trace(tmp_path / "long.jsonl", 100_000)
    for command in ("plot", "view"):
        run = run_command(command, trace, tmp_path)
        assert (run.code, run.err) == (0, ""), run.err
        assert run.memory < 400 * 2**20
    assert "b3" in run.out


# -- thinning and NaN semantics, by hand ---------------------------------------------------------


def kept(points: Points) -> list[float]:
    return list(points.t)


def expected_samples(added: int, stride: int) -> list[float]:
    """The samples a :class:`Points` keeps: every ``stride``-th, and the latest."""
    samples = [float(i) for i in range(0, added, stride)]
    return samples if (added - 1) % stride == 0 else [*samples, float(added - 1)]


def test_points_keep_every_sample_until_thinned() -> None:
    points = Points()
    assert [points.add(i, i, i, i) for i in range(5)] == [1] * 5
    assert kept(points) == [0.0, 1.0, 2.0, 3.0, 4.0] and (points.added, points.stride) == (5, 1)


def test_thinning_doubles_the_stride_and_keeps_the_first_and_the_latest_sample() -> None:
    points = Points()
    for i in range(10):
        points.add(i, i, i, i)
    assert points.thin() == 4
    assert (kept(points), points.stride) == ([0.0, 2.0, 4.0, 6.0, 8.0, 9.0], 2)
    assert points.add(10, 10, 10, 10) == 0  # 9 was kept only as the latest: 10 takes its place
    assert kept(points) == [0.0, 2.0, 4.0, 6.0, 8.0, 10.0]
    assert points.add(11, 11, 11, 11) == 1
    assert points.thin() == 3
    assert (kept(points), points.stride) == ([0.0, 4.0, 8.0, 11.0], 4)
    assert list(points.x) == list(points.y) == list(points.z) == kept(points)


@pytest.mark.parametrize("samples", [1, 2, 3, 7, 8, 9, 100, 1023, 1024, 1025])
def test_thinning_keeps_the_samples_on_the_stride_however_many_were_added(samples: int) -> None:
    points = Points()
    for i in range(samples):
        points.add(i, 0.0, 0.0, 0.0)
        if i % 37 == 36 and len(points) > 2:
            points.thin()
    assert kept(points) == expected_samples(samples, points.stride)
    stride = points.stride
    points.thin()
    assert points.stride == 2 * stride
    assert kept(points) == expected_samples(samples, 2 * stride)


def test_a_collector_keeps_at_most_its_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("acphys.plot.MAX_POINTS", 100)
    collector = PathCollector()
    for i in range(2000):
        collector.add(record(t=i / 30, body=f"b{i % 3}", events=["hit_ground"] if i % 5 == 0 else []), "x", i)
    series = [points for path in collector.paths.values() for points in path.series()]
    assert sum(map(len, series)) <= 100
    for index, path in enumerate(collector.paths.values()):
        assert path.added == 2000 // 3 + (index < 2000 % 3)
        assert (path.t[0], path.t[-1]) == (index / 30, (index + 3 * (path.added - 1)) / 30)
        assert path.stride > 1 and path.stride & (path.stride - 1) == 0  # a power of two
        assert path.events["hit_ground"] == sum(1 for i in range(index, 2000, 3) if i % 5 == 0)


NAN = math.nan
INF = math.inf


@pytest.mark.parametrize(
    ("a", "b"),
    [
        (NAN, NAN),
        (INF, INF),
        (-INF, -INF),
        (0.0, -0.0),
        (1, 1.0),
        (1.0, 1.0 + 1e-9),
        ([1.0, NAN], [1.0, NAN]),
    ],
)
def test_first_difference_takes_these_as_the_same(a: Any, b: Any) -> None:
    assert _first_difference("velocity", a, b, 1e-6) is None


@pytest.mark.parametrize(
    ("a", "b", "field", "difference"),
    [
        (NAN, 1.0, "t", None),
        (1.0, NAN, "t", None),
        (NAN, INF, "t", None),
        (INF, -INF, "t", INF),
        (INF, 1.0, "t", INF),
        (1.0, 1.1, "t", pytest.approx(0.1)),
        ([0.0, NAN, 2.0], [0.0, 0.5, 2.0], "t[1]", None),
        ([0.0, 1.0, NAN], [0.0, 1.0, NAN, 3.0], "t", None),  # lists of other lengths: compared whole
    ],
)
def test_first_difference_finds_these(a: Any, b: Any, field: str, difference: Any) -> None:
    found = _first_difference("t", a, b, 1e-6)
    assert found is not None
    assert found.field == field
    assert found.difference == difference


def test_same_takes_nan_as_nan_and_a_boolean_never_as_a_number() -> None:
    assert _same([NAN, {"a": [NAN]}], [NAN, {"a": [NAN]}])
    assert _same({"a": 1, "b": "x"}, {"b": "x", "a": 1.0})
    assert not _same(NAN, 0.0)
    assert not _same([NAN], [NAN, NAN])
    assert not _same({"a": NAN}, {"b": NAN})
    assert not _same(True, 1) and not _same(0, False) and _same(True, True)
    assert not _same("NaN", NAN)
    events = _first_difference("events", ["hit_ground"], ["leave_ground"], 1.0)
    assert events is not None and (events.field, events.a, events.b) == (
        "events",
        ["hit_ground"],
        ["leave_ground"],
    )
    assert _first_difference("contact_normal", None, None, 0.0) is None
