"""The ``BSPTREE`` collision queries a transition runs against a physics BSP.

:class:`BSPTreeCollisions` is a mixin of :class:`acphys.geometry.bsp.BSPTree`. The tree lives
in its owner's frame: a cell or part calls ``SPHEREPATH::cache_localspace_sphere`` with that
frame and scale first, so ``localspace_sphere``, ``localspace_curr_center``, ``localspace_pos``
and ``localspace_z`` describe the moving spheres in tree space (lengths divided by ``scale``).
Offsets found there are rotated back with ``localspace_pos`` and, where retail does, multiplied
by ``scale`` before they move ``check_pos``. Retail rotates with three different row orders: the
inlined ``Frame::localtoglobalvec`` (``step_sphere_up``, ``slide_sphere``),
``Position::localtoglobalvec`` (:meth:`acphys.math.position.Position.localtoglobalvec`) and
a few inlined sums of their own; each routine here uses the one retail does.

``find_collisions`` keeps retail's query kinds apart (acclient.c:361335-361498): placement or
ethereal obstruction, ``check_walkable``, ``step_down``, ``collide`` (land on a walkable face),
and, before a collision is flagged, a body in contact (step up / slide / back-face hits), an
airborne body, and a path-clipped one.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import LANDING_Z
from acphys.flags import ObjectInfoState, TransitionState, member_namespace
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    from acphys.geometry.bsp import BSPNode, BSPPolygon
    from acphys.geometry.sphere import SphereTransition
    from acphys.math.position import Position
    from acphys.transition.collision_info import CollisionInfo
    from acphys.transition.object_info import ObjectInfo
    from acphys.transition.transition import SpherePath

TS = member_namespace(TransitionState)

#: ``SPHEREPATH::InsertType`` PLACEMENT (``acphys.transition.transition.InsertType``, not imported:
#: the transition package imports the geometry package).
_PLACEMENT_INSERT = 1

#: ``BSPTREE::placement_insert`` gives up after this many nudges (acclient.c:360888-360892).
PLACEMENT_TRIES = 20
#: ``BSPTREE::adjust_to_plane`` iteration budget, shared by both of its loops (acclient.c:360979, 361010).
ADJUST_TRIES = 15
#: ``BSPTREE::adjust_to_plane`` stops bisecting once the bracket is narrower than this (acclient.c:361006).
ADJUST_BRACKET = 0.02


def plane_localtoglobal(to: Position, frm: Position, local_plane: Plane) -> Plane:
    """``local_plane`` (in ``frm``'s frame) as a plane in ``to``'s landblock.

    The normal is rotated by ``frm`` (each row summed z, y, x and spilled to ``float``); the
    point ``-d·N`` (a ``Vector3``) is taken to ``to``'s block (``Position::localtoglobal``) and
    ``d`` recomputed through it (acclient.c:467689-467713).

    Retail: Plane::localtoglobal @ 0x005AA0A0 (acclient.c:467671)
    """
    n = local_plane.N
    m = frm.frame.m
    back = -local_plane.d
    point = Vector3(back * n.x, back * n.y, back * n.z)
    normal = Vector3(
        m[6] * n.z + m[3] * n.y + m[0] * n.x,
        m[7] * n.z + m[4] * n.y + m[1] * n.x,
        m[8] * n.z + m[5] * n.y + m[2] * n.x,
    )
    p = to.localtoglobal(frm, point)
    return Plane(normal, -(normal.z * p.z + normal.y * p.y + normal.x * p.x))


def _along(origin: Vector3, movement: Vector3, t: float) -> Vector3:
    """``origin + movement·t`` as ``adjust_to_plane`` stores it: ``movement·t`` is spilled to
    ``float`` for x and y only, and each sum is stored (acclient.c:360956-360967)."""
    tx, ty, _ = unpack3(pack3(movement.x * t, movement.y * t, 0.0))
    return Vector3(tx + origin.x, ty + origin.y, t * movement.z + origin.z)


def _scaled_global(path: SpherePath, offset: Vector3, scale: float) -> Vector3:
    """``offset`` (a ``Vector3``) rotated by ``Position::localtoglobalvec`` and multiplied by the
    ``float`` ``scale``, component by component (acclient.c:361383-361389, 361165-361171)."""
    return path.localspace_pos.localtoglobalvec(offset) * scale


class BSPTreeCollisions:
    """The ``BSPTREE`` collision routines; the host class provides ``root_node``."""

    __slots__ = ()

    root_node: BSPNode

    def find_collisions(self, transition: SphereTransition, scale: float) -> TransitionState:
        """Test the moving spheres (tree space, see the module docstring) against this tree and respond.

        - placement or ethereal obstruction: COLLIDED if either sphere overlaps the solid
          (``sphere_intersects_solid`` with the centre check unless ``bldg_check`` and
          ``hits_interior_cell``), else OK;
        - ``check_walkable``: :meth:`check_walkable`; ``step_down``: :meth:`step_sphere_down`;
        - ``collide``: back sphere 0 along its movement onto the walkable faces it touches
          (``find_walkable``); if any, move ``check_pos`` there, set that face as the contact
          plane and the walkable (ADJUSTED); otherwise OK;
        - in contact (``CONTACT`` bit only): sphere 0 headed into a face steps up
          (:meth:`step_sphere_up`); else sphere 1 headed into a face slides
          (:meth:`slide_sphere`); else a face sphere 1, or failing that sphere 0, merely
          touches is recorded with ``set_neg_poly_hit`` (step-up flag 0 resp. 1), OK. The
          back-face record needs two spheres;
        - airborne (not path-clipped): a face sphere 0 touches flags the collision
          (``set_collide`` with its global normal, ``walkable_allowance = LANDING_Z``, ADJUSTED);
          else one sphere 1 touches sets the collision normal, COLLIDED;
        - path-clipped: a face sphere 0 touches goes to :meth:`collide_with_pt`; sphere 1 is not
          tested.

        Retail: BSPTREE::find_collisions @ 0x0053A440 (acclient.c:361295)
        """
        path = transition.sphere_path
        collisions = transition.collision_info
        root = self.root_node
        sphere0 = path.localspace_sphere[0]
        sphere1 = path.localspace_sphere[1] if path.num_sphere > 1 else None
        curr0 = path.localspace_curr_center[0]
        movement = sphere0.center - curr0
        if path.insert_type == _PLACEMENT_INSERT or path.obstruction_ethereal:
            center_check = not path.hits_interior_cell if path.bldg_check else True
            if root.sphere_intersects_solid(sphere0, center_check) or (
                sphere1 is not None and root.sphere_intersects_solid(sphere1, center_check)
            ):
                return TS.COLLIDED
            return TS.OK
        if path.check_walkable:
            return self.check_walkable(path, sphere0, scale)
        if path.step_down:
            return self.step_sphere_down(path, collisions, sphere0, scale)
        if path.collide:
            valid_pos = sphere0.copy()
            poly = root.find_walkable(path, valid_pos, movement, path.localspace_z)
            if poly is None:
                return TS.OK
            path.add_offset_to_check_pos(_scaled_global(path, valid_pos.center - sphere0.center, scale))
            contact = plane_localtoglobal(path.check_pos, path.localspace_pos, poly.plane)
            contact.d = f32(contact.d * scale)
            collisions.set_contact_plane(contact, False)
            collisions.contact_plane_cell_id = path.check_pos.objcell_id
            path.set_walkable(valid_pos, poly, path.localspace_z, path.localspace_pos, scale)
            return TS.ADJUSTED
        state = transition.object_info.state
        lpos = path.localspace_pos
        if state & ObjectInfoState.CONTACT:
            found0 = root.sphere_intersects_poly(sphere0, movement)
            if found0.hit:
                assert found0.polygon is not None
                return self.step_sphere_up(transition, found0.polygon.plane.N)
            if sphere1 is not None:
                found1 = root.sphere_intersects_poly(sphere1, movement, None, found0.contact_pt)
                if found1.hit:
                    assert found1.polygon is not None
                    return self.slide_sphere(path, collisions, found1.polygon.plane.N)
                if found1.polygon is not None:
                    path.set_neg_poly_hit(False, lpos.localtoglobalvec(found1.polygon.plane.N))
                elif found0.polygon is not None:
                    path.set_neg_poly_hit(True, lpos.localtoglobalvec(found0.polygon.plane.N))
            return TS.OK
        found0 = root.sphere_intersects_poly(sphere0, movement)
        if state & ObjectInfoState.PATH_CLIPPED:
            if found0.polygon is None:
                return TS.OK
            obj = transition.object_info
            return self.collide_with_pt(
                obj, path, collisions, sphere0, curr0, found0.polygon, found0.contact_pt, scale
            )
        if found0.polygon is not None:
            path.set_collide(lpos.localtoglobalvec(found0.polygon.plane.N))
            path.walkable_allowance = LANDING_Z
            return TS.ADJUSTED
        if sphere1 is not None:
            found1 = root.sphere_intersects_poly(sphere1, movement, None, found0.contact_pt)
            if found1.polygon is not None:
                collisions.set_collision_normal(lpos.localtoglobalvec(found1.polygon.plane.N))
                return TS.COLLIDED
        return TS.OK

    def placement_insert(self, transition: SphereTransition) -> TransitionState:
        """Nudge the spheres out of the solid for a placement: OK if already clear, ADJUSTED
        (``check_pos`` moved) once clear, COLLIDED after 20 tries.

        Each try asks ``sphere_intersects_solid_poly`` of sphere 0, then (clear) of sphere 1,
        with a straddle band ``rad`` that starts at sphere 0's radius (also for sphere 1). A
        polygon hit pushes the struck sphere, and the other with it, out along the polygon
        normal (``adjust_to_placement_poly``) and resets ``rad``; a hit with no polygon (the
        centre in a solid leaf) doubles ``rad``. ``center_solid`` is cleared at the start of
        each try only; the recorded polygon is cleared only after an adjustment, so a polygon
        recorded by a miss is carried into the next query, as in retail.

        The offset applied is sphere 0's tree-space displacement rotated by ``localspace_pos``,
        *not* multiplied by the scale (retail takes no scale here). The single-sphere exit
        (acclient.c:360894-360912) inlines ``add_offset_to_check_pos``; Hex-Rays shows the
        offset copied before its y and z are written, read here like the two-sphere exit
        (acclient.c:360861-360876) that spells the same step out. The two exits round
        differently: the two-sphere one stores the displacement and rotates it with
        ``Position::localtoglobalvec``, the single-sphere one rotates the unstored displacement
        with sums of its own (x, y, z terms in turn). ``rad`` is the ``float`` local
        ``transitiona``.

        Retail: BSPTREE::placement_insert @ 0x00539960 (acclient.c:360778)
        """
        from acphys.geometry.bsp import SolidPolyHit  # bsp.py imports this module for the mixin

        path = transition.sphere_path
        valid_pos = path.localspace_sphere[0].copy()
        valid_pos2 = path.localspace_sphere[1].copy() if path.num_sphere > 1 else Sphere(Vector3(), 0.0)
        rad = valid_pos.radius
        center_check = not path.hits_interior_cell if path.bldg_check else True
        hit = SolidPolyHit()
        root = self.root_node
        for tries in range(PLACEMENT_TRIES):
            hit.center_solid = False
            if root.sphere_intersects_solid_poly(valid_pos, rad, hit, center_check):
                struck, other = valid_pos, valid_pos2
            elif path.num_sphere <= 1:
                if tries == 0:
                    return TS.OK
                start, end = path.localspace_sphere[0].center, valid_pos.center
                m = path.localspace_pos.frame.m
                dx, dy, dz = end.x - start.x, end.y - start.y, end.z - start.z
                offset = Vector3(
                    dx * m[0] + dy * m[3] + dz * m[6],
                    dx * m[1] + dy * m[4] + dz * m[7],
                    dx * m[2] + dy * m[5] + dz * m[8],
                )
                path.add_offset_to_check_pos(offset)
                return TS.ADJUSTED
            elif not root.sphere_intersects_solid_poly(valid_pos2, rad, hit, center_check):
                if tries == 0:
                    return TS.OK
                offset = valid_pos.center - path.localspace_sphere[0].center
                path.add_offset_to_check_pos(path.localspace_pos.localtoglobalvec(offset))
                return TS.ADJUSTED
            else:
                struck, other = valid_pos2, valid_pos
            if hit.hit_poly is None:
                rad = rad + rad
                continue
            hit.hit_poly.adjust_to_placement_poly(struck, other, rad, hit.center_solid, center_check)
            hit.hit_poly = None
            rad = valid_pos.radius
        return TS.COLLIDED

    def adjust_to_plane(
        self, check_pos: Sphere, curr_pos: Vector3, hit_poly: BSPPolygon, contact_pt: Vector3
    ) -> bool:
        """Move ``check_pos`` back along ``curr_pos -> check_pos`` to the last point clear of the tree.

        First loop: jump to where the sphere touches ``hit_poly``'s plane
        (``adjust_sphere_to_poly``); clear there ends the loop with that time as the lower bound,
        still hitting makes it the upper bound and retries with the polygon hit now (15 tries,
        then False). Then bisect ``[lower, upper]`` until narrower than 0.02 or the shared
        15-step budget runs out, and leave the sphere at the lower bound (True).

        Hex-Rays lost the first loop's exit test (acclient.c:360954, only ``if (c3 | c2)``
        survives): an equality (or unordered) compare on the time just returned. Read as
        ``time == 1.0``, the value ``adjust_sphere_to_poly`` returns when the sphere already
        reaches the plane at ``curr_pos`` and no touching time exists: the search falls back
        to bisection. ACE compares with 1.0 too but runs the loop body only when equal, so
        for any other time it spins to failure; and its bisection swaps the bounds and returns
        False on convergence. The decompiled loops are followed here. The times are doubles
        (``time_touch``, ``ltime``, ``utime`` and the midpoint spill are 8 bytes); each placement of
        the centre is stored as :func:`_along` describes.

        Retail: BSPTREE::adjust_to_plane @ 0x00539BF0 (acclient.c:360915)
        """
        root = self.root_node
        movement = check_pos.center - curr_pos
        lower, upper = 0.0, 1.0
        count = 0
        while True:
            touch = hit_poly.adjust_sphere_to_poly(check_pos, curr_pos, movement)
            if touch == 1.0 or math.isnan(touch):
                break
            check_pos.center.set(_along(curr_pos, movement, touch))
            found = root.sphere_intersects_poly(check_pos, movement, hit_poly, contact_pt)
            if found.polygon is not None:
                hit_poly = found.polygon
            if not found.hit:
                lower = touch
                break
            count += 1
            upper = touch
            if count >= ADJUST_TRIES:
                return False
        while True:
            mid = (lower + upper) * 0.5
            check_pos.center.set(_along(curr_pos, movement, mid))
            found = root.sphere_intersects_poly(check_pos, movement, hit_poly, contact_pt)
            if found.polygon is not None:
                hit_poly = found.polygon
            if found.hit:
                upper = mid
            else:
                lower = mid
            if upper - lower < ADJUST_BRACKET:
                break
            count += 1
            if count >= ADJUST_TRIES:
                break
        check_pos.center.set(_along(curr_pos, movement, lower))
        return True

    def collide_with_pt(
        self,
        obj: ObjectInfo,
        path: SpherePath,
        collisions: CollisionInfo,
        check_pos: Sphere,
        curr_pos: Vector3,
        hit_poly: BSPPolygon,
        contact_pt: Vector3,
        scale: float,
    ) -> TransitionState:
        """A path-clipped body touched ``hit_poly``: COLLIDED with its global normal, unless
        ``PERFECT_CLIP``, which backs a copy of ``check_pos`` up to the last clear point
        (:meth:`adjust_to_plane`, COLLIDED without a normal if that fails), sets the normal and
        moves ``check_pos`` by the scaled global offset (ADJUSTED). Without ``PERFECT_CLIP`` the
        normal is rotated with inlined sums (x, y, z terms in turn, acclient.c:361138-361144),
        with it by ``Position::localtoglobalvec``.

        Retail: BSPTREE::collide_with_pt @ 0x0053A090 (acclient.c:361123)
        """
        if not obj.state & ObjectInfoState.PERFECT_CLIP:
            n, m = hit_poly.plane.N, path.localspace_pos.frame.m
            normal = Vector3(
                m[0] * n.x + m[3] * n.y + m[6] * n.z,
                m[1] * n.x + m[4] * n.y + m[7] * n.z,
                m[2] * n.x + m[5] * n.y + m[8] * n.z,
            )
            collisions.set_collision_normal(normal)
            return TS.COLLIDED
        valid_pos = check_pos.copy()
        if not self.adjust_to_plane(valid_pos, curr_pos.copy(), hit_poly, contact_pt):
            return TS.COLLIDED
        collisions.set_collision_normal(path.localspace_pos.localtoglobalvec(hit_poly.plane.N))
        path.add_offset_to_check_pos(_scaled_global(path, valid_pos.center - check_pos.center, scale))
        return TS.ADJUSTED

    def step_sphere_down(
        self, path: SpherePath, collisions: CollisionInfo, check_pos: Sphere, scale: float
    ) -> TransitionState:
        """Lower ``check_pos`` (tree space) by ``step_down_amt·walk_interp`` along ``localspace_z``
        onto the walkable faces it meets (``find_walkable``). If any: move ``check_pos`` by the
        scaled global offset, make the face the contact plane (``d`` times ``scale``, not
        water, in ``check_pos``'s cell) and the walkable, ADJUSTED; else OK.

        Stores (acclient.c:361214-361269): ``step·z.x`` and ``step·z.y`` are spilled to ``float``
        and ``1/scale`` too, but ``movement.x`` divides by the unspilled reciprocal; the
        offset rotates the unstored displacement with sums of its own (z, y, x terms in turn),
        each row stored, then multiplied by ``scale``.

        Retail: BSPTREE::step_sphere_down @ 0x0053A210 (acclient.c:361176)
        """
        step = -(path.step_down_amt * path.walk_interp)
        z = path.localspace_z
        inv = 1.0 / scale
        inv32 = f32(inv)
        sx, sy, _ = unpack3(pack3(step * z.x, step * z.y, 0.0))
        movement = Vector3(inv * sx, sy * inv32, step * z.z * inv32)
        valid_pos = check_pos.copy()
        poly = self.root_node.find_walkable(path, valid_pos, movement, z)
        if poly is None:
            return TS.OK
        end, start, m = valid_pos.center, check_pos.center, path.localspace_pos.frame.m
        dx, dy, dz = end.x - start.x, end.y - start.y, end.z - start.z
        rotated = Vector3(
            dz * m[6] + dy * m[3] + dx * m[0],
            dz * m[7] + dy * m[4] + dx * m[1],
            dz * m[8] + dy * m[5] + dx * m[2],
        )
        path.add_offset_to_check_pos(rotated * scale)
        contact = plane_localtoglobal(path.check_pos, path.localspace_pos, poly.plane)
        contact.d = f32(contact.d * scale)
        collisions.set_contact_plane(contact, False)
        collisions.contact_plane_cell_id = path.check_pos.objcell_id
        path.set_walkable(valid_pos, poly, z, path.localspace_pos, scale)
        return TS.ADJUSTED

    @staticmethod
    def step_sphere_up(transition: SphereTransition, collision_normal: Vector3) -> TransitionState:
        """Sphere 0 ran into a face while in contact: ``CTransition::step_up`` with the face's
        global normal; OK if the step succeeds, else ``step_up_slide``.

        Retail: BSPTREE::step_sphere_up @ 0x00539F20 (acclient.c:361071)
        """
        path = transition.sphere_path
        if transition.step_up(path.localspace_pos.frame.localtoglobalvec(collision_normal)):
            return TS.OK
        return path.step_up_slide(transition.object_info, transition.collision_info)

    @staticmethod
    def slide_sphere(
        path: SpherePath, collisions: CollisionInfo, collision_normal: Vector3
    ) -> TransitionState:
        """Slide along a face (tree-space normal ``collision_normal``). Retail slides sphere 0
        (``global_sphere[0]`` from ``global_curr_center[0]``) although only sphere 1 hit.

        Retail: BSPTREE::slide_sphere @ 0x00539E50 (acclient.c:361030)
        """
        normal = path.localspace_pos.frame.localtoglobalvec(collision_normal)
        return path.global_sphere[0].slide_sphere_normal(path, collisions, normal, path.global_curr_center[0])

    def check_walkable(self, path: SpherePath, check_pos: Sphere, scale: float) -> TransitionState:
        """COLLIDED if ``check_pos`` touches a face it could stand on (``hits_walkable`` with
        ``localspace_z``), else OK. ``scale`` is not read.

        Retail: BSPTREE::check_walkable @ 0x00539ED0 (acclient.c:361051)
        """
        if self.root_node.hits_walkable(path, check_pos.copy(), path.localspace_z):
            return TS.COLLIDED
        return TS.OK
