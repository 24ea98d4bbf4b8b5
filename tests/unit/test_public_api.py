"""The Python API of issue 15: flags that print their names, NumPy arrays of vectors, frames,
positions and whole simulations, ``py.typed``, bodies and events added to a running simulation,
step and collision callbacks, and the example that drives it all (``examples/api_tour.py``)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tomllib
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

import acphys
from acphys import (
    BodyArrays,
    CollisionKind,
    CollisionReport,
    Frame,
    PhysicsObj,
    PhysicsState,
    Position,
    ScenarioError,
    TransientState,
    Vector3,
)
from dat_support import SETUP_ID, f32, setup_record, simple_dat

ROOT = Path(__file__).resolve().parents[2]
LANDBLOCK = 0xA9B4


def default_sim(until: float | None = None) -> acphys.Simulation:
    sim = acphys.load_scenario()
    if until is not None:
        sim.run(until=until)
    return sim


# -- flags --------------------------------------------------------------------------------------


def test_transient_state_prints_its_flags_by_name() -> None:
    walker = default_sim(until=0.5).body("walker")
    assert isinstance(walker.transient_state, TransientState)
    assert repr(walker.transient_state) == "<TransientState.CONTACT|ON_WALKABLE|ACTIVE: 131>"
    assert walker.transient_state & TransientState.CONTACT
    assert not walker.transient_state & TransientState.WATER_CONTACT
    assert TransientState.ON_WALKABLE in walker.transient_state
    assert walker.transient_state == 131


def test_state_prints_its_flags_by_name() -> None:
    skydiver = default_sim().body("skydiver")
    assert isinstance(skydiver.state, PhysicsState)
    assert repr(skydiver.state) == "<PhysicsState.REPORT_COLLISIONS|GRAVITY|EDGE_SLIDE: 4195336>"
    assert PhysicsState.GRAVITY in skydiver.state
    assert skydiver.state.name == "REPORT_COLLISIONS|GRAVITY|EDGE_SLIDE"


def test_flag_fields_take_flags_and_ints() -> None:
    body = default_sim().body("ball")
    body.state = PhysicsState.GRAVITY | PhysicsState.REPORT_COLLISIONS
    assert repr(body.state) == "<PhysicsState.REPORT_COLLISIONS|GRAVITY: 1032>"
    body.state = 0x4
    assert body.state is PhysicsState.ETHEREAL
    body.transient_state = 0
    body.transient_state |= TransientState.CONTACT
    assert body.transient_state is TransientState.CONTACT
    body.set_state(PhysicsState.GRAVITY)
    assert body.state is PhysicsState.GRAVITY


def test_the_tick_keeps_the_flags_as_plain_ints() -> None:
    """The tick tests bits on plain ints (an ``IntFlag`` costs more); the flags are the public view."""
    sim = default_sim(until=1.0)
    for body in sim.bodies:
        assert type(vars(body)["_state"]) is int
        assert type(vars(body)["_transient_state"]) is int
        assert body.transient_state == vars(body)["_transient_state"]


# -- NumPy ----------------------------------------------------------------------------------------


def test_a_body_origin_is_a_float_array_of_three() -> None:
    origin = default_sim(until=0.5).body("walker").position.frame.origin
    array = np.asarray(origin)
    assert array.dtype == np.float64
    assert array.shape == (3,)
    assert array.tolist() == [origin.x, origin.y, origin.z]


def test_vector_arrays() -> None:
    v = Vector3(1.0, -2.5, 3.25)
    assert np.asarray(v).tolist() == [1.0, -2.5, 3.25]
    assert np.asarray(v, dtype=np.float32).dtype == np.float32
    copy = v.to_numpy()
    copy[0] = 99.0
    assert v.x == 1.0, "to_numpy is a copy"
    assert np.array([v, v]).shape == (2, 3)
    with pytest.raises(ValueError, match="without a copy"):
        np.asarray(v, copy=False)


def test_frame_and_position_arrays() -> None:
    frame = Frame.from_heading(Vector3(10.0, 20.0, 30.0), 90.0)
    array = np.asarray(frame)
    assert array.shape == (7,)
    assert array.tolist() == [10.0, 20.0, 30.0, frame.qw, frame.qx, frame.qy, frame.qz]
    assert frame.to_numpy().tolist() == array.tolist()
    position = Position((LANDBLOCK << 16) | 0x0001, frame)
    assert np.asarray(position).tolist() == array.tolist()
    assert position.to_numpy().tolist() == array.tolist()
    assert position.global_origin() == (0xA9 * 192.0 + 10.0, 0xB4 * 192.0 + 20.0, 30.0)


def test_frame_matrix_takes_local_points_to_the_parent_frame() -> None:
    frame = Frame.from_heading(Vector3(10.0, 20.0, 30.0), 90.0)  # facing east
    matrix = frame.to_matrix()
    assert matrix.shape == (4, 4)
    point = Vector3(0.3, 2.0, -1.0)
    expected = np.asarray(frame.localtoglobal(point))
    assert np.allclose(matrix @ [*point, 1.0], [*expected, 1.0], atol=1e-5)
    assert np.allclose(matrix[:3, 1], [1.0, 0.0, 0.0], atol=1e-6), "local forward (+y) is east"


def test_simulation_arrays_in_one_call() -> None:
    sim = default_sim(until=4.0)  # the drifter has crossed into landblock 0xAAB4
    arrays = sim.arrays()
    assert isinstance(arrays, BodyArrays)
    bodies = sim.bodies
    assert arrays.names == tuple(body.name for body in bodies)
    assert len(arrays) == len(bodies)
    for name in ("positions", "origins", "velocities", "cached_velocities", "omegas"):
        array = getattr(arrays, name)
        assert array.shape == (len(bodies), 3) and array.dtype == np.float64, name
    assert arrays.orientations.shape == (len(bodies), 4)
    assert arrays.cell_ids.dtype == np.uint32
    for i, body in enumerate(bodies):
        assert arrays.origins[i].tolist() == list(body.position.frame.origin)
        assert arrays.velocities[i].tolist() == list(body.velocity)
        assert arrays.omegas[i].tolist() == list(body.omega)
        assert arrays.orientations[i].tolist() == list(body.position.frame.rotation)
        assert arrays.cell_ids[i] == body.position.objcell_id
        assert arrays.transient_states[i] == body.transient_state
        assert tuple(arrays.positions[i]) == body.position.global_origin()
    drifter = arrays.index("drifter")
    assert arrays.cell_ids[drifter] >> 16 == 0xAAB4
    assert arrays.positions[drifter][0] == 0xAA * 192.0 + arrays.origins[drifter][0]
    assert arrays.positions[drifter][0] > 0xAA * 192.0  # past the seam, the map-wide x goes on
    assert np.array_equal(sim.positions(), arrays.positions)
    assert np.array_equal(sim.velocities(), arrays.velocities)
    with pytest.raises(ValueError, match="no body named"):
        arrays.index("nobody")


# -- py.typed ---------------------------------------------------------------------------------------


def test_the_package_is_marked_typed() -> None:
    assert resources.files("acphys").joinpath("py.typed").is_file()
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "py.typed" in pyproject["tool"]["setuptools"]["package-data"]["acphys"]


# -- adding bodies ----------------------------------------------------------------------------------


def test_a_body_added_while_running_runs() -> None:
    sim = default_sim(until=1.0)
    crate = sim.add_body(
        name="crate-2", setup="crate", landblock="0xA9B4", origin=[60.0, 90.0, 50.0], on_ground=True
    )
    assert sim.body("crate-2") is crate and crate in sim.bodies
    assert sim.world.has_object(crate)
    assert crate.transient_state & TransientState.CONTACT, "placed on the ground"
    ball = sim.add_body(
        {
            "name": "thrown",
            "setup": "ball",
            "landblock": "0xA9B4",
            "origin": [40.0, 100.0, 52.0],
            "state": ["gravity", "report_collisions"],
            "velocity": [3.0, 0.0, 2.0],
        }
    )
    steps: list[str] = []
    sim.on_step(lambda body, _quantum: steps.append(body.name))
    sim.run(until=2.0)
    assert steps.count("thrown") == 30 and steps.count("crate-2") == 30
    assert ball.position.frame.origin.x > 42.0
    assert ball.velocity.z < 2.0


def test_a_walker_added_while_running_walks_when_told() -> None:
    sim = default_sim(until=1.0)
    walker = sim.add_body(name="late", landblock="0xA9B4", origin=[140.0, 60.0, 50.0], on_ground=True)
    sim.add_event(1.5, "late", "motion", motion="WalkForward")
    sim.run(until=3.0)
    assert walker.position.frame.origin.y > 63.0
    assert walker.transient_state & TransientState.ON_WALKABLE


def test_add_body_refuses_a_taken_name_and_bad_keys_leaving_nothing() -> None:
    sim = default_sim(until=0.5)
    free_id = sim.world.next_object_id()
    with pytest.raises(ValueError, match="two bodies are named 'walker'"):
        sim.add_body(name="walker", landblock="0xA9B4", origin=[10.0, 10.0, 50.0])
    with pytest.raises(ScenarioError, match=r"add_body: body\.setup: no setup named 'nothing'"):
        sim.add_body(name="x", setup="nothing", landblock="0xA9B4", origin=[10.0, 10.0, 50.0])
    # refused after the body was made and placed: it is taken out again
    with pytest.raises(ScenarioError, match=r"body\.velocity: speed 60 m/s exceeds"):
        sim.add_body(
            name="x", setup="ball", landblock="0xA9B4", origin=[10.0, 10.0, 50.0], velocity=[60, 0, 0]
        )
    with pytest.raises(ScenarioError, match=r"body\.origin: on_ground, but"):
        sim.add_body(name="x", landblock="0xA9B4", origin=[10.0, 10.0, 60.0], on_ground=True)
    assert sim.world.get_object(free_id) is None
    assert sim.world.next_object_id() == free_id
    assert [body.name for body in sim.bodies].count("x") == 0
    cell = sim.world.get_cell(sim.body("walker").position.objcell_id & 0xFFFF0000 | 0x0001)
    assert all(obj.name != "x" for obj in cell.objects)
    with pytest.raises(TypeError, match="not both"):
        sim.add_body({"name": "y"}, landblock="0xA9B4")
    sim.run(until=1.0)  # and the simulation goes on


def test_add_body_takes_a_body_made_by_hand_in_its_world() -> None:
    sim = default_sim(until=0.5)
    setup = sim.body("ball").part_array.setup  # the scenario's [setup.ball], a sphere
    made = PhysicsObj(sim.world, "dot", acphys.PartArray(setup))
    start = Vector3(30.0, 30.0, 60.0)
    made.enter_world(Position((LANDBLOCK << 16) | 0x0001, Frame(start)))
    made.calc_acceleration()  # gravity (its state is retail's default, GRAVITY among it)
    assert sim.add_body(made) is made
    other = PhysicsObj(acphys.World(), "elsewhere", acphys.PartArray(setup))
    with pytest.raises(ValueError, match="another world"):
        sim.add_body(other)
    sim.run(until=1.0)
    assert made.position.frame.origin.z < 60.0, "it fell"


def test_add_body_reads_the_scenarios_dat_files_again(tmp_path: Path) -> None:
    """A DAT setup no body of the scenario used: the scenario's [data] files are opened again."""
    other = 0x02000123
    portal = {SETUP_ID: setup_record(), other: setup_record(flags=0, setup_id=other, steps=(0.25, 0.15))}
    simple_dat(tmp_path, portal)
    scenario = tmp_path / "world.toml"
    scenario.write_text(
        '[data]\nportal = "client_portal.dat"\n[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        '[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 50.0]\n',
        encoding="utf-8",
    )
    sim = acphys.load_scenario(scenario)
    sim.run(until=0.5)
    body = sim.add_body(name="b", setup="0x02000123", landblock="0xA9B4", origin=[20.0, 20.0, 50.0])
    assert body.part_array.setup.step_up_height == f32(0.25)
    with pytest.raises(ScenarioError, match="no setup 0x02000999"):
        sim.add_body(name="c", setup="0x02000999", landblock="0xA9B4", origin=[20.0, 40.0, 50.0])
    sim.run(until=1.0)


def test_no_body_is_added_from_inside_a_step() -> None:
    sim = default_sim()

    def add(_body: PhysicsObj, _quantum: float) -> None:
        sim.add_body(name="inner", setup="ball", landblock="0xA9B4", origin=[5.0, 5.0, 51.0])

    sim.on_step(add)
    with pytest.raises(RuntimeError, match="between steps"):
        sim.step()
        sim.step()
    sim.remove_callback(add)
    sim.step()  # the simulation is usable again


# -- adding events ----------------------------------------------------------------------------------


def test_events_added_while_running_fire_in_time_order() -> None:
    sim = default_sim(until=1.0)
    fired: list[tuple[str, float]] = []
    sim.add_event(2.0, "ball", lambda body: fired.append(("late", sim.time)))
    first = sim.add_event(1.5, "ball", lambda body: fired.append(("early", sim.time)))
    sim.add_event(1.5, sim.body("ball"), lambda body: fired.append(("early-2", sim.time)))
    assert first.at == 1.5 and first.body == "ball" and first.source == "add_event"
    assert [e.at for e in sim.events] == sorted(e.at for e in sim.events)
    sim.run(until=3.0)
    assert [name for name, _ in fired] == ["early", "early-2", "late"]
    assert 1.5 <= fired[0][1] < 1.5 + sim.tick_seconds
    assert 2.0 <= fired[2][1] < 2.0 + sim.tick_seconds


def test_a_scenario_action_added_while_running() -> None:
    sim = default_sim(until=1.0)
    events: list[str] = []
    sim.on_step(lambda body, _q: events.extend(body.step_events) if body.name == "walker" else None)
    sim.add_event(1.5, "walker", "stop_motion", motion="WalkForward")
    sim.run(until=2.5)
    assert "stop_motion:WalkForward" in events
    y = sim.body("walker").position.frame.origin.y
    sim.run(until=3.0)
    assert sim.body("walker").position.frame.origin.y == y, "stopped"


def test_an_event_in_the_past_is_refused() -> None:
    sim = default_sim(until=2.0)
    with pytest.raises(ValueError, match=r"an event at 1 s is in the past: the simulation is at 2 s"):
        sim.add_event(1.0, "runner", "jump")
    for bad in (math.nan, math.inf, "soon", True):
        with pytest.raises(ValueError, match="finite number of seconds"):
            sim.add_event(bad, "runner", "jump")  # type: ignore[arg-type]


def test_an_event_now_fires_at_the_next_tick() -> None:
    sim = default_sim(until=1.0)
    fired: list[float] = []
    sim.add_event(sim.time, "ball", lambda body: fired.append(sim.time))
    sim.step()
    assert fired == [sim.time]


def test_bad_events_are_refused_naming_the_key() -> None:
    sim = default_sim(until=0.5)
    with pytest.raises(ScenarioError, match=r"add_event: event\.action: unknown action 'dance'"):
        sim.add_event(1.0, "walker", "dance")
    with pytest.raises(ScenarioError, match=r"event\.speed: not used by action 'jump'"):
        sim.add_event(1.0, "walker", "jump", speed=2.0)
    with pytest.raises(ScenarioError, match=r"no body named 'nobody'"):
        sim.add_event(1.0, "nobody", "jump")
    with pytest.raises(KeyError, match="no body named 'nobody'"):
        sim.add_event(1.0, "nobody", lambda body: None)
    with pytest.raises(TypeError, match="takes no keys"):
        sim.add_event(1.0, "walker", lambda body: None, motion="Ready")
    assert all(event.source != "add_event" for event in sim.events)


def test_an_event_can_be_added_from_a_callback() -> None:
    sim = default_sim()
    fired: list[float] = []

    def once(body: PhysicsObj, _quantum: float) -> None:
        if body.name == "ball" and "hit_ground" in body.step_events:
            sim.add_event(sim.time + 0.5, "ball", lambda b: fired.append(sim.time))

    sim.on_step(once)
    sim.run(until=4.0)
    assert fired and 2.63 + 0.5 <= fired[0] < 2.63 + 0.6


# -- callbacks --------------------------------------------------------------------------------------


def test_step_callbacks_and_a_trace_both_see_every_step(tmp_path: Path) -> None:
    sim = default_sim()
    seen: list[tuple[str, float]] = []
    returned = sim.on_step(lambda body, quantum: seen.append((body.name, quantum)))
    assert callable(returned)
    trace = tmp_path / "run.jsonl"
    sim.run(until=1.0, trace=trace)
    lines = [json.loads(line) for line in trace.read_text(encoding="utf-8").splitlines()]
    records = [r for r in lines if r.get("quantum")]  # the steps (no header, no t = 0 records)
    assert len(seen) == len(records) == 7 * 30
    assert [(r["body"], r["quantum"]) for r in records] == seen
    assert all(body.observer is None and body.on_step is not None for body in sim.bodies)


def test_step_callbacks_see_the_step_events() -> None:
    sim = default_sim()
    landings: list[tuple[str, float]] = []

    @sim.on_step
    def watch(body: PhysicsObj, _quantum: float) -> None:
        if "hit_ground" in body.step_events:
            landings.append((body.name, round(body.world.physics_time, 2)))

    sim.run(until=3.0)
    assert ("ball", 2.63) in landings


def test_collision_callbacks_receive_reports() -> None:
    sim = default_sim()
    reports: list[tuple[str, CollisionReport]] = []
    sim.on_collision(lambda body, report: reports.append((body.name, report)))
    sim.run(until=3.0)
    ball = [report for name, report in reports if name == "ball"]
    assert ball and ball[0].kind is CollisionKind.ENVIRONMENT and ball[0].is_start
    assert ball[0].velocity is not None and ball[0].velocity.z < 0.0


def test_collision_between_bodies_reaches_both() -> None:
    sim = default_sim(until=2.0)
    touches: set[tuple[str, str]] = set()

    @sim.on_collision
    def touched(body: PhysicsObj, report: CollisionReport) -> None:
        if report.kind is CollisionKind.OBJECT and report.other is not None:
            touches.add((body.name, report.other.name))

    sim.add_body(
        name="thrown",
        setup="ball",
        landblock="0xA9B4",
        origin=[88.0, 68.0, 51.0],
        state=["report_collisions"],
        velocity=[-8.0, 0.0, 0.0],
    )
    sim.run(until=4.0)
    assert touches == {("thrown", "walker"), ("walker", "thrown")}


def test_removing_callbacks_clears_the_hooks() -> None:
    sim = default_sim()

    def step(body: PhysicsObj, quantum: float) -> None:
        pass

    def hit(body: PhysicsObj, report: CollisionReport) -> None:
        pass

    sim.on_step(step)
    sim.on_collision(hit)
    assert all(body.on_step is not None and body.on_collision is not None for body in sim.bodies)
    sim.remove_callback(step)
    assert all(body.on_step is None and body.on_collision is not None for body in sim.bodies)
    sim.remove_callback(hit)
    assert all(body.on_step is None and body.on_collision is None for body in sim.bodies)
    with pytest.raises(ValueError, match="not a step or collision callback"):
        sim.remove_callback(step)


def test_a_callback_may_remove_itself() -> None:
    sim = default_sim()
    calls: list[str] = []

    def once(body: PhysicsObj, _quantum: float) -> None:
        calls.append(body.name)
        sim.remove_callback(once)

    sim.on_step(once)
    sim.run(until=1.0)
    assert len(calls) == 1


def test_a_body_with_its_own_hook_is_not_overridden() -> None:
    sim = default_sim()
    sim.body("ball").on_collision = lambda body, report: None
    with pytest.raises(ValueError, match="'ball' has its own on_collision"):
        sim.on_collision(lambda body, report: None)
    assert all(body.on_collision is None for body in sim.bodies if body.name != "ball")
    sim.on_step(lambda body, q: None)  # another hook: no conflict


def test_no_callback_is_registered_from_inside_a_step() -> None:
    sim = default_sim()

    def register(_body: PhysicsObj, _quantum: float) -> None:
        sim.on_collision(lambda body, report: None)

    sim.on_step(register)
    with pytest.raises(RuntimeError, match="cannot register a callback while the bodies are being stepped"):
        sim.run(until=0.1)


def test_reading_arrays_from_a_callback() -> None:
    sim = default_sim()
    shapes: list[tuple[int, int]] = []
    sim.on_step(lambda body, _q: shapes.append(sim.arrays().positions.shape) if body.name == "ball" else None)
    sim.run(until=0.2)
    assert shapes == [(7, 3)] * 6


# -- the example --------------------------------------------------------------------------------------


def test_the_api_tour_example_runs_and_says_what_it_shows() -> None:
    example = ROOT / "examples" / "api_tour.py"
    source = example.read_text(encoding="utf-8")
    assert "acphys._" not in source and "from acphys." not in source and "._" not in source
    assert "transient_state |=" not in source and "transient_state =" not in source
    done = subprocess.run(
        [sys.executable, str(example)], capture_output=True, text=True, timeout=120, check=False
    )
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert "refused: an event at 1 s is in the past" in out
    assert "steps: skydiver 180," in out and "thrown 120" in out
    assert "thrown touched walker at 2.97 s" in out and "walker touched thrown at 2.97 s" in out
    assert "walker at 5.53 s" in out, "the walker's jump (an event added while running) lands"
    assert "walker transient_state: <TransientState.CONTACT|ON_WALKABLE|ACTIVE: 131>" in out
    assert "walker on walkable ground: True" in out
    assert "(float64, shape (3,))" in out
    assert "arrays: 8 bodies, positions (8, 3) float64" in out
    assert "at 4.50 s runner is at" in out
