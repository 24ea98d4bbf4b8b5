"""ScriptManager and physics scripts: hooks fire at their start times, scripts queue back to back.

Retail: cphysobj/CScriptManager.c (ScriptManager::AddScriptInternal acclient.c:329068,
NextHook 329141, UpdateScripts 329188), canim/CPhysicsScript.c (UnPack 336451),
canim/CPhysicsScriptTable.c (GetScript 336551 / 336930), CPhysicsObj::play_script* (318034-318069,
320325-320350), CallPES / CallPESInternal (318962-318972).
"""

from __future__ import annotations

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState
from acphys.hooks import HookType
from acphys.managers.scripts import (
    PhysicsScript,
    PhysicsScriptData,
    PhysicsScriptTable,
    PhysicsScriptTableData,
    ScriptAndModData,
    ScriptManager,
    register_script,
    unregister_script,
)
from acphys.motion.anim_hooks import AnimHook, CallPESHook, DefaultScriptHook
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.world.world import World
from support import place

SCRIPT_A = 0x33000101
SCRIPT_B = 0x33000102


class Mark(AnimHook):
    """Test data: a hook that notes its label and the world clock when it fires."""

    __slots__ = ("label", "log")

    def __init__(self, label: str, log: list[tuple[str, float]]) -> None:
        super().__init__()
        self.label = label
        self.log = log

    def execute(self, obj: PhysicsObj) -> None:
        self.log.append((self.label, obj.world.cur_time))


@pytest.fixture
def log() -> list[tuple[str, float]]:
    return []


@pytest.fixture(autouse=True)
def _scripts(log):
    register_script(
        SCRIPT_A, PhysicsScript.of((0.0, Mark("a0", log)), (0.5, Mark("a1", log)), (1.2, Mark("a2", log)))
    )
    register_script(SCRIPT_B, PhysicsScript.of((0.0, Mark("b0", log)), (0.3, Mark("b1", log))))
    yield
    unregister_script(SCRIPT_A)
    unregister_script(SCRIPT_B)


def _at(world: World, body: PhysicsObj, t: float) -> None:
    world.cur_time = t
    assert body.script_manager is not None
    body.script_manager.update_scripts()


class TestPhysicsScript:
    def test_unpack_sorts_by_start_time_and_length_is_the_last_start(self, log):
        # UnPack qsorts with PhysicsScriptData::Sort and copies the last entry's start_time into
        # length (acclient.c:336521-336526).
        script = PhysicsScript.of(
            (0.7, Mark("late", log)), (0.1, Mark("early", log)), (0.4, Mark("mid", log))
        )
        assert [entry.hook.label for entry in script.script_data] == ["early", "mid", "late"]
        assert script.length == 0.7

    def test_an_empty_script_is_refused(self):
        with pytest.raises(ValueError, match="at least one hook"):
            PhysicsScript([])

    def test_a_negative_start_time_is_refused(self, log):
        with pytest.raises(ValueError, match="start_time"):
            PhysicsScriptData(-0.1, Mark("x", log))


class TestScriptManager:
    def test_hooks_fire_at_their_start_times(self, world, log):
        body = place(world, state=PS(0))
        world.cur_time = 10.0
        assert body.play_script(SCRIPT_A)
        # AddScriptInternal: empty queue → start_time = Timer::cur_time, next hook due at
        # start_time + first start_time (acclient.c:329085-329089, 329113-329117).
        _at(world, body, 10.0)
        assert log == [("a0", 10.0)]
        _at(world, body, 10.49)  # cur_time < next_hook_time → stop (acclient.c:329197)
        assert len(log) == 1
        _at(world, body, 10.5)
        _at(world, body, 11.19)
        _at(world, body, 11.2)
        assert log == [("a0", 10.0), ("a1", 10.5), ("a2", 11.2)]
        # The last hook sets next_hook_time to -1.0 (acclient.c:329170-329173), so the same
        # pass drops the finished script and empties the queue (acclient.c:329208-329218).
        manager = body.script_manager
        assert manager.curr_data is None and manager.last_data is None
        assert manager.next_hook_time == -1.0

    def test_several_due_hooks_fire_in_one_update_in_order(self, world, log):
        body = place(world, state=PS(0))
        world.cur_time = 2.0
        body.play_script(SCRIPT_A)
        _at(world, body, 5.0)
        assert [label for label, _ in log] == ["a0", "a1", "a2"]

    def test_a_second_script_starts_when_the_first_ones_length_has_run(self, world, log):
        body = place(world, state=PS(0))
        world.cur_time = 10.0
        body.play_script(SCRIPT_A)
        _at(world, body, 10.0)
        world.cur_time = 10.6
        body.play_script(SCRIPT_B)
        # Queued behind A: start_time = A.start_time + A.length = 11.2 (acclient.c:329083-329085).
        assert body.script_manager.last_data.start_time == pytest.approx(11.2)
        _at(world, body, 11.19)
        assert [label for label, _ in log] == ["a0", "a1"]
        _at(world, body, 11.2)
        # A's last hook, A dropped, B's first hook: one pass (NextHook acclient.c:329163-329167).
        assert [label for label, _ in log] == ["a0", "a1", "a2", "b0"]
        _at(world, body, 11.49)
        assert len(log) == 4
        _at(world, body, 11.5)
        assert log[-1] == ("b1", 11.5)
        assert body.script_manager.curr_data is None

    def test_the_same_script_twice_plays_twice_in_sequence(self, world, log):
        body = place(world, state=PS(0))
        world.cur_time = 0.0
        body.play_script(SCRIPT_B)
        body.play_script(SCRIPT_B)
        for t in (0.0, 0.3, 0.6):
            _at(world, body, t)
        # Second copy starts at 0.0 + length 0.3; its hooks at 0.3 and 0.6.
        assert log == [("b0", 0.0), ("b1", 0.3), ("b0", 0.3), ("b1", 0.6)]

    def test_the_tick_fires_scripts_even_for_an_inactive_body(self, world, log):
        # UpdateObjectInternal calls ScriptManager::UpdateScripts outside the ACTIVE branch.
        body = place(world, state=PS(0))
        body.transient_state &= ~TransientState.ACTIVE
        body.play_script(SCRIPT_B)
        body.update_object_internal(0.1)
        assert log == [("b0", 0.0)]

    def test_add_script_without_a_registered_script_fails(self, world):
        body = place(world, state=PS(0))
        assert ScriptManager(body).add_script(0x33FFFFFF) is False


class TestPlayScript:
    def test_a_body_outside_the_world_answers_true_and_makes_no_manager(self, world):
        # play_script: no cell → return 1 (acclient.c:318074-318077).
        body = PhysicsObj(world, "loose")
        assert body.play_script(SCRIPT_A) is True
        assert body.script_manager is None

    def test_script_id_zero_is_refused(self, world):
        # play_script_internal: script_id 0 → 0, no manager (acclient.c:318043-318044, 318064).
        body = place(world, state=PS(0))
        assert body.play_script(0) is False
        assert body.script_manager is None

    def test_script_table_picks_the_first_variant_at_or_above_the_intensity(self):
        # PhysicsScriptTableData::GetScript walks while mod > entry.mod (acclient.c:336563).
        data = PhysicsScriptTableData([ScriptAndModData(0.5, SCRIPT_A), ScriptAndModData(1.0, SCRIPT_B)])
        table = PhysicsScriptTable({5: data})
        assert table.get_script(5, 0.3) == SCRIPT_A
        assert table.get_script(5, 0.5) == SCRIPT_A
        assert table.get_script(5, 0.7) == SCRIPT_B
        assert table.get_script(5, 1.5) == 0
        assert table.get_script(4, 0.3) == 0  # type missing (acclient.c:336951-336955)

    def test_default_script_hook_plays_the_table_script(self, world, log):
        body = place(world, state=PS(0))
        body.physics_script_table = PhysicsScriptTable(
            {7: PhysicsScriptTableData([ScriptAndModData(1.0, SCRIPT_B)])}
        )
        body.default_script, body.default_script_intensity = 7, 0.2
        DefaultScriptHook().execute(body)  # DefaultScriptHook::Execute → play_default_script
        _at(world, body, 0.0)
        assert log == [("b0", 0.0)]

    def test_default_script_without_a_table_plays_nothing(self, world):
        body = place(world, state=PS(0))
        assert body.play_default_script() is False  # acclient.c:320360-320365
        assert body.script_manager is None


class TestCallPES:
    def test_no_pause_plays_at_once(self, world, log):
        body = place(world, state=PS(0))
        CallPESHook(SCRIPT_B, 0.0).execute(body)  # delta < EPSILON → play_script_internal
        assert body.hooks == []
        _at(world, body, 0.0)
        assert log == [("b0", 0.0)]

    def test_a_pause_becomes_a_call_pes_tween_that_plays_when_it_reaches_one(self, world, log, monkeypatch):
        body = place(world, state=PS(0))
        world.physics_time = 3.0
        # RollDice(0, delta) picks the pause (acclient.c:318986); pin it to 0.4.
        monkeypatch.setattr(world.dice, "uniform", lambda lo, hi: 0.4 if hi == 1.0 else lo)
        body.call_pes(SCRIPT_B, 1.0)
        (hook,) = body.hooks
        assert (
            hook.hook_type,
            hook.interpolation_time,
            hook.start_value,
            hook.end_value,
            hook.user_data,
        ) == (
            HookType.CALL_PES,
            f32(0.4),  # the rolled pause is a float (acclient.c:318986-318987)
            0.0,
            1.0,
            SCRIPT_B,
        )
        world.physics_time = 3.3
        body.process_hooks()  # value 0.75 < 1 → nothing (CallPESInternal acclient.c:318964)
        assert body.script_manager is None
        world.physics_time = 3.5  # past the pause: fraction 1.0 → play and drop the hook
        body.process_hooks()
        assert body.hooks == []
        _at(world, body, world.cur_time)
        assert log == [("b0", world.cur_time)]
