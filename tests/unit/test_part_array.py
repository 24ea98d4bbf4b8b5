"""CPartArray: setup data scaled by the body's scale, and the motion-table plumbing."""

from __future__ import annotations

import pytest

from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.motion.movement import MovementError, MovementParameters
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.setup import Setup
from acphys.world.world import World


def _setup() -> Setup:
    return Setup(
        name="post",
        spheres=[Sphere(Vector3(0.0, 0.0, 0.5), 0.5)],
        cylspheres=[CylSphere(Vector3(), 0.3, 2.0)],
        height=2.0,
        radius=0.3,
        step_up_height=0.4,
        step_down_height=0.6,
    )


def test_size_and_step_heights_follow_the_body_scale() -> None:
    body = PhysicsObj(World(), "post", PartArray(_setup()))
    body.set_scale_static(1.5)
    parts = body.part_array
    # setup value × scale.z (GetHeight acclient.c:325387, GetRadius 325381,
    # GetStepUpHeight 325399, GetStepDownHeight 325413); SetScaleStatic keeps them in step (319007).
    # The setup's fields are floats; the products are returned in st0, unrounded.
    assert parts.scale == 1.5
    assert parts.get_height() == 3.0
    assert parts.get_radius() == f32(0.3) * 1.5
    assert parts.get_step_up_height() == f32(0.4) * 1.5
    assert parts.get_step_down_height() == f32(0.6) * 1.5
    assert parts.get_num_sphere() == 1 and parts.get_num_cylsphere() == 1
    assert parts.get_cylsphere()[0].height == 2.0  # shapes stay unscaled; the sweep scales them


def test_without_a_motion_table_motion_requests_fail_with_error_7() -> None:
    parts = PartArray(_setup())
    # CPartArray::DoInterpretedMotion / StopInterpretedMotion / StopCompletelyInternal return 7
    # when there is no motion-table manager (acclient.c:326017, 326053, 326089).
    assert parts.do_interpreted_motion(0x44000007, MovementParameters()) == MovementError.NO_ANIMATION_TABLE
    assert parts.stop_interpreted_motion(0x44000007, MovementParameters()) == MovementError.NO_ANIMATION_TABLE
    assert parts.stop_completely_internal() == MovementError.NO_ANIMATION_TABLE


def test_a_body_without_a_part_array_refuses_motion_with_0x47() -> None:
    body = PhysicsObj(World(), "ghost")
    # CPhysicsObj::DoInterpretedMotion: result = 71 without a part array (acclient.c:315752).
    assert body.do_interpreted_motion(0x44000007, MovementParameters()) == 0x47
    # CPhysicsObj::DoMotion without a movement manager: 7 (acclient.c:317314).
    assert body.do_motion(0x44000007, MovementParameters()) == 7
    assert body.last_move_was_autonomous


def test_the_same_table_keeps_its_manager_and_a_new_one_replaces_it() -> None:
    body = PhysicsObj(World(), "h", PartArray(_setup()))
    table = builtin_motion_table("humanoid")
    body.set_motion_table(table)
    manager = body.part_array.motion_table_manager
    # SetMotionTableID returns early when the id is unchanged (acclient.c:325981).
    body.part_array.set_motion_table(table)
    assert body.part_array.motion_table_manager is manager
    body.set_motion_table(builtin_motion_table("humanoid"))
    assert body.part_array.motion_table_manager is not manager
    assert body.part_array.motion_table_manager.physics_obj is body
    body.set_motion_table(None)
    assert body.part_array.motion_table_manager is None and body.movement_manager is None


def test_the_sorting_sphere_is_the_sphere_around_the_setup_spheres() -> None:
    from acphys.setup import bounding_sphere, human_setup

    # Human: bottom -0.005, top 1.83 -> centre 0.9125, radius 0.9175 (acphys's stand-in for DAT data).
    sorting = human_setup().sorting_sphere
    assert sorting.center.z == pytest.approx(0.9125) and sorting.radius == pytest.approx(0.9175)
    one = Sphere(Vector3(1.0, 2.0, 3.0), 0.5)
    assert bounding_sphere([one]).radius == 0.5 and bounding_sphere([one]).center == one.center
    assert bounding_sphere([]).radius == 0.0
    inner = Sphere(Vector3(0.0, 0.0, 0.1), 0.2)
    assert bounding_sphere([Sphere(Vector3(), 1.0), inner]).radius == 1.0
    # A middle sphere sticking out grows the radius around the end spheres' centre.
    middle = Sphere(Vector3(3.0, 0.0, 0.0), 1.0)
    wide = bounding_sphere([Sphere(Vector3(0, 0, 0), 1.0), middle, Sphere(Vector3(0, 0, 2), 1.0)])
    assert wide.center == Vector3(0.0, 0.0, 1.0)
    assert wide.radius == pytest.approx(10**0.5 + 1.0)


def test_a_setup_that_allows_a_free_heading_sweeps_with_free_rotate() -> None:
    # CPhysicsObj::get_object_info: AllowsFreeHeading -> state |= 0x10 (FREE_ROTATE); CPartArray::
    # AllowsFreeHeading returns setup->allow_free_heading (acclient.c:319073, 325393).
    from acphys.flags import ObjectInfoState
    from acphys.transition.transition import Transition

    world = World()
    free = PhysicsObj(world, "free", PartArray(Setup("free", allow_free_heading=True)))
    fixed = PhysicsObj(world, "fixed", PartArray(_setup()))
    assert free.get_object_info(Transition(world, free), admin_move=False) & ObjectInfoState.FREE_ROTATE
    assert not fixed.get_object_info(Transition(world, fixed), admin_move=False) & ObjectInfoState.FREE_ROTATE
