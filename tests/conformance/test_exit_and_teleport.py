"""CPhysicsObj::exit_world, teleport_hook and MoveOrTeleport against the retail decompilation.

Decompiled: cphysobj/CPhysicsObj.c (exit_world acclient.c:322204, teleport_hook 322236,
MoveOrTeleport 323450), smartbox/SmartBox.c (is_newer 143002, newer_event 143014). Expected values
are worked by hand from the cited lines; the managers are the real ones.
"""

from __future__ import annotations

import pytest

from acphys.body.cells import MOVE_OR_TELEPORT_SNAP_DISTANCE, PhysicsTimeStamp, is_newer
from acphys.managers.detection import DetectionManager
from acphys.managers.target import TargetStatus
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.commands import WALK_FORWARD
from acphys.motion.movement import MovementParameters
from acphys.physics_obj import PhysicsObj
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.world.world import World
from support import LANDBLOCK, place

GROUND = 50.0
TELEPORT = PhysicsTimeStamp.TELEPORT


def at(x: float, y: float, z: float = GROUND) -> Position:
    point = Vector3(x, y, z)
    return Position(outdoor_cell_id(LANDBLOCK, point), Frame(point))


def walker(world: World, name: str, x: float, y: float) -> PhysicsObj:
    table = builtin_motion_table("humanoid")
    return place(world, name=name, on_ground=True, origin=(x, y, GROUND), motion_table=table)


def heard(body: PhysicsObj) -> list[TargetStatus]:
    """What ``body``'s target reports ended with (its handle_update_target, made observable)."""
    seen: list[TargetStatus] = []
    original = body.handle_update_target

    def record(info):
        seen.append(TargetStatus(info.status))
        original(info)

    body.handle_update_target = record
    return seen


@pytest.fixture
def scene(world: World) -> tuple[PhysicsObj, PhysicsObj, PhysicsObj]:
    """A pet stuck to its owner; the owner tracks a post and watches it with two cylinders."""
    world.set_flat_ground(LANDBLOCK, GROUND)
    owner = walker(world, "owner", 96.0, 96.0)
    pet = walker(world, "pet", 93.0, 96.0)
    post = place(world, name="post", spheres=False, on_ground=True, origin=(96.0, 110.0, GROUND))
    pet.stick_to_object(owner.id)
    owner.set_target(0, post.id, 0.5, 0.5)
    owner.detection_manager = DetectionManager(owner)
    owner.detection_manager.create_detection_cylsphere(0, 5.0, post.id)
    owner.detection_manager.create_detection_cylsphere(4, 5.0, post.id)
    return owner, pet, post


class TestExitWorld:
    def test_pending_motions_retire_and_the_cell_is_kept(self, scene) -> None:
        owner, _, _ = scene
        assert owner.do_motion(WALK_FORWARD, MovementParameters()) == 0
        assert owner.part_array.motion_table_manager.pending_animations
        assert owner.get_minterp().pending_motions
        cell = owner.cell
        owner.exit_world()
        # CPartArray::HandleExitWorld -> MotionTableManager::HandleExitWorld: AnimationDone(0) until the
        # queue is empty (acclient.c:322215-322216, 329945); MovementManager::HandleExitWorld retires the
        # interpreter's pending motions (322218-322219, 343678).
        assert not owner.part_array.motion_table_manager.pending_animations
        assert not owner.get_minterp().pending_motions
        # exit_world does not touch cells (leave_world does, acclient.c:322653): still in its cell.
        assert owner.cell is cell and owner in cell.objects

    def test_target_is_cleared_and_voyeurs_hear_exit_world(self, scene) -> None:
        owner, pet, post = scene
        pet_heard = heard(pet)
        owner.exit_world()
        # ClearTarget leaves the post's voyeur table (acclient.c:322225, 328283-328285).
        assert owner.target_manager.target_info is None
        assert len(post.target_manager.voyeur_table) == 0
        # NotifyVoyeurOfEvent(ExitWorld) (acclient.c:322226): the pet's sticky manager lets go on a
        # non-OK report (388703-388704) and its target manager clears the target on ExitWorld
        # (328421-328422), which leaves the owner's voyeur table.
        assert pet_heard == [TargetStatus.EXIT_WORLD]
        assert pet.get_sticky_object_id() == 0
        assert pet.target_manager.target_info is None
        assert len(owner.target_manager.voyeur_table) == 0

    def test_the_context_zero_cylinder_is_queued_for_deletion(self, scene) -> None:
        owner, _, _ = scene
        manager = owner.detection_manager
        owner.exit_world()
        # DestroyDetectionCylsphere(0) (acclient.c:322229) queues context 0 only (327662); the next
        # CheckDetection deletes it first thing (327685).
        assert manager.pending_deletions == [0]
        manager.check_detection()
        assert list(manager.detection_table) == [4]

    def test_exit_world_unsticks_the_body_itself(self, scene) -> None:
        _, pet, _ = scene
        owner_id = pet.get_sticky_object_id()
        assert owner_id
        pet.exit_world()
        # PositionManager::UnStick -> StickyManager::HandleExitWorld (acclient.c:322221-322222,
        # 388506-388511).
        assert pet.get_sticky_object_id() == 0
        assert pet.target_manager.target_info is None


class TestTeleportHook:
    def test_move_to_stick_interpolation_and_constraint_end(self, scene) -> None:
        owner, pet, post = scene
        assert owner.move_to_position(at(96.0, 106.0), MovementParameters()) == 0
        owner.interpolate_to(at(98.0, 96.0), False)
        owner.constrain_to(at(96.0, 96.0), 5.0, 20.0)
        owner.stick_to_object(post.id)
        assert owner.is_moving_to() and owner.is_interpolating()
        pet_heard = heard(pet)
        owner.teleport_hook(True)
        # CancelMoveTo(0x3C) (acclient.c:322249), UnStick (322252), StopInterpolating (322255),
        # UnConstrain (322258).
        assert not owner.is_moving_to()
        assert owner.get_sticky_object_id() == 0
        assert not owner.is_interpolating()
        assert not owner.position_manager.constraint_manager.is_constrained
        # ClearTarget and NotifyVoyeurOfEvent(Teleported) (322262-322263): the pet lets go (388703-388704)
        # but, unlike ExitWorld, its target manager keeps the target (328421).
        assert pet_heard == [TargetStatus.TELEPORTED]
        assert owner.target_manager.target_info is None
        assert pet.get_sticky_object_id() == 0

    def test_teleported_keeps_a_plain_tracker_target(self, world: World) -> None:
        world.set_flat_ground(LANDBLOCK, GROUND)
        target = walker(world, "target", 96.0, 96.0)
        tracker = walker(world, "tracker", 90.0, 96.0)
        tracker.set_target(3, target.id, 0.5, 0.5)
        target.teleport_hook(True)
        # ReceiveUpdate clears the target only on ExitWorld (acclient.c:328421-328422).
        assert tracker.target_manager.target_info.status == TargetStatus.TELEPORTED
        assert [v.object_id for v in target.target_manager.voyeur_table] == [tracker.id]


class TestTimestamps:
    def test_is_newer_wraps_at_half_the_range(self) -> None:
        # |new - old| > 0x7FFF reads the other way round (acclient.c:143008-143011).
        assert is_newer(10, 11) and not is_newer(11, 10) and not is_newer(10, 10)
        assert is_newer(0xFFF0, 5) and not is_newer(5, 0xFFF0)
        assert is_newer(0, 0x7FFF) and not is_newer(0, 0x8000)

    def test_newer_event_stores_the_new_stamp(self, world: World) -> None:
        b = PhysicsObj(world, "b")
        # newer_event stores the stamp when newer (acclient.c:143028-143031), else leaves it.
        assert b.newer_event(TELEPORT, 7)
        assert b.update_times[TELEPORT] == 7
        assert not b.newer_event(TELEPORT, 7)
        assert not b.newer_event(TELEPORT, 6)
        assert b.update_times[TELEPORT] == 7

    def test_bad_stamps_are_refused(self, world: World) -> None:
        b = PhysicsObj(world, "b")
        with pytest.raises(ValueError, match="16-bit"):
            b.newer_event(TELEPORT, 0x10000)
        with pytest.raises(ValueError, match="16-bit"):
            b.move_or_teleport(at(96.0, 96.0), -1, True, Vector3())


class TestMoveOrTeleport:
    @pytest.fixture
    def body(self, world: World) -> PhysicsObj:
        world.set_flat_ground(LANDBLOCK, GROUND)
        b = walker(world, "mover", 96.0, 96.0)
        b.update_times[TELEPORT] = 10
        b.player_distance = 20.0
        return b

    def test_an_older_teleport_stamp_is_ignored(self, body: PhysicsObj) -> None:
        # is_newer(stamp, update_times[TELEPORT]) -> return 0 (acclient.c:323463-323468).
        assert body.move_or_teleport(at(110.0, 96.0), 9, True, Vector3()) is False
        assert body.position.frame.origin.x == 96.0
        assert not body.is_interpolating()
        assert body.update_times[TELEPORT] == 10

    def test_a_newer_stamp_teleports_and_is_stored(self, body: PhysicsObj, world: World) -> None:
        owner = walker(world, "owner", 100.0, 96.0)
        body.stick_to_object(owner.id)
        body.interpolate_to(at(97.0, 96.0), False)
        # newer_event(TELEPORT_TS) (acclient.c:323469) stores 11; teleport_hook (323471) ends the stick and
        # the interpolation; SetPosition with 0x1012 (323474-323475) places the body at p (no contact
        # needed).
        assert body.move_or_teleport(at(130.0, 140.0), 11, False, Vector3()) is True
        assert body.update_times[TELEPORT] == 11
        assert body.get_sticky_object_id() == 0 and not body.is_interpolating()
        assert (body.position.frame.origin.x, body.position.frame.origin.y) == (130.0, 140.0)
        assert body.position.objcell_id == at(130.0, 140.0).objcell_id
        # ACE divergence: ACE's newer_event never stores the stamp, so a repeat of stamp 11 teleports again
        # there; retail's stored 11 sends the repeat down the interpolation branch (323481-323493).
        assert body.move_or_teleport(at(131.0, 140.0), 11, True, Vector3()) is True
        assert body.is_interpolating()
        assert body.position.frame.origin.x == 130.0

    def test_a_wrapped_stamp_is_newer(self, body: PhysicsObj) -> None:
        body.update_times[TELEPORT] = 0xFFF0
        # 5 - 0xFFF0 is beyond 0x7FFF, so 5 is newer (acclient.c:143024-143025).
        assert body.move_or_teleport(at(120.0, 96.0), 5, False, Vector3()) is True
        assert body.update_times[TELEPORT] == 5
        assert body.position.frame.origin.x == 120.0

    def test_the_teleport_slides_out_of_an_overlap(self, body: PhysicsObj, world: World) -> None:
        # A body standing where the teleport lands: SetFlags(0x1012) includes SLIDE (acclient.c:323474), so
        # placement may push the mover aside. ACE divergence: ACE places with Teleport | DontCreateCells
        # (no SLIDE), so CheckPositionInternal demands it stay within 0.05 m (319180) and the move fails.
        walker(world, "squatter", 120.0, 96.0)
        assert body.move_or_teleport(at(120.0, 96.0), 11, False, Vector3()) is True
        # Placed, but pushed clear of the squatter's sphere, well beyond the 0.05-m no-slide tolerance.
        moved = body.position.get_offset(at(120.0, 96.0)).length()
        assert 0.05 < moved < 2.0
        assert body.position.frame.origin.y > 96.05

    def test_a_body_without_a_cell_teleports_on_the_same_stamp(self, body: PhysicsObj) -> None:
        body.leave_world()
        assert body.cell is None
        # newer_event(10) is false but !cell (acclient.c:323469) still teleports.
        assert body.move_or_teleport(at(100.0, 100.0), 10, False, Vector3()) is True
        assert body.cell is not None
        assert body.position.frame.origin.x == 100.0

    def test_same_stamp_without_contact_is_ignored(self, body: PhysicsObj) -> None:
        # if (!contact) return 0 (acclient.c:323481-323482).
        assert body.move_or_teleport(at(100.0, 96.0), 10, False, Vector3()) is False
        assert not body.is_interpolating()
        assert body.position.frame.origin.x == 96.0

    def test_near_the_player_it_interpolates(self, body: PhysicsObj) -> None:
        # player_distance < 96 -> InterpolateTo(p, IsMovingTo()) (acclient.c:323483, 323493-323494): the
        # body has not moved yet but is gliding to p.
        assert body.move_or_teleport(at(100.0, 96.0), 10, True, Vector3()) is True
        assert body.is_interpolating()
        assert body.position.frame.origin.x == 96.0

    def test_far_from_the_player_it_snaps(self, body: PhysicsObj) -> None:
        body.interpolate_to(at(97.0, 96.0), False)
        # The threshold is the body's distance to the player, not to p: 96.0 itself snaps
        # (player_distance >= 96.0, acclient.c:323483): StopInterpolating then SetPositionSimple(p, 1)
        # (323486-323488).
        body.player_distance = MOVE_OR_TELEPORT_SNAP_DISTANCE
        assert body.move_or_teleport(at(100.0, 96.0), 10, True, Vector3()) is True
        assert not body.is_interpolating()
        assert body.position.frame.origin.x == 100.0
        body.player_distance = 95.99
        assert body.move_or_teleport(at(104.0, 96.0), 10, True, Vector3()) is True
        assert body.is_interpolating()
        assert body.position.frame.origin.x == 100.0
