"""``Position``: a cell id and a frame local to that cell's landblock."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from acphys.constants import BLOCK_LENGTH
from acphys.math.cell_id import format_cell_id, get_block_offset
from acphys.math.frame import Frame
from acphys.math.vector import Vector3, float_array
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    import numpy as np

_new = object.__new__


class Position:
    """Retail ``Position`` (acclient.h:30658): ``objcell_id`` plus a landblock-local frame."""

    __slots__ = ("frame", "objcell_id")

    def __init__(self, objcell_id: int = 0, frame: Frame | None = None) -> None:
        self.objcell_id = objcell_id
        self.frame = frame.copy() if frame is not None else Frame()

    def copy(self) -> Position:
        other = _new(Position)
        other.objcell_id = self.objcell_id
        other.frame = self.frame.copy()
        return other

    def __repr__(self) -> str:
        return f"Position({format_cell_id(self.objcell_id)}, {self.frame!r})"

    def to_numpy(self) -> np.ndarray:
        """The frame's ``[x, y, z, qw, qx, qy, qz]`` (landblock-local, in the landblock of
        ``objcell_id``, which is not in the array), a new float64 array of shape (7,).
        ``numpy.asarray(position)`` gives the same."""
        return self.frame.to_numpy()

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        """``numpy.asarray(position)``: :meth:`to_numpy`, as ``dtype`` when one is given."""
        f = self.frame
        o = f.origin
        return float_array((o.x, o.y, o.z, f.qw, f.qx, f.qy, f.qz), dtype, copy, "Position")

    def global_origin(self) -> tuple[float, float, float]:
        """The origin in one frame for the whole map, as three doubles: landblock ``0xXXYY``
        starts at (XX·192, YY·192) m, so a path crossing a landblock seam stays continuous."""
        block = self.objcell_id >> 16
        o = self.frame.origin
        return ((block >> 8) * BLOCK_LENGTH + o.x, (block & 0xFF) * BLOCK_LENGTH + o.y, o.z)

    @property
    def origin(self) -> Vector3:
        return self.frame.origin

    def get_offset(self, other: Position) -> Vector3:
        """The vector from this position's origin to ``other``'s, across landblocks.

        ``other``'s y and z, moved into this landblock, are spilled to ``float``; its x is not
        (acclient.c:311697-311703).

        Retail: Position::get_offset @ 0x00509F60 (acclient.c:311690)
        """
        block = get_block_offset(self.objcell_id, other.objcell_id)
        o, s = other.frame.origin, self.frame.origin
        y, z = f32(block.y + o.y), f32(block.z + o.z)
        v = _new(Vector3)
        v.x, v.y, v.z = unpack3(pack3(block.x + o.x - s.x, y - s.y, z - s.z))
        return v

    def localtoglobal_offset(self, other: Position, v: Vector3) -> Vector3:
        """The vector from this origin to the point ``v`` local to ``other``'s frame.

        The point is taken to global summing its y term first; the global z, and x and z
        moved into this landblock, are spilled to ``float`` (acclient.c:314684-314694).

        Retail: Position::get_offset @ 0x0050D920 (acclient.c:314676)
        """
        block = get_block_offset(self.objcell_id, other.objcell_id)
        m, o, s = other.frame.m, other.frame.origin, self.frame.origin
        gx = m[3] * v.y + m[0] * v.x + m[6] * v.z + o.x
        gy = m[4] * v.y + m[1] * v.x + m[7] * v.z + o.y
        gz = f32(m[5] * v.y + m[2] * v.x + m[8] * v.z + o.z)
        x, z = f32(block.x + gx), f32(block.z + gz)
        r = _new(Vector3)
        r.x, r.y, r.z = unpack3(pack3(x - s.x, block.y + gy - s.y, z - s.z))
        return r

    def localtoglobal(self, other: Position, v: Vector3) -> Vector3:
        """The point ``v`` local to ``other``'s frame, in this position's landblock.

        Each row sums its y term first, and the global point is stored as ``float`` before the
        landblock offset is added (acclient.c:147151-147160).

        Retail: Position::localtoglobal @ 0x00456180 (acclient.c:147140)
        """
        m, o = other.frame.m, other.frame.origin
        gx, gy, gz = unpack3(
            pack3(
                m[3] * v.y + m[0] * v.x + m[6] * v.z + o.x,
                m[4] * v.y + m[1] * v.x + m[7] * v.z + o.y,
                m[5] * v.y + m[2] * v.x + m[8] * v.z + o.z,
            )
        )
        block = get_block_offset(self.objcell_id, other.objcell_id)
        r = _new(Vector3)
        r.x, r.y, r.z = unpack3(pack3(block.x + gx, block.y + gy, block.z + gz))
        return r

    def localtoglobalvec(self, v: Vector3) -> Vector3:
        """The vector ``v`` rotated by this frame, each row summing its y term first (``Frame``'s
        own sums the z term first, and rounds differently).

        Retail: Position::localtoglobalvec @ 0x00456220 (acclient.c:147164)
        """
        m = self.frame.m
        r = _new(Vector3)
        r.x, r.y, r.z = unpack3(
            pack3(
                m[3] * v.y + m[0] * v.x + m[6] * v.z,
                m[4] * v.y + m[1] * v.x + m[7] * v.z,
                m[5] * v.y + m[2] * v.x + m[8] * v.z,
            )
        )
        return r

    def globaltolocalvec(self, v: Vector3) -> Vector3:
        """A global vector rotated into this frame, each row summing its y term first.

        Retail: Position::globaltolocalvec @ 0x0050C420 (acclient.c:313494)
        """
        m = self.frame.m
        r = _new(Vector3)
        r.x, r.y, r.z = unpack3(
            pack3(
                m[1] * v.y + m[0] * v.x + m[2] * v.z,
                m[4] * v.y + m[3] * v.x + m[5] * v.z,
                m[7] * v.y + m[6] * v.x + m[8] * v.z,
            )
        )
        return r

    def localtolocal(self, other: Position, v: Vector3) -> Vector3:
        """The point ``v`` local to ``other``'s frame, expressed in this position's frame (across blocks).

        Retail inlines :meth:`localtoglobal` (the same sums and ``float`` stores,
        acclient.c:143803-143813), then takes the point into this frame.

        Retail: Position::localtolocal @ 0x004527F0 (acclient.c:143794)
        """
        return self.frame.globaltolocal(self.localtoglobal(other, v))

    def determine_quadrant(self, height: float, p: Position) -> int:
        """Where ``p``'s origin lies around this position: 0x8 left / 0x10 right, 0x20 front /
        0x40 behind, 0x1 high / 0x2 middle / 0x4 low (thirds of ``height``), in this local frame.

        Retail: Position::determine_quadrant @ 0x005A9580 (acclient.c:467065)
        """
        hit = self.localtolocal(p, Vector3())
        quadrant = 0x10 if hit.x >= 0.0 else 0x8
        quadrant |= 0x20 if hit.y >= 0.0 else 0x40
        if height * 0.333333333 > hit.z:
            return quadrant | 0x4
        if height * 0.66666667 > hit.z:
            return quadrant | 0x2
        return quadrant | 0x1
