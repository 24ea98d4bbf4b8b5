"""The clock: CPhysicsObj::update_object's time slicing and gates, and CPhysics::UseTime."""

from __future__ import annotations

import pytest

from acphys.constants import MIN_QUANTUM
from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.simulation import Physics, Simulation, driver_tick_seconds, object_table_bucket
from support import LANDBLOCK, human_setup, place


def _quanta(body) -> list[float]:
    """Record every quantum update_object hands to update_object_internal.

    UpdateObjectInternal takes a ``float quantum`` (acclient.c:322718), so each
    recorded step is the float32 of the double slice update_object computed.
    """
    seen: list[float] = []
    body.observer = lambda _body, quantum: seen.append(quantum)
    return seen


class TestTimeSlicing:
    """CPhysicsObj::update_object @ 0x00515D10 (acclient.c:323080), lines 323117-323150."""

    @pytest.mark.parametrize(
        ("elapsed", "steps", "update_time"),
        [
            # dt ≤ EPSILON: no step, resync update_time to cur_time (acclient.c:323146-323149).
            (0.0001, [], 0.0001),
            # dt ≤ MAX_QUANTUM: one step of dt, whatever its size (goto LABEL_21, 323125).
            (0.05, [0.05], 0.05),
            (0.01, [0.01], 0.01),
            (0.2, [0.2], 0.2),
            # dt > MAX_QUANTUM: 0.2-s steps while more than 0.2 remains, then the rest only if
            # it exceeds MIN_QUANTUM (323127-323139): 0.5 = 0.2 + 0.2 + 0.1.
            (0.5, [0.2, 0.2, 0.1], 0.5),
            # 0.21 = 0.2 + 0.01; 0.01 ≤ 1/30 is not integrated and update_time stays at 0.2,
            # so the 0.01 s is carried into the next update (323140-323142).
            (0.21, [0.2], 0.2),
            # dt > 2.0: dropped, update_time = cur_time (323143-323145).
            (2.5, [], 2.5),
        ],
    )
    def test_slices(self, world, elapsed, steps, update_time):
        body = place(world, state=PS(0))
        seen = _quanta(body)
        world.cur_time = elapsed
        body.update_object()
        assert seen == pytest.approx([f32(step) for step in steps], abs=1e-12)
        assert body.update_time == pytest.approx(update_time, abs=1e-12)

    def test_the_physics_timer_advances_with_each_slice(self, world):
        # PhysicsTimer::curr_time starts at update_time and grows by each quantum before the step.
        body = place(world, state=PS(0))
        times: list[float] = []
        body.observer = lambda _body, _q: times.append(world.physics_time)
        world.cur_time = 0.5
        body.update_object()
        assert times == pytest.approx([0.2, 0.4, 0.5], abs=1e-12)

    def test_the_carried_remainder_is_integrated_next_time(self, world):
        body = place(world, state=PS(0))
        seen = _quanta(body)
        world.cur_time = 0.21
        body.update_object()
        world.cur_time = 0.25
        body.update_object()
        assert seen == pytest.approx([f32(0.2), f32(0.05)], abs=1e-12)

    def test_a_dropped_interval_moves_nothing(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(1.0, 0.0, 0.0)
        world.cur_time = 2.5
        body.update_object()
        assert body.position.frame.origin.x == 96.0


class TestGates:
    """update_object's gate (acclient.c:323099-323101) and activity cull (323103-323116)."""

    @pytest.mark.parametrize("gate", ["parented", "frozen", "no cell"])
    def test_a_gated_body_is_deactivated_and_not_run(self, world, gate):
        # `if (parent || !cell || state & FROZEN_PS) transient_state &= ~ACTIVE_TS` (acclient.c:323099).
        body = place(world, state=PS.FROZEN if gate == "frozen" else PS(0))
        if gate == "parented":
            body.parent = place(world, name="carrier", state=PS(0))
        elif gate == "no cell":
            body.change_cell(None)
        seen = _quanta(body)
        world.cur_time = 0.1
        body.update_object()
        assert seen == []
        assert not body.transient_state & TS.ACTIVE

    def test_beyond_96_m_from_the_player_a_body_is_deactivated(self, world):
        player = place(world, name="player", state=PS(0), origin=(10.0, 10.0, 50.0))
        far = place(world, name="far", state=PS(0), origin=(10.0, 106.5, 50.0))
        world.player = player
        world.cur_time = 0.05
        far.update_object()
        assert far.player_distance == pytest.approx(96.5, abs=1e-12)
        assert not far.transient_state & TS.ACTIVE

    def test_the_cull_measures_across_landblocks(self, world):
        # Position::get_offset adds the block offset (Δblock × 192 m, LandDefs::get_block_offset).
        from acphys.math.cell_id import outdoor_cell_id
        from acphys.math.frame import Frame
        from acphys.math.position import Position

        player = place(world, name="player", state=PS(0), origin=(190.0, 10.0, 50.0))
        other = place(world, name="other", state=PS(0))
        point = Vector3(5.0, 10.0, 50.0)
        other.enter_world(Position(outdoor_cell_id(0xAAB4, point), Frame(point)))
        world.player = player
        world.cur_time = 0.05
        other.update_object()
        assert other.player_vector.x == pytest.approx(7.0, abs=1e-12)
        assert other.transient_state & TS.ACTIVE

    def test_within_96_m_an_inactive_body_is_activated_and_resynced(self, world):
        # set_active(1) on an inactive body sets update_time = cur_time (acclient.c:316990), so
        # the elapsed time is 0 and nothing is integrated this call.
        player = place(world, name="player", state=PS(0))
        near = place(world, name="near", state=PS(0), origin=(96.0, 150.0, 50.0))
        near.set_active(False)
        world.player = player
        seen = _quanta(near)
        world.cur_time = 0.1
        near.update_object()
        assert near.transient_state & TS.ACTIVE
        assert near.update_time == 0.1
        assert seen == []

    def test_without_a_player_activity_is_left_alone(self, world):
        body = place(world, state=PS(0))
        body.set_active(False)
        seen = _quanta(body)
        world.cur_time = 0.1
        body.update_object()
        # Still sliced and stepped (UpdateObjectInternal's inactive path), but not activated.
        assert seen == pytest.approx([0.1])
        assert not body.transient_state & TS.ACTIVE

    def test_the_cull_is_off_when_object_maintenance_is_inactive(self, world):
        player = place(world, name="player", state=PS(0))
        far = place(world, name="far", state=PS(0), origin=(96.0, 96.0, 200.0))
        world.player = player
        world.activity_cull = False
        world.cur_time = 0.05
        far.update_object()
        assert far.transient_state & TS.ACTIVE


class TestSetActive:
    """CPhysicsObj::set_active @ 0x0050FC40 (acclient.c:316979)."""

    def test_a_static_body_cannot_be_activated(self, world):
        body = place(world, state=PS.STATIC)
        body.set_active(False)
        assert body.set_active(True) is False
        assert not body.transient_state & TS.ACTIVE

    def test_activating_an_active_body_keeps_its_update_time(self, world):
        body = place(world, state=PS(0))
        world.cur_time = 1.0
        assert body.set_active(True) is True
        assert body.update_time == 0.0


class TestUseTime:
    """CPhysics::UseTime @ 0x00509950 (acclient.c:311334): `quantum >= MIN_QUANTUM_93` (311352)."""

    def test_bodies_run_only_after_min_quantum(self, world):
        body = place(world, state=PS(0))
        physics = Physics(world)
        physics.add(body)
        seen = _quanta(body)
        world.cur_time = 0.02
        assert physics.use_time() is False
        world.cur_time = MIN_QUANTUM - 1e-9
        assert physics.use_time() is False
        assert seen == []
        world.cur_time = MIN_QUANTUM
        assert physics.use_time() is True
        assert seen == [f32(MIN_QUANTUM)]
        assert physics.last_update == MIN_QUANTUM

    def test_a_clock_that_goes_backwards_resyncs(self, world):
        physics = Physics(world)
        world.cur_time = 5.0
        physics.last_update = 5.0
        world.cur_time = 4.0
        assert physics.use_time() is False
        assert physics.last_update == 4.0

    def test_a_60_hz_driver_runs_bodies_at_30_hz(self, world):
        body = place(world, state=PS(0))
        sim = Simulation(world, [body], driver_hz=60.0, duration=1.0)
        seen = _quanta(body)
        sim.run()
        assert len(seen) == 30
        assert seen == pytest.approx([2 * driver_tick_seconds(60.0)] * 30, abs=1e-15)
        assert min(seen) >= MIN_QUANTUM

    def test_a_25_hz_driver_runs_bodies_every_tick(self, world):
        body = place(world, state=PS(0))
        sim = Simulation(world, [body], driver_hz=25.0, duration=1.0)
        seen = _quanta(body)
        sim.run()
        assert seen == pytest.approx([0.04] * 25, abs=1e-8)


class TestObjectTableOrder:
    """CPhysics::UseTime walks CObjectMaint::object_table (acclient.c:311372-311378).

    The table has 128 buckets with key shift 8 (CObjectMaint::CObjectMaint, acclient.c:310011):
    AddObject puts an object at the head of bucket ``127 & (id ^ (id >> 8))``
    (acclient.c:309360-309362), and HashBaseIter::Next walks a chain, then the next
    bucket up (acclient.c:263092).
    """

    @staticmethod
    def _body(world, name, object_id, x):
        body = PhysicsObj(world, name, PartArray(human_setup()), object_id)
        point = Vector3(x, 96.0, 50.0)
        assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, point), Frame.from_heading(point, 0.0)))
        return body

    @pytest.mark.parametrize(
        ("object_id", "bucket"),
        [
            # 0x50000001 ^ 0x00500000 = 0x50500001 → 0x01.
            (0x50000001, 1),
            # 0x80000080 ^ 0x00800000 = 0x80800080 → 0x80 & 0x7F = 0.
            (0x80000080, 0),
            # 0x50000181 ^ 0x00500001 = 0x50500180 → 0x180 & 0x7F = 0.
            (0x50000181, 0),
            # 0xFFFFFFFF ^ 0x00FFFFFF = 0xFF000000 → 0.
            (0xFFFFFFFF, 0),
            # 0x8000007F ^ 0x00800000 = 0x8080007F → 0x7F.
            (0x8000007F, 127),
        ],
    )
    def test_buckets(self, object_id, bucket):
        assert object_table_bucket(object_id) == bucket

    def test_bodies_run_by_bucket_and_newest_first_within_one(self, world):
        a = self._body(world, "a", 0x50000001, 90.0)  # bucket 1
        b = self._body(world, "b", 0x80000080, 94.0)  # bucket 0
        c = self._body(world, "c", 0x50000181, 98.0)  # bucket 0, added after b: ahead of it
        physics = Physics(world)
        for body in (a, b, c):
            physics.add(body)
        ran: list[str] = []
        for body in (a, b, c):
            body.observer = lambda body, _quantum: ran.append(body.name)
        world.cur_time = 0.05
        assert physics.use_time() is True
        assert ran == ["c", "b", "a"]
        assert [body.name for body in physics.objects] == ["c", "b", "a"]

    def test_ids_counting_up_from_0x80000001_run_in_the_order_they_were_added(self, world):
        # Buckets 1, 2, ... 127 for 0x80000001 .. 0x8000007F: the first 127 bodies keep their order.
        bodies = [self._body(world, f"b{i}", None, 20.0 + i) for i in range(5)]
        assert [body.id for body in bodies] == [0x80000001 + i for i in range(5)]
        physics = Physics(world)
        for body in bodies:
            physics.add(body)
        assert physics.objects == bodies

    def test_a_removed_body_is_no_longer_run(self, world):
        # CObjectMaint::DeleteObject takes it out of object_table (acclient.c:309917), the table
        # CPhysics::UseTime walks.
        kept = self._body(world, "kept", None, 90.0)
        gone = self._body(world, "gone", None, 94.0)
        physics = Physics(world)
        physics.add(kept)
        physics.add(gone)
        ran: list[str] = []
        for body in (kept, gone):
            body.observer = lambda body, _quantum: ran.append(body.name)
        world.remove_object(gone)
        world.cur_time = 0.05
        assert physics.use_time() is True
        assert ran == ["kept"]
