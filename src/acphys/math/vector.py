"""A three-component vector with the retail ``AC1Legacy::Vector3`` helpers."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

from acphys.constants import EPSILON
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    import numpy as np

#: ``object.__new__``: the operators below build their results with it and set the slots
#: directly, skipping ``__init__``. Constructing vectors is the commonest thing a body step does.
_new = object.__new__


class Vector3:
    """A mutable 3-vector of float32 values (retail ``AC1Legacy::Vector3``: three ``float`` fields).

    Every component is a float32 (see :mod:`acphys.precision`): the constructor
    and the operators narrow what they store, as retail's operators write a
    ``Vector3``; products and sums that return a scalar (:meth:`dot`,
    :meth:`length_squared`) stay double. Code that assigns a component
    directly narrows it first. Arithmetic operators return new vectors; the
    retail in-place helpers (:meth:`normalize_check_small`) mutate, as retail's do.
    """

    __slots__ = ("x", "y", "z")

    def __init__(self, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> None:
        self.x, self.y, self.z = unpack3(pack3(x, y, z))

    def copy(self) -> Vector3:
        v = _new(Vector3)
        v.x = self.x
        v.y = self.y
        v.z = self.z
        return v

    def set(self, other: Vector3) -> None:
        """Copy ``other``'s components into this vector."""
        self.x, self.y, self.z = other.x, other.y, other.z

    def __iter__(self) -> Iterator[float]:
        yield self.x
        yield self.y
        yield self.z

    def __repr__(self) -> str:
        return f"Vector3({self.x!r}, {self.y!r}, {self.z!r})"

    def to_numpy(self) -> np.ndarray:
        """``[x, y, z]`` as a new float64 array of shape (3,) (exact: each component is a float32)."""
        return float_array((self.x, self.y, self.z))

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        """``numpy.asarray(vector)``: :meth:`to_numpy`, as ``dtype`` when one is given."""
        return float_array((self.x, self.y, self.z), dtype, copy, "Vector3")

    def __add__(self, other: Vector3) -> Vector3:
        v = _new(Vector3)
        v.x, v.y, v.z = unpack3(pack3(self.x + other.x, self.y + other.y, self.z + other.z))
        return v

    def __sub__(self, other: Vector3) -> Vector3:
        v = _new(Vector3)
        v.x, v.y, v.z = unpack3(pack3(self.x - other.x, self.y - other.y, self.z - other.z))
        return v

    def __mul__(self, scalar: float) -> Vector3:
        v = _new(Vector3)
        v.x, v.y, v.z = unpack3(pack3(self.x * scalar, self.y * scalar, self.z * scalar))
        return v

    __rmul__ = __mul__

    def __truediv__(self, scalar: float) -> Vector3:
        """Divide as retail does, by multiplying by the reciprocal: ``scalar`` is a ``float``
        parameter, and the reciprocal is stored back into its slot, so x is scaled by the
        double reciprocal and y and z by its float32 (acclient.c:146874-146881).

        Retail: Vector3::operator/ @ 0x00455DE0 (acclient.c:146865)
        """
        inv = 1.0 / f32(scalar)
        inv32 = f32(inv)
        v = _new(Vector3)
        v.x, v.y, v.z = unpack3(pack3(inv * self.x, inv32 * self.y, inv32 * self.z))
        return v

    def __neg__(self) -> Vector3:
        v = _new(Vector3)
        v.x, v.y, v.z = -self.x, -self.y, -self.z  # exact
        return v

    def exactly_equals(self, other: Vector3) -> bool:
        """Bitwise-value equality (Python's ``==`` is the retail epsilon test)."""
        return self.x == other.x and self.y == other.y and self.z == other.z

    def __eq__(self, other: object) -> bool:
        """Retail ``AC1Legacy::Vector3::operator==``: every axis within EPSILON.

        Retail: AC1Legacy::Vector3::operator== @ 0x00509F10 (acclient.c:311682)
        """
        if not isinstance(other, Vector3):
            return NotImplemented
        return (
            abs(self.x - other.x) <= EPSILON
            and abs(self.y - other.y) <= EPSILON
            and abs(self.z - other.z) <= EPSILON
        )

    __hash__ = None  # type: ignore[assignment]  # mutable, epsilon-equal: not hashable

    def dot(self, other: Vector3) -> float:
        return self.x * other.x + self.y * other.y + self.z * other.z

    def cross(self, other: Vector3) -> Vector3:
        return Vector3(
            self.y * other.z - self.z * other.y,
            self.z * other.x - self.x * other.z,
            self.x * other.y - self.y * other.x,
        )

    def length_squared(self) -> float:
        return self.x * self.x + self.y * self.y + self.z * self.z

    def length(self) -> float:
        return math.sqrt(self.length_squared())

    def is_zero(self) -> bool:
        """Every axis strictly within EPSILON of zero.

        Retail: AC1Legacy::Vector3::is_zero @ 0x0050E7B0 (acclient.c:315576)
        """
        return abs(self.x) < EPSILON and abs(self.y) < EPSILON and abs(self.z) < EPSILON

    def is_finite(self) -> bool:
        return math.isfinite(self.x) and math.isfinite(self.y) and math.isfinite(self.z)

    def normalized(self) -> Vector3:
        """This vector scaled to unit length, with no small-length check.

        Retail: AC1Legacy::Vector3::normalize @ 0x00452400 (acclient.c:143600)
        """
        inv = 1.0 / math.sqrt(self.length_squared())
        return Vector3(inv * self.x, inv * self.y, inv * self.z)

    def normalize_check_small(self) -> bool:
        """Normalise in place unless shorter than EPSILON; True means "too small, untouched".

        Retail: AC1Legacy::Vector3::normalize_check_small @ 0x00452460 (acclient.c:143621)
        """
        length = math.sqrt(self.length_squared())
        if length < EPSILON:
            return True
        inv = 1.0 / length
        self.x, self.y, self.z = unpack3(pack3(inv * self.x, inv * self.y, inv * self.z))
        return False

    def get_heading(self) -> float:
        """The compass heading of the horizontal part of this vector, in degrees.

        0 is +y (north), 90 is +x (east); a vector with no horizontal length
        has heading 0. See :meth:`acphys.math.frame.Frame.get_heading` for the
        convention.

        Retail: AC1Legacy::Vector3::get_heading @ 0x004575D0 (acclient.c:148166)
        """
        flat = Vector3(self.x, self.y, 0.0)
        if flat.normalize_check_small():
            return 0.0
        return compass_heading(flat.x, flat.y)


def float_array(
    values: Iterable[float], dtype: Any = None, copy: bool | None = None, what: str = ""
) -> np.ndarray:
    """``values`` as a new float64 NumPy array (as ``dtype`` when given): what the math classes'
    ``to_numpy`` and ``__array__`` give. Their values are Python floats, not an array, so a
    ``copy=False`` request (NumPy 2's ``numpy.asarray(x, copy=False)``) is a ValueError.
    NumPy is imported here, on first use, so that ``import acphys`` does not load it.
    """
    if copy is False:
        raise ValueError(f"a {what} is not stored as an array: it cannot be viewed without a copy")
    import numpy as np

    array = np.array(tuple(values), dtype=np.float64)
    return array if dtype is None else array.astype(dtype, copy=False)


def vectors_of_float32(rows: Iterable[tuple[float, float, float]]) -> list[Vector3]:
    """``Vector3(x, y, z)`` of each row whose components are float32 values already (as a
    float32 array's ``tolist`` gives them), without the constructor's narrowing."""
    vectors = []
    for x, y, z in rows:
        v = _new(Vector3)
        v.x = x
        v.y = y
        v.z = z
        vectors.append(v)
    return vectors


def zero_vector() -> Vector3:
    """``Vector3()`` without the constructor's narrowing, for hot paths."""
    v = _new(Vector3)
    v.x = v.y = v.z = 0.0
    return v


def compass_heading(x: float, y: float) -> float:
    """``fmod(450 - atan2(y, x) in degrees, 360)``: the compass bearing of (x, y).

    Hex-Rays prints this retail idiom as ``atan2(x, y)``; retail's own
    consumers (``Frame::set_heading`` builds ``(sin d, cos d)`` and expects
    ``get_heading`` to give ``d`` back) need the mathematical ``atan2(y, x)``.
    The test that pins this is ``tests/unit/test_frame.py::TestHeading``.
    """
    return math.fmod(450.0 - math.degrees(math.atan2(y, x)), 360.0)
