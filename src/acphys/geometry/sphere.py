"""``CSphere``: a collision sphere, and the routines that sweep one sphere past another.

The sweep routines take the moving object's path (``SPHEREPATH``), its collision record
(``COLLISIONINFO``) and its traits (``OBJECTINFO``), and return a
:class:`acphys.flags.TransitionState`. ``self`` is the obstacle sphere in global space unless a
docstring says otherwise. Retail's x87 sqrt of a negative number yields NaN, which then fails
every comparison; :func:`_x87_sqrt` keeps that behaviour where retail does not guard the root.

Float32 at rest (:mod:`acphys.precision`): ``radsum`` and ``reach`` are ``float`` parameters or
locals in retail, so they are narrowed where they are made; displacements are ``Vector3`` stores
unless a docstring says which parts stay in registers.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Protocol

from acphys.constants import EPSILON, LANDING_Z
from acphys.flags import ObjectInfoState, TransitionState, member_namespace
from acphys.geometry.plane import Plane
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, unpack3

_new = object.__new__

if TYPE_CHECKING:
    from acphys.geometry.plane import Ray
    from acphys.math.position import Position
    from acphys.transition.collision_info import CollisionInfo
    from acphys.transition.object_info import ObjectInfo
    from acphys.transition.transition import SpherePath

TS = member_namespace(TransitionState)
OI = member_namespace(ObjectInfoState)

#: ``timecheck < -0.1`` bound on the interpolation a step-down or landing may rewind to.
_MIN_WALK_INTERP = -0.1


def _x87_sqrt(value: float) -> float:
    """``fsqrt``: NaN for a negative argument (retail runs with the invalid-operation trap masked)."""
    return math.sqrt(value) if value >= 0.0 else math.nan


def _step_since_curr(path: SpherePath, center: Vector3, curr: Vector3) -> tuple[float, float, float]:
    """``center - curr`` plus the curr-to-check block offset, the three ``float`` locals the slides
    and point collisions build: the x and y differences stay in registers, the z difference is
    stored first (acclient.c:358760-358765, 358944-358951, 358844-358852)."""
    block = path.get_curr_pos_check_pos_block_offset()
    dz = f32(center.z - curr.z)
    return unpack3(pack3(block.x + (center.x - curr.x), block.y + (center.y - curr.y), block.z + dz))


def _slide_plane(collisions: CollisionInfo) -> Plane:
    """The plane a slide runs along: the contact plane if valid, else the last known one."""
    if collisions.contact_plane_valid:
        return collisions.contact_plane
    return collisions.last_known_contact_plane


class SphereTransition(Protocol):
    """What ``intersects_sphere`` and ``step_sphere_up`` read from a ``CTransition``."""

    object_info: ObjectInfo
    sphere_path: SpherePath
    collision_info: CollisionInfo

    def step_up(self, collision_normal: Vector3) -> bool: ...


class Sphere:
    """Retail ``CSphere`` (acclient.h:31107): ``{Vector3 center; float radius}``; the radius is
    narrowed to float32 when the sphere is built."""

    __slots__ = ("center", "radius")

    def __init__(self, center: Vector3, radius: float) -> None:
        self.center = center.copy()
        self.radius = f32(radius)

    @classmethod
    def owning(cls, center: Vector3, radius: float) -> Sphere:
        """A sphere that takes ``center`` itself, uncopied: for a vector the caller has just
        built and keeps no other reference to. ``radius`` must already be a float32."""
        sphere = _new(cls)
        sphere.center = center
        sphere.radius = radius
        return sphere

    def copy(self) -> Sphere:
        return Sphere.owning(self.center.copy(), self.radius)

    def __repr__(self) -> str:
        return f"Sphere({self.center!r}, {self.radius!r})"

    def intersects(self, other: Sphere) -> bool:
        """Strictly closer than the sum of the radii (touching is a miss).

        The decompiled body (acclient.c:356350-356354) keeps only the deltas and radius sum; the
        x87 flag test ``(c0 | c2) != 0`` is ``dist² < (r_a + r_b)²``.

        Retail: CSphere::intersects @ 0x005344A0 (acclient.c:356340)
        """
        dx = self.center.x - other.center.x
        dy = self.center.y - other.center.y
        dz = self.center.z - other.center.z
        reach = self.radius + other.radius
        return dx * dx + dy * dy + dz * dz < reach * reach

    @staticmethod
    def collides_with_sphere(disp: Vector3, radsum: float) -> bool:
        """Whether centres ``disp`` apart are within ``radsum``: ``|disp|² <= radsum²`` (touching hits).

        Hex-Rays lost the compare (acclient.c:358515 keeps only ``return c0 == 0``). The forced
        reading is "not (radsum² < |disp|²)": the other reading would make far spheres collide, and
        ``step_sphere_down`` (acclient.c:358649) and the placement branch of ``intersects_sphere``
        (acclient.c:359214) spell the same test out as ``radsum² < |disp|²`` -> miss.

        Retail: CSphere::collides_with_sphere @ 0x005369E0 (acclient.c:358508)
        """
        return disp.length_squared() <= radsum * radsum

    @staticmethod
    def find_time_of_collision(movement: Vector3, disp: Vector3, radsum: float) -> float:
        """The fraction of ``movement`` at which a sphere ``disp`` from an obstacle first touches it.

        -1.0 when already within ``radsum`` (to EPSILON), not moving, or never reaching it. Of
        the two roots ``(b ∓ √D)/a`` retail takes the smaller unless it is negative. ``radsum``
        is a ``float`` parameter.

        Retail: CSphere::find_time_of_collision @ 0x005368F0 (acclient.c:358480)
        """
        a = movement.length_squared()
        b = -(disp.z * movement.z + disp.y * movement.y + movement.x * disp.x)
        c = disp.length_squared() - radsum * radsum
        if c < EPSILON or a < EPSILON:
            return -1.0
        disc = b * b - c * a
        if disc < 0.0:
            return -1.0
        root = math.sqrt(disc)
        if b - root < 0.0:
            return (root + b) / a
        return (b - root) / a

    def sphere_intersects_ray(self, ray: Ray) -> float | None:
        """Where (in units of ``ray.dir``) the ray meets this sphere; None if it starts inside or misses.

        Retail: CSphere::sphere_intersects_ray @ 0x005377A0 (acclient.c:359009)
        """
        d = ray.pt - self.center
        r = ray.dir
        a = r.z * r.z + r.y * r.y + r.x * r.x
        b = -(d.z * r.z + d.y * r.y + d.x * r.x)
        c = d.x * d.x + d.z * d.z + d.y * d.y - self.radius * self.radius
        if c <= 0.0 or a < EPSILON:
            return None
        disc = b * b - c * a
        if disc < 0.0:
            return None
        root = math.sqrt(disc)
        if b <= root:
            return (root + b) / a
        return (b - root) / a

    def intersects_sphere_placed(
        self, p: Position, scale: float, transition: SphereTransition, is_creature: bool
    ) -> TransitionState:
        """``intersects_sphere`` for this sphere local to ``p`` at ``scale``, in ``check_pos``'s block
        (``Position::localtoglobal``, :meth:`acphys.math.position.Position.localtoglobal`).

        Retail: CSphere::intersects_sphere @ 0x00537FD0 (acclient.c:359389)
        """
        center = transition.sphere_path.check_pos.localtoglobal(p, self.center * scale)
        return Sphere.owning(center, f32(scale * self.radius)).intersects_sphere(transition, is_creature)

    def intersects_sphere(self, transition: SphereTransition, is_creature: bool) -> TransitionState:
        """Test the moving spheres (``global_sphere``) against this obstacle and respond.

        ``radsum`` is the radius sum less EPSILON, a ``float`` (acclient.c:359211). Dispatch
        (acclient.c:359211-359385): an
        ethereal obstruction or placement only reports overlap; ``step_down`` steps onto the
        sphere (not for creatures); ``check_walkable`` only reports overlap; before a collision
        is flagged, a body in contact steps up (sphere 0) or slides (sphere 1), a path-clipped
        one collides with a point, anything else lands (sphere 0) or collides with a point
        (sphere 1); after ``collide`` is set, a non-creature is rewound along its movement
        onto the sphere and gets a contact plane there if walkable.

        Hex-Rays artefacts resolved by the only value in reach: the ``radsum`` passed to
        ``step_sphere_up`` (acclient.c:359262) and ``collide_with_point`` (acclient.c:359308) and
        the ``collisions`` passed at acclient.c:359282/359295 show as uninitialised registers; the
        placement branch's sphere-1 displacement (acclient.c:359217-359222) is shown copied before
        two of its components are written, read here as ``global_sphere[1].center - center``.

        Retail: CSphere::intersects_sphere @ 0x00537A80 (acclient.c:359156)
        """
        path = transition.sphere_path
        obj = transition.object_info
        collisions = transition.collision_info
        moving = path.global_sphere[0]
        disp = moving.center - self.center
        radsum = f32(self.radius + moving.radius - EPSILON)
        second = path.global_sphere[1] if path.num_sphere > 1 else None

        def second_collides() -> bool:
            return second is not None and self.collides_with_sphere(second.center - self.center, radsum)

        if path.obstruction_ethereal or path.insert_type == 1:
            if radsum * radsum >= disp.y * disp.y + disp.x * disp.x + disp.z * disp.z or second_collides():
                return TS.COLLIDED
            return TS.OK
        if path.step_down:
            if is_creature:
                return TS.OK
            return self.step_sphere_down(obj, path, collisions, moving, disp, radsum)
        if path.check_walkable:
            if self.collides_with_sphere(disp, radsum) or second_collides():
                return TS.COLLIDED
            return TS.OK
        if not path.collide:
            if obj.state & (OI.CONTACT | OI.ON_WALKABLE):
                if self.collides_with_sphere(disp, radsum):
                    return self.step_sphere_up(transition, moving, disp, radsum)
                if second is not None:
                    disp2 = second.center - self.center
                    if self.collides_with_sphere(disp2, radsum):
                        return self.slide_sphere(obj, path, collisions, second, disp2, radsum, 1)
            elif obj.state & OI.PATH_CLIPPED:
                if self.collides_with_sphere(disp, radsum):
                    return self.collide_with_point(obj, path, collisions, moving, disp, radsum, 0)
            else:
                if self.collides_with_sphere(disp, radsum):
                    return self.land_on_sphere(obj, path, collisions, moving, disp, radsum)
                if second is not None:
                    disp2 = second.center - self.center
                    if self.collides_with_sphere(disp2, radsum):
                        return self.collide_with_point(obj, path, collisions, second, disp2, radsum, 1)
            return TS.OK
        if is_creature:
            return TS.OK
        if not (self.collides_with_sphere(disp, radsum) or second_collides()):
            return TS.OK
        return self._rewind_onto_sphere(path, collisions, moving, disp, f32(radsum + EPSILON))

    def _rewind_onto_sphere(
        self, path: SpherePath, collisions: CollisionInfo, moving: Sphere, disp: Vector3, reach: float
    ) -> TransitionState:
        """The ``collide`` arm of ``intersects_sphere`` (acclient.c:359321-359380).

        Back sphere 0 up along its movement since ``curr_pos`` until it touches this sphere at
        ``reach`` (radsum + EPSILON, a ``float``). Retail's quirk: it compares the root's *numerator*
        ``√D + b`` with 1.0 and, when larger, uses ``2b - (√D + b)`` = ``b - √D`` instead. An
        unguarded negative discriminant gives NaN, which fails the interp test: COLLIDED. The
        dot products sum z, y, x for ``|movement|²`` and y, x, z for the others
        (acclient.c:359333-359340); the normal is ``(disp + movement·t)`` times ``1/reach``
        (``Vector3::operator/=``).
        """
        movement = path.global_curr_center[0] - moving.center - path.get_curr_pos_check_pos_block_offset()
        a = movement.z * movement.z + movement.y * movement.y + movement.x * movement.x
        b = -(movement.y * disp.y + movement.x * disp.x + movement.z * disp.z)
        if abs(a) < EPSILON:
            return TS.COLLIDED
        disp2 = disp.y * disp.y + disp.x * disp.x + disp.z * disp.z
        numerator = _x87_sqrt(b * b - (disp2 - reach * reach) * a) + b
        if numerator > 1.0:
            numerator = b + b - numerator
        t = numerator / a
        interp = (1.0 - t) * path.walk_interp
        if not (interp < path.walk_interp and interp >= _MIN_WALK_INTERP):
            return TS.COLLIDED
        movement = movement * t
        normal = (movement + disp) * (1.0 / reach)
        if not path.is_walkable_allowable(normal.z):
            return TS.OK
        collisions.set_contact_plane(Plane.from_point(normal, moving.center - normal * moving.radius), True)
        collisions.contact_plane_cell_id = path.check_pos.objcell_id
        path.walk_interp = f32(interp)
        path.add_offset_to_check_pos(movement, moving.radius)
        return TS.ADJUSTED

    def step_sphere_down(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
    ) -> TransitionState:
        """Lower the moving sphere onto this one while stepping down; a walkable top is the contact plane.

        OK when neither moving sphere reaches this one or the resting normal is not above
        ``walkable_allowance``; COLLIDED when the step is nil or would rewind ``walk_interp``
        out of ``[-0.1, walk_interp)``. ``disp`` is overwritten with the resting normal, as
        retail does. The horizontal part of ``disp`` (sphere 0) is used even when only sphere 1
        reaches; if that exceeds ``radsum + EPSILON`` the root is NaN and retail goes on to set a
        NaN contact plane, which is kept here.

        ``float`` locals (acclient.c:358647-358697): the squares ``disp.x²`` and ``disp.y²``, the
        step ``step_down_amt·walk_interp`` (its EPSILON test reads the register), ``reach``
        (multiplied by its own register value under the root), and the drop ``step·t``; the
        interp stays double until it is stored into the path. The resting normal's z is scaled
        from the unstored ``drop + disp.z``.

        Retail: CSphere::step_sphere_down @ 0x00536D20 (acclient.c:358615)
        """
        hx, hy, _ = unpack3(pack3(disp.x * disp.x, disp.y * disp.y, 0.0))
        if radsum * radsum < disp.z * disp.z + hx + hy:
            if path.num_sphere <= 1:
                return TS.OK
            if not self.collides_with_sphere(path.global_sphere[1].center - self.center, radsum):
                return TS.OK
        step_reg = path.step_down_amt * path.walk_interp
        if abs(step_reg) < EPSILON:
            return TS.COLLIDED
        step = f32(step_reg)
        reach_reg = radsum + EPSILON
        reach = f32(reach_reg)
        t = (_x87_sqrt(reach_reg * reach - (hx + hy)) - disp.z) / step
        interp = (1.0 - t) * path.walk_interp
        if interp >= path.walk_interp or interp < _MIN_WALK_INTERP:
            return TS.COLLIDED
        drop = f32(step * t)
        rise = drop + disp.z
        inv = 1.0 / reach
        disp.x, disp.y, disp.z = unpack3(pack3(inv * disp.x, inv * disp.y, rise * inv))
        if rise * inv <= path.walkable_allowance:
            return TS.OK
        collisions.set_contact_plane(Plane.from_point(disp, self.center + disp * self.radius), True)
        collisions.contact_plane_cell_id = path.check_pos.objcell_id
        path.walk_interp = f32(interp)
        path.add_offset_to_check_pos(Vector3(0.0, 0.0, drop), check_pos.radius)
        return TS.ADJUSTED

    def step_sphere_up(
        self, transition: SphereTransition, check_pos: Sphere, disp: Vector3, radsum: float
    ) -> TransitionState:
        """Sphere 0 hit this one while in contact: step up over it if low enough, else slide.

        Too high (``step_up_height < radsum + EPSILON - disp.z``) slides sphere 0 along it;
        otherwise ``CTransition::step_up`` with the (unnormalised) normal from this centre to
        sphere 0's current centre, and a failed step falls back to ``step_up_slide``. The height
        test reads ``reach`` from the register; the slide gets it as a ``float``.

        Retail: CSphere::step_sphere_up @ 0x00537900 (acclient.c:359071)
        """
        reach = radsum + EPSILON
        path = transition.sphere_path
        if transition.object_info.step_up_height < reach - disp.z:
            obj, collisions = transition.object_info, transition.collision_info
            return self.slide_sphere_skid(obj, path, collisions, disp, f32(reach), 0)
        if transition.step_up(path.global_curr_center[0] - self.center):
            return TS.OK
        return path.step_up_slide(transition.object_info, transition.collision_info)

    def land_on_sphere(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
    ) -> TransitionState:
        """An airborne sphere 0 hit this one: flag the collision and allow landing slopes (``z_for_landing``).

        Retail: CSphere::land_on_sphere @ 0x005379A0 (acclient.c:359114)
        """
        normal = path.global_curr_center[0] - self.center
        if normal.normalize_check_small():
            return TS.COLLIDED
        path.set_collide(normal)
        path.walkable_allowance = LANDING_Z
        return TS.ADJUSTED

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

        With PERFECT_CLIP the moving sphere is backed up along its movement to where it first
        touches (at ``radsum + EPSILON``) and ADJUSTED; otherwise, or if that time is outside
        ``[EPSILON, 1]``, COLLIDED. The decompiled call for sphere 1 (acclient.c:359308) passes
        an uninitialised register for ``radsum``; the caller's radsum is the only value in reach.

        ``reach`` is a ``float``; the offset ``movement·t - movement`` keeps ``movement.x·t`` in a
        register but stores ``movement.y·t`` and ``movement.z·t``, and the normal is built from the
        offset's unstored x and y, with only ``offset.x + center.x`` stored on the way
        (acclient.c:358839-358880).

        Retail: CSphere::collide_with_point @ 0x00537230 (acclient.c:358807)
        """
        curr = path.global_curr_center[sphere_num]
        if not obj.state & OI.PERFECT_CLIP:
            normal = curr - self.center
            if not normal.normalize_check_small():
                collisions.set_collision_normal(normal)
            return TS.COLLIDED
        reach = f32(radsum + EPSILON)
        movement = _new(Vector3)
        movement.x, movement.y, movement.z = mx, my, mz = _step_since_curr(path, check_pos.center, curr)
        t = self.find_time_of_collision(movement, curr - self.center, reach)
        if t < EPSILON or t > 1.0:
            return TS.COLLIDED
        ox = mx * t - mx
        ty, tz, _ = unpack3(pack3(my * t, mz * t, 0.0))
        oy, oz = ty - my, tz - mz
        offset = Vector3(ox, oy, oz)
        c, o = check_pos.center, self.center
        nx = f32(f32(ox + c.x) - o.x)
        inv = 1.0 / reach
        normal = Vector3(nx * inv, (oy + c.y - o.y) * inv, (offset.z + c.z - o.z) * inv)
        collisions.set_collision_normal(normal)
        path.add_offset_to_check_pos(offset, check_pos.radius)
        return TS.ADJUSTED

    def slide_sphere(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        disp: Vector3,
        radsum: float,
        sphere_number: int,
    ) -> TransitionState:
        """Slide moving sphere ``sphere_number`` (``check_pos``) off this one (used for sphere 1).

        The normal runs from this centre to the moving sphere's current centre; the slide is
        :meth:`slide_sphere_normal` on ``check_pos``.

        Retail: CSphere::slide_sphere @ 0x00537A10 (acclient.c:359138)
        """
        curr = path.global_curr_center[sphere_number]
        normal = curr - self.center
        if normal.normalize_check_small():
            return TS.COLLIDED
        return check_pos.slide_sphere_normal(path, collisions, normal, curr)

    def slide_sphere_normal(
        self, path: SpherePath, collisions: CollisionInfo, collision_normal: Vector3, curr_pos: Vector3
    ) -> TransitionState:
        """Slide this moving sphere (at ``curr_pos`` before the step) along ``collision_normal``.

        A zero normal moves halfway back to ``curr_pos`` (ADJUSTED). Otherwise the step is
        projected onto ``collision_normal × contact-plane normal`` (contact plane, or the last
        known one) and the sphere moved onto that (SLID), COLLIDED if that leaves under
        √EPSILON. When the normal is parallel to the plane normal: facing it, the step loses its
        part along the normal (SLID); facing away, ``collision_normal`` is overwritten with the
        reversed step, normalised, stored as the collision normal, and the result is COLLIDED.

        Stores (acclient.c:358941-359005): the step is three ``float`` locals (see
        :func:`_step_since_curr`); of the slide direction ``collision_normal × plane.N`` only x and
        z are stored, y stays in a register, and its squared length is a ``float`` local whose EPSILON
        test reads the register; the projection scales the direction by the step·direction sum
        (y and z stored) and then by the reciprocal length (x from registers, y and z by its
        ``float`` spill); the head-on projection length is a ``float`` local.

        Retail: CSphere::slide_sphere @ 0x00537440 (acclient.c:358898)
        """
        cn = collision_normal
        if cn.x == 0.0 and cn.y == 0.0 and cn.z == 0.0:
            path.add_offset_to_check_pos((curr_pos - self.center) * 0.5, self.radius)
            return TS.ADJUSTED
        collisions.set_collision_normal(cn)
        sx, sy, sz = _step_since_curr(path, self.center, curr_pos)
        p = _slide_plane(collisions).N
        dir_y = p.x * cn.z - p.z * cn.x
        dir_z_reg = p.y * cn.x - p.x * cn.y
        dir_x, dir_z, _ = unpack3(pack3(cn.y * p.z - cn.z * p.y, dir_z_reg, 0.0))
        dir2_reg = dir_z_reg * dir_z + dir_y * dir_y + dir_x * dir_x
        if dir2_reg >= EPSILON:
            dot = dir_z * sz + dir_y * sy + dir_x * sx
            py, pz, _ = unpack3(pack3(dir_y * dot, dir_z * dot, 0.0))
            inv_reg = 1.0 / f32(dir2_reg)
            inv = f32(inv_reg)
            ax = dir_x * dot * inv_reg
            ay, az, _ = unpack3(pack3(py * inv, pz * inv, 0.0))
            if az * az + ay * ay + ax * ax < EPSILON:
                return TS.COLLIDED
            path.add_offset_to_check_pos(Vector3(ax - sx, ay - sy, az - sz), self.radius)
            return TS.SLID
        if cn.z * p.z + cn.y * p.y + p.x * cn.x >= 0.0:
            proj = f32(sx * cn.x + sz * cn.z + sy * cn.y)
            path.add_offset_to_check_pos(Vector3(-cn.x * proj, -cn.y * proj, -cn.z * proj), self.radius)
            return TS.SLID
        cn.x, cn.y, cn.z = -sx, -sy, -sz
        if not cn.normalize_check_small():
            collisions.set_collision_normal(cn)
        return TS.COLLIDED

    def slide_sphere_skid(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        disp: Vector3,
        radsum: float,
        sphere_num: int,
    ) -> TransitionState:
        """Slide moving sphere ``sphere_num`` off this obstacle when too high to step over.

        Like :meth:`slide_sphere_normal` with the normal from this centre to the sphere's current
        centre, except: a tiny normal is COLLIDED; when the normal is parallel to the plane normal
        it is ``plane.N · disp < 0`` that gives COLLIDED (else the step loses its part along the
        normal, SLID). Hex-Rays lost the compare after the projection (acclient.c:358781, only
        ``!(c0 | c2)`` survives); the routine's twin (acclient.c:358973) and ACE test
        ``|projection|² < EPSILON`` -> COLLIDED there, which is the reading taken.

        Stores (acclient.c:358738-358803): the direction is a ``Vector3``; the step is three
        ``float`` locals (see :func:`_step_since_curr`); the projection is stored scaled by the
        step·direction sum, then by the reciprocal squared length; the head-on projection length
        is a ``float`` local.

        Retail: CSphere::slide_sphere @ 0x00536F40 (acclient.c:358708)
        """
        moving = path.global_sphere[sphere_num]
        curr = path.global_curr_center[sphere_num]
        normal = curr - self.center
        if normal.normalize_check_small():
            return TS.COLLIDED
        collisions.set_collision_normal(normal)
        p = _slide_plane(collisions).N
        d = normal.cross(p)
        sx, sy, sz = _step_since_curr(path, moving.center, curr)
        dir2 = d.z * d.z + d.y * d.y + d.x * d.x
        if dir2 >= EPSILON:
            dot = sz * d.z + sy * d.y + sx * d.x
            inv = 1.0 / dir2
            along = d * dot * inv
            if along.z * along.z + along.y * along.y + along.x * along.x < EPSILON:
                return TS.COLLIDED
            path.add_offset_to_check_pos(Vector3(along.x - sx, along.y - sy, along.z - sz), moving.radius)
            return TS.SLID
        if p.z * disp.z + p.y * disp.y + p.x * disp.x < 0.0:
            return TS.COLLIDED
        proj = f32(sz * normal.z + sy * normal.y + sx * normal.x)
        offset = Vector3(-normal.x * proj, -normal.y * proj, -normal.z * proj)
        path.add_offset_to_check_pos(offset, moving.radius)
        return TS.SLID


#: ``dummy_sphere``: what a transition sweeps for an object with no spheres (r 0.1 at z 0.1).
DUMMY_SPHERE = Sphere(Vector3(0.0, 0.0, 0.1), 0.1)
