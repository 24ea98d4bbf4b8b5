"""``CylSphere``: a vertical collision cylinder with a rounded bottom, local to its owner's frame."""

from __future__ import annotations

from acphys.math.vector import Vector3


class CylSphere:
    """Retail ``CCylSphere`` (acclient.h:31672): ``{Vector3 low_pt; float height; float radius}``."""

    __slots__ = ("height", "low_pt", "radius")

    def __init__(self, low_pt: Vector3, radius: float, height: float) -> None:
        self.low_pt = low_pt.copy()
        self.radius = float(radius)
        self.height = float(height)

    def copy(self) -> CylSphere:
        return CylSphere(self.low_pt, self.radius, self.height)

    def __repr__(self) -> str:
        return f"CylSphere({self.low_pt!r}, radius={self.radius!r}, height={self.height!r})"
