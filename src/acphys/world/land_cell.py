"""Retail ``CSortCell`` and ``CLandCell``: the outdoor 24-m cells.

``CLandCell : CSortCell : CObjCell``. A sort cell may hold one building, which adds its
indoor cells to a sweep and collides first; a land cell holds the two terrain triangles of
its square (from ``LandBlockStruct.cell_polygons``) and collides a sweep with them.

Everything is landblock-local: a land cell's ``pos`` origin is its centre
``((2cx+1)·12, (2cy+1)·12, 0)`` in its landblock (``ConstructPolygons``,
acclient.c:354091-354098), and points handed to ``point_in_cell`` are in that landblock's frame.

The ``CPhysicsPart`` overloads (``find_transit_cells_for_parts``,
``add_all_outside_cells_for_parts``) are what a static object with solid geometry shadows into
cells with (``CPartArray::calc_cross_cells_static``): the land cells its parts' bounding boxes
cover, and the building's cells the boxes reach through its doors.

Not ported: the rendering members (``in_view``, ``GetViewerDistance``), ``Trace``, and the
``Always2D`` branch of the parts ``add_all_outside_cells`` (a sprite part's sphere; acphys parts
are never 2D, see :meth:`acphys.physics_part.PhysicsPart.always_2d`).

Divergences from ACE's ``LandCell.cs`` (the decompilation wins):

- ACE's sphere ``add_all_outside_cells`` never sets ``added_outside``; retail sets it on the
  first call (acclient.c:355371), so later calls from each land cell's ``find_transit_cells``
  return at once.
- ACE's ``add_outside_cell`` skips a cell whose landblock is not loaded; retail adds the id with
  no cell (acclient.c:354981-354984), so the id is still in the array.
- ACE's parts ``add_all_outside_cells`` anchors the block on every part in turn and adds a block
  per part; retail anchors it on the first part's land cell (and adds nothing when that land
  cell is not loaded) and adds one block around all the boxes (acclient.c:355255-355337). With
  acphys's one part the cells are the same.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

from acphys.constants import CELL_LENGTH, MAX_LCOORD
from acphys.flags import ObjectInfoState, PhysicsState, TransitionState, member_namespace
from acphys.geometry.bbox import BBox
from acphys.geometry.plane import Sidedness
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import (
    adjust_to_outside,
    adjust_to_outside_lcoord,
    format_cell_id,
    get_block_offset,
    gid_to_lcoord,
    lcoord_to_gid,
)
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import pack3, unpack3
from acphys.world.obj_cell import CellArray, CellTransition, ObjCell
from acphys.world.terrain import TERRAIN_SURF_CHAR, SurfChar, WaterType

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj
    from acphys.physics_part import PhysicsPart
    from acphys.transition.transition import SpherePath

OI = member_namespace(ObjectInfoState)
PS = member_namespace(PhysicsState)
TS = member_namespace(TransitionState)
WT = member_namespace(WaterType)
#: ``Sidedness.POSITIVE`` read once: an enum member read through its class is slow (see ``member_namespace``).
_POSITIVE = Sidedness.POSITIVE


class Building(Protocol):
    """What a sort cell asks of its ``CBuildingObj`` (the building side arrives separately)."""

    def find_building_transit_cells(
        self, p: Position, spheres: Sequence[Sphere], cell_array: CellArray, path: SpherePath | None
    ) -> None: ...

    def find_building_transit_cells_for_parts(
        self, parts: Sequence[PhysicsPart], cell_array: CellArray
    ) -> None: ...

    def find_building_collisions(self, transition: CellTransition) -> TransitionState: ...

    def get_object(self, obj_iid: int) -> PhysicsObj | None: ...


class LandTerrain(Protocol):
    """What a land cell reads from its landblock beyond water (``CLandBlock::get_terrain``)."""

    water_type: WaterType

    def calc_water_depth(self, cell_id: int, point: Vector3) -> float: ...

    def get_terrain(self, cell_id: int, point: Vector3) -> int: ...


class SortCell(ObjCell):
    """Retail ``CSortCell``: a cell that may hold a building."""

    __slots__ = ("building",)

    def __init__(self, cell_id: int) -> None:
        super().__init__(cell_id)
        self.building: Building | None = None

    def has_building(self) -> bool:
        """Retail: CSortCell::has_building @ 0x00534000 (acclient.c:356067)"""
        return self.building is not None

    def add_building(self, building: Building) -> None:
        """Keep ``building`` unless the cell already has one.

        Retail: CSortCell::add_building @ 0x00534030 (acclient.c:356073)
        """
        if self.building is None:
            self.building = building

    def remove_building(self, building: Building | None = None) -> None:
        """Drop the building (whichever is passed).

        Retail: CSortCell::remove_building @ 0x00534050 (acclient.c:356080)
        """
        self.building = None

    def find_transit_cells(
        self, p: Position, spheres: Sequence[Sphere], cell_array: CellArray, path: SpherePath | None
    ) -> None:
        """The building's cells the spheres reach, if there is a building.

        Retail: CSortCell::find_transit_cells @ 0x00534060 (acclient.c:356086)
        """
        if self.building is not None:
            self.building.find_building_transit_cells(p, spheres, cell_array, path)

    def find_transit_cells_for_parts(self, parts: Sequence[PhysicsPart], cell_array: CellArray) -> None:
        """The building's cells the parts' bounding boxes reach, if there is a building.

        Retail: CSortCell::find_transit_cells @ 0x00534080 (acclient.c:356096)
        """
        if self.building is not None:
            self.building.find_building_transit_cells_for_parts(parts, cell_array)

    def find_collisions(self, transition: CellTransition) -> TransitionState:
        """Collide with the building, OK without one.

        Retail: CSortCell::find_collisions @ 0x005340A0 (acclient.c:356106)
        """
        if self.building is None:
            return TS.OK
        return self.building.find_building_collisions(transition)

    def get_object(self, obj_iid: int) -> PhysicsObj | None:
        """The cell's object with this id, else the building's.

        Retail: CSortCell::get_object @ 0x005340C0 (acclient.c:356120)
        """
        found = super().get_object(obj_iid)
        if found is None and self.building is not None:
            found = self.building.get_object(obj_iid)
        return found


class LandCell(SortCell):
    """Retail ``CLandCell``: an outdoor cell and its two terrain triangles.

    ``polygons`` are the cell's two triangles in ``ConstructPolygons`` order; ``landblock``
    (``myLandBlock_``) supplies water depth and terrain types.

    Retail: CLandCell::CLandCell @ 0x00532C70 (acclient.c:354817)
    """

    __slots__ = ("polygons",)

    def __init__(self, cell_id: int, polygons: Sequence[Polygon] = ()) -> None:
        if (cell_id & 0xFFFF) >= 0x100 or not cell_id & 0xFFFF:
            raise ValueError(f"{format_cell_id(cell_id)} is not an outdoor land cell id")
        super().__init__(cell_id)
        if len(polygons) not in (0, 2):
            raise ValueError(f"a land cell has 2 terrain polygons, got {len(polygons)}")
        self.polygons: tuple[Polygon, ...] = tuple(polygons)

    # --- terrain --------------------------------------------------------------------------

    def find_terrain_poly(self, origin: Vector3) -> Polygon | None:
        """The first of the two triangles whose xy projection holds ``origin`` (edges inside).

        Retail: CLandCell::find_terrain_poly @ 0x00532CF0 (acclient.c:354858)
        """
        for poly in self.polygons:
            if poly.point_in_poly2D(origin, _POSITIVE):
                return poly
        return None

    def point_in_cell(self, point: Vector3) -> bool:
        """Whether the landblock-local ``point`` lies over one of the triangles (edges count).

        A terrain-less cell (acphys's empty world; retail cells always have their triangles)
        holds the points ``adjust_to_outside`` maps to it: its 24-m square, closed at the low
        x and y edges and open at the high ones.

        Retail: CLandCell::point_in_cell @ 0x00532D40 (acclient.c:354880)
        """
        if not self.polygons:
            cx, cy = divmod((self.id & 0xFFFF) - 1, 8)
            x0, y0 = cx * CELL_LENGTH, cy * CELL_LENGTH
            return x0 <= point.x < x0 + CELL_LENGTH and y0 <= point.y < y0 + CELL_LENGTH
        return self.find_terrain_poly(point) is not None

    def find_terrain(self, pos: Position) -> SurfChar:
        """SOLID or WATER for the corner of this cell nearest ``pos`` (any landblock).

        Retail: CLandCell::find_terrain @ 0x00532E20 (acclient.c:354950)
        """
        terrain = self._terrain()
        local = Position(self.id).get_offset(pos)
        return TERRAIN_SURF_CHAR[terrain.get_terrain(self.id, local)]

    def walkable_surface_type(self, walkable: Polygon, pos: Position) -> SurfChar:
        """SOLID unless ``walkable`` is one of this cell's triangles; then ``find_terrain``.

        Retail: CLandCell::walkable_surface_type @ 0x00533190 (acclient.c:355121)
        """
        if not any(walkable is poly for poly in self.polygons):
            return SurfChar.SOLID
        return self.find_terrain(pos)

    def _terrain(self) -> LandTerrain:
        landblock = self.landblock
        if landblock is None or not hasattr(landblock, "get_terrain"):
            raise ValueError(f"land cell {format_cell_id(self.id)} has no landblock terrain")
        return landblock  # type: ignore[return-value]

    # --- collisions -----------------------------------------------------------------------

    def find_env_collisions(self, transition: CellTransition) -> TransitionState:
        """Collide the sweep's first sphere with the terrain triangle under its low point.

        Entry restrictions first. With no triangle under the low point (it is outside this
        cell) the result is OK. An all-water landblock stops everything but viewers and
        missiles. Otherwise ``validate_walkable`` rests sphere 0 on the triangle's plane,
        lowered by the water depth at the low point; the plane counts as water when the
        cell has any.

        Retail: CLandCell::find_env_collisions @ 0x00532F20 (acclient.c:354991)
        """
        result = self.check_entry_restrictions(transition)
        if result != TS.OK:
            return result
        path = transition.sphere_path
        offset = get_block_offset(path.check_pos.objcell_id, self.id)
        local_point = path.global_low_point - offset
        walkable = self.find_terrain_poly(local_point)
        if walkable is None:
            return result
        info = transition.object_info
        if (
            self.get_block_water_type() == WT.ENTIRELY_WATER
            and not info.state & OI.IS_VIEWER
            and not info.object._state & PS.MISSILE
        ):
            return TS.COLLIDED
        water_depth = self.get_water_depth(local_point)
        sphere = path.global_sphere[0]
        check_pos = Sphere.owning(sphere.center - offset, sphere.radius)
        return info.validate_walkable(
            check_pos,
            walkable.plane,
            self.water_type != WT.NOT_WATER,
            water_depth,
            path,
            transition.collision_info,
            self.id,
        )

    def find_collisions(self, transition: CellTransition) -> TransitionState:
        """Terrain, then the building, then the shadowed objects; the first non-OK result wins.

        Retail: CLandCell::find_collisions @ 0x00532D60 (acclient.c:354886)
        """
        result = self.find_env_collisions(transition)
        if result == TS.OK:
            result = super().find_collisions(transition)
            if result == TS.OK:
                result = self.find_obj_collisions(transition)
        return result

    # --- cell lists -----------------------------------------------------------------------

    def find_transit_cells(
        self, p: Position, spheres: Sequence[Sphere], cell_array: CellArray, path: SpherePath | None
    ) -> None:
        """The outdoor cells the spheres overlap (once per array), then the building's cells.

        Retail: CLandCell::find_transit_cells @ 0x00533800 (acclient.c:355422)
        """
        LandCell.add_all_outside_cells(p, spheres, cell_array)
        super().find_transit_cells(p, spheres, cell_array, path)

    def find_transit_cells_for_parts(self, parts: Sequence[PhysicsPart], cell_array: CellArray) -> None:
        """The land cells the parts' bounding boxes cover (once per array), then the building's
        cells.

        Retail: CLandCell::find_transit_cells @ 0x00533840 (acclient.c:355432)
        """
        LandCell.add_all_outside_cells_for_parts(parts, cell_array)
        super().find_transit_cells_for_parts(parts, cell_array)

    @staticmethod
    def add_outside_cell(cell_array: CellArray, x: int, y: int) -> None:
        """Add the land cell at global lcoord ``(x, y)`` when it is inside the world (with no
        cell object when its landblock is not there).

        Retail: CLandCell::add_outside_cell @ 0x00532EC0 (acclient.c:354974)
        """
        if 0 <= x < MAX_LCOORD and 0 <= y < MAX_LCOORD:
            cell_id = lcoord_to_gid(x, y)
            cell_array.add_cell(cell_id, cell_array.source.get_cell(cell_id))

    @staticmethod
    def add_cell_block(min_x: int, min_y: int, max_x: int, max_y: int, cell_array: CellArray) -> None:
        """Add every land cell of the lcoord rectangle, column by column.

        Retail: CLandCell::add_cell_block @ 0x005331D0 (acclient.c:355139)
        """
        for x in range(min_x, max_x + 1):
            for y in range(min_y, max_y + 1):
                LandCell.add_outside_cell(cell_array, x, y)

    @staticmethod
    def check_add_cell_boundary(
        cell_array: CellArray, pt: tuple[float, float], x: int, y: int, incell_max: float, incell_min: float
    ) -> None:
        """Add the neighbours of cell ``(x, y)`` that a circle reaches: ``pt`` is its centre
        within the cell, and a coordinate above ``incell_max`` (24 - r) or below
        ``incell_min`` (r) crosses that side; the corner cells come with the east and west
        neighbours. ``pt`` and the two bounds are ``float`` (a ``Vec2D`` and two ``float``
        parameters): the caller passes float32s.

        Retail: CLandCell::check_add_cell_boundary @ 0x00533260 (acclient.c:355161)
        """
        px, py = pt
        add = LandCell.add_outside_cell
        if px > incell_max:
            add(cell_array, x + 1, y)
            if py > incell_max:
                add(cell_array, x + 1, y + 1)
            if py < incell_min:
                add(cell_array, x + 1, y - 1)
        if px < incell_min:
            add(cell_array, x - 1, y)
            if py > incell_max:
                add(cell_array, x - 1, y + 1)
            if py < incell_min:
                add(cell_array, x - 1, y - 1)
        if py > incell_max:
            add(cell_array, x, y + 1)
        if py < incell_min:
            add(cell_array, x, y - 1)

    @staticmethod
    def add_all_outside_cells(p: Position, spheres: Sequence[Sphere], cell_array: CellArray) -> None:
        """Once per array: every land cell the spheres (global, in ``p``'s landblock frame)
        overlap, sphere by sphere; the first sphere off the world ends the walk. With no
        spheres, the cell under ``p``'s origin.

        The point within its cell (``pt1``, a ``Vec2D``) and ``max_rad = 24 - radius`` are
        ``float`` locals (acclient.c:355389-355392), so the far-side test compares two float32s.

        Retail: CLandCell::add_all_outside_cells @ 0x00533630 (acclient.c:355345)
        """
        if cell_array.added_outside:
            return
        cell_array.added_outside = True
        if not spheres:
            point = p.frame.origin.copy()
            cell_id = adjust_to_outside(p.objcell_id, point)
            lcoord = gid_to_lcoord(cell_id) if cell_id else None
            if lcoord is not None:
                LandCell.add_outside_cell(cell_array, *lcoord)
            return
        for sphere in spheres:
            point = sphere.center.copy()
            # adjust_to_outside, then gid_to_lcoord of the cell it gives: never None once on the world
            lcoord = adjust_to_outside_lcoord(p.objcell_id, point)
            if lcoord is None:
                break
            radius = sphere.radius
            in_x, in_y, max_rad = unpack3(
                pack3(
                    point.x - math.floor(point.x / CELL_LENGTH) * CELL_LENGTH,
                    point.y - math.floor(point.y / CELL_LENGTH) * CELL_LENGTH,
                    CELL_LENGTH - radius,
                )
            )
            x, y = lcoord
            LandCell.add_outside_cell(cell_array, x, y)
            LandCell.check_add_cell_boundary(cell_array, (in_x, in_y), x, y, max_rad, radius)

    @staticmethod
    def add_all_outside_cells_for_parts(parts: Sequence[PhysicsPart], cell_array: CellArray) -> None:
        """Once per array: every land cell under the parts' bounding boxes.

        The first part's origin, re-homed outdoors, names the anchor land cell; nothing is added
        when it is off the world or that cell is not there. Each part's box is taken into the
        anchor's landblock (``BBox::LocalToGlobal``: corners through the part's frame, unscaled)
        and floored to cell columns and rows there (``floor(c / 24)``); the block of cells from
        the lowest to the highest, always holding the anchor, is added column by column.

        Retail: CLandCell::add_all_outside_cells @ 0x00533360 (acclient.c:355191)
        """
        if cell_array.added_outside:
            return
        cell_array.added_outside = True
        if not parts:
            return
        first = parts[0]
        cell_id = adjust_to_outside(first.pos.objcell_id, first.pos.frame.origin.copy())
        anchor = cell_array.source.get_cell(cell_id) if cell_id else None
        lcoord = gid_to_lcoord(cell_id) if isinstance(anchor, LandCell) else None
        if anchor is None or lcoord is None:
            return
        index = (cell_id & 0xFFFF) - 1
        lx, ly = index >> 3, index & 7
        min_x = min_y = max_x = max_y = 0
        for part in parts:
            box = BBox.local_to_global(part.get_bounding_box(), part.pos, anchor.pos)
            min_x = min(min_x, math.floor(box.min.x / CELL_LENGTH) - lx)
            min_y = min(min_y, math.floor(box.min.y / CELL_LENGTH) - ly)
            max_x = max(max_x, math.floor(box.max.x / CELL_LENGTH) - lx)
            max_y = max(max_y, math.floor(box.max.y / CELL_LENGTH) - ly)
        x, y = lcoord
        LandCell.add_cell_block(x + min_x, y + min_y, x + max_x, y + max_y, cell_array)
