"""One garbage set fed to every command of the command line (issue 13): each case exits 2 (never 3,
an acphys bug) with exactly one ``acphys: error:`` line on stderr, within 30 s and 1 GiB.

The files: a FIFO, /dev/zero, a directory, an empty file, random bytes, text that is not UTF-8,
a scenario naming a DAT path with a NUL in it (a NUL cannot be passed on a command line itself),
a file whose name holds a newline, a single 5,000-digit number, 100,000 open brackets, a sparse
file past the scenario size limit and a missing file; each is given to every command that reads
a file (``run``, ``check``, ``diff`` on either side, ``plot``, ``view`` and the four ``dat``
commands). ``show`` gets garbage names, ``bench`` absurd numbers and ``run --until`` times that
are not finite or would take years.

Every case is a real ``python -m acphys.cli`` process, reaped with ``os.wait4`` for its peak
memory and killed at the time limit (so a FIFO read in error fails the case instead of hanging
the suite). The processes run a few at a time in a module fixture; each case then checks its own.
"""

from __future__ import annotations

import os
import random
import resource
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

from acphys.inputs import one_line
from acphys.scenario import MAX_SCENARIO_BYTES, load_scenario

#: The issue's bounds on any one input: seconds and peak memory (``ru_maxrss`` is KiB on Linux).
TIME_LIMIT = 30.0
MEMORY_LIMIT_KIB = 1 << 20
#: A safety net under the assertion: a runaway case fails on its address space, not the machine's.
ADDRESS_SPACE = 4 << 30


def _garbage(folder: Path) -> dict[str, Path]:
    """The garbage files, made in ``folder``."""
    folder.mkdir()
    fifo = folder / "fifo"
    os.mkfifo(fifo)
    files: dict[str, Path] = {
        "fifo": fifo,
        "directory": folder / "a-directory",
        "missing": folder / "missing",
    }
    files["directory"].mkdir()
    if Path("/dev/zero").exists():
        files["/dev/zero"] = Path("/dev/zero")
    contents = {
        "empty": b"",
        "random bytes": random.Random(13).randbytes(65536),
        "not UTF-8": "name = 'café'\n[[body]]\nname = 'ü'\n".encode("latin-1"),
        "NUL in a path": b'[data]\nportal = "portal\\u0000.dat"\n',
        "newline in the name": b"x = [\n",
        "5,000 digits": b"9" * 5000 + b"\n",
        "deep brackets": b"[" * 100_000 + b"\n",
    }
    names = {"newline in the name": "bad\nname.toml"}
    for label, data in contents.items():
        path = folder / names.get(label, f"{label.replace(' ', '-').replace(',', '')}.txt")
        path.write_bytes(data)
        files[label] = path
    large = folder / "large.toml"
    with large.open("wb") as file:  # sparse: past the scenario limit, over a MiB of one trace line
        file.truncate(MAX_SCENARIO_BYTES + 1)
    files["over the size limit"] = large
    return files


GARBAGE = [
    "fifo",
    "/dev/zero",
    "directory",
    "empty",
    "random bytes",
    "not UTF-8",
    "NUL in a path",
    "newline in the name",
    "5,000 digits",
    "deep brackets",
    "over the size limit",
    "missing",
]

#: Every command that reads a file: its arguments around the garbage file ``F`` (``T`` is a good
#: trace, ``O`` a picture and ``H`` a page to write).
FILE_COMMANDS = {
    "run": ["run", "F"],
    "check": ["check", "F"],
    "diff (first)": ["diff", "F", "T"],
    "diff (second)": ["diff", "T", "F"],
    "plot": ["plot", "F", "-o", "O"],
    "view": ["view", "F"],
    "view --html": ["view", "F", "--html", "H"],
    "plot --scenario": ["plot", "T", "-o", "O", "--scenario", "F"],
    "corpus check": ["corpus", "check", "F"],
    "dat info": ["dat", "info", "F"],
    "dat list": ["dat", "list", "F"],
    "dat setup": ["dat", "setup", "F", "0x02000001"],
    "dat heights": ["dat", "heights", "F"],
}

#: Commands that take no file, with garbage arguments (``P`` is the FIFO).
OTHER_CASES = {
    "show a name with a newline": ["show", "default\nhills"],
    "show a 100 KB name": ["show", "x" * 100_000],
    "show an empty name": ["show", ""],
    "bench --bodies -1": ["bench", "--bodies", "-1"],
    "bench --bodies 1e9": ["bench", "--bodies", "1e9"],
    "bench --bodies 10**30": ["bench", "--bodies", "1" + "0" * 30],
    "bench --seconds nan": ["bench", "--seconds", "nan"],
    "bench --seconds inf": ["bench", "--seconds", "inf"],
    "bench --seconds -1": ["bench", "--seconds", "-1"],
    "bench 100,000 bodies for an hour": ["bench", "--bodies", "100000", "--seconds", "3600"],
    "bench --json to a FIFO": ["bench", "--bodies", "1", "--seconds", "0.1", "--json", "P"],
    "run --until inf": ["run", "default", "--until", "inf"],
    "run --until nan": ["run", "default", "--until", "nan"],
    "run --until -1": ["run", "default", "--until", "-1"],
    "run --until 1e300": ["run", "default", "--until", "1e300"],
    "run --until 1e7": ["run", "default", "--until", "1e7"],
}

CASES = {
    **{f"{command} <- {label}": (command, label) for command in FILE_COMMANDS for label in GARBAGE},
    **{name: (name, None) for name in OTHER_CASES},
}


@dataclass
class Outcome:
    code: int | None  # None: killed at the time limit
    stderr: str
    stdout: str
    seconds: float
    maxrss_kib: int


def _limit_address_space() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def _start(argv: list[str], log: Path) -> tuple[subprocess.Popen[bytes], float]:
    with log.open("wb") as err, log.with_suffix(".out").open("wb") as out:
        process = subprocess.Popen(
            [sys.executable, "-m", "acphys.cli", *argv],
            stdin=subprocess.DEVNULL,
            stdout=out,
            stderr=err,
            preexec_fn=_limit_address_space,
        )
    return process, time.monotonic()


def _run_all(commands: dict[str, list[str]], logs: Path) -> dict[str, Outcome]:
    """Run every command, a few at a time, each reaped by ``os.wait4`` or killed at the limit."""
    workers = max(2, os.cpu_count() or 2)
    pending = list(commands)
    running: dict[str, tuple[subprocess.Popen[bytes], float, Path]] = {}
    outcomes: dict[str, Outcome] = {}
    while pending or running:
        while pending and len(running) < workers:
            name = pending.pop()
            log = logs / f"{len(pending)}.err"
            running[name] = (*_start(commands[name], log), log)
        for name, (process, started, log) in list(running.items()):
            late = time.monotonic() - started > TIME_LIMIT
            if late:
                process.kill()
            pid, status, usage = os.wait4(process.pid, 0 if late else os.WNOHANG)
            if pid == 0:
                continue
            process.returncode = os.waitstatus_to_exitcode(status)
            del running[name]
            code = None if late else process.returncode
            text = log.read_text("utf-8", errors="replace")
            out = log.with_suffix(".out").read_text("utf-8", errors="replace")
            outcomes[name] = Outcome(code, text, out, time.monotonic() - started, usage.ru_maxrss)
        time.sleep(0.005)
    return outcomes


@dataclass
class Runs:
    files: dict[str, Path]
    outcomes: dict[str, Outcome]


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> Runs:
    root = tmp_path_factory.mktemp("garbage")
    files = _garbage(root / "files")
    trace = root / "good.jsonl"
    load_scenario("default").run(until=0.2, trace=trace)
    fill = {"T": str(trace), "O": str(root / "out.png"), "H": str(root / "out.html"), "P": str(files["fifo"])}
    commands: dict[str, list[str]] = {}
    for case, (command, label) in CASES.items():
        if label is None:
            commands[case] = [fill.get(arg, arg) for arg in OTHER_CASES[command]]
        elif label in files:
            commands[case] = [
                str(files[label]) if arg == "F" else fill.get(arg, arg) for arg in FILE_COMMANDS[command]
            ]
    logs = root / "logs"
    logs.mkdir()
    return Runs(files, _run_all(commands, logs))


#: The cases that are not bad input: an empty file is an empty trace to ``diff``.
EMPTY_TRACE_DIFFS = ("diff (first) <- empty", "diff (second) <- empty")


@pytest.mark.parametrize("case", list(CASES))
def test_garbage_is_one_error_line_and_exit_2(case: str, runs: Runs) -> None:
    if case not in runs.outcomes:
        pytest.skip("no /dev/zero here")
    done = runs.outcomes[case]
    assert done.code is not None, f"{case}: still running after {TIME_LIMIT:g} s (killed)"
    if case in EMPTY_TRACE_DIFFS:
        # Not garbage to diff: an empty trace is one that ends at once, and diverges from a real
        # one at its first record (tests/unit/test_trace.py), exit 1 with the divergence on stdout
        # (line 2: the real trace's first line is its header).
        assert (done.code, done.stderr) == (1, ""), f"{case}: exit {done.code}: {done.stderr}"
        assert done.stdout.startswith("first divergence at line 2, "), done.stdout
        return
    lines = done.stderr.splitlines()
    assert done.code == 2, f"{case}: exit {done.code}: {done.stderr}"
    assert len(lines) == 1 and lines[0].startswith("acphys: error: "), f"{case}: {lines}"
    assert "internal error" not in lines[0], lines[0]
    assert done.seconds < TIME_LIMIT, f"{case}: {done.seconds:.1f} s"
    assert done.maxrss_kib < MEMORY_LIMIT_KIB, f"{case}: {done.maxrss_kib / 1024:.0f} MiB"
    label = CASES[case][1]
    if label is not None:  # the line names the file (the garbage, not the good trace of a diff)
        assert one_line(str(runs.files[label])) in lines[0], f"{case}: {lines[0]}"
