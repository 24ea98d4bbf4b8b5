"""``BBox``: an axis-aligned box, and how retail moves boxes between frames."""

from __future__ import annotations

from acphys.math.position import Position
from acphys.math.vector import Vector3

_new = object.__new__


class BBox:
    """Retail ``BBox``: ``m_vMin`` and ``m_vMax``."""

    __slots__ = ("max", "min")

    def __init__(self, box_min: Vector3, box_max: Vector3) -> None:
        self.min = box_min.copy()
        self.max = box_max.copy()

    def __repr__(self) -> str:
        return f"BBox({self.min!r}, {self.max!r})"

    def corners(self) -> tuple[Vector3, ...]:
        """The eight corners, min and max first (the order ``LocalToGlobal`` visits them)."""
        lo, hi = self.min, self.max
        return (
            lo,
            hi,
            Vector3(hi.x, hi.y, lo.z),
            Vector3(hi.x, lo.y, hi.z),
            Vector3(lo.x, hi.y, hi.z),
            Vector3(lo.x, hi.y, lo.z),
            Vector3(hi.x, lo.y, lo.z),
            Vector3(lo.x, lo.y, hi.z),
        )

    def adjust_bbox(self, v: Vector3) -> None:
        """Grow the box to hold ``v``.

        Retail: BBox::AdjustBBox @ 0x00534150 (acclient.c:356168)
        """
        self.min.x = min(self.min.x, v.x)
        self.min.y = min(self.min.y, v.y)
        self.min.z = min(self.min.z, v.z)
        self.max.x = max(self.max.x, v.x)
        self.max.y = max(self.max.y, v.y)
        self.max.z = max(self.max.z, v.z)

    @classmethod
    def around(cls, points: list[Vector3]) -> BBox:
        """The box around ``points`` (the first point, then ``adjust_bbox``); zero box for none.

        Retail: CGfxObj::init_end @ 0x00534200 (acclient.c:356199)
        """
        if not points:
            return cls(Vector3(), Vector3())
        box = cls(points[0], points[0])
        for p in points[1:]:
            box.adjust_bbox(p)
        return box

    @classmethod
    def local_to_global(cls, from_box: BBox, from_pos: Position, to_pos: Position) -> BBox:
        """The axis-aligned box around ``from_box``'s corners taken from ``from_pos``'s frame into
        ``to_pos``'s landblock (``to_pos``'s frame is not used, only its cell id), each corner by
        :meth:`Position.localtoglobal <acphys.math.position.Position.localtoglobal>`.

        Retail: BBox::LocalToGlobal @ 0x005B2120 (acclient.c:476912)
        """
        return cls.around([to_pos.localtoglobal(from_pos, c) for c in from_box.corners()])

    @classmethod
    def local_to_local(cls, from_box: BBox, from_pos: Position, to_pos: Position) -> BBox:
        """The axis-aligned box around ``from_box``'s corners taken from ``from_pos``'s frame into
        ``to_pos``'s frame (across landblocks).

        Retail: BBox::LocalToLocal @ 0x005B1E60 (acclient.c:476802)
        """
        return cls.around([to_pos.localtolocal(from_pos, c) for c in from_box.corners()])
