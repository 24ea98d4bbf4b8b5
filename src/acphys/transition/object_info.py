"""``OBJECTINFO``: the moving object's traits a transition reads (state bits, step heights).

Divergences from ACE's ``ObjectInfo.cs`` (the decompilation wins):

- ``MissileIgnore``: ACE lets a missile obstacle hit a player it targets ("modified for 2-way");
  retail ignores every missile obstacle (acclient.c:314078-314080).
- ``Init``: ACE sets ``TargetID`` from the object's projectile target; retail's ``init`` leaves
  it alone and nothing in the client ever sets it, so it stays the 0 of ``CTransition::init``.
- ``ValidateWalkable``: ACE returns ADJUSTED from the below-the-plane branch even when the plane
  was too steep to stand on and nothing moved; retail returns OK then (acclient.c:314280). ACE's
  viewer branch only returns early (``dist > -EPSILON``) when the path began indoors; retail
  returns OK for any viewer that does not dip below the plane (acclient.c:314196).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import EPSILON, FLOOR_Z
from acphys.flags import ObjectInfoState, PhysicsState, TransitionState, member_namespace
from acphys.math.vector import Vector3
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.geometry.plane import Plane
    from acphys.geometry.sphere import Sphere
    from acphys.physics_obj import PhysicsObj
    from acphys.transition.collision_info import CollisionInfo
    from acphys.transition.sphere_path import SpherePath

OI = member_namespace(ObjectInfoState)
PS = member_namespace(PhysicsState)
TS = member_namespace(TransitionState)


def x87_divide(numerator: float, denominator: float) -> float:
    """``numerator / denominator`` as the x87 computes it with its traps masked: ±inf, or NaN for 0/0."""
    if denominator != 0.0:
        return numerator / denominator
    if numerator == 0.0 or math.isnan(numerator):
        return math.nan
    return math.copysign(math.inf, numerator) * math.copysign(1.0, denominator)


class ObjectInfo:
    """Retail ``OBJECTINFO`` (acclient.h:52284).

    ``state`` holds :class:`acphys.flags.ObjectInfoState` bits; :meth:`init` fills the rest
    from the moving object.
    """

    __slots__ = (
        "ethereal",
        "object",
        "scale",
        "state",
        "step_down",
        "step_down_height",
        "step_up_height",
        "target_id",
    )

    def __init__(
        self,
        obj: PhysicsObj | None = None,
        state: ObjectInfoState = ObjectInfoState.DEFAULT,
        scale: float = 1.0,
        step_up_height: float = 0.0,
        step_down_height: float = 0.0,
        ethereal: bool = False,
        step_down: bool = True,
        target_id: int = 0,
    ) -> None:
        self.object = obj
        self.state = ObjectInfoState(state)
        self.scale = f32(scale)
        self.step_up_height = f32(step_up_height)
        self.step_down_height = f32(step_down_height)
        self.ethereal = ethereal
        self.step_down = step_down
        #: ``targetID``.
        self.target_id = target_id

    def missile_ignore(self, collideobject: PhysicsObj) -> bool:
        """Whether the sweep passes through ``collideobject`` because one of the two is a missile.

        A missile obstacle is always ignored. A missile mover ignores anything but its target
        (``target_id``) that has a weenie and is either ethereal or, when the missile has a
        target, a creature.

        Retail: OBJECTINFO::missile_ignore @ 0x0050CEB0 (acclient.c:314069)
        """
        if collideobject._state & PS.MISSILE:
            return True
        mover = self.object
        if mover is None:
            raise ValueError("OBJECTINFO.missile_ignore: the transition has no moving object")
        if not mover._state & PS.MISSILE or collideobject.id == self.target_id:
            return False
        weenie = collideobject.weenie_obj
        if weenie is None:
            return False
        if collideobject._state & PS.ETHEREAL:
            return True
        return self.target_id != 0 and weenie.is_creature()

    def init(self, obj: PhysicsObj, object_state: ObjectInfoState) -> None:
        """Describe ``obj`` for a sweep: ``object_state`` (from ``get_object_info``), its scale and
        step heights (``CPhysicsObj::GetStepUpHeight``/``GetStepDownHeight``: the part array's,
        0 without one), ``ethereal`` from ETHEREAL, ``step_down`` unless MISSILE, and the
        weenie's IS_IMPENETRABLE / IS_PLAYER / IS_PK / IS_PKLITE bits. ``target_id`` is kept.
        The step heights come back as doubles (setup height times scale z) and are narrowed
        into their ``float`` fields (acclient.c:314128-314129).

        Retail: OBJECTINFO::init @ 0x0050CF30 (acclient.c:314117)
        """
        self.object = obj
        self.state = ObjectInfoState(object_state)
        self.scale = obj.scale
        parts = obj.part_array
        self.step_up_height = f32(parts.get_step_up_height()) if parts is not None else 0.0
        self.step_down_height = f32(parts.get_step_down_height()) if parts is not None else 0.0
        self.ethereal = bool(obj._state & PS.ETHEREAL)
        self.step_down = not obj._state & PS.MISSILE
        weenie = obj.weenie_obj
        if weenie is not None:
            if weenie.is_impenetrable():
                self.state |= OI.IS_IMPENETRABLE
            if weenie.is_player():
                self.state |= OI.IS_PLAYER
            if weenie.is_pk():
                self.state |= OI.IS_PK
            if weenie.is_pk_lite():
                self.state |= OI.IS_PKLITE

    def get_walkable_z(self) -> float:
        """``floor_z``, the steepest normal z a body may stand on (``CPhysicsObj::get_walkable_z``).

        Retail: OBJECTINFO::get_walkable_z @ 0x0050CF20 (acclient.c:314108)
        """
        return FLOOR_Z

    def is_valid_walkable(self, normal: Vector3) -> bool:
        """``CPhysicsObj::is_valid_walkable``: ``normal.z >= floor_z``.

        Retail: OBJECTINFO::is_valid_walkable @ 0x0050CF10 (acclient.c:314099)
        """
        return normal.z >= FLOOR_Z

    def kill_velocity(self) -> None:
        """Zero the moving object's velocity.

        Retail: OBJECTINFO::kill_velocity @ 0x0050CFE0 (acclient.c:314147)
        """
        if self.object is None:
            raise ValueError("OBJECTINFO.kill_velocity: the transition has no moving object")
        self.object.set_velocity(Vector3())

    def validate_walkable(
        self,
        check_pos: Sphere,
        contact_plane: Plane,
        is_water: bool,
        water_depth: float,
        path: SpherePath,
        collisions: CollisionInfo,
        land_cell_id: int,
    ) -> TransitionState:
        """Rest ``check_pos`` on a terrain plane (lowered by ``water_depth``).

        A viewer is pushed back out along its step when the sphere dips below the plane. A body
        whose sphere bottom is within EPSILON of the plane touches it; below, it is lifted onto it
        (ADJUSTED), or COLLIDED while probing walkables or when a step-down would not shorten.
        Touching or lifted, the plane becomes the contact plane unless the body stands on
        walkable ground, is not stepping down and the plane is too steep; a body without contact
        that is not stepping down also gets the plane's normal as its collision normal. The
        divisions run as the x87 does them (a zero ``step_down_amt`` gives infinities, not an error).

        ``float`` stores (acclient.c:314182-314269): ``water_depth`` (a parameter); for a viewer the
        plane distance (the division reads it narrowed, the compare before it does not) and the
        step's x and y (its z stays in the FPU); for a body the depth below the plane and the new
        ``walk_interp``.

        Retail: OBJECTINFO::validate_walkable @ 0x0050D010 (acclient.c:314160)
        """
        state = self.state
        normal = contact_plane.N
        center = check_pos.center
        if state & OI.IS_VIEWER:
            dist = normal.x * center.x + normal.y * center.y + center.z * normal.z + contact_plane.d
            dist -= check_pos.radius
            if dist > -EPSILON:
                return TS.OK
            curr = path.global_curr_center[0]
            step_x, step_y = f32(center.x - curr.x), f32(center.y - curr.y)
            step_z = center.z - curr.z
            t = x87_divide(f32(dist), step_z * normal.z + step_x * normal.x + step_y * normal.y)
            if (
                (t <= 0.0 or t > 1.0)
                and path.begin_pos is not None
                and (path.begin_pos.objcell_id & 0xFFFF) >= 0x100
            ):
                return TS.OK
            path.add_offset_to_check_pos(Vector3(step_x * -t, step_y * -t, step_z * -t))
            collisions.set_collision_normal(normal)
            collisions.collided_with_environment = True
            return TS.ADJUSTED
        dist = (
            center.y * normal.y
            + (center.z - check_pos.radius) * normal.z
            + center.x * normal.x
            + contact_plane.d
            + f32(water_depth)
        )
        contact = path.step_down or not state & OI.ON_WALKABLE or self.is_valid_walkable(normal)
        if dist >= -EPSILON:
            if dist > EPSILON:
                return TS.OK
            if contact:
                collisions.set_contact_plane(contact_plane, is_water)
                collisions.contact_plane_cell_id = land_cell_id
            result = TS.OK
        else:
            if path.check_walkable:
                return TS.COLLIDED
            depth = f32(x87_divide(dist, normal.z))
            result = TS.OK
            if contact:
                collisions.set_contact_plane(contact_plane, is_water)
                collisions.contact_plane_cell_id = land_cell_id
                if path.step_down:
                    scale = x87_divide(-1.0, path.step_down_amt * path.walk_interp)
                    interp = (1.0 - scale * depth) * path.walk_interp
                    if interp >= path.walk_interp or interp < -0.1:
                        return TS.COLLIDED
                    path.walk_interp = f32(interp)
                path.add_offset_to_check_pos(Vector3(0.0, 0.0, -depth))
                result = TS.ADJUSTED
        if not state & OI.CONTACT and not path.step_down:
            collisions.set_collision_normal(normal)
            collisions.collided_with_environment = True
        return result
