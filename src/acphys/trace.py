"""Traces (contract 2): one JSON record per body per physics step, and their diff.

A record is written after every ``update_object_internal`` call::

    {"t": 0.05, "body": "runner", "quantum": 0.05, "cell": "0xA9B40021",
     "origin": [x, y, z], "orientation": [w, x, y, z],
     "velocity": [...], "cached_velocity": [...], "omega": [...],
     "transient": ["active", "contact", "on_walkable"],
     "contact_normal": [...] or null, "events": ["hit_ground"]}

``t`` is the physics time after the step; ``origin`` is local to the
landblock named by ``cell``; ``contact_normal`` is the contact plane's normal
while the body is in contact.
"""

from __future__ import annotations

import errno
import json
import math
import os
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO, TextIO

from acphys.flags import TransientState, flag_names
from acphys.inputs import InputError, one_line, open_regular
from acphys.math.cell_id import format_cell_id
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
    "quantum",
    "cell",
    "origin",
    "orientation",
    "velocity",
    "cached_velocity",
    "omega",
    "transient",
    "contact_normal",
    "events",
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
    """The trace record of ``body`` right after a step of ``quantum`` seconds."""
    frame = body.position.frame
    in_contact = body.transient_state & TransientState.CONTACT
    return {
        "t": body.world.physics_time,
        "body": body.name,
        "quantum": quantum,
        "cell": format_cell_id(body.position.objcell_id),
        "origin": list(frame.origin),
        "orientation": [frame.qw, frame.qx, frame.qy, frame.qz],
        "velocity": list(body.velocity),
        "cached_velocity": list(body.cached_velocity),
        "omega": list(body.omega),
        "transient": flag_names(body.transient_state, TransientState),
        "contact_normal": list(body.contact_plane.N) if in_contact else None,
        "events": list(body.step_events),
    }


class TraceWriter:
    """Writes a record for every step of the bodies it is attached to."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
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


@dataclass
class Divergence:
    """Where two traces first differ."""

    line: int
    t: float | None
    body: str | None
    field: str
    a: Any
    b: Any
    difference: float | None = None

    def describe(self) -> str:
        where = f"line {self.line}"
        if _is_number(self.t):
            where += f", t={self.t:.6g}"
        elif self.t is not None:
            where += f", t={self.t!r}"
        if self.body is not None:
            where += f", body {self.body!r}"
        text = f"first divergence at {where}: {self.field}: {self.a!r} vs {self.b!r}"
        if self.difference is not None:
            text += f" (differs by {self.difference:.6g})"
        return text


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _first_difference(field: str, a: Any, b: Any, tol: float) -> Divergence | None:
    """Where ``a`` and ``b`` first differ beyond ``tol`` (the record fields are left unset).

    NaN equals NaN and infinity itself, so a trace never diverges from itself;
    -0.0 equals 0.0 (they differ by nothing).
    """
    if _is_number(a) and _is_number(b):
        if a == b or (a != a and b != b):
            return None
        difference = abs(a - b)
        if math.isnan(difference):
            return Divergence(0, None, None, field, a, b)
        return Divergence(0, None, None, field, a, b, difference) if difference > tol else None
    numeric_list = isinstance(a, list) and isinstance(b, list) and field not in ("transient", "events")
    if numeric_list and len(a) == len(b):
        for index, (x, y) in enumerate(zip(a, b, strict=True)):
            found = _first_difference(f"{field}[{index}]", x, y, tol)
            if found is not None:
                return found
        return None
    return None if _same(a, b) else Divergence(0, None, None, field, a, b)


def _same(a: Any, b: Any) -> bool:
    """Whether two JSON values are equal, a boolean never equal to a number and NaN equal to NaN."""
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(map(_same, a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[key], b[key]) for key in a)
    if isinstance(a, bool) or isinstance(b, bool):
        return type(a) is type(b) and a == b
    return a == b or (isinstance(a, float) and isinstance(b, float) and a != a and b != b)


def diff_traces(path_a: str | Path, path_b: str | Path, tol: float = 1e-6) -> Divergence | None:
    """The first record and field where two traces differ by more than ``tol``, or None.

    Records are compared in order; numbers (and numeric list elements) by
    absolute difference, everything else exactly; NaN equals NaN in the same
    field and -0.0 equals 0.0. A trace that ends early diverges at the first
    record the other has and it lacks. Both files stream through.
    """
    if not tol >= 0.0:
        raise ValueError(f"tolerance must be a non-negative number, got {tol}")
    records_a = read_trace(path_a)
    records_b = read_trace(path_b)
    record_index = 0
    while True:
        item_a = next(records_a, None)
        item_b = next(records_b, None)
        record_index += 1
        if item_a is None and item_b is None:
            return None
        if item_a is None or item_b is None:
            line, record = item_b if item_a is None else item_a  # type: ignore[misc]
            return Divergence(
                line=line,
                t=record.get("t"),
                body=record.get("body"),
                field="record",
                a="<end of trace>" if item_a is None else f"record {record_index}",
                b="<end of trace>" if item_b is None else f"record {record_index}",
            )
        line, a = item_a
        _, b = item_b
        for key in sorted(a.keys() | b.keys(), key=_key_order):
            if key not in a or key not in b:
                return Divergence(line, a.get("t"), a.get("body"), key, a.get(key), b.get(key))
            found = _first_difference(key, a[key], b[key], tol)
            if found is not None:
                found.line, found.t, found.body = line, a.get("t"), a.get("body")
                return found


def _key_order(key: str) -> tuple[int, str]:
    return (RECORD_KEYS.index(key) if key in RECORD_KEYS else len(RECORD_KEYS), key)
