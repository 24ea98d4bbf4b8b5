"""CPhysicsObj::MoveToObject / TurnToObject and their _Internal halves, and the scenario events.

MoveToObject @ 0x00512860 (acclient.c:319766) makes the movement manager, looks the target up
(nothing more when there is none), and calls MoveToObject_Internal @ 0x005102E0 (317482) with
the target's part-array height and radius and its top-level object (``v9[5].hash_next``, the
parent, when set), which performs a type-6 MovementStruct. TurnToObject @ 0x00512940 (319827)
looks the target up first and calls TurnToObject_Internal @ 0x005103F0 (317532): type 8.
"""

from __future__ import annotations

import pytest

import acphys
from acphys.body.children import WHOLE_OBJECT
from acphys.flags import TransientState as TS
from acphys.math.frame import Frame
from acphys.math.vector import Vector3 as V
from acphys.motion.motion_table import MotionTable
from acphys.motion.move_to import cylinder_distance
from acphys.motion.movement import MovementParameters, MovementType
from acphys.precision import f32
from acphys.scenario import parse_scenario
from acphys.scenario.motion_tables import builtin_motion_table
from support import place

TICK = 1.0 / 30.0


def _human(world, name, x, y, table: MotionTable | None = None):
    return place(world, name=name, origin=(x, y, 50.0), on_ground=True, motion_table=table)


def _run(world, bodies, seconds):
    for _ in range(round(seconds / TICK)):
        world.cur_time += TICK
        for body in bodies:
            body.update_object()


class TestMoveToObject:
    def test_an_unknown_target_only_makes_the_movement_manager(self, world):
        walker = _human(world, "walker", 96.0, 96.0)
        assert walker.movement_manager is None
        walker.transient_state &= ~TS.ACTIVE
        walker.move_to_object(0x50000099, MovementParameters())
        # MovementManager::Create + EnterDefaultState, and a non-static body is woken
        # (acclient.c:319784-319798); GetObjectA finds nothing, so no request (319801-319806).
        assert walker.movement_manager is not None
        assert walker.transient_state & TS.ACTIVE
        assert walker.movement_manager.moveto_manager is None

    def test_the_request_carries_the_targets_size_and_top_level_object(self, world):
        world.set_flat_ground(0xA9B4, 50.0)
        walker = _human(world, "walker", 96.0, 96.0, builtin_motion_table("humanoid"))
        target = _human(world, "target", 96.0, 104.0)
        walker.move_to_object(target.id, MovementParameters())
        moveto = walker.movement_manager.moveto_manager
        assert moveto.movement_type == MovementType.MOVE_TO_OBJECT
        assert moveto.sought_object_id == target.id
        assert moveto.top_level_object_id == target.id
        # CPartArray::GetRadius / GetHeight of the human: 0.48 and 1.835 (acclient.c:319807-319817),
        # float fields of the setup and of the move-to manager.
        assert moveto.sought_object_radius == f32(0.48)
        assert moveto.sought_object_height == f32(1.835)

    def test_a_held_target_is_sought_through_its_holder(self, world):
        world.set_flat_ground(0xA9B4, 50.0)
        walker = _human(world, "walker", 96.0, 96.0, builtin_motion_table("humanoid"))
        holder = _human(world, "holder", 96.0, 104.0)
        sword = _human(world, "sword", 20.0, 20.0)
        assert sword.set_parent(holder, WHOLE_OBJECT, Frame(V(0.5, 0.0, 1.0)))
        walker.move_to_object(sword.id, MovementParameters())
        moveto = walker.movement_manager.moveto_manager
        # The parent's id is the top-level id (acclient.c:319819-319822); the sword stays the sought object.
        assert moveto.sought_object_id == sword.id
        assert moveto.top_level_object_id == holder.id

    def test_the_walker_arrives_within_distance_to_object(self, world):
        world.set_flat_ground(0xA9B4, 50.0)
        walker = _human(world, "walker", 96.0, 96.0, builtin_motion_table("humanoid"))
        target = _human(world, "target", 96.0, 104.0, builtin_motion_table("humanoid"))
        _run(world, [walker, target], 0.5)
        walker.move_to_object(target.id, MovementParameters())
        moveto = walker.movement_manager.moveto_manager
        for _ in range(300):
            _run(world, [walker, target], TICK)
            if not moveto.is_moving_to():
                break
        assert not moveto.is_moving_to()
        gap = cylinder_distance(
            walker.get_radius(),
            walker.get_height(),
            walker.position,
            target.get_radius(),
            target.get_height(),
            target.position,
        )
        assert gap <= MovementParameters().distance_to_object  # 0.6 (HandleMoveToPosition, acclient.c:345688)
        assert walker.position.frame.origin.y > 96.0 + 6.0


class TestTurnToObject:
    def test_an_unknown_target_does_nothing(self, world):
        walker = _human(world, "walker", 96.0, 96.0)
        walker.turn_to_object(0x50000099, MovementParameters())
        # TurnToObject only reaches TurnToObject_Internal (which makes the manager) when found.
        assert walker.movement_manager is None

    def test_the_walker_turns_to_face_the_target(self, world):
        world.set_flat_ground(0xA9B4, 50.0)
        walker = _human(world, "walker", 96.0, 96.0, builtin_motion_table("humanoid"))
        target = _human(world, "target", 104.0, 96.0)
        walker.turn_to_object(target.id, MovementParameters())
        moveto = walker.movement_manager.moveto_manager
        assert moveto.movement_type == MovementType.TURN_TO_OBJECT
        for _ in range(120):
            _run(world, [walker, target], TICK)
            if not moveto.is_moving_to():
                break
        # Due east of the walker: compass heading 90 (desired_heading 0 added to the bearing).
        assert walker.position.frame.get_heading() == pytest.approx(90.0, abs=1e-3)
        assert walker.position.frame.origin.x == pytest.approx(96.0, abs=1e-9)


def test_the_scenario_events_reach_the_body(tmp_path):
    text = """
[scenario]
name = "meet"
duration = 4.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[body]]
name = "walker"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
on_ground = true

[[body]]
name = "friend"
landblock = "0xA9B4"
origin = [104.0, 100.0, 50.0]
on_ground = true

[[event]]
at = 0.2
body = "walker"
action = "move_to_object"
target = "friend"
distance = 1.0

[[event]]
at = 0.2
body = "friend"
action = "turn_to_object"
target = "walker"
"""
    sim = parse_scenario(text, source="meet.toml")
    trace = tmp_path / "meet.jsonl"
    sim.run(trace=trace)
    walker, friend = sim.body("walker"), sim.body("friend")
    gap = cylinder_distance(
        walker.get_radius(),
        walker.get_height(),
        walker.position,
        friend.get_radius(),
        friend.get_height(),
        friend.position,
    )
    assert gap <= 1.0
    assert not walker.movement_manager.moveto_manager.is_moving_to()
    lines = trace.read_text(encoding="utf-8")
    assert '"move_to_object:friend"' in lines and '"turn_to_object:walker"' in lines


def test_a_target_that_is_not_another_body_is_an_error() -> None:
    text = """
[[body]]
name = "walker"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]

[[event]]
at = 0.0
body = "walker"
action = "move_to_object"
target = "walker"
"""
    with pytest.raises(acphys.ScenarioError, match=r"event\[0\]\.target: no other body named 'walker'"):
        parse_scenario(text, source="x.toml")
