"""StickyManager: a body stuck to a moving target, against retail.

Decompiled: cpmanager/CStickyManager.c (adjust_offset acclient.c:388518, UseTime 388604,
StickTo 388664, HandleUpdateTarget 388690, HandleExitWorld 388501). Target reports come from the
real TargetManager (``acphys.managers.target``): ``StickTo`` calls ``set_target``, the target
answers through ``add_voyeur`` and the report reaches the sticky manager via
``CPhysicsObj::HandleUpdateTarget``.
"""

from __future__ import annotations

import pytest

from acphys.managers.target import TargetInfo, TargetStatus
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32
from support import LANDBLOCK, place

DT = 1.0 / 30.0
GROUND = 50.0


@pytest.fixture
def pair(world):
    world.set_flat_ground(LANDBLOCK, GROUND)
    pet = place(world, name="pet", on_ground=True, origin=(40.0, 100.0, GROUND))
    pet.get_minterp()  # a movement manager, as a creature has
    owner = place(world, name="owner", spheres=False, on_ground=True, origin=(45.0, 100.0, GROUND))
    return pet, owner


def _gap(pet, owner) -> float:
    """Position::cylinder_distance_no_z (acclient.c:467268): the 3-D centre distance less both radii."""
    return pet.position.get_offset(owner.position).length() - pet.get_radius() - owner.get_radius()


class TestStick:
    def test_stick_to_object_tracks_the_target_and_is_initialized_by_its_answer(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        sticky = pet.position_manager.sticky_manager
        # StickTo: target_id set, timeout cur_time + 1 (388683-388686), set_target(0, id, 0.5, 0.5)
        # (388687); the owner answers at once with an OK report (HandleUpdateTarget 388699-388703).
        assert pet.get_sticky_object_id() == owner.id
        assert sticky.sticky_timeout_time == pytest.approx(pet.world.cur_time + 1.0)
        assert pet.target_manager.target_info.object_id == owner.id
        assert sticky.initialized
        assert sticky.target_position.frame.origin.x == pytest.approx(45.0)

    def test_the_body_closes_at_five_times_its_max_speed_and_faces_the_target(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        start = _gap(pet, owner)
        pet.update_object_internal(DT)
        # max speed 4 (no weenie, acclient.c:343485) * 5 = 20 m/s (388572): 20/30 m a step (388589);
        # the heading becomes 90 (the owner is due east, 388593-388600). The body's origin is
        # float32 (an ulp is 3.8e-6 at 40 m) and the step is applied with the new float32 rotation,
        # so the gap closes by 20/30 m within a few ulps; the heading is read back from a float32
        # quaternion.
        assert start - _gap(pet, owner) == pytest.approx(20.0 * DT, abs=1e-5)
        assert pet.position.frame.get_heading() == pytest.approx(90.0, abs=1e-5)

    def test_the_offset_is_the_step_along_the_local_direction(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        offset = Frame()
        pet.position_manager.adjust_offset(offset, DT)
        # The direction is (1, 0, 0) exactly (normalize_check_small of (5, 0, 0), z zeroed at
        # 388556); the step 20 * DT stays double (v14, 388581) and is stored once per axis
        # (388587-388591).
        assert offset.origin.exactly_equals(Vector3(f32(20.0 * DT), 0.0, 0.0))

    def test_the_body_stops_at_the_0_3m_standoff(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        for _ in range(15):
            pet.update_object_internal(DT)
        # Within reach the step is exactly the gap less 0.3 (388559, 388581-388585). The gap is 3-D
        # but the step flat (z zeroed, 388556), so the pet (5 mm higher) converges on it.
        assert _gap(pet, owner) == pytest.approx(0.3, abs=1e-4)

    def test_the_body_follows_a_moving_target(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        for _ in range(15):
            pet.update_object_internal(DT)
        moved = owner.position.copy()
        moved.frame.origin.set(Vector3(45.0, 102.0, GROUND))
        assert owner.set_position_simple(moved, True) == 0
        # The live object's position is used when the world knows it (388544-388547).
        for _ in range(10):
            pet.update_object_internal(DT)
        assert _gap(pet, owner) == pytest.approx(0.3, abs=1e-4)
        assert pet.position.frame.get_heading() == pytest.approx(
            pet.position.get_offset(owner.position).get_heading(), abs=1e-4
        )

    def test_the_stick_drops_on_timeout(self, world, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        # UseTime: Timer::cur_time > timeout (strictly, 388613) lets go: target 0, clear_target,
        # cancel_moveto (388616-388619).
        world.cur_time = 1.0
        pet.update_object_internal(DT)
        assert pet.get_sticky_object_id() == owner.id
        world.cur_time = 1.0001
        pet.update_object_internal(DT)
        assert pet.get_sticky_object_id() == 0
        assert pet.target_manager.target_info is None
        before = pet.position.frame.origin.copy()
        pet.update_object_internal(DT)
        assert pet.position.frame.origin.exactly_equals(before)


class TestReports:
    def test_a_bad_status_lets_go(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        # Any status but OK for the stuck object: let go (388705-388711).
        pet.handle_update_target(TargetInfo(owner.id, TargetStatus.EXIT_WORLD))
        assert pet.get_sticky_object_id() == 0

    def test_reports_about_other_objects_are_ignored(self, pair):
        pet, owner = pair
        pet.stick_to_object(owner.id)
        pet.handle_update_target(TargetInfo(owner.id + 1, TargetStatus.EXIT_WORLD))
        assert pet.get_sticky_object_id() == owner.id

    def test_not_pulled_before_the_first_ok_report(self, pair):
        # adjust_offset needs target_id and initialized (388540).
        pet, _owner = pair
        pet.make_position_manager().stick_to(0x7FFF0000, 0.0, 0.0)  # nobody answers for this id
        before = pet.position.frame.origin.copy()
        pet.update_object_internal(DT)
        assert pet.position.frame.origin.exactly_equals(before)

    def test_the_last_reported_position_is_used_when_the_target_is_unknown(self, pair):
        pet, _owner = pair
        far = 0x7FFF0000
        pet.make_position_manager().stick_to(far, 0.0, 0.0)
        reported = pet.position.copy()
        reported.frame.origin.set(Vector3(40.0, 103.0, GROUND))
        pet.handle_update_target(TargetInfo(far, TargetStatus.OK, reported))
        offset = Frame()
        pet.position_manager.adjust_offset(offset, DT)
        # Due north, 20/30 m closer (388546-388547): the offset is the step stored once (388587-388591).
        assert offset.origin.exactly_equals(Vector3(0.0, f32(20.0 * DT), 0.0))
        pet.update_object_internal(DT)
        # The body's float32 origin at y = 100 (an ulp is 7.6e-6) takes the step within a few ulps.
        assert pet.position.frame.origin.y == pytest.approx(100.0 + 20.0 * DT, abs=2e-5)

    def test_unstick_lets_go(self, pair):
        # PositionManager::UnStick is the sticky manager's HandleExitWorld (388306, 388501).
        pet, owner = pair
        pet.stick_to_object(owner.id)
        pet.unstick_from_object()
        assert pet.get_sticky_object_id() == 0
        assert pet.target_manager.target_info is None

    def test_sticking_to_a_child_sticks_to_its_parent(self, world, pair):
        # stick_to_object climbs to the parent (acclient.c:319744-319746).
        pet, owner = pair
        child = place(world, name="sword", spheres=False, origin=(45.0, 100.0, GROUND))
        child.parent = owner
        pet.stick_to_object(child.id)
        assert pet.get_sticky_object_id() == owner.id
