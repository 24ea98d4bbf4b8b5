"""``World``: the cells bodies live in and the global clocks retail keeps as statics.

Retail keeps the clocks and the player as globals (``Timer::cur_time``,
``PhysicsTimer::curr_time``, ``CPhysicsObj::player_object``,
``CObjectMaint::is_active``); acphys keeps them on the world, so several
independent worlds can run side by side.

Cells come from the world's :class:`~acphys.world.landblock.Landscape`:
landblocks added with their terrain (``add_landblock``, or ``set_flat_ground``
for flat walkable ground) and env cells added by id. Every other outdoor cell
of the map exists too, as a land cell without terrain: acphys's empty world,
where nothing is underfoot.
"""

from __future__ import annotations

import math
import random
from typing import TYPE_CHECKING

from acphys.math.cell_id import FIRST_ENV_CELL, inbound_valid_cellid, is_outdoor
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.world.land_cell import LandCell
from acphys.world.landblock import LandBlock, Landscape
from acphys.world.obj_cell import ObjCell
from acphys.world.terrain import HEIGHT_TABLE_SIZE, MAX_LAND_HEIGHT, NUM_VERTICES, LandBlockStruct

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj
    from acphys.transition.transition import Transition


#: The first id ``add_object`` hands out (the range retail servers use for dynamic objects).
FIRST_OBJECT_ID = 0x80000001


def flat_landblock(landblock: int, height: float) -> LandBlock:
    """Landblock ``0xXXYY`` of flat, dry ground at ``height`` metres (in [0, 800], as retail heights are).

    Every height byte is 0 and the height table holds ``height`` throughout, narrowed to float32
    (the table is ``float``, see :func:`~acphys.world.terrain.set_height_table`).
    """
    if not 0 <= landblock <= 0xFFFF:
        raise ValueError(f"landblock must be 0xXXYY, got 0x{landblock:X}")
    if not (math.isfinite(height) and 0.0 <= f32(height) <= MAX_LAND_HEIGHT):
        raise ValueError(f"ground height must be in [0, {MAX_LAND_HEIGHT:g}] m, got {height}")
    zeros = [0] * NUM_VERTICES
    return LandBlock(LandBlockStruct((landblock << 16) | 0xFFFF, zeros, zeros, [height] * HEIGHT_TABLE_SIZE))


class World:
    """The cells, the clocks, the objects, the player object and the transition pool of one
    simulation."""

    def __init__(self, seed: int = 0) -> None:
        #: Retail's ``Random::RollDice`` draws (placement scatter, CallPES pauses, particles) come
        #: from this generator, so the same world and seed repeat a run exactly.
        self.dice = random.Random(seed)
        #: ``Timer::cur_time``: the wall clock the driver advances (seconds).
        self.cur_time = 0.0
        #: ``PhysicsTimer::curr_time``: the time of the physics slice being integrated.
        self.physics_time = 0.0
        #: ``CPhysicsObj::player_object``: the body the 96-m activity cull is measured from.
        self.player: PhysicsObj | None = None
        #: ``CObjectMaint::is_active``: the cull is on in shipped play (docs/01-physics.md §2).
        self.activity_cull = True
        #: Landblocks with terrain, and env cells.
        self.landscape = Landscape()
        self._void_cells: dict[int, LandCell] = {}
        #: ``CObjectMaint``'s object table: every body made in this world, by id.
        self._objects: dict[int, PhysicsObj] = {}
        self._next_object_id = FIRST_OBJECT_ID
        #: ``CObjectMaint``'s lost cell (keys, in the order they came): bodies whose position is in
        #: no cell, waiting for one.
        self._lost_cell: dict[PhysicsObj, None] = {}
        #: ``CTransition::transit``: the pool the sweeps take their transitions from
        #: (:meth:`acphys.transition.transition.Transition.pool`), made on the first sweep.
        self.transition_pool: list[Transition] = []

    # -- objects ---------------------------------------------------------------------------

    def add_object(self, obj: PhysicsObj, object_id: int | None = None) -> int:
        """Register ``obj`` under ``object_id`` (or the next free id) and return the id."""
        if object_id is None:
            object_id = self.next_object_id()
        if not 0 < object_id <= 0xFFFFFFFF:
            raise ValueError(f"object id must be a non-zero 32-bit id, got {object_id:#x}")
        if object_id in self._objects:
            owner = self._objects[object_id].name
            raise ValueError(f"object id 0x{object_id:08X} is already used by {owner!r}")
        self._objects[object_id] = obj
        return object_id

    def next_object_id(self) -> int:
        """The id :meth:`add_object` gives the next object registered without one."""
        while self._next_object_id in self._objects:
            self._next_object_id += 1
        return self._next_object_id

    def remove_object(self, obj: PhysicsObj) -> None:
        """Delete ``obj`` from the world: ``exit_world``, ``leave_world``, out of the object table,
        then off its parent and rid of its children.

        Retail: CObjectMaint::DeleteObject @ 0x00508460 (acclient.c:309917)
        """
        if not self.has_object(obj):
            raise ValueError(f"{obj.name!r} (0x{obj.id:08X}) is not an object of this world")
        obj.exit_world()
        obj.leave_world()
        del self._objects[obj.id]
        obj.unset_parent()
        obj.unparent_children()

    def has_object(self, obj: PhysicsObj) -> bool:
        """Whether ``obj`` is in the object table (made here and not removed)."""
        return self._objects.get(obj.id) is obj

    def get_object(self, object_id: int) -> PhysicsObj | None:
        """The body with this id, or None (retail ``CObjectMaint::GetObjectA``)."""
        return self._objects.get(object_id)

    @property
    def lost_cell(self) -> list[PhysicsObj]:
        """The bodies in the lost cell, in the order they came."""
        return list(self._lost_cell)

    def goto_lost_cell(self, obj: PhysicsObj) -> None:
        """Park ``obj`` in the lost cell (once), as ``CObjectMaint::GotoLostCell`` does."""
        self._lost_cell.setdefault(obj, None)

    def remove_from_lost_cell(self, obj: PhysicsObj) -> None:
        """Take ``obj`` out of the lost cell, if it is there (``CObjectMaint::RemoveFromLostCell``)."""
        self._lost_cell.pop(obj, None)

    # -- terrain and cells -----------------------------------------------------------------

    def add_landblock(self, landblock: LandBlock) -> None:
        """Add a landblock with its terrain and land cells (its id must be new)."""
        self.landscape.add_landblock(landblock)

    def set_flat_ground(self, landblock: int, height: float) -> None:
        """Give ``landblock`` (``0xXXYY``) flat, dry, walkable ground at ``height`` metres."""
        self.add_landblock(flat_landblock(landblock, height))

    def add_cell(self, cell: ObjCell) -> None:
        """Add an env cell (indoors: id low word 0x100 and up)."""
        self.landscape.add_cell(cell)

    def ground_height(self, cell_id: int, point: Vector3) -> float | None:
        """The terrain height under the landblock-local ``point``, or None where there is no terrain."""
        landblock = self.landscape.get_landblock(cell_id)
        return None if landblock is None else landblock.terrain.get_height(point)

    def ground_normal(self, cell_id: int, point: Vector3) -> Vector3 | None:
        """The terrain's unit normal under the landblock-local ``point``, or None where there is none."""
        landblock = self.landscape.get_landblock(cell_id)
        return None if landblock is None else landblock.terrain.get_normal(point)

    def get_cell(self, cell_id: int) -> ObjCell | None:
        """The cell with this id, or None (off the map, or an env cell nobody added).

        An outdoor cell of a landblock without terrain is a land cell with no polygons.
        """
        cell = self.landscape.get_cell(cell_id)
        if cell is not None or (cell_id & 0xFFFF) >= FIRST_ENV_CELL:
            return cell
        if not (inbound_valid_cellid(cell_id) and is_outdoor(cell_id)):
            return None
        void = self._void_cells.get(cell_id)
        if void is None:
            void = self._void_cells[cell_id] = LandCell(cell_id)
        return void
