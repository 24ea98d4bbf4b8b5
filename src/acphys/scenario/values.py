"""Typed readers for scenario values: each names the file and key in its error."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from acphys.flags import PhysicsState, flag_names, parse_flag_names
from acphys.inputs import one_line
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
        for number, line in enumerate(text.split("\n"), start=1):  # TOML's newlines only
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
        table = next(t for t in reversed(_tables_holding(key)) if t in self.tables)
        header, keys = self.tables[table]
        rest = key[len(table) :].lstrip(".")
        first = re.split(r"[.\[]", rest, maxsplit=1)[0]
        return keys.get(first, header or None) if rest else (header or None)


#: The deepest a scenario may nest arrays and inline tables. tomllib reads them recursively,
#: two or three Python frames a level, and past about 300 levels hits Python's default recursion
#: limit of 1000 (a RecursionError); the scenario format itself nests at most 5 deep (a solid's
#: polygons of points).
MAX_NESTING = 64
#: The most parts a dotted key (``a.b.c`` has 3) may have: tomllib's time and memory grow with
#: the square of it (a key of 20,000 parts takes a gigabyte; 32 parts keep a file of nothing
#: but such keys to seconds). Scenario keys have at most 3.
MAX_KEY_PARTS = 32
#: The most characters a number may be written with: a float64 needs 17 significant digits, a
#: 5,000-digit integer makes tomllib raise (Python's 4,300-digit limit on converting to int),
#: and one of 100 characters converts to a float or an int of at most 400 bits without trouble.
MAX_NUMBER_CHARS = 100

_STRINGS_AND_COMMENTS = re.compile(
    r'"""(?:[^"\\]++|\\.|""?+(?!"))*+"{3,5}'  # a multi-line basic string
    r"|'''(?:[^']++|''?+(?!'))*+'{3,5}"  # a multi-line literal string
    r'|"(?:[^"\\\n]++|\\.)*+"'  # a basic string
    r"|'[^'\n]*+'"  # a literal string
    r"|#[^\n]*+",  # a comment
    re.DOTALL,
)
_BRACKETS = re.compile(r"[\[{]++|[\]}]++")
# A key part is a bare key or a string (by now an empty ``""`` holding the string's newlines).
_LONG_KEY = re.compile(rf'(?:(?:[A-Za-z0-9_\-]++|"\n*+")[ \t]*+\.[ \t]*+){{{MAX_KEY_PARTS}}}[A-Za-z0-9_\-"]')
_LONG_NUMBER = re.compile(rf"(?<![\w.+\-])(?:[+\-](?=[0-9])|[0-9])[\w.+\-:]{{{MAX_NUMBER_CHARS},}}")


def _blank(match: re.Match[str]) -> str:
    """A string as an empty ``""`` holding its newlines (lines still count); a comment as nothing."""
    text = match.group()
    return "" if text.startswith("#") else '"' + "\n" * text.count("\n") + '"'


def check_toml_limits(source: str, text: str) -> None:
    """Refuse TOML text that would make tomllib recurse too deep, take quadratic time and memory,
    or fail to convert a number: nesting past ``MAX_NESTING``, a key of more than
    ``MAX_KEY_PARTS`` parts, a number longer than ``MAX_NUMBER_CHARS``. Strings and comments are
    left out of the count; the :class:`ScenarioError` names the line and the limit.
    """
    code = _STRINGS_AND_COMMENTS.sub(_blank, text)

    def fail(position: int, problem: str) -> ScenarioError:
        line = code.count("\n", 0, position) + 1
        return ScenarioError(one_line(f"{source}: line {line}: {problem}"))

    if match := _LONG_KEY.search(code):
        raise fail(match.start(), f"a key of more than {MAX_KEY_PARTS} dotted parts (the scenario key limit)")
    if match := _LONG_NUMBER.search(code):
        raise fail(
            match.start(),
            f"a number of {len(match.group()):,} characters, more than the {MAX_NUMBER_CHARS} "
            "a scenario number may have",
        )
    depth = 0
    for match in _BRACKETS.finditer(code):
        if match.group()[0] in "[{":
            depth += match.end() - match.start()
            if depth > MAX_NESTING:
                raise fail(
                    match.start(),
                    f"arrays and inline tables nested deeper than {MAX_NESTING} levels "
                    "(the scenario nesting limit)",
                )
        else:  # an unmatched close is tomllib's to report: count on from 0
            depth = max(0, depth - (match.end() - match.start()))


class Skipped(Exception):
    """A part of a scenario that uses another part which already failed: its problem is already
    reported, so this one says nothing (:meth:`Ctx.part` swallows it)."""


def _tables_holding(key: str) -> list[str]:
    """The table paths the key path ``key`` lies in, outermost first: ``""``, ``"body"``,
    ``"body[2]"`` and ``"body[2].origin"`` for ``"body[2].origin"`` (looked up, not searched
    for, so that a message costs the same in a scenario of ten thousand bodies)."""
    return ["", *(key[:i] for i, char in enumerate(key) if char in ".[" and i), key]


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
        where += [self.labels[table] for table in _tables_holding(key) if table in self.labels]
        trailer = f" ({', '.join(where)})" if where else ""
        # One line whatever the key or a name holds (a TOML key may be "a\nb").
        return ScenarioError(one_line(f"{self.source}: {key}: {problem}{trailer}"))

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
    try:
        result = float(value)
    except OverflowError:  # an integer past the float range
        raise ctx.fail(key, f"expected a finite number, got {kind(value)}") from None
    if not math.isfinite(result):
        raise ctx.fail(key, f"expected a finite number, got {value}")
    return result


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


#: The longest id string read: ``0x`` and 16 hex digits, room for any leading zeros of a 32-bit id.
_ID_CHARS = 18


def _id(ctx: Ctx, key: str, value: Any, what: str) -> int:
    """An id as an integer or a hex string; ``what`` names it with an example in the error."""
    if isinstance(value, str):
        try:
            if len(value) > _ID_CHARS:
                raise ValueError(value)
            number = int(value, 16)
        except ValueError:
            raise ctx.fail(key, f"expected {what}, got {quoted(value)}") from None
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
        raise ctx.fail(key, f"unknown state {quoted(error.args[0])} (known: {known})") from None


def list_of_tables(ctx: Ctx, key: str, value: Any) -> list[Any]:
    if not isinstance(value, list):
        raise ctx.fail(key, f"expected an array of tables ([[{key}]]), got {kind(value)}")
    return value


def at_most(ctx: Ctx, key: str, items: list[Any], most: int, what: str, limit: str) -> list[Any]:
    """``items``, unless there are more than ``most`` of them (a bound on what building costs);
    ``what`` names them ("bodies") and ``limit`` the limit ("MAX_BODIES") in the message."""
    if len(items) > most:
        raise ctx.fail(key, f"{len(items):,} {what}: more than the {most:,} allowed ({limit})")
    return items


#: The most characters of a string a message quotes (a value may be megabytes long).
QUOTED_CHARS = 60


def quoted(text: str) -> str:
    """``text`` as Python writes a string, cut to ``QUOTED_CHARS`` characters for a message."""
    if len(text) <= QUOTED_CHARS:
        return repr(text)
    return f"{text[:QUOTED_CHARS]!r}... ({len(text):,} characters)"


def kind(value: Any) -> str:
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, int) and value.bit_length() > 64:
        return f"a {value.bit_length()}-bit whole number"
    if isinstance(value, (int, float)):
        return f"the number {value}"
    if isinstance(value, str):
        return f"the string {quoted(value)}"
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
    if isinstance(value, str) and len(value) > QUOTED_CHARS:  # longer than any motion name
        raise ctx.fail(key, f"expected a motion name or id, got {quoted(value)}")
    if isinstance(value, str) and value.startswith("0x"):
        try:
            value = int(value, 16)
        except ValueError:
            raise ctx.fail(key, f"expected a motion name or id, got {quoted(value)}") from None
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
