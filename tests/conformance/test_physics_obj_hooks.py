"""The body's physics-object hooks: FPHook tweens run by process_hooks and process_fp_hook's cases.

Retail: FPHook::Execute @ 0x0051BAA0 (acclient.c:329694), CPhysicsObj::process_fp_hook
(acclient.c:320571), SetTranslucency (318693), SetTranslucency2 (316920),
SetTranslucencyInternal (316802), SetPart*/SetLuminosity/SetDiffusion (318758-318894),
the look hooks' Execute (acclient.c:342341-342461). FPHook's start and end values are
``float`` fields and Execute's fraction and value ``float`` (acclient.c:329705-329713).
"""

from __future__ import annotations

import pytest
from tests.support import place

from acphys.flags import PhysicsState as PS
from acphys.hooks import HookType
from acphys.motion.anim_hooks import LuminousPartHook, ScaleHook, TransparentHook
from acphys.precision import f32

TICK = 1.0 / 30.0


def _run(world, body, until: float) -> None:
    """Drive the real clock (update_object) in 1/30 s steps up to ``until``."""
    while world.cur_time < until - 1e-9:
        world.cur_time = min(world.cur_time + TICK, until)
        body.update_object()


class TestTranslucency:
    def test_set_translucency_tweens_from_zero_not_from_the_current_value(self, world):
        # SetTranslucency builds FPHook(type 1, curr_time, delta, 0.0, target) (acclient.c:318708):
        # the start is 0.0 whatever the body's translucency is.
        body = place(world, state=PS(0))
        body.translucency = 0.6
        world.physics_time = 2.0
        body.set_translucency(0.8, 1.0)
        world.physics_time = 2.5
        body.process_hooks()
        # (end - 0.0) · fraction 0.5 + 0.0, with end the float32 0.8.
        assert body.translucency == f32((f32(0.8) - 0.0) * 0.5 + 0.0)
        assert body.translucency == pytest.approx(0.4, abs=1e-7)

    def test_translucency_reaches_its_end_value_at_the_end_time_and_the_hook_goes(self, world):
        body = place(world, state=PS(0))
        body.update_time = world.cur_time = world.physics_time = 1.0
        body.set_translucency2(0.2, 0.9, 0.5)
        _run(world, body, 1.3)
        # FPHook::Execute: value = (end - start) * (elapsed / delta) + start, the fraction and the
        # value stored as floats (acclient.c:329705-329713); elapsed is the double physics timer's.
        fraction = f32((world.physics_time - 1.0) / 0.5)
        assert body.translucency == f32((f32(0.9) - f32(0.2)) * fraction + f32(0.2))
        assert body.translucency == pytest.approx(0.2 + 0.7 * (0.3 / 0.5), abs=1e-6)
        assert len(body.hooks) == 1
        _run(world, body, 1.5)
        # The fraction clamps to exactly 1.0 (acclient.c:329707): (0.9 - 0.2) * 1 + 0.2 is the
        # float32 0.9 again.
        assert body.translucency == f32(0.9)
        assert body.hooks == []  # Execute returns fraction == 1 → unlinked (acclient.c:318656-318670)

    def test_translucency_never_drops_below_the_original(self, world):
        # SetTranslucencyInternal clamps to translucencyOriginal (acclient.c:316806-316807).
        body = place(world, state=PS(0))
        body.translucency_original = 0.3
        body.set_translucency(0.1)
        assert body.translucency == 0.3
        body.set_translucency(0.5)
        assert body.translucency == 0.5

    def test_transparent_hook_routes_to_set_translucency2(self, world):
        # TransparentHook::Execute → SetTranslucency2(start, end, time) (acclient.c:342343).
        body = place(world, state=PS(0))
        world.physics_time = 4.0
        TransparentHook(0.5, 1.0, 2.0).execute(body)
        (hook,) = body.hooks
        assert (hook.hook_type, hook.start_value, hook.end_value, hook.interpolation_time) == (
            HookType.TRANSLUCENCY,
            0.5,
            1.0,
            2.0,
        )
        assert hook.time_created == 4.0


class TestScale:
    def test_scale_hook_tweens_the_scale_to_its_end_at_the_end_time(self, world):
        body = place(world, state=PS(0))
        body.update_time = world.cur_time = world.physics_time = 0.0
        body.add_anim_hook(ScaleHook(2.5, 0.6))  # ScaleHook::Execute → SetScale(end, time)
        _run(world, body, TICK)  # the anim hook fires in this tick's process_hooks (start 1.0)
        assert body.scale == 1.0  # created at this tick's physics time: elapsed 0 → start value
        _run(world, body, TICK + 0.3)
        assert body.scale == pytest.approx(1.0 + 1.5 * 0.5, abs=1e-9)
        _run(world, body, TICK + 0.6)
        assert body.scale == 2.5
        assert body.part_array.scale == 2.5  # SetScaleStatic reaches the part array
        # The hook's 0.6 s is the float32 0.60000002 (ScaleHook's time is a float): at elapsed 0.6
        # the float fraction is 0.99999994, whose value already rounds to 2.5, but Execute only
        # reports the end for a fraction of exactly 1 (acclient.c:329707-329715): one tick later.
        assert len(body.hooks) == 1
        _run(world, body, 2 * TICK + 0.6)
        assert body.scale == 2.5
        assert body.hooks == []


class TestPartLooks:
    def test_part_luminosity_is_recorded_with_its_part_and_value(self, world):
        # LuminousPartHook → SetPartLuminosity; delta < EPSILON → process_fp_hook case 5,
        # CPartArray::SetPartLuminosityInternal(part, end) (acclient.c:318819-318822).
        body = place(world, state=PS(0))
        LuminousPartHook(part=0, start=0.0, end=0.75, time=0.0).execute(body)
        assert body.hooks == []
        assert body.step_events == ["fp_hook:PART_LUMINOSITY:0=0.75"]

    def test_diffusion_tween_carries_kind_and_values(self, world):
        # SetDiffusion → FPHook(type 4, ..., start, end, 0) (acclient.c:318909).
        body = place(world, state=PS(0))
        body.set_diffusion(0.2, 0.4, 1.0)
        (hook,) = body.hooks
        assert (hook.hook_type, hook.start_value, hook.end_value, hook.user_data) == (
            HookType.DIFFUSION,
            f32(0.2),
            f32(0.4),
            0,
        )
        world.physics_time += 0.5
        body.process_hooks()
        assert body.step_events == ["fp_hook:DIFFUSION:0=0.3"]
