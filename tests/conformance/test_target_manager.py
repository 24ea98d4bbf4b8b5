"""TargetManager and the body's target glue, against the retail decompilation (CTargetting.c, CPhysicsObj.c).

Expected values are worked by hand from the cited acclient.c lines.
"""

from __future__ import annotations

import itertools

import pytest

from acphys.managers.target import LongNIHash, TargetInfo, TargetManager, TargetStatus
from acphys.math.vector import Vector3
from acphys.motion.motion_table import MotionTable
from acphys.motion.move_to import cylinder_distance
from acphys.motion.movement import MovementParameters, MovementStruct, MovementType
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.world.world import World
from support import LANDBLOCK, place

TICK = 1.0 / 30.0


def body(
    world: World,
    name: str,
    x: float,
    y: float,
    *,
    spheres: bool = True,
    motion_table: MotionTable | None = None,
) -> PhysicsObj:
    """A grounded body at (x, y, 50)."""
    origin = (x, y, 50.0)
    return place(world, name=name, origin=origin, on_ground=True, spheres=spheres, motion_table=motion_table)


def at(world: World, physics_time: float, cur_time: float | None = None) -> None:
    world.physics_time = physics_time
    world.cur_time = physics_time if cur_time is None else cur_time


@pytest.fixture
def pair(world: World) -> tuple[PhysicsObj, PhysicsObj]:
    """A tracker at (96, 96) and its target at (96, 100), on flat ground, the tracker already tracking."""
    world.set_flat_ground(LANDBLOCK, 50.0)
    tracker = body(world, "tracker", 96.0, 96.0)
    target = body(world, "target", 96.0, 100.0)
    tracker.set_target(0, target.id, 0.5, 0.0)
    return tracker, target


# -- SetTarget / AddVoyeur / ReceiveUpdate ----------------------------------------------------


def test_set_target_makes_the_manager_and_the_target_answers(pair: tuple[PhysicsObj, PhysicsObj]) -> None:
    tracker, target = pair
    # set_target creates the tracker's manager (acclient.c:315999-316006); SetTarget calls add_voyeur on the
    # target (acclient.c:328628), which creates the target's manager (acclient.c:316064-316071), enters the
    # voyeur and sends it the target's position at once (acclient.c:328380).
    assert isinstance(tracker.target_manager, TargetManager)
    assert isinstance(target.target_manager, TargetManager)
    voyeurs = list(target.target_manager.voyeur_table)
    assert [(v.object_id, v.radius, v.quantum) for v in voyeurs] == [(tracker.id, 0.5, 0.0)]
    # ReceiveUpdate took the report: status Ok, positions (acclient.c:328409-328431).
    info = tracker.target_manager.target_info
    assert info.status == TargetStatus.OK
    assert info.target_position.frame.origin.exactly_equals(target.position.frame.origin)
    assert info.interpolated_position.frame.origin.exactly_equals(target.position.frame.origin)
    assert info.target_position is not target.position  # a copy, not the body's own position
    # interpolated_heading = normalised offset tracker -> interpolated position (acclient.c:328433-328438).
    assert info.interpolated_heading.exactly_equals(Vector3(0.0, 1.0, 0.0))


def test_coincident_target_heading_is_up(world: World) -> None:
    # normalize_check_small fails on a zero offset -> (0, 0, 1) (acclient.c:328438-328447).
    world.set_flat_ground(LANDBLOCK, 50.0)
    tracker = body(world, "tracker", 96.0, 96.0, spheres=False)
    target = body(world, "target", 96.0, 96.0, spheres=False)
    tracker.set_target(0, target.id, 0.5, 0.0)
    assert tracker.target_manager.target_info.interpolated_heading.exactly_equals(Vector3(0.0, 0.0, 1.0))


def test_context_id_survives_reports(world: World) -> None:
    # ReceiveUpdate copies everything but context_id (acclient.c:328409-328431); the voyeur's report carries
    # context 0 (acclient.c:328111).
    world.set_flat_ground(LANDBLOCK, 50.0)
    tracker = body(world, "tracker", 96.0, 96.0)
    target = body(world, "target", 96.0, 100.0)
    tracker.set_target(9, target.id, 0.5, 0.0)
    assert tracker.target_manager.target_info.context_id == 9
    assert tracker.target_manager.target_info.status == TargetStatus.OK


def test_reports_about_other_objects_are_ignored(pair: tuple[PhysicsObj, PhysicsObj]) -> None:
    # target_update->object_id == target_info->object_id is required (acclient.c:328409).
    tracker, target = pair
    tracker.receive_target_update(TargetInfo(target.id + 1, TargetStatus.EXIT_WORLD))
    assert tracker.target_manager.target_info.status == TargetStatus.OK


def test_exit_world_report_clears_the_target(pair: tuple[PhysicsObj, PhysicsObj]) -> None:
    # NotifyVoyeurOfEvent sends every voyeur the event at the current position (acclient.c:328180); the
    # tracker's ReceiveUpdate then ClearTargets on ExitWorld (acclient.c:328451), which removes it from the
    # target's voyeur table while that table is being walked.
    tracker, target = pair
    target.target_manager.notify_voyeur_of_event(TargetStatus.EXIT_WORLD)
    assert tracker.target_manager.target_info is None
    assert len(target.target_manager.voyeur_table) == 0


def test_clear_target_leaves_the_voyeur_table(pair: tuple[PhysicsObj, PhysicsObj]) -> None:
    # ClearTarget: remove_voyeur on the target, then forget it (acclient.c:328283-328294).
    tracker, target = pair
    tracker.clear_target()
    assert tracker.target_manager.target_info is None
    assert target.remove_voyeur(tracker.id) is False  # already gone (acclient.c:328659)


def test_retargeting_leaves_the_old_target(world: World) -> None:
    # SetTarget first removes itself from the old target's table (acclient.c:328591-328605).
    world.set_flat_ground(LANDBLOCK, 50.0)
    tracker = body(world, "tracker", 96.0, 96.0)
    first = body(world, "first", 96.0, 100.0)
    second = body(world, "second", 100.0, 96.0)
    tracker.set_target(0, first.id, 0.5, 0.0)
    tracker.set_target(0, second.id, 0.5, 0.0)
    assert len(first.target_manager.voyeur_table) == 0
    assert [v.object_id for v in second.target_manager.voyeur_table] == [tracker.id]
    assert tracker.target_manager.target_info.interpolated_heading.exactly_equals(Vector3(1.0, 0.0, 0.0))


def test_target_zero_forgets_the_old_target(pair: tuple[PhysicsObj, PhysicsObj]) -> None:
    # object_id 0: the old target is dropped and no new one made; a TimedOut report goes to HandleUpdateTarget
    # (acclient.c:328612-328638).
    tracker, target = pair
    tracker.set_target(0, 0, 0.5, 0.0)
    assert tracker.target_manager.target_info is None
    assert len(target.target_manager.voyeur_table) == 0


def test_body_without_a_manager_skips_the_other_calls(world: World) -> None:
    # clear_target, set_target_quantum, get_target_quantum, receive_target_update and remove_voyeur do not
    # create the manager (acclient.c:316011-316087).
    b = place(world)
    b.clear_target()
    b.set_target_quantum(3.0)
    b.receive_target_update(TargetInfo(5, TargetStatus.OK))
    assert b.get_target_quantum() == 0.0
    assert b.remove_voyeur(5) is False
    assert b.target_manager is None


# -- the timeout ------------------------------------------------------------------------------


def test_unanswered_target_times_out_on_the_wall_clock(world: World) -> None:
    world.set_flat_ground(LANDBLOCK, 50.0)
    walker = body(world, "walker", 96.0, 96.0, motion_table=builtin_motion_table("humanoid"))
    missing = 0x70000001
    at(world, 0.0)
    walker.movement_manager.perform_movement(
        MovementStruct(
            MovementType.MOVE_TO_OBJECT, object_id=missing, top_level_id=missing, params=MovementParameters()
        )
    )
    manager = walker.target_manager
    # No such object: the target stays Undef, stamped with Timer::cur_time (acclient.c:328620-328630).
    assert manager.target_info.status == TargetStatus.UNDEF
    assert manager.target_info.last_update_time == 0.0
    moveto = walker.movement_manager.moveto_manager
    # last_update_time + 10 < Timer::cur_time is strict (acclient.c:328471): at exactly 10 s nothing happens.
    at(world, 10.0)
    manager.handle_targetting()
    assert manager.target_info.status == TargetStatus.UNDEF and moveto.is_moving_to()
    # The clock is Timer::cur_time, not the physics timer: here the physics timer only passes the 0.5-s
    # gate (acclient.c:328468) while the wall clock is past 10 s. ACE compares with PhysicsTimer and skips the
    # whole pass while the target never answered (TargetPosition == null), so it never times out.
    at(world, 10.5, cur_time=10.01)
    manager.handle_targetting()
    # TimedOut goes to HandleUpdateTarget (acclient.c:328473-328475): the move-to, not yet started, cancels
    # (MoveToManager::HandleUpdateTarget, acclient.c:346108), and its CleanUp clears the target.
    assert not moveto.is_moving_to()
    assert manager.target_info is None


def test_timed_out_target_is_kept_and_reported_once(world: World) -> None:
    # HandleTargetting sets status 6 and reports; it keeps the target (acclient.c:328470-328475). The next
    # pass sees status != Undef and stays quiet.
    b = place(world)
    b.set_target(0, 0x70000001, 0.5, 0.0)
    manager = b.target_manager
    at(world, 10.5)
    manager.handle_targetting()
    assert manager.target_info.status == TargetStatus.TIMED_OUT
    manager.target_info.last_update_time = -1.0  # would time out again were the status still Undef
    manager.target_info.status = TargetStatus.OK
    at(world, 11.0)
    manager.handle_targetting()
    assert manager.target_info.status == TargetStatus.OK


def test_targetting_runs_every_half_second_of_physics_time(pair: tuple[PhysicsObj, PhysicsObj]) -> None:
    tracker, target = pair
    manager = target.target_manager
    target.cached_velocity = Vector3(2.0, 0.0, 0.0)
    target.position.frame.origin.x = 97.0  # 1 m from the last position sent
    # curr_time - last_update_time >= 0.5 (acclient.c:328468): 0.49 does nothing, and does not restamp.
    at(world := target.world, 0.49)
    manager.handle_targetting()
    assert manager.last_update_time == 0.0
    assert tracker.target_manager.target_info.target_position.frame.origin.x == 96.0
    at(world, 0.5)
    manager.handle_targetting()
    assert manager.last_update_time == 0.5  # acclient.c:328493
    assert tracker.target_manager.target_info.target_position.frame.origin.x == 97.0


# -- voyeur updates at the target quantum ---------------------------------------------------------


class TestVoyeurUpdates:
    def start(self, pair: tuple[PhysicsObj, PhysicsObj], quantum: float) -> tuple[PhysicsObj, PhysicsObj]:
        tracker, target = pair
        target.cached_velocity = Vector3(1.0, 0.0, 0.0)  # what get_velocity returns (acclient.c:318565)
        tracker.set_target_quantum(quantum)
        at(target.world, 0.5)
        target.target_manager.handle_targetting()
        return tracker, target

    def test_quantum_reaches_the_voyeur_without_a_report(self, pair: tuple[PhysicsObj, PhysicsObj]) -> None:
        # SetTargetQuantum stores it and calls add_voyeur (acclient.c:328080-328086); a known voyeur only
        # takes radius and quantum (acclient.c:328325-328327), narrowed to float by add_voyeur's parameter
        # (acclient.c:316056). A 0.4-m prediction is within the 0.5 radius: no report.
        tracker, target = self.start(pair, 0.4)
        voyeur = next(iter(target.target_manager.voyeur_table))
        assert voyeur.quantum == f32(0.4) != 0.4
        assert tracker.get_target_quantum() == 0.4  # the tracker's own copy is not narrowed
        assert voyeur.last_sent_position.frame.origin.x == 96.0

    def test_prediction_past_the_radius_is_sent(self, pair: tuple[PhysicsObj, PhysicsObj]) -> None:
        # GetInterpolatedPosition: position + velocity * (float)quantum (acclient.c:328147-328154),
        # the x term added in registers and stored once into the float32 origin;
        # 0.6 m > 0.5 -> SendVoyeurUpdate Ok with that position (acclient.c:328175-328176).
        tracker, target = self.start(pair, 0.6)
        info = tracker.target_manager.target_info
        predicted = f32(f32(0.6) * 1.0 + 96.0)
        assert predicted == 96.5999984741211 != 96.0 + f32(0.6)
        assert info.interpolated_position.frame.origin.x == predicted
        assert info.target_position.frame.origin.x == 96.0
        assert info.velocity.exactly_equals(Vector3(1.0, 0.0, 0.0))
        # The report carries the voyeur's (narrowed) quantum, which ReceiveUpdate copies (acclient.c:328413).
        assert info.quantum == f32(0.6)
        voyeur = next(iter(target.target_manager.voyeur_table))
        assert voyeur.last_sent_position.frame.origin.x == predicted

    def test_prediction_exactly_at_the_radius_is_not_sent(self, pair: tuple[PhysicsObj, PhysicsObj]) -> None:
        # distance > radius is strict (acclient.c:328175): 0.5 m is not sent.
        tracker, _ = self.start(pair, 0.5)
        assert tracker.target_manager.target_info.interpolated_position.frame.origin.x == 96.0


def test_voyeur_table_iterates_in_retail_bucket_order() -> None:
    # (key ^ key >> 16) % 4 picks the bucket; add links at the bucket head (acclient.c:327166); the
    # iterator walks buckets in order (acclient.c:327998). 0x50000001 and 0x50000005 share bucket 1,
    # 0x50000002 is in bucket 2.
    table: LongNIHash[str] = LongNIHash(4)
    table.add("a", 0x50000001)
    table.add("b", 0x50000002)
    table.add("c", 0x50000005)
    assert list(table) == ["c", "a", "b"]
    assert table.remove(0x50000001) == "a"
    assert list(table) == ["c", "b"]


def test_context_reports_do_not_reach_the_movement_manager(world: World) -> None:
    # HandleUpdateTarget passes a report on only when its context_id is 0 (acclient.c:319973).
    world.set_flat_ground(LANDBLOCK, 50.0)
    walker = body(world, "walker", 96.0, 96.0, motion_table=builtin_motion_table("humanoid"))
    missing = 0x70000001
    walker.movement_manager.perform_movement(
        MovementStruct(
            MovementType.MOVE_TO_OBJECT, object_id=missing, top_level_id=missing, params=MovementParameters()
        )
    )
    moveto = walker.movement_manager.moveto_manager
    there = place(world, name="marker", spheres=False, origin=(96.0, 100.0, 50.0)).position
    walker.handle_update_target(TargetInfo(missing, TargetStatus.OK, there, there, context_id=3))
    assert moveto.initialized is False
    walker.handle_update_target(TargetInfo(missing, TargetStatus.OK, there, there))
    assert moveto.initialized is True


# -- MoveToObject end to end ------------------------------------------------------------------------


def run(world: World, bodies: list[PhysicsObj], seconds: float) -> None:
    for _ in range(round(seconds / TICK)):
        world.cur_time += TICK
        for b in bodies:
            b.update_object()


#: The sought object's radius in the move-to request: the built-in human's (its spheres' 0.48 m).
HUMAN_RADIUS = 0.48


def walk_until_done(world: World, walker: PhysicsObj, target: PhysicsObj) -> None:
    moveto = walker.movement_manager.moveto_manager
    for _ in range(600):
        run(world, [walker, target], TICK)
        if not moveto.is_moving_to():
            return
    raise AssertionError("the move-to never finished")


def test_move_to_object_walks_to_a_standing_target(world: World) -> None:
    world.set_flat_ground(LANDBLOCK, 50.0)
    table = builtin_motion_table
    walker = body(world, "walker", 96.0, 96.0, motion_table=table("humanoid"))
    target = body(world, "target", 96.0, 104.0, motion_table=table("humanoid"))
    run(world, [walker, target], 0.5)
    walker.movement_manager.perform_movement(
        MovementStruct(
            MovementType.MOVE_TO_OBJECT,
            object_id=target.id,
            top_level_id=target.id,
            radius=HUMAN_RADIUS,
            height=target.get_height(),
            params=MovementParameters(),
        )
    )
    moveto = walker.movement_manager.moveto_manager
    # MoveToObject -> set_target(0, id, 0.5, 0.0) (acclient.c:345220); the target answers inside the call, so
    # MoveToObject_Internal has already queued the walk (acclient.c:346095-346099).
    assert moveto.initialized
    assert [v.object_id for v in target.target_manager.voyeur_table] == [walker.id]
    walk_until_done(world, walker, target)
    # Arrival: the cylinder distance is within distance_to_object (acclient.c:345688).
    gap = cylinder_distance(
        walker.get_radius(),
        walker.get_height(),
        walker.position,
        HUMAN_RADIUS,
        target.get_height(),
        target.position,
    )
    assert gap <= MovementParameters().distance_to_object
    # CleanUp clears the target, which leaves the target's voyeur table (acclient.c:345165, 328283-328285).
    assert walker.target_manager.target_info is None
    assert len(target.target_manager.voyeur_table) == 0


def test_move_to_object_follows_a_walking_target(world: World) -> None:
    world.set_flat_ground(LANDBLOCK, 50.0)
    table = builtin_motion_table
    walker = body(world, "walker", 96.0, 96.0, motion_table=table("humanoid"))
    target = body(world, "target", 96.0, 104.0, motion_table=table("humanoid"))
    run(world, [walker, target], 0.5)
    goal = place(world, name="goal", spheres=False, origin=(110.0, 104.0, 50.0)).position
    target.move_to_position(goal, MovementParameters())
    walker.movement_manager.perform_movement(
        MovementStruct(
            MovementType.MOVE_TO_OBJECT,
            object_id=target.id,
            top_level_id=target.id,
            radius=HUMAN_RADIUS,
            height=target.get_height(),
            params=MovementParameters(),
        )
    )
    voyeur = next(iter(target.target_manager.voyeur_table))
    sent = [voyeur.last_sent_position.frame.origin.x]
    stamps = [world.physics_time]
    quanta = [voyeur.quantum]
    moveto = walker.movement_manager.moveto_manager
    for _ in range(600):
        run(world, [walker, target], TICK)
        x = voyeur.last_sent_position.frame.origin.x
        if x != sent[-1]:
            sent.append(x)
            stamps.append(world.physics_time)
            quanta.append(voyeur.quantum)
            # Each report re-aims the walk at the reported position (acclient.c:346072-346073).
            assert moveto.sought_position.frame.origin.x == x
        if not moveto.is_moving_to():
            break
    assert not moveto.is_moving_to()
    # The target walks east at 3.12 m/s; it re-reports on a HandleTargetting pass (at most every 0.5 s of
    # physics time, acclient.c:328468) once it is more than 0.5 m from the last report (acclient.c:328175):
    # every pass while it walks. Fifteen 1/30-s ticks sum to 0.49999999999999994 s in doubles, short of the
    # gate, so the passes come every 16 ticks (0.533 s), 0.533 × 3.12 = 1.664 m apart.
    # The walker retunes the target quantum once it walks (HandleMoveToPosition, acclient.c:345694-345704:
    # time = distance / |cached_velocity| = (4.776 - 0.48 - 0.48) / 3.12: the cylinder distance less both
    # 0.48-m radii, more than 1 s off the initial 0), which shifts the
    # phase of the target's passes once; from the third report on they are steady.
    # The walker's |cached_velocity| is the float32 origin's step over the quantum: near y = 100 an ulp of
    # 7.6e-6 m is 2.3e-4 m/s at 30 Hz (it reads 3.11989, not 3.12), and the walk it integrates drifts as
    # much, so the quantum is (4.776 - 0.96) / 3.12 within 2e-4 s.
    assert quanta[0] == 0.0
    assert quanta[1] == pytest.approx((4.776 - 0.48 - 0.48) / 3.12, abs=2e-4)
    assert len(sent) >= 6
    assert [round(b - a, 3) for a, b in itertools.pairwise(stamps[2:])] == [0.533] * (len(sent) - 3)
    assert [round(b - a, 3) for a, b in itertools.pairwise(sent[2:-1])] == [1.664] * (len(sent) - 4)
    gap = cylinder_distance(
        walker.get_radius(),
        walker.get_height(),
        walker.position,
        HUMAN_RADIUS,
        target.get_height(),
        target.position,
    )
    assert gap <= MovementParameters().distance_to_object
    assert len(target.target_manager.voyeur_table) == 0
