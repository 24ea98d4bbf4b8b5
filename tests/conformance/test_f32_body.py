"""Float32 at rest, float64 in flight: the stores of the body (``CPhysicsObj``).

Each test works a retail function by hand: double arithmetic between stores, ``f32`` at each
store into a ``float`` (field, local, 4-byte spill, float parameter), citing the decompiled
lines. Inputs are chosen so that narrowing at a different place, or not at all, gives a
different answer, and each test checks that too, so it cannot pass by accident. The last tests
check that every ``float`` field of a body is a float32 after real use.
"""

from __future__ import annotations

import math

from acphys.body.cells import SetPositionStruct
from acphys.constants import EPSILON
from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.geometry.plane import Plane
from acphys.hooks import FPHook, HookType
from acphys.math.vector import Vector3
from acphys.precision import f32, is_f32
from acphys.simulation import Simulation
from acphys.transition.collision_info import CollisionInfo
from acphys.world.world import World
from support import place

#: The quantum as UpdateObjectInternal receives it: a ``float`` parameter (acclient.c:322719).
DT = f32(1.0 / 30.0)


def test_the_displacement_keeps_retails_spills_per_axis(world) -> None:
    # UpdatePhysicsInternal @ 0x00510700 (acclient.c:317756-317769), with a = (ax, ay, az):
    #   x: v8 = ax·0.5·dt (ST18_4), v9 = v8·dt (ST18_4), w.x = dt·vx + v9, x = w.x + x
    #   y: v10 = ay·0.5·dt·dt (ST1C_4), y = dt·vy + v10 + y
    #   z: w.z = az·0.5, result.z = dt·vz, w.z = result.z + w.z·dt·dt, z = w.z + z
    # Each axis gets inputs for which its spills change the stored origin.
    body = place(world, state=PS(0))
    body.velocity = Vector3(-2.69, 15.21, 11.39)
    body.acceleration = Vector3(10.5, -4.4, 10.7)
    v, a = body.velocity.copy(), body.acceleration.copy()
    frame = body.position.frame.copy()
    frame.origin = Vector3(3.25, 3.25, 1.5)
    body.update_physics_internal(DT, frame)

    x = f32(f32(DT * v.x + f32(f32(a.x * 0.5 * DT) * DT)) + 3.25)
    y = f32(DT * v.y + f32(a.y * 0.5 * DT * DT) + 3.25)
    z = f32(f32(f32(DT * v.z) + f32(a.z * 0.5) * DT * DT) + 1.5)
    assert frame.origin.exactly_equals(Vector3(x, y, z))
    # One narrowing of the exact-arithmetic sum gives something else on every axis, and the x
    # rule applied to y, or the y rule to x, would too.
    assert x != f32(DT * v.x + a.x * 0.5 * DT * DT + 3.25)
    assert y != f32(DT * v.y + a.y * 0.5 * DT * DT + 3.25)
    assert z != f32(DT * v.z + a.z * 0.5 * DT * DT + 1.5)
    assert x != f32(DT * v.x + f32(a.x * 0.5 * DT * DT) + 3.25)


def test_the_z_velocity_term_is_spilled_before_it_is_added(world) -> None:
    # UpdatePhysicsInternal (acclient.c:317771-317776): v14 = dt·ax and v15 = dt·ay stay in
    # registers, result.z = dt·az is a float local; then v += those.
    body = place(world, state=PS(0))
    body.velocity = Vector3(0.406, 0.406, 0.406)
    body.acceleration = Vector3(-15.38, -15.38, -15.38)
    vz, az = body.velocity.z, body.acceleration.z
    body.update_physics_internal(DT, body.position.frame.copy())
    assert body.velocity.z == f32(f32(DT * az) + vz)
    assert body.velocity.x == body.velocity.y == f32(DT * az + vz)
    assert body.velocity.z != body.velocity.x


def test_velocity_mag2_is_a_float_local_and_decides_the_deadband(world) -> None:
    # UpdatePhysicsInternal: `float velocity_mag2 = |v|²` (acclient.c:317726), then
    # `velocity_mag2 - 0.25 * 0.25 < 0.00019999999` zeroes v (acclient.c:317750). Here |v|² in
    # double is under the deadband, but it rounds up to a float32 that is not: v is kept.
    body = place(world, state=PS(0))
    body.velocity = Vector3(0.2503995, 0.0003, 0.0)
    v = body.velocity
    double_mag2 = v.x * v.x + v.y * v.y + v.z * v.z
    assert double_mag2 - 0.0625 < EPSILON
    assert not f32(double_mag2) - 0.0625 < EPSILON
    vx, vy = v.x, v.y
    body.update_physics_internal(DT, body.position.frame.copy())
    assert (body.velocity.x, body.velocity.y) == (vx, vy)  # kept (no acceleration to add)


def test_friction_spills_the_z_part_of_the_normal_component(world) -> None:
    # calc_friction @ 0x0050EE70 (acclient.c:316137-316154), not sledding: v9 = N·v summed z, y,
    # x; v10 = v9·N.x and v12 = v9·N.y in registers, v13 = v9·N.z spilled (ST10_4); v -= those;
    # then v *= pow(1 - friction, dt), each component stored.
    body = place(world, state=PS(0), on_ground=True)
    normal = Vector3(0.05630802735686302, -0.06298618018627167, 0.996424674987793)
    body.contact_plane = Plane(normal, 0.0)
    body.velocity = Vector3(1.96, 3.28, -0.88)
    v, n = body.velocity.copy(), body.contact_plane.N
    body.calc_friction(DT, v.length_squared())

    ns = n.z * v.z + n.y * v.y + n.x * v.x
    factor = math.pow(1.0 - body.friction, DT)
    vz = f32(v.z - f32(ns * n.z))
    assert body.velocity.z == f32(factor * vz)
    assert body.velocity.x == f32(factor * f32(v.x - ns * n.x))
    assert body.velocity.y == f32(factor * f32(v.y - ns * n.y))
    assert body.velocity.z != f32(factor * f32(v.z - ns * n.z))  # without the spill


def test_cached_velocity_divides_x_by_the_double_reciprocal_and_y_by_the_float_one(world) -> None:
    # UpdateObjectInternal (acclient.c:322816-322828) divides the offset by the quantum with
    # Vector3::operator/ (acclient.c:146876-146883): v4 = 1.0 / quantum, stored into the float
    # parameter's slot; x = v4·x with the register value, y and z times the stored float.
    # Equal x and y offsets give different cached velocities.
    body = place(world, state=PS(0))
    body.velocity = Vector3(1.01, 1.01, 0.0)
    body.update_object_internal(DT)
    x1 = f32(f32(DT * f32(1.01) + 0.0) + 96.0)
    y1 = f32(DT * f32(1.01) + 0.0 + 96.0)
    assert body.position.frame.origin.x == x1 and body.position.frame.origin.y == y1 == x1
    offset = f32(x1 - 96.0)  # Position::get_offset, one landblock
    inv = 1.0 / DT
    assert body.cached_velocity.x == f32(inv * offset)
    assert body.cached_velocity.y == f32(f32(inv) * offset)
    assert body.cached_velocity.x != body.cached_velocity.y


def test_the_bounce_spills_the_y_and_z_terms_of_the_impulse(world) -> None:
    # handle_all_collisions @ 0x00514780 (acclient.c:321876-321886): v13 = v·n summed z, y, x;
    # v14 = -(v13·(e + 1)) in a register; v15 = v14·n.y (ST24_4) and v16 = v14·n.z (ST28_4)
    # spilled; x = v14·n.x + x in registers; each component stored.
    body = place(world, state=PS(0))
    info = CollisionInfo()
    info.collision_normal_valid = True
    info.collision_normal = Vector3(-0.036674614995718, -0.12559892237186432, 0.9914029836654663)
    body.velocity = Vector3(-3.61, 3.67, -8.95)
    v, n = body.velocity.copy(), info.collision_normal
    body.handle_all_collisions(info, False, False)

    impulse = -((v.z * n.z + v.y * n.y + n.x * v.x) * (body.elasticity + 1.0))
    assert body.velocity.x == f32(impulse * n.x + v.x)
    assert body.velocity.y == f32(f32(impulse * n.y) + v.y)
    assert body.velocity.z == f32(f32(impulse * n.z) + v.z)
    assert body.velocity.y != f32(impulse * n.y + v.y)
    assert body.velocity.z != f32(impulse * n.z + v.z)


def test_the_activity_cull_tests_the_unrounded_distance(world) -> None:
    # update_object @ 0x00515D10 (acclient.c:323112-323114): v4 = sqrt(|player_vector|²) in st7,
    # player_distance = v4 (a float field), then `v4 > 96.0`. 96.0000000052 m is stored as 96.0,
    # yet the body is past the cull.
    player = place(world, name="player", origin=(10.0, 10.0, 50.0))
    body = place(world, name="far", origin=(106.0, 10.001, 50.0))
    world.player = player
    body.update_object()
    assert body.player_distance == 96.0
    assert body.player_vector.length() > 96.0
    assert not body.transient_state & TS.ACTIVE
    # At exactly 96 m the body stays in.
    near = place(world, name="near", origin=(10.0, 106.0, 50.0))
    near.update_object()
    assert near.player_distance == 96.0
    assert near.transient_state & TS.ACTIVE


def test_a_tween_fraction_rounding_to_one_ends_the_hook(world) -> None:
    # FPHook::Execute @ 0x0051BAA0 (acclient.c:329705-329715): `float v5 = elapsed /
    # interpolation_time`, and the hook is done when v5 == 1.0. 1.5e-8 s before the end the
    # double fraction is under 1 but the float one is 1: the value is the end and the hook goes.
    body = place(world, state=PS(0))
    hook = FPHook(HookType.SCALE, 0.0, 1.0, 1.0, 3.3)
    world.physics_time = 1.0 - 2.0**-26
    assert world.physics_time / 1.0 < 1.0
    assert hook.execute(body) is True
    assert body.scale == f32(3.3) == hook.end_value
    # Half-way, the value (end - start)·fraction + start is stored as a float too.
    world.physics_time = 0.3
    assert hook.execute(body) is False
    assert body.scale == f32((f32(3.3) - 1.0) * f32(0.3) + 1.0)
    assert body.scale != (f32(3.3) - 1.0) * f32(0.3) + 1.0


def test_float_parameters_of_the_setters_are_narrowed(world) -> None:
    # SetScaleStatic(float) (acclient.c:319007), set_elasticity(float) (acclient.c:317060),
    # SetTranslucencyInternal(float) (acclient.c:316802); the struct fields are floats too.
    body = place(world, state=PS(0))
    body.set_scale_static(1.1)
    assert body.scale == f32(1.1) != 1.1
    assert body.part_array.scale == f32(1.1)
    body.set_elasticity(0.07)
    assert body.elasticity == f32(0.07) != 0.07
    body.set_elasticity(math.nan)  # `_elasticity >= 0.0` fails: 0 (acclient.c:317065-317080)
    assert body.elasticity == 0.0
    body.set_translucency(0.3)
    assert body.translucency == f32(0.3) != 0.3
    # SetPositionStruct's scatter radii are float fields (acclient.h:52398).
    sps = SetPositionStruct(xrad=0.1, yrad=2.2)
    assert (sps.xrad, sps.yrad) == (f32(0.1), f32(2.2))


def _assert_float_fields_are_f32(body) -> None:
    vectors = {
        "velocity": body.velocity,
        "acceleration": body.acceleration,
        "omega": body.omega,
        "cached_velocity": body.cached_velocity,
        "sliding_normal": body.sliding_normal,
        "player_vector": body.player_vector,
        "contact_plane.N": body.contact_plane.N,
        "origin": body.position.frame.origin,
    }
    for name, v in vectors.items():
        assert all(is_f32(c) for c in v), (body.name, name, tuple(v))
    scalars = {
        "friction": body.friction,
        "elasticity": body.elasticity,
        "scale": body.scale,
        "translucency": body.translucency,
        "translucency_original": body.translucency_original,
        "player_distance": body.player_distance,
        "contact_plane.d": body.contact_plane.d,
        "default_script_intensity": body.default_script_intensity,
    }
    for name, value in scalars.items():
        assert is_f32(value), (body.name, name, value)
    for hook in body.hooks:
        assert is_f32(hook.start_value) and is_f32(hook.end_value)


def test_a_bodys_float_fields_are_float32_after_real_use() -> None:
    world = World()
    world.set_flat_ground(0xA9B4, 0.37)
    player = place(world, name="player", origin=(90.0, 90.0, 0.37), on_ground=True)
    world.player = player
    ball = place(world, name="ball", origin=(96.0, 96.0, 3.0))  # falls, lands, bounces, slides
    ball.set_elasticity(0.1)
    ball.set_velocity(Vector3(1.37, -0.71, 2.3))
    ball.set_omega(Vector3(0.0, 0.0, 1.3))
    ball.set_scale(1.7, 0.9)
    ball.set_translucency(0.45, 0.7)
    sled = place(
        world, name="sled", origin=(100.0, 92.0, 0.37), state=PS.GRAVITY | PS.SLEDDING, on_ground=True
    )
    sled.set_local_velocity(Vector3(0.3, 3.1, 0.0))
    player.set_velocity(Vector3(0.0, 1.9, 0.0))
    simulation = Simulation(world, [player, ball, sled], duration=2.0)
    simulation.run()
    assert ball.transient_state & TS.CONTACT  # it did land
    assert ball.scale == f32(1.7) and ball.translucency == f32(0.45)
    for body in (player, ball, sled):
        _assert_float_fields_are_f32(body)
