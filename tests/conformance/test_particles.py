"""Particles: closed-form paths, lifespans, birthrates, degradation, the manager and the hook route.

Retail: cphysobj/CParticleEmitter.c (Particle::Update acclient.c:330312, Particle::Init 330648,
EmitParticle 331002, UpdateParticles 331096, KillParticle 330273, StopEmitter 330294),
CParticleEmitterInfo.c (ShouldEmitParticle 324499, GetRandom* 324323-324639),
CParticleManager.c (329273-329527), CPhysicsObj::create_particle_emitter (316329) and friends.
"""

from __future__ import annotations

import math

import pytest
from tests.support import place

from acphys.flags import PhysicsState as PS
from acphys.managers.particles import (
    FIRST_EMITTER_ID,
    EmitterType,
    ParticleEmitterInfo,
    ParticleType,
    register_emitter_info,
    unregister_emitter_info,
)
from acphys.managers.scripts import PhysicsScript, register_script, unregister_script
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.anim_hooks import CreateParticleHook, StopParticleHook
from acphys.precision import f32

INFO = 0x32000001
SCRIPT = 0x33000201
GFX = 0x01000001


def _info(**kw) -> ParticleEmitterInfo:
    """One particle, no randomness: zero offset range, fixed magnitudes, lifespan 1 s."""
    fields = dict(
        emitter_type=EmitterType.BIRTHRATE_PER_SEC,
        particle_type=ParticleType.LOCAL_VELOCITY,
        hw_gfxobj_id=GFX,
        birthrate=10.0,
        max_particles=1,
        initial_particles=1,
        total_particles=1,
        lifespan=1.0,
        a=Vector3(0.0, 1.0, 0.0),
    )
    fields.update(kw)
    return ParticleEmitterInfo(**fields)


@pytest.fixture(autouse=True)
def _registry():
    yield
    unregister_emitter_info(INFO)
    unregister_script(SCRIPT)


def _emit(world, body, info: ParticleEmitterInfo, t0: float = 5.0, part_index: int = -1):
    register_emitter_info(INFO, info)
    world.cur_time = world.physics_time = t0
    emitter_id = body.create_particle_emitter(INFO, part_index, Frame(), 0)
    assert emitter_id
    return body.particle_manager.get_emitter(emitter_id)


def _tick(world, body, t: float) -> None:
    world.cur_time = world.physics_time = t
    body.particle_manager.update_particles()


class TestClosedForm:
    def test_local_velocity_is_turned_by_the_birth_frame_and_the_particle_dies_at_its_lifespan(self, world):
        body = place(world, state=PS(0), heading=90.0)  # facing +x
        emitter = _emit(world, body, _info())
        ((slot, part),) = emitter.live_particles()
        # Init: a = start_frame.localtoglobalvec(a) for LocalVelocity (acclient.c:330711-330718);
        # Update: origin = parent origin + offset + t·a (acclient.c:330366-330381).
        assert part.frame.origin == Vector3(96.0, 96.0, 50.0)
        _tick(world, body, 5.25)
        assert part.frame.origin.x == pytest.approx(96.25, abs=1e-12)
        assert part.frame.origin.y == pytest.approx(96.0, abs=1e-12)
        _tick(world, body, 5.999)
        assert emitter.parts[slot] is part
        assert emitter.stopped  # total_particles reached on the first update (acclient.c:330305-330306)
        # KillParticle: lifetime >= lifespan frees the slot (acclient.c:330278-330289); the stopped
        # emitter then has no particles, reports done, and the manager drops it on the same
        # update (acclient.c:331227-331229, 329516-329521).
        _tick(world, body, 6.0)
        assert part.frame.origin.x == pytest.approx(97.0, abs=1e-12)
        assert emitter.num_particles == 0
        assert body.get_num_emitters() == 0

    def test_parabolic_lvga_adds_half_b_t_squared_with_b_global(self, world):
        body = place(world, state=PS(0), heading=90.0)
        info = _info(
            particle_type=ParticleType.PARABOLIC_LVGA, a=Vector3(0.0, 2.0, 0.0), b=Vector3(0.0, 0.0, -9.8)
        )
        emitter = _emit(world, body, info)
        ((_, part),) = emitter.live_particles()
        _tick(world, body, 5.5)
        # origin + offset + t·a + ½·t²·b, a local → (2, 0, 0) global, b global as given
        # (Init acclient.c:330703-330718, Update 330435-330465).
        a = emitter.particles[0].a
        assert a.x == pytest.approx(2.0, abs=1e-6) and a.y == pytest.approx(0.0, abs=1e-6)
        # With t = 0.5 (exact) and the float spills of case 3: x = f32(t·a.x + (o.x + p.x) + sx)
        # with sx = f32(f32(0.5·b.x)·t·f32(t)) = 0; y = f32(f32(f32(o.y + p.y) + f32(t·a.y)) + 0);
        # z = f32(f32(f32(o.z + p.z) + f32(t·a.z)) + f32(f32(0.5·b.z·t)·f32(t))), b.z = f32(-9.8).
        assert part.frame.origin.x == f32(0.5 * a.x + (0.0 + 96.0))
        assert part.frame.origin.y == f32(f32(96.0 + f32(0.5 * a.y)))
        assert part.frame.origin.z == f32(50.0 + f32(f32(f32(-9.8) * 0.5 * 0.5) * 0.5))
        assert part.frame.origin.z == pytest.approx(50.0 - 0.5 * 9.8 * 0.25, abs=1e-5)

    def test_swarm_weights_each_wave_by_c(self, world):
        # Update case 5: cos(b.x t)·c.x + t·a.x + offset + parent (acclient.c:330443-330453).
        # ACE's Particle.Update adds C unweighted and cos/sin without C: it diverges here.
        body = place(world, state=PS(0))
        info = _info(
            particle_type=ParticleType.SWARM, a=Vector3(), b=Vector3(1.0, 2.0, 3.0), c=Vector3(0.5, 0.25, 2.0)
        )
        emitter = _emit(world, body, info)
        ((_, part),) = emitter.live_particles()
        assert part.frame.origin == Vector3(96.5, 96.0, 52.0)  # t = 0: (c.x, 0, c.z)
        _tick(world, body, 5.4)
        # The lifetime is the double 5.4 - 5.0; each axis is summed in registers and stored once.
        t = 5.4 - 5.0
        assert part.frame.origin.x == f32(math.cos(1.0 * t) * 0.5 + t * 0.0 + 0.0 + 96.0)
        assert part.frame.origin.y == f32(math.sin(2.0 * t) * 0.25 + t * 0.0 + 0.0 + 96.0)
        assert part.frame.origin.z == f32(math.cos(3.0 * t) * 2.0 + t * 0.0 + 0.0 + 50.0)
        assert part.frame.origin.x == pytest.approx(96.0 + 0.5 * math.cos(1.0 * 0.4), abs=1e-5)

    def test_global_velocity_ignores_the_heading(self, world):
        body = place(world, state=PS(0), heading=90.0)
        emitter = _emit(world, body, _info(particle_type=ParticleType.GLOBAL_VELOCITY))
        ((_, part),) = emitter.live_particles()
        _tick(world, body, 5.5)  # Init case 12: a kept global (acclient.c:330734-330737)
        assert part.frame.origin == Vector3(96.0, 96.5, 50.0)

    def test_scale_and_translucency_ramp_over_the_lifespan(self, world):
        body = place(world, state=PS(0))
        info = _info(start_scale=1.0, final_scale=3.0, start_trans=0.0, final_trans=0.5, lifespan=2.0)
        emitter = _emit(world, body, info)
        ((_, part),) = emitter.live_particles()
        _tick(world, body, 5.5)
        # fraction = lifetime / lifespan; scale and translucency lerp (acclient.c:330526-330540).
        assert part.gfxobj_scale.x == pytest.approx(1.5, abs=1e-12)
        assert part.translucency == pytest.approx(0.125, abs=1e-12)

    def test_parent_local_particles_follow_the_parent(self, world):
        # is_parent_local: Update gets the parent's current frame (acclient.c:331196-331205).
        body = place(world, state=PS(0))
        emitter = _emit(world, body, _info(is_parent_local=True, particle_type=ParticleType.STILL))
        ((_, part),) = emitter.live_particles()
        body.position.frame.origin = Vector3(100.0, 96.0, 50.0)
        _tick(world, body, 5.1)
        assert part.frame.origin == Vector3(100.0, 96.0, 50.0)


class TestBirthrate:
    def test_per_second_emits_when_more_than_birthrate_has_passed(self, world):
        body = place(world, state=PS(0))
        info = _info(birthrate=0.25, max_particles=10, initial_particles=0, total_particles=0, lifespan=10.0)
        emitter = _emit(world, body, info, t0=1.0)
        counts = []
        for t in (1.25, 1.3, 1.5, 1.6):
            _tick(world, body, t)
            counts.append(emitter.total_emitted)
        # cur_time - last_emit_time > birthrate (strict, acclient.c:324507-324509); the first
        # last_emit_time is the creation clock (acclient.c:330585-330589).
        assert counts == [0, 1, 1, 2]

    def test_per_metre_measures_travel_since_the_last_birth(self, world):
        body = place(world, state=PS(0))
        info = _info(
            emitter_type=EmitterType.BIRTHRATE_PER_METER,
            birthrate=1.0,
            max_particles=10,
            initial_particles=0,
            total_particles=0,
            lifespan=10.0,
        )
        emitter = _emit(world, body, info)
        # SetInfo copies the unparented particle object's origin (zero) into last_emit_offset
        # (acclient.c:330927-330929): the first update is ~137 m from it and emits at once.
        _tick(world, body, 5.1)
        assert emitter.total_emitted == 1
        body.position.frame.origin = Vector3(96.5, 96.0, 50.0)
        _tick(world, body, 5.2)
        assert emitter.total_emitted == 1
        body.position.frame.origin = Vector3(97.2, 96.0, 50.0)
        _tick(world, body, 5.3)
        assert emitter.total_emitted == 2

    def test_total_seconds_stops_the_emitter(self, world):
        body = place(world, state=PS(0))
        info = _info(
            birthrate=0.0, max_particles=5, initial_particles=0, total_particles=0, total_seconds=0.5
        )
        emitter = _emit(world, body, info, t0=0.0)
        _tick(world, body, 0.5)
        assert not emitter.stopped  # creation + total_seconds < curr_time is strict (acclient.c:330301)
        _tick(world, body, 0.6)
        assert emitter.stopped


class TestDegradation:
    def test_beyond_the_degrade_distance_an_unlimited_emitter_freezes_its_particles(self, world):
        body = place(world, state=PS(0))
        viewer = place(world, name="viewer", state=PS(0), origin=(96.0, 126.0, 50.0))  # 30 m away
        info = _info(total_particles=0, degrade_distance=50.0, lifespan=100.0)
        emitter = _emit(world, body, info, t0=0.0)
        ((_, part),) = emitter.live_particles()
        world.player = viewer
        _tick(world, body, 0.5)
        assert part.frame.origin.y == pytest.approx(96.5, abs=1e-12)
        viewer.position.frame.origin = Vector3(96.0, 186.0, 50.0)  # 90 m: beyond 50
        _tick(world, body, 1.0)
        _tick(world, body, 3.0)
        # Degraded: hidden, not moved, every birthtime set to now (acclient.c:331120-331124, 331169-331177).
        assert emitter.no_draw and emitter.degraded_out
        assert part.frame.origin.y == pytest.approx(96.5, abs=1e-12)
        viewer.position.frame.origin = Vector3(96.0, 126.0, 50.0)
        _tick(world, body, 3.25)
        # Persistent lifetime: 0.5 before, + 0.25 since the last degraded update (birthtime 3.0).
        assert not emitter.no_draw
        assert emitter.particles[0].lifetime == pytest.approx(0.75, abs=1e-12)
        assert part.frame.origin.y == pytest.approx(96.75, abs=1e-12)

    def test_beyond_the_degrade_distance_a_limited_emitter_still_ages_and_kills(self, world):
        body = place(world, state=PS(0))
        viewer = place(world, name="viewer", state=PS(0), origin=(96.0, 186.0, 50.0))
        emitter = _emit(world, body, _info(degrade_distance=50.0), t0=0.0)
        world.player = viewer
        _tick(world, body, 1.0)  # lifetime = now - birthtime, then KillParticle (acclient.c:331138-331147)
        assert emitter.num_particles == 0
        assert emitter.particles[0].lifetime == 1.0


class TestManager:
    def test_ids_count_up_from_0xffff0000_and_a_given_id_replaces(self, world):
        body = place(world, state=PS(0))
        register_emitter_info(INFO, _info(total_particles=0))
        first = body.create_particle_emitter(INFO, -1, Frame(), 0)
        second = body.create_particle_emitter(INFO, -1, Frame(), 0)
        assert (first, second) == (FIRST_EMITTER_ID, FIRST_EMITTER_ID + 1)  # acclient.c:329310, 329408
        assert body.create_particle_emitter(INFO, -1, Frame(), 7) == 7
        assert body.create_particle_emitter(INFO, -1, Frame(), 7) == 7  # old 7 destroyed first
        assert body.get_num_emitters() == 3
        # Blocking: an existing id refuses (acclient.c:329540-329541).
        assert body.create_blocking_particle_emitter(INFO, -1, Frame(), 7) == 0
        assert body.destroy_particle_emitter(7) is True
        assert body.destroy_particle_emitter(7) is False

    def test_an_info_without_graphics_or_a_missing_part_cannot_start(self, world):
        body = place(world, state=PS(0))
        register_emitter_info(INFO, _info(hw_gfxobj_id=0))  # SetInfo fails (acclient.c:330917-330921)
        assert body.create_particle_emitter(INFO, -1, Frame(), 0) == 0
        register_emitter_info(INFO, _info())
        assert body.create_particle_emitter(INFO, 5, Frame(), 0) == 0  # no part 5 to parent to
        assert body.create_particle_emitter(0x32FFFFFF, -1, Frame(), 0) == 0

    def test_stop_lets_particles_live_out_their_lifespans(self, world):
        body = place(world, state=PS(0))
        emitter = _emit(world, body, _info(total_particles=0, max_particles=3, birthrate=0.0), t0=0.0)
        StopParticleHook(emitter.id).execute(body)  # StopParticleEmitter sets stopped (acclient.c:329459)
        _tick(world, body, 0.5)
        assert emitter.num_particles == 1  # no new births once stopped
        _tick(world, body, 1.0)
        assert body.get_num_emitters() == 0


class TestScriptedEffect:
    def test_a_script_creates_an_emitter_whose_particle_positions_are_traced(self, world):
        body = place(world, state=PS(0))
        register_emitter_info(INFO, _info(total_particles=0, lifespan=0.5, initial_particles=1))
        register_script(SCRIPT, PhysicsScript.of((0.2, CreateParticleHook(INFO, -1, Frame(), 0x11))))
        body.update_time = world.cur_time = 0.0
        assert body.play_script(SCRIPT)
        trace: list[tuple[float, float]] = []
        for step in range(1, 19):
            world.cur_time = step / 30.0
            body.update_object()
            if body.particle_manager is not None and body.particle_manager.get_emitter(0x11) is not None:
                emitter = body.particle_manager.get_emitter(0x11)
                trace.extend(
                    (world.physics_time, part.frame.origin.y) for _, part in emitter.live_particles()
                )
        # The hook fires on the first tick at or after 0.2 s (tick 6); the particle is born at that
        # tick's physics time and moves 1 m/s along +y; it dies at lifespan 0.5.
        born = trace[0][0]
        assert born == pytest.approx(0.2, abs=1e-9)
        for t, y in trace:
            # Update case 2: y = f32(f32(offset.y + parent.y) + f32(t·a.y)) (acclient.c:330418-330434).
            assert y == f32(96.0 + f32(t - born))
        assert trace[-1][0] - born < 0.5
