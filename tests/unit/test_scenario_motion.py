"""Scenario motion tables, motion events, the built-in humanoid and the default scenario's walkers."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import pytest

import acphys
from acphys.motion import commands as cmd
from acphys.motion.anim_hooks import AnimHookDir, EtherealHook, SoundHook
from acphys.motion.interp import RUN_ANIM_SPEED, SIDESTEP_ANIM_SPEED, WALK_ANIM_SPEED
from acphys.motion.motion_table import DEFAULT_SUBSTATE_ONLY, cycle_key
from acphys.precision import f32
from acphys.scenario import ScenarioError, parse_scenario
from acphys.scenario.motion_tables import builtin_motion_table, builtin_motion_tables
from support import step_records, ulp32, walk_tolerance

RUNNER = """
[scenario]
duration = 1.0
driver_hz = 20.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[motion_table.runner]
default_style = "NonCombat"

[[motion_table.runner.cycle]]
motion = "Ready"
framerate = 30.0
frames = 30

[[motion_table.runner.cycle]]
motion = "RunForward"
framerate = 30.0
frames = 30
velocity = [0.0, 4.0, 0.0]

[[motion_table.runner.cycle]]
motion = "TurnRight"
framerate = 30.0
frames = 30
omega = [0.0, 0.0, -90.0]
flags = ["default_substate_only"]

[[motion_table.runner.link]]
from = "Ready"
to = "RunForward"
framerate = 30.0
frames = 3
pos_frame = [0.0, 0.01, 0.0]
hooks = [
    { frame = 1, kind = "Sound" },
    { frame = 2, kind = "Ethereal", ethereal = false, direction = "forward" },
]

[[motion_table.runner.modifier]]
motion = "TurnRight"
framerate = 30.0
frames = 30
omega = [0.0, 0.0, -90.0]

[[body]]
name = "runner"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
motion_table = "runner"
on_ground = true
"""


def _table(sim: acphys.Simulation):
    return sim.body("runner").part_array.motion_table_manager.table


class TestMotionTableFromAScenario:
    def test_cycles_links_and_modifiers_are_keyed_as_retail_keys_them(self) -> None:
        table = _table(parse_scenario(RUNNER))
        style = cmd.NON_COMBAT
        assert table.default_style == style
        assert table.style_defaults == {style: cmd.READY}
        assert set(table.cycles) == {
            cycle_key(style, m) for m in (cmd.READY, cmd.RUN_FORWARD, cmd.TURN_RIGHT)
        }
        # A link is keyed (style, from), then by the full target id (get_link, acclient.c:337584).
        assert set(table.links) == {cycle_key(style, cmd.READY)}
        assert set(table.links[cycle_key(style, cmd.READY)]) == {cmd.RUN_FORWARD}
        # A modifier without a style is the style-independent one: the bare command index.
        assert set(table.modifiers) == {cmd.TURN_RIGHT & 0xFFFFFF}

    def test_values_are_converted_and_stored_as_float32(self) -> None:
        table = _table(parse_scenario(RUNNER))
        turn = table.cycles[cycle_key(cmd.NON_COMBAT, cmd.TURN_RIGHT)]
        assert turn.bitfield == DEFAULT_SUBSTATE_ONLY
        assert turn.omega.z == f32(math.radians(-90.0))
        run = table.cycles[cycle_key(cmd.NON_COMBAT, cmd.RUN_FORWARD)]
        assert run.velocity.y == 4.0
        assert run.anims[0].framerate == 30.0
        assert run.anims[0].animation.num_frames == 30
        assert run.anims[0].animation.pos_frames is None

    def test_position_frames_and_hooks_land_on_their_frames(self) -> None:
        link = _table(parse_scenario(RUNNER)).links[cycle_key(cmd.NON_COMBAT, cmd.READY)][cmd.RUN_FORWARD]
        animation = link.anims[0].animation
        assert [frame.origin.y for frame in animation.pos_frames] == [f32(0.01)] * 3
        assert animation.part_frames[0].hooks == []
        (sound,) = animation.part_frames[1].hooks
        assert isinstance(sound, SoundHook) and sound.direction == AnimHookDir.BOTH
        (ethereal,) = animation.part_frames[2].hooks
        assert isinstance(ethereal, EtherealHook) and ethereal.direction == AnimHookDir.FORWARD

    def test_a_motion_event_runs_the_body_through_its_table(self, tmp_path: Path) -> None:
        sim = parse_scenario(
            RUNNER + '\n[[event]]\nat = 0.0\nbody = "runner"\naction = "motion"\nmotion = "RunForward"\n'
        )
        trace = tmp_path / "run.jsonl"
        sim.run(trace=trace)
        records = step_records(trace)
        # enter_world's SetPosition commits the placement on the ground: set_on_walkable reports
        # hit_ground and handle_all_collisions the environment (acclient.c:323369); then the motion.
        assert records[0]["events"] == ["hit_ground", "collision:environment", "motion:RunForward"]
        # 30 boundaries of 4/30 m in the second (the link's two, the entry into the cycle, 27 more),
        # plus the link's position frames 0 and 1: overrunning the link leaves before its last frame
        # is composed (CSequence::update_internal, acclient.c:340658).
        runner = sim.body("runner")
        # (30 float32 position stores near 98 m)
        assert runner.position.frame.origin.y - 96.0 == pytest.approx(
            4.0 + 0.02, abs=walk_tolerance(98.0, 32)
        )
        assert runner.velocity.exactly_equals(acphys.Vector3())
        assert any("hook:SoundHook" in record["events"] for record in records)

    def test_a_refused_motion_is_reported_in_the_trace(self, tmp_path: Path) -> None:
        airborne = RUNNER.replace("on_ground = true", 'state = ["gravity"]').replace(
            "origin = [96.0, 96.0, 50.0]", "origin = [96.0, 96.0, 60.0]"
        )
        sim = parse_scenario(airborne + '\n[[event]]\nat = 0.1\nbody = "runner"\naction = "jump"\n')
        trace = tmp_path / "jump.jsonl"
        sim.run(until=0.3, trace=trace)
        events = [e for record in step_records(trace) for e in record["events"]]
        # An airborne gravity creature cannot jump: 0x24 (CMotionInterp::jump_is_allowed, acclient.c:343921).
        assert "jump:error:0x24" in events


class TestTheHumanoid:
    def test_it_is_the_only_builtin_and_a_fresh_copy_each_time(self) -> None:
        assert builtin_motion_tables() == ["humanoid"]
        assert builtin_motion_table("humanoid") is not builtin_motion_table("humanoid")
        with pytest.raises(KeyError, match="no built-in motion table 'ogre'"):
            builtin_motion_table("ogre")

    def test_its_velocities_are_the_retail_locomotion_speeds(self) -> None:
        table = builtin_motion_table("humanoid")
        style = cmd.NON_COMBAT

        def velocity(motion: int) -> acphys.Vector3:
            return table.cycles[cycle_key(style, motion)].velocity

        # CMotionInterp::get_state_velocity: walk 3.1199999, run 4.0, sidestep 1.25 (acclient.c:343539).
        assert velocity(cmd.WALK_FORWARD).y == WALK_ANIM_SPEED
        assert velocity(cmd.RUN_FORWARD).y == RUN_ANIM_SPEED
        assert velocity(cmd.SIDE_STEP_RIGHT).x == SIDESTEP_ANIM_SPEED
        # Backwards, left and turn-left are not entries: adjust_motion maps them onto these.
        for motion in (cmd.WALK_BACKWARDS, cmd.SIDE_STEP_LEFT, cmd.TURN_LEFT):
            assert cycle_key(style, motion) not in table.cycles

    def test_the_human_setup_comes_with_it(self) -> None:
        sim = parse_scenario(
            '[[body]]\nname = "h"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 1.0]\non_ground = true\n'
        )
        body = sim.body("h")
        assert body.part_array.motion_table_manager is not None
        assert body.movement_manager is not None
        # MakeMovementManager(init_motion) entered the default state: the Ready cycle on the ground ...
        assert body.part_array.motion_table_manager.state.substate == cmd.READY
        # ... and Falling in the air: enter_default_state (acclient.c:344559) ends in LeaveGround, whose
        # apply_interpreted_movement plays Falling when contact forbids moving (acclient.c:344146).
        sim = parse_scenario('[[body]]\nname = "h"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 9.0]\n')
        assert sim.body("h").part_array.motion_table_manager.state.substate == cmd.FALLING

    def test_a_body_can_opt_out(self) -> None:
        sim = parse_scenario(
            '[[body]]\nname = "h"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 1.0]\nmotion_table = "none"\n'
        )
        assert sim.body("h").movement_manager is None


class TestTheDefaultScenario:
    def test_the_walker_and_the_runner_step_one_animation_frame_at_a_time(self, tmp_path: Path) -> None:
        trace = tmp_path / "default.jsonl"
        acphys.load_scenario().run(until=2.5, trace=trace)
        records = step_records(trace)
        for name, speed in (("walker", float(WALK_ANIM_SPEED)), ("runner", RUN_ANIM_SPEED)):
            ys = [record["origin"][1] for record in records if record["body"] == name]
            frame = speed / 30.0
            steps = [(b - a) / frame for a, b in itertools.pairwise(ys)]
            # Every step is a whole number of frames (0, 1 or 2 at 30 fps and 30 Hz), to the
            # rounding of the two float32 positions it is the difference of.
            tolerance = 2 * ulp32(max(ys)) / frame
            assert all(abs(s - round(s)) < tolerance and round(s) in (0, 1, 2) for s in steps), name
            assert sum(round(s) for s in steps) >= 55, name  # moving from 0.5 s to 2.5 s


def test_motion_events_need_a_motion_table() -> None:
    text = (
        "[setup.rock]\nspheres = [{ center = [0.0, 0.0, 0.5], radius = 0.5 }]\n"
        '[[body]]\nname = "r"\nsetup = "rock"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 1.0]\n'
        '[[event]]\nat = 0.0\nbody = "r"\naction = "turn_to"\nheading = 90.0\n'
    )
    with pytest.raises(ScenarioError, match=r"event\[0\].action: body 'r' has no motion table"):
        parse_scenario(text)


def test_the_readme_example_scenario_runs() -> None:
    readme = Path(__file__).resolve().parents[2] / "README.md"
    block = readme.read_text(encoding="utf-8").split("```toml\n", 1)[1].split("```", 1)[0]
    sim = parse_scenario(block, source="README.md")
    sim.run()
    walker = sim.body("walker")
    # Walking north from 0.5 s to 3 s at 3.12 m/s, on the ground and with no velocity of its own.
    assert walker.position.frame.origin.y - 96.0 == pytest.approx(2.5 * 3.12, abs=0.25)
    assert walker.velocity.exactly_equals(acphys.Vector3())


def test_the_package_docstring_example_holds() -> None:
    import doctest

    result = doctest.testmod(acphys)
    assert result.attempted >= 5 and result.failed == 0


def test_the_example_script_runs(capsys: pytest.CaptureFixture[str]) -> None:
    import runpy

    script = Path(__file__).resolve().parents[2] / "examples" / "walk_to_a_point.py"
    runpy.run_path(str(script), run_name="__main__")
    out = capsys.readouterr().out
    assert "still moving to: False" in out
    assert "facing 90.0 degrees" in out
    assert "jump: error 0x0" in out
    assert "on walkable ground: True" in out
