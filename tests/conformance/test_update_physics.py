"""CPhysicsObj::UpdatePhysicsInternal, calc_friction and calc_acceleration against retail.

Expected values are derived by hand from the decompiled lines cited on each
test; float32 constants are written out as the values retail holds.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.geometry.plane import Plane
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from support import place

DT = 1.0 / 30.0
#: PhysicsGlobals::gravity, float32(-9.8000002) widened (acclient_data.h:6877).
G = -9.800000190734863
#: DEFAULT_FRICTION, float32(0.94999999) widened (acclient_data.h:1430).
F = 0.949999988079071


class TestFreeFall:
    """UpdatePhysicsInternal @ 0x00510700 (acclient.c:317700)."""

    def test_first_step_from_rest_does_not_translate(self, world):
        # velocity_mag2 = 0 fails the `> 0` branch, so no `x += v*dt + a*dt²/2`;
        # the unconditional `v += a*dt` (acclient.c:317776-317780) still runs.
        body = place(world, state=PS.GRAVITY)
        body.update_object_internal(DT)
        assert body.position.frame.origin.z == 50.0
        assert body.velocity.z == pytest.approx(G * DT, abs=1e-15)
        assert body.cached_velocity.exactly_equals(Vector3())

    def test_later_steps_add_v_dt_plus_half_a_dt_squared(self, world):
        # After n steps from rest: v = n·g·dt, and step k (k ≥ 2) moves by
        # (k-1)·g·dt² + g·dt²/2, so z_n = z0 + g·dt²·(n² - 1)/2 (acclient.c:317756-317770).
        body = place(world, state=PS.GRAVITY)
        for n in range(1, 7):
            body.update_object_internal(DT)
            expected_z = 50.0 + G * DT * DT * (n * n - 1) / 2
            assert body.position.frame.origin.z == pytest.approx(expected_z, abs=1e-12)
            assert body.velocity.z == pytest.approx(n * G * DT, abs=1e-12)

    def test_cached_velocity_is_the_achieved_displacement_over_the_quantum(self, world):
        # UpdateObjectInternal (acclient.c:322816-322828): cached_velocity = offset(curr_pos) / quantum.
        body = place(world, state=PS.GRAVITY)
        body.update_object_internal(DT)
        body.update_object_internal(DT)
        # Step 2 moved by g·dt·dt + g·dt²/2 = 1.5·g·dt².
        assert body.cached_velocity.z == pytest.approx(1.5 * G * DT, abs=1e-12)
        assert body.cached_velocity.x == 0.0 and body.cached_velocity.y == 0.0


class TestTerminalVelocity:
    """UpdatePhysicsInternal: `velocity_mag2 > 50.0 * 50.0` (acclient.c:317740-317747)."""

    def test_speed_over_50_is_normalised_to_50_before_integrating(self, world):
        body = place(world, state=PS.GRAVITY)
        body.velocity = Vector3(0.0, 30.0, -60.0)  # |v| = sqrt(4500) = 67.08
        body.update_object_internal(DT)
        # Clamped: (0, 30, -60)/sqrt(4500)·50 = (0, 22.3607, -44.7214); the translation uses the
        # clamped velocity, then v += a·dt adds g·dt to z.
        scale = 50.0 / math.sqrt(4500.0)
        assert body.position.frame.origin.y == pytest.approx(96.0 + 30.0 * scale * DT, abs=1e-12)
        assert body.position.frame.origin.z == pytest.approx(
            50.0 + (-60.0 * scale * DT + G * 0.5 * DT * DT), abs=1e-12
        )
        assert body.velocity.y == pytest.approx(30.0 * scale, abs=1e-12)
        assert body.velocity.z == pytest.approx(-60.0 * scale + G * DT, abs=1e-12)

    def test_exactly_50_is_not_clamped(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(0.0, 0.0, -50.0)
        body.update_object_internal(DT)
        assert body.velocity.z == -50.0


class TestDeadband:
    """UpdatePhysicsInternal: `velocity_mag2 - 0.25 * 0.25 < EPSILON` zeroes v (acclient.c:317750)."""

    def test_just_under_the_deadband_zeroes_velocity_but_still_adds_half_a_dt2(self, world):
        # |v| = 0.2502: v² - 0.0625 = 0.0001 < 0.0002 → v = 0, then the translation still adds
        # a·dt²/2 and v += a·dt (acclient.c:317756-317780).
        body = place(world, state=PS.GRAVITY)
        body.velocity = Vector3(0.2502, 0.0, 0.0)
        body.update_object_internal(DT)
        origin = body.position.frame.origin
        assert origin.x == 96.0
        assert origin.z == pytest.approx(50.0 + G * 0.5 * DT * DT, abs=1e-12)
        assert body.velocity.x == 0.0
        assert body.velocity.z == pytest.approx(G * DT, abs=1e-15)

    def test_just_over_the_deadband_keeps_velocity(self, world):
        # |v| = 0.2505: v² - 0.0625 = 0.00025 ≥ 0.0002: kept.
        body = place(world, state=PS(0))
        body.velocity = Vector3(0.2505, 0.0, 0.0)
        body.update_object_internal(DT)
        assert body.velocity.x == 0.2505
        assert body.position.frame.origin.x == pytest.approx(96.0 + 0.2505 * DT, abs=1e-12)

    def test_the_deadband_tests_the_pre_friction_speed(self, world):
        # On walkable ground |v| = 0.26 decays by (1-f)^dt to 0.2353, under 0.25; but the test
        # reads velocity_mag2 computed before calc_friction (0.0676 - 0.0625 ≥ EPSILON): kept.
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(0.26, 0.0, 0.0)
        body.update_object_internal(DT)
        decayed = 0.26 * (1.0 - F) ** DT
        assert decayed < 0.25
        assert body.velocity.x == pytest.approx(decayed, abs=1e-12)

    def test_gravity_at_a_small_quantum_never_builds_up(self, world):
        # At dt = 1/60 the first step gives |v| = 0.1633 < 0.25, which the next step zeroes:
        # a body falls only a·dt²/2 per step. (Retail avoids such quanta: CPhysics::UseTime
        # runs bodies at most every 1/30 s.)
        body = place(world, state=PS.GRAVITY)
        small = 1.0 / 60.0
        body.update_object_internal(small)
        for step in range(2, 6):
            body.update_object_internal(small)
            assert body.position.frame.origin.z == pytest.approx(
                50.0 + (step - 1) * G * 0.5 * small * small, abs=1e-12
            )


class TestFriction:
    """CPhysicsObj::calc_friction @ 0x0050EE70 (acclient.c:316090)."""

    def test_decay_is_one_minus_f_to_the_dt_on_walkable_ground(self, world):
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(3.0, 0.0, 0.0)
        body.update_object_internal(DT)
        factor = (1.0 - F) ** DT  # pow(1.0 - friction, quantum), acclient.c:316150
        assert body.velocity.x == pytest.approx(3.0 * factor, abs=1e-12)
        # The translation uses the decayed velocity (acclient.c:317756).
        assert body.position.frame.origin.x == pytest.approx(96.0 + 3.0 * factor * DT, abs=1e-12)

    def test_no_friction_in_the_air(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(3.0, 0.0, 0.0)
        body.update_object_internal(DT)
        assert body.velocity.x == 3.0

    def test_normal_component_is_removed_before_the_decay(self):
        # v·N = 0.2 < 0.25: v -= (v·N)N, then v *= (1-f)^dt (acclient.c:316130-316152).
        from acphys.world.world import World

        body = place(World(), state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(3.0, 0.0, 0.2)
        body.calc_friction(DT, body.velocity.length_squared())
        factor = (1.0 - F) ** DT
        assert body.velocity.x == pytest.approx(3.0 * factor, abs=1e-12)
        assert body.velocity.z == 0.0

    def test_moving_away_from_the_plane_skips_friction(self, world):
        # v·N ≥ 0.25 returns before touching v (acclient.c:316133).
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(3.0, 0.0, 0.25)
        body.calc_friction(DT, body.velocity.length_squared())
        assert body.velocity.exactly_equals(Vector3(3.0, 0.0, 0.25))

    def test_friction_uses_the_contact_plane_normal(self, world):
        # A 30° slope: N = (0, -sin30, cos30). v along the slope (0, cos30, sin30)·2 has v·N = 0,
        # so only the decay applies.
        body = place(world, state=PS.GRAVITY, on_ground=True)
        s, c = math.sin(math.radians(30)), math.cos(math.radians(30))
        body.contact_plane = Plane(Vector3(0.0, -s, c), 0.0)
        body.velocity = Vector3(0.0, 2 * c, 2 * s)
        body.calc_friction(DT, 4.0)
        factor = (1.0 - F) ** DT
        assert body.velocity.y == pytest.approx(2 * c * factor, abs=1e-12)
        assert body.velocity.z == pytest.approx(2 * s * factor, abs=1e-12)


class TestSleddingFriction:
    """calc_friction's SLEDDING_PS branch (acclient.c:316098-316125)."""

    def _sled(self, world, normal: Vector3, speed: float):
        body = place(world, state=PS.GRAVITY | PS.SLEDDING, on_ground=True)
        body.contact_plane = Plane(normal, 0.0)
        # A velocity along the plane (perpendicular to N, in the y-z plane).
        along = Vector3(0.0, normal.z, -normal.y).normalized()
        body.velocity = along * speed
        return body

    def test_under_1_25_m_s_the_sled_stops_dead(self, world):
        # velocity_mag2 < 1.5625 → frict = 1.0 → pow(0, dt) = 0.
        body = self._sled(world, Vector3(0.0, 0.0, 1.0), 1.2)
        body.calc_friction(DT, 1.2 * 1.2)
        assert body.velocity.length() == 0.0

    def test_between_1_25_and_2_5_m_s_the_body_friction_applies(self, world):
        slope = math.radians(30)
        body = self._sled(world, Vector3(0.0, -math.sin(slope), math.cos(slope)), 2.0)
        body.calc_friction(DT, 4.0)
        assert body.velocity.length() == pytest.approx(2.0 * (1.0 - F) ** DT, abs=1e-12)

    def test_fast_on_a_slope_steeper_than_10_degrees_uses_0_2(self, world):
        # v² = 9 ≥ 6.25 and N.z = cos 20° < cos 10° → frict = 0.2: factor 0.8^dt.
        slope = math.radians(20)
        body = self._sled(world, Vector3(0.0, -math.sin(slope), math.cos(slope)), 3.0)
        body.calc_friction(DT, 9.0)
        assert body.velocity.length() == pytest.approx(3.0 * (1.0 - 0.20000000298023224) ** DT, abs=1e-12)

    def test_fast_on_gentle_ground_uses_the_body_friction(self, world):
        # N.z = cos 5° ≥ cos 10°: the object's friction.
        slope = math.radians(5)
        body = self._sled(world, Vector3(0.0, -math.sin(slope), math.cos(slope)), 3.0)
        body.calc_friction(DT, 9.0)
        assert body.velocity.length() == pytest.approx(3.0 * (1.0 - F) ** DT, abs=1e-12)

    def test_the_threshold_reads_the_magnitude_passed_in(self, world):
        # The thresholds compare the velocity_mag2 argument (the clamped pre-friction value),
        # not the current velocity: v is 3 m/s but 1.0 is passed → full stop.
        body = self._sled(world, Vector3(0.0, 0.0, 1.0), 3.0)
        body.calc_friction(DT, 1.0)
        assert body.velocity.length() == 0.0


class TestCalcAcceleration:
    """CPhysicsObj::calc_acceleration @ 0x00510950 (acclient.c:317786)."""

    def test_contact_and_walkable_zero_acceleration_and_omega(self, world):
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.omega = Vector3(0.0, 0.0, 1.0)
        body.calc_acceleration()
        assert body.acceleration.exactly_equals(Vector3())
        assert body.omega.exactly_equals(Vector3())

    def test_contact_without_walkable_falls(self, world):
        body = place(world, state=PS.GRAVITY)
        body.transient_state |= TS.CONTACT
        body.omega = Vector3(0.0, 0.0, 1.0)
        body.calc_acceleration()
        assert body.acceleration.exactly_equals(Vector3(0.0, 0.0, G))
        assert body.omega.z == 1.0

    def test_sledding_on_walkable_ground_keeps_gravity(self, world):
        body = place(world, state=PS.GRAVITY | PS.SLEDDING, on_ground=True)
        body.calc_acceleration()
        assert body.acceleration.z == G

    def test_airborne_without_gravity_has_no_acceleration(self, world):
        body = place(world, state=PS.REPORT_COLLISIONS)
        body.acceleration = Vector3(1.0, 2.0, 3.0)
        body.calc_acceleration()
        assert body.acceleration.exactly_equals(Vector3())


class TestOmega:
    """UpdatePhysicsInternal ends with Frame::grotate(omega · dt) (acclient.c:317781-317783)."""

    def test_omega_rotates_through_grotate(self, world):
        body = place(world, spheres=False, state=PS(0))
        body.omega = Vector3(0.0, 0.0, math.pi / 2)
        body.update_object_internal(0.2)
        # Rotation by θ = 0.1π about +z: q = (cos 0.05π, 0, 0, sin 0.05π); a CCW turn lowers
        # the compass heading by 18°.
        frame = body.position.frame
        assert frame.qw == pytest.approx(math.cos(0.05 * math.pi), abs=1e-12)
        assert frame.qz == pytest.approx(math.sin(0.05 * math.pi), abs=1e-12)
        assert frame.get_heading() == pytest.approx(342.0, abs=1e-9)

    def test_omega_about_a_tilted_axis_is_a_global_rotation(self, world):
        # grotate multiplies from the left: the axis is global even for a turned body.
        body = place(world, spheres=False, state=PS(0), heading=90.0)
        start = body.position.frame.copy()
        body.omega = Vector3(1.0, 0.0, 0.0)
        body.update_object_internal(0.1)
        expected = Frame()
        half = 0.05
        w, x = math.cos(half), math.sin(half)
        # (w, x, 0, 0) · q_start
        expected.set_rotate(
            w * start.qw - x * start.qx,
            w * start.qx + x * start.qw,
            w * start.qy - x * start.qz,
            w * start.qz + x * start.qy,
        )
        frame = body.position.frame
        assert (frame.qw, frame.qx, frame.qy, frame.qz) == pytest.approx(
            (expected.qw, expected.qx, expected.qy, expected.qz), abs=1e-12
        )


def test_an_omega_too_large_to_rotate_by_is_refused(world) -> None:
    # Frame::grotate squares omega's length (acclient.c:357421); past float range it would
    # turn the frame to NaN, so set_omega refuses it rather than letting the body go NaN.
    body = place(world)
    with pytest.raises(ValueError, match="too large to rotate by"):
        body.set_omega(Vector3(1e300, 0.0, 0.0))
    body.set_omega(Vector3(1e3, 0.0, 0.0))
    assert body.omega == Vector3(1e3, 0.0, 0.0)
