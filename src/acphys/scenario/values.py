"""Typed readers for scenario values: each names the file and key in its error."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from acphys.flags import PhysicsState, flag_names, parse_flag_names
from acphys.math.vector import Vector3
from acphys.motion.commands import MOTION_IDS, STYLE_MASK, motion_id
from acphys.precision import FLT_MAX, f32


class ScenarioError(ValueError):
    """A scenario that cannot be loaded; the message says where and what, one line per problem.

    ``problems`` lists them (a scenario read in full reports every independent problem at once).
    """

    def __init__(self, message: str, problems: list[str] | None = None) -> None:
        super().__init__(message)
        self.problems = problems if problems is not None else [message]


_ARRAY_HEADER = re.compile(r"\[\[\s*([A-Za-z0-9_.\-]+)\s*\]\]")
_TABLE_HEADER = re.compile(r"\[\s*([A-Za-z0-9_.\-]+)\s*\]")
_KEY = re.compile(r"([A-Za-z0-9_\-]+)\s*=")


class TomlLines:
    """Where the tables and keys of a TOML text are: the line of ``[[body]]`` number 2, of its
    ``origin = ...``. tomllib gives no positions for values, so this scans the text's headers and
    ``key =`` lines (enough for the scenario format; a key it cannot place has no line)."""

    def __init__(self, text: str) -> None:
        #: table path ("body[2]", "setup.ball", "motion_table.runner.cycle[0]") -> header line, keys
        self.tables: dict[str, tuple[int, dict[str, int]]] = {"": (0, {})}
        #: key path ("body[2].id") -> the text after its ``=``, as written
        self.written: dict[str, str] = {}
        counts: dict[str, int] = {}
        current = ""
        for number, line in enumerate(text.splitlines(), start=1):
            stripped = line.strip()
            if match := _ARRAY_HEADER.match(stripped):
                name = match.group(1)
                index = counts[name] = counts.get(name, -1) + 1
                current = f"{name}[{index}]"
                self.tables[current] = (number, {})
            elif match := _TABLE_HEADER.match(stripped):
                current = match.group(1)
                self.tables[current] = (number, {})
            elif match := _KEY.match(stripped):
                self.tables[current][1].setdefault(match.group(1), number)
                path = f"{current}.{match.group(1)}" if current else match.group(1)
                self.written.setdefault(path, stripped[match.end() :].split("#", 1)[0].strip())

    def line(self, key: str) -> int | None:
        """The line of ``key`` (a scenario key path), else of the table holding it, else None."""
        table = max((t for t in self.tables if _within(key, t)), key=len)
        header, keys = self.tables[table]
        rest = key[len(table) :].lstrip(".")
        first = re.split(r"[.\[]", rest, maxsplit=1)[0]
        return keys.get(first, header or None) if rest else (header or None)


class Skipped(Exception):
    """A part of a scenario that uses another part which already failed: its problem is already
    reported, so this one says nothing (:meth:`Ctx.part` swallows it)."""


def _within(key: str, table: str) -> bool:
    """Whether the key path ``key`` lies in the table path ``table``."""
    return not table or key == table or key.startswith((f"{table}.", f"{table}["))


@dataclass
class Ctx:
    """Where in which file a value came from, for error messages, and the problems found so far.

    ``lines`` (when the TOML text is at hand) adds the line of the key to each message, and a
    table given a label (:meth:`label`: ``body "walker"``) names itself in its keys' messages.
    """

    source: str
    lines: TomlLines | None = None
    problems: list[str] = field(default_factory=list)
    #: Things that load but look like mistakes, one line each (``acphys check`` prints them).
    warnings: list[str] = field(default_factory=list)
    #: The named parts that failed ("setup.ball", "body.walker", ...), so what uses them is skipped.
    failed: set[str] = field(default_factory=set)
    labels: dict[str, str] = field(default_factory=dict)

    def label(self, table: str, text: str) -> None:
        """Name the table path ``table`` ("body[2]") in the messages of its keys."""
        self.labels[table] = text

    def warn(self, key: str, text: str) -> None:
        """Note something that loads but looks like a mistake."""
        self.warnings.append(str(self.fail(key, text)))

    def fail(self, key: str, problem: str) -> ScenarioError:
        where = []
        line = self.lines.line(key) if self.lines is not None else None
        if line is not None:
            where.append(f"line {line}")
        where += [text for table, text in self.labels.items() if table and _within(key, table)]
        trailer = f" ({', '.join(where)})" if where else ""
        return ScenarioError(f"{self.source}: {key}: {problem}{trailer}")

    @contextmanager
    def part(self, name: str | None = None) -> Iterator[None]:
        """Read one independent part of a scenario: its error is recorded and reading goes on.

        A failed part called ``name`` is remembered: :meth:`uses` skips what needs it.
        """
        try:
            yield
        except ScenarioError as error:
            self.problems.extend(error.problems)
            if name is not None:
                self.failed.add(name)
        except Skipped:
            if name is not None:
                self.failed.add(name)

    def uses(self, name: str) -> None:
        """Skip the part being read if it needs ``name`` ("setup.ball") and that part, or the
        whole section holding it ("setup"), failed."""
        if name in self.failed or name.split(".", 1)[0] in self.failed:
            raise Skipped(name)

    def missing(self, section: str, key: str, problem: str) -> ScenarioError:
        """The error for a name that ``section`` ("body") lacks, unless a part of it failed before
        its name could be read (the name may be that one's): then the part being read is skipped."""
        self.uses(f"{section}.?")
        return self.fail(key, problem)

    def check(self) -> None:
        """Raise every problem recorded, one line each."""
        if self.problems:
            raise ScenarioError("\n".join(self.problems), list(self.problems))


def table(ctx: Ctx, key: str, value: Any, allowed: tuple[str, ...]) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise ctx.fail(key, f"expected a table, got {kind(value)}")
    unknown = [name for name in value if name not in allowed]
    if unknown:
        raise ctx.fail(
            f"{key}.{unknown[0]}" if key else unknown[0],
            f"unknown key (expected one of: {', '.join(allowed)})",
        )
    return value


def number(ctx: Ctx, key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ctx.fail(key, f"expected a number, got {kind(value)}")
    if not math.isfinite(value):
        raise ctx.fail(key, f"expected a finite number, got {value}")
    return float(value)


def ranged(ctx: Ctx, key: str, value: Any, low: float, high: float, *, open_low: bool = False) -> float:
    result = number(ctx, key, value)
    if result < low or result > high or (open_low and result == low):
        bracket = "(" if open_low else "["
        raise ctx.fail(key, f"expected a number in {bracket}{low:g}, {high:g}], got {result:g}")
    return result


def float32(ctx: Ctx, key: str, value: Any, low: float, high: float, *, open_low: bool = False) -> float:
    """A number in ``[low, high]`` that the engine keeps in a ``float``: the float32 that retail's
    data would hold (see :mod:`acphys.precision`). The range is checked on the number as written.

    Scenario times (``duration``, ``driver_hz``, an event's ``at``) are the harness's own and stay
    double; vectors are float32 already (:func:`vector` makes a ``Vector3``).
    """
    return f32(ranged(ctx, key, value, low, high, open_low=open_low))


#: How far from its own origin a shape's geometry may reach, in metres (a wall, a house, a tower):
#: bounded so that a typo cannot make one object shadow into millions of cells.
SHAPE_EXTENT = 1000.0


def _three_numbers(ctx: Ctx, key: str, value: Any) -> tuple[float, float, float]:
    if not isinstance(value, list) or len(value) != 3:
        raise ctx.fail(key, f"expected a list of 3 numbers, got {kind(value)}")
    x, y, z = (number(ctx, f"{key}[{i}]", item) for i, item in enumerate(value))
    return x, y, z


def vector(ctx: Ctx, key: str, value: Any) -> Vector3:
    """Three numbers as a ``Vector3``: the float32s retail stores, so each must be in float32 range."""
    components = _three_numbers(ctx, key, value)
    for i, component in enumerate(components):
        if abs(component) > FLT_MAX:
            raise ctx.fail(f"{key}[{i}]", f"{component:g} is beyond the float32 range (±{FLT_MAX:.4g})")
    return Vector3(*components)


def local_point(ctx: Ctx, key: str, value: Any) -> Vector3:
    """A point of a shape, in its own frame: within ``SHAPE_EXTENT`` of the origin on each axis."""
    point = vector(ctx, key, value)
    if max(abs(point.x), abs(point.y), abs(point.z)) > SHAPE_EXTENT:
        raise ctx.fail(
            key,
            f"each coordinate must be within ±{SHAPE_EXTENT:g} m of the shape's origin, "
            f"got ({point.x:g}, {point.y:g}, {point.z:g})",
        )
    return point


def string(ctx: Ctx, key: str, value: Any) -> str:
    if not isinstance(value, str) or not value:
        raise ctx.fail(key, f"expected a non-empty string, got {kind(value)}")
    return value


def boolean(ctx: Ctx, key: str, value: Any) -> bool:
    if not isinstance(value, bool):
        raise ctx.fail(key, f"expected true or false, got {kind(value)}")
    return value


def _id(ctx: Ctx, key: str, value: Any, what: str) -> int:
    """An id as an integer or a hex string; ``what`` names it with an example in the error."""
    if isinstance(value, str):
        try:
            number = int(value, 16)
        except ValueError:
            raise ctx.fail(key, f"expected {what}, got {value!r}") from None
        if not value.lower().startswith("0x"):
            ctx.warn(key, f'"{value}" is read as hex, 0x{number:X}: write "0x{value}" to say so')
        return number
    if isinstance(value, int) and not isinstance(value, bool):
        written = ctx.lines.written.get(key, "") if ctx.lines is not None else ""
        if written.isdigit() and len(written) in (4, 8):
            ctx.warn(key, f'{written} is read as decimal, 0x{value:X}: write "0x{written}" if hex was meant')
        return value
    raise ctx.fail(key, f"expected {what}, got {kind(value)}")


def landblock(ctx: Ctx, key: str, value: Any) -> int:
    """A landblock id ``0xXXYY`` as an integer or a hex string."""
    number = _id(ctx, key, value, 'a landblock id like "0xA9B4"')
    if not 0 <= number <= 0xFEFE:
        raise ctx.fail(key, f"landblock 0x{number:X} is outside the world (0x0000-0xFEFE)")
    return number


def object_id(ctx: Ctx, key: str, value: Any) -> int:
    """A 32-bit object id (a server guid such as ``"0x50000001"``), non-zero."""
    number = _id(ctx, key, value, 'an object id like "0x50000001"')
    if not 0 < number <= 0xFFFFFFFF:
        raise ctx.fail(key, f"object id {number:#x} is not a non-zero 32-bit id")
    return number


def state(ctx: Ctx, key: str, value: Any) -> PhysicsState:
    if not isinstance(value, list) or not all(isinstance(name, str) for name in value):
        raise ctx.fail(key, f"expected a list of state names, got {kind(value)}")
    try:
        return parse_flag_names(PhysicsState, value)
    except KeyError as error:
        known = ", ".join(flag_names(PhysicsState(sum(PhysicsState))))
        raise ctx.fail(key, f"unknown state {error.args[0]!r} (known: {known})") from None


def list_of_tables(ctx: Ctx, key: str, value: Any) -> list[Any]:
    if not isinstance(value, list):
        raise ctx.fail(key, f"expected an array of tables ([[{key}]]), got {kind(value)}")
    return value


def kind(value: Any) -> str:
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, (int, float)):
        return f"the number {value}"
    if isinstance(value, str):
        return f"the string {value!r}"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, dict):
        return "a table"
    return type(value).__name__


#: The fastest spin a scenario may give, in degrees per second about each axis (100 turns a second).
MAX_SPIN = 36000.0


def degrees_per_second(ctx: Ctx, key: str, value: Any) -> Vector3:
    """An angular velocity given in degrees per second (at most ``MAX_SPIN`` about each axis),
    returned in radians per second."""
    x, y, z = _three_numbers(ctx, key, value)
    if max(abs(x), abs(y), abs(z)) > MAX_SPIN:
        raise ctx.fail(key, f"each component must be within ±{MAX_SPIN:g} deg/s, got ({x:g}, {y:g}, {z:g})")
    return Vector3(math.radians(x), math.radians(y), math.radians(z))


def motion(ctx: Ctx, key: str, value: Any) -> int:
    """A retail motion or style, by name or id."""
    if isinstance(value, str) and value.startswith("0x"):
        try:
            value = int(value, 16)
        except ValueError:
            raise ctx.fail(key, f"expected a motion name or id, got {value!r}") from None
    if not isinstance(value, (str, int)) or isinstance(value, bool):
        raise ctx.fail(key, f"expected a motion name or id, got {kind(value)}")
    try:
        return motion_id(value)
    except KeyError as error:
        raise ctx.fail(
            key, f"{error.args[0]} (retail names such as {', '.join(list(MOTION_IDS)[3:8])})"
        ) from None


def style(ctx: Ctx, key: str, value: Any) -> int:
    """A retail style (stance), by name or id."""
    result = motion(ctx, key, value)
    if not result & STYLE_MASK:
        raise ctx.fail(key, f"0x{result:08X} is not a style (styles are NonCombat, HandCombat, ...)")
    return result
