"""``CylSphere``: a vertical collision cylinder, local to its owner's frame.

The sweep routines follow :mod:`acphys.geometry.sphere`: they take the moving object's path
(``SPHEREPATH``), collision record (``COLLISIONINFO``) and traits (``OBJECTINFO``) and return a
:class:`acphys.flags.TransitionState`. ``self`` is the obstacle cylinder in global space (``low_pt``
is the centre of its bottom disc) unless a docstring says otherwise, and ``disp`` is a moving
sphere's centre less ``low_pt``. Retail treats the cylinder as a flat-capped column: a sphere is in
it when its centre is within the radius sum horizontally and it overlaps ``[low_pt.z,
low_pt.z + height]`` vertically by more than EPSILON.

Float32 at rest (:mod:`acphys.precision`): ``radsum`` and ``reach`` are ``float`` in retail;
the docstrings name the other ``float`` locals each routine keeps.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import EPSILON, LANDING_Z
from acphys.flags import ObjectInfoState, TransitionState, member_namespace
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere, _step_since_curr
from acphys.math.vector import Vector3
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.geometry.sphere import SphereTransition
    from acphys.math.position import Position
    from acphys.transition.collision_info import CollisionInfo
    from acphys.transition.object_info import ObjectInfo
    from acphys.transition.transition import SpherePath

TS = member_namespace(TransitionState)

#: ``SPHEREPATH::InsertType`` PLACEMENT (acclient.h:6160).
_PLACEMENT = 1

#: ``timecheck < -0.1`` bound on the interpolation a step-down or landing may rewind to.
_MIN_WALK_INTERP = -0.1

_UP = Vector3(0.0, 0.0, 1.0)


def _pick_root(a: float, b: float, disc: float) -> float:
    """``(b - √D)/a``, or ``(b + √D)/a`` when the former's numerator is negative."""
    root = math.sqrt(disc)
    if b - root < 0.0:
        return (root + b) / a
    return (b - root) / a


class CylSphere:
    """Retail ``CCylSphere`` (acclient.h:31672): ``{Vector3 low_pt; float height; float radius}``;
    the radius and height are narrowed to float32 when the cylinder is built."""

    __slots__ = ("height", "low_pt", "radius")

    def __init__(self, low_pt: Vector3, radius: float, height: float) -> None:
        self.low_pt = low_pt.copy()
        self.radius = f32(radius)
        self.height = f32(height)

    def copy(self) -> CylSphere:
        return CylSphere(self.low_pt, self.radius, self.height)

    def __repr__(self) -> str:
        return f"CylSphere({self.low_pt!r}, radius={self.radius!r}, height={self.height!r})"

    def collides_with_sphere(self, check_pos: Sphere, disp: Vector3, radsum: float) -> bool:
        """Whether ``check_pos`` (centre ``disp`` from ``low_pt``) is in this cylinder.

        Horizontally ``disp.x² + disp.y² <= radsum²`` (touching hits); vertically the sphere must
        reach more than EPSILON into ``[0, height]``: ``r - EPSILON + h/2 >= |h/2 - disp.z|``, so a
        sphere resting exactly on the top cap is a miss.

        Retail: CCylSphere::collides_with_sphere @ 0x0053A880 (acclient.c:361501)
        """
        if not radsum * radsum >= disp.x * disp.x + disp.y * disp.y:
            return False
        half = self.height * 0.5
        return check_pos.radius - EPSILON + half >= abs(half - disp.z)

    def normal_of_collision(
        self, path: SpherePath, check_pos: Sphere, disp: Vector3, radsum: float, sphere_num: int
    ) -> tuple[bool, Vector3]:
        """``(definite, normal)`` for moving sphere ``sphere_num`` hitting this cylinder (normal not unit).

        From where the sphere was (``global_curr_center[sphere_num]``): if it was horizontally
        outside ``radsum`` the normal is its horizontal offset from the axis, definite when it
        already overlapped the cylinder vertically or does not move vertically (to EPSILON);
        otherwise it came through a cap: ``(0,0,1)`` unless ``disp`` is higher than before, then
        ``(0,0,-1)``, always definite.

        The old offset stays in registers for the horizontal test (summed y first) and the normal;
        its z is the ``float`` local ``old_disp_8`` (acclient.c:361667-361670).

        Retail: CCylSphere::normal_of_collision @ 0x0053AB50 (acclient.c:361651)
        """
        curr, low = path.global_curr_center[sphere_num], self.low_pt
        old_x, old_y = curr.x - low.x, curr.y - low.y
        old_z = f32(curr.z - low.z)
        if radsum * radsum < old_y * old_y + old_x * old_x:
            half = self.height * 0.5
            definite = (
                check_pos.radius - EPSILON + half >= abs(half - old_z) or abs(old_z - disp.z) <= EPSILON
            )
            return definite, Vector3(old_x, old_y, 0.0)
        if disp.z - old_z <= 0.0:
            return True, Vector3(0.0, 0.0, 1.0)
        return True, Vector3(0.0, 0.0, -1.0)

    def _cap_time(self, movement_z: float, old_z: float, radius: float) -> float:
        """The movement fraction at which a sphere ``old_z`` above ``low_pt`` meets the cap it heads for.

        Up (``movement_z > 0``): its top reaches the bottom cap; otherwise its bottom reaches the top
        (acclient.c:361798-361808, 361872-361875).
        """
        if movement_z > 0.0:
            return -((old_z + radius) / movement_z)
        return (radius + self.height - old_z) / movement_z

    def _side_normal(self, curr: Vector3, offset: Vector3, reach: float) -> Vector3:
        """The horizontal part of ``curr + offset - low_pt``, times ``1/reach`` (``Vector3::operator/=``,
        not normalised)."""
        point = curr + offset - self.low_pt
        return Vector3(point.x, point.y, 0.0) * (1.0 / reach)

    def collide_with_point(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
        sphere_num: int,
    ) -> TransitionState:
        """A path-clipped (or airborne sphere 1) hit: set the collision normal; PERFECT_CLIP rewinds.

        Without PERFECT_CLIP (or with a tiny normal) COLLIDED. With it, ``check_pos`` is backed up
        along ``movement`` (from sphere 0's current centre, whatever ``sphere_num`` is, to
        ``check_pos`` plus the block offset) to where it first touches at ``reach = radsum +
        EPSILON``: the cap time for a cap normal, the root of the horizontal circle for a side
        normal. An indefinite normal tries the cap it heads for first and switches to the side when
        the sphere would be horizontally outside then (keeping the cap time if the quadratic has no
        usable root). A time outside ``[0, 1]``, or no root for a definite side hit, is COLLIDED.
        The adjustment is ``curr[0] + movement·t - check_pos.center``.

        ``float`` locals (acclient.c:361780-361793, 361813-361949): the movement (see
        :func:`acphys.geometry.sphere._step_since_curr`), the old offset from ``low_pt``, ``reach``
        and, in the indefinite case, ``reach²``; every offset is ``movement`` times the time spilled
        to ``float``, except the indefinite cap offset, which multiplies by the double time. The
        ``[0, 1]`` test reads the double time.

        Retail: CCylSphere::collide_with_point @ 0x0053ACB0 (acclient.c:361704)
        """
        definite, normal = self.normal_of_collision(path, check_pos, disp, radsum, sphere_num)
        if normal.normalize_check_small():
            return TS.COLLIDED
        if not obj.state & ObjectInfoState.PERFECT_CLIP:
            collisions.set_collision_normal(normal)
            return TS.COLLIDED
        curr = path.global_curr_center[0]
        movement = Vector3(*_step_since_curr(path, check_pos.center, curr))
        mx, my, mz = movement.x, movement.y, movement.z
        old = curr - self.low_pt
        ox, oy = old.x, old.y
        reach = f32(radsum + EPSILON)
        a = my * my + mx * mx
        b = -(my * oy + mx * ox)
        if not definite:
            if abs(mz) < EPSILON:
                return TS.COLLIDED
            normal = Vector3(0.0, 0.0, -1.0 if mz > 0.0 else 1.0)
            time = self._cap_time(mz, old.z, check_pos.radius)
            offset = movement * time
            reach2 = f32(reach * reach)
            px, py = offset.x + ox, offset.y + oy
            if py * py + px * px >= reach2:
                if abs(a) < EPSILON:
                    return TS.COLLIDED
                disc = b * b - (oy * oy + ox * ox - reach2) * a
                if disc >= 0.0 and a > EPSILON:
                    time = _pick_root(a, b, disc)
                    offset = movement * f32(time)
                normal = self._side_normal(curr, offset, reach)
        elif normal.z != 0.0:
            if abs(mz) < EPSILON:
                return TS.COLLIDED
            time = self._cap_time(mz, old.z, check_pos.radius)
            offset = movement * f32(time)
        else:
            disc = b * b - (oy * oy + ox * ox - reach * reach) * a
            if disc < 0.0 or a < EPSILON:
                return TS.COLLIDED
            time = _pick_root(a, b, disc)
            offset = movement * f32(time)
            normal = self._side_normal(curr, offset, reach)
        if time < 0.0 or time > 1.0:
            return TS.COLLIDED
        collisions.set_collision_normal(normal)
        path.add_offset_to_check_pos(curr + offset - check_pos.center, check_pos.radius)
        return TS.ADJUSTED

    def slide_sphere(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
        sphere_num: int,
    ) -> TransitionState:
        """Slide moving sphere ``sphere_num`` (``check_pos``) along this cylinder's collision normal.

        COLLIDED for a tiny normal; else :meth:`Sphere.slide_sphere_normal` on ``check_pos`` from
        ``global_curr_center[sphere_num]``.

        Retail: CCylSphere::slide_sphere @ 0x0053B2A0 (acclient.c:361956)
        """
        _, normal = self.normal_of_collision(path, check_pos, disp, radsum, sphere_num)
        if normal.normalize_check_small():
            return TS.COLLIDED
        return check_pos.slide_sphere_normal(path, collisions, normal, path.global_curr_center[sphere_num])

    def step_sphere_up(
        self, transition: SphereTransition, check_pos: Sphere, disp: Vector3, radsum: float
    ) -> TransitionState:
        """Sphere 0 hit this cylinder while in contact: step up onto it if low enough, else slide.

        Too high (``step_up_height < r + height - disp.z``, the rise to the top cap) slides sphere
        0. Otherwise the collision normal, rotated by ``localspace_pos`` (retail's
        ``Position::localtoglobalvec``, acclient.c:362004, although the normal is already global),
        goes to ``CTransition::step_up``; a failed step falls back to ``step_up_slide``.

        Retail: CCylSphere::step_sphere_up @ 0x0053B310 (acclient.c:361975)
        """
        path = transition.sphere_path
        obj, collisions = transition.object_info, transition.collision_info
        if obj.step_up_height < check_pos.radius + self.height - disp.z:
            return self.slide_sphere(obj, path, collisions, check_pos, disp, radsum, 0)
        _, normal = self.normal_of_collision(path, check_pos, disp, radsum, 0)
        if normal.normalize_check_small():
            return TS.COLLIDED
        if transition.step_up(path.localspace_pos.localtoglobalvec(normal)):
            return TS.OK
        return path.step_up_slide(obj, collisions)

    def step_sphere_down(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
    ) -> TransitionState:
        """Raise the stepping-down sphere onto the top cap, which becomes the contact plane.

        OK when neither moving sphere is in the cylinder; COLLIDED when the step is nil or the rise
        ``height + r - disp.z`` (sphere 0's, even when only sphere 1 hit) would take ``walk_interp``
        out of ``[-0.1, walk_interp)``. Otherwise the plane ``z = low_pt.z + height`` (through
        ``check_pos``'s raised bottom) is set with ``is_water`` 1, whatever its walkability.
        Hex-Rays shows the cylinder pointer for the sphere-1 test as the entry ``ecx``
        (acclient.c:361594-361602, 361607): that is ``this``. The rise is stored as a ``float``
        (``radsuma``) before the contact point and the offset are built from it; the interp test
        reads the double rise (acclient.c:361607-361634).

        Retail: CCylSphere::step_sphere_down @ 0x0053A9B0 (acclient.c:361573)
        """
        if not self.collides_with_sphere(check_pos, disp, radsum):
            if path.num_sphere <= 1:
                return TS.OK
            second = path.global_sphere[1]
            if not self.collides_with_sphere(second, second.center - self.low_pt, radsum):
                return TS.OK
        step = path.step_down_amt * path.walk_interp
        if abs(step) < EPSILON:
            return TS.COLLIDED
        rise_reg = self.height + check_pos.radius - disp.z
        interp = (1.0 - rise_reg / step) * path.walk_interp
        if interp >= path.walk_interp or interp < _MIN_WALK_INTERP:
            return TS.COLLIDED
        rise = f32(rise_reg)
        c = check_pos.center
        contact = Vector3(c.x, c.y, rise - check_pos.radius + c.z)
        collisions.set_contact_plane(Plane.from_point(_UP, contact), True)
        collisions.contact_plane_cell_id = path.check_pos.objcell_id
        path.walk_interp = f32(interp)
        path.add_offset_to_check_pos(Vector3(0.0, 0.0, rise), check_pos.radius)
        return TS.ADJUSTED

    def land_on_cylinder(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
    ) -> TransitionState:
        """An airborne sphere 0 hit this cylinder: flag the collision and allow landing slopes.

        Retail: CCylSphere::land_on_cylinder @ 0x0053B3D0 (acclient.c:362014)
        """
        _, normal = self.normal_of_collision(path, check_pos, disp, radsum, 0)
        if normal.normalize_check_small():
            return TS.COLLIDED
        path.set_collide(normal)
        path.walkable_allowance = LANDING_Z
        return TS.ADJUSTED

    def intersects_sphere_placed(
        self, p: Position, scale: float, transition: SphereTransition
    ) -> TransitionState:
        """``intersects_sphere`` for this cylinder local to ``p`` at ``scale``, in ``check_pos``'s block.

        First caches the path's spheres in ``p``'s frame at scale 1.0 (the ``localspace_pos``
        that :meth:`step_sphere_up` rotates by). ``low_pt`` goes through ``Position::localtoglobal``
        (:meth:`Position.localtoglobal <acphys.math.position.Position.localtoglobal>`).

        Retail: CCylSphere::intersects_sphere @ 0x0053B8F0 (acclient.c:362243)
        """
        path = transition.sphere_path
        path.cache_localspace_sphere(p, 1.0)
        low_pt = path.check_pos.localtoglobal(p, self.low_pt * scale)
        return CylSphere(low_pt, scale * self.radius, scale * self.height).intersects_sphere(transition)

    def intersects_sphere(self, transition: SphereTransition) -> TransitionState:
        """Test the moving spheres (``global_sphere``) against this cylinder and respond.

        ``radsum`` is the radius sum less EPSILON, a ``float`` (acclient.c:362082). Dispatch
        (acclient.c:362083-362240): placement
        or an ethereal obstruction and ``check_walkable`` only report overlap (COLLIDED);
        ``step_down`` steps onto the top (creatures too: retail has no creature test here); before a
        collision is flagged, a body in contact steps up (sphere 0) or slides (sphere 1), a
        path-clipped one collides with a point (sphere 0 only), anything else lands (sphere 0) or
        collides with a point (sphere 1); after ``collide`` is set, see :meth:`_rewind_onto_top`.

        Retail: CCylSphere::intersects_sphere @ 0x0053B440 (acclient.c:362034)
        """
        path = transition.sphere_path
        obj = transition.object_info
        collisions = transition.collision_info
        moving = path.global_sphere[0]
        disp = moving.center - self.low_pt
        radsum = f32(self.radius - EPSILON + moving.radius)
        second = path.global_sphere[1] if path.num_sphere > 1 else None
        disp2 = second.center - self.low_pt if second is not None else Vector3()

        def second_collides() -> bool:
            return second is not None and self.collides_with_sphere(second, disp2, radsum)

        if path.insert_type == _PLACEMENT or path.obstruction_ethereal:
            if self.collides_with_sphere(moving, disp, radsum) or second_collides():
                return TS.COLLIDED
            return TS.OK
        if path.step_down:
            return self.step_sphere_down(obj, path, collisions, moving, disp, radsum)
        if path.check_walkable:
            if self.collides_with_sphere(moving, disp, radsum) or second_collides():
                return TS.COLLIDED
            return TS.OK
        if not path.collide:
            if obj.state & (ObjectInfoState.CONTACT | ObjectInfoState.ON_WALKABLE):
                if self.collides_with_sphere(moving, disp, radsum):
                    return self.step_sphere_up(transition, moving, disp, radsum)
                if second is not None and second_collides():
                    return self.slide_sphere(obj, path, collisions, second, disp2, radsum, 1)
            elif obj.state & ObjectInfoState.PATH_CLIPPED:
                if self.collides_with_sphere(moving, disp, radsum):
                    return self.collide_with_point(obj, path, collisions, moving, disp, radsum, 0)
            else:
                if self.collides_with_sphere(moving, disp, radsum):
                    return self.land_on_cylinder(obj, path, collisions, moving, disp, radsum)
                if second is not None and second_collides():
                    return self.collide_with_point(obj, path, collisions, second, disp2, radsum, 1)
            return TS.OK
        if not (self.collides_with_sphere(moving, disp, radsum) or second_collides()):
            return TS.OK
        return self._rewind_onto_top(path, collisions, moving, disp, radsum)

    def _rewind_onto_top(
        self, path: SpherePath, collisions: CollisionInfo, moving: Sphere, disp: Vector3, radsum: float
    ) -> TransitionState:
        """The ``collide`` arm of ``intersects_sphere`` (acclient.c:362201-362237).

        Back sphere 0 up along its movement since ``curr_pos`` until its bottom is on the top cap.
        COLLIDED for no vertical movement (to EPSILON) or an interp outside ``[-0.1, walk_interp)``;
        OK (no response at all) when at that time it would be horizontally outside ``radsum``, which
        is every hit on the side. Otherwise the top cap becomes the contact plane (``is_water`` 1,
        no walkability test) and ADJUSTED. The offset is the movement times the time spilled to
        ``float``; the interp reads the double time (acclient.c:362206-362232).
        """
        movement = path.global_curr_center[0] - moving.center - path.get_curr_pos_check_pos_block_offset()
        if abs(movement.z) < EPSILON:
            return TS.COLLIDED
        t = (self.height + moving.radius - disp.z) / movement.z
        offset = movement * f32(t)
        ox, oy = offset.x + disp.x, offset.y + disp.y
        if radsum * radsum < oy * oy + ox * ox:
            return TS.OK
        interp = (1.0 - t) * path.walk_interp
        if not (interp < path.walk_interp and interp >= _MIN_WALK_INTERP):
            return TS.COLLIDED
        contact = moving.center + offset
        contact.z = f32(contact.z - moving.radius)
        collisions.set_contact_plane(Plane.from_point(_UP, contact), True)
        collisions.contact_plane_cell_id = path.check_pos.objcell_id
        path.walk_interp = f32(interp)
        path.add_offset_to_check_pos(offset, moving.radius)
        return TS.ADJUSTED
