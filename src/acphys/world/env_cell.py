"""Indoor cells: retail ``CEnvCell`` with ``CCellStruct``, ``CEnvironment`` and ``CCellPortal``.

An env cell (``0xXXYYnnnn``, ``nnnn >= 0x100``) is a room: a position (landblock-local frame),
a cell structure in that frame with a *cell BSP* (the room's volume: a chain of inward-facing
planes on ``pos_node`` links) and a *physics BSP* (its walls), and portals. A portal is one of
the structure's polygons leading to another env cell, or (``other_cell_id`` ``OUTSIDE_CELL_ID``)
to the outdoor cells. ``portal_side`` 1 means the other cell lies on the positive side of the
portal polygon's plane, 0 the negative side (``CEnvCell::find_transit_cells``, acclient.c:348356).

Lookups retail makes through the global ``CEnvCell::GetVisible`` go through
``cell_array.source.get_cell`` (see :mod:`acphys.world.obj_cell`).

The ``CPhysicsPart`` overloads (``find_transit_cells_for_parts``,
``check_building_transit_for_parts``) carry a static object's bounding boxes through portals.

Not ported: drawing (surfaces, drawing BSP, light arrays, clip planes, visibility) and DAT
unpacking beyond the portal flag word.

Divergences from ACE's ``EnvCell.cs`` (the decompilation wins):

- ACE's ``point_in_cell`` always asks the cell BSP; retail answers false for a cell without
  portals (acclient.c:347941).
- ACE's sphere ``check_building_transit`` adds the cell once per sphere inside; retail stops at
  the first such sphere (acclient.c:348138-348149). ``add_cell`` ignores repeats, so only the
  work differs.
- ACE's parts ``check_building_transit`` takes a box wholly on the portal's *other* side
  (``Positive`` with ``PortalSide``, ``Negative`` without); retail takes a box crossing the
  portal plane or wholly on the side of ``portal_side``'s value read as a ``Sidedness``
  (acclient.c:348221-348222), which for a door (``portal_side`` 0: outside negative) is the
  room's side.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.flags import ObjectInfoState, TransitionState
from acphys.geometry.bbox import BBox
from acphys.geometry.bsp import CELL_OUTSIDE
from acphys.geometry.plane import Sidedness
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import FIRST_ENV_CELL, format_cell_id
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, unpack3
from acphys.transition.transition import InsertType
from acphys.world.obj_cell import CellArray, CellSource, CellTransition, ObjCell

if TYPE_CHECKING:
    from acphys.geometry.bsp import BSPTree
    from acphys.geometry.polygon import Polygon
    from acphys.math.position import Position
    from acphys.physics_obj import PhysicsObj
    from acphys.physics_part import PhysicsPart
    from acphys.transition.transition import SpherePath

#: ``other_cell_id`` of a portal that opens to the outdoor cells (``-1``, acclient.c:348301).
OUTSIDE_CELL_ID = 0xFFFFFFFF

#: ``CCellPortal::UnPack`` flag bits (acclient.c:362389-362398).
PORTAL_EXACT_MATCH = 0x1
PORTAL_NEGATIVE_SIDE = 0x2
PORTAL_TO_OUTSIDE = 0x4


class CellStruct:
    """Retail ``CCellStruct`` (acclient.h:32275): a room's polygons, portals and BSPs, in the
    cell's local frame.

    ``polygons`` are the drawing polygons (a polygon's id is its index there); ``portals`` are
    the ones that are portals; ``physics_bsp`` is None for a cell nothing collides with.
    """

    __slots__ = ("cell_bsp", "cellstruct_id", "physics_bsp", "physics_polygons", "polygons", "portals")

    def __init__(
        self,
        cell_bsp: BSPTree,
        physics_bsp: BSPTree | None = None,
        polygons: Sequence[Polygon] = (),
        portals: Sequence[Polygon] = (),
        physics_polygons: Sequence[Polygon] = (),
        cellstruct_id: int = 0,
    ) -> None:
        self.cellstruct_id = cellstruct_id
        self.cell_bsp = cell_bsp
        self.physics_bsp = physics_bsp
        self.polygons = list(polygons)
        self.physics_polygons = list(physics_polygons)
        self.portals = list(portals)
        for portal in self.portals:
            if not any(portal is poly for poly in self.polygons):
                raise ValueError(f"portal polygon {portal!r} is not one of the cell structure's polygons")

    def get_portal(self, poly_id: int) -> Polygon | None:
        """The portal whose polygon id (index in ``polygons``) is ``poly_id``, or None.

        Retail: CCellStruct::get_portal @ 0x005338B0 (acclient.c:355463)
        """
        if not 0 <= poly_id < len(self.polygons):
            return None
        poly = self.polygons[poly_id]
        return poly if any(poly is portal for portal in self.portals) else None

    def point_in_cell(self, origin: Vector3) -> bool:
        """Retail: CCellStruct::point_in_cell @ 0x005338F0 (acclient.c:355495)"""
        return self.cell_bsp.point_inside_cell_bsp(origin)

    def sphere_intersects_cell(self, sphere: Sphere) -> int:
        """``CELL_OUTSIDE``, ``CELL_PARTIALLY_INSIDE`` or ``CELL_ENTIRELY_INSIDE``.

        Retail: CCellStruct::sphere_intersects_cell @ 0x00533900 (acclient.c:355501)
        """
        return self.cell_bsp.sphere_intersects_cell_bsp(sphere)

    def box_intersects_cell(self, box_min: Vector3, box_max: Vector3) -> bool:
        """Retail: CCellStruct::box_intersects_cell @ 0x00533910 (acclient.c:355507)"""
        return self.cell_bsp.box_intersects_cell_bsp(box_min, box_max)


class Environment:
    """Retail ``CEnvironment`` (acclient.h:32293): the cell structures env cells pick by index."""

    __slots__ = ("cells", "env_id")

    def __init__(self, cells: Sequence[CellStruct], env_id: int = 0) -> None:
        self.env_id = env_id
        self.cells = list(cells)

    @property
    def num_cells(self) -> int:
        return len(self.cells)

    def get_cellstruct(self, index: int) -> CellStruct:
        """The structure at ``index`` (retail indexes unchecked; here a bad index is an error).

        Retail: CEnvironment::get_cellstruct @ 0x00530BF0 (acclient.c:352896)
        """
        if not 0 <= index < len(self.cells):
            raise ValueError(f"environment has {len(self.cells)} cell structures, no index {index}")
        return self.cells[index]


class CellPortal:
    """Retail ``CCellPortal`` (acclient.h:32300): a portal polygon of the cell's structure and
    the cell behind it.

    Retail: CCellPortal::CCellPortal @ 0x0053BA10 (acclient.c:362329)
    """

    __slots__ = ("exact_match", "other_cell_id", "other_portal_id", "portal", "portal_side")

    def __init__(
        self,
        portal: Polygon,
        other_cell_id: int,
        portal_side: int,
        other_portal_id: int = -1,
        exact_match: bool = False,
    ) -> None:
        if portal_side not in (0, 1):
            raise ValueError(f"portal_side must be 0 or 1, got {portal_side!r}")
        if not 0 <= other_cell_id <= 0xFFFFFFFF:
            raise ValueError(f"other cell id must be a 32-bit id, got {other_cell_id!r}")
        if other_cell_id != OUTSIDE_CELL_ID and (other_cell_id & 0xFFFF) < FIRST_ENV_CELL:
            raise ValueError(
                f"a cell portal leads to an env cell or outside, not to {format_cell_id(other_cell_id)}"
            )
        self.portal = portal
        self.other_cell_id = other_cell_id
        self.portal_side = portal_side
        self.other_portal_id = other_portal_id
        self.exact_match = bool(exact_match)

    def __repr__(self) -> str:
        other = "outside" if self.other_cell_id == OUTSIDE_CELL_ID else format_cell_id(self.other_cell_id)
        return f"CellPortal(to {other}, side={self.portal_side}, other_portal={self.other_portal_id})"

    @classmethod
    def unpack(
        cls, block_mask: int, flags: int, portal: Polygon, other_cell: int, other_portal_id: int
    ) -> CellPortal:
        """A portal from its packed words: bit 0 ``exact_match``, bit 1 set means
        ``portal_side`` 0, bit 2 opens to the outside; otherwise the other cell is
        ``block_mask | other_cell``. ``other_portal_id`` is a signed 16-bit word.

        Retail: CCellPortal::UnPack @ 0x0053BAB0 (acclient.c:362378)
        """
        if not 0 <= flags <= 0xFFFF or not 0 <= other_cell <= 0xFFFF:
            raise ValueError(f"portal flags and other cell are 16-bit words, got {flags:#x}, {other_cell:#x}")
        if not -0x8000 <= other_portal_id <= 0x7FFF:
            raise ValueError(f"other portal id is a signed 16-bit word, got {other_portal_id}")
        other_id = OUTSIDE_CELL_ID if flags & PORTAL_TO_OUTSIDE else (block_mask | other_cell)
        side = 0 if flags & PORTAL_NEGATIVE_SIDE else 1
        return cls(portal, other_id, side, other_portal_id, bool(flags & PORTAL_EXACT_MATCH))

    def get_other_cell(self, source: CellSource) -> ObjCell | None:
        """Retail: CCellPortal::GetOtherCell @ 0x0053BA30 (acclient.c:362340)"""
        return source.get_cell(self.other_cell_id)


def _portal_dist(portal: Polygon, local: Vector3) -> float:
    n = portal.plane.N
    return local.y * n.y + local.z * n.z + local.x * n.x + portal.plane.d


def _outside_portal_dist(frame: Frame, portal: Polygon, center: Vector3) -> float:
    """The signed distance from ``portal``'s plane to the global ``center`` taken into ``frame``,
    as the outside-portal test inlines ``globaltolocal``: the offset from the origin stays double,
    the local x and y are spilled to ``float``, the local z is not (acclient.c:348310-348320).
    """
    m, o = frame.m, frame.origin
    dx, dy, dz = center.x - o.x, center.y - o.y, center.z - o.z
    lx, ly, _ = unpack3(pack3(dx * m[0] + dz * m[2] + dy * m[1], dx * m[3] + dz * m[5] + dy * m[4], 0.0))
    n = portal.plane.N
    return (dz * m[8] + dy * m[7] + dx * m[6]) * n.z + ly * n.y + lx * n.x + portal.plane.d


def _part_portal_dist(cell_pos: Position, part: PhysicsPart, sphere: Sphere, portal: Polygon) -> float:
    """The signed distance from ``portal``'s plane to the part's sphere centre, in the cell's frame."""
    return _portal_dist(portal, cell_pos.localtolocal(part.pos, sphere.center))


class EnvCell(ObjCell):
    """Retail ``CEnvCell`` (acclient.h:32072): an indoor cell.

    ``pos.frame`` places ``structure`` in the landblock. Static objects are bodies the world
    adds to the cell like any other (retail ``init_static_objects`` makes them from the DAT).

    Retail: CEnvCell::CEnvCell @ 0x0052C240 (acclient.c:347888)
    """

    __slots__ = ("env", "portals", "structure")

    def __init__(
        self,
        cell_id: int,
        structure: CellStruct,
        frame: Frame | None = None,
        portals: Sequence[CellPortal] = (),
        env: Environment | None = None,
    ) -> None:
        super().__init__(cell_id)
        if (cell_id & 0xFFFF) < FIRST_ENV_CELL or (cell_id & 0xFFFF) == 0xFFFF:
            raise ValueError(f"an env cell id has a low word 0x0100-0xFFFE, got {format_cell_id(cell_id)}")
        self.structure = structure
        self.env = env
        if frame is not None:
            self.pos.frame = frame.copy()
        self.portals = list(portals)
        for portal in self.portals:
            if not any(portal.portal is poly for poly in structure.portals):
                raise ValueError(f"{portal!r} of {format_cell_id(cell_id)} is not a portal of its structure")

    @property
    def num_portals(self) -> int:
        return len(self.portals)

    def find_collisions(self, transition: CellTransition) -> TransitionState:
        """The cell's walls, then (if OK) the bodies shadowed in it.

        Retail: CEnvCell::find_collisions @ 0x0052C100 (acclient.c:347809)
        """
        result = self.find_env_collisions(transition)
        if result == TransitionState.OK:
            result = self.find_obj_collisions(transition)
        return result

    def find_env_collisions(self, transition: CellTransition) -> TransitionState:
        """Entry restrictions, then the physics BSP in the cell's frame (scale 1): initial
        placement uses ``placement_insert``, anything else ``find_collisions``. Clears
        ``obstruction_ethereal``; a result other than OK flags an environment collision unless
        the body is in contact.

        Retail: CEnvCell::find_env_collisions @ 0x0052C130 (acclient.c:347822)
        """
        result = self.check_entry_restrictions(transition)
        if result != TransitionState.OK:
            return result
        path = transition.sphere_path
        path.obstruction_ethereal = False
        bsp = self.structure.physics_bsp
        if bsp is None:
            return result
        path.cache_localspace_sphere(self.pos, 1.0)
        if path.insert_type == InsertType.INITIAL_PLACEMENT:
            result = bsp.placement_insert(transition)
        else:
            result = bsp.find_collisions(transition, 1.0)
        if result != TransitionState.OK and not transition.object_info.state & ObjectInfoState.CONTACT:
            transition.collision_info.collided_with_environment = True
        return result

    def point_in_cell(self, point: Vector3) -> bool:
        """Whether the landblock-local ``point`` is in the room; a cell without portals never is.

        Retail: CEnvCell::point_in_cell @ 0x0052C300 (acclient.c:347934)
        """
        if not self.portals:
            return False
        return self.structure.point_in_cell(self.pos.frame.globaltolocal(point))

    def find_transit_cells(
        self, p: Position, spheres: Sequence[Sphere], cell_array: CellArray, path: SpherePath | None
    ) -> None:
        """Add the cells the global ``spheres`` reach through this cell's portals.

        - a portal to the outside is crossed when some sphere is within ``radius + EPSILON`` of
          its (unbounded) plane; then, after all portals, every outdoor cell the spheres touch
          is added (``LandCell.add_all_outside_cells``);
        - a loaded other cell is added when some sphere, in that cell's frame, is not outside its
          cell BSP (the portal plane is not consulted);
        - an unloaded other cell is added (as an id) when some sphere is, on portal side 1, above
          ``-(radius + EPSILON)`` from the portal plane, or on side 0 below ``radius + EPSILON``.

        The two portal tests differ in what is stored: the outside test inlines the transform
        (see ``_outside_portal_dist``) and keeps ``radius + EPSILON`` in a ``float`` local
        (acclient.c:348315); the unloaded-cell test stores the local centre (a ``Vector3``) and
        keeps the reach in a register (acclient.c:348371).

        Retail: CEnvCell::find_transit_cells @ 0x0052C820 (acclient.c:348249)
        """
        check_outside = False
        frame = self.pos.frame
        to_local = frame.globaltolocal
        for portal in self.portals:
            if portal.other_cell_id == OUTSIDE_CELL_ID:
                for sphere in spheres:
                    reach = f32(sphere.radius + EPSILON)
                    dist = _outside_portal_dist(frame, portal.portal, sphere.center)
                    if -reach < dist < reach:
                        check_outside = True
                        break
                continue
            other = portal.get_other_cell(cell_array.source)
            if isinstance(other, EnvCell):
                other_local = other.pos.frame.globaltolocal
                for sphere in spheres:
                    local = Sphere.owning(other_local(sphere.center), sphere.radius)
                    if other.structure.sphere_intersects_cell(local) != CELL_OUTSIDE:
                        cell_array.add_cell(other.id, other)
                        break
                continue
            for sphere in spheres:
                reach = sphere.radius + EPSILON
                dist = _portal_dist(portal.portal, to_local(sphere.center))
                if (dist > -reach and portal.portal_side == 1) or (dist < reach and portal.portal_side == 0):
                    cell_array.add_cell(portal.other_cell_id, None)
                    break
        if check_outside:
            from acphys.world.land_cell import LandCell

            LandCell.add_all_outside_cells(p, spheres, cell_array)

    def find_transit_cells_for_parts(self, parts: Sequence[PhysicsPart], cell_array: CellArray) -> None:
        """Add the cells the parts' bounding boxes reach through this cell's portals.

        Portal by portal, the first part that gets through decides. A part (with a sphere) gets
        through when its sphere is not wholly on this cell's side of the portal plane (more than
        ``radius + EPSILON`` negative for ``portal_side`` 1, positive for 0) and its box, in this
        cell's frame, is not wholly on the ``Sidedness`` equal to ``portal_side``. Then: a portal
        to the outside marks the outdoor cells for after the loop (``add_all_outside_cells`` for
        the parts); an unloaded other cell is added as an id; a loaded one is added when the box,
        in its frame, intersects its cell BSP, and otherwise the next part is tried.
        ``radius + EPSILON`` is a ``float`` local (acclient.c:348462-348466).

        Retail: CEnvCell::find_transit_cells @ 0x0052CAE0 (acclient.c:348406)
        """
        check_outside = False
        for portal in self.portals:
            plane = portal.portal.plane
            side = portal.portal_side
            for part in parts:
                sphere = part.get_sphere()
                if sphere is None:
                    continue
                reach = f32(sphere.radius + EPSILON)
                dist = _part_portal_dist(self.pos, part, sphere, portal.portal)
                if (side == 0 and dist > reach) or (side == 1 and dist < -reach):
                    continue
                bbox = part.get_bounding_box()
                if plane.intersect_box(BBox.local_to_local(bbox, part.pos, self.pos)) == side:
                    continue
                if portal.other_cell_id == OUTSIDE_CELL_ID:
                    check_outside = True
                    break
                other = portal.get_other_cell(cell_array.source)
                if not isinstance(other, EnvCell):
                    cell_array.add_cell(portal.other_cell_id, None)
                    break
                cell_box = BBox.local_to_local(bbox, part.pos, other.pos)
                if other.structure.box_intersects_cell(cell_box.min, cell_box.max):
                    cell_array.add_cell(other.id, other)
                    break
        if check_outside:
            from acphys.world.land_cell import LandCell

            LandCell.add_all_outside_cells_for_parts(parts, cell_array)

    def check_building_transit_for_parts(
        self, portal_id: int, parts: Sequence[PhysicsPart], cell_array: CellArray
    ) -> None:
        """From a building door into this cell (through this cell's portal ``portal_id``): the
        first part (with a sphere) whose sphere is not wholly on the outside of the portal plane
        (more than ``radius + EPSILON`` positive for ``portal_side`` 1, negative for 0), whose box
        in this cell's frame crosses the plane or lies wholly on the ``Sidedness`` equal to
        ``portal_side``, and whose box intersects the cell BSP adds this cell, and the cells the
        parts reach from it (``find_transit_cells_for_parts``). ``portal_id < 0``: nothing.
        ``radius + EPSILON`` is a ``float`` local (acclient.c:348199-348204).

        Retail: CEnvCell::check_building_transit @ 0x0052C680 (acclient.c:348153)
        """
        if portal_id < 0:
            return
        if portal_id >= len(self.portals):
            count = len(self.portals)
            raise ValueError(f"{format_cell_id(self.id)} has {count} portals, no portal {portal_id}")
        portal = self.portals[portal_id]
        plane = portal.portal.plane
        side = portal.portal_side
        for part in parts:
            sphere = part.get_sphere()
            if sphere is None:
                continue
            reach = f32(sphere.radius + EPSILON)
            dist = _part_portal_dist(self.pos, part, sphere, portal.portal)
            if (side == 1 and dist > reach) or (side == 0 and dist < -reach):
                continue
            box = BBox.local_to_local(part.get_bounding_box(), part.pos, self.pos)
            where = plane.intersect_box(box)
            if where not in (Sidedness.CROSSING, side):
                continue
            if self.structure.box_intersects_cell(box.min, box.max):
                cell_array.add_cell(self.id, self)
                self.find_transit_cells_for_parts(parts, cell_array)
                return

    def check_building_transit(
        self,
        portal_id: int,
        p: Position,
        spheres: Sequence[Sphere],
        cell_array: CellArray,
        path: SpherePath | None,
    ) -> None:
        """From a building portal into this cell: with ``portal_id >= 0``, the first sphere not
        outside the cell BSP (in this cell's frame) adds the cell and sets
        ``path.hits_interior_cell``. ``p`` is unused, as in retail.

        Retail: CEnvCell::check_building_transit @ 0x0052C5D0 (acclient.c:348109)
        """
        if portal_id < 0:
            return
        to_local = self.pos.frame.globaltolocal
        for sphere in spheres:
            if self.structure.sphere_intersects_cell(Sphere.owning(to_local(sphere.center), sphere.radius)):
                if path is not None:
                    path.hits_interior_cell = True
                cell_array.add_cell(self.id, self)
                return

    def recursively_get_object(
        self, obj_iid: int, source: CellSource, visited_cells: set[int]
    ) -> PhysicsObj | None:
        """This cell's object ``obj_iid``, else the first found through the portals, depth
        first; an other cell is marked visited before it is searched (this cell is not).

        Retail: CEnvCell::recursively_get_object @ 0x0052D8A0 (acclient.c:349403)
        """
        found = self.get_object(obj_iid)
        if found is not None:
            return found
        for portal in self.portals:
            other_id = portal.other_cell_id
            if other_id in visited_cells or other_id == OUTSIDE_CELL_ID:
                continue
            other = portal.get_other_cell(source)
            if isinstance(other, EnvCell):
                visited_cells.add(other_id)
                found = other.recursively_get_object(obj_iid, source, visited_cells)
                if found is not None:
                    return found
        return None
