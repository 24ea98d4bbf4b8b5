"""Where the objects the kernel does not step could answer a sweep: each as balls and columns.

A sweep asks every object shadowed in a cell it inserts into (``CObjCell::find_obj_collisions``).
For an object that is not one of the engine's bodies (a static object: a pillar, a rock, a
crate), the kernel keeps only the places its collision shapes fill, in landblock-global metres
(:func:`reach_shapes`), because ``CPhysicsObj::FindObjCollisions`` answers OK and changes nothing
a step reads when every moving sphere misses them:

* a physics BSP is tried part by part, each first against the part's bounding sphere
  (``CGfxObj::find_obj_collisions`` @ 0x00534700, acclient.c:356514): a **part ball** of that
  sphere at the part's frame and scale, met by the moving spheres as
  ``SPHEREPATH::cache_localspace_sphere`` places them, the local spheres at the check position's
  frame (the global spheres lag behind a sweep step's turn: they are only moved by offsets);
* cylspheres (without a BSP) respond in every arm of ``CCylSphere::intersects_sphere`` @ 0x0053B440
  (acclient.c:362034) only after ``collides_with_sphere`` finds a moving sphere within the radius
  sum horizontally: an upright **column** of the cylinder's radius through its axis;
* spheres (without either) respond only to a moving sphere within the radius sum
  (``CSphere::intersects_sphere`` @ 0x00537FD0, acclient.c:359389): a **ball**.

What asking such an object writes besides is the path's localspace spheres
(``SPHEREPATH::cache_localspace_sphere``), a cache every reader writes first and that the two
paths do not hand each other (:mod:`acphys.fast.pool`). So a sweep farther from all of an
object's balls and columns than the moving spheres' largest radius and :data:`MARGIN` passes it
by in the kernel (:func:`acphys.fast.kernels.sweep.statics_out_of_reach`); a nearer one, or any
sweep in a cell holding an object this cannot bound, runs on the reference path. Not retail: the
kernel's bookkeeping.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from acphys.constants import BLOCK_LENGTH
from acphys.flags import PhysicsState
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.math.position import Position
    from acphys.math.vector import Vector3
    from acphys.physics_obj import PhysicsObj

#: How much farther (m) than touching a shape must be for the kernel to pass its object by: far
#: beyond the float32 rounding of positions (about 3e-5 m at 400 m), far below any shape (the
#: reference's shadow files keep the same margin, ``acphys.world.obj_cell.SHADOW_REACH_MARGIN``).
MARGIN = 0.01
#: A row of :attr:`~acphys.fast.world_arrays.WorldArrays.other_shapes`: x, y, z, radius, kind.
SHAPE_WIDTH = 5
#: Kinds of shape: a ball and a column (only x and y are measured) met by the global spheres, a
#: part ball met by the local spheres at the check position's frame.
BALL, COLUMN, PART_BALL = 0.0, 1.0, 2.0
#: The count of an object whose shapes cannot be bounded: every sweep in its cells bails.
UNBOUNDED = -1

Shape = tuple[float, float, float, float, float]


def reach_shapes(obj: PhysicsObj) -> list[Shape] | None:
    """The balls and columns around every shape of ``obj`` that a sweep could meet (see the module
    docstring), or None when the kernel leaves every sweep near it to the reference path: an
    object with a weenie (``FindObjCollisions`` asks it whether it is a creature, a player, ...), a
    particle emitter (its parts do not follow its frame), a BSP part without a bounding sphere, a
    cell or a positive scale (the reference raises on a zero one), a coordinate that is not
    finite. A negative scale turns a radius negative, which the shapes' tests square: the ball or
    column takes its length."""
    if obj.weenie_obj is not None or obj.state & PhysicsState.PARTICLE_EMITTER:
        return None
    parts = obj.part_array
    if parts is None:
        return []  # FindObjCollisions tests nothing
    shapes: list[Shape] = []
    at, scale = obj.position, obj.scale
    if obj.state & PhysicsState.HAS_PHYSICS_BSP:
        for part in parts.parts:
            if part.physics_bsp is None:
                continue
            bound, size = part.physics_sphere, f32(part.gfxobj_scale.z)
            if bound is None or not part.pos.objcell_id or not size > 0.0:
                return None
            shapes.append((*placed(part.pos, bound.center * size), abs(bound.radius) * size, PART_BALL))
    elif parts.get_num_cylsphere():
        for cyl in parts.get_cylsphere():
            shapes.append((*placed(at, cyl.low_pt * scale), abs(cyl.radius * scale), COLUMN))
    else:
        for sphere in parts.get_sphere():
            shapes.append((*placed(at, sphere.center * scale), abs(sphere.radius * scale), BALL))
    if not all(math.isfinite(value) for shape in shapes for value in shape):
        return None
    return shapes


def placed(position: Position, local: Vector3) -> tuple[float, float, float]:
    """The point ``local`` to ``position``'s frame, in landblock-global metres."""
    point = position.frame.localtoglobal(local)
    cell_id = position.objcell_id
    return (
        point.x + ((cell_id >> 24) & 0xFF) * BLOCK_LENGTH,
        point.y + ((cell_id >> 16) & 0xFF) * BLOCK_LENGTH,
        point.z,
    )


def shape_arrays(objects: list[PhysicsObj]) -> tuple[np.ndarray, np.ndarray]:
    """``(spans, shapes)`` of ``objects``: int32 ``(n, 2)`` rows ``(first row, count)`` (count
    :data:`UNBOUNDED` for an object :func:`reach_shapes` cannot bound) into float64
    ``(rows, SHAPE_WIDTH)`` shapes."""
    spans = np.zeros((len(objects), 2), dtype=np.int32)
    rows: list[Shape] = []
    for k, obj in enumerate(objects):
        shapes = reach_shapes(obj)
        spans[k] = (len(rows), UNBOUNDED if shapes is None else len(shapes))
        rows.extend(shapes or ())
    return spans, np.array(rows, dtype=np.float64).reshape(len(rows), SHAPE_WIDTH)
