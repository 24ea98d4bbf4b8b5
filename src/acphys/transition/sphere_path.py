"""``SPHEREPATH``: the path a transition sweeps and the spheres it sweeps along it.

Split out of :mod:`acphys.transition.transition` (which re-exports ``SpherePath`` and
``InsertType``) to keep the CTransition machine in a module of its own.
"""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

from acphys.flags import TransitionState
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import get_block_offset
from acphys.math.position import Position
from acphys.math.vector import Vector3, zero_vector
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    from acphys.geometry.polygon import Polygon
    from acphys.transition.collision_info import CollisionInfo
    from acphys.transition.object_info import ObjectInfo
    from acphys.world.obj_cell import ObjCell

_new = object.__new__


class InsertType(enum.IntEnum):
    """``SPHEREPATH::InsertType`` (acclient.h:6160)."""

    TRANSITION = 0
    PLACEMENT = 1
    INITIAL_PLACEMENT = 2


class SpherePath:
    """Retail ``SPHEREPATH`` (acclient.h:32625): the path and the spheres swept along it.

    ``num_sphere`` is the length of ``local_sphere``; ``global_sphere`` and
    ``global_curr_center`` are rebuilt with that length by the cache routines.
    """

    __slots__ = (
        "backup",
        "backup_cell",
        "backup_check_pos",
        "begin_cell",
        "begin_pos",
        "bldg_check",
        "cell_array_valid",
        "check_cell",
        "check_pos",
        "check_walkable",
        "collide",
        "curr_cell",
        "curr_pos",
        "end_pos",
        "global_curr_center",
        "global_low_point",
        "global_offset",
        "global_sphere",
        "hits_interior_cell",
        "insert_type",
        "local_low_point",
        "local_sphere",
        "localspace_curr_center",
        "localspace_low_point",
        "localspace_pos",
        "localspace_sphere",
        "localspace_z",
        "neg_collision_normal",
        "neg_poly_hit",
        "neg_step_up",
        "obstruction_ethereal",
        "placement_allows_sliding",
        "step_down",
        "step_down_amt",
        "step_up",
        "step_up_normal",
        "walk_interp",
        "walkable",
        "walkable_allowance",
        "walkable_check_pos",
        "walkable_pos",
        "walkable_scale",
        "walkable_up",
    )

    def __init__(self) -> None:
        self.local_sphere: list[Sphere] = []
        self.local_low_point = zero_vector()
        self.global_sphere: list[Sphere] = []
        self.global_low_point = zero_vector()
        self.localspace_sphere: list[Sphere] = []
        self.localspace_low_point = zero_vector()
        self.localspace_curr_center: list[Vector3] = []
        self.global_curr_center: list[Vector3] = []
        self.localspace_pos = Position()
        self.localspace_z = zero_vector()
        self.begin_cell: ObjCell | None = None
        #: ``begin_pos``: None for a placement (retail's null pointer).
        self.begin_pos: Position | None = None
        self.end_pos: Position | None = None
        self.curr_cell: ObjCell | None = None
        self.curr_pos = Position()
        self.global_offset = zero_vector()
        self.step_up = False
        self.step_up_normal = zero_vector()
        self.collide = False
        self.check_cell: ObjCell | None = None
        self.check_pos = Position()
        self.insert_type = InsertType.TRANSITION
        self.step_down = False
        self.backup = InsertType.TRANSITION
        self.backup_cell: ObjCell | None = None
        self.backup_check_pos = Position()
        self.obstruction_ethereal = False
        self.hits_interior_cell = False
        self.bldg_check = False
        self.walkable_allowance = 0.0
        self.walk_interp = 0.0
        self.step_down_amt = 0.0
        self.walkable_check_pos = Sphere(zero_vector(), 0.0)
        #: ``CPolygon *walkable``: the walkable polygon found under the sphere, if any.
        self.walkable: Polygon | None = None
        self.check_walkable = False
        self.walkable_up = zero_vector()
        self.walkable_pos = Position()
        self.walkable_scale = 0.0
        self.cell_array_valid = False
        self.neg_step_up = False
        self.neg_collision_normal = zero_vector()
        self.neg_poly_hit = False
        self.placement_allows_sliding = True

    @property
    def num_sphere(self) -> int:
        return len(self.local_sphere)

    def init(self) -> None:
        """Forget the spheres, the path and the per-sweep flags; placements may slide.

        Retail: SPHEREPATH::init @ 0x0050C330 (acclient.c:313430)
        """
        self.local_sphere = []
        self.begin_cell = None
        self.begin_pos = None
        self.curr_cell = None
        self.check_cell = None
        self.insert_type = InsertType.TRANSITION
        self.step_down = False
        self.step_up = False
        self.collide = False
        self.hits_interior_cell = False
        self.bldg_check = False
        self.obstruction_ethereal = False
        self.backup_cell = None
        self.walkable_allowance = 0.0
        self.walkable = None
        self.check_walkable = False
        self.cell_array_valid = False
        self.neg_step_up = False
        self.neg_poly_hit = False
        self.placement_allows_sliding = True

    def init_sphere(self, spheres: list[Sphere], scale: float) -> None:
        """Take the first two of ``spheres``, scaled, as the local spheres; the low point is the
        bottom of the first one.

        ``scale`` is a ``float`` parameter; the scaled centres and radii are ``float`` stores
        (acclient.c:313673-313681), so a 0.2-m sphere sweeps with radius ``f32(0.2)``.

        Retail: SPHEREPATH::init_sphere @ 0x0050C670 (acclient.c:313646)
        """
        if not spheres:
            raise ValueError("SPHEREPATH.init_sphere: a sweep needs at least one sphere")
        scale = f32(scale)
        self.local_sphere = [
            Sphere.owning(sphere.center * scale, f32(scale * sphere.radius)) for sphere in spheres[:2]
        ]
        first = self.local_sphere[0]
        self.local_low_point = Vector3(first.center.x, first.center.y, first.center.z - first.radius)

    def init_path(self, begin_cell: ObjCell | None, begin_pos: Position | None, end_pos: Position) -> None:
        """Sweep from ``begin_pos`` (in ``begin_cell``) to ``end_pos``; with no ``begin_pos`` the
        sweep is a placement at ``end_pos``. ``curr_pos`` starts at the beginning and
        ``global_curr_center`` is cached there.

        Retail: SPHEREPATH::init_path @ 0x0050CE20 (acclient.c:314042)
        """
        self.begin_cell = begin_cell
        self.begin_pos = None if begin_pos is None else begin_pos.copy()
        self.end_pos = end_pos.copy()
        self.curr_pos = (end_pos if begin_pos is None else begin_pos).copy()
        self.curr_cell = begin_cell
        self.cache_global_curr_center()
        self.insert_type = InsertType.TRANSITION if begin_pos is not None else InsertType.PLACEMENT

    def is_walkable_allowable(self, zval: float) -> bool:
        """Whether a normal with z ``zval`` is walkable here: strictly above ``walkable_allowance``.

        Retail: SPHEREPATH::is_walkable_allowable @ 0x005368D0 (acclient.c:358474)
        """
        return zval > self.walkable_allowance

    def cache_global_curr_center(self) -> None:
        """Place each local sphere centre in ``curr_pos``'s frame as ``global_curr_center``.

        The sums run in retail's order, which is not ``Frame::localtoglobal``'s
        (acclient.c:313724-313741).

        Retail: SPHEREPATH::cache_global_curr_center @ 0x0050C740 (acclient.c:313696)
        """
        frame = self.curr_pos.frame
        m, o = frame.m, frame.origin
        centers = []
        for sphere in self.local_sphere:
            c = sphere.center
            v = _new(Vector3)
            v.x, v.y, v.z = unpack3(
                pack3(
                    c.x * m[0] + c.y * m[3] + c.z * m[6] + o.x,
                    m[7] * c.z + c.x * m[1] + m[4] * c.y + o.y,
                    m[8] * c.z + m[5] * c.y + m[2] * c.x + o.z,
                )
            )
            centers.append(v)
        self.global_curr_center = centers

    def cache_global_sphere(self, offset: Vector3 | None) -> None:
        """Move the global spheres and low point by ``offset``; with None, rebuild them at ``check_pos``.

        The rebuilt centres sum in retail's order (acclient.c:313809-313826); the low point in
        ``Frame::localtoglobal``'s (acclient.c:313830-313847).

        Retail: SPHEREPATH::cache_global_sphere @ 0x0050C810 (acclient.c:313747)
        """
        if offset is not None:
            for sphere in self.global_sphere:
                sphere.center = sphere.center + offset
            self.global_low_point = self.global_low_point + offset
            return
        frame = self.check_pos.frame
        m, o = frame.m, frame.origin
        spheres = []
        for sphere in self.local_sphere:
            c = sphere.center
            v = _new(Vector3)
            v.x, v.y, v.z = unpack3(
                pack3(
                    c.x * m[0] + c.y * m[3] + c.z * m[6] + o.x,
                    m[7] * c.z + c.x * m[1] + m[4] * c.y + o.y,
                    m[8] * c.z + m[2] * c.x + m[5] * c.y + o.z,
                )
            )
            spheres.append(Sphere.owning(v, sphere.radius))
        self.global_sphere = spheres
        self.global_low_point = frame.localtoglobal(self.local_low_point)

    def add_offset_to_check_pos(self, offset: Vector3, radius: float | None = None) -> None:
        """Move ``check_pos`` and the global spheres by ``offset``; the cell array goes stale.

        ``radius`` is the unused argument of the three-argument overload.

        Retail: SPHEREPATH::add_offset_to_check_pos @ 0x00509D10 (acclient.c:311556), and the
        overload SPHEREPATH::add_offset_to_check_pos @ 0x00536A60 (acclient.c:358525)
        """
        self.cell_array_valid = False
        self.check_pos.frame.origin = self.check_pos.frame.origin + offset
        self.cache_global_sphere(offset)

    def set_check_pos(self, pos: Position, cell: ObjCell | None) -> None:
        """Make ``pos`` (in ``cell``) the candidate and rebuild the global spheres there.

        Retail: SPHEREPATH::set_check_pos @ 0x0050A8B0 (acclient.c:312090)
        """
        self.check_pos = pos.copy()
        self.check_cell = cell
        self.cell_array_valid = False
        self.cache_global_sphere(None)

    def save_check_pos(self) -> None:
        """Remember the candidate (cell and position) in ``backup_cell``/``backup_check_pos``.

        Retail: SPHEREPATH::save_check_pos @ 0x0050A880 (acclient.c:312082)
        """
        self.backup_cell = self.check_cell
        self.backup_check_pos = self.check_pos.copy()

    def restore_check_pos(self) -> None:
        """Return to the saved candidate and rebuild the global spheres there.

        Retail: SPHEREPATH::restore_check_pos @ 0x0050B100 (acclient.c:312527)
        """
        self.check_pos = self.backup_check_pos.copy()
        self.check_cell = self.backup_cell
        self.cell_array_valid = False
        self.cache_global_sphere(None)

    def set_collide(self, collision_normal: Vector3) -> None:
        """Flag a collision to resolve: save the candidate, keep the normal, restart ``walk_interp``.

        Retail: SPHEREPATH::set_collide @ 0x005378A0 (acclient.c:359049)
        """
        self.collide = True
        self.save_check_pos()
        self.step_up_normal = collision_normal.copy()
        self.walk_interp = 1.0

    def set_neg_poly_hit(self, step_up: bool, collision_normal: Vector3) -> None:
        """Record a back-face polygon hit with the reversed normal.

        Retail: SPHEREPATH::set_neg_poly_hit @ 0x005398E0 (acclient.c:360742)
        """
        self.neg_step_up = step_up
        self.neg_poly_hit = True
        self.neg_collision_normal = -collision_normal

    def set_walkable(
        self, sphere: Sphere, poly: Polygon, zaxis: Vector3, local_pos: Position, scale: float
    ) -> None:
        """Remember the walkable polygon found, with the sphere, up axis and frame it was found in.

        Retail: SPHEREPATH::set_walkable @ 0x00539FC0 (acclient.c:361093)
        """
        self.walkable_check_pos = sphere.copy()
        self.walkable = poly
        self.walkable_up = zaxis.copy()
        self.walkable_pos = local_pos.copy()
        self.walkable_scale = f32(scale)

    def set_walkable_check_pos(self, sphere: Sphere) -> None:
        """Retail: SPHEREPATH::set_walkable_check_pos @ 0x00509CE0 (acclient.c:311550)"""
        self.walkable_check_pos = sphere.copy()

    def get_walkable_pos(self) -> Position:
        """A copy of ``walkable_pos``.

        Retail: SPHEREPATH::get_walkable_pos @ 0x0050A8F0 (acclient.c:312103)
        """
        return self.walkable_pos.copy()

    def get_curr_pos_check_pos_block_offset(self) -> Vector3:
        """The landblock offset from ``curr_pos``'s block to ``check_pos``'s.

        Retail: SPHEREPATH::get_curr_pos_check_pos_block_offset @ 0x00509FD0 (acclient.c:311718)
        """
        return get_block_offset(self.curr_pos.objcell_id, self.check_pos.objcell_id)

    def cache_localspace_sphere(self, p: Position, scale: float) -> None:
        """Describe the spheres in the frame of ``p`` at ``scale`` (what a BSP walk reads).

        ``localspace_sphere`` (at ``check_pos``) and ``localspace_curr_center`` (at
        ``curr_pos``) are the local spheres taken into ``p``'s frame and divided by ``scale``;
        ``localspace_pos`` is a copy of ``p``; ``localspace_z`` the global up axis in ``p``'s
        frame; ``localspace_low_point`` the bottom of localspace sphere 0 along it.

        ``scale`` is a ``float`` parameter and its reciprocal a ``float`` local; the low point's
        y and z offsets are spilled to ``float``, its x offset is not (acclient.c:313949-313958).

        Retail: SPHEREPATH::cache_localspace_sphere @ 0x0050C9D0 (acclient.c:313851)
        """
        scale = f32(scale)
        if scale == 0.0:
            raise ValueError("cache_localspace_sphere: scale must not be 0")
        inv = f32(1.0 / scale)
        self.localspace_sphere = []
        self.localspace_curr_center = []
        for sphere in self.local_sphere:
            center = p.localtolocal(self.check_pos, sphere.center)
            self.localspace_sphere.append(Sphere.owning(center * inv, f32(inv * sphere.radius)))
            self.localspace_curr_center.append(p.localtolocal(self.curr_pos, sphere.center) * inv)
        self.localspace_pos = p.copy()
        m = p.frame.m
        z = self.localspace_z = Vector3(
            (m[1] + m[0]) * 0.0 + m[2], (m[4] + m[3]) * 0.0 + m[5], (m[7] + m[6]) * 0.0 + m[8]
        )
        if self.localspace_sphere:
            low = self.localspace_sphere[0]
            c, r = low.center, low.radius
            self.localspace_low_point = Vector3(c.x - r * z.x, c.y - f32(r * z.y), c.z - f32(r * z.z))

    def adjust_check_pos(self, cell_id: int) -> None:
        """Re-home ``check_pos`` into ``cell_id``; for an outdoor cell (low word below 0x100) the
        origin and the global spheres shift by the landblock offset from ``cell_id``'s block.

        Retail: SPHEREPATH::adjust_check_pos @ 0x0050CC00 (acclient.c:313961)
        """
        if (cell_id & 0xFFFF) < 0x100:
            offset = get_block_offset(cell_id, self.check_pos.objcell_id)
            self.cache_global_sphere(offset)
            self.check_pos.frame.origin = self.check_pos.frame.origin + offset
        self.check_pos.objcell_id = cell_id

    def precipice_slide(self, collisions: CollisionInfo) -> TransitionState:
        """Slide along the edge of the walkable polygon the sphere has walked off.

        The crossed edge's inward normal (``find_crossed_edge`` on ``walkable_check_pos`` along
        ``walkable_up``) is taken to global space by ``walkable_pos``, flipped if the step of
        sphere 0 (since ``curr_pos``, across blocks) runs along it, and sphere 0 slides along
        it (``CSphere::slide_sphere``). ``walkable`` is cleared either way and ``step_up`` on a
        slide; with no crossed edge the result is COLLIDED.

        Of the step (across blocks) only its z difference and its x total are ``float`` spills
        (acclient.c:314022-314026); the rest stays in the FPU.

        Retail: SPHEREPATH::precipice_slide @ 0x0050CC80 (acclient.c:313979)
        """
        if self.walkable is None:
            raise ValueError("precipice_slide: no walkable polygon recorded (SPHEREPATH::walkable)")
        edge = self.walkable.find_crossed_edge(self.walkable_check_pos, self.walkable_up)
        self.walkable = None
        if edge is None:
            return TransitionState.COLLIDED
        self.step_up = False
        normal = self.walkable_pos.frame.localtoglobalvec(edge)
        block = get_block_offset(self.curr_pos.objcell_id, self.check_pos.objcell_id)
        center, curr = self.global_sphere[0].center, self.global_curr_center[0]
        step_x, step_y, step_z = center.x - curr.x, center.y - curr.y, f32(center.z - curr.z)
        along_x = f32(block.x + step_x)
        along = normal.z * (block.z + step_z) + (block.y + step_y) * normal.y + along_x * normal.x
        if along > 0.0:
            normal = -normal
        return self.global_sphere[0].slide_sphere_normal(self, collisions, normal, curr)

    def check_walkables(self) -> bool:
        """Whether the sphere still stands on the recorded walkable polygon; True if none.

        Halves ``walkable_check_pos.radius`` in place (each call halves it again) and asks the
        polygon's ``check_walkable`` along ``walkable_up``.

        Retail: SPHEREPATH::check_walkables @ 0x0050C3E0 (acclient.c:313467)
        """
        if self.walkable is None:
            return True
        self.walkable_check_pos.radius = self.walkable_check_pos.radius * 0.5
        return self.walkable.check_walkable(self.walkable_check_pos, self.walkable_up)

    def step_up_slide(self, obj: ObjectInfo, collisions: CollisionInfo) -> TransitionState:
        """A failed step-up: drop the contact plane and slide sphere 0 along ``step_up_normal``.

        ``obj`` is unused by retail. Retail: SPHEREPATH::step_up_slide @ 0x0050C3B0 (acclient.c:313455)
        """
        collisions.contact_plane_valid = False
        collisions.contact_plane_is_water = False
        self.step_up = False
        return self.global_sphere[0].slide_sphere_normal(
            self, collisions, self.step_up_normal, self.global_curr_center[0]
        )
