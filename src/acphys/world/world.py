"""``World``: the cells bodies live in and the global clocks retail keeps as statics.

Retail keeps the clocks and the player as globals (``Timer::cur_time``,
``PhysicsTimer::curr_time``, ``CPhysicsObj::player_object``,
``CObjectMaint::is_active``); acphys keeps them on the world, so several
independent worlds can run side by side.

This issue's world has no geometry: every outdoor cell of every landblock
exists and is empty. Terrain, objects and indoor cells arrive with the world
issue.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.math.cell_id import format_cell_id, inbound_valid_cellid, is_outdoor

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj


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

    def get_cell(self, cell_id: int) -> ObjCell | None:
        """The cell with this id, or None when there is none (off the world, or indoors)."""
        cell = self._cells.get(cell_id)
        if cell is None:
            if not (inbound_valid_cellid(cell_id) and is_outdoor(cell_id)):
                return None
            cell = self._cells[cell_id] = ObjCell(cell_id)
        return cell
