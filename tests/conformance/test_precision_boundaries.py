"""Three places where float32 storage decides the outcome, end to end through scenarios.

Each was measured to go the other way when acphys stored float64 (the lengths, radii and
framerates as written, not as retail's data holds them). The scenarios keep every position
exactly representable (a sphere of radius 0.5 centred 0.5 above its origin on flat ground at
50 m), so what decides is the stored data, not the rounding of a position.
"""

from __future__ import annotations

import math

import pytest

import acphys
from acphys.precision import f32
from acphys.transition.transition import Transition

GROUND = 50.0
STEP = 3.12 / 30.0  # one WalkForward frame of root motion (CMotionInterp::get_state_velocity)


def _steps_scenario() -> str:
    boxes = {"b060": (90.0, 0.6, 0.4), "b059": (96.0, 0.59, 0.4), "b030": (102.0, 0.3, 0.2)}
    text = '[scenario]\nname = "steps"\nduration = 1.5\ndriver_hz = 60.0\n'
    text += f'[[landblock]]\nid = "0xA9B4"\nheight = {GROUND}\n'
    for name, (x, top, step) in boxes.items():
        text += (
            f"[setup.{name}]\nboxes = [{{ min = [-1.0, 0.0, 0.0], max = [1.0, 4.0, {top}] }}]\n"
            f"[setup.walker-{name}]\nspheres = [{{ center = [0.0, 0.0, 0.5], radius = 0.5 }}]\n"
            f'step_up_height = {step}\nstep_down_height = {step}\nmotion_table = "humanoid"\n'
            f'[[object]]\nname = "{name}"\nsetup = "{name}"\nlandblock = "0xA9B4"\n'
            f"origin = [{x}, 98.0, {GROUND}]\n"
            f'[[body]]\nname = "at-{name}"\nsetup = "walker-{name}"\nlandblock = "0xA9B4"\n'
            f'origin = [{x}, 96.0, {GROUND}]\nstate = ["gravity", "report_collisions"]\non_ground = true\n'
            f'[[event]]\nat = 0.0\nbody = "at-{name}"\naction = "motion"\nmotion = "WalkForward"\n'
        )
    return text


@pytest.fixture(scope="module")
def steps() -> acphys.Simulation:
    sim = acphys.parse_scenario(_steps_scenario(), source="steps")
    sim.run()
    return sim


class TestStepUpAtOneAndAHalfTimesTheStepHeight:
    """CTransition::step_up (acclient.c:312793) steps down by step_up_height without lowering the
    check position, so the sphere may rise 1.5 x step_up_height: CPolygon::adjust_sphere_to_plane
    (acclient.c:359533) rejects a new walk_interp below -0.5 (acclient.c:359575). The box top is a
    float32 in the box's frame and so is the step-up height (OBJECTINFO::step_up_height, a float):
    interp = 1 - rise / step, and f32(0.6) / f32(0.4) = 1.5000000373 > 1.5."""

    def test_the_ratio_at_the_limit_is_over_one_and_a_half_in_float32_only(self) -> None:
        assert 1.0 - f32(0.6) / f32(0.4) < -0.5 <= 1.0 - 0.6 / 0.4
        assert 1.0 - f32(0.3) / f32(0.2) < -0.5 <= 1.0 - 0.3 / 0.2
        assert 1.0 - f32(0.59) / f32(0.4) >= -0.5

    @pytest.mark.parametrize("box", ["b060", "b030"])
    def test_a_box_of_exactly_one_and_a_half_step_heights_blocks(self, steps, box: str) -> None:
        body = steps.body(f"at-{box}")
        origin = body.position.frame.origin
        # Held on the ground before the face at y = 98 (radius 0.5): the rolled-back step leaves
        # it sliding along the face (CTransition::validate_transition, acclient.c:312193).
        assert origin.z == GROUND
        assert origin.y < 98.0 - 0.5
        assert origin.y > 98.0 - 0.5 - STEP - 1e-3
        assert body.transient_state & acphys.TransientState.SLIDING

    def test_a_box_just_under_the_limit_is_climbed(self, steps) -> None:
        origin = steps.body("at-b059").position.frame.origin
        # Up on the top (the sphere's low point on the float32 plane z = 50 + 0.59) and walking on.
        assert origin.z == f32(GROUND + f32(0.59))
        assert origin.y > 98.0


def test_a_dart_moving_one_metre_a_quantum_takes_five_sub_steps_and_stops_touching(monkeypatch) -> None:
    # CTransition::calc_num_steps (acclient.c:311763): ceil(|offset| / radius) sub-steps. The
    # offset between float32 positions is 1 m minus float32 rounding, the radius is f32(0.2)
    # (SPHEREPATH::init_sphere stores it, acclient.c:313681): 4.9999999 → 5. With a double
    # offset of 30 · f32(1/30) = 1.00000005 m and a double 0.2 it was 6, and the dart stopped a
    # sixth of a metre short of the pillar.
    counts: list[int] = []
    real = Transition.calc_num_steps

    def counting(self: Transition):
        result = real(self)
        counts.append(result[2])
        return result

    monkeypatch.setattr(Transition, "calc_num_steps", counting)
    text = (
        '[scenario]\nname = "dart"\nduration = 0.4\ndriver_hz = 30.0\n'
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        '[setup.dart]\nspheres = [{ center = [0.0, 0.0, 0.0], radius = 0.2 }]\nmotion_table = "none"\n'
        "[setup.pillar]\ncylspheres = [{ low_pt = [0.0, 0.0, 0.0], radius = 1.0, height = 3.0 }]\n"
        '[[object]]\nname = "pillar"\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [100.0, 100.0, 50.0]\n'
        '[[body]]\nname = "dart"\nsetup = "dart"\nlandblock = "0xA9B4"\norigin = [90.0, 100.0, 51.0]\n'
        'state = ["missile", "report_collisions"]\nvelocity = [30.0, 0.0, 0.0]\n'
    )
    sim = acphys.parse_scenario(text, source="dart")
    dart = sim.body("dart")
    stops: list[tuple[float, list[str]]] = []
    dart.observer = lambda body, _q: stops.append((body.position.frame.origin.x, list(body.step_events)))
    sim.run()
    # Every flight step before the hit is five sub-steps (the placement's own sweeps are one).
    flight = [n for n in counts if n > 1]
    assert flight[:8] == [5] * 8
    hit = next(i for i, (_x, events) in enumerate(stops) if "collision:environment" in events)
    x_hit = stops[hit][0]
    # A PATH_CLIPPED sweep stops at its last clear sub-step (find_transitional_position,
    # acclient.c:313170): 8 steps and 4 sub-steps of 0.2 m from x = 90 put the front of the dart
    # on the pillar's face at 99, to the float32 drift of those 44 stores (under EPSILON).
    assert hit == 8
    assert 99.0 - (x_hit + 0.2) == pytest.approx(0.0, abs=2e-4)
    assert 99.0 - (x_hit + 0.2) >= 0.0


def _crossing_steps(framerate: float, quantum: float, steps: int) -> list[int]:
    """The steps on which CSequence::update_internal crosses a frame boundary: frame_number (a
    double) gains framerate · quantum each step (acclient.c:340690-340713)."""
    frame_number, crossed = 0.0, []
    for step in range(1, steps + 1):
        before = math.floor(frame_number)
        frame_number = framerate * quantum + frame_number
        crossed += [step] * (math.floor(frame_number) - before)
    return crossed


def test_walking_at_speed_064_crosses_frames_on_the_float32_framerate() -> None:
    # CMotionTable::add_motion stores the node framerate framerate · speed as a float: with the
    # float speed f32(0.64), 30 · 0.64 is 19.19999886, not 19.2, and the walk crosses its frames
    # one step later than 19.2 would at steps 26, 51, 76 and 101 (25, 50, 75 and 100 at 19.2).
    text = (
        '[scenario]\nname = "slow"\nduration = 3.4\ndriver_hz = 30.0\n'
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        '[[body]]\nname = "slow"\nlandblock = "0xA9B4"\norigin = [96.0, 60.0, 50.0]\non_ground = true\n'
        '[[event]]\nat = 0.0\nbody = "slow"\naction = "motion"\nmotion = "WalkForward"\nspeed = 0.64\n'
    )
    sim = acphys.parse_scenario(text, source="slow")
    ys: list[float] = []
    sim.body("slow").observer = lambda body, _q: ys.append(body.position.frame.origin.y)
    sim.run()
    quantum = f32(1.0 / 30.0)
    retail = _crossing_steps(f32(30.0 * f32(0.64)), quantum, len(ys))
    double = _crossing_steps(19.2, quantum, len(ys))
    assert sorted(set(retail) ^ set(double)) == [25, 26, 50, 51, 75, 76, 100, 101]
    # Root motion moves the body on the steps whose frame boundary it crosses (the first step
    # only enters the cycle): step k's record is ys[k - 1].
    moved = [k for k in range(2, len(ys) + 1) if ys[k - 1] != ys[k - 2]]
    assert moved == retail
