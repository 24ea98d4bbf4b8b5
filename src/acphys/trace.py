"""Traces (contract 2): one JSON record per body per physics step, and their diff.

A trace (schema ``acphys.trace/2``, :data:`SCHEMA`; the JSON Schema is :func:`trace_schema`)
opens with a header naming what wrote it::

    {"schema": "acphys.trace/2", "acphys": "0.1.0", "engine": "reference", "driver_hz": 30.0,
     "scenario": {"name": "yard", "sha256": "..."}}

then holds one record per body as the run starts (``quantum`` 0, no events), and one after every
``update_object_internal`` call::

    {"t": 0.05, "body": "runner", "id": "0x80000001", "quantum": 0.05, "cell": "0xA9B40021",
     "origin": [x, y, z], "orientation": [w, x, y, z], "heading": 90.0,
     "velocity": [...], "cached_velocity": [...], "omega": [...],
     "transient": ["active", "contact", "on_walkable"], "contact_normal": [...] or null,
     "motion": {"style": "NonCombat", "forward": "WalkForward", "forward_speed": 1.0, ...},
     "events": ["hit_ground"]}

``t`` is the physics time after the step; ``origin`` is local to the
landblock named by ``cell``; ``heading`` is the compass heading of ``orientation``;
``contact_normal`` is the contact plane's normal while the body is in contact; ``motion`` is
the motion interpreter's state and the animation playing (null for a body without parts).
A v1 trace (acphys before the header) has no header, no start records, no ``id``, ``heading``
or ``motion``; the readers take both.
"""

from __future__ import annotations

import errno
import json
import os
import re
from collections.abc import Iterable, Iterator
from importlib import resources
from pathlib import Path
from typing import Any, BinaryIO, TextIO

from acphys.flags import TransientState, flag_names
from acphys.inputs import InputError, one_line, open_regular
from acphys.math.cell_id import format_cell_id
from acphys.math.frame import Frame
from acphys.motion.commands import motion_name
from acphys.motion.movement import HoldKey
from acphys.physics_obj import PhysicsObj

#: The schema a trace's header names (``{"schema": SCHEMA, ...}``, its first line). A trace
#: without a header is a v1 trace: body records alone, without ``id``, ``heading`` or ``motion``.
SCHEMA = "acphys.trace/2"
#: The schemas :func:`read_trace` reads (v1 has no header to name one).
SCHEMAS = (SCHEMA,)

#: The keys of a record, in the order they are written.
RECORD_KEYS = (
    "t",
    "body",
    "id",
    "quantum",
    "cell",
    "origin",
    "orientation",
    "heading",
    "velocity",
    "cached_velocity",
    "omega",
    "transient",
    "contact_normal",
    "motion",
    "events",
)
#: The keys of a record's ``motion``, in the order they are written.
MOTION_KEYS = (
    "style",
    "forward",
    "forward_speed",
    "sidestep",
    "sidestep_speed",
    "turn",
    "turn_speed",
    "hold_key",
    "animation",
    "frame",
)


#: The longest line a record can take, in bytes with its newline. A record acphys writes is about
#: 400 bytes and its events a few dozen each; a MiB holds thousands of events in one step and
#: bounds what one line makes the reader hold (a file with no newline is refused, not slurped).
MAX_LINE_BYTES = 1 << 20
#: How deep a record's arrays and objects can nest. acphys writes lists in an object (depth 2);
#: the bound keeps the JSON parser and the comparisons of ``diff`` far from Python's recursion limit.
MAX_DEPTH = 32
#: The most digits an integer in a record can have. acphys writes floats (any length of those
#: reads as a float64); Python refuses integers of more than 4300 digits, and ``diff`` computes
#: with the integers it reads.
MAX_INT_DIGITS = 100

_BRACKET = re.compile(rb"[][{}]")
_STRING = re.compile(rb'"(?:[^"\\]++|\\.)*+"', re.DOTALL)
_SURROGATE_ESCAPE = re.compile(rb"\\u[dD][89a-fA-F]")


class TraceError(ValueError):
    """A trace file that cannot be read; the message names the file and line."""


def step_record(body: PhysicsObj, quantum: float) -> dict[str, Any]:
    """The trace record of ``body`` right after a step of ``quantum`` seconds (0: the record of
    where a run starts, without the events the first step will report)."""
    frame = body.position.frame
    in_contact = body.transient_state & TransientState.CONTACT
    orientation = [frame.qw, frame.qx, frame.qy, frame.qz]
    sequence = body.part_array.sequence if body.part_array is not None else None
    node = sequence.curr_anim if sequence is not None else None
    playing = node is not None and node.animation is not None
    return {
        "t": body.world.physics_time,
        "body": body.name,
        "id": f"0x{body.id:08X}",
        "quantum": quantum,
        "cell": format_cell_id(body.position.objcell_id),
        "origin": list(frame.origin),
        "orientation": orientation,
        "heading": heading_of(orientation),
        "velocity": list(body.velocity),
        "cached_velocity": list(body.cached_velocity),
        "omega": list(body.omega),
        "transient": flag_names(body.transient_state, TransientState),
        "contact_normal": list(body.contact_plane.N) if in_contact else None,
        "motion": motion_record(
            body,
            node.animation.name if playing else None,  # type: ignore[union-attr]
            sequence.frame_number if playing else None,  # type: ignore[union-attr]
        ),
        "events": list(body.step_events) if quantum else [],
    }


def heading_of(orientation: list[float]) -> float:
    """The compass heading in degrees [0, 360) of a record's ``orientation`` ``[w, x, y, z]``:
    retail's ``Frame::get_heading`` of the matrix the quaternion caches."""
    return Frame(None, *orientation).get_heading()


def motion_record(body: PhysicsObj, animation: str | None, frame: float | None) -> dict[str, Any] | None:
    """A record's ``motion``: the interpreted motion state (style, forward, sidestep and turn
    commands by name with their speeds; null commands for none) and the raw state's hold key,
    when the body has a motion interpreter, and the ``animation`` playing (the current node's,
    by name) at ``frame``; None for a body with neither."""
    if body.part_array is None:
        return None
    manager = body.movement_manager
    interp = manager.motion_interpreter if manager is not None else None
    if interp is None:
        if animation is None:
            return None
        motion: dict[str, Any] = dict.fromkeys(MOTION_KEYS)
    else:
        state = interp.interpreted_state
        motion = {
            "style": motion_name(state.current_style),
            "forward": motion_name(state.forward_command),
            "forward_speed": state.forward_speed,
            "sidestep": motion_name(state.sidestep_command) if state.sidestep_command else None,
            "sidestep_speed": state.sidestep_speed,
            "turn": motion_name(state.turn_command) if state.turn_command else None,
            "turn_speed": state.turn_speed,
            "hold_key": HoldKey(interp.raw_state.current_holdkey).name.lower(),
        }
    motion["animation"] = animation
    motion["frame"] = frame
    return motion


def trace_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of one line of a trace, as shipped in the package
    (``acphys/data/trace.schema.json``; ``acphys schema trace`` prints it)."""
    text = resources.files("acphys.data").joinpath("trace.schema.json").read_text("utf-8")
    return json.loads(text)


def trace_header(scenario: str, sha256: str | None, driver_hz: float, engine: str) -> dict[str, Any]:
    """The first record of a v2 trace: what wrote it and from what."""
    from acphys import __version__

    return {
        "schema": SCHEMA,
        "acphys": __version__,
        "engine": engine,
        "driver_hz": driver_hz,
        "scenario": {"name": scenario, "sha256": sha256},
    }


class TraceWriter:
    """Writes a record for every step of the bodies it is attached to."""

    def __init__(self, path: str | Path, header: dict[str, Any] | None = None) -> None:
        """A writer of the trace at ``path``; ``header`` (:func:`trace_header`) is its first line."""
        self.path = Path(path)
        self.header = header
        self._file: TextIO | None = None
        self.records = 0

    def __enter__(self) -> TraceWriter:
        try:  # a named pipe that no process reads is refused rather than waited on
            descriptor = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NONBLOCK, 0o666)
        except OSError as error:
            if error.errno != errno.ENXIO:
                raise
            label = one_line(str(self.path))
            raise TraceError(f"{label}: cannot write: a named pipe that no process reads") from None
        os.set_blocking(descriptor, True)
        self._file = os.fdopen(descriptor, "w", encoding="utf-8")
        if self.header is not None:
            self._file.write(json.dumps(self.header, allow_nan=False))
            self._file.write("\n")
        return self

    def __exit__(self, *exc: object) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None

    def attach(self, bodies: Iterable[PhysicsObj]) -> None:
        for body in bodies:
            body.observer = self.write_step

    def detach(self, bodies: Iterable[PhysicsObj]) -> None:
        for body in bodies:
            if body.observer == self.write_step:
                body.observer = None

    def write_step(self, body: PhysicsObj, quantum: float) -> None:
        self.write_record(step_record(body, quantum))

    def write_start(self, bodies: Iterable[PhysicsObj]) -> None:
        """A record of each of ``bodies`` as it stands (``quantum`` 0), before a run's first step."""
        for body in bodies:
            self.write_record(step_record(body, 0.0))

    def write_record(self, record: dict[str, Any]) -> None:
        """Write one record (a :func:`step_record`, or the fast engine's equivalent)."""
        if self._file is None:
            raise RuntimeError("TraceWriter is not open; use it as a context manager")
        self._file.write(json.dumps(record, allow_nan=False))
        self._file.write("\n")
        self.records += 1


def read_trace(path: str | Path) -> Iterator[tuple[int, dict[str, Any]]]:
    """Yield ``(line_number, record)`` for each body record of a trace file, reading one line at a
    time; a v2 trace's header (its first record, :func:`read_header`) is not yielded.

    A trace of any length streams through in constant memory. A line is refused
    (:class:`TraceError` naming the file, the line and the limit) when it is
    longer than :data:`MAX_LINE_BYTES`, not UTF-8, nested deeper than
    :data:`MAX_DEPTH`, holds an integer of more than :data:`MAX_INT_DIGITS`
    digits or a string that is not text, or is not a JSON object with ``t``
    and ``body``.
    """
    for number, record in _records(path):
        if "schema" not in record or "body" in record:
            yield number, record


def read_header(path: str | Path) -> dict[str, Any] | None:
    """The header of a v2 trace (``{"schema": SCHEMA, ...}``, its first record), or None for a
    v1 trace (or an empty one), which has none."""
    for _, record in _records(path):
        return record if "schema" in record and "body" not in record else None
    return None


def _records(path: str | Path) -> Iterator[tuple[int, dict[str, Any]]]:
    """Every record of a trace file, the header first if it has one (see :func:`read_trace`)."""
    label = one_line(str(path))
    with _open_trace(path, label) as handle:
        number = 0
        first = True
        while line := handle.readline(MAX_LINE_BYTES + 1):
            number += 1
            try:
                record = _parse_line(line, header=first)
            except TraceError as error:
                raise TraceError(f"{label}:{number}: {error}") from None
            if record is not None:
                first = False
                yield number, record


def _open_trace(path: str | Path, label: str) -> BinaryIO:
    """``path`` opened for reading, if it is a regular file (a FIFO would block, a device never end)."""
    try:
        return open_regular(path)
    except InputError as error:
        raise TraceError(f"{label}: cannot open: {error.strerror}") from None


def _parse_line(line: bytes, header: bool = False) -> dict[str, Any] | None:
    """The record on one line of a trace (None for a blank line), within the reader's limits;
    a :class:`TraceError` says what is wrong with the line (the caller names the file and line).
    With ``header``, the line may be a v2 header instead (an object naming its ``schema``)."""
    if len(line) > MAX_LINE_BYTES:
        raise TraceError(f"the line is longer than {MAX_LINE_BYTES} bytes, the limit for a record")
    try:
        text = line.decode("utf-8")
    except UnicodeDecodeError as error:
        raise TraceError(f"not UTF-8: byte {line[error.start]:#04x} at column {error.start + 1}") from None
    if text[0] != "{" and text.isspace():
        return None
    if line.count(b"[") + line.count(b"{") > MAX_DEPTH and _depth(line) > MAX_DEPTH:
        raise TraceError(f"values nest more than {MAX_DEPTH} deep, the limit for a record")
    try:
        record = _decode(text)
    except json.JSONDecodeError as error:
        raise TraceError(f"not JSON: {error.msg} at column {error.colno}") from None
    except _IntegerTooLong as error:
        raise TraceError(f"an integer of {error.args[0]} digits; the limit is {MAX_INT_DIGITS}") from None
    if type(record) is not dict:
        raise TraceError("a record must be a JSON object")
    if b"\\u" in line and _SURROGATE_ESCAPE.search(line) and not _is_text(record):
        raise TraceError("a string holds a lone UTF-16 surrogate escape, which is not text")
    if header and "schema" in record and "body" not in record:
        if record["schema"] not in SCHEMAS:
            raise TraceError(f"unknown trace schema {brief(record['schema'])}; this acphys reads {SCHEMA}")
        return record
    if "t" not in record or "body" not in record:
        missing = [key for key in ("t", "body") if key not in record]
        raise TraceError(f"record has no {', '.join(missing)}")
    return record


def _depth(line: bytes) -> int:
    """How deep the arrays and objects of a JSON line nest, counted up to just past
    :data:`MAX_DEPTH` (brackets inside strings do not count)."""
    depth = deepest = 0
    for bracket in _BRACKET.findall(_STRING.sub(b"", line)):
        depth += 1 if bracket in b"[{" else -1
        deepest = max(deepest, depth)
        if deepest > MAX_DEPTH:
            break
    return deepest


class _IntegerTooLong(Exception):
    """An integer of more than :data:`MAX_INT_DIGITS` digits; its argument is how many."""


def _bounded_int(numeral: str) -> int:
    digits = len(numeral) - numeral.startswith("-")
    if digits > MAX_INT_DIGITS:
        raise _IntegerTooLong(digits)
    return int(numeral)


#: Reads a line's JSON (floats in C; integers, rare in a trace, checked in Python first).
_DECODER = json.JSONDecoder(parse_int=_bounded_int)
_SCAN = _DECODER.scan_once


def _decode(text: str) -> Any:
    """The JSON value of a line that is not blank.

    A line that is one object, as acphys writes them, goes straight to the decoder's scanner
    (skipping the Python around it: a sixth of the time of a record); any other line, or one the
    scanner stops on, through :meth:`json.JSONDecoder.decode`, whose errors say where it is wrong.
    """
    if text[0] == "{":
        try:
            value, end = _SCAN(text, 0)
        except (StopIteration, ValueError):
            pass
        else:
            if not text[end:].strip(" \t\r\n"):  # what JSON counts as white space
                return value
    return _DECODER.decode(text)


def _is_text(value: Any) -> bool:
    """Whether every string in ``value`` (keys too) can be written as UTF-8."""
    if isinstance(value, str):
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:
            return False
        return True
    if isinstance(value, list):
        return all(map(_is_text, value))
    if isinstance(value, dict):
        return all(_is_text(key) and _is_text(item) for key, item in value.items())
    return True


def brief(value: Any, limit: int = 80) -> str:
    """The ``repr`` of ``value`` for a message: cut to ``limit`` characters."""
    text = repr(value)
    return text if len(text) <= limit else f"{text[: limit - 3]}..."
