"""No scenario number reaches the engine unrounded, and the engine keeps storing float32.

Every number a scenario gives the engine is the float32 retail's data would hold
(:mod:`acphys.precision`), and every ``float`` the engine stores stays a float32 through a run.
These tests walk everything a simulation holds (bodies, world, cells, geometry, motion tables,
managers, and the values the events will hand the engine) and check each Python float with
:func:`acphys.precision.is_f32`, except the fields retail declares ``double`` (listed below with
their declarations in acclient.h) and the harness's own clock values.
"""

from __future__ import annotations

import enum
import types
from collections.abc import Iterator
from typing import Any

import pytest

import acphys
from acphys.precision import is_f32
from acphys.scenario import builtin_scenarios

#: (class, attribute) pairs that hold doubles on purpose.
DOUBLE_FIELDS = {
    ("PhysicsObj", "update_time"),  # CPhysicsObj::update_time, long double (acclient.h:30719)
    ("Sequence", "frame_number"),  # CSequence::frame_number, long double (acclient.h:30754)
    ("TargetManager", "last_update_time"),  # TargetManager::last_update_time (acclient.h:31002)
    ("StickyManager", "sticky_timeout_time"),  # long double (acclient.h:31525)
    ("MoveToManager", "previous_distance_time"),  # long double (acclient.h:31482)
    ("MoveToManager", "original_distance_time"),  # long double (acclient.h:31484)
    ("ScriptManager", "next_hook_time"),  # long double (acclient.h:30821)
    ("ScriptData", "start_time"),  # long double (acclient.h:31208)
    ("PhysicsScriptData", "start_time"),  # long double (acclient.h:31994)
    ("FPHook", "time_created"),  # long double (acclient.h:30965)
    ("CollisionRecord", "touched_time"),  # long double (acclient.h:52279)
    ("ParticleEmitterInfo", "birthrate"),  # long double (acclient.h:52416)
    ("ParticleEmitterInfo", "total_seconds"),  # long double (acclient.h:52420)
    ("ParticleEmitterInfo", "lifespan_rand"),  # long double (acclient.h:52421)
    ("ParticleEmitterInfo", "lifespan"),  # long double (acclient.h:52422)
    ("Particle", "birthtime"),  # long double (acclient.h:52447)
    ("Particle", "lifespan"),  # long double (acclient.h:52455)
    ("Particle", "lifetime"),  # long double (acclient.h:52456)
    ("ParticleEmitter", "creation_time"),  # long double (acclient.h:52482)
    ("ParticleEmitter", "last_emit_time"),  # long double (acclient.h:52485)
    ("ParticleEmitter", "last_update_time"),  # long double (acclient.h:52488)
    ("World", "cur_time"),  # Timer::cur_time, a double: the clock
    ("World", "physics_time"),  # PhysicsTimer::curr_time, a double
    ("Physics", "last_update"),  # CPhysics's last UseTime, a double
    ("Event", "at"),  # the harness's event time
    ("Simulation", "duration"),  # the harness's
    ("Simulation", "driver_hz"),  # the harness's
    ("Simulation", "time"),  # the harness's
}


def _slots(cls: type) -> Iterator[str]:
    for klass in cls.__mro__:
        slots = klass.__dict__.get("__slots__", ())
        yield from (slots,) if isinstance(slots, str) else slots


def non_float32(root: object) -> list[tuple[str, float]]:
    """Every float reachable from ``root`` that is not a float32 and not a declared double."""
    found: list[tuple[str, float]] = []
    seen: set[int] = set()
    stack: list[tuple[Any, str, str]] = [(root, type(root).__name__, "")]
    while stack:
        value, owner, name = stack.pop()
        if isinstance(value, float):
            if not is_f32(value) and (owner, name) not in DOUBLE_FIELDS:
                found.append((f"{owner}.{name}", value))
            continue
        if isinstance(value, (bool, int, str, bytes, type(None), enum.Enum, type, types.ModuleType)):
            continue
        if id(value) in seen:
            continue
        seen.add(id(value))
        if isinstance(value, types.FunctionType):  # an event's action: walk what it will apply
            cells = value.__closure__ or ()
            stack.extend((cell.cell_contents, owner, name) for cell in cells if _filled(cell))
        elif isinstance(value, dict):
            stack.extend((item, owner, name) for item in value.values())
        elif isinstance(value, (list, tuple, set, frozenset)):
            stack.extend((item, owner, name) for item in value)
        elif hasattr(value, "__dict__") or hasattr(type(value), "__slots__"):
            cls = type(value).__name__
            names = [*getattr(value, "__dict__", {}), *_slots(type(value))]
            stack.extend((getattr(value, attr), cls, attr) for attr in names if hasattr(value, attr))
    return found


def _filled(cell: types.CellType) -> bool:
    try:
        cell.cell_contents  # noqa: B018
    except ValueError:
        return False
    return True


#: Every kind of number the scenario reader takes, none of them a float32 as written.
AWKWARD = """
[scenario]
name = "awkward"
duration = 2.0
driver_hz = 60.0
player = "walker"

[[landblock]]
id = "0xA9B4"
heights = [%(heights)s]
height_table = [%(table)s]

[motion_table.strider]
default_style = "NonCombat"
[[motion_table.strider.cycle]]
motion = "Ready"
framerate = 29.97
frames = 10
[[motion_table.strider.cycle]]
motion = "WalkForward"
framerate = 29.97
frames = 10
velocity = [0.1, 3.3, 0.07]
omega = [0.3, 0.7, 1.1]
pos_frame = [0.01, 0.03, 0.0]
hooks = [{ frame = 2, kind = "Scale", end = 1.1, time = 0.7 }]

[script.grow]
hooks = [{ at = 0.1, kind = "Scale", end = 1.3, time = 0.3 }]

[setup.walker]
spheres = [{ center = [0.0, 0.0, 0.47], radius = 0.47 }, { center = [0.0, 0.0, 1.33], radius = 0.47 }]
height = 1.81
radius = 0.47
step_up_height = 0.37
step_down_height = 0.41
motion_table = "strider"
holding_locations = [{ location = 1, origin = [0.3, 0.7, 1.1], heading = 33.3 }]

[setup.post]
cylspheres = [{ low_pt = [0.1, 0.1, 0.0], radius = 0.33, height = 2.7 }]

[setup.crate]
boxes = [{ min = [-0.3, -0.3, 0.0], max = [0.3, 0.3, 0.7] }]

[[object]]
name = "post"
setup = "post"
landblock = "0xA9B4"
origin = [60.1, 60.3, 34.5]
heading = 33.3
scale = 1.1

[[object]]
setup = "crate"
landblock = "0xA9B4"
origin = [70.1, 60.3, 34.5]
heading = 12.3
scale = 0.9

[[building]]
landblock = "0xA9B4"
origin = [140.1, 140.3, 34.5]
rooms = [{ name = "hall", min = [-3.3, -2.7, 0], max = [3.3, 2.7, 2.9] }]
doorways = [{ between = ["hall", "outside"], min = [-3.3, -0.7, 0], max = [-3.3, 0.7, 2.1] }]
wall_thickness = 0.23

[[body]]
name = "walker"
setup = "walker"
landblock = "0xA9B4"
origin = [96.1, 96.3, 34.5]
heading = 33.3
state = ["gravity", "report_collisions", "edge_slide"]
friction = 0.93
elasticity = 0.07
scale = 1.1
on_ground = true
run_skill = 230
jump_skill = 170

[[body]]
name = "pet"
setup = "walker"
landblock = "0xA9B4"
origin = [90.1, 96.3, 34.5]
velocity = [0.1, 0.3, 0.7]
omega = [3.3, 7.7, 11.1]
on_ground = true
npc = true

[[event]]
at = 0.1
body = "walker"
action = "motion"
motion = "WalkForward"
speed = 0.77
hold_run = true

[[event]]
at = 0.2
body = "pet"
action = "stick_to"
target = "walker"

[[event]]
at = 0.3
body = "walker"
action = "constrain_to"
origin = [100.1, 100.3, 34.5]
start = 3.3
max = 7.7

[[event]]
at = 0.4
body = "walker"
action = "play_script"
script = "grow"

[[event]]
at = 0.5
body = "walker"
action = "turn_to"
heading = 77.7
speed = 0.9

[[event]]
at = 0.6
body = "walker"
action = "move_to"
origin = [110.1, 110.3, 34.5]
distance = 0.7
min_distance = 0.3
fail_distance = 33.3
speed = 0.9

[[event]]
at = 0.7
body = "pet"
action = "interpolate_to"
origin = [80.1, 90.3, 34.5]
heading = 12.3

[[event]]
at = 0.8
body = "walker"
action = "jump"
extent = 0.77

[[event]]
at = 0.9
body = "pet"
action = "set_velocity"
velocity = [0.3, 0.7, 1.1]

[[event]]
at = 1.0
body = "pet"
action = "set_omega"
omega = [1.1, 2.3, 4.7]
"""


def _awkward() -> str:
    heights = ", ".join(str(20 + (i // 9 == 8)) for i in range(81))  # 34.1 m; the east edge 35.8
    table = ", ".join(str(round(i * 1.7 + 0.1, 1)) for i in range(256))
    return AWKWARD % {"heights": heights, "table": table}


def test_the_walker_finds_a_double_where_one_is_stored() -> None:
    # The check itself: a body field set to a double is found, a declared double is not.
    sim = acphys.parse_scenario(_awkward(), source="awkward.toml")
    body = sim.body("walker")
    assert not non_float32(body)
    body.friction = 0.1
    assert ("PhysicsObj.friction", 0.1) in non_float32(body)
    # ... and deep in the world: a static object's shape, reached from its cell.
    post = next(obj for obj in sim.bodies[0].world._objects.values() if obj.name == "post")
    post.part_array.setup.cylspheres[0].radius = 0.33
    assert sorted(non_float32(sim)) == [("CylSphere.radius", 0.33), ("PhysicsObj.friction", 0.1)]


def test_every_scenario_number_enters_the_engine_as_float32() -> None:
    sim = acphys.parse_scenario(_awkward(), source="awkward.toml")
    assert non_float32(sim) == []


def test_the_awkward_scenario_stays_float32_through_its_run() -> None:
    sim = acphys.parse_scenario(_awkward(), source="awkward.toml")
    sim.run()
    assert non_float32(sim) == []


@pytest.mark.parametrize("name", builtin_scenarios())
def test_every_bundled_scenario_stores_float32_through_its_run(name: str) -> None:
    sim = acphys.load_scenario(name)
    sim.run(until=min(sim.duration, 3.0))
    assert non_float32(sim) == []
