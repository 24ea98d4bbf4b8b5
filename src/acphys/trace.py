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

import json
import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TextIO

from acphys.flags import TransientState, flag_names
from acphys.math.cell_id import format_cell_id
from acphys.physics_obj import PhysicsObj

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
        self._file = self.path.open("w", encoding="utf-8")
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
        if self._file is None:
            raise RuntimeError("TraceWriter is not open; use it as a context manager")
        self._file.write(json.dumps(step_record(body, quantum), allow_nan=False))
        self._file.write("\n")
        self.records += 1


def read_trace(path: str | Path) -> Iterator[tuple[int, dict[str, Any]]]:
    """Yield ``(line_number, record)`` for each record of a trace file."""
    path = Path(path)
    try:
        handle = path.open(encoding="utf-8")
    except OSError as error:
        raise TraceError(f"{path}: cannot open: {error.strerror}") from None
    with handle:
        for number, line in enumerate(handle, start=1):
            if not line.strip():
                continue
            try:
                record = json.loads(line)
            except json.JSONDecodeError as error:
                raise TraceError(f"{path}:{number}: not JSON: {error.msg}") from None
            if not isinstance(record, dict):
                raise TraceError(f"{path}:{number}: a record must be a JSON object")
            missing = [key for key in ("t", "body") if key not in record]
            if missing:
                raise TraceError(f"{path}:{number}: record has no {', '.join(missing)}")
            yield number, record


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
        if self.t is not None:
            where += f", t={self.t:.6g}"
        if self.body is not None:
            where += f", body {self.body!r}"
        text = f"first divergence at {where}: {self.field}: {self.a!r} vs {self.b!r}"
        if self.difference is not None:
            text += f" (differs by {self.difference:.6g})"
        return text


def _first_difference(field: str, a: Any, b: Any, tol: float) -> Divergence | None:
    """Where ``a`` and ``b`` first differ beyond ``tol`` (the record fields are left unset)."""
    if isinstance(a, bool) or isinstance(b, bool):
        return None if type(a) is type(b) and a == b else Divergence(0, None, None, field, a, b)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        difference = abs(a - b)
        if math.isnan(difference) or difference > tol:
            return Divergence(0, None, None, field, a, b, difference)
        return None
    numeric_list = isinstance(a, list) and isinstance(b, list) and field not in ("transient", "events")
    if numeric_list and len(a) == len(b):
        for index, (x, y) in enumerate(zip(a, b, strict=True)):
            found = _first_difference(f"{field}[{index}]", x, y, tol)
            if found is not None:
                return found
        return None
    return None if a == b else Divergence(0, None, None, field, a, b)


def diff_traces(path_a: str | Path, path_b: str | Path, tol: float = 1e-6) -> Divergence | None:
    """The first record and field where two traces differ by more than ``tol``, or None.

    Records are compared in order; numbers (and numeric list elements) by
    absolute difference, everything else exactly. A trace that ends early
    diverges at the first record the other has and it lacks.
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
