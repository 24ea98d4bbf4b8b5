"""CPhysicsObj::UpdatePhysicsInternal, calc_friction and calc_acceleration against retail.

Expected values are derived by hand from the decompiled lines cited on each
test; float32 constants are written out as the values retail holds. Retail
stores every velocity, origin and spill as a ``float`` (see
:mod:`acphys.precision`), so each derivation narrows with ``f32`` exactly where
the cited lines store.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.geometry.plane import Plane
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32
from support import place

#: The quantum as UpdateObjectInternal receives it: a ``float`` parameter (acclient.c:322719).
DT = f32(1.0 / 30.0)
#: PhysicsGlobals::gravity, float32(-9.8000002) widened (acclient_data.h:6877).
G = -9.800000190734863
#: DEFAULT_FRICTION, float32(0.94999999) widened (acclient_data.h:1430).
F = 0.949999988079071


def _z_step(z: float, vz: float, dt: float, az: float = G) -> tuple[float, float]:
    """One UpdatePhysicsInternal step of a body moving in z alone, with velocity (so the
    ``velocity_mag2 > 0`` branch runs) and no deadband: ``result.z = dt·vz`` and
    ``w.z = az·0.5`` are float locals, ``w.z = result.z + w.z·dt·dt`` is stored again, then
    the origin (acclient.c:317756-317769); ``result.z = dt·az`` is stored before it is added
    to the velocity (acclient.c:317771-317776).
    """
    move = f32(f32(dt * vz) + f32(az * 0.5) * dt * dt)
    return f32(move + z), f32(f32(dt * az) + vz)


def _friction(v: Vector3, n: Vector3, friction: float, dt: float) -> tuple[float, float, float]:
    """calc_friction on walkable ground (acclient.c:316111-316154): ``v·N`` summed z, y, x; the
    z part of ``(v·N)N`` spilled (``ST10_4``) before it is taken off; each component stored;
    then each scaled by ``pow(1 - f, dt)`` and stored.
    """
    ns = v.z * n.z + v.y * n.y + v.x * n.x
    vx, vy, vz = f32(v.x - ns * n.x), f32(v.y - ns * n.y), f32(v.z - f32(ns * n.z))
    factor = math.pow(1.0 - friction, dt)
    return f32(factor * vx), f32(factor * vy), f32(factor * vz)


class TestFreeFall:
    """UpdatePhysicsInternal @ 0x00510700 (acclient.c:317700)."""

    def test_first_step_from_rest_does_not_translate(self, world):
        # velocity_mag2 = 0 fails the `> 0` branch, so no `x += v*dt + a*dt²/2`;
        # the unconditional `v += a*dt` (acclient.c:317771-317776) still runs, stored as floats.
        body = place(world, state=PS.GRAVITY)
        body.update_object_internal(DT)
        assert body.position.frame.origin.z == 50.0
        assert body.velocity.z == f32(f32(DT * G) + 0.0)
        assert body.cached_velocity.exactly_equals(Vector3())

    def test_later_steps_add_v_dt_plus_half_a_dt_squared(self, world):
        # After n steps from rest: v = n·g·dt, and step k (k ≥ 2) moves by
        # (k-1)·g·dt² + g·dt²/2, so z_n ≈ z0 + g·dt²·(n² - 1)/2 (acclient.c:317756-317776);
        # step by step, with the float stores of _z_step, exactly.
        body = place(world, state=PS.GRAVITY)
        z, vz = 50.0, f32(DT * G)
        body.update_object_internal(DT)
        for n in range(2, 7):
            body.update_object_internal(DT)
            z, vz = _z_step(z, vz, DT)
            assert body.position.frame.origin.z == z
            assert body.velocity.z == vz
            assert z == pytest.approx(50.0 + G * DT * DT * (n * n - 1) / 2, abs=1e-5)

    def test_cached_velocity_is_the_achieved_displacement_over_the_quantum(self, world):
        # UpdateObjectInternal (acclient.c:322816-322828): cached_velocity = offset(curr_pos) / quantum,
        # where Vector3::operator/ multiplies y and z by the float32 reciprocal (acclient.c:146876-146883).
        body = place(world, state=PS.GRAVITY)
        body.update_object_internal(DT)
        body.update_object_internal(DT)
        # Step 2 moved by g·dt·dt + g·dt²/2 ≈ 1.5·g·dt².
        z2, _ = _z_step(50.0, f32(DT * G), DT)
        offset_z = f32(z2 - 50.0)  # Position::get_offset, same landblock
        assert body.cached_velocity.z == f32(f32(1.0 / DT) * offset_z)
        # The 0.016-m step is a difference of float32 heights near 50 m (ulp 3.8e-6), divided by 1/30.
        assert body.cached_velocity.z == pytest.approx(1.5 * G * DT, abs=2e-4)
        assert body.cached_velocity.x == 0.0 and body.cached_velocity.y == 0.0


class TestTerminalVelocity:
    """UpdatePhysicsInternal: `velocity_mag2 > 50.0 * 50.0` (acclient.c:317740-317747)."""

    def test_speed_over_50_is_normalised_to_50_before_integrating(self, world):
        body = place(world, state=PS.GRAVITY)
        body.velocity = Vector3(0.0, 30.0, -60.0)  # |v| = sqrt(4500) = 67.08
        # The candidate frame UpdatePhysicsInternal builds (the sweep then moves the body there
        # in steps of its own, which round on their way; see the last assertions).
        candidate = body.position.frame.copy()
        body.update_physics_internal(DT, candidate)
        # Clamped: (0, 30, -60)/sqrt(4500)·50 ≈ (0, 22.3607, -44.7214): AC1Legacy::Vector3::normalize
        # stores each component, then each is stored times 50 (acclient.c:317742-317746). The
        # translation uses the clamped velocity, then v += a·dt adds g·dt to z.
        inv = 1.0 / math.sqrt(4500.0)
        vy, vz = f32(50.0 * f32(inv * 30.0)), f32(50.0 * f32(inv * -60.0))
        # y: `v12 + v10 + y` with v10 = a.y·0.5·dt·dt = 0 spilled (acclient.c:317762, 317768).
        assert candidate.origin.y == f32(DT * vy + 0.0 + 96.0)
        z, vz_after = _z_step(50.0, vz, DT)
        assert candidate.origin.z == z
        assert body.velocity.y == vy
        assert body.velocity.z == vz_after
        scale = 50.0 / math.sqrt(4500.0)
        assert body.velocity.z == pytest.approx(-60.0 * scale + G * DT, abs=1e-5)
        # The whole step commits the same move, to within the float32 rounding of the sweep's steps.
        body.velocity = Vector3(0.0, 30.0, -60.0)
        body.update_object_internal(DT)
        assert body.velocity.exactly_equals(Vector3(0.0, vy, vz_after))
        assert body.position.frame.origin.y == pytest.approx(candidate.origin.y, abs=3e-5)
        assert body.position.frame.origin.z == pytest.approx(candidate.origin.z, abs=3e-5)

    def test_exactly_50_is_not_clamped(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(0.0, 0.0, -50.0)
        body.update_object_internal(DT)
        assert body.velocity.z == -50.0


class TestDeadband:
    """UpdatePhysicsInternal: `velocity_mag2 - 0.25 * 0.25 < EPSILON` zeroes v (acclient.c:317750)."""

    def test_just_under_the_deadband_zeroes_velocity_but_still_adds_half_a_dt2(self, world):
        # |v| = 0.2502: v² - 0.0625 = 0.0001 < 0.0002 → v = 0, then the translation still adds
        # a·dt²/2 and v += a·dt (acclient.c:317750-317776).
        body = place(world, state=PS.GRAVITY)
        body.velocity = Vector3(0.2502, 0.0, 0.0)
        body.update_object_internal(DT)
        origin = body.position.frame.origin
        assert origin.x == 96.0
        z, vz = _z_step(50.0, 0.0, DT)
        assert origin.z == z
        assert body.velocity.x == 0.0
        assert body.velocity.z == vz

    def test_just_over_the_deadband_keeps_velocity(self, world):
        # |v| = 0.2505 (float32 0.25049999): v² - 0.0625 = 0.00025 ≥ 0.0002: kept.
        body = place(world, state=PS(0))
        body.velocity = Vector3(0.2505, 0.0, 0.0)
        body.update_object_internal(DT)
        vx = f32(0.2505)
        assert body.velocity.x == vx
        # `w.x = dt·vx + (a.x·0.5·dt)·dt`, stored, then the origin (acclient.c:317766-317767).
        assert body.position.frame.origin.x == f32(f32(DT * vx + 0.0) + 96.0)

    def test_the_deadband_tests_the_pre_friction_speed(self, world):
        # On walkable ground |v| = 0.26 decays by (1-f)^dt to 0.2353, under 0.25; but the test
        # reads velocity_mag2 computed before calc_friction (0.0676 - 0.0625 ≥ EPSILON): kept.
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(0.26, 0.0, 0.0)
        body.update_object_internal(DT)
        decayed = _friction(Vector3(0.26, 0.0, 0.0), Vector3(0.0, 0.0, 1.0), F, DT)[0]
        assert decayed < 0.25
        assert body.velocity.x == decayed

    def test_gravity_at_a_small_quantum_never_builds_up(self, world):
        # At dt = 1/60 the first step gives |v| = 0.1633 < 0.25, which the next step zeroes:
        # a body falls only a·dt²/2 per step. (Retail avoids such quanta: CPhysics::UseTime
        # runs bodies at most every 1/30 s.)
        body = place(world, state=PS.GRAVITY)
        small = f32(1.0 / 60.0)
        body.update_object_internal(small)
        z = 50.0
        for step in range(2, 6):
            body.update_object_internal(small)
            z, _ = _z_step(z, 0.0, small)  # the deadband zeroed v before the translation
            assert body.position.frame.origin.z == z
            assert z == pytest.approx(50.0 + (step - 1) * G * 0.5 * small * small, abs=1e-5)


class TestFriction:
    """CPhysicsObj::calc_friction @ 0x0050EE70 (acclient.c:316090)."""

    def test_decay_is_one_minus_f_to_the_dt_on_walkable_ground(self, world):
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(3.0, 0.0, 0.0)
        body.update_object_internal(DT)
        factor = (1.0 - F) ** DT  # pow(1.0 - friction, quantum), acclient.c:316151
        vx = f32(factor * 3.0)
        assert body.velocity.x == vx
        # The translation uses the decayed velocity (acclient.c:317766-317767).
        assert body.position.frame.origin.x == f32(f32(DT * vx + 0.0) + 96.0)

    def test_no_friction_in_the_air(self, world):
        body = place(world, state=PS(0))
        body.velocity = Vector3(3.0, 0.0, 0.0)
        body.update_object_internal(DT)
        assert body.velocity.x == 3.0

    def test_normal_component_is_removed_before_the_decay(self):
        # v·N = 0.2 < 0.25: v -= (v·N)N, then v *= (1-f)^dt (acclient.c:316137-316154).
        from acphys.world.world import World

        body = place(World(), state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(3.0, 0.0, 0.2)
        body.calc_friction(DT, body.velocity.length_squared())
        factor = (1.0 - F) ** DT
        assert body.velocity.x == f32(factor * 3.0)
        assert body.velocity.z == 0.0

    def test_moving_away_from_the_plane_skips_friction(self, world):
        # v·N ≥ 0.25 returns before touching v (acclient.c:316133).
        body = place(world, state=PS.GRAVITY, on_ground=True)
        body.velocity = Vector3(3.0, 0.0, 0.25)
        body.calc_friction(DT, body.velocity.length_squared())
        assert body.velocity.exactly_equals(Vector3(3.0, 0.0, 0.25))

    def test_friction_uses_the_contact_plane_normal(self, world):
        # A 30° slope: N = (0, -sin30, cos30). v along the slope (0, cos30, sin30)·2 has v·N = 0
        # (to within the float32 rounding of N and v, which _friction takes off as retail does),
        # so essentially only the decay applies.
        body = place(world, state=PS.GRAVITY, on_ground=True)
        s, c = math.sin(math.radians(30)), math.cos(math.radians(30))
        normal = Vector3(0.0, -s, c)
        body.contact_plane = Plane(normal, 0.0)
        body.velocity = Vector3(0.0, 2 * c, 2 * s)
        expected = _friction(body.velocity, normal, F, DT)
        body.calc_friction(DT, 4.0)
        assert tuple(body.velocity) == expected
        factor = (1.0 - F) ** DT
        assert body.velocity.y == pytest.approx(2 * c * factor, abs=1e-6)
        assert body.velocity.z == pytest.approx(2 * s * factor, abs=1e-6)


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
        normal = Vector3(0.0, -math.sin(slope), math.cos(slope))
        body = self._sled(world, normal, 2.0)
        expected = _friction(body.velocity, normal, F, DT)
        body.calc_friction(DT, 4.0)
        assert tuple(body.velocity) == expected
        assert body.velocity.length() == pytest.approx(2.0 * (1.0 - F) ** DT, abs=1e-6)

    def test_fast_on_a_slope_steeper_than_10_degrees_uses_0_2(self, world):
        # v² = 9 ≥ 6.25 and N.z = cos 20° < cos 10° → frict = 0.2 (a float local, float32 0.2):
        # factor 0.8^dt (acclient.c:316117-316126).
        slope = math.radians(20)
        normal = Vector3(0.0, -math.sin(slope), math.cos(slope))
        body = self._sled(world, normal, 3.0)
        expected = _friction(body.velocity, normal, f32(0.2), DT)
        body.calc_friction(DT, 9.0)
        assert tuple(body.velocity) == expected
        assert body.velocity.length() == pytest.approx(3.0 * (1.0 - 0.20000000298023224) ** DT, abs=1e-6)

    def test_fast_on_gentle_ground_uses_the_body_friction(self, world):
        # N.z = cos 5° ≥ cos 10°: the object's friction.
        slope = math.radians(5)
        normal = Vector3(0.0, -math.sin(slope), math.cos(slope))
        body = self._sled(world, normal, 3.0)
        expected = _friction(body.velocity, normal, F, DT)
        body.calc_friction(DT, 9.0)
        assert tuple(body.velocity) == expected
        assert body.velocity.length() == pytest.approx(3.0 * (1.0 - F) ** DT, abs=1e-6)

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
        body.update_object_internal(f32(0.2))
        # Rotation by θ = 0.1π about +z: q = (cos 0.05π, 0, 0, sin 0.05π); a CCW turn lowers
        # the compass heading by 18°. omega·dt is the float vector ``w`` (acclient.c:317777-317783);
        # the quaternion is float32 (Frame::grotate's own stores are the math tests' business), so
        # the comparison allows a few float32 ulps.
        frame = body.position.frame
        assert frame.qw == pytest.approx(math.cos(0.05 * math.pi), abs=1e-7)
        assert frame.qz == pytest.approx(math.sin(0.05 * math.pi), abs=1e-7)
        assert frame.get_heading() == pytest.approx(342.0, abs=1e-4)

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


def test_an_omega_beyond_float_range_is_refused(world) -> None:
    # An omega component past float32 range is an infinity once stored in a Vector3 (retail's
    # m_omegaVector is floats), and Frame::grotate (acclient.c:357421) would turn the frame to
    # NaN with it; set_omega refuses it rather than letting the body go NaN. Any finite float32
    # omega squares to a finite double, so it can always be rotated by.
    body = place(world)
    with pytest.raises(ValueError, match="omega must be finite"):
        body.set_omega(Vector3(1e300, 0.0, 0.0))
    body.set_omega(Vector3(3e38, 0.0, 0.0))
    assert body.omega.exactly_equals(Vector3(3e38, 0.0, 0.0))
    body.set_omega(Vector3(1e3, 0.0, 0.0))
    assert body.omega == Vector3(1e3, 0.0, 0.0)
