"""Scenario motion requests and the run key; player and creature bodies; unconstrain.

Retail's keyboard path (``CommandInterpreter::MovePlayer``, acclient.c:717799) sends DoMotion and
StopMotion with default MovementParameters, whose ``hold_key_to_apply`` is ``HoldKey_Invalid``
(``MovementParameters::MovementParameters`` @ 0x00524380, acclient.c:339436): the run key stays
as it is. A scenario event without ``hold_run`` does the same.
"""

from __future__ import annotations

import math

import pytest

import acphys
from acphys.motion import commands as cmd
from acphys.motion.movement import HoldKey

HEADER = (
    '[scenario]\nname = "run-key"\nduration = 3.0\ndriver_hz = 30.0\n'
    '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
)
BODY = '[[body]]\nname = "runner"\nlandblock = "0xA9B4"\norigin = [96.0, 60.0, 50.0]\non_ground = true\n'


def _event(at: float, action: str, motion: str, extra: str = "") -> str:
    return f'[[event]]\nat = {at}\nbody = "runner"\naction = "{action}"\nmotion = "{motion}"\n{extra}'


def _speeds(text: str) -> dict[float, tuple[float, list[str]]]:
    """Speed over ground (m/s) and events of each step, by the step's time."""
    sim = acphys.parse_scenario(text, source="run-key")
    previous = sim.body("runner").position.frame.origin.copy()
    steps: dict[float, tuple[float, list[str]]] = {}

    def record(body: acphys.PhysicsObj, quantum: float) -> None:
        nonlocal previous
        origin = body.position.frame.origin
        steps[round(sim.world.physics_time, 4)] = (
            (origin - previous).length() / quantum,
            list(body.step_events),
        )
        previous = origin.copy()

    sim.body("runner").observer = record
    sim.run()
    return steps


def _at(steps: dict[float, tuple[float, list[str]]], t: float) -> tuple[float, list[str]]:
    return steps[min(steps, key=lambda k: abs(k - t))]


def test_a_running_body_that_starts_turning_keeps_running() -> None:
    steps = _speeds(
        HEADER
        + BODY
        + _event(0.0, "motion", "WalkForward", "hold_run = true\n")
        + _event(1.0, "motion", "TurnRight")
    )
    assert _at(steps, 0.5)[0] == pytest.approx(4.0, abs=1e-3)  # running (RunForward, 4 m/s)
    assert "motion:TurnRight" in _at(steps, 1.0)[1]
    # The turn comes without hold_run: HoldKey_Invalid leaves the run key pressed, so the body
    # keeps running at 4 m/s instead of slowing to the 3.12 m/s walk.
    assert _at(steps, 1.5)[0] == pytest.approx(4.0, abs=1e-3)


def test_releasing_the_run_key_on_the_turn_slows_to_a_walk() -> None:
    steps = _speeds(
        HEADER
        + BODY
        + _event(0.0, "motion", "WalkForward", "hold_run = true\n")
        + _event(1.0, "motion", "TurnRight", "hold_run = false\n")
    )
    assert _at(steps, 1.5)[0] == pytest.approx(3.12, abs=1e-3)


def test_stop_motion_walk_forward_stops_a_run() -> None:
    steps = _speeds(
        HEADER
        + BODY
        + _event(0.0, "motion", "WalkForward", "hold_run = true\n")
        + _event(2.0, "stop_motion", "WalkForward")
    )
    # RunForward is WalkForward with the run key: StopMotion of WalkForward with the key as it is
    # (held) matches the raw state's forward command and stops it (no error).
    assert _at(steps, 2.0)[1] == ["stop_motion:WalkForward"]
    assert _at(steps, 2.5)[0] == 0.0


def test_stop_motion_with_the_run_key_released_is_refused_while_running() -> None:
    steps = _speeds(
        HEADER
        + BODY
        + _event(0.0, "motion", "WalkForward", "hold_run = true\n")
        + _event(2.0, "stop_motion", "WalkForward", "hold_run = false\n")
    )
    # HoldKey_None asks to stop a walk, and the body is running: retail's 0x43 (the motion is not
    # the current one), and it runs on.
    assert _at(steps, 2.0)[1] == ["stop_motion:WalkForward:error:0x43"]
    assert _at(steps, 2.5)[0] == pytest.approx(4.0, abs=1e-3)


def test_an_absent_hold_run_is_holdkey_invalid_and_present_ones_are_run_or_none() -> None:
    from acphys.scenario.events import _params
    from acphys.scenario.values import Ctx

    ctx = Ctx("x")
    assert _params(ctx, "e", {}).hold_key_to_apply is HoldKey.INVALID
    assert _params(ctx, "e", {"hold_run": True}).hold_key_to_apply is HoldKey.RUN
    assert _params(ctx, "e", {"hold_run": False}).hold_key_to_apply is HoldKey.NONE


@pytest.mark.parametrize(("npc", "runs_on"), [(False, False), (True, True)])
def test_on_landing_a_player_replays_its_raw_state_and_a_creature_its_interpreted_one(
    npc: bool, runs_on: bool
) -> None:
    # A body in the air sent RunForward directly: RawMotionState::ApplyMotion never keeps
    # RunForward (a player runs by WalkForward with the run key), the interpreted state does.
    # On landing CMotionInterp::HitGround replays the movement (apply_current_movement,
    # acclient.c:344300): the player path (no weenie, or IsThePlayer) replays the raw state and
    # stands; npc = true gives a creature weenie that is not the player, which replays the
    # interpreted state and runs on.
    # 3 m up: beyond the 1.5-m step-down with which placement would put a human on the ground.
    text = HEADER + BODY.replace("on_ground = true", "npc = true" if npc else "").replace("50.0]", "53.0]")
    text += '[[event]]\nat = 0.0\nbody = "runner"\naction = "motion"\nmotion = "RunForward"\n'
    sim = acphys.parse_scenario(text, source="npc")
    body = sim.body("runner")
    assert (body.weenie_obj is not None and not body.weenie_obj.is_the_player()) == npc
    sim.run()
    assert body.transient_state & acphys.TransientState.ON_WALKABLE
    assert (body.position.frame.origin.y > 62.0) == runs_on
    assert (body.get_minterp().interpreted_state.forward_command == cmd.RUN_FORWARD) == runs_on


def test_unconstrain_leaves_a_body_without_a_position_manager_as_it_is() -> None:
    # Retail has no CPhysicsObj entry for UnConstrain: PositionManager::UnConstrain
    # (acclient.c:388380) acts on a manager the body has. Making one would activate the body.
    text = HEADER + BODY + '[[event]]\nat = 0.5\nbody = "runner"\naction = "unconstrain"\n'
    sim = acphys.parse_scenario(text, source="unconstrain")
    body = sim.body("runner")
    sim.run(until=1.0)
    assert body.position_manager is None
    assert math.isfinite(body.position.frame.origin.y)
