"""CSphere sweep routines against hand-built paths; expected values worked from the decompiled CSphere.c."""

from __future__ import annotations

import math

import pytest

from acphys.constants import EPSILON, FLOOR_Z, LANDING_Z
from acphys.flags import ObjectInfoState as OIS
from acphys.flags import TransitionState as TS
from acphys.geometry.plane import Plane, Ray
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo
from acphys.transition.transition import InsertType, SpherePath

CELL = 0xA9B40001


class Sweep:
    """The CTransition parts the sphere routines read; ``step_up`` (not ported yet) is scripted."""

    def __init__(self, path: SpherePath, state: OIS = OIS.DEFAULT, step_up_ok: bool = False) -> None:
        self.sphere_path = path
        self.collision_info = CollisionInfo()
        self.object_info = ObjectInfo(state=state, step_up_height=0.4)
        self.step_up_ok = step_up_ok
        self.step_up_normals: list[Vector3] = []

    def step_up(self, collision_normal: Vector3) -> bool:
        self.step_up_normals.append(collision_normal.copy())
        return self.step_up_ok


def make_path(curr: Vector3, check: Vector3, radius: float = 0.5, second: bool = False) -> SpherePath:
    """One sphere (two if ``second``) of ``radius`` centred ``radius`` above the origin (1 m higher)."""
    path = SpherePath()
    path.local_sphere = [Sphere(Vector3(0, 0, radius), radius)]
    if second:
        path.local_sphere.append(Sphere(Vector3(0, 0, radius + 1.0), radius))
    path.curr_pos = Position(CELL, Frame(origin=curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(CELL, Frame(origin=check)), None)
    path.walk_interp = 1.0
    return path


def close(a: Vector3, b: Vector3, tol: float = 1e-9) -> bool:
    return all(abs(p - q) <= tol for p, q in zip(a, b, strict=True))


class TestPrimitives:
    def test_intersects_strict(self) -> None:
        a = Sphere(Vector3(), 1.0)
        assert a.intersects(Sphere(Vector3(1.9, 0, 0), 1.0))
        assert not a.intersects(Sphere(Vector3(2.0, 0, 0), 1.0))  # dist² < (ra+rb)² (acclient.c:356354)

    def test_collides_with_sphere_touching_hits(self) -> None:
        # Lost compare read as |disp|² <= radsum² (acclient.c:358515); touching collides.
        assert Sphere.collides_with_sphere(Vector3(2.0, 0, 0), 2.0)
        assert not Sphere.collides_with_sphere(Vector3(2.0, 0, 0.001), 2.0)

    def test_find_time_of_collision(self) -> None:
        # a=16, b=12, c=8, D=16 -> (b-√D)/a = 0.5 (acclient.c:358500-358503); ACE returns -0.5.
        assert Sphere.find_time_of_collision(Vector3(4, 0, 0), Vector3(-3, 0, 0), 1.0) == 0.5
        # Moving away: b-√D = -16 < 0 -> (√D+b)/a = (4-12)/16 (acclient.c:358501).
        assert Sphere.find_time_of_collision(Vector3(-4, 0, 0), Vector3(-3, 0, 0), 1.0) == -0.5
        # Already within: c = |d|² - r² < EPSILON -> -1 (acclient.c:358493); 1.0001² - 1 is not.
        assert Sphere.find_time_of_collision(Vector3(4, 0, 0), Vector3(-1.0001, 0, 0), 1.0) > 0.0
        # Already inside to EPSILON, not moving, or missing: -1 (acclient.c:358493).
        assert Sphere.find_time_of_collision(Vector3(4, 0, 0), Vector3(-1.00005, 0, 0), 1.0) == -1.0
        assert Sphere.find_time_of_collision(Vector3(0.01, 0, 0), Vector3(-3, 0, 0), 1.0) == -1.0
        assert Sphere.find_time_of_collision(Vector3(4, 0, 0), Vector3(-3, 2, 0), 1.0) == -1.0

    def test_sphere_intersects_ray(self) -> None:
        s = Sphere(Vector3(), 1.0)
        assert s.sphere_intersects_ray(Ray(Vector3(-3, 0, 0), Vector3(1, 0, 0))) == 2.0  # (b-√D)/a (359041)
        # Grazing: D = 0 exactly, still a hit at t = b/a = 3 (acclient.c:359028 tests D < 0).
        assert s.sphere_intersects_ray(Ray(Vector3(-3, 1, 0), Vector3(1, 0, 0))) == 3.0
        # Start on the surface: c <= 0 is a miss (acclient.c:359028).
        assert s.sphere_intersects_ray(Ray(Vector3(-1, 0, 0), Vector3(1, 0, 0))) is None
        # Pointing away: b = -3 <= √D = 1 -> (√D+b)/a = -2, still reported (acclient.c:359035-359038).
        assert s.sphere_intersects_ray(Ray(Vector3(-3, 0, 0), Vector3(-1, 0, 0))) == -2.0


class TestPlacementAndCheckWalkable:
    def test_placement_has_epsilon_slack(self) -> None:
        # radsum = 1.5 - EPSILON; placement collides when radsum² >= dist² (acclient.c:359211-359215).
        path = make_path(Vector3(), Vector3())
        path.insert_type = InsertType.PLACEMENT
        sweep = Sweep(path)
        touching = Sphere(Vector3(1.5, 0, 0.5), 1.0)
        assert touching.intersects_sphere(sweep, False) == TS.OK
        within = Sphere(Vector3(1.5 - 2 * EPSILON, 0, 0.5), 1.0)
        assert within.intersects_sphere(sweep, False) == TS.COLLIDED

    def test_ethereal_obstruction_checks_second_sphere(self) -> None:
        path = make_path(Vector3(), Vector3(), second=True)
        path.obstruction_ethereal = True
        # Sphere 1 at z 1.5 overlaps an obstacle at z 2.6 (dist 1.1 < 1.4998); sphere 0 does not.
        assert Sphere(Vector3(0, 0, 2.6), 1.0).intersects_sphere(Sweep(path), True) == TS.COLLIDED  # 359221

    def test_check_walkable_reports_only(self) -> None:
        path = make_path(Vector3(), Vector3())
        path.check_walkable = True
        sweep = Sweep(path)
        assert Sphere(Vector3(1.0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.COLLIDED  # 359254
        assert not path.collide and not sweep.collision_info.collision_normal_valid


class TestStepDown:
    def test_step_down_onto_sphere_top(self) -> None:
        # Moving r .5 at z 1.4 over an r 1 sphere at the origin, stepping down 0.5 (acclient.c:358649-358705):
        # t = (√(1.5²) - 1.4)/0.5 = 0.2, interp 0.8, drop 0.1, normal (0,0,1), plane through (0,0,1).
        path = make_path(Vector3(0, 0, 0.9), Vector3(0, 0, 0.9))
        path.step_down = True
        path.step_down_amt = 0.5
        path.walkable_allowance = FLOOR_Z
        sweep = Sweep(path)
        assert Sphere(Vector3(), 1.0).intersects_sphere(sweep, False) == TS.ADJUSTED
        info = sweep.collision_info
        assert info.contact_plane_valid and info.contact_plane_is_water  # is_water passed as 1 (358695)
        assert close(info.contact_plane.N, Vector3(0, 0, 1), 1e-6)
        assert info.contact_plane.d == pytest.approx(-1.0, abs=1e-6)
        assert info.contact_plane_cell_id == CELL  # acclient.c:358696
        assert path.walk_interp == pytest.approx(0.8, abs=1e-6)  # acclient.c:358697
        assert path.check_pos.frame.origin.z == pytest.approx(1.0, abs=1e-6)  # +drop (358702)
        assert path.global_sphere[0].center.z == pytest.approx(1.5, abs=1e-6)

    def test_creature_does_not_step_down_on_spheres(self) -> None:
        path = make_path(Vector3(0, 0, 0.9), Vector3(0, 0, 0.9))
        path.step_down = True
        path.step_down_amt = 0.5
        assert Sphere(Vector3(), 1.0).intersects_sphere(Sweep(path), True) == TS.OK  # acclient.c:359384

    def test_nil_step_collides(self) -> None:
        path = make_path(Vector3(0, 0, 0.9), Vector3(0, 0, 0.9))
        path.step_down = True
        path.step_down_amt = 0.5
        path.walk_interp = 0.0
        assert Sphere(Vector3(), 1.0).intersects_sphere(Sweep(path), False) == TS.COLLIDED  # 358664

    def test_steep_rest_is_ok_without_contact(self) -> None:
        # Off to the side: normal z = (z+drop)/1.5 below FLOOR_Z -> OK, nothing set (acclient.c:358685).
        path = make_path(Vector3(1.2, 0, 0.2), Vector3(1.2, 0, 0.2))
        path.step_down = True
        path.step_down_amt = 0.5
        path.walkable_allowance = FLOOR_Z
        sweep = Sweep(path)
        # disp (1.2, 0, 0.7): t = (√(2.25-1.44) - 0.7)/0.5 = 0.4, normal z = 0.9/1.5 = 0.6 < 0.664.
        assert Sphere(Vector3(), 1.0).intersects_sphere(sweep, False) == TS.OK
        assert not sweep.collision_info.contact_plane_valid
        assert path.walk_interp == 1.0


class TestBeforeCollide:
    def test_contact_steps_up_with_unnormalised_normal(self) -> None:
        path = make_path(Vector3(-2.0, 0, 0), Vector3(-1.0, 0, 0))
        sweep = Sweep(path, OIS.CONTACT, step_up_ok=True)
        sweep.object_info.step_up_height = 2.0
        assert Sphere(Vector3(0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.OK  # acclient.c:359104
        assert close(sweep.step_up_normals[0], Vector3(-2.0, 0, 0))  # gcc[0] - centre (359096-359101)

    def test_failed_step_up_slides_on_step_up_normal(self) -> None:
        # step_up_slide with a zero step_up_normal moves halfway back to curr (acclient.c:358928-358939).
        path = make_path(Vector3(-2.0, 0, 0), Vector3(-1.0, 0, 0))
        sweep = Sweep(path, OIS.CONTACT | OIS.ON_WALKABLE, step_up_ok=False)
        sweep.object_info.step_up_height = 2.0
        assert Sphere(Vector3(0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(-1.5, 0, 0))
        assert not path.step_up and not sweep.collision_info.contact_plane_valid  # 313460-313463

    def test_too_high_slides_along_ground(self) -> None:
        # Step height 0.4 < 1.5 - 0: slide (acclient.c:359083). Normal (-1,0,0) x ground N = (0,1,0);
        # step (1.2,0.3,0) projects to (0,0.3,0); offset = (0,0.3,0) - step = (-1.2,0,0) (358767-358786).
        path = make_path(Vector3(0, 0, 0), Vector3(1.2, 0.3, 0))
        sweep = Sweep(path, OIS.CONTACT)
        sweep.collision_info.set_contact_plane(Plane.horizontal(0.0), False)
        assert Sphere(Vector3(2.0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.SLID
        assert close(path.check_pos.frame.origin, Vector3(0, 0.3, 0))
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0))

    def test_skid_head_on_uses_last_known_plane_and_disp(self) -> None:
        # No contact plane: last_known (zero normal here) -> direction 0, plane.N·disp = 0 >= 0, so the
        # step loses its part along the normal (acclient.c:358790-358803).
        path = make_path(Vector3(0, 0, 0), Vector3(1.2, 0.3, 0))
        sweep = Sweep(path, OIS.CONTACT)
        assert Sphere(Vector3(2.0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.SLID
        assert close(path.check_pos.frame.origin, Vector3(0, 0.3, 0))

    def test_airborne_lands(self) -> None:
        path = make_path(Vector3(0, 0, 2.0), Vector3(0, 0, 1.0))
        sweep = Sweep(path)
        assert Sphere(Vector3(0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.ADJUSTED  # 359133
        assert path.collide and path.walk_interp == 1.0  # set_collide (acclient.c:359058-359067)
        assert close(path.step_up_normal, Vector3(0, 0, 1))
        assert path.walkable_allowance == LANDING_Z  # acclient.c:359132
        assert close(path.backup_check_pos.frame.origin, Vector3(0, 0, 1.0))

    def test_path_clipped_without_perfect_clip_collides(self) -> None:
        path = make_path(Vector3(-3.0, 0, 0), Vector3(-1.0, 0, 0))
        sweep = Sweep(path, OIS.PATH_CLIPPED)
        assert Sphere(Vector3(0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.COLLIDED  # 358895
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0))
        assert close(path.check_pos.frame.origin, Vector3(-1.0, 0, 0))

    def test_perfect_clip_just_reaches(self) -> None:
        # old_disp (-3,0,0), movement (2,0,0), reach 1.5: t = (6-3)/4 = 0.75; offset = 0.75m - m = (-0.5,0,0)
        # (acclient.c:358843-358880). ACE adds (offset + check - centre) = (-1.5,0,0) instead.
        path = make_path(Vector3(-3.0, 0, 0), Vector3(-1.0, 0, 0))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert Sphere(Vector3(0, 0, 0.5), 1.0).intersects_sphere(sweep, False) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(-1.5, 0, 0), 1e-6)
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0), 1e-6)

    def test_second_sphere_slides_with_moving_sphere_as_this(self) -> None:
        # Sphere 1 (z 1.5) hits an obstacle at (2, 0, 1.5); slide_sphere runs on check_pos (359138-359151).
        path = make_path(Vector3(0, 0, 0), Vector3(1.2, 0.3, 0), second=True)
        sweep = Sweep(path, OIS.CONTACT)
        sweep.collision_info.set_contact_plane(Plane.horizontal(0.0), False)
        assert Sphere(Vector3(2.0, 0, 1.5), 1.0).intersects_sphere(sweep, False) == TS.SLID
        assert close(path.check_pos.frame.origin, Vector3(0, 0.3, 0))


class TestCollideRewind:
    def test_landing_rewind_sets_plane_at_unrewound_low_point(self) -> None:
        # disp (0,0,1.2), movement (0,0,0.8): a .64, b -.96, D 1.44 -> numerator .24, t .375, interp .625,
        # normal (0,0,1); the plane point is gs0 - r·n = (0,0,0.7), taken before the offset (359321-359375).
        path = make_path(Vector3(0, 0, 1.5), Vector3(0, 0, 0.7))
        path.collide = True
        path.walkable_allowance = LANDING_Z
        sweep = Sweep(path)
        assert Sphere(Vector3(), 1.0).intersects_sphere(sweep, False) == TS.ADJUSTED
        plane = sweep.collision_info.contact_plane
        assert close(plane.N, Vector3(0, 0, 1), 1e-6) and plane.d == pytest.approx(-0.7, abs=1e-6)
        assert path.walk_interp == pytest.approx(0.625, abs=1e-6)
        assert path.check_pos.frame.origin.z == pytest.approx(1.0, abs=1e-6)

    def test_numerator_above_one_quirk_collides(self) -> None:
        # Fall from 5: numerator √32.49 - 4.56 = 1.14 > 1 -> 2b - 1.14 = -10.26 (acclient.c:359346),
        # t -0.71, interp 1.71 >= walk_interp -> COLLIDED (359351, 359380). The true root 1.14/14.44 fits.
        path = make_path(Vector3(0, 0, 4.5), Vector3(0, 0, 0.7))
        path.collide = True
        sweep = Sweep(path)
        assert Sphere(Vector3(), 1.0).intersects_sphere(sweep, False) == TS.COLLIDED
        assert not sweep.collision_info.contact_plane_valid

    def test_creature_is_ok(self) -> None:
        path = make_path(Vector3(0, 0, 1.5), Vector3(0, 0, 0.7))
        path.collide = True
        assert Sphere(Vector3(), 1.0).intersects_sphere(Sweep(path), True) == TS.OK  # acclient.c:359321


class TestSlideSphereNormal:
    def test_facing_plane_normal_drops_normal_part(self) -> None:
        # n ∥ plane N and n·N >= 0: offset = -n (step·n) = (0,0,0.3) (acclient.c:358982-358996).
        path = make_path(Vector3(0, 0, 0.3), Vector3(1.0, 0, 0))
        info = CollisionInfo()
        info.set_contact_plane(Plane.horizontal(0.0), False)
        curr = path.global_curr_center[0]
        ts = path.global_sphere[0].slide_sphere_normal(path, info, Vector3(0, 0, 1), curr)
        assert ts == TS.SLID
        assert close(path.check_pos.frame.origin, Vector3(1.0, 0, 0.3))

    def test_facing_away_collides_and_rewrites_normal(self) -> None:
        # n·N < 0: collision normal becomes -step normalised and the result is COLLIDED
        # (acclient.c:358998-359006). ACE returns OK here.
        path = make_path(Vector3(0, 0, 0.3), Vector3(0.3, 0, 0))
        info = CollisionInfo()
        info.set_contact_plane(Plane.horizontal(0.0), False)
        normal = Vector3(0, 0, -1)
        ts = path.global_sphere[0].slide_sphere_normal(path, info, normal, path.global_curr_center[0])
        assert ts == TS.COLLIDED
        # float32: the step is (0.3f, 0, f32(0.5 - 0.8f)) = (0.3f, 0, -0.3f) (acclient.c:358944-358951),
        # reversed and normalised in place (normalize_check_small, acclient.c:359004).
        expected = Vector3(-f32(0.3), 0, f32(0.3))
        assert not expected.normalize_check_small()
        assert close(expected, Vector3(-0.3, 0, 0.3) * (1 / math.sqrt(0.18)), 1e-6)
        assert normal.exactly_equals(expected) and info.collision_normal.exactly_equals(expected)

    def test_tiny_projection_collides(self) -> None:
        # Step straight into the normal: projection on the tangent is 0 < EPSILON (acclient.c:358973).
        path = make_path(Vector3(0, 0, 0), Vector3(0.5, 0, 0))
        info = CollisionInfo()
        info.set_contact_plane(Plane.horizontal(0.0), False)
        curr = path.global_curr_center[0]
        ts = path.global_sphere[0].slide_sphere_normal(path, info, Vector3(-1, 0, 0), curr)
        assert ts == TS.COLLIDED
        assert close(path.check_pos.frame.origin, Vector3(0.5, 0, 0))


def test_intersects_sphere_placed_scales_into_check_block() -> None:
    # Local (0,0,1) r .5 at scale 2 on a frame at (10,0,0) in the next landblock east (+192 m in x):
    # centre (202, 0, 2), r 1 (acclient.c:359401-359411).
    path = make_path(Vector3(201.0, 0, 1.5), Vector3(201.0, 0, 1.5))
    path.insert_type = InsertType.PLACEMENT
    east = Position(0xAAB40001, Frame(origin=Vector3(10.0, 0, 0)))
    local = Sphere(Vector3(0, 0, 1.0), 0.5)
    assert local.intersects_sphere_placed(east, 2.0, Sweep(path), False) == TS.COLLIDED
    path = make_path(Vector3(200.5, 0, 1.5), Vector3(200.5, 0, 1.5))  # exactly 1.5 apart: radsum slack
    path.insert_type = InsertType.PLACEMENT
    assert local.intersects_sphere_placed(east, 2.0, Sweep(path), False) == TS.OK
