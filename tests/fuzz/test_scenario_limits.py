"""The scenario reader's limits (issue 13): every hostile scenario is one ScenarioError line naming
the file, the key or line and the limit, never a RecursionError, an OverflowError, a hang or
gigabytes: files that are not regular files, too large or not UTF-8; TOML nested 500 arrays or
50,000 inline tables deep, keys of many parts, 5,000-digit numbers; a NUL in a ``[data]`` path;
a driver rate of 1e-300 Hz and runs of billions of ticks; keys and names holding a newline; and
lists (landblocks, objects, buildings, rooms, doorways, bodies, animation frames) whose building
would take minutes or gigabytes. Every input is generated here, large ones sparse.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

from acphys import scenario
from acphys.motion.commands import MOTION_IDS
from acphys.scenario import MAX_SCENARIO_BYTES, ScenarioError, load_scenario, parse_scenario, world_data
from acphys.scenario.motion_tables import MAX_SCENARIO_FRAMES
from acphys.scenario.values import MAX_KEY_PARTS, MAX_NESTING, MAX_NUMBER_CHARS
from acphys.scenario.world_data import MAX_BUILDINGS
from acphys.simulation import MAX_DRIVER_HZ, MAX_DRIVER_TICKS, MIN_DRIVER_HZ

BODY = '[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [10.0, 10.0, 0.0]\n'


def _problem(text: str, folder: Path | None = None) -> str:
    """The one-line ScenarioError of ``text`` read as the file ``s.toml`` (in ``folder``)."""
    with pytest.raises(ScenarioError) as caught:
        parse_scenario(text, source="s.toml", folder=folder)
    message = str(caught.value)
    assert len(caught.value.problems) == 1 and "\n" not in message, message
    return message


def _load_problem(path: Path) -> str:
    with pytest.raises(ScenarioError) as caught:
        load_scenario(path)
    message = str(caught.value)
    assert "\n" not in message, message
    return message


# -- the file ---------------------------------------------------------------------------------


def test_a_fifo_a_device_or_a_directory_is_refused_before_it_is_read(tmp_path: Path) -> None:
    """A FIFO blocked the reader until something wrote to it; /dev/zero ran out of memory. The
    FIFO is read by a subprocess, so that a regression fails on the timeout, not by hanging."""
    fifo = tmp_path / "world.toml"
    os.mkfifo(fifo)
    done = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys; from acphys.scenario import load_scenario; load_scenario(sys.argv[1])",
            fifo,
        ],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert (
        done.stderr.splitlines()[-1]
        == f"acphys.scenario.values.ScenarioError: {fifo}: cannot read: not a regular file (a FIFO)"
    )
    assert _load_problem(tmp_path) == f"{tmp_path}: cannot read: not a regular file (a directory)"
    if Path("/dev/zero").exists():
        assert (
            _load_problem(Path("/dev/zero"))
            == "/dev/zero: cannot read: not a regular file (a character device)"
        )


def test_a_file_over_the_size_limit_is_refused_unread(tmp_path: Path) -> None:
    big = tmp_path / "big.toml"
    with big.open("wb") as file:  # sparse: nothing is written but the size
        file.truncate(MAX_SCENARIO_BYTES + 1)
    assert _load_problem(big) == (
        f"{big}: cannot read: larger than the scenario size limit ({MAX_SCENARIO_BYTES:,} bytes)"
    )


@pytest.mark.parametrize(("data", "line", "offset"), [(b"\xff", 1, 0), (b"a = 1\nb = '\xc3(", 2, 11)])
def test_a_file_that_is_not_utf8_names_the_byte_offset(
    tmp_path: Path, data: bytes, line: int, offset: int
) -> None:
    path = tmp_path / "latin.toml"
    path.write_bytes(data)
    byte = data[offset]
    assert _load_problem(path) == (
        f"{path}: line {line}: not UTF-8 text: byte {byte:#04x} at offset {offset} (a scenario is UTF-8 TOML)"
    )


def test_a_path_with_a_nul_or_a_newline_is_one_line(tmp_path: Path) -> None:
    assert (
        _load_problem(tmp_path / "a\0b.toml")
        == f"{tmp_path}/a\\x00b.toml: cannot read: a path cannot hold a NUL byte"
    )
    assert _load_problem(tmp_path / "a\nb.toml") == f"{tmp_path}/a\\nb.toml: no such file"


# -- the TOML ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "value",
    ["[" * 500 + "]" * 500, "{a = " * 50_000 + "1" + "}" * 50_000, "[{x = " * 40 + "1" + "}]" * 40],
    ids=["500 arrays", "50,000 inline tables", "80 mixed"],
)
def test_deep_nesting_is_refused_before_tomllib_recurses(value: str) -> None:
    assert _problem(BODY + f"x = {value}\n") == (
        f"s.toml: line 5: arrays and inline tables nested deeper than {MAX_NESTING} levels "
        "(the scenario nesting limit)"
    )


def test_a_long_number_or_key_is_refused_before_tomllib_converts_it() -> None:
    for digits in (5_000, MAX_NUMBER_CHARS + 1):
        assert _problem(f"[scenario]\nseed = {'7' * digits}\n" + BODY) == (
            f"s.toml: line 2: a number of {digits:,} characters, more than the {MAX_NUMBER_CHARS} "
            "a scenario number may have"
        )
    key = ".".join(["k"] * (MAX_KEY_PARTS + 1))
    assert _problem(BODY + f"{key} = 1\n") == (
        f"s.toml: line 5: a key of more than {MAX_KEY_PARTS} dotted parts (the scenario key limit)"
    )


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ('x = "a\x01"\n', "Illegal character '\\x01' (at line 1, column 7)"),
        ("x = 1\x00\n", "Expected newline or end of document after a statement (at line 1, column 6)"),
        ("x = [1,\n", "Invalid value (at line 2, column 3)"),
    ],
    ids=["control character", "NUL", "unclosed"],
)
def test_toml_that_tomllib_refuses_is_one_line(text: str, problem: str) -> None:
    assert _problem(text + BODY) == f"s.toml: not valid TOML: {problem}"


def test_keys_and_names_holding_a_newline_stay_one_line(tmp_path: Path) -> None:
    assert _problem('"a\\nb" = 1\n' + BODY).startswith(
        "s.toml: a\\nb: unknown key (expected one of: scenario,"
    )
    named = BODY.replace('"a"', '"a\\nb"')
    assert _problem(named.replace('"0xA9B4"', '"0xZZ"')) == (
        's.toml: body[0].landblock: expected a landblock id like "0xA9B4", got '
        "'0xZZ' (line 3, body 'a\\nb')"
    )
    sim = parse_scenario(named.replace('"0xA9B4"', "1234"), source="s.toml")
    assert sim.warnings == [
        's.toml: body[0].landblock: 1234 is read as decimal, 0x4D2: write "0x1234" if hex was meant '
        "(line 3, body 'a\\nb')"
    ]


# -- values -----------------------------------------------------------------------------------


def test_a_nul_in_a_data_path_names_the_key(tmp_path: Path) -> None:
    assert _problem('[data]\nportal = "x\\u0000.dat"\n' + BODY, tmp_path) == (
        f"s.toml: data.portal: {tmp_path}/x\\x00.dat: a path cannot hold a NUL byte (line 2)"
    )


@pytest.mark.parametrize("hz", ["1e-300", "0.4", "-60.0", "1e300", "10001.0", "nan"])
def test_a_driver_rate_outside_its_range_names_the_key_and_the_range(hz: str) -> None:
    got = "nan" if hz == "nan" else f"{float(hz):g}"
    expected = (
        "expected a finite number, got nan"
        if hz == "nan"
        else f"expected a number in [{MIN_DRIVER_HZ:g}, {MAX_DRIVER_HZ:g}], got {got}"
    )
    assert (
        _problem(f"[scenario]\ndriver_hz = {hz}\n" + BODY)
        == f"s.toml: scenario.driver_hz: {expected} (line 2)"
    )


def test_a_run_of_too_many_driver_ticks_is_refused() -> None:
    assert _problem("[scenario]\nduration = 1e6\ndriver_hz = 100.0\n" + BODY) == (
        f"s.toml: scenario.duration: 1e+06 s at 100 Hz is 1e+08 driver ticks, more than the "
        f"{MAX_DRIVER_TICKS:,} a run may take (MAX_DRIVER_TICKS) (line 2)"
    )
    assert _problem(f"[scenario]\nduration = {'9' * 99}\n" + BODY) == (
        "s.toml: scenario.duration: expected a number in (0, 1e+06], got 1e+99 (line 2)"
    )


@pytest.mark.parametrize("until", [math.inf, -math.inf, math.nan])
def test_running_to_a_time_that_is_not_finite_is_a_value_error(until: float) -> None:
    sim = parse_scenario(BODY)
    with pytest.raises(ValueError, match=f"^until must be a finite number of seconds, got {until}$"):
        sim.run(until=until)
    assert sim.tick == 0


def test_running_past_the_tick_limit_is_a_value_error() -> None:
    sim = parse_scenario(BODY)
    with pytest.raises(ValueError) as caught:
        sim.run(until=1e300)
    assert str(caught.value) == (
        f"running to 1e+300 s at 60 Hz is 6e+301 driver ticks, more than the {MAX_DRIVER_TICKS:,} "
        "a run may take (MAX_DRIVER_TICKS)"
    )
    sim.run(until=0.1)  # a run within the limit still runs
    assert sim.tick == 6


# -- what building costs --------------------------------------------------------------------------


def _landblocks(count: int) -> str:
    return "".join(
        f'[[landblock]]\nid = "0x{i // 250:02X}{i % 250:02X}"\nheight = 1.0\n' for i in range(count)
    )


def _objects(count: int) -> str:
    return "".join(
        '[[object]]\nsetup = "human"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 0.0]\n' for _ in range(count)
    )


def _bodies(count: int) -> str:
    return "".join(
        f'[[body]]\nname = "b{i}"\nlandblock = 1\norigin = [1.0, 1.0, 0.0]\n' for i in range(count)
    )


def _buildings(count: int) -> str:
    return "".join('[[building]]\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 0.0]\n' for _ in range(count))


def _rooms(count: int) -> str:
    rooms = ", ".join(
        f'{{ name = "r{i}", min = [0.0, 0.0, {i}.0], max = [1.0, 1.0, {i + 1}.0] }}' for i in range(count)
    )
    return (
        f'[[building]]\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 0.0]\nrooms = [{rooms}]\ndoorways = []\n'
    )


def _doorways(count: int) -> str:
    door = '{ between = ["r", "outside"], min = [0.0, 0.2, 0.0], max = [0.0, 0.8, 0.8] }'
    return (
        '[[building]]\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 0.0]\n'
        'rooms = [{ name = "r", min = [0.0, 0.0, 0.0], max = [1.0, 1.0, 1.0] }]\n'
        f"doorways = [{', '.join([door] * count)}]\n"
    )


@pytest.mark.parametrize(
    ("make", "module", "name", "key", "what"),
    [
        (_landblocks, world_data, "MAX_LANDBLOCKS", "landblock", "landblocks"),
        (_objects, world_data, "MAX_OBJECTS", "object", "objects"),
        (_bodies, scenario, "MAX_BODIES", "body", "bodies"),
        (_buildings, world_data, "MAX_BUILDINGS", "building", "buildings"),
        (_rooms, world_data, "MAX_ROOMS", "building[0].rooms", "rooms"),
        (_doorways, world_data, "MAX_DOORWAYS", "building[0].doorways", "doorways"),
    ],
    ids=["landblocks", "objects", "bodies", "buildings", "rooms", "doorways"],
)
def test_more_entries_than_a_limit_are_refused_before_any_is_built(
    make: Callable[[int], str],
    module: ModuleType,
    name: str,
    key: str,
    what: str,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Limits up to ``MAX_BUILDINGS`` are met at their value; the larger ones (bodies, objects:
    20,001 entries take tomllib 4 s to read) are lowered to 3, the same check in a fraction of the time."""
    limit = getattr(module, name)
    if limit > MAX_BUILDINGS:
        limit = 3
        monkeypatch.setattr(module, name, limit)
    text = make(limit + 1) + ("" if key == "body" else BODY)
    problem = _problem(text)
    assert problem.startswith(
        f"s.toml: {key}: {limit + 1:,} {what}: more than the {limit:,} allowed ({name})"
    ), problem


def test_animation_frames_past_the_scenario_limit_are_refused_before_any_is_built() -> None:
    """20 cycles of 100,000 frames (a 2.6 KB file) built 2 million frames: 940 MB and 15 s."""
    motions = [name for name in MOTION_IDS if name.startswith("Walk") or name.startswith("Run")]
    cycles = "".join(
        f'[[motion_table.m.cycle]]\nmotion = "{motion}"\nframerate = 30.0\nframes = 100000\n'
        "pos_frame = [0.0, 0.0, 0.0]\n"
        for motion in (["Ready", *motions] * 20)[:20]
    )
    text = f'[motion_table.m]\ndefault_style = "NonCombat"\n{cycles}' + BODY
    assert _problem(text) == (
        "s.toml: motion_table: the animations declare 2,000,000 frames in all: more than the "
        f"{MAX_SCENARIO_FRAMES:,} allowed (MAX_SCENARIO_FRAMES)"
    )
