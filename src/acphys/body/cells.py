"""Where a body is: its cell, its shadows in the cells it overlaps, entering and leaving, placement."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from acphys.constants import BLOCK_LENGTH
from acphys.flags import ObjectInfoState, PhysicsState, TransientState, member_namespace
from acphys.geometry.sphere import DUMMY_SPHERE
from acphys.math.cell_id import adjust_to_outside, is_outdoor
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, unpack3
from acphys.transition.transition import Transition
from acphys.world.obj_cell import Box, CellArray, ObjCell, ShadowObj

if TYPE_CHECKING:
    from acphys.world.env_cell import EnvCell
    from acphys.world.world import World

PS = member_namespace(PhysicsState)
TS = member_namespace(TransientState)


def _find_visible_child_cell(
    cell: EnvCell, origin: Vector3, search_cells: bool, world: World
) -> ObjCell | None:
    """The room holding the landblock-local ``origin``: ``cell`` itself, else (``search_cells``)
    the first loaded cell of its stab list that holds it, else (not searching) the first
    portal neighbour that does.

    Retail: CEnvCell::find_visible_child_cell @ 0x0052DC50 (acclient.c:349697)
    """
    if cell.point_in_cell(origin):
        return cell
    if search_cells:
        candidates = (world.get_cell(cell_id) for cell_id in cell.stab_list)
    else:
        candidates = (portal.get_other_cell(world) for portal in cell.portals)
    for other in candidates:
        if other is not None and other.point_in_cell(origin):
            return other
    return None


#: ``CheckPositionInternal``: how far (signed, in x and in y) a placement without SLIDE may move
#: the body (acclient.c:319180-319181).
PLACEMENT_TOLERANCE = f32(0.050000001)


class SetPositionFlags(enum.IntFlag):
    """``SetPositionFlag`` (acclient.h:6123): what ``SetPosition`` may do."""

    PLACEMENT = 0x1
    TELEPORT = 0x2
    RESTORE = 0x4
    SLIDE = 0x10
    DONT_CREATE_CELLS = 0x20
    SCATTER = 0x100
    RANDOM_SCATTER = 0x200
    LINE = 0x400
    SEND_POSITION_EVENT = 0x1000


#: ``enter_world``'s PLACEMENT | SLIDE, combined once. The bits of a ``SetPositionStruct`` are
#: tested on plain ints (``int(flags) & int(FLAG)``): ``IntFlag``'s ``&`` builds a flag member.
_ENTER_WORLD_FLAGS = SetPositionFlags.PLACEMENT | SetPositionFlags.SLIDE


class PhysicsTimeStamp(enum.IntEnum):
    """``PhysicsTimeStamp`` (acclient.h:6084): the slots of ``update_times``."""

    POSITION = 0x0
    MOVEMENT = 0x1
    STATE = 0x2
    VECTOR = 0x3
    TELEPORT = 0x4
    SERVER_CONTROLLED_MOVE = 0x5
    FORCE_POSITION = 0x6
    OBJDESC = 0x7
    INSTANCE = 0x8


#: ``NUM_PHYSICS_TS``: how many 16-bit stamps a body keeps (acclient.h:6095).
NUM_PHYSICS_TS = 9

#: ``MoveOrTeleport``: from this far from the player a same-teleport move snaps instead of
#: interpolating (``player_distance >= 96.0``, acclient.c:323483).
MOVE_OR_TELEPORT_SNAP_DISTANCE = 96.0


def is_newer(timestamp: int, new_time: int) -> bool:
    """Whether the 16-bit stamp ``new_time`` is later than ``timestamp``, wrapping: a gap above
    0x7FFF reads the other way round.

    Retail: CPhysicsObj::is_newer @ 0x00451AD0 (acclient.c:143002)
    """
    if abs(new_time - timestamp) > 0x7FFF:
        return new_time < timestamp
    return timestamp < new_time


def _check_stamp(stamp: int) -> int:
    if isinstance(stamp, bool) or not isinstance(stamp, int) or not 0 <= stamp <= 0xFFFF:
        raise ValueError(f"physics timestamp must be a 16-bit integer, got {stamp!r}")
    return stamp


class SetPositionError(enum.IntEnum):
    """``SetPositionError`` (acclient.h:6111): what ``SetPosition`` returns."""

    OK = 0x0
    GENERAL_FAILURE = 0x1
    NO_VALID_POSITION = 0x2
    NO_CELL = 0x3
    COLLIDED = 0x4


@dataclass(slots=True)
class SetPositionStruct:
    """Retail ``SetPositionStruct`` (acclient.h:52398): a position and how to place a body there.

    ``xrad`` and ``yrad`` are ``float`` fields: they are narrowed when the struct is made.

    Retail: SetPositionStruct::SetPositionStruct @ 0x0051BB50 (acclient.c:329731)
    """

    pos: Position = field(default_factory=Position)
    flags: SetPositionFlags = field(default=SetPositionFlags(0))
    line: Vector3 = field(default_factory=Vector3)
    xrad: float = 0.0
    yrad: float = 0.0
    num_tries: int = 0

    def __post_init__(self) -> None:
        self.xrad = f32(self.xrad)
        self.yrad = f32(self.yrad)


class CellMembership:
    """Cells, shadows, placement and the lost cell (part of :class:`PhysicsObj`)."""

    # -- cells and placement ---------------------------------------------------------------

    def change_cell(self, new_cell: ObjCell | None) -> None:
        """Leave the current cell and enter ``new_cell`` (or none).

        Retail: CPhysicsObj::change_cell @ 0x00513390 (acclient.c:320421)
        """
        if self.cell is not None:
            self.leave_cell()
        if new_cell is not None:
            self.enter_cell(new_cell)
        else:
            self.position.objcell_id = 0
            if self.part_array is not None and not self._state & PS.PARTICLE_EMITTER:
                self.part_array.set_cell_id(0)
            self.cell = None

    def enter_cell(self, new_cell: ObjCell) -> None:
        """Join ``new_cell``'s object list, with every child, and take its id (bodies without
        parts cannot).

        Retail: CPhysicsObj::enter_cell @ 0x00510ED0 (acclient.c:318201)
        """
        if self.part_array is None:
            return
        new_cell.add_object(self)
        if self.children is not None:
            for child in list(self.children.objects):
                child.enter_cell(new_cell)
        self.position.objcell_id = new_cell.id
        if not self._state & PS.PARTICLE_EMITTER:
            self.part_array.set_cell_id(new_cell.id)
        self.cell = new_cell

    def leave_cell(self) -> None:
        """Leave the cell's object list, with every child.

        Retail: CPhysicsObj::leave_cell @ 0x00510F50 (acclient.c:318243)
        """
        if self.cell is not None:
            self.cell.remove_object(self)
            if self.children is not None:
                for child in list(self.children.objects):
                    child.leave_cell()
            self.cell = None

    def store_position(self, pos: Position) -> None:
        """Take ``pos`` as the position without touching cells, re-homing outdoor origins.

        Retail: CPhysicsObj::store_position @ 0x005141A0 (acclient.c:321388)
        """
        stored = pos.copy()
        if is_outdoor(stored.objcell_id):
            stored.objcell_id = adjust_to_outside(stored.objcell_id, stored.frame.origin)
        self.position.objcell_id = stored.objcell_id
        self.set_frame(stored.frame)

    def leave_world(self) -> None:
        """Take the body out of the world: out of the lost cell, its shadows and its cell, off the
        ground (telling the movement manager), inactive, with no contact, sliding or stationary state.

        First every object collision is ended (``report_collision_end(True)``).

        Retail: CPhysicsObj::leave_world @ 0x005155A0 (acclient.c:322653)
        """
        self.report_collision_end(True)
        self.world.remove_from_lost_cell(self)
        self._transient_state &= ~TS.ACTIVE
        self.remove_shadows_from_cells()
        self.leave_cell()
        self.position.objcell_id = 0
        if self.part_array is not None and not self._state & PS.PARTICLE_EMITTER:
            self.part_array.set_cell_id(0)
        self.clear_transient_states()  # inline in retail (acclient.c:322680-322691)

    def prepare_to_leave_visibility(self) -> None:
        """Take the body out of every cell (its shadows, the lost cell, its own cell).

        Retail also queues the body for destruction by the object maintainer,
        which is client bookkeeping, not physics.

        Retail: CPhysicsObj::prepare_to_leave_visibility @ 0x00511F40 (acclient.c:319195)
        """
        self.remove_shadows_from_cells()
        self.world.remove_from_lost_cell(self)
        self.leave_cell()

    def enter_world(self, pos: Position) -> bool:
        """Put the body into the world at ``pos``: store it, then place it sliding.

        Retail: CPhysicsObj::enter_world @ 0x00516310 (acclient.c:323440), which calls
        CPhysicsObj::enter_world @ 0x00516170 (acclient.c:323345): a parented body cannot;
        ``update_time`` resyncs; ``set_position`` with PLACEMENT | SLIDE at the stored position
        must return OK; then a non-static body is activated and the part array and movement
        manager handle entering the world.
        """
        self.store_position(pos)
        if self.parent is not None:
            return False
        self.update_time = self.world.cur_time
        sps = SetPositionStruct(self.position.copy(), _ENTER_WORLD_FLAGS)
        if self.set_position(sps) != SetPositionError.OK:
            return False
        self.set_active(True)
        if self.part_array is not None:
            self.part_array.handle_enter_world()
        if self.movement_manager is not None:
            self.movement_manager.handle_enter_world()
        return True

    def newer_event(self, stamp: PhysicsTimeStamp, new_time: int) -> bool:
        """Whether ``new_time`` is later than the body's ``stamp`` slot (:func:`is_newer`); if so it
        is stored there.

        Retail: CPhysicsObj::newer_event @ 0x00451B10 (acclient.c:143014)
        """
        _check_stamp(new_time)
        if not is_newer(self.update_times[stamp], new_time):
            return False
        self.update_times[stamp] = new_time
        return True

    def move_or_teleport(
        self, p: Position, teleport_timestamp: int, contact: bool, velocity: Vector3
    ) -> bool:
        """A server position for the body; False when ignored.

        A teleport stamp older than the body's is ignored. A newer one (stored) or a body with no
        cell teleports: ``teleport_hook``, then ``set_position`` with TELEPORT | SLIDE |
        SEND_POSITION_EVENT. Otherwise the move is ignored without ``contact``; a body 96 m or
        more from the player (``player_distance``, not the distance to ``p``) stops interpolating
        and snaps there (``set_position_simple``, sliding); a nearer one interpolates, keeping
        its heading while it is moving to something. ``velocity`` is unused, as in retail.

        Retail: CPhysicsObj::MoveOrTeleport @ 0x00516330 (acclient.c:323450)
        """
        _check_stamp(teleport_timestamp)
        if is_newer(teleport_timestamp, self.update_times[PhysicsTimeStamp.TELEPORT]):
            return False
        if self.newer_event(PhysicsTimeStamp.TELEPORT, teleport_timestamp) or self.cell is None:
            self.teleport_hook(True)
            flags = SetPositionFlags.TELEPORT | SetPositionFlags.SLIDE | SetPositionFlags.SEND_POSITION_EVENT
            self.set_position(SetPositionStruct(p.copy(), flags))
            return True
        if not contact:
            return False
        if self.player_distance >= MOVE_OR_TELEPORT_SNAP_DISTANCE:
            if self.position_manager is not None:
                self.position_manager.stop_interpolating()
            self.set_position_simple(p, True)
        else:
            self.interpolate_to(p, self.is_moving_to())
        return True

    def set_position_simple(self, pos: Position, sliding: bool) -> int:
        """``set_position`` with TELEPORT | SEND_POSITION_EVENT (and SLIDE when ``sliding``).

        Retail: CPhysicsObj::SetPositionSimple @ 0x005162B0 (acclient.c:323420)
        """
        flags = SetPositionFlags.TELEPORT | SetPositionFlags.SEND_POSITION_EVENT
        if sliding:
            flags |= SetPositionFlags.SLIDE
        return self.set_position(SetPositionStruct(pos.copy(), flags))

    def set_position(self, sps: SetPositionStruct) -> int:
        """Place the body as ``sps`` asks; a :class:`SetPositionError` code (0 is OK).

        A transition from the pool (object state 0) carries the body's spheres, scaled (the
        dummy sphere without any); the pool is full when ten are already running.

        Retail: CPhysicsObj::SetPosition @ 0x005160C0 (acclient.c:323289)
        """
        transit = Transition.make_transition(self.world)
        try:
            transit.init_object(self, ObjectInfoState.DEFAULT)
            if self.part_array is not None and self.part_array.get_num_sphere():
                transit.init_sphere(self.part_array.get_sphere(), self.scale)
            else:
                transit.init_sphere([DUMMY_SPHERE], 1.0)
            return self.set_position_from_struct(sps, transit)
        finally:
            Transition.cleanup_transition()

    def set_position_from_struct(self, sps: SetPositionStruct, transit: Transition) -> int:
        """RANDOM_SCATTER goes straight to the scatter tries; otherwise ``sps.pos`` is tried and,
        failing that with SCATTER, the scatter tries.

        Retail: CPhysicsObj::SetPositionInternal @ 0x00516040 (acclient.c:323257)
        """
        if int(sps.flags) & int(SetPositionFlags.RANDOM_SCATTER):
            return self.set_scatter_position_internal(sps, transit)
        result = self.set_position_with_struct(sps.pos.copy(), sps, transit)
        if result != SetPositionError.OK and int(sps.flags) & int(SetPositionFlags.SCATTER):
            result = self.set_scatter_position_internal(sps, transit)
        return result

    def set_scatter_position_internal(self, sps: SetPositionStruct, transit: Transition) -> int:
        """Up to ``num_tries`` placements at ``sps.pos`` moved by ``RollDice(-1, 1)`` times
        ``xrad`` and ``yrad`` (x then y); the first OK wins. No tries is GENERAL_FAILURE.
        The x offset is spilled to ``float`` before it is added, the y offset is not
        (acclient.c:323236-323242).

        Retail: CPhysicsObj::SetScatterPositionInternal @ 0x00515F00 (acclient.c:323166)
        """
        result = SetPositionError.GENERAL_FAILURE
        for _ in range(sps.num_tries):
            pos = sps.pos.copy()
            dx = f32(self.world.dice.uniform(-1.0, 1.0) * sps.xrad)
            dy = self.world.dice.uniform(-1.0, 1.0) * sps.yrad
            origin = pos.frame.origin
            origin.x, origin.y, origin.z = unpack3(pack3(dx + origin.x, dy + origin.y, origin.z))
            result = self.set_position_with_struct(pos, sps, transit)
            if result == SetPositionError.OK:
                break
        return result

    def set_position_with_struct(self, p: Position, sps: SetPositionStruct, transit: Transition) -> int:
        """Place the body at ``p`` through a placement transition and commit it.

        A body with no cell prepares to enter the world. ``adjust_position`` finds the cell
        under sphere 0's centre; with none the body goes to the lost cell, inactive, and the
        result is OK. Otherwise DONT_CREATE_CELLS keeps the cell array to loaded cells, and
        ``check_position_internal`` must succeed (else COLLIDED when ``handle_all_collisions``
        reports, NO_VALID_POSITION if not), with a cell (else NO_CELL), before the commit.
        Retail first forces storage and corpse weenies into the cell (``ForceIntoCell``); acphys
        weenies are never either.

        Retail: CPhysicsObj::SetPositionInternal @ 0x00515BD0 (acclient.c:323034)
        """
        if self.cell is None:
            self.prepare_to_enter_world()
        new_cell = self.adjust_position(p, transit.sphere_path.local_sphere[0].center, search_cells=True)
        if new_cell is None:
            self.prepare_to_leave_visibility()
            self.store_position(p)
            self.world.goto_lost_cell(self)
            self._transient_state &= ~TS.ACTIVE
            return SetPositionError.OK
        if int(sps.flags) & int(SetPositionFlags.DONT_CREATE_CELLS):
            transit.cell_array.do_not_load_cells = True
        if not self.check_position_internal(new_cell, p, transit, sps):
            reported = self.handle_all_collisions(transit.collision_info, False, False)
            return SetPositionError.COLLIDED if reported else SetPositionError.NO_VALID_POSITION
        if transit.sphere_path.curr_cell is None:
            return SetPositionError.NO_CELL
        self.set_position_internal(transit)
        return SetPositionError.OK

    def check_position_internal(
        self, new_cell: ObjCell, new_pos: Position, transit: Transition, sps: SetPositionStruct
    ) -> bool:
        """Run the placement; without SLIDE it must stay put: ``new_pos`` takes the placed
        origin when it moved less than 0.05 m in x and in y (signed, as retail compares) and
        stayed in ``new_cell``.

        Retail: CPhysicsObj::CheckPositionInternal @ 0x00511E90 (acclient.c:319172)
        """
        transit.init_path(new_cell, None, new_pos)
        slide = int(sps.flags) & int(SetPositionFlags.SLIDE) != 0
        if not slide:
            transit.sphere_path.placement_allows_sliding = False
        if not transit.find_valid_position():
            return False
        if slide:
            return True
        placed = transit.sphere_path.curr_pos
        if (
            placed.frame.origin.x - new_pos.frame.origin.x < PLACEMENT_TOLERANCE
            and placed.frame.origin.y - new_pos.frame.origin.y < PLACEMENT_TOLERANCE
            and placed.objcell_id == new_cell.id
        ):
            new_pos.frame.origin.set(placed.frame.origin)
            return True
        return False

    def adjust_position(self, p: Position, low_pt: Vector3, search_cells: bool) -> ObjCell | None:
        """The cell for ``p`` (re-homing ``p.objcell_id``), None for an invalid cell id or none.

        Outdoors, the land cell under the origin. Indoors, the room holding ``low_pt`` (placed
        by ``p``): the room itself or, with ``search_cells``, one in its stab list (else one
        through its portals); failing that, a room that sees outside hands over to the land
        cell under the origin. (Retail's unused ``bDontCreateCells`` argument is dropped.)

        Retail: CPhysicsObj::AdjustPosition @ 0x00511D80 (acclient.c:319116)
        """
        index = p.objcell_id & 0xFFFF
        if not (1 <= index <= 0x40 or 0x100 <= index <= 0xFFFD or index == 0xFFFF):
            return None
        world = self.world
        if index < 0x100:
            p.objcell_id = adjust_to_outside(p.objcell_id, p.frame.origin)
            return world.get_cell(p.objcell_id) if p.objcell_id else None
        visible = world.get_cell(p.objcell_id)
        if visible is None:
            return None
        child = _find_visible_child_cell(visible, p.frame.localtoglobal(low_pt), search_cells, world)
        if child is not None:
            p.objcell_id = child.id
            return child
        if not visible.seen_outside:
            return None
        p.objcell_id = adjust_to_outside(p.objcell_id, p.frame.origin)
        return world.get_cell(p.objcell_id) if p.objcell_id else None

    def prepare_to_enter_world(self) -> None:
        """Resync ``update_time``, leave the lost cell and activate a non-static body.

        Retail also takes the body and its children off the destroy list (object maintenance).

        Retail: CPhysicsObj::prepare_to_enter_world @ 0x00511FA0 (acclient.c:319217)
        """
        self.update_time = self.world.cur_time
        self.world.remove_from_lost_cell(self)
        self.set_active(True)

    # -- shadows: the cells a body overlaps ---------------------------------------------------

    def add_obj_to_cell(self, new_cell: ObjCell, new_frame: Frame) -> None:
        """Put a static object into ``new_cell`` at ``new_frame`` and shadow it into every cell it overlaps.

        Retail: CPhysicsObj::add_obj_to_cell @ 0x005159E0 (acclient.c:322896)
        """
        self.enter_cell(new_cell)
        self.position.frame.assign(new_frame)
        if not self._state & PS.PARTICLE_EMITTER and self.part_array is not None:
            self.part_array.set_frame(self.position.frame)
        self.calc_cross_cells_static()

    def calc_cross_cells_static(self) -> None:
        """A static object's shadows: its cylspheres' cells, else its parts' bounding boxes; cells not
        yet loaded are left out.

        Retail: CPhysicsObj::calc_cross_cells_static @ 0x00515160 (acclient.c:322404)
        """
        cell_array = CellArray(self.world)
        cell_array.do_not_load_cells = True
        parts = self.part_array
        if not self._state & PS.HAS_PHYSICS_BSP and parts is not None and parts.get_num_cylsphere():
            ObjCell.find_cell_list_for_cylspheres(self.position, parts.get_cylsphere(), cell_array)
        else:
            self.find_bbox_cell_list(cell_array)
        self.remove_shadows_from_cells()
        self.add_shadows_to_cells(cell_array)

    def calc_cross_cells(self) -> None:
        """A body's shadows: its bounding boxes (physics-BSP objects), its cylspheres, else its
        sorting sphere.

        Retail: CPhysicsObj::calc_cross_cells @ 0x00515230 (acclient.c:322446)
        """
        cell_array = CellArray(self.world)
        parts = self.part_array
        if self._state & PS.HAS_PHYSICS_BSP:
            self.find_bbox_cell_list(cell_array)
        elif parts is not None and parts.get_num_cylsphere():
            ObjCell.find_cell_list_for_cylspheres(self.position, parts.get_cylsphere(), cell_array)
        else:
            sphere = parts.get_sorting_sphere() if parts is not None else DUMMY_SPHERE
            ObjCell.find_cell_list_for_sphere(self.position, sphere, cell_array)
        self.remove_shadows_from_cells()
        self.add_shadows_to_cells(cell_array)

    def find_bbox_cell_list(self, cell_array: CellArray) -> None:
        """The body's own cell, then every cell its parts' bounding boxes reach from there.

        Retail: CPhysicsObj::find_bbox_cell_list @ 0x00510FC0 (acclient.c:318275)
        """
        cell_array.clear()
        if self.cell is None:
            return
        cell_array.add_cell(self.cell.id, self.cell)
        if self.part_array is None:
            return
        index = 0
        while index < cell_array.num_cells:
            cell = cell_array.cells[index].cell
            if cell is not None:
                self.part_array.calc_cross_cells_static(cell, cell_array)
            index += 1

    def add_shadows_to_cells(self, cell_array: CellArray) -> None:
        """Make one shadow per cell of ``cell_array`` and enter it into that cell (if loaded).

        Retail: CPhysicsObj::add_shadows_to_cells @ 0x00514AE0 (acclient.c:321977)
        """
        self.shadow_objects = [ShadowObj(self, info.cell_id) for info in cell_array.cells]
        for shadow, info in zip(self.shadow_objects, cell_array.cells, strict=True):
            if info.cell is not None:
                info.cell.add_shadow_object(shadow, cell_array.num_cells)

    def remove_shadows_from_cells(self) -> None:
        """Take every shadow out of its cell.

        Retail: CPhysicsObj::remove_shadows_from_cells @ 0x00511230 (acclient.c:318417)
        """
        for shadow in self.shadow_objects:
            if shadow.cell is not None:
                shadow.cell.remove_shadow_object(shadow)
        self.shadow_objects = []

    # -- the box a crowded cell files a shadow by (not retail) ------------------------------

    def collision_box(self) -> Box | None:
        """The box, in landblock-global metres, around the spheres ``find_obj_collisions`` tests
        (placed at ``position`` and ``scale`` as ``intersects_sphere_placed`` places them); None
        for a body every sweep must ask: one with cylspheres or a physics BSP, a particle
        emitter (its parts do not follow its frame, so a turn would not re-file it), one with no
        cell, or one with a coordinate that is not finite.

        Not retail: a cell with many shadows files them by this box, so that a sweep asks only
        the bodies it could touch (:meth:`ObjCell.find_obj_collisions`); the part array re-files
        the body whenever its frame, cell or scale changes (:meth:`shadows_moved`).
        """
        parts = self.part_array
        cell_id = self.position.objcell_id
        if parts is None or not cell_id or self._state & PS.PARTICLE_EMITTER or parts.get_num_cylsphere():
            return None
        if any(part.physics_bsp is not None for part in parts.parts):
            return None
        frame = self.position.frame
        m, origin = frame.m, frame.origin
        ox = origin.x + ((cell_id >> 24) & 0xFF) * BLOCK_LENGTH
        oy = origin.y + ((cell_id >> 16) & 0xFF) * BLOCK_LENGTH
        oz = origin.z
        scale = self.scale
        x0 = y0 = z0 = math.inf
        x1 = y1 = z1 = -math.inf
        for sphere in parts.get_sphere():
            center = sphere.center
            cx, cy, cz = center.x * scale, center.y * scale, center.z * scale
            x = m[3] * cy + m[0] * cx + m[6] * cz + ox
            y = m[4] * cy + m[1] * cx + m[7] * cz + oy
            z = m[5] * cy + m[2] * cx + m[8] * cz + oz
            radius = sphere.radius * scale
            x0, x1 = min(x0, x - radius), max(x1, x + radius)
            y0, y1 = min(y0, y - radius), max(y1, y + radius)
            z0, z1 = min(z0, z - radius), max(z1, z + radius)
        box = (x0, y0, z0, x1, y1, z1)
        if not math.isfinite(x0 + y0 + z0 + x1 + y1 + z1):
            return None
        return box

    def shadows_moved(self) -> None:
        """The body's frame, cell or scale changed: its shadows in cells that file them are
        filed again by its new :meth:`collision_box`."""
        box: Box | None = None
        boxed = False
        for shadow in self.shadow_objects:
            cell = shadow.cell
            if cell is not None and cell.shadow_tiles is not None:
                if not boxed:
                    box, boxed = self.collision_box(), True
                cell.refile_shadow(shadow, box)
