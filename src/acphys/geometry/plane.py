"""``Plane``: a unit normal ``N`` and offset ``d``, the points p with N·p + d = 0."""

from __future__ import annotations

from acphys.math.vector import Vector3


class Plane:
    """Retail ``Plane`` (acclient.h): ``{Vector3 N; float d}``."""

    __slots__ = ("N", "d")

    def __init__(self, normal: Vector3 | None = None, d: float = 0.0) -> None:
        self.N = normal.copy() if normal is not None else Vector3()
        self.d = float(d)

    @classmethod
    def horizontal(cls, z: float) -> Plane:
        """The upward-facing horizontal plane through height ``z``."""
        return cls(Vector3(0.0, 0.0, 1.0), -z)

    def copy(self) -> Plane:
        return Plane(self.N, self.d)

    def set(self, other: Plane) -> None:
        self.N.set(other.N)
        self.d = other.d

    def __repr__(self) -> str:
        return f"Plane(N={self.N!r}, d={self.d!r})"
