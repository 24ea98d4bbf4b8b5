"""Vectors, frames, positions and cell ids: the maths every pipeline stage uses."""

from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3

__all__ = ["Frame", "Position", "Vector3"]
