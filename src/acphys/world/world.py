"""``World``: the cells bodies live in and the global clocks retail keeps as statics.

Retail keeps the clocks and the player as globals (``Timer::cur_time``,
``PhysicsTimer::curr_time``, ``CPhysicsObj::player_object``,
``CObjectMaint::is_active``); acphys keeps them on the world, so several
independent worlds can run side by side.

Every outdoor cell of every landblock exists. A landblock may have flat
ground at a given height (``set_flat_ground``); until the world issue brings
terrain, objects and indoor cells, that is the only geometry there is.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.math.cell_id import format_cell_id, inbound_valid_cellid, is_outdoor, landblock_of

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj


#: The first id ``add_object`` hands out (the range retail servers use for dynamic objects).
FIRST_OBJECT_ID = 0x80000001


class ObjCell:
    """Retail ``CObjCell``: a cell bodies are in. Here, an id and its objects."""

    __slots__ = ("id", "objects")

    def __init__(self, cell_id: int) -> None:
        self.id = cell_id
        self.objects: list[PhysicsObj] = []

    def __repr__(self) -> str:
        return f"ObjCell({format_cell_id(self.id)})"


class World:
    """The cells, the clocks and the player object of one simulation."""

    def __init__(self) -> None:
        #: ``Timer::cur_time``: the wall clock the driver advances (seconds).
        self.cur_time = 0.0
        #: ``PhysicsTimer::curr_time``: the time of the physics slice being integrated.
        self.physics_time = 0.0
        #: ``CPhysicsObj::player_object``: the body the 96-m activity cull is measured from.
        self.player: PhysicsObj | None = None
        #: ``CObjectMaint::is_active``: the cull is on in shipped play (docs/01-physics.md §2).
        self.activity_cull = True
        self._cells: dict[int, ObjCell] = {}
        self._ground: dict[int, float] = {}
        #: ``CObjectMaint``'s object table: every body made in this world, by id.
        self._objects: dict[int, PhysicsObj] = {}
        self._next_object_id = FIRST_OBJECT_ID

    def add_object(self, obj: PhysicsObj, object_id: int | None = None) -> int:
        """Register ``obj`` under ``object_id`` (or the next free id) and return the id."""
        if object_id is None:
            while self._next_object_id in self._objects:
                self._next_object_id += 1
            object_id = self._next_object_id
        if not 0 < object_id <= 0xFFFFFFFF:
            raise ValueError(f"object id must be a non-zero 32-bit id, got {object_id:#x}")
        if object_id in self._objects:
            owner = self._objects[object_id].name
            raise ValueError(f"object id 0x{object_id:08X} is already used by {owner!r}")
        self._objects[object_id] = obj
        return object_id

    def get_object(self, object_id: int) -> PhysicsObj | None:
        """The body with this id, or None (retail ``CObjectMaint::GetObjectA``)."""
        return self._objects.get(object_id)

    def set_flat_ground(self, landblock: int, height: float) -> None:
        """Give ``landblock`` (``0xXXYY``) flat, walkable ground at ``height`` metres."""
        if not 0 <= landblock <= 0xFFFF:
            raise ValueError(f"landblock must be 0xXXYY, got 0x{landblock:X}")
        if height != height or height in (float("inf"), float("-inf")):
            raise ValueError(f"ground height must be finite, got {height}")
        self._ground[landblock] = float(height)

    def ground_height(self, cell_id: int) -> float | None:
        """The flat ground height of the landblock holding ``cell_id``, or None where there is none."""
        return self._ground.get(landblock_of(cell_id))

    def get_cell(self, cell_id: int) -> ObjCell | None:
        """The cell with this id, or None when there is none (off the world, or indoors)."""
        cell = self._cells.get(cell_id)
        if cell is None:
            if not (inbound_valid_cellid(cell_id) and is_outdoor(cell_id)):
                return None
            cell = self._cells[cell_id] = ObjCell(cell_id)
        return cell
