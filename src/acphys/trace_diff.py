"""Where two traces differ (``acphys diff``), for checking a port of the physics against acphys.

Records are paired per body: the k-th record of a body in one trace with the k-th record of that
body in the other, so that an extra or a missing record shows as that and nothing else. Numbers
(and the elements of numeric lists) compare by absolute difference, everything else exactly; NaN
equals NaN and -0.0 equals 0.0. Both traces stream through: what is held is, per body, the records
one trace has that the other has not reached yet (at most :data:`MAX_UNPAIRED`) and the last few
compared (``context``).

A v1 trace (no header) against a v2 trace is compared on what both have: v2's ``id``, ``heading``
and ``motion`` and its start records (``quantum`` 0) are skipped.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections import Counter, deque
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from acphys.inputs import one_line
from acphys.trace import MOTION_KEYS, RECORD_KEYS, TraceError, brief, read_header, read_trace

#: The fields of a v2 record that a v1 record lacks; skipped when one of the traces is v1.
V2_ONLY = ("id", "heading", "motion")
#: The most records of one body one trace may hold unpaired, ahead of the other: past it the
#: comparison stops (the other trace lacks the body, or writes it far out of step).
MAX_UNPAIRED = 10_000
#: What a ``record`` divergence shows for the trace that lacks the record.
END_OF_TRACE = "<end of trace>"
NO_SUCH_BODY = "<no record of this body>"
NO_MATCH = "<none so far>"
#: What a divergence shows for a field one record lacks.
ABSENT = "<absent>"
_LACKING = (END_OF_TRACE, NO_SUCH_BODY, NO_MATCH)
_INDEX = re.compile(r"\[(\d+)\]")


class DiffError(ValueError):
    """A comparison that cannot be made as asked (a bad tolerance, an unknown field or body)."""


@dataclass
class ContextRow:
    """A pair of records of a body before its divergence: their lines, the time, and the values in
    both of what diverges next (``origin[2]``) and their difference when they are numbers."""

    line_a: int
    line_b: int
    t: Any
    a: Any
    b: Any
    difference: float | None


@dataclass
class Divergence:
    """Where two traces differ: ``field`` of the records of ``body`` at ``line`` in trace a and
    ``line_b`` in b, or (field ``record``) a record one trace has and the other lacks; ``line`` is
    then the line in the trace that has it."""

    line: int
    t: float | None
    body: str | None
    field: str
    a: Any
    b: Any
    difference: float | None = None
    line_b: int | None = None
    #: The records of the body compared just before (the oldest first), when asked for.
    context: list[ContextRow] = dataclasses.field(default_factory=list)

    @property
    def line_a(self) -> int | None:
        """The line in trace a (None when a lacks the record)."""
        return None if self.field == "record" and self.a in _LACKING else self.line

    def describe(self) -> str:
        where = f"line {self.line}"
        if self.line_b is not None and self.line_b != self.line:
            where += f" (b: line {self.line_b})"
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

    def as_dict(self) -> dict[str, Any]:
        return {
            "body": self.body,
            "line_a": self.line_a,
            "line_b": self.line_b,
            "t": self.t,
            "field": self.field,
            "a": self.a,
            "b": self.b,
            "difference": self.difference,
            "context": [dataclasses.asdict(row) for row in self.context],
        }


@dataclass
class DiffReport:
    """What :func:`compare_traces` found."""

    path_a: str
    path_b: str
    header_a: dict[str, Any] | None
    header_b: dict[str, Any] | None
    tolerance: float
    #: The first divergence (every diverging body's first, with ``all_bodies``), in line order.
    divergences: list[Divergence] = dataclasses.field(default_factory=list)
    #: Diverging records (pairs, or records the other trace lacks) per field and per body.
    field_counts: Counter[str] = dataclasses.field(default_factory=Counter)
    body_counts: Counter[str] = dataclasses.field(default_factory=Counter)
    records_compared: int = 0
    bodies_compared: int = 0
    #: The bodies each trace lacks (``{"a": [...], "b": [...]}``), or None when the comparison
    #: stopped before the ends of the traces.
    missing_bodies: dict[str, list[str]] | None = None
    warnings: list[str] = dataclasses.field(default_factory=list)
    #: Why the comparison stopped before the traces ended, other than at a first divergence.
    stopped: str | None = None

    @property
    def identical(self) -> bool:
        return not self.divergences

    @property
    def first(self) -> Divergence | None:
        return self.divergences[0] if self.divergences else None

    def as_dict(self) -> dict[str, Any]:
        """The report as JSON values (a non-finite number as its JSON spelling, a string)."""
        return _jsonable(
            {
                "identical": self.identical,
                "tolerance": self.tolerance,
                "a": {"path": self.path_a, "header": self.header_a},
                "b": {"path": self.path_b, "header": self.header_b},
                "records_compared": self.records_compared,
                "bodies_compared": self.bodies_compared,
                "divergences": [divergence.as_dict() for divergence in self.divergences],
                "field_counts": dict(self.field_counts.most_common()),
                "diverging_records": dict(self.body_counts.most_common()),
                "missing_bodies": self.missing_bodies,
                "warnings": self.warnings,
                "stopped": self.stopped,
            }
        )


def diff_traces(path_a: str | Path, path_b: str | Path, tol: float = 1e-6) -> Divergence | None:
    """The first divergence of two traces beyond ``tol`` (see :func:`compare_traces`), or None."""
    return compare_traces(path_a, path_b, tol, context=0).first


def compare_traces(
    path_a: str | Path,
    path_b: str | Path,
    tol: float = 1e-6,
    *,
    bodies: Sequence[str] | None = None,
    fields: Sequence[str] | None = None,
    ignore: Sequence[str] = (),
    all_bodies: bool = False,
    context: int = 2,
) -> DiffReport:
    """Compare two traces, records paired per body, up to the first divergence or (``all_bodies``)
    to their ends, for the first divergence of every body and the diverging records per field.

    ``bodies``, ``fields`` and ``ignore`` restrict the comparison as ``acphys diff``'s options do
    (a field may be a sub-field of ``motion``, like ``motion.forward``); ``context`` is how many
    records of a diverging body before its divergence each divergence keeps. Raises
    :class:`DiffError` for a bad argument or a body in neither trace, :class:`TraceError` for a
    trace that cannot be read.
    """
    if not tol >= 0.0:
        raise DiffError(f"tolerance must be a non-negative number, got {tol}")
    if context < 0:
        raise DiffError(f"context must be a non-negative number of records, got {context}")
    selection = _Selection(fields, ignore)
    header_a, header_b = read_header(path_a), read_header(path_b)
    one_v1 = {_version(path_a, header_a), _version(path_b, header_b)} == {1, 2}
    if one_v1:
        selection.skip = frozenset(V2_ONLY)
    report = DiffReport(str(path_a), str(path_b), header_a, header_b, tol)
    report.warnings += _header_warnings(header_a, header_b)
    if one_v1 and fields is not None and any(_top(name) in V2_ONLY for name in fields):
        report.warnings.append(f"one trace is v1: {', '.join(V2_ONLY)} are not compared")
    wanted = None if bodies is None else set(bodies)
    comparison = _Comparison(report, selection, all_bodies, context)
    a = _Side("a", path_a, wanted, skip_start=one_v1)
    b = _Side("b", path_b, wanted, skip_start=one_v1)
    complete = comparison.run(a, b)
    if complete:
        comparison.finish(a, b)
    report.divergences.sort(key=lambda divergence: divergence.line)
    if not all_bodies:
        del report.divergences[1:]
    report.bodies_compared = len(a.counts.keys() | b.counts.keys())
    if wanted is not None:
        _check_bodies(bodies or (), a, b, complete)
    return report


def _version(path: str | Path, header: dict[str, Any] | None) -> int | None:
    """A trace's version: 2 with a header, 1 without, None for a trace without records."""
    if header is not None:
        return 2
    return None if next(read_trace(path), None) is None else 1


def _header_warnings(header_a: dict[str, Any] | None, header_b: dict[str, Any] | None) -> list[str]:
    """A warning when both traces name their scenario's SHA-256 and the two differ."""
    a, b = ((header or {}).get("scenario") for header in (header_a, header_b))
    if not (isinstance(a, dict) and isinstance(b, dict)):
        return []
    if a.get("sha256") is None or b.get("sha256") is None or a["sha256"] == b["sha256"]:
        return []
    ran = [
        f"{side} ran {brief(x.get('name'), 40)} (sha256 {brief(x['sha256'], 20)})"
        for side, x in (("a", a), ("b", b))
    ]
    return [f"the traces are of different scenarios: {ran[0]}, {ran[1]}"]


def _check_bodies(bodies: Iterable[str], a: _Side, b: _Side, complete: bool) -> None:
    """Refuse (DiffError) a body in neither trace; a comparison that stopped early reads on for
    the names first."""
    unknown = [name for name in bodies if name not in a.names and name not in b.names]
    if unknown and not complete:
        for side in (a, b):
            side.read_names()
        unknown = [name for name in unknown if name not in a.names and name not in b.names]
    if unknown:
        known = list(dict.fromkeys([*a.names, *b.names]))
        shown = ", ".join(map(repr, known[:10])) or "none"
        more = f" and {len(known) - 10:,} more" if len(known) > 10 else ""
        raise DiffError(
            f"--bodies: no body named {', '.join(map(repr, unknown))} in either trace "
            f"(they have: {shown}{more})"
        )


# -- what is compared -------------------------------------------------------------------------


def _top(name: str) -> str:
    return name.split(".", 1)[0]


class _Selection:
    """The fields compared: every field but ``ignore`` and ``skip`` (the fields one trace does not
    have), or only ``fields``; a name may be a field or a sub-field of ``motion`` (``motion.forward``)."""

    #: How many layouts of a record's keys the selection keeps the compared keys of.
    LAYOUTS = 64

    def __init__(self, fields: Sequence[str] | None, ignore: Sequence[str]) -> None:
        known = [key for key in RECORD_KEYS if key != "body"]
        subfields = [f"motion.{key}" for key in MOTION_KEYS]
        for option, names in (("--fields", fields or ()), ("--ignore", ignore)):
            for name in names:
                if name == "body":
                    raise DiffError(f"{option}: body names the records compared; choose them with --bodies")
                if name not in known and name not in subfields:
                    raise DiffError(
                        f"{option}: unknown field {name!r} (fields: {', '.join(known)}; "
                        f"and motion.KEY for a KEY of {', '.join(MOTION_KEYS)})"
                    )
        self.fields = None if fields is None else frozenset(fields)
        self.ignore = frozenset(ignore)
        self.skip: frozenset[str] = frozenset()
        self._keys: dict[tuple[tuple[str, ...], tuple[str, ...]], list[str]] = {}

    def keys(self, a: dict[str, Any], b: dict[str, Any]) -> list[str]:
        """The keys of two records compared, in the order a record writes them."""
        layout = (tuple(a), tuple(b))
        keys = self._keys.get(layout)
        if keys is None:
            if len(self._keys) >= self.LAYOUTS:
                self._keys.clear()
            keys = [key for key in sorted(a.keys() | b.keys(), key=_key_order) if self._compares(key)]
            self._keys[layout] = keys
        return keys

    def _compares(self, key: str) -> bool:
        if key in self.ignore or key in self.skip or key == "body":
            return False
        return self.fields is None or key in self.fields or any(_top(name) == key for name in self.fields)

    def subfields(self, key: str, a: Any, b: Any) -> list[str] | None:
        """The sub-fields of ``key`` compared one by one, or None to compare it whole."""
        if self.fields is not None and key not in self.fields:
            chosen = [name.split(".", 1)[1] for name in self.fields if _top(name) == key]
            return [sub for sub in _ordered(chosen) if f"{key}.{sub}" not in self.ignore]
        if isinstance(a, dict) and isinstance(b, dict):
            return [sub for sub in _ordered([*a, *b]) if f"{key}.{sub}" not in self.ignore]
        return None


def _ordered(keys: Iterable[str]) -> list[str]:
    """Sub-field names once each, in the order a record writes them."""
    unique = dict.fromkeys(keys)
    return [key for key in MOTION_KEYS if key in unique] + [key for key in unique if key not in MOTION_KEYS]


def _record_differences(
    a: dict[str, Any], b: dict[str, Any], selection: _Selection, tol: float
) -> list[Divergence]:
    """The first difference in each compared field (or sub-field) of two records, in record order;
    the divergences' ``field`` is the path to it (``origin[2]``) and their record fields unset."""
    found = []
    for key in selection.keys(a, b):
        value_a, value_b = a.get(key, ABSENT), b.get(key, ABSENT)
        if _equal(value_a, value_b):
            continue
        subfields = selection.subfields(key, value_a, value_b)
        if subfields is None:
            divergence = _first_difference(key, value_a, value_b, tol)
            if divergence is not None:
                found.append(divergence)
            continue
        for sub in subfields:
            divergence = _first_difference(f"{key}.{sub}", _sub(value_a, sub), _sub(value_b, sub), tol)
            if divergence is not None:
                found.append(divergence)
    return found


#: The types of the values :func:`_equal` takes in a list or an object.
_FLAT = frozenset((float, int, str, type(None)))


def _equal(a: Any, b: Any) -> bool:
    """Whether two values are plainly equal: a quick True for what acphys writes (numbers, strings,
    null, and flat lists and objects of those, element types alike); False to compare in full."""
    kind = type(a)
    if kind is not type(b) or a != b:
        return False
    if kind is list:
        types = list(map(type, a))
        return types == list(map(type, b)) and _FLAT.issuperset(types)
    if kind is dict:
        types = list(map(type, a.values()))
        return list(a) == list(b) and types == list(map(type, b.values())) and _FLAT.issuperset(types)
    return kind in _FLAT


def _sub(value: Any, key: str) -> Any:
    """A sub-field's value (a null or absent ``motion`` has null or absent sub-fields)."""
    return value.get(key, ABSENT) if isinstance(value, dict) else value


def _unit(field: str) -> str:
    """The field or sub-field a divergence's path is in (``origin`` for ``origin[2]``)."""
    return field.split("[", 1)[0]


def _context_row(field: str, line_a: int, a: dict[str, Any], line_b: int, b: dict[str, Any]) -> ContextRow:
    """What a context row shows of a pair of records: the values at ``field``'s path."""
    value_a, value_b = _at(a, field), _at(b, field)
    numbers = _is_number(value_a) and _is_number(value_b)
    return ContextRow(
        line_a, line_b, a.get("t"), value_a, value_b, abs(value_a - value_b) if numbers else None
    )


def _at(record: dict[str, Any], field: str) -> Any:
    """The value at a divergence's path in a record (``origin[2]``, ``motion.forward``)."""
    unit = _unit(field)
    top, _, sub = unit.partition(".")
    value = record.get(top, ABSENT)
    if sub:
        value = _sub(value, sub)
    for index in map(int, _INDEX.findall(field, len(unit))):
        value = value[index] if isinstance(value, list) and index < len(value) else ABSENT
    return value


def _key_order(key: str) -> tuple[int, str]:
    return (RECORD_KEYS.index(key) if key in RECORD_KEYS else len(RECORD_KEYS), key)


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


# -- reading both traces ----------------------------------------------------------------------


class _Side:
    """One trace as it is read: the records of each body not paired yet, and how far it has got."""

    def __init__(self, name: str, path: str | Path, wanted: set[str] | None, skip_start: bool) -> None:
        self.name = name
        self.label = one_line(str(path))
        self._records = read_trace(path)
        self._wanted = wanted
        self._skip_start = skip_start
        #: The time of the record read last (None when it is not a number), and how many were read.
        self.t: float | None = -math.inf
        self.reads = 0
        self.ended = False
        #: Every body named so far (compared or not), and the records read of each compared one.
        self.names: dict[str, None] = {}
        self.counts: Counter[str] = Counter()
        self.unpaired: dict[str, deque[tuple[int, dict[str, Any]]]] = {}

    def read(self) -> tuple[int, dict[str, Any]] | None:
        """The next record to compare, or None at the end of the trace."""
        for line, record in self._records:
            self.reads += 1
            t, body = record["t"], record["body"]
            self.t = float(t) if _is_number(t) and t == t else None
            if not isinstance(body, str):
                raise TraceError(f"{self.label}:{line}: body must be a string, got {brief(body)}")
            self.names[body] = None
            if self._wanted is not None and body not in self._wanted:
                continue
            quantum = record.get("quantum")
            if self._skip_start and _is_number(quantum) and quantum == 0:
                continue
            self.counts[body] += 1
            return line, record
        self.ended = True
        return None

    def read_names(self) -> None:
        """Read to the end for the bodies' names alone."""
        self._wanted = set()
        while not self.ended:
            self.read()


def _next_side(a: _Side, b: _Side) -> _Side | None:
    """The trace to read on: the one behind in time (the same scenario keeps the two in step
    whatever bodies they hold), or the one with fewer records read."""
    if a.ended or b.ended:
        return None if a.ended and b.ended else b if a.ended else a
    if a.t is not None and b.t is not None and a.t != b.t:
        return a if a.t < b.t else b
    return a if a.reads <= b.reads else b


class _Comparison:
    """Pairs the records of two :class:`_Side` per body and fills a :class:`DiffReport`."""

    def __init__(self, report: DiffReport, selection: _Selection, all_bodies: bool, context: int) -> None:
        self.report = report
        self.selection = selection
        self.all_bodies = all_bodies
        self.context = context
        #: The last ``context`` pairs of each body not diverged yet.
        self.recent: dict[str, deque[tuple[int, dict[str, Any], int, dict[str, Any]]]] = {}
        self.diverged: set[str] = set()

    def run(self, a: _Side, b: _Side) -> bool:
        """Read both traces, comparing each pair as it forms; False when it stopped early."""
        while (side := _next_side(a, b)) is not None:
            item = side.read()
            if item is None:
                continue
            line, record = item
            body = record["body"]
            other = b if side is a else a
            waiting = other.unpaired.get(body)
            if waiting:
                other_line, other_record = waiting.popleft()
                if side is a:
                    stop = self.compare(body, line, record, other_line, other_record)
                else:
                    stop = self.compare(body, other_line, other_record, line, record)
                if stop:
                    return False
                continue
            queue = side.unpaired.setdefault(body, deque())
            queue.append(item)
            if len(queue) > MAX_UNPAIRED:
                self.lacking(side, body, NO_MATCH)
                self.report.stopped = (
                    f"stopped at line {line} of {side.name}: {side.name} has {len(queue):,} records of "
                    f"body {body!r} that {other.name} has not matched; {other.name} lacks the body "
                    "or writes it out of step (compare the other bodies with --bodies)"
                )
                return False
        return True

    def compare(self, body: str, line_a: int, a: dict[str, Any], line_b: int, b: dict[str, Any]) -> bool:
        """Compare a pair; True to stop (at a first divergence, unless every body is wanted)."""
        report = self.report
        report.records_compared += 1
        found = _record_differences(a, b, self.selection, report.tolerance)
        if not found:
            if self.context and body not in self.diverged:
                recent = self.recent.get(body)
                if recent is None:
                    recent = self.recent[body] = deque(maxlen=self.context)
                recent.append((line_a, a, line_b, b))
            return False
        report.body_counts[body] += 1
        report.field_counts.update(_unit(divergence.field) for divergence in found)
        if body in self.diverged:
            return False
        first = found[0]
        first.line, first.line_b, first.t, first.body = line_a, line_b, a.get("t"), body
        first.context = [_context_row(first.field, *pair) for pair in self.recent.pop(body, ())]
        report.divergences.append(first)
        self.diverged.add(body)
        return not self.all_bodies

    def lacking(self, side: _Side, body: str, other_value: str) -> None:
        """Report the records of ``body`` that ``side`` holds unpaired: the first (when the body has
        not diverged already) and their count."""
        queue = side.unpaired[body]
        line, record = queue[0]
        self.report.body_counts[body] += len(queue)
        self.report.field_counts["record"] += len(queue)
        if body in self.diverged:
            return
        self.diverged.add(body)
        mine = f"record {side.counts[body] - len(queue) + 1}"
        a, b = (mine, other_value) if side.name == "a" else (other_value, mine)
        self.report.divergences.append(
            Divergence(line, record.get("t"), body, "record", a, b, line_b=None if side.name == "a" else line)
        )

    def finish(self, a: _Side, b: _Side) -> None:
        """At the ends of both traces: the records one has that the other lacks, and the bodies."""
        for side, other in ((a, b), (b, a)):
            for body, queue in side.unpaired.items():
                if queue:
                    self.lacking(side, body, END_OF_TRACE if other.counts[body] else NO_SUCH_BODY)
        self.report.missing_bodies = {
            "a": [body for body in b.counts if not a.counts[body]],
            "b": [body for body in a.counts if not b.counts[body]],
        }


def _jsonable(value: Any) -> Any:
    """``value`` with each non-finite float as the string JSON's extensions spell it."""
    if isinstance(value, float) and not math.isfinite(value):
        return "NaN" if value != value else "Infinity" if value > 0 else "-Infinity"
    if isinstance(value, list):
        return [_jsonable(item) for item in value]
    if isinstance(value, dict):
        return {key: _jsonable(item) for key, item in value.items()}
    return value
