"""Float32 at rest in the geometry: planes, polygons, spheres, cylinders and BSP queries.

Retail stores every ``float`` as IEEE single and computes between stores at double precision
(:mod:`acphys.precision`). Each test below picks inputs where narrowing at retail's stores gives
another result than float64 throughout, derives the float32 value by hand with explicit ``f32``
calls at the stores the decompiled routine makes (lines cited), and asserts it exactly.

The acceptance case: a body climbing a box. ``CTransition::step_up`` steps down by the
``step_up_height`` from the candidate position without lowering it first, so the rise is at most
1.5 step-up heights: ``CPolygon::adjust_sphere_to_plane`` refuses an interp below -0.5. What is
``float`` there (acclient.c:359533-359590): the plane (``N``, ``d`` from ``make_plane``), the
sphere (centre, radius), the movement (a ``Vector3`` that ``BSPTREE::step_sphere_down`` builds
from the float ``step_down_amt`` = ``step_up_height``, the float ``walk_interp`` and the float
``localspace_z``), ``walk_interp``, and the new interp ``valid_posa``; the distance, ``N·movement``,
the gap and the time stay in registers. With the box top at 0.6f and the sphere resting on z = 0
the gap is exactly -0.6f, so the time is the register ratio 0.6f / 0.4f = 1.5000000373: the
interp -0.5000000373 (stored as -0.50000006) is below -0.5 and the step is refused. On float64
lengths 0.6 / 0.4 = 1.4999999999999998 and it would be accepted.
"""

from __future__ import annotations

import math

from acphys.constants import EPSILON, FLOOR_Z
from acphys.flags import ObjectInfoState as OIS
from acphys.flags import TransitionState as TS
from acphys.geometry.bbox import BBox
from acphys.geometry.bsp import (
    CELL_OUTSIDE,
    CELL_PARTIALLY_INSIDE,
    CELL_SPHERE_SLACK,
    BSPLeaf,
    BSPNode,
    BSPTree,
)
from acphys.geometry.bsp_builder import box_faces, build_box_tree, build_boxes_tree
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.plane import Plane, Ray
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32, is_f32
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo
from acphys.transition.transition import InsertType, SpherePath

CELL = 0xA9B40001
EAST_CELL = 0xAAB40001  # the landblock 192 m east of CELL's
UP = Vector3(0.0, 0.0, 1.0)
HUMAN_R = f32(0.48)  # the radius of the human setup's spheres, as a DAT holds it


class Sweep:
    """The ``CTransition`` parts the geometry routines read; ``step_up`` is scripted."""

    def __init__(self, path: SpherePath, state: OIS = OIS.DEFAULT, step_up_height: float = 0.4) -> None:
        self.sphere_path = path
        self.collision_info = CollisionInfo()
        self.object_info = ObjectInfo(state=state, step_up_height=step_up_height)

    def step_up(self, collision_normal: Vector3) -> bool:
        return False


def make_path(curr: Vector3, check: Vector3, radius: float = 0.5) -> SpherePath:
    """One sphere of ``radius`` centred ``radius`` above the origin, tree space = global space."""
    path = SpherePath()
    path.local_sphere = [Sphere(Vector3(0, 0, radius), radius)]
    path.curr_pos = Position(CELL, Frame(origin=curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(CELL, Frame(origin=check)), None)
    path.walk_interp = 1.0
    path.walkable_allowance = FLOOR_Z
    path.cache_localspace_sphere(Position(CELL, Frame()), 1.0)
    return path


def top_face(height: float) -> Polygon:
    """The top face of the box (-1,-1,0)-(1,1,height), as the BSP builder makes it."""
    return box_faces(Vector3(-1, -1, 0), Vector3(1, 1, height))[4]


class TestStepUpLimit:
    """The acceptance case at the polygon level and at the BSP step-down a step-up runs."""

    @staticmethod
    def climb(height: float, step_up: float) -> tuple[float | None, Sphere]:
        """``adjust_sphere_to_plane`` of a standing sphere (bottom on z = 0) against the top face of a
        ``height`` box, moving by the step-up's step-down ``(0, 0, -step_up)`` from walk_interp 1."""
        sphere = Sphere(Vector3(0.4, 0.0, HUMAN_R), HUMAN_R)
        # BSPTREE::step_sphere_down builds the movement -(step_down_amt · walk_interp) · z / scale
        # (acclient.c:361214-361237): with z = (0,0,1), scale 1 and walk_interp 1 it is -step_up.
        movement = Vector3(0.0, 0.0, -(f32(step_up) * 1.0))
        return top_face(height).adjust_sphere_to_plane(sphere, movement, 1.0), sphere

    def test_the_box_planes_are_what_make_plane_derives(self) -> None:
        # CPolygon::make_plane on the float32 vertices (acclient.c:359665-359716): a 2x2 face sums
        # the cross z 4 + 4 = 8, 1/sqrt(64) = 0.125 is exact, so N = (0, 0, 1) and d = -f32(h).
        for height in (0.6, 0.59, 0.3):
            plane = top_face(height).plane
            assert plane.N.exactly_equals(UP)
            assert plane.d == -f32(height)

    def test_one_and_a_half_step_ups_on_float32_lengths_is_refused(self) -> None:
        # acclient.c:359552-359575: dist = N.y·c.y + N.z·c.z + c.x·N.x + d = r - 0.6f (exact),
        # N·movement = -0.4f <= -EPSILON so gap = dist - r = -0.6f, t = -0.6f / -0.4f.
        t = f32(0.6) / f32(0.4)
        assert t == 1.5000000372529025
        interp = (1.0 - t) * 1.0
        assert interp == -0.5000000372529025
        # valid_posa = interp is a float local (acclient.c:359574), and the -0.5 bound reads it
        # (the register value is already below -0.5; the store keeps it there):
        assert f32(interp) == -0.5000000596046448 < -0.5
        interp_out, sphere = self.climb(0.6, 0.4)
        assert interp_out is None
        assert sphere.center.exactly_equals(Vector3(0.4, 0.0, HUMAN_R))  # untouched
        # On float64 lengths the same routine would accept: 1 - 0.6/0.4 = -0.4999999999999998.
        assert 1.0 - 0.6 / 0.4 == -0.4999999999999998
        assert not 1.0 - 0.6 / 0.4 < -0.5

    def test_fifty_metres_up_the_positions_decide_instead(self) -> None:
        # Not retail's data but a caution for scenarios: at z = 50 a float32 has an ulp of 3.8e-6,
        # 100 times the 3.7e-8 margin above. A human standing 0.005 above a floor at 50 (sphere z
        # 0.475, r 0.48) has its centre at f32(f32(50.005) + 0.475f) = 50.47999954 and a 0.6 box
        # top at f32(50.6) = 50.59999847: the gap is -0.59999892, t = 1.4999973, and the step is
        # climbed (acclient.c:359575).
        center_z = f32(f32(50.005) + f32(0.475))
        top = box_faces(Vector3(-1, -1, 50.0), Vector3(1, 1, 50.6))[4]
        assert top.plane.d == -f32(50.6)
        sphere = Sphere(Vector3(0.4, 0.0, center_z), HUMAN_R)
        gap = (center_z - f32(50.6)) - HUMAN_R
        t = gap / -f32(0.4)
        assert t == 1.4999972805381225
        assert top.adjust_sphere_to_plane(sphere, Vector3(0.0, 0.0, -f32(0.4)), 1.0) == f32(1.0 - t)

    def test_a_0_3_box_with_step_up_0_2_is_refused_too(self) -> None:
        # 0.3f / 0.2f = 1.5000000373 as well: interp stored -0.50000006 < -0.5 (acclient.c:359575).
        assert f32(1.0 - f32(0.3) / f32(0.2)) == -0.5000000596046448
        assert self.climb(0.3, 0.2)[0] is None
        assert not 1.0 - 0.3 / 0.2 < -0.5  # float64 would climb it

    def test_a_0_59_box_is_climbed(self) -> None:
        # t = 0.59f / 0.4f = 1.47499991; interp stored f32(1 - t) (acclient.c:359574, 359586); the
        # centre moves back by t·movement, the z term a float spill (acclient.c:359582-359585).
        t = f32(0.59) / f32(0.4)
        interp_out, sphere = self.climb(0.59, 0.4)
        assert interp_out == f32(1.0 - t) == -0.47499990463256836
        expected_z = f32(HUMAN_R - f32(t * -f32(0.4)))
        assert sphere.center.exactly_equals(Vector3(0.4, 0.0, expected_z))
        assert expected_z == 1.0699999332427979  # the bottom on the top face: 0.48 + 0.59

    @staticmethod
    def step_up_step_down(height: float, step_up: float) -> tuple[TS, SpherePath, Sweep]:
        """``BSPTREE::find_collisions`` in the step-down of a step-up (``step_down`` set, check_pos not
        lowered, ``step_down_amt`` = the step-up height, walk_interp 1) for a human sphere that
        has walked into a ``height`` box standing on z = 0."""
        tree = build_box_tree(Vector3(0, -1, 0), Vector3(2, 1, height))
        path = make_path(Vector3(-0.5, 0, 0), Vector3(0.3, 0, 0), radius=HUMAN_R)
        path.step_up = True
        path.step_down = True
        path.step_down_amt = f32(step_up)  # SPHEREPATH::step_down_amt is a float
        path.walk_interp = 1.0
        sweep = Sweep(path, OIS.CONTACT | OIS.ON_WALKABLE, step_up_height=step_up)
        return tree.find_collisions(sweep, 1.0), path, sweep

    def test_the_step_down_of_a_step_up_refuses_a_0_6_box(self) -> None:
        # BSPTREE::step_sphere_down (acclient.c:361176) -> find_walkable -> the top face refuses
        # (acclient.c:359575): no walkable polygon, OK, nothing moved.
        ts, path, sweep = self.step_up_step_down(0.6, 0.4)
        assert ts == TS.OK
        assert path.walk_interp == 1.0
        assert path.check_pos.frame.origin.exactly_equals(Vector3(0.3, 0, 0))
        assert not sweep.collision_info.contact_plane_valid

    def test_the_step_down_of_a_step_up_climbs_a_0_59_box(self) -> None:
        ts, path, sweep = self.step_up_step_down(0.59, 0.4)
        assert ts == TS.ADJUSTED
        t = f32(0.59) / f32(0.4)
        assert path.walk_interp == f32(1.0 - t)
        # The offset: the unstored centre displacement rotated (identity) and stored, times scale 1
        # (acclient.c:361247-361269), added to the origin (a float store).
        center_z = f32(HUMAN_R - f32(t * -f32(0.4)))
        assert path.check_pos.frame.origin.exactly_equals(Vector3(0.3, 0, f32(0.0 + f32(center_z - HUMAN_R))))
        plane = sweep.collision_info.contact_plane
        assert plane.N.exactly_equals(UP) and plane.d == -f32(0.59)

    def test_a_0_3_box_with_step_up_0_2_blocks_at_the_bsp(self) -> None:
        assert self.step_up_step_down(0.3, 0.2)[0] == TS.OK


class TestPolygonStores:
    #: A triangle whose normal's y differs by where the reciprocal length is spilled.
    TRI = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.5), (0.0, 1.0, 0.46))

    def test_make_plane_scales_x_by_the_register_and_y_z_by_the_float_reciprocal(self) -> None:
        # acclient.c:359665-359716 with v0 = 0: a = v1 (x, y spilled), b = v2 (registers); the
        # cross x, y are float spills, their z the float local normal_8.
        poly = Polygon([Vector3(*v) for v in self.TRI])
        az, bz = 0.5, f32(0.46)
        cx = f32(0.0 * bz - az * 1.0)
        cy = f32(az * 0.0 - bz * 1.0)
        cz = f32(1.0 * 1.0 - 0.0 * 0.0 + 0.0)
        inv = 1.0 / math.sqrt(cz * cz + cy * cy + cx * cx)
        inv32 = f32(inv)
        normal = Vector3(inv * cx, inv32 * cy, inv32 * cz)
        assert poly.plane.N.exactly_equals(normal)
        assert normal.y != f32(inv * cy)  # a register reciprocal would give -0.38049027
        total = 0.0
        for v in poly.vertices:
            total = total + normal.z * v.z + normal.y * v.y + normal.x * v.x
        assert poly.plane.d == f32(-(total / 3))
        assert is_f32(poly.plane.d) and all(is_f32(c) for c in poly.plane.N)

    def test_the_contact_point_z_subtracts_the_spilled_dist_times_n_z(self) -> None:
        # acclient.c:359961-359968: v10 = dist·N.z is a float spill, the contact x and y are not.
        poly = Polygon([Vector3(*v) for v in self.TRI])
        n, d = poly.plane.N, poly.plane.d
        sphere = Sphere(Vector3(0.13, 0.35, 0.49), 0.5)
        c = sphere.center
        dist = n.y * c.y + n.z * c.z + c.x * n.x + d
        contact = Vector3(7.0, 7.0, 7.0)
        poly.polygon_hits_sphere(sphere, contact)
        expected = Vector3(c.x - dist * n.x, c.y - dist * n.y, c.z - f32(dist * n.z))
        assert contact.exactly_equals(expected)
        assert expected.z != f32(c.z - dist * n.z)

    def test_adjust_sphere_to_plane_spills_the_y_and_z_steps_only(self) -> None:
        # acclient.c:359581-359585: v14 = t·m.y and v15 = t·m.z are float spills; x is not.
        poly = Polygon([Vector3(*v) for v in self.TRI])
        n, d = poly.plane.N, poly.plane.d
        sphere = Sphere(Vector3(0.11, 0.27, 0.28), 0.5)
        m = Vector3(-0.18, 0.05, -0.46)
        c = sphere.center.copy()
        dist = n.y * c.y + n.z * c.z + c.x * n.x + d
        along = n.z * m.z + n.y * m.y + n.x * m.x
        t = (dist - sphere.radius) / along
        interp = poly.adjust_sphere_to_plane(sphere, m, 1.0)
        assert interp == f32((1.0 - t) * 1.0)
        expected = Vector3(c.x - t * m.x, c.y - f32(t * m.y), c.z - f32(t * m.z))
        assert sphere.center.exactly_equals(expected)
        assert not expected.exactly_equals(Vector3(c.x - t * m.x, c.y - t * m.y, c.z - t * m.z))
        assert expected.x != f32(c.x - f32(t * m.x))

    def test_radsq_and_the_radius_are_floats(self) -> None:
        # CSphere::radius is a float: 0.5 + EPSILON is stored as 0.50019997, and rad = r - EPSILON
        # (acclient.c:360053) is 0.49999997, short of a face 0.5 away (acclient.c:360054).
        sphere = Sphere(Vector3(0.5, 0.5, 0.5), 0.5 + EPSILON)
        assert sphere.radius == f32(0.5 + EPSILON) == 0.5001999735832214
        square = Polygon([Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(0, 1, 0)])
        assert not square.hits_sphere(sphere)
        assert 0.5 + EPSILON - EPSILON >= 0.5  # a float64 radius would reach


class TestSphereStores:
    def test_the_radius_sum_is_a_float(self) -> None:
        # CSphere::intersects_sphere stores radsum = r + r' - EPSILON as a float (acclient.c:359211):
        # f32(1.4998000000050524) = 1.4997999668. A placement at |disp|² = 2.24939995, between
        # the float and the double radsum squared, is clear (acclient.c:359214).
        radsum = f32(1.0 + 0.5 - EPSILON)
        assert radsum == 1.4997999668121338
        a, b = 1.0142805576324463, 1.1048234701156616
        assert radsum * radsum < b * b + a * a <= (1.0 + 0.5 - EPSILON) ** 2
        path = make_path(Vector3(a, b, 0), Vector3(a, b, 0))
        path.insert_type = InsertType.PLACEMENT
        assert Sphere(Vector3(0, 0, 0.5), 1.0).intersects_sphere(Sweep(path), False) == TS.OK

    def test_step_sphere_down_keeps_its_squares_step_reach_and_drop_in_floats(self) -> None:
        # CSphere::step_sphere_down (acclient.c:358647-358703): disp.x², disp.y², the step, reach
        # and the drop are float locals; interp is double until stored into walk_interp.
        path = make_path(Vector3(0, 0, 0.89), Vector3(0, 0, 0.89))
        path.step_down = True
        path.step_down_amt = f32(0.5)
        sweep = Sweep(path)
        obstacle = Sphere(Vector3(-0.21, -0.26, 0.0), 1.0)
        disp = path.global_sphere[0].center - obstacle.center
        origin_z = path.check_pos.frame.origin.z
        assert obstacle.intersects_sphere(sweep, False) == TS.ADJUSTED
        radsum = f32(1.0 + 0.5 - EPSILON)
        hx, hy = f32(disp.x * disp.x), f32(disp.y * disp.y)
        step = f32(0.5 * 1.0)
        reach_reg = radsum + EPSILON
        reach = f32(reach_reg)
        t = (math.sqrt(reach_reg * reach - (hx + hy)) - disp.z) / step
        assert path.walk_interp == f32((1.0 - t) * 1.0) == 0.8554145693778992
        float64 = 1.0 - (math.sqrt(1.5 * 1.5 - (disp.x**2 + disp.y**2)) - disp.z) / 0.5
        assert f32(float64) != path.walk_interp
        drop = f32(step * t)
        assert path.check_pos.frame.origin.z == f32(origin_z + drop)
        inv = 1.0 / reach
        normal = Vector3(inv * disp.x, inv * disp.y, (drop + disp.z) * inv)
        assert sweep.collision_info.contact_plane.N.exactly_equals(normal)

    def test_collide_with_point_spills_the_y_and_z_time_products_only(self) -> None:
        # CSphere::collide_with_point (acclient.c:358839-358880): reach is a float; the movement is
        # three floats; offset.x = m.x·t - m.x in registers, offset.y = f32(m.y·t) - m.y.
        path = make_path(Vector3(-3.0, -0.155, 0), Vector3(-1.24, -0.31, 0))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        obstacle = Sphere(Vector3(0, 0, 0.5), 1.0)
        curr, check = path.global_curr_center[0].copy(), path.global_sphere[0].center.copy()
        origin = path.check_pos.frame.origin.copy()
        assert obstacle.intersects_sphere(sweep, False) == TS.ADJUSTED
        m = Vector3(check.x - curr.x, check.y - curr.y, check.z - curr.z)
        reach = f32(f32(1.0 + 0.5 - EPSILON) + EPSILON)
        d = curr - obstacle.center
        a = m.x * m.x + m.y * m.y + m.z * m.z
        b = -(d.z * m.z + d.y * m.y + m.x * d.x)
        c = d.x * d.x + d.y * d.y + d.z * d.z - reach * reach
        root = math.sqrt(b * b - c * a)
        t = (b - root) / a
        ox, oy = f32(m.x * t - m.x), f32(f32(m.y * t) - m.y)
        assert (ox, oy) != (f32(f32(m.x * t) - m.x), f32(m.y * t - m.y))
        assert path.check_pos.frame.origin.exactly_equals(Vector3(origin.x + ox, origin.y + oy, origin.z))


class TestCylSphereStores:
    def test_the_rewind_onto_the_top_scales_the_movement_by_the_spilled_time(self) -> None:
        # CCylSphere::intersects_sphere, collide arm (acclient.c:362206-362232): the time is spilled
        # to float (v16) before it scales the movement; the interp reads the double time.
        path = SpherePath()
        path.local_sphere = [Sphere(Vector3(0, 0, 0.5), 0.5)]
        path.curr_pos = Position(CELL, Frame(origin=Vector3(0.44, 0, 2.6)))
        path.cache_global_curr_center()
        path.set_check_pos(Position(CELL, Frame(origin=Vector3(0.03, 0, 1.65))), None)
        path.walk_interp = 1.0
        path.collide = True
        moving = path.global_sphere[0].center.copy()
        movement = path.global_curr_center[0] - moving
        origin = path.check_pos.frame.origin.copy()
        assert CylSphere(Vector3(), 1.0, 2.0).intersects_sphere(Sweep(path)) == TS.ADJUSTED
        t = (2.0 + 0.5 - moving.z) / movement.z
        offset = movement * f32(t)
        assert path.check_pos.frame.origin.exactly_equals(origin + offset)
        assert f32(origin.x + f32(movement.x * t)) != path.check_pos.frame.origin.x  # unspilled time
        assert path.walk_interp == f32((1.0 - t) * 1.0)

    def test_radius_and_height_are_floats(self) -> None:
        cyl = CylSphere(Vector3(0.1, 0.2, 0.3), 0.35, 1.7)
        assert (cyl.radius, cyl.height) == (f32(0.35), f32(1.7))
        assert all(is_f32(c) for c in cyl.low_pt)


class TestBspStores:
    def test_the_cell_slack_is_a_float_read_from_the_register_at_the_first_node(self) -> None:
        # BSPNODE::sphere_intersects_cell_bsp (acclient.c:362989-363013): r + 0.01f is tested from
        # the register at the first node and from the float local curr_spherea further on.
        slack = 1.0 + CELL_SPHERE_SLACK
        stored = f32(slack)
        assert stored < slack  # 1.0099999905 < 1.0099999998
        sphere = Sphere(Vector3(-stored, 0, 0), 1.0)  # dist -1.0099999905 on the plane x = 0
        first = BSPTree(BSPNode(Plane(Vector3(1, 0, 0), 0.0)))
        assert first.sphere_intersects_cell_bsp(sphere) == CELL_PARTIALLY_INSIDE  # -1.0099999905 > -slack
        behind = BSPNode(Plane(Vector3(1, 0, 0), 0.0))
        second = BSPTree(BSPNode(Plane(Vector3(1, 0, 0), 100.0), pos_node=behind))
        assert second.sphere_intersects_cell_bsp(sphere) == CELL_OUTSIDE  # <= -stored

    def test_position_localtoglobal_spills_before_the_block_shift(self) -> None:
        # Position::localtoglobal (acclient.c:147150-147160): the global point is a float spill,
        # then the block offset (192 m) is added and stored.
        frm = Position(EAST_CELL, Frame.from_heading(Vector3(2.394, 1.0, 0.0), 30.0))
        to = Position(CELL, Frame())
        v = Vector3(1.463, 0.709, 0.5)
        m, o = frm.frame.m, frm.frame.origin
        gx = m[3] * v.y + m[0] * v.x + m[6] * v.z + o.x
        got = to.localtoglobal(frm, v)
        assert got.x == f32(192.0 + f32(gx)) == 196.0155029296875
        assert got.x != f32(192.0 + gx)
        # BBox::LocalToGlobal takes every corner through it (acclient.c:476912): a point box.
        box = BBox.local_to_global(BBox(v, v), frm, to)
        assert box.min.exactly_equals(got) and box.max.exactly_equals(got)

    def test_the_builder_rounds_node_radii_up_to_hold_their_vertices(self) -> None:
        tree = build_boxes_tree([(Vector3(0.1, 0.2, 0.3), Vector3(1.7, 2.9, 1.3))])
        nodes = [tree.root_node]
        while nodes:
            node = nodes.pop()
            assert is_f32(node.sphere.radius) and all(is_f32(c) for c in node.sphere.center)
            if isinstance(node, BSPLeaf):
                for poly in node.polys:
                    for v in poly.vertices:
                        c = node.sphere.center
                        reach = ((v.x - c.x) ** 2 + (v.y - c.y) ** 2 + (v.z - c.z) ** 2) ** 0.5
                        assert reach <= node.sphere.radius
            else:
                assert node.pos_node is not None and node.neg_node is not None
                nodes += [node.pos_node, node.neg_node]


class TestPlaneStores:
    def test_set_height_and_snap_to_plane_store_floats(self) -> None:
        s = math.sqrt(0.5)
        plane = Plane(Vector3(-s, 0.0, s), -0.3)
        assert plane.d == f32(-0.3) and is_f32(plane.N.x)
        vc = Vector3(3.1, 4.2, 0.0)
        plane.set_height(vc)  # acclient.c:351348 stores vc->z
        n = plane.N
        assert vc.z == f32(-((vc.y * n.y + vc.x * n.x + plane.d) / n.z))
        assert vc.z != -((vc.y * n.y + vc.x * n.x + plane.d) / n.z)
        offset = Vector3(0.7, 0.2, 9.0)
        plane.snap_to_plane(offset)  # acclient.c:311532 stores offset->z
        inv = 1.0 / n.z
        assert offset.z == f32(-(0.2 * 0 + offset.x * n.x + n.z * 0.0 + plane.d) * inv - inv * -plane.d)

    def test_ray_length_is_a_float(self) -> None:
        assert Ray(Vector3(), UP, 0.3).length == f32(0.3)


def test_geometry_fields_are_float32_after_real_use() -> None:
    """A box tree, a step-up step-down onto it and a landing on a cylinder leave only float32
    values in the geometry and in what the geometry stored into the path and the collision info."""
    ts, path, sweep = TestStepUpLimit.step_up_step_down(0.59, 0.4)
    assert ts == TS.ADJUSTED
    tree = build_box_tree(Vector3(0, -1, 0), Vector3(2, 1, 0.59))
    nodes: list[BSPNode] = [tree.root_node]
    while nodes:
        node = nodes.pop()
        assert is_f32(node.splitting_plane.d) and all(is_f32(c) for c in node.splitting_plane.N)
        assert is_f32(node.sphere.radius) and all(is_f32(c) for c in node.sphere.center)
        for poly in node.polys:
            assert isinstance(poly, Polygon)
            assert is_f32(poly.plane.d) and all(is_f32(c) for c in poly.plane.N)
            assert all(is_f32(c) for v in poly.vertices for c in v)
        if node.pos_node is not None:
            nodes.append(node.pos_node)
        if node.neg_node is not None:
            nodes.append(node.neg_node)
    plane = sweep.collision_info.contact_plane
    assert is_f32(plane.d) and all(is_f32(c) for c in plane.N)
    assert is_f32(path.walk_interp)
    assert all(is_f32(c) for c in path.check_pos.frame.origin)

    land = SpherePath()
    land.local_sphere = [Sphere(Vector3(0, 0, 0.5), 0.5)]
    land.curr_pos = Position(CELL, Frame(origin=Vector3(0.44, 0, 2.6)))
    land.cache_global_curr_center()
    land.set_check_pos(Position(CELL, Frame(origin=Vector3(0.03, 0, 1.65))), None)
    land.walk_interp = 1.0
    land.collide = True
    landing = Sweep(land)
    assert CylSphere(Vector3(), 1.0, 2.0).intersects_sphere(landing) == TS.ADJUSTED
    cp = landing.collision_info.contact_plane
    assert is_f32(cp.d) and all(is_f32(c) for c in cp.N)
    assert is_f32(land.walk_interp) and all(is_f32(c) for c in land.check_pos.frame.origin)
