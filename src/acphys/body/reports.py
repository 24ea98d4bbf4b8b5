"""Collisions a body is part of: the collision table, reports to the user, object collisions."""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from acphys.flags import ObjectInfoState, PhysicsState, TransientState, TransitionState, member_namespace
from acphys.geometry.sphere import DUMMY_SPHERE
from acphys.math.cell_id import get_block_offset
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.transition.transition import Transition

if TYPE_CHECKING:
    from acphys.geometry.sphere import SphereTransition
    from acphys.physics_obj import PhysicsObj
    from acphys.transition.sphere_path import SpherePath

PS = member_namespace(PhysicsState)
TS = member_namespace(TransientState)
OI = member_namespace(ObjectInfoState)
TR = member_namespace(TransitionState)

#: How much farther apart than touching two spheres must be for :meth:`CollisionReports.out_of_reach`
#: to skip the exact test: far beyond the rounding of that test's few metre-scale operations.
REACH_MARGIN = 1e-3


class CollisionKind(enum.Enum):
    """Which weenie callback retail makes for a collision report (``CWeenieObject`` vtable slot)."""

    #: ``DoCollision(EnvCollisionProfile)`` (slot 19): the environment, or an object reporting as it.
    ENVIRONMENT = "environment"
    #: ``DoCollision(ObjCollisionProfile)`` (slot 20): another object.
    OBJECT = "object"
    #: ``DoCollision(AtkCollisionProfile)`` (slot 21): a missile learns where it hit an object.
    ATTACK = "attack"
    #: ``DoCollisionEnd(object_id)`` (slot 22): the collision record with that object expired.
    END = "end"


@dataclass(frozen=True, slots=True)
class CollisionReport:
    """One collision report as retail's collision profiles carry it.

    ``velocity`` is the receiver's own velocity for ENVIRONMENT and the reporting body's
    velocity minus the other's for OBJECT (the same vector for both sides of a pair, as retail
    passes it); None for ATTACK and END. ``me_in_contact`` / ``other_is_missile`` /
    ``other_in_contact`` are the profiles' bits (0x20 / 0x8 / 0x10 of ``ObjCollisionProfile``,
    0x1 of ``EnvCollisionProfile``). ``part`` and ``location`` are the ``AtkCollisionProfile``'s
    (``part`` is always -1 here; ``location`` is ``Position::determine_quadrant``'s bits).
    ``other`` is None for the environment and for an END whose object no longer exists.
    """

    kind: CollisionKind
    other_id: int = 0
    other: PhysicsObj | None = None
    velocity: Vector3 | None = None
    me_in_contact: bool = False
    other_is_missile: bool = False
    other_in_contact: bool = False
    part: int = -1
    location: int = 0

    @property
    def is_environment(self) -> bool:
        return self.kind is CollisionKind.ENVIRONMENT

    @property
    def is_end(self) -> bool:
        return self.kind is CollisionKind.END

    @property
    def is_start(self) -> bool:
        return self.kind is not CollisionKind.END


#: ``PhysicsObj.on_collision``: called with the receiving body and each report it receives.
CollisionCallback = Callable[["PhysicsObj", CollisionReport], None]


@dataclass(slots=True)
class CollisionRecord:
    """Retail ``CPhysicsObj::CollisionRecord`` (acclient.h:52277): when an object was last touched."""

    touched_time: float
    ethereal: bool


class CollisionTable:
    """Retail ``collision_table``: a ``LongNIValHash<CollisionRecord>`` of 4 buckets keyed by object id.

    Iteration follows the hash: bucket ``(id ^ (id >> 8)) & 3`` in order 0..3
    (``HashBase::InternalInit``: mask 3, key shift 8), and within a bucket the
    newest key first (``HashBase::clobber`` pushes a new key at the chain head and
    replaces a known one in place).
    """

    __slots__ = ("_records",)

    TABLE_MASK = 3
    KEY_SHIFT = 8

    def __init__(self) -> None:
        #: Insertion order is first-insertion order: a clobbered key keeps its place.
        self._records: dict[int, CollisionRecord] = {}

    def __len__(self) -> int:
        return len(self._records)

    def __contains__(self, object_id: object) -> bool:
        return object_id in self._records

    def get(self, object_id: int) -> CollisionRecord | None:
        return self._records.get(object_id)

    def clobber(self, object_id: int, record: CollisionRecord) -> bool:
        """Store ``record`` under ``object_id``; True when a record was already there (and is replaced).

        Retail: LongNIValHash<CPhysicsObj::CollisionRecord>::clobber @ 0x00513830 (acclient.c:320726)
        """
        known = object_id in self._records
        self._records[object_id] = record
        return known

    def remove(self, object_id: int) -> None:
        del self._records[object_id]

    def oldest_first(self) -> list[int]:
        """The keys in the order they were first stored (not retail's iteration order: the
        order :meth:`ids` derives it from)."""
        return list(self._records)

    def ids(self) -> list[int]:
        """The keys in retail iteration order (``HashBaseIter::Next``)."""
        newest_first = list(reversed(self._records))
        return [
            key
            for bucket in range(self.TABLE_MASK + 1)
            for key in newest_first
            if (key ^ (key >> self.KEY_SHIFT)) & self.TABLE_MASK == bucket
        ]


class CollisionReports:
    """The collision bookkeeping and the object side of a sweep (part of :class:`PhysicsObj`)."""

    def report_environment_collision(self, prev_has_contact: bool) -> bool:
        """Report the first frame of touching the environment; a missile stops aligning to its path.

        The report, made when ``REPORT_COLLISIONS`` is set, carries the body's velocity and
        ``prev_has_contact`` (retail's ``EnvCollisionProfile``).

        Retail: CPhysicsObj::report_environment_collision @ 0x00512FC0 (acclient.c:320193)
        """
        if self.colliding_with_environment:
            return False
        reported = bool(self._state & PS.REPORT_COLLISIONS)
        if reported:
            self._receive_collision(
                CollisionReport(
                    CollisionKind.ENVIRONMENT, velocity=self.velocity.copy(), me_in_contact=prev_has_contact
                )
            )
        self.colliding_with_environment = True
        if self._state & PS.MISSILE:
            self._state &= ~(PS.MISSILE | PS.ALIGN_PATH | PS.PATH_CLIPPED)
        return reported

    def _receive_collision(self, report: CollisionReport) -> None:
        """Deliver ``report`` to this body: a step event, then ``on_collision``.

        Retail hands the profile to the body's weenie (``DoCollision``, ``DoCollisionEnd``); acphys
        gates on ``REPORT_COLLISIONS`` alone (every body answers as if it had a weenie), records
        ``collision:environment``, ``collision:NAME`` or ``collision_end:NAME``, and calls the hook.
        """
        if report.kind is CollisionKind.ENVIRONMENT:
            self.step_events.append("collision:environment")
        else:
            other = report.other
            name = other.name if other is not None and other.name else f"0x{report.other_id:08X}"
            prefix = "collision_end:" if report.kind is CollisionKind.END else "collision:"
            self.step_events.append(prefix + name)
        if self.on_collision is not None:
            self.on_collision(self, report)

    def track_object_collision(self, obj: PhysicsObj, prev_has_contact: bool) -> bool:
        """Touch ``obj``: a static one reports as the environment; any other is stamped in the table
        with the physics time and its ``ETHEREAL`` bit, and reported only if it was not there yet.

        Retail: CPhysicsObj::track_object_collision @ 0x00513F10 (acclient.c:321216)
        """
        if obj._state & PS.STATIC:
            return self.report_environment_collision(prev_has_contact)
        if self.collision_table is None:
            self.collision_table = CollisionTable()
        record = CollisionRecord(self.world.physics_time, bool(obj._state & PS.ETHEREAL))
        if self.collision_table.clobber(obj.id, record):
            return False
        return self.report_object_collision(obj, prev_has_contact)

    def report_object_collision(self, obj: PhysicsObj, prev_has_contact: bool) -> bool:
        """Tell both bodies about a collision between them; True when a report was made.

        An ``obj`` with ``REPORT_COLLISIONS_AS_ENVIRONMENT`` is the environment. Otherwise, unless
        ``obj`` ignores collisions, this body (with ``REPORT_COLLISIONS``) hears of ``obj`` (an
        ATTACK with the quadrant it hit if this body is a missile, else an OBJECT), and a missile
        stops being one (MISSILE, ALIGN_PATH, PATH_CLIPPED cleared). Then ``obj`` (with
        ``REPORT_COLLISIONS``) hears of this body unless this body ignores collisions. Both OBJECT
        reports carry this body's velocity minus ``obj``'s. Retail quirk kept: in the report to
        ``obj`` the missile bit is this body's ``prev_has_contact`` and the in-contact bit is
        whether this body was a missile (``build_collision_profile`` arguments swapped,
        acclient.c:320310-320316). The height handed to ``determine_quadrant`` is spilled to
        ``float`` (acclient.c:320266 and 320297).

        Retail: CPhysicsObj::report_object_collision @ 0x00513060 (acclient.c:320227)
        """
        if obj._state & PS.REPORT_COLLISIONS_AS_ENVIRONMENT:
            return self.report_environment_collision(prev_has_contact)
        reported = False
        was_missile = bool(self._state & PS.MISSILE)
        relative = self.velocity - obj.velocity
        if not obj._state & PS.IGNORE_COLLISIONS:
            if self._state & PS.REPORT_COLLISIONS:
                if was_missile:
                    location = obj.position.determine_quadrant(f32(obj.get_height()), self.position)
                    report = CollisionReport(CollisionKind.ATTACK, obj.id, obj, location=location)
                else:
                    report = CollisionReport(
                        CollisionKind.OBJECT,
                        obj.id,
                        obj,
                        velocity=relative.copy(),
                        me_in_contact=prev_has_contact,
                        other_is_missile=bool(obj._state & PS.MISSILE),
                        other_in_contact=bool(obj._transient_state & TS.CONTACT),
                    )
                self._receive_collision(report)
                reported = True
            if was_missile:
                self._state &= ~(PS.MISSILE | PS.ALIGN_PATH | PS.PATH_CLIPPED)
        if obj._state & PS.REPORT_COLLISIONS and not self._state & PS.IGNORE_COLLISIONS:
            if obj._state & PS.MISSILE:
                location = self.position.determine_quadrant(f32(self.get_height()), obj.position)
                report = CollisionReport(CollisionKind.ATTACK, self.id, self, location=location)
            else:
                report = CollisionReport(
                    CollisionKind.OBJECT,
                    self.id,
                    self,
                    velocity=relative.copy(),
                    me_in_contact=bool(obj._transient_state & TS.CONTACT),
                    other_is_missile=prev_has_contact,
                    other_in_contact=was_missile,
                )
            obj._receive_collision(report)
            reported = True
        return reported

    def report_object_collision_end(self, object_id: int) -> bool:
        """Tell both bodies a collision with ``object_id`` ended; False when that object is gone.

        No report when the object reports as the environment. When it no longer exists, only
        this body hears of the end.

        Retail: CPhysicsObj::report_object_collision_end @ 0x00510A90 (acclient.c:317868)
        """
        obj = self.world.get_object(object_id)
        if obj is None:
            if self._state & PS.REPORT_COLLISIONS:
                self._receive_collision(CollisionReport(CollisionKind.END, object_id))
            return False
        if not obj._state & PS.REPORT_COLLISIONS_AS_ENVIRONMENT:
            if self._state & PS.REPORT_COLLISIONS:
                self._receive_collision(CollisionReport(CollisionKind.END, object_id, obj))
            if obj._state & PS.REPORT_COLLISIONS:
                obj._receive_collision(CollisionReport(CollisionKind.END, self.id, self))
        return True

    def report_collision_start(self) -> None:
        """Report again a collision with every object still in the table (used on unhiding).

        Retail: CPhysicsObj::report_collision_start @ 0x00513FD0 (acclient.c:321262)
        """
        if self.collision_table is None:
            return
        for object_id in self.collision_table.ids():
            obj = self.world.get_object(object_id)
            if obj is not None:
                self.report_object_collision(obj, bool(self._transient_state & TS.CONTACT))

    def report_collision_end(self, force_end: bool) -> None:
        """Drop and end-report the records untouched for over 1 s, ethereal ones untouched for any
        time at all, or (``force_end``) every record.

        All expired records are taken out first, in table order, then reported in that order.

        Retail: CPhysicsObj::report_collision_end @ 0x00514620 (acclient.c:321712)
        """
        table = self.collision_table
        if table is None:
            return
        now = self.world.physics_time
        ended = []
        for object_id in table.ids():
            record = table.get(object_id)
            assert record is not None
            age = now - record.touched_time
            if age > 1.0 or (record.ethereal and age > 0.0) or force_end:
                table.remove(object_id)
                ended.append(object_id)
        for object_id in ended:
            self.report_object_collision_end(object_id)

    def check_collision(self, obj: PhysicsObj) -> bool:
        """Whether this body, where it stands, overlaps ``obj`` (never for a static body).

        A transition with this body's object info (``get_object_info``, not an admin move), its
        spheres (the dummy sphere without any) and a path from its position to itself asks
        ``CTransition::check_collisions``: a placement test against ``obj`` alone.

        Retail: CPhysicsObj::check_collision @ 0x00512ED0 (acclient.c:320127)
        """
        if self._state & PS.STATIC:
            return False
        transit = Transition.make_transition(self.world)
        try:
            transit.init_object(self, self.get_object_info(transit, False))
            if self.part_array is not None and self.part_array.get_num_sphere():
                transit.init_sphere(self.part_array.get_sphere(), self.scale)
            else:
                transit.init_sphere([DUMMY_SPHERE], 1.0)
            transit.init_path(self.cell, self.position, self.position)
            return transit.check_collisions(obj)
        finally:
            Transition.cleanup_transition()

    # -- collisions: a sweep meets this body --------------------------------------------------

    def out_of_reach(self, path: SpherePath) -> bool:
        """Whether every moving sphere of ``path`` (at ``check_pos``) misses every sphere of this
        body by more than ``REACH_MARGIN``, so that ``CSphere::intersects_sphere`` could only
        answer OK and change nothing.

        Not a retail routine: a shortcut for :meth:`find_obj_collisions`, which would otherwise
        test every pair through ``intersects_sphere_placed``. The body's sphere centres are
        placed as that routine places them (``localtoglobal`` of the scaled centre, plus the
        block offset), without building vectors; outside a step-down, every branch of
        ``intersects_sphere`` answers OK without side effects for spheres that do not touch
        (acclient.c:359211-359385), and the caller keeps step-downs for the exact test. A NaN
        anywhere is never rejected.
        """
        frame = self.position.frame
        m = frame.m
        origin = frame.origin
        ox, oy, oz = origin.x, origin.y, origin.z
        check_cell = path.check_pos.objcell_id
        if (check_cell >> 16) != (self.position.objcell_id >> 16):
            block = get_block_offset(check_cell, self.position.objcell_id)
            ox, oy, oz = ox + block.x, oy + block.y, oz + block.z
        scale = self.scale
        moving_spheres = path.global_sphere
        for sphere in self.part_array.get_sphere():
            c = sphere.center
            cx, cy, cz = c.x * scale, c.y * scale, c.z * scale
            x = m[6] * cz + m[0] * cx + m[3] * cy + ox
            y = m[7] * cz + m[1] * cx + m[4] * cy + oy
            z = m[8] * cz + m[2] * cx + m[5] * cy + oz
            radius = sphere.radius * scale + REACH_MARGIN
            for moving in moving_spheres:
                center = moving.center
                dx, dy, dz = center.x - x, center.y - y, center.z - z
                limit = radius + moving.radius
                if not dx * dx + dy * dy + dz * dz > limit * limit:
                    return False
        return True

    def find_obj_collisions(self, transition: SphereTransition) -> TransitionState:
        """Collide the transition's moving spheres with this body (found through a cell's shadow).

        OK at once for an ethereal body that ignores collisions, and for a creature (by its
        weenie) when the mover is a viewer. An ethereal body, or any non-static one when the mover
        is ethereal, is an ethereal obstruction: skipped (OK) while stepping down, else tested with
        ``sphere_path.obstruction_ethereal`` set, so the shapes only report overlap. Two players
        pass through each other (the exemption) unless the mover is impenetrable, this body is, or
        both are PK or both PK-lite. Unless exempt or ``OBJECTINFO.missile_ignore``, the body's
        physics BSP is tried through its parts (``HAS_PHYSICS_BSP``), else its cylspheres, else its
        spheres, each placed at ``position`` and ``scale``, until one answers other than OK.

        Such an answer, outside a step-down, is recorded: a static body flags
        ``collided_with_environment`` (unless the mover is in contact) and is not added to the
        collision objects; an ethereal obstruction, or a creature (a missile body or a creature
        weenie) met by a mover that ignores creatures, becomes OK with the collision normal
        invalidated and is added as OK; any other body is added with the answer.
        ``obstruction_ethereal`` is cleared on the way out.

        Retail: CPhysicsObj::FindObjCollisions @ 0x0050F050 (acclient.c:316158)
        """
        state = self._state
        if state & PS.ETHEREAL and state & PS.IGNORE_COLLISIONS:
            return TR.OK
        path = transition.sphere_path
        info = transition.object_info
        weenie = self.weenie_obj
        if weenie is not None and info.state & OI.IS_VIEWER and weenie.is_creature():
            return TR.OK
        ethereal = bool(state & PS.ETHEREAL or (info.ethereal and not state & PS.STATIC))
        if ethereal and path.step_down:
            return TR.OK
        path.obstruction_ethereal = ethereal
        exempt = (
            weenie is not None
            and weenie.is_player()
            and bool(info.state & OI.IS_PLAYER)
            and not info.state & OI.IS_IMPENETRABLE
            and not weenie.is_impenetrable()
            and not (info.state & OI.IS_PK and weenie.is_pk())
            and not (info.state & OI.IS_PKLITE and weenie.is_pk_lite())
        )
        is_creature = bool(state & PS.MISSILE) or (weenie is not None and weenie.is_creature())
        parts = self.part_array
        result = TR.OK
        if state & PS.HAS_PHYSICS_BSP and not exempt and not info.missile_ignore(self):
            if parts is not None:
                result = parts.find_obj_collisions(transition)
        elif parts is not None and parts.get_num_cylsphere() and not exempt and not info.missile_ignore(self):
            for cylsphere in parts.get_cylsphere():
                result = cylsphere.intersects_sphere_placed(self.position, self.scale, transition)
                if result != TR.OK:
                    break
        elif (
            parts is not None
            and parts.get_num_sphere()
            and not exempt
            and not info.missile_ignore(self)
            and (path.step_down or not self.out_of_reach(path))
        ):
            for sphere in parts.get_sphere():
                result = sphere.intersects_sphere_placed(self.position, self.scale, transition, is_creature)
                if result != TR.OK:
                    break
        if result != TR.OK and not path.step_down:
            collisions = transition.collision_info
            if state & PS.STATIC:
                if not info.state & OI.CONTACT:
                    collisions.collided_with_environment = True
            elif ethereal or (is_creature and info.state & OI.IGNORE_CREATURES):
                result = TR.OK
                collisions.collision_normal_valid = False
                collisions.add_object(self, TR.OK)
            else:
                collisions.add_object(self, result)
        path.obstruction_ethereal = False
        return result
