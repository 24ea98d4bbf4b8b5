"""Scenario files (contract 1): a world, bodies and a timeline of events, in TOML.

Units: metres, seconds, and degrees for every angle (``heading`` in degrees,
``omega`` in degrees per second about each axis). Traces report ``omega`` in
retail's radians per second.

Every problem is a :class:`ScenarioError` whose message names the file, the
key and what was expected. Keys acphys does not know yet are errors too, so a
typo never passes silently.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from acphys.constants import BLOCK_LENGTH, MAX_ELASTICITY, MAX_VELOCITY
from acphys.flags import TransientState
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.scenario import values as read
from acphys.scenario.values import Ctx, ScenarioError
from acphys.setup import BUILTIN_SETUPS, Setup
from acphys.simulation import Event, Simulation
from acphys.world.world import World

#: The scenario ``acphys run`` uses when none is given.
DEFAULT_SCENARIO = "default"

EVENT_ACTIONS = ("set_velocity", "set_omega", "set_state")


# -- sections -------------------------------------------------------------------------------


@dataclass
class _Header:
    name: str
    duration: float
    driver_hz: float
    player: str | None


def _read_header(ctx: Ctx, raw: Any, default_name: str) -> _Header:
    table = read.table(ctx, "scenario", raw, ("name", "duration", "driver_hz", "player"))
    name = read.string(ctx, "scenario.name", table["name"]) if "name" in table else default_name
    duration = read.ranged(ctx, "scenario.duration", table.get("duration", 10.0), 0.0, 1e6, open_low=True)
    driver_hz = read.ranged(ctx, "scenario.driver_hz", table.get("driver_hz", 60.0), 0.0, 1e4, open_low=True)
    player = read.string(ctx, "scenario.player", table["player"]) if "player" in table else None
    return _Header(name, duration, driver_hz, player)


def _read_setups(ctx: Ctx, raw: Any) -> dict[str, Setup]:
    if not isinstance(raw, dict):
        raise ctx.fail("setup", f"expected tables [setup.NAME], got {read.kind(raw)}")
    setups: dict[str, Setup] = {}
    for name, value in raw.items():
        key = f"setup.{name}"
        table = read.table(ctx, key, value, ("spheres", "step_up_height", "step_down_height"))
        spheres = []
        for index, item in enumerate(read.list_of_tables(ctx, f"{key}.spheres", table.get("spheres", []))):
            sphere_key = f"{key}.spheres[{index}]"
            entry = read.table(ctx, sphere_key, item, ("center", "radius"))
            if "center" not in entry or "radius" not in entry:
                raise ctx.fail(sphere_key, "a sphere needs center = [x, y, z] and radius")
            center = read.vector(ctx, f"{sphere_key}.center", entry["center"])
            radius = read.ranged(ctx, f"{sphere_key}.radius", entry["radius"], 0.0, 1000.0, open_low=True)
            spheres.append(Sphere(center, radius))
        setups[name] = Setup(
            name=name,
            spheres=spheres,
            step_up_height=read.ranged(
                ctx, f"{key}.step_up_height", table.get("step_up_height", 0.0), 0.0, 100.0
            ),
            step_down_height=read.ranged(
                ctx, f"{key}.step_down_height", table.get("step_down_height", 0.0), 0.0, 100.0
            ),
        )
    return setups


BODY_KEYS = (
    "name",
    "setup",
    "landblock",
    "origin",
    "heading",
    "state",
    "velocity",
    "omega",
    "friction",
    "elasticity",
    "scale",
    "on_ground",
)


def _omega(ctx: Ctx, key: str, value: Any) -> Vector3:
    """An angular velocity given in degrees per second, returned in radians per second."""
    degrees = read.vector(ctx, key, value)
    return Vector3(*(math.radians(component) for component in degrees))


def _read_body(ctx: Ctx, key: str, raw: Any, world: World, setups: dict[str, Setup]) -> PhysicsObj:
    table = read.table(ctx, key, raw, BODY_KEYS)
    for required in ("name", "landblock", "origin"):
        if required not in table:
            raise ctx.fail(f"{key}.{required}", "missing (every body needs name, landblock and origin)")
    name = read.string(ctx, f"{key}.name", table["name"])
    setup_name = read.string(ctx, f"{key}.setup", table.get("setup", "human"))
    if setup_name in setups:
        setup = setups[setup_name]
    elif setup_name in BUILTIN_SETUPS:
        setup = BUILTIN_SETUPS[setup_name]()
    else:
        known = ", ".join([*BUILTIN_SETUPS, *setups])
        raise ctx.fail(f"{key}.setup", f"no setup named {setup_name!r} (known: {known})")
    landblock = read.landblock(ctx, f"{key}.landblock", table["landblock"])
    origin = read.vector(ctx, f"{key}.origin", table["origin"])
    if not (0.0 <= origin.x < BLOCK_LENGTH and 0.0 <= origin.y < BLOCK_LENGTH):
        raise ctx.fail(
            f"{key}.origin",
            f"x and y must be landblock-local, in [0, 192), got ({origin.x:g}, {origin.y:g})",
        )
    heading = read.ranged(ctx, f"{key}.heading", table.get("heading", 0.0), -360.0, 360.0)

    body = PhysicsObj(world, name, PartArray(setup))
    if "state" in table:
        body.state = read.state(ctx, f"{key}.state", table["state"])
    body.friction = read.ranged(ctx, f"{key}.friction", table.get("friction", body.friction), 0.0, 1.0)
    body.elasticity = read.ranged(
        ctx, f"{key}.elasticity", table.get("elasticity", body.elasticity), 0.0, MAX_ELASTICITY
    )
    body.scale = read.ranged(ctx, f"{key}.scale", table.get("scale", 1.0), 0.0, 1000.0, open_low=True)

    frame = Frame.from_heading(origin, heading)
    body.enter_world(Position(outdoor_cell_id(landblock, origin), frame))
    if read.boolean(ctx, f"{key}.on_ground", table.get("on_ground", False)):
        body.transient_state |= TransientState.CONTACT | TransientState.ON_WALKABLE
        body.contact_plane = Plane.horizontal(origin.z)
        body.contact_plane_cell_id = body.position.objcell_id
    body.calc_acceleration()
    if "velocity" in table:
        body.set_velocity(_speed_limited(ctx, f"{key}.velocity", table["velocity"]))
    if "omega" in table:
        body.set_omega(_omega(ctx, f"{key}.omega", table["omega"]))
    return body


def _speed_limited(ctx: Ctx, key: str, value: Any) -> Vector3:
    velocity = read.vector(ctx, key, value)
    if velocity.length() > MAX_VELOCITY:
        raise ctx.fail(key, f"speed {velocity.length():g} m/s exceeds the retail limit of 50 m/s")
    return velocity


EVENT_KEYS = ("at", "body", "action", "velocity", "omega", "state")
_EVENT_VALUE_KEY = {"set_velocity": "velocity", "set_omega": "omega", "set_state": "state"}


def _read_event(ctx: Ctx, key: str, raw: Any, bodies: set[str], duration: float) -> Event:
    table = read.table(ctx, key, raw, EVENT_KEYS)
    for required in ("at", "body", "action"):
        if required not in table:
            raise ctx.fail(f"{key}.{required}", "missing (every event needs at, body and action)")
    at = read.number(ctx, f"{key}.at", table["at"])
    if not 0.0 <= at <= duration:
        raise ctx.fail(f"{key}.at", f"{at:g} s is outside the scenario's [0, {duration:g}] s")
    body = read.string(ctx, f"{key}.body", table["body"])
    if body not in bodies:
        raise ctx.fail(f"{key}.body", f"no body named {body!r} (bodies: {', '.join(sorted(bodies))})")
    action = read.string(ctx, f"{key}.action", table["action"])
    if action not in EVENT_ACTIONS:
        raise ctx.fail(
            f"{key}.action",
            f"unknown action {action!r} (expected one of: {', '.join(EVENT_ACTIONS)})",
        )
    value_key = _EVENT_VALUE_KEY[action]
    extra = [name for name in table if name not in ("at", "body", "action", value_key)]
    if extra:
        raise ctx.fail(f"{key}.{extra[0]}", f"not used by action {action!r} (it takes {value_key})")
    if value_key not in table:
        raise ctx.fail(f"{key}.{value_key}", f"missing (action {action!r} needs {value_key})")
    value = table[value_key]
    apply: Callable[[PhysicsObj], None]
    if action == "set_velocity":
        velocity = _speed_limited(ctx, f"{key}.velocity", value)
        apply = lambda obj: obj.set_velocity(velocity)  # noqa: E731
    elif action == "set_omega":
        omega = _omega(ctx, f"{key}.omega", value)
        apply = lambda obj: obj.set_omega(omega)  # noqa: E731
    else:
        state = read.state(ctx, f"{key}.state", value)
        apply = lambda obj: obj.set_state(state)  # noqa: E731
    return Event(at=at, body=body, action=action, apply=apply, source=key)


# -- entry points ---------------------------------------------------------------------------

TOP_KEYS = ("scenario", "setup", "body", "event")


def parse_scenario(text: str, source: str = "<scenario>", default_name: str = "scenario") -> Simulation:
    """Build a :class:`Simulation` from scenario TOML text; ``source`` names it in errors."""
    ctx = Ctx(source)
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ScenarioError(f"{source}: not valid TOML: {error}") from None
    read.table(ctx, "", document, TOP_KEYS)
    header = _read_header(ctx, document.get("scenario", {}), default_name)
    setups = _read_setups(ctx, document.get("setup", {}))

    world = World()
    raw_bodies = read.list_of_tables(ctx, "body", document.get("body", []))
    if not raw_bodies:
        raise ctx.fail("body", "missing: a scenario needs at least one [[body]]")
    bodies: list[PhysicsObj] = []
    for index, raw in enumerate(raw_bodies):
        body = _read_body(ctx, f"body[{index}]", raw, world, setups)
        if any(other.name == body.name for other in bodies):
            raise ctx.fail(f"body[{index}].name", f"two bodies are named {body.name!r}")
        bodies.append(body)
    names = {body.name for body in bodies}
    if header.player is not None:
        if header.player not in names:
            raise ctx.fail("scenario.player", f"no body named {header.player!r}")
        world.player = next(body for body in bodies if body.name == header.player)

    raw_events = read.list_of_tables(ctx, "event", document.get("event", []))
    events = [
        _read_event(ctx, f"event[{index}]", raw, names, header.duration)
        for index, raw in enumerate(raw_events)
    ]
    return Simulation(
        world,
        bodies,
        events,
        driver_hz=header.driver_hz,
        duration=header.duration,
        name=header.name,
    )


def load_scenario(path: str | Path | None = None) -> Simulation:
    """Load a scenario file, or the embedded default scenario when ``path`` is None.

    A name without a path that matches a built-in scenario (``"default"``) loads that one.
    """
    if path is None or (isinstance(path, str) and path in builtin_scenarios()):
        name = DEFAULT_SCENARIO if path is None else str(path)
        text = resources.files("acphys.data.scenarios").joinpath(f"{name}.toml").read_text("utf-8")
        return parse_scenario(text, source=f"<built-in {name}>", default_name=name)
    file = Path(path)
    try:
        text = file.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError(f"{file}: no such file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise ScenarioError(f"{file}: cannot read: {error}") from None
    return parse_scenario(text, source=str(file), default_name=file.stem)


def builtin_scenarios() -> list[str]:
    """The names of the scenarios shipped with acphys."""
    folder = resources.files("acphys.data.scenarios")
    return sorted(entry.name[:-5] for entry in folder.iterdir() if entry.name.endswith(".toml"))


__all__ = ["ScenarioError", "builtin_scenarios", "load_scenario", "parse_scenario"]
