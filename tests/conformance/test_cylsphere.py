"""CCylSphere sweep routines against hand-built paths; expected values worked from CCylSphere.c.

Unless a test says otherwise the obstacle is a cylinder of radius 1 and height 2 standing on the
origin, the mover a sphere of radius 0.5 whose centre is 0.5 above its position (a second one 1 m
higher), so ``radsum`` = 1.4998 and ``reach`` = radsum + EPSILON = 1.5. Both are ``float`` in
retail: ``radsum`` is float32 1.49979997 and ``reach`` comes back to exactly 1.5.

Positions and centres are float32 (``f32(1.9) + 0.5`` is stored as 2.4000001, a tie rounded to
even), so where a result depends on them the expected value is derived with explicit ``f32``
steps at the stores the routine makes.
"""

from __future__ import annotations

import pytest

from acphys.constants import EPSILON, LANDING_Z
from acphys.flags import ObjectInfoState as OIS
from acphys.flags import TransitionState as TS
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo
from acphys.transition.transition import InsertType, SpherePath

CELL = 0xA9B40001
EAST_CELL = 0xAAB40001  # the landblock 192 m east of CELL's
#: ``radsum`` as CCylSphere::intersects_sphere passes it: a ``float`` (acclient.c:362080).
RADSUM = f32(1.0 - EPSILON + 0.5)


class Sweep:
    """The CTransition parts the cylinder routines read; ``step_up`` (not ported yet) is scripted."""

    def __init__(self, path: SpherePath, state: OIS = OIS.DEFAULT, step_up_ok: bool = False) -> None:
        self.sphere_path = path
        self.collision_info = CollisionInfo()
        self.object_info = ObjectInfo(state=state, step_up_height=0.4)
        self.step_up_ok = step_up_ok
        self.step_up_normals: list[Vector3] = []

    def step_up(self, collision_normal: Vector3) -> bool:
        self.step_up_normals.append(collision_normal.copy())
        return self.step_up_ok


def make_path(curr: Vector3, check: Vector3, second: bool = False) -> SpherePath:
    path = SpherePath()
    path.local_sphere = [Sphere(Vector3(0, 0, 0.5), 0.5)]
    if second:
        path.local_sphere.append(Sphere(Vector3(0, 0, 1.5), 0.5))
    path.curr_pos = Position(CELL, Frame(origin=curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(CELL, Frame(origin=check)), None)
    path.walk_interp = 1.0
    return path


def cyl(low_z: float = 0.0, height: float = 2.0) -> CylSphere:
    return CylSphere(Vector3(0, 0, low_z), 1.0, height)


def close(a: Vector3, b: Vector3, tol: float = 1e-9) -> bool:
    return all(abs(p - q) <= tol for p, q in zip(a, b, strict=True))


def origin(path: SpherePath) -> Vector3:
    return path.check_pos.frame.origin


class TestCollidesWithSphere:
    ball = Sphere(Vector3(), 0.5)

    def test_exactly_touching_the_side_hits(self) -> None:
        # radsum² >= dx² + dy² (acclient.c:361504): equality collides.
        assert cyl().collides_with_sphere(self.ball, Vector3(RADSUM, 0, 1.0), RADSUM)
        assert not cyl().collides_with_sphere(self.ball, Vector3(RADSUM + 1e-6, 0, 1.0), RADSUM)

    def test_resting_exactly_on_the_top_cap_misses(self) -> None:
        # r - EPSILON + h/2 >= |h/2 - disp.z| (acclient.c:361505): centre 2.5 (bottom on the cap) is out,
        # the sphere must sink EPSILON into the cap to count.
        assert not cyl().collides_with_sphere(self.ball, Vector3(0, 0, 2.5), RADSUM)
        assert cyl().collides_with_sphere(self.ball, Vector3(0, 0, 1.0 + (0.5 - EPSILON + 1.0)), RADSUM)
        # Same slack under the bottom cap.
        assert not cyl().collides_with_sphere(self.ball, Vector3(0, 0, -0.5), RADSUM)
        assert cyl().collides_with_sphere(self.ball, Vector3(0, 0, -0.5 + 2 * EPSILON), RADSUM)

    def test_corner_is_a_box_not_a_rounded_edge(self) -> None:
        # Both tests pass independently, so the sphere "hits" the corner region diagonally beyond
        # the rim (acclient.c:361504-361505): centre 1.4 out and 0.45 above the top.
        assert cyl().collides_with_sphere(self.ball, Vector3(1.4, 0, 2.45), RADSUM)


class TestNormalOfCollision:
    def test_from_outside_side_is_horizontal_and_definite(self) -> None:
        path = make_path(Vector3(2, 0, 0), Vector3(1.2, 0, 0))
        ball = path.global_sphere[0]
        definite, normal = cyl().normal_of_collision(path, ball, Vector3(1.2, 0, 0.5), RADSUM, 0)
        assert definite  # vertical overlap at the old centre (acclient.c:361680)
        assert close(normal, Vector3(2, 0, 0))  # old disp with z zeroed, not normalised (361673-361679)

    def test_from_outside_above_moving_down_is_indefinite(self) -> None:
        path = make_path(Vector3(2, 0, 3), Vector3(1.2, 0, 0.5))
        ball = path.global_sphere[0]
        definite, normal = cyl().normal_of_collision(path, ball, Vector3(1.2, 0, 1.0), RADSUM, 0)
        assert not definite and close(normal, Vector3(2, 0, 0))  # acclient.c:361680-361683
        # Not moving vertically (|3.5 - 3.5| <= EPSILON) makes it definite again (acclient.c:361681).
        definite, _ = cyl().normal_of_collision(path, ball, Vector3(1.2, 0, 3.5), RADSUM, 0)
        assert definite

    def test_from_above_or_below_is_a_cap_normal(self) -> None:
        path = make_path(Vector3(0.5, 0, 3), Vector3(0.5, 0, 1.8))
        ball = path.global_sphere[0]
        # disp.z - old.z <= 0 -> up (acclient.c:361689-361694); level counts as down.
        up, down = (True, Vector3(0, 0, 1)), (True, Vector3(0, 0, -1))
        assert cyl().normal_of_collision(path, ball, Vector3(0.5, 0, 2.3), RADSUM, 0) == up
        assert cyl().normal_of_collision(path, ball, Vector3(0.5, 0, 3.5), RADSUM, 0) == up
        # Moving up -> down-facing normal (acclient.c:361696-361699).
        assert cyl().normal_of_collision(path, ball, Vector3(0.5, 0, 3.6), RADSUM, 0) == down


class TestPlacementAndCheckWalkable:
    def test_placement_reports_overlap_only(self) -> None:
        path = make_path(Vector3(), Vector3(1.4, 0, 0))
        path.insert_type = InsertType.PLACEMENT
        sweep = Sweep(path)
        assert cyl().intersects_sphere(sweep) == TS.COLLIDED  # acclient.c:362086-362087
        assert close(origin(path), Vector3(1.4, 0, 0)) and not sweep.collision_info.collision_normal_valid
        path.set_check_pos(Position(CELL, Frame(origin=Vector3(1.5, 0, 0))), None)
        assert cyl().intersects_sphere(sweep) == TS.OK  # 1.5² > radsum² (acclient.c:362240)

    def test_ethereal_obstruction_checks_second_sphere(self) -> None:
        # Sphere 0 (centre z 0.5) is under a cylinder starting at 1.2; sphere 1 (z 1.5) is in it.
        path = make_path(Vector3(), Vector3(), second=True)
        path.obstruction_ethereal = True
        assert cyl(low_z=1.2).intersects_sphere(Sweep(path)) == TS.COLLIDED  # acclient.c:362088-362106
        assert cyl(low_z=2.1).intersects_sphere(Sweep(path)) == TS.OK

    def test_check_walkable_checks_both_spheres(self) -> None:
        path = make_path(Vector3(), Vector3(), second=True)
        path.check_walkable = True
        assert cyl(low_z=1.2).intersects_sphere(Sweep(path)) == TS.COLLIDED  # acclient.c:362118-362125
        assert cyl(low_z=2.1).intersects_sphere(Sweep(path)) == TS.OK  # acclient.c:362106


class TestStepDown:
    def test_stepping_down_onto_the_top(self) -> None:
        # Centre 2.4 (0.1 into the top), step 0.5: rise = 2 + 0.5 - 2.4 = 0.1, interp = (1 - 0.2)·1
        # (acclient.c:361604-361610); plane z = 2 through the raised bottom (361619-361627).
        path = make_path(Vector3(0.5, 0, 1.9), Vector3(0.5, 0, 1.9))
        path.step_down = True
        path.step_down_amt = 0.5
        sweep = Sweep(path, OIS.CONTACT)
        assert cyl().intersects_sphere(sweep) == TS.ADJUSTED  # acclient.c:361636
        info = sweep.collision_info
        assert info.contact_plane_valid and info.contact_plane_is_water  # is_water passed as 1 (361627)
        assert close(info.contact_plane.N, Vector3(0, 0, 1))
        assert info.contact_plane.d == pytest.approx(-2.0, abs=1e-9)
        assert info.contact_plane_cell_id == CELL  # acclient.c:361629; ACE leaves the cell id alone
        # float32: the centre is f32(1.9f + 0.5) = 2.4000001, so the rise is 0.0999999 and the
        # interp (1 - rise/0.5), stored into the float walk_interp (acclient.c:361630), 0.8000002.
        center_z = f32(f32(1.9) + 0.5)
        assert path.walk_interp == f32((1.0 - (2.0 + 0.5 - center_z) / 0.5) * 1.0) == 0.8000001907348633
        assert origin(path).z == pytest.approx(2.0, abs=1e-6)  # +rise (acclient.c:361635), float32

    def test_resting_on_the_top_is_ok(self) -> None:
        path = make_path(Vector3(0.5, 0, 2.0), Vector3(0.5, 0, 2.0))
        path.step_down = True
        path.step_down_amt = 0.5
        sweep = Sweep(path)
        assert cyl().intersects_sphere(sweep) == TS.OK  # acclient.c:361646
        assert not sweep.collision_info.contact_plane_valid

    def test_nil_step_and_too_deep_collide(self) -> None:
        path = make_path(Vector3(0.5, 0, 1.9), Vector3(0.5, 0, 1.9))
        path.step_down = True
        path.step_down_amt = 0.0
        assert cyl().intersects_sphere(Sweep(path)) == TS.COLLIDED  # |step| < EPSILON (acclient.c:361605)
        # Centre 1.8: rise 0.7, interp = 1 - 1.4 = -0.4 < -0.1 (acclient.c:361610-361612).
        path = make_path(Vector3(0.5, 0, 1.3), Vector3(0.5, 0, 1.3))
        path.step_down = True
        path.step_down_amt = 0.5
        assert cyl().intersects_sphere(Sweep(path)) == TS.COLLIDED
        assert origin(path).z == f32(1.3)  # untouched

    def test_second_sphere_alone_uses_sphere_zero_rise(self) -> None:
        # Only sphere 1 reaches a cylinder from 1.9 (acclient.c:361595-361602); the rise is still
        # sphere 0's, 2 + 0.5 + 1.4 = 3.9, so interp = 1 - 7.8 is out of range: COLLIDED.
        path = make_path(Vector3(), Vector3(), second=True)
        path.step_down = True
        path.step_down_amt = 0.5
        assert cyl(low_z=1.9).intersects_sphere(Sweep(path)) == TS.COLLIDED
        path.local_sphere.pop()
        path.cache_global_sphere(None)
        assert cyl(low_z=1.9).intersects_sphere(Sweep(path)) == TS.OK


class TestContact:
    def test_low_cylinder_steps_up_with_side_normal(self) -> None:
        # Height 0.3: rise 0.5 + 0.3 - 0.5 = 0.3 <= step_up_height 0.4 (acclient.c:361983); normal from
        # the old centre (2,0,.5) is (2,0,0), normalised (361997-361998), through localspace_pos (identity).
        path = make_path(Vector3(2, 0, 0), Vector3(1.2, 0, 0))
        sweep = Sweep(path, OIS.CONTACT, step_up_ok=True)
        assert cyl(height=0.3).intersects_sphere(sweep) == TS.OK  # acclient.c:362005-362006
        assert close(sweep.step_up_normals[0], Vector3(1, 0, 0))

    def test_step_up_normal_is_rotated_by_localspace_pos(self) -> None:
        # The normal is already global, yet retail rotates it by localspace_pos (acclient.c:362004).
        # Heading 90 takes local +x to global -y.
        path = make_path(Vector3(2, 0, 0), Vector3(1.2, 0, 0))
        path.localspace_pos = Position(CELL, Frame.from_heading(Vector3(), 90.0))
        sweep = Sweep(path, OIS.ON_WALKABLE, step_up_ok=True)
        assert cyl(height=0.3).intersects_sphere(sweep) == TS.OK
        # float32 tolerance: the heading-90 frame's matrix is float32 (cos 90° is not 0 there).
        assert close(sweep.step_up_normals[0], Vector3(0, -1, 0), 1e-6)

    def test_failed_step_up_falls_back_to_step_up_slide(self) -> None:
        # step_up_slide with a zero step_up_normal moves halfway back to curr (acclient.c:362008).
        path = make_path(Vector3(2, 0, 0), Vector3(1.2, 0, 0))
        sweep = Sweep(path, OIS.CONTACT, step_up_ok=False)
        sweep.collision_info.set_contact_plane(Plane.horizontal(0.0), False)
        assert cyl(height=0.3).intersects_sphere(sweep) == TS.ADJUSTED
        assert close(origin(path), Vector3(1.6, 0, 0))
        assert not sweep.collision_info.contact_plane_valid

    def test_too_high_slides_along_the_side(self) -> None:
        # Rise 0.5 + 2 - 0.5 = 2 > 0.4: slide sphere 0 (acclient.c:361983-361985). Normal (1,0,0) x
        # ground N = (0,-1,0); step (-0.8,0.3,0) keeps (0,0.3,0): offset (0.8,0,0) (CSphere::slide_sphere).
        path = make_path(Vector3(2, 0, 0), Vector3(1.2, 0.3, 0))
        sweep = Sweep(path, OIS.CONTACT)
        sweep.collision_info.set_contact_plane(Plane.horizontal(0.0), False)
        assert cyl().intersects_sphere(sweep) == TS.SLID
        assert close(origin(path), Vector3(2.0, 0.3, 0), 1e-9)
        assert close(sweep.collision_info.collision_normal, Vector3(1, 0, 0))
        assert not sweep.step_up_normals

    def test_second_sphere_slide_uses_its_own_disp(self) -> None:
        # Overhang from 1.8: only sphere 1 (old centre 1.5, new 1.6) is in it. Retail passes sphere 1's
        # disp (acclient.c:362141-362151), so disp.z - old.z = 0.1 > 0 -> normal (0,0,-1) (361696-361699);
        # against the ground plane that is head-on and facing away: COLLIDED with normal (0,0,-1).
        # ACE passes sphere 0's disp (-1.2 - -0.3 <= 0 -> (0,0,1)) and returns SLID.
        path = make_path(Vector3(), Vector3(0, 0, 0.1), second=True)
        sweep = Sweep(path, OIS.CONTACT)
        sweep.collision_info.set_contact_plane(Plane.horizontal(0.0), False)
        assert cyl(low_z=1.8, height=1.0).intersects_sphere(sweep) == TS.COLLIDED
        assert close(sweep.collision_info.collision_normal, Vector3(0, 0, -1))
        assert close(origin(path), Vector3(0, 0, 0.1))


class TestAirborne:
    def test_lands_on_the_top(self) -> None:
        path = make_path(Vector3(0.5, 0, 3), Vector3(0.5, 0, 1.8))
        assert cyl().intersects_sphere(Sweep(path)) == TS.ADJUSTED  # acclient.c:362029
        assert path.collide and path.walk_interp == 1.0  # set_collide (acclient.c:362027)
        assert close(path.step_up_normal, Vector3(0, 0, 1))
        assert path.walkable_allowance == LANDING_Z  # z_for_landing_2 (acclient.c:362028)

    def test_hits_the_side(self) -> None:
        path = make_path(Vector3(2, 0, 1), Vector3(1.2, 0, 1))
        assert cyl().intersects_sphere(Sweep(path)) == TS.ADJUSTED
        assert close(path.step_up_normal, Vector3(1, 0, 0))  # normalised (2,0,0) (acclient.c:362020-362021)

    def test_exactly_on_top_is_no_hit(self) -> None:
        path = make_path(Vector3(0.5, 0, 3), Vector3(0.5, 0, 2.0))
        assert cyl().intersects_sphere(Sweep(path)) == TS.OK  # acclient.c:362194
        assert not path.collide

    def test_path_clipped_ignores_sphere_one(self) -> None:
        path = make_path(Vector3(3, 0, 0), Vector3(1, 0, 0), second=True)
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl(low_z=1.2).intersects_sphere(sweep) == TS.OK  # acclient.c:362154-362165, 362194
        assert close(origin(path), Vector3(1, 0, 0))


class TestCollideWithPoint:
    def test_without_perfect_clip_only_sets_normal(self) -> None:
        path = make_path(Vector3(2, 0, 0), Vector3(1.2, 0.3, 0))
        sweep = Sweep(path, OIS.PATH_CLIPPED)
        assert cyl().intersects_sphere(sweep) == TS.COLLIDED  # acclient.c:361773-361776
        assert close(sweep.collision_info.collision_normal, Vector3(1, 0, 0))
        assert close(origin(path), Vector3(1.2, 0.3, 0))

    def test_side_hit_rewinds_to_the_touch(self) -> None:
        # Definite side: movement (-2,0,0), old (3,0): a 4, b 6, D = 36 - (9 - 2.25)·4 = 9, t = (6-3)/4
        # (acclient.c:361897-361911); offset (-1.5,0,0); adjust = curr + offset - check (361938-361949).
        path = make_path(Vector3(3, 0, 0), Vector3(1, 0, 0))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl().intersects_sphere(sweep) == TS.ADJUSTED  # acclient.c:361950
        assert close(origin(path), Vector3(1.5, 0, 0), 1e-9)
        assert close(sweep.collision_info.collision_normal, Vector3(1, 0, 0), 1e-9)

    def test_grazing_the_side(self) -> None:
        # Called directly, passing left to right at y = 1.49 and 1.51 from x 3 to 0. At 1.49:
        # D = 81 - (9 + 1.49² - 2.25)·9 >= 0, t = (9 - √D)/9 ≈ 0.94 (acclient.c:361897-361911), so
        # the sphere stops at x = 3 - 3t. At 1.51 D < 0: COLLIDED, untouched (361900, 361953).
        # float32: y is f32(1.49); the offset is movement times the time spilled to float
        # (acclient.c:361913-361923), and the adjusted centre and the origin are stores.
        y32 = f32(1.49)
        disc = 81.0 - (y32 * y32 + 9.0 - 1.5 * 1.5) * 9.0
        t = (9.0 - disc**0.5) / 9.0
        x_stop = f32(3.0 + f32(-3.0 * f32(t)))
        assert x_stop == pytest.approx(3.0 - 3.0 * t, abs=1e-6)
        for y, expected, x in ((1.49, TS.ADJUSTED, x_stop), (1.51, TS.COLLIDED, 0.0)):
            path = make_path(Vector3(3, y, 0), Vector3(0, y, 0))
            sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
            ball = path.global_sphere[0]
            info = sweep.collision_info
            result = cyl().collide_with_point(sweep.object_info, path, info, ball, ball.center, RADSUM, 0)
            assert result == expected
            assert origin(path).x == x

    def test_top_hit_rewinds_onto_the_cap(self) -> None:
        # Definite cap (0,0,1): t = (0.5 + 2 - 3.5)/-1.2 (acclient.c:361872-361875); offset z -1.0;
        # adjust = 3.5 - 1.0 - 2.3 = 0.2 (acclient.c:361938-361949).
        path = make_path(Vector3(0.5, 0, 3), Vector3(0.5, 0, 1.8))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl().intersects_sphere(sweep) == TS.ADJUSTED
        assert close(origin(path), Vector3(0.5, 0, 2.0), 1e-9)
        assert close(sweep.collision_info.collision_normal, Vector3(0, 0, 1))

    def test_bottom_hit_rewinds_under_the_cap(self) -> None:
        # Moving up into a cylinder from z 2: t = -((-1.5 + 0.5)/1.2) (acclient.c:361873); offset z 1.0;
        # adjust = 0.5 + 1.0 - 1.7 = -0.2: the sphere's top is left on the underside.
        path = make_path(Vector3(0.2, 0, 0), Vector3(0.2, 0, 1.2))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl(low_z=2.0, height=1.0).intersects_sphere(sweep) == TS.ADJUSTED
        assert close(origin(path), Vector3(0.2, 0, 1.0), 1e-9)
        assert close(sweep.collision_info.collision_normal, Vector3(0, 0, -1))

    def test_already_embedded_in_the_top_collides(self) -> None:
        # Old centre 2.1 is already under the top: t = (2.5 - 2.1)/-0.1 = -4 < 0 (acclient.c:361889-361895).
        path = make_path(Vector3(0.5, 0, 1.6), Vector3(0.5, 0, 1.5))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl().intersects_sphere(sweep) == TS.COLLIDED
        assert not sweep.collision_info.collision_normal_valid

    def test_indefinite_diagonal_onto_the_top(self) -> None:
        # Old centre (2,0,3.5) is clear both ways: indefinite. movement (-1,0,-1.4): cap time
        # (0.5 + 2 - 3.5)/-1.4 = 1/1.4 (acclient.c:361798-361808); horizontal 2 - 1/1.4 < 1.5 keeps the
        # top (361822); adjust = (2 - 1/1.4 - 1, 0, 3.5 - 1 - 2.1). ACE's cap time uses movement.z in
        # place of old.z, (2.5 + 1.4)/-1.4 < 0, and it collides.
        path = make_path(Vector3(2, 0, 3), Vector3(1, 0, 1.6))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl().intersects_sphere(sweep) == TS.ADJUSTED
        # float32: the check centre z is f32(1.6f + 0.5) = 2.0999999, so movement.z is -1.4000001;
        # the indefinite cap offset multiplies by the double time (acclient.c:361813-361820), then
        # curr + offset, the adjustment and the origin are stores (acclient.c:361938-361949).
        move_z = f32(f32(f32(1.6) + 0.5) - 3.5)
        time = (0.5 + 2.0 - 3.5) / move_z
        x = f32(1.0 + f32(f32(2.0 + f32(-1.0 * time)) - 1.0))
        assert x == pytest.approx(2 - 1 / 1.4, abs=1e-6)
        assert origin(path).exactly_equals(Vector3(x, 0, origin(path).z))
        assert origin(path).z == pytest.approx(2.0, abs=1e-6)
        assert close(sweep.collision_info.collision_normal, Vector3(0, 0, 1))

    def test_indefinite_diagonal_onto_the_side(self) -> None:
        # Old (3,0,3.5), movement (-1.8,0,-2): cap time 0.5 leaves it 2.1 out (acclient.c:361822), so
        # the side root: a 3.24, b 5.4, D 7.29, t = (5.4 - 2.7)/3.24 (361824-361843); offset
        # (-1.5,0,-5/3); normal (1.5,0,0)/1.5 (361853-361864); adjust (0.3, 0, 3.5 - 5/3 - 1.5). ACE
        # subtracts the offset instead (curr - offset - check) and would move it away from the cylinder.
        path = make_path(Vector3(3, 0, 3), Vector3(1.2, 0, 1))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert cyl().intersects_sphere(sweep) == TS.ADJUSTED
        # float32: movement.x = f32(1.2f - 3) = -1.7999999523; the side root with reach² the float
        # f32(1.5²) (acclient.c:361821-361841); the offset uses the time spilled to float
        # (361842-361851); curr + offset, the adjustment and the origin are stores (361938-361949).
        mx = f32(f32(1.2) - 3.0)
        a, b = mx * mx, -(mx * 3.0)
        disc = b * b - (9.0 - f32(1.5 * 1.5)) * a
        t32 = f32((b - disc**0.5) / a)
        x = f32(f32(1.2) + f32(f32(3.0 + f32(mx * t32)) - f32(1.2)))
        z = f32(1.0 + f32(f32(3.5 + f32(-2.0 * t32)) - 1.5))
        assert (x, z) == pytest.approx((1.5, 3.0 - 5.0 / 3.0), abs=1e-6)
        assert origin(path).exactly_equals(Vector3(x, 0, z))
        assert close(sweep.collision_info.collision_normal, Vector3(1, 0, 0), 1e-9)

    def test_sphere_one_rewinds_from_sphere_zero_centre(self) -> None:
        # Airborne, only sphere 1 in a cylinder from 1.2 (acclient.c:362178-362191). The normal uses
        # sphere 1's old centre, but movement and old disp use global_curr_center[0] (361778-361792):
        # movement = (1,0,1.5) - (3,0,0.5) = (-2,0,1), t = 0.75, adjust = (3-1.5-1, 0, 0.5+0.75-1.5).
        path = make_path(Vector3(3, 0, 0), Vector3(1, 0, 0), second=True)
        sweep = Sweep(path, OIS.PERFECT_CLIP)
        assert cyl(low_z=1.2).intersects_sphere(sweep) == TS.ADJUSTED
        assert close(origin(path), Vector3(1.5, 0, -0.25), 1e-9)
        assert close(sweep.collision_info.collision_normal, Vector3(1, 0, 0), 1e-9)


class TestCollideRewind:
    def test_landing_rewinds_onto_the_top(self) -> None:
        # movement = curr - check = (0,0,1.2); t = (2 + 0.5 - 2.3)/1.2 (acclient.c:362201-362206);
        # interp 5/6 (362215); plane z 2 through the rewound bottom (362219-362232).
        path = make_path(Vector3(0.5, 0, 3), Vector3(0.5, 0, 1.8))
        path.collide = True
        sweep = Sweep(path)
        assert cyl().intersects_sphere(sweep) == TS.ADJUSTED  # acclient.c:362234
        info = sweep.collision_info
        assert info.contact_plane_valid and info.contact_plane_is_water
        assert info.contact_plane.d == pytest.approx(-2.0, abs=1e-9)
        assert info.contact_plane_cell_id == CELL
        # float32: the check centre z is f32(1.8f + 0.5) = 2.29999995, movement.z the Vector3
        # f32(3.5 - 2.29999995); interp is (1 - t) stored into the float walk_interp (362232).
        center_z = f32(f32(1.8) + 0.5)
        t = (2.0 + 0.5 - center_z) / f32(3.5 - center_z)
        assert path.walk_interp == f32((1.0 - t) * 1.0) == pytest.approx(5 / 6, abs=1e-6)
        assert origin(path).z == pytest.approx(2.0, abs=1e-6)

    def test_side_hit_after_collide_is_ok(self) -> None:
        # movement (1.3,0,0.2): t = 1.2/0.2 = 6 puts it 9 m out: radsum² < ... -> OK
        # (acclient.c:362212-362214).
        path = make_path(Vector3(2.5, 0, 1.0), Vector3(1.2, 0, 0.8))
        path.collide = True
        sweep = Sweep(path)
        assert cyl().intersects_sphere(sweep) == TS.OK
        assert not sweep.collision_info.contact_plane_valid and path.walk_interp == 1.0

    def test_level_movement_and_deep_rewind_collide(self) -> None:
        path = make_path(Vector3(2.5, 0, 0.8), Vector3(1.2, 0, 0.8))
        path.collide = True
        assert cyl().intersects_sphere(Sweep(path)) == TS.COLLIDED  # |movement.z| < EPSILON (362204)
        # movement z 0.05, t = 0.1/0.05 = 2: interp -1 < -0.1 (acclient.c:362217, 362237).
        path = make_path(Vector3(0.5, 0, 1.95), Vector3(0.5, 0, 1.9))
        path.collide = True
        assert cyl().intersects_sphere(Sweep(path)) == TS.COLLIDED


class TestPlaced:
    def test_scaled_cylinder_from_the_next_block(self) -> None:
        # Local cylinder r .5 h 1 at scale 2, owner 190 m west of the east block's origin: from CELL's
        # block the low point is 192 - 190 = 2 east (Position::localtoglobal, acclient.c:362259-362267).
        # A sphere at x 3.4 is within radsum 1 + 0.5 - EPSILON of it only because of the scale.
        path = make_path(Vector3(5, 0, 0), Vector3(3.4, 0, 0))
        path.insert_type = InsertType.PLACEMENT
        owner = Position(EAST_CELL, Frame(origin=Vector3(-190.0, 0, 0)))
        small = CylSphere(Vector3(), 0.5, 1.0)
        assert small.intersects_sphere_placed(owner, 2.0, Sweep(path)) == TS.COLLIDED
        assert small.intersects_sphere_placed(owner, 1.0, Sweep(path)) == TS.OK
        # cache_localspace_sphere(p, 1.0) ran first (acclient.c:362258): the spheres in the owner's frame.
        assert path.localspace_pos.objcell_id == EAST_CELL
        # (3.4,0,.5) from CELL's block is (3.4 - 192, 0, .5) from the east block: local x = 3.4 - 192 + 190.
        # float32 tolerance: the point passes through x = -188.6 as a float32 (ulp 1.5e-5).
        assert close(path.localspace_sphere[0].center, Vector3(1.4, 0, 0.5), 2e-5)
        assert close(path.localspace_curr_center[0], Vector3(3.0, 0, 0.5), 2e-5)
        assert close(path.localspace_low_point, Vector3(1.4, 0, 0.0), 2e-5)
        assert close(path.localspace_z, Vector3(0, 0, 1))

    def test_rotated_owner_localspace(self) -> None:
        # Heading 90: global +x is local +y, so the sphere 3.4 east of an owner at the origin sits at
        # local (0, 3.4); localspace_z stays up (acclient.c:313851 cache, z from the matrix's third column).
        path = make_path(Vector3(5, 0, 0), Vector3(3.4, 0, 0))
        path.insert_type = InsertType.PLACEMENT
        owner = Position(CELL, Frame.from_heading(Vector3(), 90.0))
        assert CylSphere(Vector3(), 1.0, 2.0).intersects_sphere_placed(owner, 1.0, Sweep(path)) == TS.OK
        # float32 tolerance: the heading-90 frame's matrix is float32 (cos 90° is not 0 there).
        assert close(path.localspace_sphere[0].center, Vector3(0, 3.4, 0.5), 1e-6)
        assert close(path.localspace_z, Vector3(0, 0, 1), 1e-9)
