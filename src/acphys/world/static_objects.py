"""Static world objects: pillars, walls, ledges and stairs that stand in cells and never move.

Retail makes them from a landblock's object list (``CLandBlockInfo``): the
object gets the ``STATIC`` state (and ``HAS_PHYSICS_BSP`` when its setup has
solid geometry), enters the cell under its origin with
``CPhysicsObj::add_obj_to_cell``, and casts shadows into every cell it
overlaps, where the collision sweep finds it.
"""

from __future__ import annotations

from acphys.flags import PhysicsState
from acphys.math.cell_id import format_cell_id
from acphys.math.position import Position
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.setup import Setup
from acphys.world.world import World


def add_static_object(
    world: World, name: str, setup: Setup, position: Position, scale: float = 1.0
) -> PhysicsObj:
    """Make a static object of ``setup`` at ``position`` (scaled by ``scale``) and put it in its cell.

    Its state is ``STATIC | REPORT_COLLISIONS`` (plus ``HAS_PHYSICS_BSP``):
    retail reads the rest from the object's DAT physics description, which
    acphys does not ship. Raises ``ValueError`` when ``position`` is in no
    cell of ``world``.
    """
    if not scale > 0.0:
        raise ValueError(f"static object {name!r}: scale must be positive, got {scale}")
    cell = world.get_cell(position.objcell_id)
    if cell is None:
        raise ValueError(
            f"static object {name!r}: no cell {format_cell_id(position.objcell_id)} in the world"
        )
    obj = PhysicsObj(world, name, PartArray(setup))
    obj.state = PhysicsState.STATIC | PhysicsState.REPORT_COLLISIONS
    if setup.has_physics_bsp:
        obj.state |= PhysicsState.HAS_PHYSICS_BSP
    obj.set_scale_static(scale)
    obj.add_obj_to_cell(cell, position.frame)
    return obj
