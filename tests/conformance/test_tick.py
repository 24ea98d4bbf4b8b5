"""One step: UpdateObjectInternal, UpdatePositionInternal, set_frame and the commit, against retail."""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.hooks import FPHook, HookType
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.transition.collision_info import CollisionInfo
from support import place

#: The quantum as UpdateObjectInternal receives it: a ``float`` parameter (acclient.c:322719).
DT = f32(1.0 / 30.0)
#: One float32 ulp of a coordinate between 64 and 128 m: positions are stored as floats, so a
#: value derived in exact arithmetic is met to within this.
ULP_96 = 2.0**-17
#: Quaternion components are float32 (Frame::set_rotate); Frame::grotate's own rounding is
#: pinned by the math tests, here a few float32 ulps are allowed.
QUAT_TOL = 1e-7
#: A compass heading read back from a float32 quaternion, in degrees.
HEADING_TOL = 1e-4


class _CountingSweeps:
    """Wraps a body's transition() to count the sweeps UpdateObjectInternal asks for."""

    def __init__(self, body) -> None:
        self.calls = 0
        original = body.transition

        def counted(*args, **kwargs):
            self.calls += 1
            return original(*args, **kwargs)

        body.transition = counted


class TestUnchangedOrigin:
    """UpdateObjectInternal @ 0x005156B0 (acclient.c:322718): the origin test at 322781-322795."""

    def test_an_unchanged_origin_skips_the_sweep_and_keeps_contact(self, world):
        # Velocity 0 on walkable ground: the candidate origin equals the current one, so no
        # transition: set_frame(new rotation), cached_velocity = 0. A sweep in this empty world
        # would have found no contact plane and cleared CONTACT.
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.omega = Vector3(0.0, 0.0, 1.0)  # set after calc_acceleration, so it survives
        sweeps = _CountingSweeps(body)
        body.update_object_internal(DT)
        assert sweeps.calls == 0
        assert body.transient_state & TS.CONTACT
        assert body.position.frame.qz == pytest.approx(math.sin(0.5 * DT), abs=QUAT_TOL)
        assert body.cached_velocity.exactly_equals(Vector3())

    def test_a_move_within_epsilon_counts_as_unchanged_and_is_discarded(self, world):
        # AC1Legacy::Vector3::operator== (acclient.c:311682) is |a - b| <= EPSILON per axis.
        # Root motion of 0.003 m/s for 1/30 s moves 0.0001 m: unchanged, and the old origin is
        # written back exactly (acclient.c:322783-322787).
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.part_array.sequence.set_velocity(Vector3(0.0, 0.003, 0.0))
        sweeps = _CountingSweeps(body)
        body.update_object_internal(DT)
        assert sweeps.calls == 0
        assert body.position.frame.origin.y == 96.0

    def test_a_real_move_is_swept(self, world):
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.part_array.sequence.set_velocity(Vector3(0.0, 3.0, 0.0))
        sweeps = _CountingSweeps(body)
        body.update_object_internal(DT)
        assert sweeps.calls == 1
        assert body.position.frame.origin.y == pytest.approx(96.1, abs=ULP_96)
        # The empty world has no ground: SetPositionInternal clears CONTACT and ON_WALKABLE and
        # reports leaving the ground (acclient.c:322604-322613).
        assert not body.transient_state & (TS.CONTACT | TS.ON_WALKABLE)
        assert body.step_events == ["leave_ground"]
        assert body.acceleration.z < 0.0


class TestNoSpheres:
    """UpdateObjectInternal's no-sphere branch (acclient.c:322847-322866)."""

    def test_keeps_its_origin_while_turning(self, world):
        body = place(world, spheres=False, state=PS(0))
        body.velocity = Vector3(1.0, 0.0, 0.0)
        body.omega = Vector3(0.0, 0.0, 2.0)
        body.update_object_internal(f32(0.1))
        frame = body.position.frame
        assert frame.origin.exactly_equals(Vector3(96.0, 96.0, 50.0))
        assert frame.qz == pytest.approx(math.sin(0.1), abs=QUAT_TOL)
        assert body.cached_velocity.exactly_equals(Vector3())
        # The velocity itself was still integrated (UpdatePhysicsInternal ran).
        assert body.velocity.x == 1.0

    def test_on_walkable_ground_without_a_movement_manager_it_deactivates(self, world):
        body = place(world, spheres=False, state=PS(0), on_ground=True)
        body.update_object_internal(DT)
        assert not body.transient_state & TS.ACTIVE

    def test_in_the_air_it_stays_active(self, world):
        body = place(world, spheres=False, state=PS(0))
        body.update_object_internal(DT)
        assert body.transient_state & TS.ACTIVE


class TestInactiveAndCellless:
    def test_an_inactive_body_does_not_move(self, world):
        # The whole active path is gated on ACTIVE_TS (acclient.c:322758).
        body = place(world, state=PS.GRAVITY)
        body.velocity = Vector3(0.0, 0.0, -5.0)
        body.set_active(False)
        body.update_object_internal(DT)
        assert body.position.frame.origin.z == 50.0
        assert body.velocity.z == -5.0

    def test_a_stationary_body_without_a_movement_manager_deactivates_on_walkable_ground(self, world):
        # UpdatePhysicsInternal: velocity_mag2 <= 0, no movement_manager, ON_WALKABLE → clear
        # ACTIVE (acclient.c:317731-317735).
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.update_object_internal(DT)
        assert not body.transient_state & TS.ACTIVE


class TestSetFrame:
    """CPhysicsObj::set_frame @ 0x00514090 (acclient.c:321327)."""

    def test_a_nan_quaternion_with_a_sound_origin_is_committed_as_zero(self, world):
        body = place(world, state=PS(0))
        bad = Frame(Vector3(10.0, 20.0, 30.0))
        bad.qw = math.nan
        body.set_frame(bad)
        frame = body.position.frame
        assert (frame.qw, frame.qx, frame.qy, frame.qz) == (0.0, 0.0, 0.0, 0.0)
        assert frame.origin.exactly_equals(Vector3(10.0, 20.0, 30.0))

    def test_the_zero_quaternion_becomes_identity_on_the_next_step(self, world):
        # Frame::combine → set_rotate(0, 0, 0, 0) normalises to NaN, IsValid fails and the
        # candidate keeps its identity rotation (Frame::set_rotate, acclient.c:357062).
        body = place(world, spheres=False, state=PS(0))
        bad = body.position.frame.copy()
        bad.qz = math.nan
        body.set_frame(bad)
        body.update_object_internal(DT)
        frame = body.position.frame
        assert (frame.qw, frame.qx, frame.qy, frame.qz) == (1.0, 0.0, 0.0, 0.0)

    def test_an_unnormalised_but_finite_quaternion_is_committed_as_given(self, world):
        # IsValid fails (norm 4) but IsValidExceptForHeading needs a NaN: no reset.
        body = place(world, state=PS(0))
        odd = Frame(Vector3(1.0, 2.0, 3.0))
        odd.qw = 2.0
        body.set_frame(odd)
        assert body.position.frame.qw == 2.0


class TestHeadingAlignment:
    """UpdateObjectInternal: ALIGNPATH, else SLEDDING with velocity (acclient.c:322800-322810)."""

    def test_align_path_faces_the_position_delta(self, world):
        body = place(world, state=PS.ALIGN_PATH)
        body.velocity = Vector3(-2.0, 2.0, 0.0)  # moving north-west
        body.update_object_internal(DT)
        assert body.position.frame.get_heading() == pytest.approx(315.0, abs=HEADING_TOL)

    def test_sledding_faces_the_velocity(self, world):
        body = place(world, state=PS.SLEDDING)
        body.velocity = Vector3(3.0, 0.0, 0.0)  # east
        body.update_object_internal(DT)
        assert body.position.frame.get_heading() == pytest.approx(90.0, abs=HEADING_TOL)

    def test_align_path_wins_over_sledding(self, world):
        # Root motion 1 m north this step while the velocity points east: ALIGNPATH faces the
        # delta (mostly north), not the velocity (due east). The sled's 3 m/s on flat ground
        # decays by the body friction (calc_friction) before moving it east.
        body = place(world, state=PS.ALIGN_PATH | PS.SLEDDING, on_ground=True)
        body.part_array.sequence.set_velocity(Vector3(0.0, 30.0, 0.0))
        body.velocity = Vector3(3.0, 0.0, 0.0)
        body.update_object_internal(DT)
        # The delta is a difference of float32 origins near 96 m (ulp 7.6e-6), so the 0.09-m
        # east step is known to about 1e-4 of itself: the heading faces the committed delta
        # (to the heading's own float32 rounding), which is the exact-arithmetic delta to 0.01°.
        origin = body.position.frame.origin
        committed = math.degrees(math.atan2(origin.x - 96.0, origin.y - 96.0))
        assert body.position.frame.get_heading() == pytest.approx(committed, abs=HEADING_TOL)
        east = 3.0 * (1.0 - 0.949999988079071) ** DT * DT
        delta_heading = math.degrees(math.atan2(east, 1.0))
        assert body.position.frame.get_heading() == pytest.approx(delta_heading, abs=1e-2)


class TestRootMotion:
    """UpdatePositionInternal @ 0x00512C30 (acclient.c:319988): root motion at 320009-320026."""

    def test_root_motion_is_scaled_by_m_scale_on_walkable_ground(self, world):
        body = place(world, state=PS.GRAVITY, on_ground=True, heading=90.0)
        body.scale = 2.0
        body.part_array.sequence.set_velocity(Vector3(0.0, 3.0, 0.0))  # body-local forward
        body.update_object_internal(f32(0.1))
        # 3 m/s · 0.1 s · scale 2 = 0.6 m along the facing (east), rotated by Frame::combine;
        # the scaled offset and the origins are floats (acclient.c:320016-320019).
        assert body.position.frame.origin.x == pytest.approx(96.6, abs=ULP_96)
        assert body.position.frame.origin.y == pytest.approx(96.0, abs=ULP_96)

    def test_root_motion_translation_is_zero_in_the_air_but_its_rotation_applies(self, world):
        body = place(world, state=PS(0))
        body.part_array.sequence.set_velocity(Vector3(0.0, 3.0, 0.0))
        body.part_array.sequence.set_omega(Vector3(0.0, 0.0, 1.0))
        body.update_object_internal(f32(0.1))
        assert body.position.frame.origin.exactly_equals(Vector3(96.0, 96.0, 50.0))
        assert body.position.frame.qz == pytest.approx(math.sin(0.05), abs=QUAT_TOL)

    def test_hidden_skips_root_motion_and_integration(self, world):
        body = place(world, state=PS.GRAVITY | PS.HIDDEN, on_ground=True)
        body.part_array.sequence.set_velocity(Vector3(0.0, 3.0, 0.0))
        body.velocity = Vector3(1.0, 0.0, 0.0)
        body.update_object_internal(0.1)
        assert body.position.frame.origin.exactly_equals(Vector3(96.0, 96.0, 50.0))
        assert body.velocity.x == 1.0  # not even friction ran

    def test_hooks_run_even_when_hidden(self, world):
        body = place(world, state=PS.HIDDEN)
        body.set_scale(3.0, delta=1.0)
        world.physics_time = 0.5
        body.update_object_internal(DT)
        assert body.scale == pytest.approx(2.0, abs=1e-12)


class TestHooks:
    """process_hooks @ 0x00511550 (acclient.c:318640) and FPHook::Execute @ 0x0051BAA0 (329694)."""

    def test_a_scale_tween_interpolates_and_is_dropped_when_done(self, world):
        body = place(world, state=PS(0))
        world.physics_time = 1.0
        body.set_scale(2.0, delta=0.5)  # from 1.0 at t=1.0 to 2.0 at t=1.5
        world.physics_time = 1.25
        body.process_hooks()
        assert body.scale == pytest.approx(1.5, abs=1e-12)
        assert len(body.hooks) == 1
        world.physics_time = 1.6
        body.process_hooks()
        assert body.scale == 2.0
        assert body.hooks == []

    def test_a_delta_under_epsilon_scales_at_once(self, world):
        # SetScale: delta < 0.00019999999 → m_scale = new_scale, no hook (acclient.c:320621).
        body = place(world, state=PS(0))
        body.set_scale(0.5, delta=0.0001)
        assert body.scale == 0.5
        assert body.hooks == []

    def test_new_hooks_go_to_the_head_of_the_list(self, world):
        body = place(world, state=PS(0))
        body.set_scale(2.0, delta=1.0)
        body.hooks.insert(0, FPHook(HookType.TRANSLUCENCY, 0.0, 1.0, 0.0, 1.0))
        body.set_scale(3.0, delta=1.0)
        kinds = [hook.hook_type for hook in body.hooks]
        assert kinds == [HookType.SCALE, HookType.TRANSLUCENCY, HookType.SCALE]


class TestHandleAllCollisions:
    """CPhysicsObj::handle_all_collisions @ 0x00514780 (acclient.c:321807)."""

    def _info(self, normal: Vector3 | None = None, frames: int = 0) -> CollisionInfo:
        info = CollisionInfo()
        if normal is not None:
            info.collision_normal_valid = True
            info.collision_normal = normal
        info.frames_stationary_fall = frames
        return info

    def test_bounce_reflects_the_approaching_component_with_elasticity(self, world):
        # v += -(v·n)(1 + e) n when v·n < 0 (acclient.c:321876-321886); e is float32 0.05, and
        # the z term of the impulse is spilled (ST28_4) before it is added to the stored z.
        body = place(world, state=PS(0))
        body.set_elasticity(0.05)
        body.velocity = Vector3(3.0, 0.0, -4.0)
        body.handle_all_collisions(self._info(Vector3(0.0, 0.0, 1.0)), False, False)
        assert body.velocity.x == 3.0
        impulse = -(-4.0 * (f32(0.05) + 1.0))
        assert body.velocity.z == f32(f32(impulse * 1.0) + -4.0)
        assert body.velocity.z == pytest.approx(-4.0 + 4.0 * 1.05, abs=1e-6)

    def test_no_bounce_when_moving_away(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(0.0, 0.0, 2.0)
        body.handle_all_collisions(self._info(Vector3(0.0, 0.0, 1.0)), False, False)
        assert body.velocity.z == 2.0

    def test_inelastic_stops_dead(self, world):
        body = place(world, state=PS.INELASTIC)
        body.velocity = Vector3(3.0, 0.0, -4.0)
        body.handle_all_collisions(self._info(Vector3(0.0, 0.0, 1.0)), False, False)
        assert body.velocity.exactly_equals(Vector3())

    def test_walkable_to_walkable_does_not_bounce(self, world):
        body = place(world, state=PS(0), on_ground=True)
        body.velocity = Vector3(3.0, 0.0, -4.0)
        body.handle_all_collisions(self._info(Vector3(0.0, 0.0, 1.0)), True, True)
        assert body.velocity.z == -4.0

    def test_walkable_to_walkable_sledding_still_bounces(self, world):
        body = place(world, state=PS.SLEDDING, on_ground=True)
        body.velocity = Vector3(0.0, 0.0, -4.0)
        body.handle_all_collisions(self._info(Vector3(0.0, 0.0, 1.0)), True, True)
        assert body.velocity.z > 0.0

    def test_two_stationary_frames_zero_velocity_and_set_stationary_stop(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(3.0, 0.0, -4.0)
        body.handle_all_collisions(self._info(Vector3(0.0, 0.0, 1.0), frames=2), False, False)
        assert body.velocity.exactly_equals(Vector3())
        assert body.transient_state & TS.STATIONARY_STOP

    def test_three_stationary_frames_clear_the_stationary_bits(self, world):
        # frames == 3 jumps to the mask 0xFFFFFF8F (acclient.c:321896-321899).
        body = place(world, state=PS(0))
        body.transient_state |= TS.STATIONARY_FALL | TS.STATIONARY_STOP
        body.handle_all_collisions(self._info(frames=3), False, False)
        assert not body.transient_state & (TS.STATIONARY_FALL | TS.STATIONARY_STOP | TS.STATIONARY_STUCK)

    def test_one_stationary_frame_adds_stationary_fall(self, world):
        body = place(world, state=PS(0))
        body.transient_state |= TS.STATIONARY_STOP
        body.handle_all_collisions(self._info(frames=1), False, False)
        assert body.transient_state & TS.STATIONARY_FALL
        assert body.transient_state & TS.STATIONARY_STOP  # OR-ed in, not replaced

    def test_landing_on_walkable_ground_reports_an_environment_collision(self, world):
        body = place(world, state=PS.REPORT_COLLISIONS | PS.MISSILE | PS.ALIGN_PATH, on_ground=True)
        assert body.handle_all_collisions(self._info(), False, False) is True
        assert body.step_events == ["collision:environment"]
        assert body.colliding_with_environment
        # report_environment_collision drops MISSILE|ALIGNPATH|PATHCLIPPED (acclient.c:320214).
        assert not body.state & (PS.MISSILE | PS.ALIGN_PATH)


class TestCellCrossing:
    def test_a_body_crossing_the_seam_is_rehomed_into_the_next_landblock(self, world):
        # The sweep's position is re-homed with LandDefs::adjust_to_outside (acclient.c:467433).
        body = place(world, state=PS(0), origin=(191.95, 100.0, 55.0))
        body.velocity = Vector3(3.0, 0.0, 0.0)
        body.update_object_internal(DT)
        assert body.position.objcell_id == 0xAAB40005  # cx 0, cy 4 → 1 + 0 + 4
        # The candidate x is float32 near 192 m (acclient.c:317766-317767), re-homed exactly by
        # 192 m: 0.05 m and a float32 ulp at 192 (1.5e-5) off.
        x0 = f32(191.95)
        x1 = f32(f32(DT * 3.0 + 0.0) + x0)
        assert body.position.frame.origin.x == x1 - 192.0
        assert body.position.frame.origin.x == pytest.approx(0.05, abs=2.0**-16)
        assert body.cell is world.get_cell(0xAAB40005)
        assert body in body.cell.objects
        # Position::get_offset across the seam (x: block + origin - start, stored once), times the
        # unrounded reciprocal of the quantum for x (acclient.c:146876-146883).
        offset_x = f32(192.0 + (x1 - 192.0) - x0)
        assert body.cached_velocity.x == f32((1.0 / DT) * offset_x)
        assert body.cached_velocity.x == pytest.approx(3.0, abs=1e-3)

    def test_a_move_off_the_edge_of_the_world_fails_and_keeps_the_origin(self, world):
        # No cell holds the candidate (lcoord x = -1, LandDefs::get_outside_lcoord): the sweep
        # fails and UpdateObjectInternal keeps the old origin (acclient.c:322833-322845).
        from acphys.math.cell_id import outdoor_cell_id
        from acphys.math.frame import Frame
        from acphys.math.position import Position

        body = place(world, state=PS(0))
        point = Vector3(0.1, 5.0, 50.0)
        assert body.enter_world(Position(outdoor_cell_id(0x0000, point), Frame(point)))
        body.velocity = Vector3(-6.0, 0.0, 0.0)
        body.update_object_internal(DT)
        assert body.position.objcell_id == 0x00000001
        assert body.position.frame.origin.exactly_equals(point)
        assert body.cached_velocity.exactly_equals(Vector3())


class TestSetVelocity:
    """CPhysicsObj::set_velocity @ 0x005113F0 (acclient.c:318577)."""

    def test_clamps_to_50_and_activates_with_a_resync(self, world):
        body = place(world, state=PS(0))
        body.set_active(False)
        world.cur_time = 3.0
        body.set_velocity(Vector3(0.0, 60.0, 80.0))
        # AC1Legacy::Vector3::normalize stores each component, then each is stored times 50
        # (acclient.c:318597-318600): float32(0.6) · 50 is not 30.
        assert body.velocity.y == f32(50.0 * f32(1.0 / 100.0 * 60.0))
        assert body.velocity.z == f32(50.0 * f32(1.0 / 100.0 * 80.0))
        assert body.velocity.y == pytest.approx(30.0, abs=1e-5)
        assert body.velocity.z == pytest.approx(40.0, abs=1e-5)
        assert body.transient_state & TS.ACTIVE
        assert body.update_time == 3.0
        assert body.jumped_this_frame

    def test_set_local_velocity_rotates_into_the_world(self, world):
        # set_local_velocity @ 0x005114D0 (acclient.c:318617): m_fl2gv · v, then set_velocity.
        body = place(world, state=PS(0), heading=90.0)  # facing east
        body.set_local_velocity(Vector3(0.0, 2.0, 0.0))  # 2 m/s forward
        # The float32 matrix of a 90° heading (Frame::cache) is 6e-8 off a pure rotation.
        m = body.position.frame.m
        assert body.velocity.exactly_equals(Vector3(m[3] * 2.0, m[4] * 2.0, m[5] * 2.0))
        assert body.velocity.x == pytest.approx(2.0, abs=1e-6)
        assert body.velocity.y == pytest.approx(0.0, abs=1e-6)

    def test_rejects_nan(self, world):
        body = place(world, state=PS(0))
        with pytest.raises(ValueError, match="velocity must be finite"):
            body.set_velocity(Vector3(math.nan, 0.0, 0.0))

    def test_set_elasticity_clamps_to_the_retail_range(self, world):
        # set_elasticity @ 0x0050FD40 (acclient.c:317060): <0 → 0, >0.1 → float32 0.1.
        body = place(world, state=PS(0))
        body.set_elasticity(-1.0)
        assert body.elasticity == 0.0
        body.set_elasticity(0.5)
        assert body.elasticity == pytest.approx(0.1, abs=1e-8)
