"""Trace records into compact per-body columns for the page.

Every field of a record the inspector shows is kept as a column: numbers as float32 (what retail
stores them as, so exact) except ``t`` (float64); ``cell`` as uint32; ``transient`` as a bit mask
over a table of the names seen; ``motion`` (without its ``frame``) as an index into a table of the
distinct states seen, ``frame`` as its own column; a missing or null value as NaN (or -1 for
``motion``). Events are kept apart, with their body, time and place.

A record must have ``t``, ``body``, ``cell`` and ``origin`` (as ``acphys plot`` requires); the
other fields may be missing (a v1 trace has no ``motion`` nor ``heading``). A body's records must
go forward in time.
"""

from __future__ import annotations

import json
import math
import re
from array import array
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from acphys.flags import TransientState, flag_names
from acphys.inputs import one_line
from acphys.trace import TraceError, brief, read_trace

#: The most records the page keeps, of all bodies together (about 100 bytes each before
#: compression): past it every body keeps every 2nd record, then every 4th, ... (events are
#: all kept, up to :data:`MAX_EVENTS`). 100 bodies for 20 s at 30 Hz are 60,000.
MAX_RECORDS = 200_000
#: The most events the page keeps (the later ones are counted, not shown).
MAX_EVENTS = 100_000
#: The most distinct event strings, motion states and transient flag names the tables hold.
MAX_EVENT_STRINGS = 10_000
MAX_MOTION_STATES = 65_536
MAX_TRANSIENT_NAMES = 32
#: Event strings and body names are cut to this many characters on the page.
MAX_TEXT = 200
#: The most bodies a page shows (each costs some 100 bytes of description and its list entry;
#: pick others with ``--bodies``).
MAX_BODIES = 20_000
#: Numbers a page draws: finite and within the float32 range.
MAX_MAGNITUDE = 3.4028234663852886e38

_CELL = re.compile(r"0x[0-9A-Fa-f]{1,8}")
_NAN = math.nan

#: The per-record columns: name, array type code, values per record.
COLUMNS: tuple[tuple[str, str, int], ...] = (
    ("t", "d", 1),
    ("quantum", "f", 1),
    ("cell", "I", 1),
    ("origin", "f", 3),
    ("orientation", "f", 4),
    ("heading", "f", 1),
    ("velocity", "f", 3),
    ("cached_velocity", "f", 3),
    ("omega", "f", 3),
    ("contact_normal", "f", 3),
    ("transient", "I", 1),
    ("motion", "i", 1),
    ("frame", "f", 1),
)


@dataclass
class BodyRecords:
    """One body's kept records, a column each (see :data:`COLUMNS`)."""

    name: str
    id: str | None
    columns: dict[str, array[Any]] = field(
        default_factory=lambda: {name: array(code) for name, code, _ in COLUMNS}
    )
    #: Records read (kept or not); record k is kept when k % stride == 0.
    read: int = 0
    stride: int = 1

    def __len__(self) -> int:
        return len(self.columns["t"])

    def thin(self) -> int:
        """Keep every 2nd kept record; returns how many were dropped."""
        before = len(self)
        for name, _code, width in COLUMNS:
            column = self.columns[name]
            if width == 1:
                self.columns[name] = column[::2]
            else:
                kept = array(column.typecode)
                for k in range(0, len(column) // width, 2):
                    kept.extend(column[k * width : (k + 1) * width])
                self.columns[name] = kept
        self.stride *= 2
        return before - len(self)


@dataclass
class Events:
    """Events, one entry each: the body's index, the time, the cell and local place of the record
    that lists it, and the index of its text in ``strings``."""

    body: array[int] = field(default_factory=lambda: array("I"))
    t: array[float] = field(default_factory=lambda: array("d"))
    cell: array[int] = field(default_factory=lambda: array("I"))
    origin: array[float] = field(default_factory=lambda: array("f"))
    text: array[int] = field(default_factory=lambda: array("I"))
    strings: list[str] = field(default_factory=list)
    dropped: int = 0

    def __len__(self) -> int:
        return len(self.t)


class RecordCollector:
    """Builds :class:`BodyRecords` and :class:`Events` from trace records."""

    def __init__(self, bodies: Iterable[str] | None = None) -> None:
        self.bodies: dict[str, BodyRecords] = {}
        self.only = set(bodies) if bodies is not None else None
        self.events = Events()
        #: Retail's flags in bit order first (as a record lists them), then any other name seen.
        self.transient_names: list[str] = flag_names(~0 & 0xFFFFFFFF, TransientState)[:MAX_TRANSIENT_NAMES]
        self.motions: list[dict[str, Any]] = []
        self.warnings: list[str] = []
        self._transient_bits: dict[str, int] = {name: bit for bit, name in enumerate(self.transient_names)}
        self._motion_index: dict[str, int] = {}
        self._strings: dict[str, int] = {}
        self._kept = 0
        self._body_index: dict[str, int] = {}

    # -- reading ------------------------------------------------------------------------------

    def add(self, record: dict[str, Any], where: str) -> None:
        """Add one record; ``where`` (file:line) prefixes any :class:`TraceError`."""
        t, name, cell, origin = record.get("t"), record.get("body"), record.get("cell"), record.get("origin")
        if not _number(t):
            raise TraceError(
                f"{where}: t must be a number, finite and within the float32 range, got {brief(t)}"
            )
        if not isinstance(name, str):
            raise TraceError(f"{where}: body must be a string, got {brief(name)}")
        if not (isinstance(cell, str) and _CELL.fullmatch(cell)):
            raise TraceError(f'{where}: cell must be a hex cell id like "0xA9B40021", got {brief(cell)}')
        if not _vector(origin, 3):
            raise TraceError(
                f"{where}: origin must be 3 numbers, finite, within the float32 range, got {brief(origin)}"
            )
        if self.only is not None and name not in self.only:
            return
        body = self.bodies.get(name)
        if body is None:
            if len(self.bodies) == MAX_BODIES:
                raise TraceError(
                    f"{where}: more than {MAX_BODIES:,} bodies, the limit for a page "
                    "(choose some with --bodies)"
                )
            ident = record.get("id")
            body = self.bodies[name] = BodyRecords(name, ident if isinstance(ident, str) else None)
            self._body_index[name] = len(self._body_index)
        columns = body.columns
        kept = not len(body) or body.read % body.stride == 0
        if len(columns["t"]) and float(t) < columns["t"][-1]:
            raise TraceError(
                f"{where}: body {one_line(name)!r} goes back in time ({float(t):g} s after "
                f"{columns['t'][-1]:g} s); a page needs each body's records in time order"
            )
        body.read += 1
        cell_id = int(cell, 16)
        events = record.get("events")
        if isinstance(events, list) and events:
            self._add_events(self._body_index[name], float(t), cell_id, origin, events)
        if not kept:
            return
        columns["t"].append(float(t))
        columns["quantum"].append(_float(record.get("quantum")))
        columns["cell"].append(cell_id)
        columns["origin"].extend(origin)
        orientation = record.get("orientation")
        columns["orientation"].extend(orientation if _vector(orientation, 4) else (1.0, 0.0, 0.0, 0.0))
        columns["heading"].append(_float(record.get("heading")))
        for key in ("velocity", "cached_velocity", "omega", "contact_normal"):
            value = record.get(key)
            columns[key].extend(value if _vector(value, 3) else (_NAN, _NAN, _NAN))
        columns["transient"].append(self._transient(record.get("transient")))
        motion = record.get("motion")
        if isinstance(motion, dict):
            columns["motion"].append(self._motion(motion))
            columns["frame"].append(_float(motion.get("frame")))
        else:
            columns["motion"].append(-1)
            columns["frame"].append(_NAN)
        self._kept += 1
        if self._kept > MAX_RECORDS:
            self._thin()

    def _transient(self, names: Any) -> int:
        if not isinstance(names, list):
            return 0
        mask = 0
        for name in names:
            if not isinstance(name, str):
                continue
            bit = self._transient_bits.get(name)
            if bit is None:
                if len(self.transient_names) == MAX_TRANSIENT_NAMES:
                    self._warn(
                        f"more than {MAX_TRANSIENT_NAMES} transient flag names: the rest are not shown"
                    )
                    continue
                bit = self._transient_bits[name] = len(self.transient_names)
                self.transient_names.append(_text(name))
            mask |= 1 << bit
        return mask

    def _motion(self, motion: dict[str, Any]) -> int:
        state = {key: value for key, value in motion.items() if key != "frame"}
        key = json.dumps(state, sort_keys=True, default=str)
        index = self._motion_index.get(key)
        if index is None:
            if len(self.motions) == MAX_MOTION_STATES:
                self._warn(f"more than {MAX_MOTION_STATES:,} motion states: the rest are not shown")
                return -1
            index = self._motion_index[key] = len(self.motions)
            self.motions.append({key: _plain(value) for key, value in state.items()})
        return index

    def _add_events(self, body: int, t: float, cell: int, origin: list[float], events: list[Any]) -> None:
        store = self.events
        for event in events:
            if not isinstance(event, str):
                continue
            if len(store) == MAX_EVENTS:
                store.dropped += 1
                continue
            index = self._strings.get(event)
            if index is None:
                if len(store.strings) == MAX_EVENT_STRINGS:
                    store.dropped += 1
                    continue
                index = self._strings[event] = len(store.strings)
                store.strings.append(_text(event))
            store.body.append(body)
            store.t.append(t)
            store.cell.append(cell)
            store.origin.extend(origin)
            store.text.append(index)

    def _thin(self) -> None:
        """Thin the bodies with the most records until at most half :data:`MAX_RECORDS` are kept."""
        while self._kept > MAX_RECORDS // 2:
            longest = max(len(body) for body in self.bodies.values())
            if longest <= 2:
                break
            for body in self.bodies.values():
                if len(body) * 2 > longest:
                    self._kept -= body.thin()

    def _warn(self, message: str) -> None:
        if message not in self.warnings:
            self.warnings.append(message)

    def finish(self) -> list[str]:
        """The warnings of the whole read (thinned bodies, dropped events)."""
        thinned = [body for body in self.bodies.values() if body.stride > 1]
        if thinned:
            strides = sorted({body.stride for body in thinned})
            self._warn(
                f"more than {MAX_RECORDS:,} records: {len(thinned)} bodies are shown from every "
                f"{'/'.join(map(str, strides))}th record"
            )
        if self.events.dropped:
            self._warn(f"{self.events.dropped:,} events past the first {MAX_EVENTS:,} are not shown")
        return self.warnings


def collect_records(
    trace: str | Path, bodies: Iterable[str] | None = None, warn: Callable[[str], None] | None = None
) -> RecordCollector:
    """Every record of a trace file (of ``bodies`` only, when given), as columns."""
    collector = RecordCollector(bodies)
    label = one_line(str(trace))
    for line, record in read_trace(trace):
        collector.add(record, f"{label}:{line}")
    if not collector.bodies:
        if bodies is not None:
            raise TraceError(f"{label}: no records of the bodies {', '.join(map(repr, bodies))}")
        raise TraceError(f"{label}: the trace has no records")
    if bodies is not None:
        missing = [name for name in bodies if name not in collector.bodies]
        if missing:
            raise TraceError(f"{label}: no body named {', '.join(map(repr, missing))} in the trace")
    for message in collector.finish():
        if warn is not None:
            warn(message)
    return collector


def records_cells(collector: RecordCollector) -> Iterator[int]:
    """The cell of each body's first and last record (to place the scene frame)."""
    for body in collector.bodies.values():
        cells = body.columns["cell"]
        if cells:
            yield cells[0]
            yield cells[-1]


def _number(value: Any) -> bool:
    if type(value) is float:
        return -MAX_MAGNITUDE <= value <= MAX_MAGNITUDE
    return isinstance(value, (int, float)) and not isinstance(value, bool) and abs(value) <= MAX_MAGNITUDE


def _vector(value: Any, size: int) -> bool:
    return isinstance(value, list) and len(value) == size and all(_number(v) for v in value)


def _float(value: Any) -> float:
    return float(value) if _number(value) else _NAN


def _text(value: str) -> str:
    text = one_line(value)
    return text if len(text) <= MAX_TEXT else text[: MAX_TEXT - 1] + "…"


def _plain(value: Any) -> Any:
    """A motion value as the page shows it: strings cut, numbers kept, anything else as brief text."""
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, str):
        return _text(value)
    if _number(value):
        return float(value)
    return brief(value, MAX_TEXT)
