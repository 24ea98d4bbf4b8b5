"""Scenario files (contract 1): a world, bodies and a timeline of events, in TOML.

Units: metres, seconds, and degrees for every angle (``heading`` in degrees,
``omega`` in degrees per second about each axis). Traces report ``omega`` in
retail's radians per second.

Every problem is a :class:`ScenarioError` whose message names the file, the
key and what was expected. Keys acphys does not know yet are errors too, so a
typo never passes silently.
"""

from __future__ import annotations

import errno
import hashlib
import json
import math
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from acphys.constants import BLOCK_LENGTH, MAX_ELASTICITY
from acphys.flags import TransientState
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.inputs import InputError, one_line, read_limited
from acphys.math.cell_id import FIRST_ENV_CELL
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.motion.motion_table import MotionTable
from acphys.motion.weenie import Weenie
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.scenario import values as read
from acphys.scenario.events import read_event, speed_limited
from acphys.scenario.live import ScenarioParts
from acphys.scenario.motion_tables import builtin_motion_table, builtin_motion_tables, read_motion_tables
from acphys.scenario.retail_data import HUMAN_SETUP_ID, SETUP_ID_TYPE, RetailData, read_data, setup_id
from acphys.scenario.scripts import read_scripts
from acphys.scenario.values import Ctx, ScenarioError
from acphys.scenario.world_data import (
    SetupLookup,
    cell_at,
    read_buildings,
    read_landblocks,
    read_objects,
    read_solids,
    warn_outside_landblocks,
)
from acphys.setup import BUILTIN_SETUPS, LocationType, Setup, bounding_sphere
from acphys.simulation import MAX_DRIVER_HZ, MAX_DRIVER_TICKS, MIN_DRIVER_HZ, Event, Simulation
from acphys.world.world import World

#: The scenario ``acphys run`` uses when none is given.
DEFAULT_SCENARIO = "default"
#: The largest scenario file read, in bytes. The largest scenario acphys measures (10,000 walking
#: bodies and their events, benchmarks/scale.py) is 1.8 MB; tomllib reads about half a megabyte
#: a second of its slowest text (an array of small numbers), so the 4 MiB allowed are read in
#: about 10 s and 100 MB at worst, inside the command line's 30 s and 1 GB for any input.
MAX_SCENARIO_BYTES = 4 * 1024 * 1024
#: The most ``[[body]]`` a scenario may have: the most ``acphys bench`` drives (its scenarios are
#: built from text, not read from a file, so the size limit does not bound them). A scenario file
#: within ``MAX_SCENARIO_BYTES`` holds at most some 40,000 bodies of the shortest form.
MAX_BODIES = 100_000


# -- sections -------------------------------------------------------------------------------


@dataclass
class _Header:
    name: str
    duration: float
    driver_hz: float
    player: str | None
    seed: int


def _read_header(ctx: Ctx, raw: Any, default_name: str) -> _Header:
    table = read.table(ctx, "scenario", raw, ("name", "duration", "driver_hz", "player", "seed"))
    name = read.string(ctx, "scenario.name", table["name"]) if "name" in table else default_name
    duration = read.ranged(ctx, "scenario.duration", table.get("duration", 10.0), 0.0, 1e6, open_low=True)
    driver_hz = read.ranged(
        ctx, "scenario.driver_hz", table.get("driver_hz", 60.0), MIN_DRIVER_HZ, MAX_DRIVER_HZ
    )
    if duration * driver_hz > MAX_DRIVER_TICKS:
        raise ctx.fail(
            "scenario.duration",
            f"{duration:g} s at {driver_hz:g} Hz is {duration * driver_hz:.3g} driver ticks, "
            f"more than the {MAX_DRIVER_TICKS:,} a run may take (MAX_DRIVER_TICKS)",
        )
    player = read.string(ctx, "scenario.player", table["player"]) if "player" in table else None
    seed = table.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ctx.fail("scenario.seed", f"expected a non-negative whole number, got {read.kind(seed)}")
    return _Header(name, duration, driver_hz, player, seed)


SETUP_KEYS = (
    "spheres",
    "cylspheres",
    "height",
    "radius",
    "step_up_height",
    "step_down_height",
    "motion_table",
    "boxes",
    "polygons",
    "solids",
    "holding_locations",
)
#: The motion table each built-in setup comes with (retail's ``default_mtable_id``).
BUILTIN_SETUP_TABLES = {"human": "humanoid"}


class Tables(dict[str, MotionTable]):
    """A scenario's ``[motion_table.NAME]`` tables, and the built-in tables it uses: each built-in
    one is made once per scenario (:meth:`builtin`), so that every body naming it shares it, as
    retail objects share the cached ``CMotionTable`` (each keeps its own state in its
    ``MotionTableManager``), while two scenarios never share one."""

    def __init__(self, own: dict[str, MotionTable]) -> None:
        super().__init__(own)
        self._builtins: dict[str, MotionTable] = {}

    def builtin(self, name: str) -> MotionTable:
        """The built-in table ``name`` (``"humanoid"``), made on first use."""
        if name not in self._builtins:
            self._builtins[name] = builtin_motion_table(name)
        return self._builtins[name]


def _motion_table(ctx: Ctx, key: str, value: Any, tables: Tables, data: RetailData) -> MotionTable | None:
    """A motion table by name: one of the scenario's, a built-in one, a portal DAT table id
    (``"0x09000001"``), or ``"none"``."""
    name = read.string(ctx, key, value)
    if name == "none":
        return None
    if name in tables:
        return tables[name]
    if name in builtin_motion_tables():
        return tables.builtin(name)
    dat_id = setup_id(name)
    if dat_id is not None:
        return data.motion_table(key, dat_id)
    ctx.uses(f"motion_table.{name}")
    known = ", ".join(["none", *builtin_motion_tables(), *tables, "a DAT table id like '0x09000001'"])
    raise ctx.missing("motion_table", key, f"no motion table named {name!r} (known: {known})")


def _read_setups(ctx: Ctx, raw: Any, tables: Tables, data: RetailData) -> dict[str, Setup]:
    """Every ``[setup.NAME]``; a setup with a problem is reported and left out."""
    if not isinstance(raw, dict):
        raise ctx.fail("setup", f"expected tables [setup.NAME], got {read.kind(raw)}")
    setups: dict[str, Setup] = {}
    for name, value in raw.items():
        with ctx.part(f"setup.{name}"):
            setups[name] = _read_setup(ctx, f"setup.{name}", name, value, tables, data)
    return setups


def _read_setup(ctx: Ctx, key: str, name: str, value: Any, tables: Tables, data: RetailData) -> Setup:
    """One ``[setup.NAME]``."""
    table = read.table(ctx, key, value, SETUP_KEYS)
    spheres = []
    for index, item in enumerate(read.list_of_tables(ctx, f"{key}.spheres", table.get("spheres", []))):
        sphere_key = f"{key}.spheres[{index}]"
        entry = read.table(ctx, sphere_key, item, ("center", "radius"))
        if "center" not in entry or "radius" not in entry:
            raise ctx.fail(sphere_key, "a sphere needs center = [x, y, z] and radius")
        center = read.local_point(ctx, f"{sphere_key}.center", entry["center"])
        radius = read.float32(ctx, f"{sphere_key}.radius", entry["radius"], 0.0, 1000.0, open_low=True)
        spheres.append(Sphere(center, radius))
    cylspheres = []
    for index, item in enumerate(read.list_of_tables(ctx, f"{key}.cylspheres", table.get("cylspheres", []))):
        cyl_key = f"{key}.cylspheres[{index}]"
        entry = read.table(ctx, cyl_key, item, ("low_pt", "radius", "height"))
        if any(part not in entry for part in ("low_pt", "radius", "height")):
            raise ctx.fail(cyl_key, "a cylsphere needs low_pt = [x, y, z], radius and height")
        low_pt = read.local_point(ctx, f"{cyl_key}.low_pt", entry["low_pt"])
        radius = read.float32(ctx, f"{cyl_key}.radius", entry["radius"], 0.0, 1000.0, open_low=True)
        height = read.float32(ctx, f"{cyl_key}.height", entry["height"], 0.0, 1000.0)
        cylspheres.append(CylSphere(low_pt, radius, height))

    holding: dict[int, LocationType] = {}
    for index, item in enumerate(
        read.list_of_tables(ctx, f"{key}.holding_locations", table.get("holding_locations", []))
    ):
        holding_key = f"{key}.holding_locations[{index}]"
        entry = read.table(ctx, holding_key, item, ("location", "part", "origin", "heading"))
        where = entry.get("location")
        if not isinstance(where, int) or isinstance(where, bool) or not 0 <= where <= 0xFFFFFFFF:
            raise ctx.fail(f"{holding_key}.location", f"expected a location id (an integer), got {where!r}")
        if where in holding:
            raise ctx.fail(f"{holding_key}.location", f"location {where} is given twice")
        part = entry.get("part", -1)
        if part not in (-1, 0) or isinstance(part, bool):
            raise ctx.fail(f"{holding_key}.part", f"a scenario setup has one part: -1 or 0, got {part!r}")
        origin = read.local_point(ctx, f"{holding_key}.origin", entry.get("origin", [0.0, 0.0, 0.0]))
        heading = read.float32(ctx, f"{holding_key}.heading", entry.get("heading", 0.0), -360.0, 360.0)
        holding[where] = LocationType(part & 0xFFFFFFFF, Frame.from_heading(origin, heading))

    def length(field: str) -> float:
        return read.float32(ctx, f"{key}.{field}", table.get(field, 0.0), 0.0, 1000.0)

    motion_table = None
    if "motion_table" in table:
        motion_table = _motion_table(ctx, f"{key}.motion_table", table["motion_table"], tables, data)
    return Setup(
        name=name,
        spheres=spheres,
        cylspheres=cylspheres,
        height=length("height"),
        radius=length("radius"),
        step_up_height=length("step_up_height"),
        step_down_height=length("step_down_height"),
        physics_bsp=read_solids(ctx, key, table),
        sorting_sphere=bounding_sphere(spheres),
        motion_table=motion_table,
        holding_locations=holding,
    )


def _builtin_setup(key: str, name: str, data: RetailData, tables: Tables) -> Setup:
    """A built-in setup; with a portal DAT the human is retail's setup 0x02000001, with the
    motion table its record names when the portal holds that table (else ``humanoid``)."""
    table = None
    if name == "human" and data.portal is not None:
        setup = data.setup(key, HUMAN_SETUP_ID, name)
        table = data.default_motion_table(key, HUMAN_SETUP_ID)
    else:
        setup = BUILTIN_SETUPS[name]()
    if table is None and name in BUILTIN_SETUP_TABLES:
        table = tables.builtin(BUILTIN_SETUP_TABLES[name])
    if table is not None:
        setup.motion_table = table
    return setup


BODY_KEYS = (
    "name",
    "id",
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
    "motion_table",
    "run_skill",
    "jump_skill",
    "npc",
)


def _skill(ctx: Ctx, key: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 10000:
        raise ctx.fail(key, f"expected a whole skill level in [0, 10000], got {read.kind(value)}")
    return value


def _setup_lookup(ctx: Ctx, setups: dict[str, Setup], data: RetailData, tables: Tables) -> SetupLookup:
    """Finds a setup by name: the scenario's ``[setup.NAME]`` first, then the built-in ones,
    then a portal DAT setup id (``"0x02000001"``)."""

    def find(key: str, value: Any) -> Setup:
        name = read.string(ctx, key, value)
        if name in setups:
            return setups[name]
        if name in BUILTIN_SETUPS:
            return _builtin_setup(key, name, data, tables)
        dat_id = setup_id(name)
        if dat_id is not None:
            if dat_id >> 24 != SETUP_ID_TYPE:
                raise ctx.fail(key, f"{name} is not a setup id (setup ids are 0x02xxxxxx)")
            return data.setup(key, dat_id)
        ctx.uses(f"setup.{name}")
        known = ", ".join([*BUILTIN_SETUPS, *setups, "a DAT setup id like '0x02000001'"])
        raise ctx.missing("setup", key, f"no setup named {name!r} (known: {known})")

    return find


#: Finds a body's ``motion_table`` by its key and value (:func:`_motion_table`).
TableLookup = Callable[[str, Any], MotionTable | None]


def _shared(find: SetupLookup) -> SetupLookup:
    """``find`` called once per setup name: every body naming the same setup gets the same
    object, as retail objects share the cached DAT ``CSetup`` (each body keeps its own state in
    its part array). Built-in and DAT setups are made afresh by each call of ``find``; motion
    tables need no such wrapper, they are shared where they are made (:class:`Tables`,
    ``RetailData.motion_table``). A value that is not a name, or a name ``find`` refuses, is
    looked up (and reported) each time.
    """
    found: dict[str, Setup] = {}

    def lookup(key: str, value: Any) -> Setup:
        if not isinstance(value, str):
            return find(key, value)
        if value not in found:
            found[value] = find(key, value)
        return found[value]

    return lookup


def _read_body(
    ctx: Ctx, key: str, raw: Any, world: World, find_setup: SetupLookup, find_table: TableLookup
) -> PhysicsObj:
    table = read.table(ctx, key, raw, BODY_KEYS)
    for required in ("name", "landblock", "origin"):
        if required not in table:
            raise ctx.fail(f"{key}.{required}", "missing (every body needs name, landblock and origin)")
    name = read.string(ctx, f"{key}.name", table["name"])
    setup = find_setup(f"{key}.setup", table.get("setup", "human"))
    landblock = read.landblock(ctx, f"{key}.landblock", table["landblock"])
    origin = read.vector(ctx, f"{key}.origin", table["origin"])
    if not (0.0 <= origin.x < BLOCK_LENGTH and 0.0 <= origin.y < BLOCK_LENGTH):
        raise ctx.fail(
            f"{key}.origin",
            f"x and y must be landblock-local, in [0, 192), got ({origin.x:g}, {origin.y:g})",
        )
    heading = read.float32(ctx, f"{key}.heading", table.get("heading", 0.0), -360.0, 360.0)

    body_id = read.object_id(ctx, f"{key}.id", table["id"]) if "id" in table else None
    owner = world.get_object(body_id) if body_id is not None else None
    if owner is not None:
        raise ctx.fail(f"{key}.id", f"0x{body_id:08X} is already the id of {owner.name!r}")
    body = PhysicsObj(world, name, PartArray(setup), body_id)
    if "state" in table:
        body.state = read.state(ctx, f"{key}.state", table["state"])
    body.friction = read.float32(ctx, f"{key}.friction", table.get("friction", body.friction), 0.0, 1.0)
    body.elasticity = read.float32(
        ctx, f"{key}.elasticity", table.get("elasticity", body.elasticity), 0.0, MAX_ELASTICITY
    )
    body.set_scale_static(
        read.float32(ctx, f"{key}.scale", table.get("scale", 1.0), 0.0, 1000.0, open_low=True)
    )
    npc = read.boolean(ctx, f"{key}.npc", table.get("npc", False))
    if npc or "run_skill" in table or "jump_skill" in table:
        # A creature weenie; npc makes it one that is not the player (IsThePlayer false), so the
        # motion interpreter replays its interpreted state, not its raw one (apply_current_movement).
        body.weenie_obj = Weenie(
            the_player=not npc,
            run_skill=_skill(ctx, f"{key}.run_skill", table.get("run_skill", 0)),
            jump_skill=_skill(ctx, f"{key}.jump_skill", table.get("jump_skill", 0)),
        )
    motion_table = setup.motion_table
    if "motion_table" in table:
        motion_table = find_table(f"{key}.motion_table", table["motion_table"])

    frame = Frame.from_heading(origin, heading)
    warn_outside_landblocks(ctx, f"{key}.landblock", world, landblock)
    body.enter_world(Position(cell_at(world, landblock, origin), frame))
    on_ground = read.boolean(ctx, f"{key}.on_ground", table.get("on_ground", False))
    if on_ground and not body.transient_state & TransientState.CONTACT:
        _put_on_ground(ctx, f"{key}.origin", body)
    body.calc_acceleration()
    if motion_table is not None:
        body.set_motion_table(motion_table)
    if "velocity" in table:
        body.set_velocity(speed_limited(ctx, f"{key}.velocity", table["velocity"]))
    if "omega" in table:
        body.set_omega(read.degrees_per_second(ctx, f"{key}.omega", table["omega"]))
    return body


#: How far below its origin ``on_ground`` looks for the ground a body is to stand on, in metres.
ON_GROUND_REACH = 2.0


def _put_on_ground(ctx: Ctx, key: str, body: PhysicsObj) -> None:
    """``on_ground = true`` for a body that placement left out of contact: drop it straight down
    onto what is under it (terrain, a floor, an object), as one swept fall of at most
    ``ON_GROUND_REACH`` committed by ``SetPositionInternal``. Not retail: the scenario's promise
    that the body starts on the ground. (A body under the terrain needs nothing of this: retail's
    placement lifts it onto the terrain.) A body further above the terrain is an error naming the
    gap, and so is a drop within reach that ends on no ground (another body in the way); where
    there is no ground at all (no terrain, nothing below), the body gets a level contact plane at
    its origin.
    """
    here = body.position
    origin = here.frame.origin
    outdoors = (here.objcell_id & 0xFFFF) < FIRST_ENV_CELL
    terrain = body.world.ground_height(here.objcell_id, origin) if outdoors else None
    below = here.copy()
    below.frame.origin.z = f32(origin.z - ON_GROUND_REACH)
    transit = body.transition(here, below)
    if transit is not None and transit.collision_info.contact_plane_valid:
        body.set_position_internal(transit)
        return
    if terrain is not None:
        gap = origin.z - terrain
        if gap > ON_GROUND_REACH:
            raise ctx.fail(
                key,
                f"on_ground, but {gap:.3g} m above the terrain under it (z {terrain:g}), out of the "
                f"{ON_GROUND_REACH:g} m on_ground reaches: lower the origin or leave on_ground out",
            )
        raise ctx.fail(
            key,
            f"on_ground, but its drop onto the terrain {gap:.3g} m below (z {terrain:g}) finds nothing "
            "to stand on: something is in its way (another body or an object where it stands?)",
        )
    # Nothing underfoot (no terrain here): a level contact plane at the origin.
    body.transient_state |= TransientState.CONTACT | TransientState.ON_WALKABLE
    body.contact_plane = Plane.horizontal(origin.z)
    body.contact_plane_cell_id = here.objcell_id


# -- entry points ---------------------------------------------------------------------------

TOP_KEYS = (
    "scenario",
    "data",
    "landblock",
    "motion_table",
    "script",
    "setup",
    "building",
    "object",
    "body",
    "event",
)


def parse_scenario(
    text: str,
    source: str = "<scenario>",
    default_name: str = "scenario",
    folder: str | Path | None = None,
    engine: str = "reference",
) -> Simulation:
    """Build a :class:`Simulation` from scenario TOML text; ``source`` names it in errors.

    ``folder`` is where relative ``[data]`` paths resolve (the scenario file's folder; the
    current directory when None). ``engine`` is ``"reference"`` or ``"fast"`` (see
    :mod:`acphys.fast`).
    """
    read.check_toml_limits(source, text)
    try:
        document = tomllib.loads(text)
    except RecursionError:  # check_toml_limits keeps nesting well inside the limit; a last guard
        raise ScenarioError(one_line(f"{source}: not valid TOML: nested too deeply to read")) from None
    except ValueError as error:  # TOMLDecodeError, or a number Python will not convert
        raise ScenarioError(one_line(f"{source}: not valid TOML: {error}")) from None
    sim = build_scenario(document, source, default_name, folder, read.TomlLines(text), engine)
    sim.scenario_sha256 = hashlib.sha256(text.encode("utf-8")).hexdigest()  # the text as written
    return sim


def _read_bodies(
    ctx: Ctx,
    raw: Any,
    world: World,
    find_setup: SetupLookup,
    find_table: TableLookup,
    objects: list[PhysicsObj],
) -> list[PhysicsObj]:
    """Every ``[[body]]`` (at least one); a body with a problem is reported and left out."""
    bodies: list[PhysicsObj] = []
    with ctx.part("body"):
        raw_bodies = read.at_most(
            ctx, "body", read.list_of_tables(ctx, "body", raw), MAX_BODIES, "bodies", "MAX_BODIES"
        )
        if not raw_bodies:
            raise ctx.fail("body", "missing: a scenario needs at least one [[body]]")
        object_names = {body.name for body in objects}
        body_names: set[str] = set()
        for index, item in enumerate(raw_bodies):
            name = item.get("name") if isinstance(item, dict) else None
            if isinstance(name, str):
                ctx.label(f"body[{index}]", f"body {name!r}")
            with ctx.part(f"body.{name}" if isinstance(name, str) else "body.?"):
                body = _read_body(ctx, f"body[{index}]", item, world, find_setup, find_table)
                if body.name in body_names:
                    raise ctx.fail(f"body[{index}].name", f"two bodies are named {body.name!r}")
                if body.name in object_names:
                    raise ctx.fail(
                        f"body[{index}].name", f"a body and an object are both named {body.name!r}"
                    )
                body_names.add(body.name)
                bodies.append(body)
    return bodies


def build_scenario(
    document: dict[str, Any],
    source: str = "<scenario>",
    default_name: str = "scenario",
    folder: str | Path | None = None,
    lines: read.TomlLines | None = None,
    engine: str = "reference",
) -> Simulation:
    """Build a :class:`Simulation` from a scenario already read into Python values (what
    ``tomllib`` gives for the TOML), checking every key as :func:`parse_scenario` does.

    Every independent problem is found: the :class:`ScenarioError` lists them all, one line
    each, with the TOML line of the key when ``lines`` (the text's :class:`TomlLines`) is given.
    """
    ctx = Ctx(source, lines)
    with ctx.part():
        read.table(ctx, "", document, TOP_KEYS)
    header = _Header(default_name, math.inf, 60.0, None, 0)  # what a broken header leaves to check
    with ctx.part():
        header = _read_header(ctx, document.get("scenario", {}), default_name)
    tables = Tables({})
    with ctx.part("motion_table"):
        tables = Tables(read_motion_tables(ctx, document.get("motion_table", {})))
    scripts: dict[str, int] = {}
    with ctx.part("script"):
        scripts = read_scripts(ctx, document.get("script", {}))

    world = World(seed=header.seed)
    with read_data(ctx, document.get("data", {}), folder) as data:
        setups: dict[str, Setup] = {}
        with ctx.part("setup"):
            setups = _read_setups(ctx, document.get("setup", {}), tables, data)
        with ctx.part():
            read_landblocks(ctx, document.get("landblock", []), world, data)
        with ctx.part():
            read_buildings(ctx, document.get("building", []), world)
        find_setup = _shared(_setup_lookup(ctx, setups, data, tables))

        def find_table(key: str, value: Any) -> MotionTable | None:
            return _motion_table(ctx, key, value, tables, data)

        objects: list[PhysicsObj] = []
        with ctx.part():
            objects = read_objects(ctx, document.get("object", []), world, find_setup)
        bodies = _read_bodies(ctx, document.get("body", []), world, find_setup, find_table, objects)
    by_name = {body.name: body for body in bodies}
    if header.player is not None:
        with ctx.part():
            ctx.uses(f"body.{header.player}")
            if header.player not in by_name:
                raise ctx.missing("body", "scenario.player", f"no body named {header.player!r}")
            world.player = by_name[header.player]

    events: list[Event] = []
    with ctx.part():
        for index, raw in enumerate(read.list_of_tables(ctx, "event", document.get("event", []))):
            if isinstance(raw, dict) and isinstance(raw.get("body"), str):
                ctx.label(f"event[{index}]", f"{raw.get('action', 'event')} of {raw['body']!r}")
            with ctx.part():
                events.append(read_event(ctx, f"event[{index}]", raw, by_name, header.duration, scripts))
    ctx.check()
    sim = Simulation(
        world,
        bodies,
        events,
        driver_hz=header.driver_hz,
        duration=header.duration,
        name=header.name,
        engine=engine,
    )
    sim.warnings = ctx.warnings
    sim.scenario_parts = ScenarioParts(setups, tables, scripts, document.get("data", {}), folder)
    sim.scenario_sha256 = _document_sha256(document)
    return sim


def _document_sha256(document: dict[str, Any]) -> str:
    """A scenario's hash for trace headers when built from values: of their canonical JSON."""
    text = json.dumps(document, sort_keys=True, default=str, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def builtin_scenario_text(name: str) -> str:
    """The TOML text of the built-in scenario ``name`` (a KeyError names the known ones)."""
    if name not in builtin_scenarios():
        raise KeyError(f"no built-in scenario {name!r} (built-in: {', '.join(builtin_scenarios())})")
    return resources.files("acphys.data.scenarios").joinpath(f"{name}.toml").read_text("utf-8")


def load_scenario(path: str | Path | None = None, engine: str = "reference") -> Simulation:
    """Load a scenario file, or the embedded default scenario when ``path`` is None.

    A name without a path that matches a built-in scenario (``"default"``) loads that one. The
    file must be a regular file of at most ``MAX_SCENARIO_BYTES`` of UTF-8 text. ``engine`` is
    ``"reference"`` (plain Python, the truth) or ``"fast"`` (compiled, :mod:`acphys.fast`).
    """
    if path is None or (isinstance(path, str) and path in builtin_scenarios()):
        name = DEFAULT_SCENARIO if path is None else str(path)
        return parse_scenario(
            builtin_scenario_text(name), source=f"<built-in {name}>", default_name=name, engine=engine
        )
    file = Path(path)
    source = one_line(str(file))
    bare_name = isinstance(path, str) and file.suffix == "" and len(file.parts) == 1  # a built-in's?
    try:
        data = read_limited(file, MAX_SCENARIO_BYTES, "the scenario size limit")
    except InputError as error:
        if error.errno == errno.ENOENT and bare_name:
            known = ", ".join(builtin_scenarios())
            raise ScenarioError(f"{source}: no such file nor built-in scenario (built-in: {known})") from None
        if error.errno == errno.ENOENT:
            raise ScenarioError(f"{source}: no such file") from None
        raise ScenarioError(f"{source}: cannot read: {error.strerror}") from None
    return parse_scenario(
        _utf8(source, data), source=source, default_name=file.stem, folder=file.parent, engine=engine
    )


def _utf8(source: str, data: bytes) -> str:
    """A scenario file's bytes as text; bytes that are not UTF-8 are refused by their offset."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data.count(b"\n", 0, error.start) + 1
        raise ScenarioError(
            f"{source}: line {line}: not UTF-8 text: byte {data[error.start]:#04x} at offset {error.start:,} "
            "(a scenario is UTF-8 TOML)"
        ) from None


def builtin_scenarios() -> list[str]:
    """The names of the scenarios shipped with acphys."""
    folder = resources.files("acphys.data.scenarios")
    return sorted(entry.name[:-5] for entry in folder.iterdir() if entry.name.endswith(".toml"))


__all__ = [
    "ScenarioError",
    "build_scenario",
    "builtin_scenario_text",
    "builtin_scenarios",
    "load_scenario",
    "parse_scenario",
]
