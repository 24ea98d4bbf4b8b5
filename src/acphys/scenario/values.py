"""Typed readers for scenario values: each names the file and key in its error."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from acphys.flags import PhysicsState, flag_names, parse_flag_names
from acphys.math.vector import Vector3
from acphys.motion.commands import MOTION_IDS, STYLE_MASK, motion_id
from acphys.precision import FLT_MAX, f32


class ScenarioError(ValueError):
    """A scenario that cannot be loaded; the message says where and what."""


@dataclass
class Ctx:
    """Where in which file a value came from, for error messages."""

    source: str

    def fail(self, key: str, problem: str) -> ScenarioError:
        return ScenarioError(f"{self.source}: {key}: {problem}")


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
            return int(value, 16)
        except ValueError:
            raise ctx.fail(key, f"expected {what}, got {value!r}") from None
    if isinstance(value, int) and not isinstance(value, bool):
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
