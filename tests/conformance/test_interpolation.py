"""InterpolationManager: gliding to server positions, blips, the progress audit, against retail.

Decompiled: cpmanager/CInterpolationManager.c (InterpolateTo acclient.c:389016, adjust_offset
389177, UseTime 389277, NodeCompleted 388881, StopInterpolating 388852).
"""

from __future__ import annotations

import pytest

from acphys.flags import TransientState as TS
from acphys.managers.interpolation import BIG_DISTANCE, InterpolationManager
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.commands import RUN_FORWARD
from acphys.precision import f32
from support import LANDBLOCK, place

DT = 1.0 / 30.0
GROUND = 50.0


@pytest.fixture
def body(world):
    world.set_flat_ground(LANDBLOCK, GROUND)
    return place(world, on_ground=True, origin=(40.0, 100.0, GROUND))


def _server_position(body, dx: float, dy: float = 0.0, heading: float = 0.0) -> Position:
    """A position ``(dx, dy)`` from the body, at its height, facing ``heading``."""
    here = body.position.frame.origin
    point = Vector3(here.x + dx, here.y + dy, here.z)
    return Position(outdoor_cell_id(LANDBLOCK, point), Frame.from_heading(point, heading))


def _distance(body, p: Position) -> float:
    return body.position.get_offset(p).length()


class TestGlide:
    def test_a_position_3m_away_is_glided_to_at_twice_the_adjusted_max_speed(self, body):
        target = _server_position(body, 3.0)
        body.interpolate_to(target, False)
        start_x = body.position.frame.origin.x
        body.update_object_internal(DT)
        # No weenie: adjusted max speed = 1.0 * 4 (acclient.c:343511); doubled (389237) = 8 m/s,
        # the step cut to 8 * quantum (389255, 389260-389263): the float locals give the step
        # f32(3 * f32(f32(8 * DT) / 3)) along x, and the body's float32 origin takes it at x = 40.
        step = f32(3.0 * f32(f32(8.0 * DT) / 3.0))
        assert body.position.frame.origin.x - start_x == f32(start_x + step) - start_x
        assert step == pytest.approx(8.0 * DT, abs=1e-7)
        assert body.is_interpolating()

    def test_the_glide_completes_within_5cm_and_the_queue_empties(self, body):
        target = _server_position(body, 3.0)
        body.interpolate_to(target, False)
        # 3 m at 8/30 m a step: 11 full steps (2.9333 m), the 12th covers the last 0.0667 m
        # (> 0.05, so no completion at 389258); the 13th finds it within 0.05 (389217) and
        # NodeCompleted(1) with nothing left stops interpolating (388928-388931).
        for _ in range(12):
            body.update_object_internal(DT)
        assert body.is_interpolating()
        assert _distance(body, target) < 0.05
        body.update_object_internal(DT)
        assert not body.is_interpolating()
        assert _distance(body, target) < 0.05

    def test_the_speed_falls_back_to_7_5_when_the_body_has_none(self, body):
        # A running body with forward_speed 0 has adjusted max speed 0 (acclient.c:343533-343534):
        # below EPSILON the speed is MAX_INTERPOLATED_VELOCITY = 7.5 (389239-389240).
        minterp = body.get_minterp()
        minterp.interpreted_state.forward_command = RUN_FORWARD
        minterp.interpreted_state.forward_speed = 0.0
        target = _server_position(body, 3.0)
        offset = Frame()
        body.interpolate_to(target, False)
        body.position_manager.adjust_offset(offset, DT)
        assert offset.origin.x == pytest.approx(7.5 * DT, abs=1e-9)

    def test_the_glide_reaches_the_caller(self, body):
        # The adjustment replaces the caller's offset (Frame::operator= at acclient.c:389267);
        # ACE assigns its parameter instead and the body never moves (RETAIL_NOTES §5).
        body.interpolate_to(_server_position(body, 3.0), False)
        offset = Frame()
        offset.origin.set(Vector3(0.0, 0.5, 0.0))  # root motion the glide discards
        body.position_manager.adjust_offset(offset, DT)
        # The 3-m adjustment cut to the step: progress_madea = f32(8 * DT), the scale
        # _rhs = f32(progress_madea / 3) and the origin f32(3 * _rhs) (acclient.c:389255-389263).
        assert offset.origin.x == f32(3.0 * f32(f32(8.0 * DT) / 3.0))
        assert offset.origin.y == 0.0

    def test_an_airborne_body_is_not_pulled(self, body):
        # adjust_offset returns without CONTACT (acclient.c:389208-389209).
        body.transient_state &= ~TS.CONTACT
        body.interpolate_to(_server_position(body, 3.0), False)
        offset = Frame()
        body.position_manager.adjust_offset(offset, DT)
        assert offset.origin.exactly_equals(Vector3())


class TestHeading:
    def test_without_keep_heading_the_body_turns_to_the_node_at_once(self, body):
        # The adjustment is the whole frame difference (Position::subtract2, acclient.c:389254);
        # only its origin is cut to the step.
        body.interpolate_to(_server_position(body, 3.0, heading=90.0), False)
        body.update_object_internal(DT)
        # The heading is read back from a float32 quaternion: within 1e-5 degrees.
        assert body.position.frame.get_heading() == pytest.approx(90.0, abs=1e-5)

    def test_keep_heading_keeps_the_body_facing_as_it_was(self, body):
        # The node takes the body's heading (389112-389115) and the adjustment's heading is
        # reset to 0 (389265-389266).
        body.interpolate_to(_server_position(body, 3.0, heading=90.0), True)
        node = body.position_manager.interpolation_manager.position_queue[0]
        assert node.frame.get_heading() == pytest.approx(0.0, abs=1e-6)
        body.update_object_internal(DT)
        assert body.position.frame.get_heading() == pytest.approx(0.0, abs=1e-6)

    def test_a_position_within_5cm_only_sets_the_heading(self, body):
        # Within 0.05 m of the body: set_heading to p's heading (unless kept) and stop
        # (acclient.c:389131-389136); nothing is queued.
        body.interpolate_to(_server_position(body, 0.03, heading=45.0), False)
        assert not body.is_interpolating()
        # The heading is read back from a float32 quaternion: within 1e-5 degrees.
        assert body.position.frame.get_heading() == pytest.approx(45.0, abs=1e-5)


class TestQueue:
    def test_the_queue_keeps_the_newest_20(self, body):
        # Before queuing, the oldest nodes go while 20 or more remain (acclient.c:389071-389097).
        for i in range(25):
            body.interpolate_to(_server_position(body, 1.0 + i), False)
        queue = body.position_manager.interpolation_manager.position_queue
        start = body.position.frame.origin.x
        assert len(queue) == 20
        assert queue[0].frame.origin.x == pytest.approx(start + 6.0)
        assert queue[-1].frame.origin.x == pytest.approx(start + 25.0)

    def test_a_trailing_node_within_5cm_is_replaced(self, body):
        # Trailing nodes closer than 0.05 m to the new position are dropped (389059-389070).
        body.interpolate_to(_server_position(body, 2.0), False)
        body.interpolate_to(_server_position(body, 3.0), False)
        body.interpolate_to(_server_position(body, 3.04), False)
        queue = body.position_manager.interpolation_manager.position_queue
        start = body.position.frame.origin.x
        assert [round(p.frame.origin.x - start, 2) for p in queue] == [2.0, 3.04]


class TestBlip:
    def test_a_position_150m_away_snaps(self, body):
        # Outdoors the blip distance is 100 m (acclient.c:315860); beyond it the node is queued
        # with node_fail_counter 4 (389164/389170), and UseTime (> 3, 389302) places the body there.
        target = _server_position(body, 150.0)
        body.interpolate_to(target, False)
        assert body.position_manager.interpolation_manager.node_fail_counter == 4
        body.update_object_internal(DT)
        assert body.position.frame.origin.x == pytest.approx(target.frame.origin.x, abs=1e-9)
        assert body.position.objcell_id == target.objcell_id
        assert not body.is_interpolating()

    def test_99m_away_still_glides(self, body):
        # 99 <= 100: the glide branch (acclient.c:389055).
        body.interpolate_to(_server_position(body, 99.0), False)
        assert body.position_manager.interpolation_manager.node_fail_counter == 0

    @pytest.mark.parametrize(
        ("cell", "is_player", "expected"),
        [(0x0004, False, 100.0), (0x0004, True, 100.0), (0x0100, False, 20.0), (0x0100, True, 25.0)],
    )
    def test_blip_distances(self, world, body, cell, is_player, expected):
        # CPhysicsObj::GetAutonomyBlipDistance (acclient.c:315860-315879).
        body.position.objcell_id = (LANDBLOCK << 16) | cell
        if is_player:
            world.player = body
        assert body.get_autonomy_blip_distance() == expected


class TestAudit:
    @staticmethod
    def _frozen(body):
        """Zero every offset with a real leash: a constraint at max 0 (acclient.c:389500-389503)."""
        body.constrain_to(body.position, 0.0, 0.0)

    def test_the_first_audit_always_passes(self, body):
        # original_distance is BIG_DISTANCE until an audit passes (388821), so the 5th frame's
        # progress is ~999996 m: passed, and original_distance becomes the current distance.
        self._frozen(body)
        target = _server_position(body, 3.0)
        body.interpolate_to(target, False)
        manager = body.position_manager.interpolation_manager
        assert manager.original_distance == BIG_DISTANCE
        for _ in range(5):
            body.update_object_internal(DT)
        assert manager.frame_counter == 0
        assert manager.original_distance == pytest.approx(_distance(body, target))

    def test_a_body_making_no_progress_fails_and_snaps(self, body):
        # Frame 10: progress 0 < EPSILON fails (389248); 3 m > 0.2, so node_fail_counter = 1 and
        # NodeCompleted(0) with nothing queued keeps the node as blipto_position (388933-388937);
        # the same tick's UseTime, with the queue empty and the count above 0 (389305-389309),
        # places the body there (389366).
        self._frozen(body)
        start = body.position.frame.origin.copy()
        target = _server_position(body, 3.0)
        body.interpolate_to(target, False)
        for _ in range(9):
            body.update_object_internal(DT)
        assert body.position.frame.origin.exactly_equals(start)
        assert body.is_interpolating()
        body.update_object_internal(DT)
        assert body.position.frame.origin.x == pytest.approx(target.frame.origin.x, abs=1e-9)
        assert not body.is_interpolating()

    def test_with_nodes_queued_the_snap_waits_for_the_fourth_failure(self, body):
        # A failed node with more queued: the next becomes the head with original_distance set
        # (388913-388917), so each fails 5 frames later. UseTime snaps to the last node only once
        # node_fail_counter > 3 (389302), at frame 10 + 3 * 5 = 25.
        self._frozen(body)
        start = body.position.frame.origin.copy()
        nodes = [_server_position(body, float(i)) for i in range(1, 6)]
        for node in nodes:
            body.interpolate_to(node, False)
        manager = body.position_manager.interpolation_manager
        for _ in range(24):
            body.update_object_internal(DT)
        assert manager.node_fail_counter == 3
        assert len(manager.position_queue) == 2
        assert body.position.frame.origin.exactly_equals(start)
        body.update_object_internal(DT)
        assert body.position.frame.origin.x == pytest.approx(nodes[-1].frame.origin.x, abs=1e-9)
        assert not body.is_interpolating()
        assert manager.node_fail_counter == 0

    def test_a_failing_node_within_20cm_counts_as_reached(self, body):
        # Failing the audit within 0.2 m is NodeCompleted(1) (acclient.c:389270-389271): no
        # failure counted, no snap. ACE lacks this branch and counts a failure.
        self._frozen(body)
        start = body.position.frame.origin.copy()
        body.interpolate_to(_server_position(body, 0.1), False)
        manager = body.position_manager.interpolation_manager
        for _ in range(10):
            body.update_object_internal(DT)
        assert not body.is_interpolating()
        assert manager.node_fail_counter == 0
        assert body.position.frame.origin.exactly_equals(start)

    def test_steady_progress_passes_the_audit(self, body):
        # Gliding at full speed closes 5 * 8/30 m in 5/30 s: ratio 1 >= 0.3 (389248).
        body.interpolate_to(_server_position(body, 10.0), False)
        manager = body.position_manager.interpolation_manager
        for _ in range(10):
            body.update_object_internal(DT)
        assert manager.frame_counter == 0
        assert manager.node_fail_counter == 0
        assert body.is_interpolating()


def test_stop_interpolating_resets_everything(body):
    # acclient.c:388856-388877.
    manager = InterpolationManager(body)
    manager.interpolate_to(_server_position(body, 150.0), False)
    manager.stop_interpolating()
    assert not manager.position_queue
    assert manager.node_fail_counter == 0
    assert manager.original_distance == BIG_DISTANCE


def test_a_non_finite_target_is_refused(body):
    bad = Position(body.position.objcell_id, Frame(Vector3(float("nan"), 0.0, 0.0)))
    with pytest.raises(ValueError, match="finite"):
        body.interpolate_to(bad, False)
