"""Scenario files (README "Scenarios"): validation errors, units, defaults and event timing.

The malformed fixtures live in tests/scenarios/bad/; each starts with comment lines
``# key: <key path>`` (absent when no key applies) and ``# problem: <phrase>`` that say
what its error message must contain. Every test loads the real scenario; nothing is mocked.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

import acphys
from acphys.flags import DEFAULT_PHYSICS_STATE, PhysicsState, TransientState
from acphys.math import Vector3
from acphys.precision import f32
from acphys.scenario import builtin_scenarios
from support import UNIT_TOL, ulp32

SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
BAD = SCENARIOS / "bad"
VALID = SCENARIOS / "valid_minimal.toml"
BAD_FILES = sorted(BAD.glob("*.toml"))

#: Every case of the brief must have its fixture.
REQUIRED_BAD = {
    "unknown_top_key",
    "unknown_body_key",
    "origin_string",
    "velocity_two_elements",
    "heading_string",
    "velocity_nan",
    "origin_infinite",
    "no_body",
    "body_missing_landblock",
    "duplicate_body_names",
    "unknown_setup",
    "unknown_state",
    "origin_x_outside_block",
    "friction_above_one",
    "elasticity_above_limit",
    "velocity_too_fast",
    "event_unknown_body",
    "event_unknown_action",
    "event_negative_time",
    "event_after_duration",
    "event_extra_key",
    "event_unknown_key",
    "player_missing_body",
    "invalid_toml",
}

BODY = """
[[body]]
name = "a"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
"""


def expectation(path: Path) -> tuple[str | None, str]:
    """The ``# key:`` and ``# problem:`` header of a malformed fixture."""
    header = dict(re.findall(r"^# (key|problem): (.+)$", path.read_text(encoding="utf-8"), re.MULTILINE))
    assert "problem" in header, f"{path.name} has no '# problem:' line"
    return header.get("key"), header["problem"]


def assert_names_source_and_key(message: str, source: str, key: str | None, problem: str) -> None:
    assert message.startswith(f"{source}: "), message
    if key is not None:
        assert f"{source}: {key}: " in message, message
    assert problem in message, message
    assert "\n" not in message, message


def test_every_required_malformed_fixture_exists() -> None:
    missing = REQUIRED_BAD - {path.stem for path in BAD_FILES}
    assert not missing, f"no fixture for {sorted(missing)}"


@pytest.mark.parametrize("path", BAD_FILES, ids=[path.stem for path in BAD_FILES])
def test_load_scenario_rejects_malformed_file_naming_file_and_key(path: Path) -> None:
    key, problem = expectation(path)
    with pytest.raises(acphys.ScenarioError) as caught:
        acphys.load_scenario(path)
    assert_names_source_and_key(str(caught.value), str(path), key, problem)


@pytest.mark.parametrize("path", BAD_FILES, ids=[path.stem for path in BAD_FILES])
def test_parse_scenario_rejects_malformed_text_naming_source_and_key(path: Path) -> None:
    key, problem = expectation(path)
    with pytest.raises(acphys.ScenarioError) as caught:
        acphys.parse_scenario(path.read_text(encoding="utf-8"), source="memory.toml")
    assert_names_source_and_key(str(caught.value), "memory.toml", key, problem)


def test_invalid_toml_names_the_line() -> None:
    with pytest.raises(acphys.ScenarioError, match=r"line 4"):
        acphys.load_scenario(BAD / "invalid_toml.toml")


@pytest.mark.parametrize(
    ("text", "key", "problem"),
    [
        ('[scenario]\nduration = "long"\n' + BODY, "scenario.duration", "expected a number"),
        ("[scenario]\nduration = 0\n" + BODY, "scenario.duration", "(0, "),
        ("[scenario]\ndriver_hz = nan\n" + BODY, "scenario.driver_hz", "finite"),
        ("scenario = 5\n" + BODY, "scenario", "expected a table"),
        ('[body]\nname = "a"\n', "body", "array of tables"),
        (BODY + "velocity = [1.0, 2.0, -inf]\n", "body[0].velocity[2]", "finite"),
        (BODY + 'velocity = [1.0, "x", 0.0]\n', "body[0].velocity[1]", "expected a number"),
        (BODY + "velocity = [true, 0.0, 0.0]\n", "body[0].velocity[0]", "expected a number"),
        (BODY + "omega = [0.0, 0.0, inf]\n", "body[0].omega[2]", "finite"),
        (BODY + "heading = 400.0\n", "body[0].heading", "[-360, 360]"),
        (BODY + 'state = "gravity"\n', "body[0].state", "list of state names"),
        (BODY + 'on_ground = "yes"\n', "body[0].on_ground", "true or false"),
        (BODY + "scale = 0.0\n", "body[0].scale", "(0, 1000]"),
        (BODY + "friction = -0.1\n", "body[0].friction", "[0, 1]"),
        (BODY.replace('"0xA9B4"', '"0xFFFF"'), "body[0].landblock", "outside the world"),
        (BODY.replace('"0xA9B4"', '"A9-B4"'), "body[0].landblock", "landblock id"),
        (BODY.replace("96.0, 96.0", "96.0, 192.0"), "body[0].origin", "[0, 192)"),
        (BODY.replace("96.0, 96.0", "-0.5, 96.0"), "body[0].origin", "[0, 192)"),
        (BODY.replace('name = "a"\n', ""), "body[0].name", "missing"),
        (BODY.replace('"a"', '""'), "body[0].name", "non-empty string"),
        (BODY.replace("origin = [96.0, 96.0, 50.0]\n", ""), "body[0].origin", "missing"),
        ("[setup.b]\nspheres = []\nmass = 1.0\n" + BODY, "setup.b.mass", "unknown key"),
        (
            "[setup.b]\nspheres = [{ center = [0, 0], radius = 1 }]\n" + BODY,
            "setup.b.spheres[0].center",
            "list of 3 numbers",
        ),
        (
            "[setup.b]\nspheres = [{ center = [0, 0, 0], radius = -1 }]\n" + BODY,
            "setup.b.spheres[0].radius",
            "(0, 1000]",
        ),
        (
            BODY + '[[event]]\nat = 1.0\nbody = "a"\naction = "set_omega"\n',
            "event[0].omega",
            "missing",
        ),
        (
            BODY + '[[event]]\nbody = "a"\naction = "set_omega"\nomega = [0, 0, 1]\n',
            "event[0].at",
            "missing",
        ),
        (
            BODY + '[[event]]\nat = nan\nbody = "a"\naction = "set_omega"\nomega = [0, 0, 1]\n',
            "event[0].at",
            "finite",
        ),
        (
            BODY + '[[event]]\nat = 1.0\nbody = "a"\naction = "set_velocity"\nvelocity = [60, 0, 0]\n',
            "event[0].velocity",
            "50 m/s",
        ),
        (
            BODY + '[[event]]\nat = 1.0\nbody = "a"\naction = "set_state"\nstate = ["fly"]\n',
            "event[0].state",
            "unknown state 'fly'",
        ),
        (BODY + "[event]\nat = 1.0\n", "event", "array of tables"),
    ],
)
def test_more_invalid_values_name_source_and_key(text: str, key: str, problem: str) -> None:
    with pytest.raises(acphys.ScenarioError) as caught:
        acphys.parse_scenario(text, source="inline.toml")
    assert_names_source_and_key(str(caught.value), "inline.toml", key, problem)


def test_a_missing_file_names_the_file(tmp_path: Path) -> None:
    missing = tmp_path / "nope.toml"
    with pytest.raises(acphys.ScenarioError, match=re.escape(f"{missing}: no such file")):
        acphys.load_scenario(missing)


def test_a_directory_is_not_a_scenario(tmp_path: Path) -> None:
    with pytest.raises(acphys.ScenarioError, match=re.escape(f"{tmp_path}: cannot read")):
        acphys.load_scenario(tmp_path)


# -- valid scenarios ------------------------------------------------------------------------


def test_the_default_scenario_loads_with_its_seven_bodies() -> None:
    sim = acphys.load_scenario()
    assert sim.name == "default"
    names = ["skydiver", "ball", "spinner", "drifter", "sitter", "walker", "runner"]
    assert [body.name for body in sim.bodies] == names
    assert sim.duration == 8.0
    assert sim.driver_hz == 60.0
    assert "default" in builtin_scenarios()
    by_name = acphys.load_scenario("default")
    assert [body.name for body in by_name.bodies] == [body.name for body in sim.bodies]


def test_the_valid_fixture_loads_every_key() -> None:
    sim = acphys.load_scenario(VALID)
    assert sim.name == "minimal"
    assert (sim.duration, sim.driver_hz) == (2.0, 60.0)
    walker, rock = sim.body("walker"), sim.body("rock")
    assert sim.bodies == [walker, rock]
    assert sim.world.player is walker

    assert list(walker.position.frame.origin) == [10.0, 20.0, 30.0]
    assert walker.position.objcell_id == 0xA9B40001
    assert walker.state == PhysicsState.REPORT_COLLISIONS
    assert list(walker.velocity) == [1.0, 0.0, 0.0]
    # float32 fields, as retail stores them (acphys.precision)
    assert (walker.friction, walker.elasticity, walker.scale) == (0.5, f32(0.1), 1.5)
    assert not walker.transient_state & TransientState.CONTACT

    # An integer landblock is the same as its hex string; (0, 191.5) is outdoor cell 8.
    assert rock.position.objcell_id == 0xA9B40008
    assert rock.part_array is not None and rock.part_array.get_num_sphere() == 1


def test_a_scenario_without_a_name_is_named_after_its_file(tmp_path: Path) -> None:
    path = tmp_path / "unnamed-drop.toml"
    path.write_text(BODY, encoding="utf-8")
    sim = acphys.load_scenario(path)
    assert sim.name == "unnamed-drop"
    assert sim.duration == 10.0 and sim.driver_hz == 60.0


@pytest.mark.parametrize(
    ("heading", "facing"),
    [(0.0, (0.0, 1.0, 0.0)), (90.0, (1.0, 0.0, 0.0)), (180.0, (0.0, -1.0, 0.0)), (-90.0, (-1.0, 0.0, 0.0))],
)
def test_heading_is_compass_degrees(heading: float, facing: tuple[float, float, float]) -> None:
    sim = acphys.parse_scenario(BODY + f"heading = {heading}\n")
    frame = sim.body("a").position.frame
    # through float32 angles and a float32 quaternion: good to about 1e-5 degrees
    assert frame.get_heading() == pytest.approx(heading % 360.0, abs=2e-5)
    forward = frame.localtoglobalvec(Vector3(0.0, 1.0, 0.0))
    assert list(forward) == pytest.approx(list(facing), abs=UNIT_TOL)


def test_heading_defaults_to_north() -> None:
    frame = acphys.parse_scenario(BODY).body("a").position.frame
    assert (frame.qw, frame.qx, frame.qy, frame.qz) == pytest.approx((1.0, 0.0, 0.0, 0.0))


def test_omega_in_degrees_per_second_is_stored_in_radians_per_second() -> None:
    sim = acphys.parse_scenario(BODY + "omega = [90.0, -180.0, 45.0]\n")
    assert list(sim.body("a").omega) == pytest.approx([math.pi / 2, -math.pi, math.pi / 4])
    spinner = acphys.load_scenario().body("spinner")
    assert list(spinner.omega) == pytest.approx([0.0, 0.0, math.pi / 2])


def test_on_ground_starts_in_walkable_contact_with_a_horizontal_plane() -> None:
    sim = acphys.parse_scenario(BODY + "on_ground = true\n")
    body = sim.body("a")
    both = TransientState.CONTACT | TransientState.ON_WALKABLE
    assert body.transient_state & both == both
    assert list(body.contact_plane.N) == [0.0, 0.0, 1.0]
    assert body.contact_plane.d == -50.0  # the plane z = 50 through the origin
    assert body.contact_plane_cell_id == body.position.objcell_id


def test_without_on_ground_there_is_no_contact() -> None:
    body = acphys.parse_scenario(BODY + "on_ground = false\n").body("a")
    assert not body.transient_state & (TransientState.CONTACT | TransientState.ON_WALKABLE)
    assert not acphys.parse_scenario(BODY).body("a").transient_state & TransientState.CONTACT


def test_an_omitted_state_is_the_retail_default() -> None:
    assert acphys.parse_scenario(BODY).body("a").state == DEFAULT_PHYSICS_STATE
    assert acphys.load_scenario().body("sitter").state == DEFAULT_PHYSICS_STATE


def test_state_names_are_lower_case_only() -> None:
    with pytest.raises(acphys.ScenarioError, match=r"body\[0\]\.state: unknown state 'GRAVITY'"):
        acphys.parse_scenario(BODY + 'state = ["GRAVITY"]\n')


def test_state_names_combine_and_an_empty_list_clears() -> None:
    body = acphys.parse_scenario(BODY + 'state = ["gravity", "ethereal"]\n').body("a")
    assert body.state == PhysicsState.GRAVITY | PhysicsState.ETHEREAL
    assert acphys.parse_scenario(BODY + "state = []\n").body("a").state == PhysicsState(0)


@pytest.mark.parametrize(
    "line",
    [
        "velocity = [30.0, 40.0, 0.0]",  # exactly 50 m/s
        "elasticity = 0.1",
        "friction = 1.0",
        "heading = 360.0",
    ],
)
def test_limits_are_inclusive(line: str) -> None:
    acphys.parse_scenario(BODY + line + "\n", source="edge.toml")


def test_origin_at_the_block_edges_is_accepted() -> None:
    sim = acphys.parse_scenario(BODY.replace("96.0, 96.0", "0.0, 191.999"))
    assert list(sim.body("a").position.frame.origin) == [0.0, f32(191.999), 50.0]


# -- events ---------------------------------------------------------------------------------

EVENT_BODY = """
[scenario]
duration = 2.0
driver_hz = 60.0

[[body]]
name = "a"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
state = []
"""


def _event(at: float, action: str, value: str) -> str:
    key = action.removeprefix("set_")
    return f'\n[[event]]\nat = {at}\nbody = "a"\naction = "{action}"\n{key} = {value}\n'


@pytest.mark.parametrize(
    ("at", "tick"),
    [(0.0, 1), (0.25, 15), (0.49, 30), (0.5, 30), (0.51, 31), (2.0, 120)],
)
def test_an_event_fires_at_the_first_driver_tick_at_or_after_its_time(at: float, tick: int) -> None:
    sim = acphys.parse_scenario(EVENT_BODY + _event(at, "set_velocity", "[3.0, 0.0, 0.0]"))
    body = sim.body("a")
    for _ in range(tick - 1):
        sim.step()
        assert list(body.velocity) == [0.0, 0.0, 0.0], f"fired early, at tick {sim.tick}"
    if tick > 1:
        assert sim.time < at, "the tick before is already past the event"
    sim.step()
    assert sim.time >= at
    assert list(body.velocity) == [3.0, 0.0, 0.0]


def test_an_event_exactly_at_a_tick_fires_at_that_tick() -> None:
    # A 32-Hz driver ticks at exact binary times: tick 16 is exactly 0.5 s.
    text = EVENT_BODY.replace("driver_hz = 60.0", "driver_hz = 32.0")
    sim = acphys.parse_scenario(text + _event(0.5, "set_velocity", "[3.0, 0.0, 0.0]"))
    assert sim.tick_seconds == 1.0 / 32.0
    for _ in range(15):
        sim.step()
    assert list(sim.body("a").velocity) == [0.0, 0.0, 0.0]
    sim.step()
    assert sim.time == 0.5
    assert list(sim.body("a").velocity) == [3.0, 0.0, 0.0]


def test_set_velocity_at_half_a_second_is_applied_before_that_ticks_physics() -> None:
    sim = acphys.parse_scenario(EVENT_BODY + _event(0.5, "set_velocity", "[3.0, 0.0, 0.0]"))
    body = sim.body("a")
    sim.run(until=0.48)
    assert sim.tick == 29
    assert list(body.velocity) == [0.0, 0.0, 0.0]
    assert body.position.frame.origin.x == 96.0
    sim.step()  # the tick that reaches 0.5 s also runs the bodies (an even tick of a 60-Hz driver)
    assert list(body.velocity) == [3.0, 0.0, 0.0]
    # The new velocity already moved the body during this tick's step of 1/30 s.
    assert body.position.frame.origin.x == pytest.approx(96.0 + 3.0 / 30.0, abs=ulp32(96.0))


def test_set_omega_converts_degrees_and_set_state_replaces_the_state() -> None:
    text = EVENT_BODY + _event(0.5, "set_omega", "[0.0, 0.0, 90.0]") + _event(1.0, "set_state", '["gravity"]')
    sim = acphys.parse_scenario(text)
    body = sim.body("a")
    sim.run(until=0.5)
    assert list(body.omega) == pytest.approx([0.0, 0.0, math.pi / 2])
    assert body.state == PhysicsState(0)
    sim.run(until=1.0)
    assert body.state == PhysicsState.GRAVITY


def test_events_due_at_the_same_tick_apply_in_file_order() -> None:
    text = (
        EVENT_BODY
        + _event(0.5, "set_velocity", "[1.0, 0.0, 0.0]")
        + _event(0.495, "set_velocity", "[2.0, 0.0, 0.0]")
        + _event(0.5, "set_velocity", "[0.0, 4.0, 0.0]")
    )
    sim = acphys.parse_scenario(text)
    sim.run(until=0.5)
    assert list(sim.body("a").velocity) == [0.0, 4.0, 0.0]


def test_events_listed_out_of_time_order_fire_at_their_own_times() -> None:
    text = (
        EVENT_BODY
        + _event(1.0, "set_velocity", "[0.0, 0.0, 1.0]")
        + _event(0.5, "set_velocity", "[1.0, 0.0, 0.0]")
    )
    sim = acphys.parse_scenario(text)
    body = sim.body("a")
    sim.run(until=0.5)
    assert list(body.velocity) == [1.0, 0.0, 0.0]
    sim.run(until=1.0)
    assert list(body.velocity) == [0.0, 0.0, 1.0]


def test_the_default_spinner_reverses_at_four_seconds() -> None:
    sim = acphys.load_scenario()
    spinner = sim.body("spinner")
    sim.run(until=3.98)
    assert sim.tick == 239
    assert spinner.omega.z == pytest.approx(math.pi / 2)
    sim.run(until=4.0)
    assert sim.tick == 240
    assert spinner.omega.z == pytest.approx(-math.pi / 4)
