"""``Sphere``: a collision sphere, centre local to its owner's frame."""

from __future__ import annotations

from acphys.math.vector import Vector3


class Sphere:
    """Retail ``CSphere`` (acclient.h): ``{Vector3 center; float radius}``."""

    __slots__ = ("center", "radius")

    def __init__(self, center: Vector3, radius: float) -> None:
        self.center = center.copy()
        self.radius = float(radius)

    def copy(self) -> Sphere:
        return Sphere(self.center, self.radius)

    def __repr__(self) -> str:
        return f"Sphere({self.center!r}, {self.radius!r})"


#: ``dummy_sphere``: what a transition sweeps for an object with no spheres (r 0.1 at z 0.1).
DUMMY_SPHERE = Sphere(Vector3(0.0, 0.0, 0.1), 0.1)
