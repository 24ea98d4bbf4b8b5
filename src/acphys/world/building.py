"""Buildings: retail ``CBuildingObj`` and its ``CBldPortal`` doors into env cells.

A building stands in one outdoor cell (the ``CSortCell`` holding its origin, acclient.c:352157-
352166), so only transitions whose cell array holds that cell see it. It has one part with a
physics BSP, its outer shell, collided with ``bldg_check`` set; and portals, each naming the env
cell behind a door and that cell's portal to the outside (``other_portal_id``). A sphere entering
through a door reaches the env cell by ``find_building_transit_cells``.

Retail's ``CBuildingObj`` derives from ``CPhysicsObj``; a building only uses its position, its
one part and its cell, so here it is a small class of its own holding that part (a
:class:`acphys.physics_part.PhysicsPart` with the shell's physics BSP, building-local, at the
building's scale), whose position is the building's own. Not ported: the leaf cells and shadow
parts (drawing).

Divergences from ACE (the decompilation wins):

- ACE's ``BuildingObj.get_object`` returns null; retail searches the building's cells through
  their portals (acclient.c:719279).
- ACE's ``BldPortal.add_to_stablist`` appends an id when it *is* already in the list (and
  rebuilds the list from its own stabs when full); retail appends the ids not yet there
  (acclient.c:362436-362470).
- ACE's ``GfxObj.FindObjCollisions`` tests ``|d|² - (r1 + r2)² < EPSILON`` before the BSP (see
  :mod:`acphys.physics_part`, which holds the shared part collision).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from acphys.flags import ObjectInfoState, TransitionState
from acphys.math.cell_id import FIRST_ENV_CELL, format_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_part import PhysicsPart
from acphys.setup import Setup
from acphys.world.env_cell import PORTAL_EXACT_MATCH, PORTAL_NEGATIVE_SIDE, EnvCell
from acphys.world.obj_cell import CellArray, CellSource, CellTransition, ObjCell

if TYPE_CHECKING:
    from acphys.geometry.bsp import BSPTree
    from acphys.geometry.sphere import Sphere
    from acphys.physics_obj import PhysicsObj
    from acphys.transition.transition import SpherePath
    from acphys.world.land_cell import SortCell


class BldPortal:
    """Retail ``CBldPortal`` (acclient.h:32094): a building door into an env cell.

    ``other_portal_id`` is the env cell's portal (index) that opens outside; ``stab_list`` the
    env cells seen through the door.

    Retail: CBldPortal::CBldPortal @ 0x0053BB30 (acclient.c:362405)
    """

    __slots__ = ("exact_match", "other_cell_id", "other_portal_id", "portal_side", "stab_list")

    def __init__(
        self,
        other_cell_id: int,
        other_portal_id: int,
        portal_side: int = 1,
        exact_match: bool = False,
        stab_list: Sequence[int] = (),
    ) -> None:
        if (other_cell_id & 0xFFFF) < FIRST_ENV_CELL or not 0 <= other_cell_id <= 0xFFFFFFFF:
            raise ValueError(f"a building portal leads into an env cell, not {format_cell_id(other_cell_id)}")
        if portal_side not in (0, 1):
            raise ValueError(f"portal_side must be 0 or 1, got {portal_side!r}")
        self.other_cell_id = other_cell_id
        self.other_portal_id = other_portal_id
        self.portal_side = portal_side
        self.exact_match = bool(exact_match)
        self.stab_list = list(stab_list)

    def __repr__(self) -> str:
        return f"BldPortal(to {format_cell_id(self.other_cell_id)}, portal {self.other_portal_id})"

    @classmethod
    def unpack(
        cls, block_mask: int, flags: int, other_cell: int, other_portal_id: int, stabs: Sequence[int]
    ) -> BldPortal:
        """A portal from its packed words: bit 0 ``exact_match``, bit 1 set means
        ``portal_side`` 0; the other cell and the stabs are ``block_mask | word``;
        ``other_portal_id`` is a signed 16-bit word. (No outside bit: it always leads in.)

        Retail: CBldPortal::UnPack @ 0x0053BC40 (acclient.c:362498)
        """
        words = [flags, other_cell, *stabs]
        if any(not 0 <= w <= 0xFFFF for w in words):
            raise ValueError(f"building portal words are 16-bit, got {[hex(w) for w in words]}")
        if not -0x8000 <= other_portal_id <= 0x7FFF:
            raise ValueError(f"other portal id is a signed 16-bit word, got {other_portal_id}")
        side = 0 if flags & PORTAL_NEGATIVE_SIDE else 1
        return cls(
            block_mask | other_cell,
            other_portal_id,
            side,
            bool(flags & PORTAL_EXACT_MATCH),
            [block_mask | s for s in stabs],
        )

    def get_other_cell(self, source: CellSource) -> ObjCell | None:
        """Retail: CBldPortal::GetOtherCell @ 0x0053BC30 (acclient.c:362492)"""
        return source.get_cell(self.other_cell_id)

    def add_to_stablist(self, block_stab_list: list[int]) -> None:
        """Append each of this portal's stabs not already in ``block_stab_list``.

        Retail: CBldPortal::add_to_stablist @ 0x0053BB60 (acclient.c:362422)
        """
        for stab in self.stab_list:
            if stab not in block_stab_list:
                block_stab_list.append(stab)


class BuildingObj:
    """Retail ``CBuildingObj`` (acclient.h:31909): a shell (one part's physics BSP) and doors.

    ``pos`` is the building's position (outdoor cell id, landblock-local frame) and its part's
    (the part sits at the building's origin); the shell BSP is in the building's frame at
    ``scale``. ``source`` is where ``get_object`` looks cells up
    (retail's global ``CEnvCell::GetVisible``): the world the building stands in.

    Retail: CBuildingObj::makeBuilding @ 0x006B53A0 (acclient.c:719152)
    """

    __slots__ = ("building_id", "cell", "part", "portals", "pos", "source")

    def __init__(
        self,
        physics_bsp: BSPTree | None,
        frame: Frame,
        portals: Sequence[BldPortal] = (),
        scale: float = 1.0,
        building_id: int = 0,
        source: CellSource | None = None,
    ) -> None:
        if not scale > 0.0:
            raise ValueError(f"building scale must be positive, got {scale!r}")
        self.building_id = building_id
        self.pos = Position(0, frame)
        self.part = PhysicsPart(Setup("building", physics_bsp=physics_bsp))
        self.part.pos = self.pos
        self.part.gfxobj_scale = Vector3(scale, scale, scale)
        self.portals = list(portals)
        self.cell: SortCell | None = None
        self.source = source

    def __repr__(self) -> str:
        return f"BuildingObj({self.building_id:#x} in {format_cell_id(self.pos.objcell_id)})"

    @property
    def physics_bsp(self) -> BSPTree | None:
        """The shell's physics BSP (the part's)."""
        return self.part.physics_bsp

    @property
    def scale(self) -> float:
        """The building's scale (the part's ``gfxobj_scale``)."""
        return self.part.gfxobj_scale.z

    @property
    def num_portals(self) -> int:
        return len(self.portals)

    def add_to_cell(self, new_cell: SortCell) -> None:
        """Stand in ``new_cell``: it takes the building (if it has none yet), the building takes
        its id.

        Retail: CBuildingObj::add_to_cell @ 0x006B5550 (acclient.c:719256)
        """
        new_cell.add_building(self)
        self.pos.objcell_id = new_cell.id
        self.cell = new_cell

    def remove(self) -> None:
        """Leave the cell (which forgets its building) and clear the cell id.

        Retail: CBuildingObj::remove @ 0x006B5200 (acclient.c:719056)
        """
        if self.cell is not None:
            self.cell.remove_building(self)
        self.pos.objcell_id = 0
        self.cell = None

    def add_to_stablist(self, block_stab_list: list[int]) -> None:
        """Retail: CBuildingObj::add_to_stablist @ 0x006B51B0 (acclient.c:719040)"""
        for portal in self.portals:
            portal.add_to_stablist(block_stab_list)

    def find_building_collisions(self, transition: CellTransition) -> TransitionState:
        """The shell part (``PhysicsPart.find_obj_collisions``), with ``sphere_path.bldg_check``
        set for the duration; a result other than OK flags an environment collision unless the
        body is in contact.

        Retail: CBuildingObj::find_building_collisions @ 0x006B5300 (acclient.c:719115)
        """
        path = transition.sphere_path
        path.bldg_check = True
        result = self.part.find_obj_collisions(transition)
        path.bldg_check = False
        if result != TransitionState.OK and not transition.object_info.state & ObjectInfoState.CONTACT:
            transition.collision_info.collided_with_environment = True
        return result

    def find_building_transit_cells(
        self, p: Position, spheres: Sequence[Sphere], cell_array: CellArray, path: SpherePath | None
    ) -> None:
        """Through each door whose env cell is there, let that cell check the spheres
        (``EnvCell.check_building_transit`` with the door's ``other_portal_id``).

        Retail: CBuildingObj::find_building_transit_cells @ 0x006B5230 (acclient.c:719067)
        """
        for portal in self.portals:
            other = portal.get_other_cell(cell_array.source)
            if isinstance(other, EnvCell):
                other.check_building_transit(portal.other_portal_id, p, spheres, cell_array, path)

    def find_building_transit_cells_for_parts(
        self, parts: Sequence[PhysicsPart], cell_array: CellArray
    ) -> None:
        """Through each door whose env cell is there, let that cell check the parts' bounding
        boxes (``EnvCell.check_building_transit_for_parts`` with the door's ``other_portal_id``).

        Retail: CBuildingObj::find_building_transit_cells @ 0x006B52A0 (acclient.c:719091)
        """
        for portal in self.portals:
            other = portal.get_other_cell(cell_array.source)
            if isinstance(other, EnvCell):
                other.check_building_transit_for_parts(portal.other_portal_id, parts, cell_array)

    def get_object(self, obj_iid: int) -> PhysicsObj | None:
        """The object ``obj_iid`` in the building's cells, searched door by door through the
        cells' portals (one visited set for the whole search); needs ``source``.

        Retail: CBuildingObj::get_object @ 0x006B55A0 (acclient.c:719279)
        """
        source = self.source
        if source is None:
            raise ValueError(f"{self!r} has no cell source to search its cells in")
        visited: set[int] = set()
        for portal in self.portals:
            other = portal.get_other_cell(source)
            if isinstance(other, EnvCell):
                found = other.recursively_get_object(obj_iid, source, visited)
                if found is not None:
                    return found
        return None
