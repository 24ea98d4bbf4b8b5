"""``CTransition``: one sweep of a body from where it is to where it wants to be.

``find_transitional_position`` cuts the path into steps no longer than sphere 0's radius
(``calc_num_steps``). Each step's offset is first bent by the contact plane and the sliding
normal (``adjust_offset``), then the candidate (``check_pos``) is moved, inserted into its cells
(``transitional_insert``: each cell's ``find_collisions`` and the cells the spheres reach, with
step-up, step-down, edge and cliff slides), and accepted or rolled back by
``validate_transition``, which also keeps the stationary-fall counter and the contact state.

``SPHEREPATH`` lives in :mod:`acphys.transition.sphere_path` (re-exported here); placements
(``find_placement_position`` and its helpers) in :mod:`acphys.transition.placement`.

Sweeps take their transition from retail's static pool of ten (``Transition.make_transition``,
``CTransition::makeTransition``): one per nesting level, built once and reused, for the body's
sweeps (``CPhysicsObj::transition``), its placements (``SetPosition``) and its collision checks.
Handing one out runs ``init``, which resets only what ``CTransition::init`` resets (the object
info's object, state and target, ``SPHEREPATH::init``'s fields, ``COLLISIONINFO``'s flags and
counters, the cell array); the rest (positions, planes and normals behind cleared validity flags,
walkable and step records) carries over from the last sweep that used the slot, as in the client.
A ``Transition(...)`` built directly (the tests do) starts from the defaults.

Not ported: ``find_transitional_position``'s placement-insert branch (acclient.c:313288-313297):
it runs only for a path whose ``insert_type`` is not TRANSITION, and ``find_valid_position``
sends those to ``find_placement_position`` instead; every temporary change of ``insert_type``
inside a step is undone before the step ends.

Divergences from ACE's ``Transition.cs`` (the decompilation wins):

- ``EdgeSlide`` evaluates ``CliffSlide`` and ``PrecipiceSlide`` as arguments of
  ``SetEdgeSlide``, so they slide from the stepped-down candidate before it is restored;
  retail restores the candidate first and slides from there (acclient.c:312713-312725).
- ``InitLastKnownContactPlane`` stores the cell id as ``LastKnownContactPlaneCellID``; retail
  writes it to ``contact_plane_cell_id`` (acclient.c:315617).
- ``FindTransitionalPosition`` gives up on more than 1000 steps (server shortcut); retail has
  no cap.
- The small-offset stop in ``find_transitional_position`` is a compare Hex-Rays lost
  (acclient.c:313271-313273: only ``global_offset.z`` and the FPU flags survive). acphys reads it
  as ACE does, ``|global_offset|² < EPSILON²``, the only reading under which the stop (return
  ``step != 0 && ts == OK``) makes sense.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, ClassVar

from acphys.constants import EPSILON, LANDING_Z, SMALL_STEP_DOWN_HEIGHT
from acphys.flags import ObjectInfoState, PhysicsState, TransitionState, member_namespace
from acphys.geometry.plane import Plane
from acphys.math.cell_id import adjust_to_outside, get_block_offset
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo, x87_divide
from acphys.transition.sphere_path import InsertType, SpherePath
from acphys.world import obj_cell as cells  # a module, not names from it: the cells import this module

if TYPE_CHECKING:
    from acphys.geometry.sphere import Sphere
    from acphys.math.position import Position
    from acphys.physics_obj import PhysicsObj
    from acphys.world.obj_cell import CellSource, ObjCell
    from acphys.world.world import World

__all__ = ["MAX_TRANSITION_LEVEL", "InsertType", "SpherePath", "Transition"]

TS = member_namespace(TransitionState)
OI = member_namespace(ObjectInfoState)
IT = member_namespace(InsertType)

#: ``makeTransition`` hands out at most ten nested transitions (acclient.c:312564).
MAX_TRANSITION_LEVEL = 10


class Transition:
    """Retail ``CTransition`` (acclient.h:52329): object info, sphere path, collision info and
    the cell array of one sweep.

    ``obj`` only becomes ``object_info.object``; :meth:`init_object` reads its state.
    ``cell_array`` ends holding the cells the spheres overlap where the sweep stopped: where
    ``SetPositionInternal`` casts the body's shadows.

    Retail: CTransition::CTransition @ 0x0050A980 (acclient.c:312147)
    """

    __slots__ = ("cell_array", "collision_info", "object_info", "sphere_path", "world")

    #: ``CTransition::transition_level``: how many transitions are running, nested.
    transition_level: ClassVar[int] = 0

    def __init__(self, world: CellSource, obj: PhysicsObj | None = None) -> None:
        self.world = world
        self.object_info = ObjectInfo()
        self.sphere_path = SpherePath()
        self.collision_info = CollisionInfo()
        self.cell_array = cells.CellArray(world)
        self.init()
        self.object_info.object = obj

    # -- the pool ---------------------------------------------------------------------------------

    @classmethod
    def pool(cls, world: World) -> list[Transition]:
        """``transit``, retail's static pool of ten transitions, of ``world``: made on the first
        request and reused ever after. One client has one; here each world (a simulation) has
        its own, so what one simulation's sweeps leave in the pool never reaches another's."""
        if not world.transition_pool:
            world.transition_pool = [cls(world) for _ in range(MAX_TRANSITION_LEVEL)]
        return world.transition_pool

    @classmethod
    def make_transition(cls, world: World) -> Transition:
        """``world``'s pool transition for the next nesting level, ``init``-ed; past ten levels, a
        ``RuntimeError`` (retail returns no transition, and the sweep that asked for it fails).

        The pool is retail's (:meth:`pool`): ten transitions made once and reused, so what
        ``init`` does not reset (the sphere path's positions, low points, walkable and step
        records, the collision record's planes) carries over from the last sweep that used the
        slot, as it does in the client.

        Retail: CTransition::makeTransition @ 0x0050B150 (acclient.c:312542)
        """
        if cls.transition_level >= MAX_TRANSITION_LEVEL:
            raise RuntimeError(
                f"CTransition::makeTransition: more than {MAX_TRANSITION_LEVEL} nested transitions"
            )
        transit = cls.pool(world)[cls.transition_level]
        transit.init()
        cls.transition_level += 1
        return transit

    @classmethod
    def cleanup_transition(cls) -> None:
        """Give the innermost nesting level back.

        Retail: CTransition::cleanupTransition @ 0x00509DC0 (acclient.c:311588)
        """
        if cls.transition_level <= 0:
            raise RuntimeError("CTransition::cleanupTransition: no transition is running")
        cls.transition_level -= 1

    # -- set-up ---------------------------------------------------------------------------------

    def init(self) -> None:
        """Clear the object, the path, the collision record and the cell array.

        Retail: CTransition::init @ 0x00509DD0 (acclient.c:311595)
        """
        info = self.object_info
        info.object = None
        info.state = OI.DEFAULT
        info.target_id = 0
        self.sphere_path.init()
        self.collision_info.init()
        self.cell_array.clear()
        self.cell_array.do_not_load_cells = False

    def init_object(self, obj: PhysicsObj, object_state: ObjectInfoState) -> None:
        """``OBJECTINFO::init`` for the moving object (the decompilation has only the prototype,
        acclient_protos.h:6191, of this forwarder).

        Retail: OBJECTINFO::init @ 0x0050CF30 (acclient.c:314117)
        """
        self.object_info.init(obj, object_state)

    def init_sphere(self, spheres: list[Sphere], scale: float) -> None:
        """The body's first two spheres, scaled, as the spheres to sweep.

        Retail: CTransition::init_sphere @ 0x00509E50 (acclient.c:311619)
        """
        self.sphere_path.init_sphere(spheres, scale)

    def init_path(self, begin_cell: ObjCell | None, begin_pos: Position | None, end_pos: Position) -> None:
        """The path from ``begin_pos`` (in ``begin_cell``) to ``end_pos``; None begins a placement.

        Retail: CTransition::init_path @ 0x00509E60 (acclient.c:311625)
        """
        self.sphere_path.init_path(begin_cell, begin_pos, end_pos)

    def init_contact_plane(self, cell_id: int, plane: Plane, is_water: bool) -> None:
        """Start in contact with ``plane``: it is both the contact and the last known contact plane.

        Retail: CTransition::init_contact_plane @ 0x0050E850 (acclient.c:315598)
        """
        info = self.collision_info
        info.last_known_contact_plane_valid = True
        info.last_known_contact_plane = plane.copy()
        info.last_known_contact_plane_is_water = is_water
        info.last_known_contact_plane_cell_id = cell_id
        info.contact_plane_valid = True
        info.contact_plane = plane.copy()
        info.contact_plane_is_water = is_water
        info.contact_plane_cell_id = cell_id

    def init_last_known_contact_plane(self, cell_id: int, plane: Plane, is_water: bool) -> None:
        """Remember ``plane`` as the last known contact plane. Retail stores ``cell_id`` as the
        *contact* plane's cell id, leaving the last known one untouched.

        Retail: CTransition::init_last_known_contact_plane @ 0x0050E8E0 (acclient.c:315611)
        """
        info = self.collision_info
        info.last_known_contact_plane_valid = True
        info.last_known_contact_plane = plane.copy()
        info.last_known_contact_plane_is_water = is_water
        info.contact_plane_cell_id = cell_id

    def init_sliding_normal(self, normal: Vector3) -> None:
        """Start sliding along the horizontal part of ``normal``, normalised (zero if too short).

        Retail: CTransition::init_sliding_normal @ 0x0050FF20 (acclient.c:317252)
        """
        info = self.collision_info
        info.sliding_normal_valid = True
        info.sliding_normal = Vector3(normal.x, normal.y, 0.0)
        if info.sliding_normal.normalize_check_small():
            info.sliding_normal = Vector3()

    # -- the sweep --------------------------------------------------------------------------------

    def find_valid_position(self) -> bool:
        """Sweep the path (a transition) or place the body (a placement); True when the body has
        a valid ``curr_pos``/``curr_cell``.

        Retail: CTransition::find_valid_position @ 0x0050C310 (acclient.c:313418)
        """
        if self.sphere_path.insert_type == IT.TRANSITION:
            return self.find_transitional_position()
        try:
            from acphys.transition.placement import find_placement_position
        except ModuleNotFoundError as exc:
            if exc.name != "acphys.transition.placement":
                raise
            raise NotImplementedError(
                "placement inserts (SPHEREPATH insert_type PLACEMENT) need "
                "acphys.transition.placement.find_placement_position, which is not there yet"
            ) from exc
        return find_placement_position(self)

    def calc_num_steps(self) -> tuple[Vector3, Vector3, int]:
        """``(offset, offset_per_step, num_steps)`` for the path.

        Steps are at most sphere 0's radius: ``ceil(dist / radius)`` of them when the path is
        longer than one radius, else one (none for a zero offset). A viewer takes full-radius
        steps, ``floor(dist / radius) + 1`` of them (none within EPSILON). A placement (no
        ``begin_pos``) is one step of nothing.

        Retail: CTransition::calc_num_steps @ 0x0050A0B0 (acclient.c:311763)
        """
        path = self.sphere_path
        if path.begin_pos is None or path.end_pos is None:
            return Vector3(), Vector3(), 1
        offset = path.begin_pos.get_offset(path.end_pos)
        radius = path.local_sphere[0].radius
        if not radius > 0.0:
            raise ValueError(f"CTransition.calc_num_steps: sphere 0 has radius {radius}, steps need > 0")
        dist = offset.length()
        if self.object_info.state & OI.IS_VIEWER:
            if dist <= EPSILON:
                return offset, Vector3(), 0
            steps = dist / radius
            return offset, offset * (1.0 / steps), math.floor(steps) + 1
        steps = dist / (1.0 * radius)
        if steps > 1.0:
            num_steps = math.ceil(steps)
            return offset, offset * (1.0 / num_steps), num_steps
        if offset.x != 0.0 or offset.y != 0.0 or offset.z != 0.0:
            return offset, offset.copy(), 1
        return offset, Vector3(), 0

    def adjust_offset(self, offset: Vector3) -> Vector3:
        """Bend one step's ``offset`` by the sliding normal and the contact plane.

        A valid sliding normal the step runs into (``offset · n < 0``) constrains it; one it
        leaves is dropped. On a contact plane the step runs along the slide line (the plane
        and sliding normal's intersection; zero if they are parallel), or loses its part into
        the plane, or (leaving the plane) has its z snapped onto it; a sphere sunk more than
        EPSILON into a dry contact plane with a cell is lifted onto it when the lift is less
        than its radius. Without a contact plane the step loses its part into the sliding normal.

        The dot products run in retail's orders. ``float`` stores (acclient.c:311909-311995):
        the step's component into the plane (a local), and of each product subtracted from the
        step only the ones the decompilation spills (z into the plane; y and z into the sliding
        normal); the sphere's centre moved across blocks stays in the FPU.

        Retail: CTransition::adjust_offset @ 0x0050A370 (acclient.c:311863)
        """
        info = self.collision_info
        path = self.sphere_path
        new_offset = offset.copy()
        x, y, z = new_offset.x, new_offset.y, new_offset.z
        sliding = info.sliding_normal
        slide = False
        if info.sliding_normal_valid:
            if z * sliding.z + y * sliding.y + x * sliding.x < 0.0:
                slide = True
            else:
                info.sliding_normal_valid = False
        if info.contact_plane_valid:
            plane = info.contact_plane
            n = plane.N
            into_plane = f32(z * n.z + y * n.y + x * n.x)
            if slide:
                line = Vector3(
                    sliding.z * n.y - sliding.y * n.z,
                    sliding.x * n.z - sliding.z * n.x,
                    sliding.y * n.x - sliding.x * n.y,
                )
                if line.normalize_check_small():
                    new_offset = Vector3()
                else:
                    along = line.z * z + line.y * y + line.x * x
                    new_offset = Vector3(line.x * along, line.y * along, line.z * along)
            elif into_plane <= 0.0:
                new_offset = Vector3(x - into_plane * n.x, y - into_plane * n.y, z - f32(into_plane * n.z))
            else:
                plane.snap_to_plane(new_offset)
            if not info.contact_plane_is_water and info.contact_plane_cell_id:
                block = get_block_offset(path.check_pos.objcell_id, info.contact_plane_cell_id)
                sphere = path.global_sphere[0]
                c = sphere.center
                dist = (c.z - block.z) * n.z + (c.y - block.y) * n.y + (c.x - block.x) * n.x + plane.d
                if dist < sphere.radius - EPSILON:
                    lift = x87_divide(sphere.radius - dist, n.z)
                    if sphere.radius > abs(lift):
                        path.add_offset_to_check_pos(Vector3(0.0, 0.0, lift))
        elif slide:
            along = x * sliding.x + z * sliding.z + y * sliding.y
            new_offset = Vector3(
                x - along * sliding.x, y - f32(along * sliding.y), z - f32(along * sliding.z)
            )
        return new_offset

    def find_transitional_position(self) -> bool:
        """Sweep sphere by sphere-radius step from ``curr_pos`` towards ``end_pos``.

        The rotation is the end's at once for FREE_ROTATE, else slerped per step. Each step's
        adjusted offset moves ``check_pos``, which is inserted (three attempts) and validated;
        the sweep stops early on a stationary-fall frame, on a collision of a PATH_CLIPPED
        body, or (not for viewers) when a step's offset shrinks below EPSILON, which fails on
        the first step. A path of no steps takes the end rotation and just refreshes the cell
        array. True when the last step validated OK.

        Retail: CTransition::find_transitional_position @ 0x0050BDF0 (acclient.c:313170)
        """
        path = self.sphere_path
        info = self.collision_info
        obj = self.object_info
        if path.begin_cell is None or path.begin_pos is None or path.end_pos is None:
            return False
        begin, end = path.begin_pos.frame, path.end_pos.frame
        ts = TS.OK
        offset, offset_per_step, num_steps = self.calc_num_steps()
        if obj.state & OI.FREE_ROTATE:
            path.curr_pos.frame.set_rotate(end.qw, end.qx, end.qy, end.qz)
        path.set_check_pos(path.curr_pos, path.curr_cell)
        if num_steps <= 0:
            if not obj.state & OI.FREE_ROTATE:
                path.curr_pos.frame.set_rotate(end.qw, end.qx, end.qy, end.qz)
            path.set_check_pos(path.curr_pos, path.curr_cell)
            path.cell_array_valid = True
            path.hits_interior_cell = False
            self._find_cell_list(want_cell=False)
            return True
        for step in range(num_steps):
            if obj.state & OI.IS_VIEWER and step == num_steps - 1:
                dist = math.sqrt(offset.z * offset.z + offset.y * offset.y + offset.x * offset.x)
                if dist > EPSILON:
                    rest = (dist - path.local_sphere[0].radius * (num_steps - 1)) / dist
                    offset_per_step = offset * rest
            path.global_offset = self.adjust_offset(offset_per_step)
            if not obj.state & OI.IS_VIEWER and path.global_offset.length_squared() < EPSILON * EPSILON:
                return step != 0 and ts == TS.OK
            if not obj.state & OI.FREE_ROTATE:
                path.check_pos.frame.interpolate_rotation(begin, end, (step + 1) / num_steps)
            info.sliding_normal_valid = False
            info.contact_plane_valid = False
            info.contact_plane_is_water = False
            path.add_offset_to_check_pos(path.global_offset)
            ts = self.validate_transition(self.transitional_insert(3))
            if info.frames_stationary_fall:
                break
            if info.collision_normal_valid and obj.state & OI.PATH_CLIPPED:
                break
        return ts == TS.OK

    # -- insertion ------------------------------------------------------------------------------

    def insert_into_cell(self, cell: ObjCell | None, num_insertion_attempts: int) -> TransitionState:
        """Collide with everything in ``cell`` until OK or COLLIDED, at most
        ``num_insertion_attempts`` times; a slide drops the contact plane. No cell: COLLIDED.

        Retail: CTransition::insert_into_cell @ 0x00509E70 (acclient.c:311631)
        """
        if cell is None:
            return TS.COLLIDED
        ts = TS.OK
        for _ in range(num_insertion_attempts):
            ts = cell.find_collisions(self)
            if ts in (TS.OK, TS.COLLIDED):
                return ts
            if ts == TS.SLID:
                self.collision_info.contact_plane_valid = False
                self.collision_info.contact_plane_is_water = False
        return ts

    def check_other_cells(self, curr_cell: ObjCell | None) -> TransitionState:
        """Collide with every other cell the spheres reach, then re-home ``check_pos``.

        The first COLLIDED, ADJUSTED or SLID (which drops the contact plane) is returned. Else
        ``check_cell`` becomes the cell holding sphere 0's centre and ``check_pos`` moves into
        it. With no such cell: COLLIDED while stepping down; otherwise the candidate keeps its
        place with no cell (re-homed to the outdoor cell id under it), or, off the world,
        COLLIDED.

        The walk reads the live cell array, entry by entry up to its current length, as retail
        does (acclient.c:312404-312424): a cell's ``find_collisions`` may step up or down, whose
        nested insert rebuilds the array, and the walk then goes on from the same index in the
        rebuilt one.

        Retail: CTransition::check_other_cells @ 0x0050AE50 (acclient.c:312380)
        """
        path = self.sphere_path
        ts = TS.OK
        path.cell_array_valid = True
        path.hits_interior_cell = False
        new_cell = self._find_cell_list(want_cell=True)
        cell_array = self.cell_array
        index = 0
        while index < len(cell_array.cells):
            cell = cell_array.cells[index].cell
            index += 1
            if cell is None or cell is curr_cell:
                continue
            ts = cell.find_collisions(self)
            if ts == TS.SLID:
                self.collision_info.contact_plane_valid = False
                self.collision_info.contact_plane_is_water = False
                return ts
            if ts in (TS.COLLIDED, TS.ADJUSTED):
                return ts
        path.check_cell = new_cell
        if new_cell is not None:
            path.adjust_check_pos(new_cell.id)
            return ts
        if path.step_down:
            return TS.COLLIDED
        pos = path.check_pos.copy()
        if (pos.objcell_id & 0xFFFF) < 0x100:
            pos.objcell_id = adjust_to_outside(pos.objcell_id, pos.frame.origin)
        if not pos.objcell_id:
            return TS.COLLIDED
        path.adjust_check_pos(pos.objcell_id)
        path.set_check_pos(pos, None)
        path.cell_array_valid = True
        return ts

    def build_cell_array(self, want_new_cell: bool = False) -> ObjCell | None:
        """Refill the cell array around ``check_pos`` (with ``want_new_cell``, return the cell
        holding sphere 0's centre).

        Retail: CTransition::build_cell_array @ 0x00509EE0 (acclient.c:311674)
        """
        self.sphere_path.cell_array_valid = True
        self.sphere_path.hits_interior_cell = False
        return self._find_cell_list(want_cell=want_new_cell)

    def _find_cell_list(self, want_cell: bool) -> ObjCell | None:
        """``CObjCell::find_cell_list(&cell_array, new_cell_p, &sphere_path)``."""
        return cells.ObjCell.find_cell_list_for_path(self.cell_array, self.sphere_path, want_cell)

    def check_collisions(self, obj: PhysicsObj) -> bool:
        """Whether the spheres at ``curr_pos`` overlap ``obj`` (as a placement insert).

        Retail: CTransition::check_collisions @ 0x0050AA00 (acclient.c:312174)
        """
        path = self.sphere_path
        path.insert_type = IT.PLACEMENT
        path.set_check_pos(path.curr_pos, path.curr_cell)
        return obj.find_obj_collisions(self) != TS.OK

    def transitional_insert(self, num_insertion_attempts: int) -> TransitionState:
        """Insert ``check_pos`` into its cell and the cells around, resolving what it meets.

        Up to ``num_insertion_attempts`` rounds (callers pass 3, 5 or 1): insert into the
        check cell (with the same number of attempts), then the other cells. ADJUSTED, SLID
        and a resolved back-face hit go round again. On OK: a pending ``collide`` (sphere 1
        hit) is re-inserted as a placement if there is walkable ground under the body, else
        the candidate is restored and COLLIDED (killing the velocity if a contact plane was
        known, else with ``step_up_normal`` as the collision normal); a back-face hit slides
        or steps up; a body that was in contact and found no contact plane steps down (its
        step-down height, halved once and tried twice when over two radii, 0.04 off walkable
        ground) and, failing that, edge-slides. No check cell: OK. The step-down height and
        its z are ``float`` locals (acclient.c:312966-312993).

        Retail: CTransition::transitional_insert @ 0x0050B6F0 (acclient.c:312833)
        """
        path = self.sphere_path
        info = self.collision_info
        obj = self.object_info
        if path.check_cell is None:
            return TS.OK
        ts = TS.INVALID
        for _ in range(num_insertion_attempts):
            ts = self.insert_into_cell(path.check_cell, num_insertion_attempts)
            if ts == TS.OK:
                ts = self.check_other_cells(path.check_cell)
                if ts != TS.OK:
                    path.neg_poly_hit = False
                if ts == TS.COLLIDED:
                    return ts
            elif ts == TS.SLID:
                info.contact_plane_valid = False
                info.contact_plane_is_water = False
                path.neg_poly_hit = False
            elif ts == TS.ADJUSTED:
                path.neg_poly_hit = False
            elif ts == TS.COLLIDED:
                path.neg_poly_hit = False
                return ts
            if ts != TS.OK:
                continue
            if path.collide:
                return self._resolve_collide(num_insertion_attempts)
            if path.neg_poly_hit and not path.step_down and not path.step_up:
                path.neg_poly_hit = False
                if not path.neg_step_up:
                    ts = path.global_sphere[0].slide_sphere_normal(
                        path, info, path.neg_collision_normal, path.global_curr_center[0]
                    )
                elif not self.step_up(path.neg_collision_normal):
                    ts = path.step_up_slide(obj, info)
                continue
            if info.contact_plane_valid:
                return TS.OK
            if not obj.state & OI.CONTACT or path.step_down or path.check_cell is None or not obj.step_down:
                return TS.OK
            step_down_ht = SMALL_STEP_DOWN_HEIGHT
            z_val = LANDING_Z
            if obj.state & OI.ON_WALKABLE:
                z_val = obj.get_walkable_z()
                step_down_ht = obj.step_down_height
            path.walkable_allowance = z_val
            path.save_check_pos()
            radius = path.global_sphere[0].radius
            if path.num_sphere < 2 and radius + radius < step_down_ht:
                step_down_ht = f32(radius * 0.5)
            if radius + radius >= step_down_ht:
                stepped = self.step_down(step_down_ht, z_val)
            else:
                step_down_ht = f32(step_down_ht * 0.5)
                stepped = self.step_down(step_down_ht, z_val) or self.step_down(step_down_ht, z_val)
            if stepped:
                path.walkable = None
                return TS.OK
            done, ts = self.edge_slide(ts, step_down_ht, z_val)
            if done:
                return ts
        return ts

    def _resolve_collide(self, num_insertion_attempts: int) -> TransitionState:
        """``transitional_insert`` on OK with ``sphere_path.collide`` set (acclient.c:312897-312938)."""
        path = self.sphere_path
        info = self.collision_info
        path.collide = False
        if info.contact_plane_valid and self.check_walkable(LANDING_Z):
            path.backup = path.insert_type
            path.insert_type = IT.PLACEMENT
            ts = self.transitional_insert(num_insertion_attempts)
            path.insert_type = path.backup
            path.walkable = None
            if ts == TS.OK:
                return ts
        else:
            path.walkable = None
        path.restore_check_pos()
        info.contact_plane_valid = False
        info.contact_plane_is_water = False
        if info.last_known_contact_plane_valid:
            self.object_info.kill_velocity()
            info.last_known_contact_plane_valid = False
        else:
            info.set_collision_normal(path.step_up_normal)
        return TS.COLLIDED

    # -- walkables, steps and slides ------------------------------------------------------------

    def check_walkable(self, z_chk: float) -> bool:
        """Whether walkable ground (normal z above ``z_chk``) lies under the candidate.

        True at once for a body not on walkable ground, or one still over its recorded walkable
        polygon. Otherwise the candidate is probed one insert lower by the step-down height
        (half a radius for a one-sphere body whose height exceeds two radii, then halved once
        more if still over two radii) with ``check_walkable`` set, and restored; ground is
        there when that insert did not come back OK. ``z_chk`` is a ``float`` parameter; the
        probe height stays in the FPU until the offset stores it (acclient.c:312502-312514).

        Retail: CTransition::check_walkable @ 0x0050AFF0 (acclient.c:312474)
        """
        path = self.sphere_path
        if not self.object_info.state & OI.ON_WALKABLE or path.check_walkables():
            return True
        backup_pos = path.check_pos.copy()
        backup_cell = path.check_cell
        step_down_ht = self.object_info.step_down_height
        path.walkable_allowance = f32(z_chk)
        path.check_walkable = True
        radius = path.global_sphere[0].radius
        if path.num_sphere < 2 and step_down_ht > radius + radius:
            step_down_ht = radius * 0.5
        if step_down_ht > radius + radius:
            step_down_ht = step_down_ht * 0.5
        path.add_offset_to_check_pos(Vector3(0.0, 0.0, -step_down_ht))
        ts = self.transitional_insert(1)
        path.check_walkable = False
        path.set_check_pos(backup_pos, backup_cell)
        return ts != TS.OK

    def step_down(self, step_down_ht: float, z_val: float) -> bool:
        """Lower the candidate by ``step_down_ht`` (not during a step-up) and insert it; True
        when it lands on a contact plane with normal z ≥ ``z_val`` (for EDGE_SLIDE bodies with
        walkable ground under it) and a placement re-insert there is OK. Both arguments are
        ``float`` parameters (acclient.c:312628).

        Retail: CTransition::step_down @ 0x0050B2A0 (acclient.c:312628)
        """
        path = self.sphere_path
        info = self.collision_info
        step_down_ht, z_val = f32(step_down_ht), f32(z_val)
        path.neg_poly_hit = False
        path.step_down = True
        path.step_down_amt = step_down_ht
        path.walk_interp = 1.0
        if not path.step_up:
            path.add_offset_to_check_pos(Vector3(0.0, 0.0, -step_down_ht))
        ts = self.transitional_insert(5)
        path.step_down = False
        if not (ts == TS.OK and info.contact_plane_valid and info.contact_plane.N.z >= z_val):
            return False
        if self.object_info.state & OI.EDGE_SLIDE and not path.step_up and not self.check_walkable(z_val):
            return False
        path.backup = path.insert_type
        path.insert_type = IT.PLACEMENT
        ts = self.transitional_insert(1)
        path.insert_type = path.backup
        return ts == TS.OK

    def step_up(self, collision_normal: Vector3) -> bool:
        """Try to climb what sphere 0 ran into (``collision_normal``): a step-down by the
        step-up height onto walkable ground (0.04 onto landing ground off walkable ground)
        from the saved candidate, which is restored if the step fails. The height and the
        walkable z are ``float`` locals (acclient.c:312799-312814).

        Retail: CTransition::step_up @ 0x0050B610 (acclient.c:312793)
        """
        path = self.sphere_path
        info = self.collision_info
        obj = self.object_info
        info.contact_plane_valid = False
        info.contact_plane_is_water = False
        path.step_up = True
        path.step_up_normal = collision_normal.copy()
        step_down_ht = SMALL_STEP_DOWN_HEIGHT
        z_val = LANDING_Z
        if obj.state & OI.ON_WALKABLE:
            z_val = obj.get_walkable_z()
            step_down_ht = obj.step_up_height
        path.walkable_allowance = z_val
        path.save_check_pos()
        stepped = self.step_down(step_down_ht, z_val)
        path.step_up = False
        path.walkable = None
        if not stepped:
            path.restore_check_pos()
        return stepped

    def edge_slide(
        self, ts: TransitionState, step_down_ht: float, z_val: float
    ) -> tuple[bool, TransitionState]:
        """A body that found nothing to step down onto: ``(stop, ts)``.

        Without both ON_WALKABLE and EDGE_SLIDE the candidate is restored and accepted without
        contact (stop, OK). With them: onto a too-steep contact plane, a cliff slide (go on);
        past a recorded walkable polygon, a precipice slide (stop only if COLLIDED); on some
        contact plane, restored without contact (stop, OK); in the air, a step-down from the
        current position looks for the walkable polygon to slide along (stop, COLLIDED if none).

        Retail: CTransition::edge_slide @ 0x0050B3D0 (acclient.c:312684)
        """
        path = self.sphere_path
        info = self.collision_info
        state = self.object_info.state
        if not (state & OI.ON_WALKABLE and state & OI.EDGE_SLIDE):
            path.walkable = None
            path.restore_check_pos()
            info.contact_plane_valid = False
            info.contact_plane_is_water = False
            path.cell_array_valid = True
            return True, TS.OK
        if info.contact_plane_valid and info.contact_plane.N.z < z_val:
            path.walkable = None
            path.restore_check_pos()
            ts = self.cliff_slide(info.contact_plane)
            info.contact_plane_valid = False
            info.contact_plane_is_water = False
            return False, ts
        if path.walkable is not None:
            path.restore_check_pos()
            info.contact_plane_valid = False
            info.contact_plane_is_water = False
            ts = path.precipice_slide(info)
            return ts == TS.COLLIDED, ts
        if info.contact_plane_valid:
            path.walkable = None
            path.restore_check_pos()
            path.cell_array_valid = True
            info.contact_plane_valid = False
            info.contact_plane_is_water = False
            return True, TS.OK
        path.add_offset_to_check_pos(path.global_curr_center[0] - path.global_sphere[0].center)
        self.step_down(step_down_ht, z_val)
        info.contact_plane_valid = False
        info.contact_plane_is_water = False
        path.restore_check_pos()
        if path.walkable is not None:
            info.contact_plane_valid = False
            info.contact_plane_is_water = False
            path.cache_localspace_sphere(path.get_walkable_pos(), path.walkable_scale)
            path.set_walkable_check_pos(path.localspace_sphere[0])
            ts = path.precipice_slide(info)
            return ts == TS.COLLIDED, ts
        path.walkable = None
        path.cell_array_valid = True
        return True, TS.COLLIDED

    def cliff_slide(self, contact_plane: Plane) -> TransitionState:
        """Slide along the crease between ``contact_plane`` (too steep) and the last known one.

        The horizontal direction across the crease (``z × (N × N_last)``) becomes the collision
        normal, facing against the step; the candidate moves by the step's component along it.
        OK when the planes are parallel. Of the step (across blocks) only its z difference and its
        x total are ``float`` spills (acclient.c:312047-312053).

        Retail: CTransition::cliff_slide @ 0x0050A6D0 (acclient.c:312004)
        """
        path = self.sphere_path
        info = self.collision_info
        n = contact_plane.N
        last = info.last_known_contact_plane.N
        cx = n.y * last.z - n.z * last.y
        cy = last.x * n.z - last.z * n.x
        cz = (n.x * last.y - n.y * last.x) * 0.0
        normal = Vector3(cz - cy, cx - cz, cy * 0.0 - cx * 0.0)
        if normal.normalize_check_small():
            return TS.OK
        block = get_block_offset(path.curr_pos.objcell_id, path.check_pos.objcell_id)
        center, curr = path.global_sphere[0].center, path.global_curr_center[0]
        step_x, step_y, step_z = center.x - curr.x, center.y - curr.y, f32(center.z - curr.z)
        along_x = f32(block.x + step_x)
        along = (block.z + step_z) * normal.z + (block.y + step_y) * normal.y + along_x * normal.x
        if along <= 0.0:
            path.add_offset_to_check_pos(normal * along)
            info.set_collision_normal(normal)
        else:
            path.add_offset_to_check_pos(normal * -along)
            info.set_collision_normal(-normal)
        return TS.ADJUSTED

    # -- validation ------------------------------------------------------------------------------

    def validate_transition(self, ts: TransitionState) -> TransitionState:
        """Accept or roll back one step, then update the sliding normal, the stationary-fall
        counter and the contact state.

        OK commits ``check_pos`` as ``curr_pos``. COLLIDED, ADJUSTED or SLID roll back to
        ``curr_pos`` (rebuilding the cell array) and become OK: the velocity is killed if a
        contact plane was known, and that plane is taken back when sphere 0 still touches it;
        a missing collision normal becomes +z. A valid collision normal becomes the sliding
        normal. For a GRAVITY body (not a viewer), a step that moved (or re-took a walkable
        plane) zeroes ``frames_stationary_fall``; any other counts 0 → 1 → 2 → 3, and the
        third fabricates a floor under sphere 0 as the contact plane (and, out of contact, as
        an environment collision). The contact plane, if any, becomes the last known one and
        sets CONTACT and (walkable) ON_WALKABLE in the object state. (Retail's ``redo`` out
        parameter is always 0 and is dropped.)

        Retail: CTransition::validate_transition @ 0x0050AA70 (acclient.c:312193)
        """
        path = self.sphere_path
        info = self.collision_info
        obj = self.object_info
        moved = True
        unchanged = path.check_pos.objcell_id == path.curr_pos.objcell_id and path.check_pos.frame.is_equal(
            path.curr_pos.frame
        )
        if ts != TS.OK or unchanged:
            moved = False
        if ts == TS.OK:
            path.curr_pos = path.check_pos.copy()
            path.curr_cell = path.check_cell
            path.cache_global_curr_center()
            path.set_check_pos(path.curr_pos, path.curr_cell)
        elif TS.COLLIDED <= ts <= TS.SLID:
            if info.last_known_contact_plane_valid:
                obj.kill_velocity()
                plane = info.last_known_contact_plane
                center = path.global_curr_center[0]
                dist = center.z * plane.N.z + center.y * plane.N.y + center.x * plane.N.x + plane.d
                if path.global_sphere[0].radius + EPSILON > abs(dist):
                    info.set_contact_plane(plane, info.last_known_contact_plane_is_water)
                    info.contact_plane_cell_id = info.last_known_contact_plane_cell_id
                    if obj.state & OI.ON_WALKABLE:
                        moved = True
            if not info.collision_normal_valid:
                info.set_collision_normal(Vector3(0.0, 0.0, 1.0))
            path.set_check_pos(path.curr_pos, path.curr_cell)
            self.build_cell_array()
            ts = TS.OK
        if info.collision_normal_valid:
            info.set_sliding_normal(info.collision_normal)
        mover = obj.object
        if not obj.state & OI.IS_VIEWER and mover is not None and mover._state & PhysicsState.GRAVITY:
            if moved:
                info.frames_stationary_fall = 0
            elif info.frames_stationary_fall == 0:
                info.frames_stationary_fall = 1
            elif info.frames_stationary_fall == 1:
                info.frames_stationary_fall = 2
            else:
                info.frames_stationary_fall = 3
                sphere = path.global_sphere[0]
                center = sphere.center
                height = (center.y + center.x) * 0.0 + center.z
                floor = Plane(Vector3(0.0, 0.0, 1.0), sphere.radius - height)
                info.set_contact_plane(floor, False)
                info.contact_plane_cell_id = path.check_pos.objcell_id
                if not obj.state & OI.CONTACT:
                    info.set_collision_normal(floor.N)
                    info.collided_with_environment = True
        info.last_known_contact_plane_valid = info.contact_plane_valid
        if info.contact_plane_valid:
            info.last_known_contact_plane = info.contact_plane.copy()
            info.last_known_contact_plane_cell_id = info.contact_plane_cell_id
            info.last_known_contact_plane_is_water = info.contact_plane_is_water
            obj.state |= OI.CONTACT
            if obj.is_valid_walkable(info.contact_plane.N):
                obj.state |= OI.ON_WALKABLE
            else:
                obj.state &= ~OI.ON_WALKABLE
        else:
            obj.state &= ~(OI.CONTACT | OI.ON_WALKABLE)
        return ts
