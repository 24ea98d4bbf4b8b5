"""``Plane``: a unit normal ``N`` and offset ``d``, the points p with N·p + d = 0; and ``Ray``."""

from __future__ import annotations

from enum import IntEnum
from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.math.vector import Vector3, zero_vector
from acphys.precision import f32

_new = object.__new__

if TYPE_CHECKING:
    from acphys.geometry.bbox import BBox


class Sidedness(IntEnum):
    """Retail ``Sidedness`` (acclient.h:2527)."""

    POSITIVE = 0
    NEGATIVE = 1
    IN_PLANE = 2
    CROSSING = 3


class Ray:
    """Retail ``Ray`` (acclient.h:32617): start point ``pt``, direction ``dir``, ``length`` (a ``float``)."""

    __slots__ = ("dir", "length", "pt")

    def __init__(self, pt: Vector3, direction: Vector3, length: float = 0.0) -> None:
        self.pt = pt.copy()
        self.dir = direction.copy()
        self.length = f32(length)

    def __repr__(self) -> str:
        return f"Ray(pt={self.pt!r}, dir={self.dir!r}, length={self.length!r})"


class Plane:
    """Retail ``Plane`` (acclient.h:30682): ``{Vector3 N; float d}``; ``d`` is narrowed to float32
    when the plane is built, as every store into it is."""

    __slots__ = ("N", "d")

    def __init__(self, normal: Vector3 | None = None, d: float = 0.0) -> None:
        self.N = normal.copy() if normal is not None else zero_vector()
        self.d = f32(d)

    @classmethod
    def horizontal(cls, z: float) -> Plane:
        """The upward-facing horizontal plane through height ``z``."""
        return cls(Vector3(0.0, 0.0, 1.0), -z)

    @classmethod
    def from_point(cls, normal: Vector3, point: Vector3) -> Plane:
        """The plane with normal ``normal`` through ``point``: ``d = -(N·point)``.

        Retail: Plane::Plane @ 0x00536A20 (acclient.c:358518)
        """
        return cls(normal, -(point.z * normal.z + point.y * normal.y + point.x * normal.x))

    def copy(self) -> Plane:
        plane = _new(Plane)
        plane.N = self.N.copy()
        plane.d = self.d
        return plane

    def set(self, other: Plane) -> None:
        self.N.set(other.N)
        self.d = other.d

    def compute_time_of_intersection(self, ray: Ray) -> tuple[bool, float | None]:
        """Where along ``ray`` (in units of ``ray.dir``) the plane is crossed.

        Returns ``(hit, time)``. A ray within EPSILON of parallel (``|N·dir| < EPSILON``) gives
        ``(False, None)`` and retail leaves ``time`` unwritten; otherwise ``time`` is
        ``(N·pt + d) * (-1 / N·dir)``, always written, and ``hit`` is ``time >= 0``.

        Retail: Plane::compute_time_of_intersection @ 0x00538320 (acclient.c:359592)
        """
        n = self.N
        along = ray.dir.z * n.z + ray.dir.y * n.y + ray.dir.x * n.x
        if not abs(along) >= EPSILON:
            return False, None
        time = (ray.pt.z * n.z + ray.pt.y * n.y + ray.pt.x * n.x + self.d) * (-1.0 / along)
        return time >= 0.0, time

    def snap_to_plane(self, offset: Vector3) -> None:
        """Give the displacement ``offset`` the z that keeps it in the plane: ``-(Nx·x + Ny·y) / Nz``.

        Retail evaluates it as ``-(x·Nx + y·Ny + 0·Nz + d)/Nz - (1/Nz)·(-d)``, so ``d`` cancels only
        up to rounding; that expression is kept, and stored into the float ``offset.z``. Nothing
        happens when ``|N.z| <= EPSILON``.

        Retail: Plane::snap_to_plane @ 0x00509C50 (acclient.c:311526)
        """
        n = self.N
        if abs(n.z) > EPSILON:
            inv = 1.0 / n.z
            offset.z = f32(-(offset.y * n.y + offset.x * n.x + n.z * 0.0 + self.d) * inv - inv * -self.d)

    def set_height(self, vc: Vector3) -> bool:
        """Move the point ``vc`` vertically onto the plane; False (``vc`` untouched) if ``|N.z| <= EPSILON``.

        Retail: Plane::set_height @ 0x0052F050 (acclient.c:351337)
        """
        n = self.N
        if abs(n.z) <= EPSILON:
            return False
        vc.z = f32(-((vc.y * n.y + vc.x * n.x + self.d) / n.z))
        return True

    def which_side2(self, v: Vector3, bias: float, epsilon: float) -> Sidedness:
        """Side of the plane ``v`` lies on, its distance shifted by ``bias``, within ``±epsilon`` in-plane.

        Retail: Plane::which_side2 @ 0x006B61E0 (acclient.c:719915)
        """
        dist = v.z * self.N.z + v.y * self.N.y + v.x * self.N.x + self.d + bias
        if dist <= epsilon:
            return Sidedness.IN_PLANE if dist >= -epsilon else Sidedness.NEGATIVE
        return Sidedness.POSITIVE

    def intersect_box(self, box: BBox) -> Sidedness:
        """POSITIVE or NEGATIVE when all eight corners of ``box`` are more than EPSILON on that side,
        else CROSSING (a corner within EPSILON counts as crossing; never IN_PLANE).

        Retail: Plane::intersect_box @ 0x005AA170 (acclient.c:467717)
        """
        sides = {self.which_side2(c, 0.0, EPSILON) for c in box.corners()}
        if len(sides) == 1 and Sidedness.IN_PLANE not in sides:
            return sides.pop()
        return Sidedness.CROSSING

    def __repr__(self) -> str:
        return f"Plane(N={self.N!r}, d={self.d!r})"
