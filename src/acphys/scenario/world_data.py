"""Scenario world data: landblock terrain and water, solid setups, static objects and buildings.

Not retail routines: retail reads all of this from the DAT. These readers turn the scenario keys
(README "Scenarios") into the retail structures acphys ports: ``LandBlockStruct`` records,
physics BSPs (``acphys.geometry.bsp_builder``), static objects and ``build_house`` buildings.
Every problem is a :class:`ScenarioError` naming the file and the key.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable
from importlib import resources
from typing import Any

from acphys.constants import BLOCK_LENGTH
from acphys.dat.env_cell import init_buildings, init_static_objects
from acphys.dat.landblock_info import init_static_objs
from acphys.geometry.bsp import BSPTree
from acphys.geometry.bsp_builder import MAX_UNION_SOLIDS, SolidError, box_faces, build_union_tree
from acphys.geometry.polygon import Polygon
from acphys.math.cell_id import FIRST_ENV_CELL, cell_of, outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.scenario import values as read
from acphys.scenario.retail_data import RetailData
from acphys.scenario.values import Ctx
from acphys.setup import Setup
from acphys.world.land_cell import SortCell
from acphys.world.landblock import LandBlock
from acphys.world.rooms import DoorwaySpec, RoomSpec, build_house
from acphys.world.static_objects import add_static_object
from acphys.world.terrain import HEIGHT_TABLE_SIZE, MAX_LAND_HEIGHT, NUM_VERTICES, LandBlockStruct
from acphys.world.world import World

#: Terrain type of every vertex of ``water = "all"``: 16, the first of the water types 16-20.
WATER_TERRAIN_TYPE = 16
#: The word ``water = "all"`` gives every vertex (terrain type in bits 2..6).
WATER_WORD = WATER_TERRAIN_TYPE << 2

#: The most ``[[landblock]]`` a scenario may list: each is some 7 ms and 150 KB to build (its
#: terrain and 64 land cells), and 256 (a 3-km square) are 2 s; the world has 65,000.
MAX_LANDBLOCKS = 256
#: The most ``[[object]]`` a scenario may list (twice the 10,000 bodies acphys measures; some
#: 0.4 ms each to place).
MAX_OBJECTS = 20_000
#: The most ``[[building]]`` a scenario may list (some 3 ms each), and the most rooms and doorways
#: one building may have: rooms are tested against each other for overlap, so their cost grows
#: with the square of their number.
MAX_BUILDINGS = 1_000
MAX_ROOMS = 256
MAX_DOORWAYS = 256

#: Finds a setup by name for the key naming it (built-in or ``[setup.NAME]``).
SetupLookup = Callable[[str, Any], Setup]

# -- landblocks -------------------------------------------------------------------------------

LANDBLOCK_KEYS = ("id", "height", "heights", "height_table", "water")


def _whole_numbers(ctx: Ctx, key: str, value: Any, what: str, high: int) -> list[int]:
    """``NUM_VERTICES`` integers in [0, high]."""
    if not isinstance(value, list) or len(value) != NUM_VERTICES:
        raise ctx.fail(
            key, f"expected {NUM_VERTICES} {what} (vertex (x, y) at index x*9 + y), got {read.kind(value)}"
        )
    for index, item in enumerate(value):
        if isinstance(item, bool) or not isinstance(item, int) or not 0 <= item <= high:
            raise ctx.fail(
                f"{key}[{index}]", f"expected a whole number in [0, {high}], got {read.kind(item)}"
            )
    return list(value)


def _height_table(ctx: Ctx, key: str, value: Any) -> list[float]:
    if not isinstance(value, list) or len(value) != HEIGHT_TABLE_SIZE:
        raise ctx.fail(key, f"expected {HEIGHT_TABLE_SIZE} heights in metres, got {read.kind(value)}")
    return [read.float32(ctx, f"{key}[{i}]", item, 0.0, MAX_LAND_HEIGHT) for i, item in enumerate(value)]


def _retail_height_table(ctx: Ctx, key: str, height_bytes: list[int]) -> list[float]:
    """Retail's land height table as far as acphys ships it (``data/land_height_table.toml``:
    bytes 0-200, 2 m a step); a height byte beyond it is an error naming the byte. The entries
    past the shipped ones are never read (no byte reaches them) and repeat the last."""
    text = resources.files("acphys.data").joinpath("land_height_table.toml").read_text("utf-8")
    known = tomllib.loads(text)["heights"]
    highest = max(height_bytes)
    if highest >= len(known):
        index = height_bytes.index(highest)
        raise ctx.fail(
            f"{key}[{index}]",
            f"height byte {highest} is past the part of retail's height table acphys ships (bytes "
            f"0-{len(known) - 1}, 2 m a step to {known[-1]:g} m): give height_table, or a [data] portal",
        )
    return known + [known[-1]] * (HEIGHT_TABLE_SIZE - len(known))


def _water(ctx: Ctx, key: str, value: Any) -> list[int]:
    """81 terrain words: ``"none"`` (type 0 everywhere), ``"all"`` or the raw words."""
    if value == "none":
        return [0] * NUM_VERTICES
    if value == "all":
        return [WATER_WORD] * NUM_VERTICES
    if isinstance(value, list):
        return _whole_numbers(ctx, key, value, "terrain words", 0xFFFF)
    raise ctx.fail(key, f'expected "none", "all" or {NUM_VERTICES} terrain words, got {read.kind(value)}')


def read_landblocks(ctx: Ctx, raw: Any, world: World, data: RetailData) -> None:
    """Add each ``[[landblock]]`` to ``world``: flat ``height``, ``heights`` through a
    ``height_table`` (the portal DAT's region table when it has none), or with only ``id`` the
    cell DAT's terrain, static objects, env cells (0xXXYY0100 up, ``num_cells`` of them),
    buildings and the env cells' static objects (placed once every landblock is in); ``water``
    as terrain words. A landblock with a problem is reported and left out."""
    seen: set[int] = set()
    from_dat: list[tuple[str, int, LandBlock]] = []
    entries = read.list_of_tables(ctx, "landblock", raw)
    read.at_most(ctx, "landblock", entries, MAX_LANDBLOCKS, "landblocks", "MAX_LANDBLOCKS")
    for index, item in enumerate(entries):
        with ctx.part():
            _read_landblock(ctx, f"landblock[{index}]", item, world, data, seen, from_dat)
    for key, landblock, block in from_dat:
        info = data.landblock_info(key, landblock)
        if info is None:
            continue

        def object_setup(object_id: int, key: str = key) -> Setup | None:
            return data.object_setup(key, object_id)

        init_static_objs(world, block, info, object_setup)
        first = info.block_mask | FIRST_ENV_CELL
        env_cells = [data.env_cell(key, first + n) for n in range(info.num_cells)]
        for _record, cell in env_cells:
            world.add_cell(cell)
        init_buildings(world, block, info, object_setup)
        for record, cell in env_cells:
            init_static_objects(world, cell, record, object_setup)


def _read_landblock(
    ctx: Ctx,
    key: str,
    item: Any,
    world: World,
    data: RetailData,
    seen: set[int],
    from_dat: list[tuple[str, int, LandBlock]],
) -> None:
    """One ``[[landblock]]``: added to ``world``, or to ``from_dat`` when its terrain comes from the
    cell DAT (whose objects and cells :func:`read_landblocks` adds once every landblock is in)."""
    entry = read.table(ctx, key, item, LANDBLOCK_KEYS)
    if "id" not in entry:
        raise ctx.fail(f"{key}.id", "missing (a landblock needs id and height, or heights)")
    landblock = read.landblock(ctx, f"{key}.id", entry["id"])
    if landblock in seen:
        raise ctx.fail(f"{key}.id", f"landblock 0x{landblock:04X} is listed twice")
    seen.add(landblock)
    if "height" in entry and "heights" in entry:
        raise ctx.fail(f"{key}.heights", "give height (flat ground) or heights (81 height bytes), not both")
    if "heights" in entry:
        height_bytes = _whole_numbers(ctx, f"{key}.heights", entry["heights"], "height bytes", 0xFF)
        if "height_table" in entry:
            table = _height_table(ctx, f"{key}.height_table", entry["height_table"])
        elif data.portal is not None:
            table = list(data.height_table(f"{key}.heights"))
        else:
            table = _retail_height_table(ctx, f"{key}.heights", height_bytes)
    elif "height" in entry:
        if "height_table" in entry:
            raise ctx.fail(f"{key}.height_table", "only with heights (flat ground at height needs none)")
        height = read.float32(ctx, f"{key}.height", entry["height"], 0.0, MAX_LAND_HEIGHT)
        height_bytes, table = [0] * NUM_VERTICES, [height] * HEIGHT_TABLE_SIZE
    elif data.cell is not None:
        for extra in ("height_table", "water"):
            if extra in entry:
                raise ctx.fail(
                    f"{key}.{extra}",
                    "only with height or heights (a landblock from the cell DAT has its own terrain)",
                )
        block = LandBlock(data.landblock(f"{key}.id", landblock))
        world.add_landblock(block)
        from_dat.append((f"{key}.id", landblock, block))
        return
    else:
        raise ctx.fail(
            f"{key}.height",
            "missing (a landblock needs height, or heights and height_table, or a [data] cell "
            "to read its terrain from)",
        )
    words = _water(ctx, f"{key}.water", entry.get("water", "none"))
    world.add_landblock(LandBlock(LandBlockStruct((landblock << 16) | 0xFFFF, height_bytes, words, table)))


# -- solid setups -----------------------------------------------------------------------------


def _face(ctx: Ctx, key: str, value: Any) -> Polygon:
    if not isinstance(value, list) or len(value) < 3:
        raise ctx.fail(key, f"expected a face of at least 3 points [x, y, z], got {read.kind(value)}")
    points = [read.local_point(ctx, f"{key}[{i}]", item) for i, item in enumerate(value)]
    try:
        return Polygon(points)
    except ValueError as error:
        raise ctx.fail(key, str(error)) from None


def _faces(ctx: Ctx, key: str, value: Any) -> list[Polygon]:
    if not isinstance(value, list):
        raise ctx.fail(key, f"expected a list of faces [[x, y, z], ...], got {read.kind(value)}")
    return [_face(ctx, f"{key}[{i}]", item) for i, item in enumerate(value)]


def read_solids(ctx: Ctx, key: str, table: dict[str, Any]) -> BSPTree | None:
    """The physics BSP of a setup's ``boxes``, ``polygons`` (one convex solid) and ``solids``
    (several), or None when it has none."""
    boxes = read.list_of_tables(ctx, f"{key}.boxes", table.get("boxes", []))
    raw_solids = table.get("solids", [])
    if not isinstance(raw_solids, list):
        raise ctx.fail(
            f"{key}.solids", f"expected a list of solids (each a list of faces), got {read.kind(raw_solids)}"
        )
    count = len(boxes) + len(raw_solids) + ("polygons" in table)
    if count > MAX_UNION_SOLIDS:
        raise ctx.fail(
            key, f"a setup has at most {MAX_UNION_SOLIDS} boxes and solids (MAX_UNION_SOLIDS), got {count}"
        )
    solids: list[tuple[str, list[Polygon]]] = []
    for index, item in enumerate(boxes):
        box_key = f"{key}.boxes[{index}]"
        entry = read.table(ctx, box_key, item, ("min", "max"))
        if "min" not in entry or "max" not in entry:
            raise ctx.fail(box_key, "a box needs min = [x, y, z] and max = [x, y, z]")
        lo, hi = (
            read.local_point(ctx, f"{box_key}.min", entry["min"]),
            read.local_point(ctx, f"{box_key}.max", entry["max"]),
        )
        try:
            solids.append((box_key, box_faces(lo, hi)))
        except ValueError as error:
            raise ctx.fail(box_key, str(error)) from None
    if "polygons" in table:
        solids.append((f"{key}.polygons", _faces(ctx, f"{key}.polygons", table["polygons"])))
    for index, item in enumerate(raw_solids):
        solids.append((f"{key}.solids[{index}]", _faces(ctx, f"{key}.solids[{index}]", item)))
    if not solids:
        return None
    try:
        return build_union_tree([faces for _key, faces in solids])
    except SolidError as error:
        raise ctx.fail(solids[error.index][0], str(error)) from None
    except ValueError as error:
        raise ctx.fail(key, str(error)) from None


# -- placement --------------------------------------------------------------------------------


def _landblock_point(ctx: Ctx, key: str, value: Any) -> Vector3:
    origin = read.vector(ctx, key, value)
    if not (0.0 <= origin.x < BLOCK_LENGTH and 0.0 <= origin.y < BLOCK_LENGTH):
        raise ctx.fail(key, f"x and y must be landblock-local, in [0, 192), got ({origin.x:g}, {origin.y:g})")
    return origin


def warn_outside_landblocks(ctx: Ctx, key: str, world: World, landblock: int) -> None:
    """Warn of a body or object in a landblock the scenario does not declare when it declares
    others: it would stand in a void without terrain."""
    declared = world.landscape.landblocks()
    if declared and landblock not in declared:
        listed = ", ".join(f"0x{block:04X}" for block in sorted(declared))
        ctx.warn(key, f"0x{landblock:04X} is none of the declared landblocks ({listed}): no terrain there")


def cell_at(world: World, landblock: int, point: Vector3) -> int:
    """The cell holding the landblock-local ``point``: a room containing it (a scenario
    ``[[building]]``'s or one a cell DAT loaded), else the outdoor cell."""
    for cell in world.landscape.env_cells(landblock):
        if cell.point_in_cell(point):
            return cell.id
    return outdoor_cell_id(landblock, point)


OBJECT_KEYS = ("name", "setup", "landblock", "origin", "heading", "scale")


def read_objects(ctx: Ctx, raw: Any, world: World, find_setup: SetupLookup) -> list[PhysicsObj]:
    """Place each ``[[object]]`` in ``world`` (in the room holding its origin, if any); an object
    with a problem is reported and left out."""
    objects: list[PhysicsObj] = []
    names: set[str] = set()
    entries = read.list_of_tables(ctx, "object", raw)
    read.at_most(ctx, "object", entries, MAX_OBJECTS, "objects", "MAX_OBJECTS")
    for index, item in enumerate(entries):
        with ctx.part():
            placed = _read_object(ctx, f"object[{index}]", index, item, world, find_setup, names)
            names.add(placed.name)
            objects.append(placed)
    return objects


def _read_object(
    ctx: Ctx,
    key: str,
    index: int,
    item: Any,
    world: World,
    find_setup: SetupLookup,
    names: set[str],
) -> PhysicsObj:
    """One ``[[object]]``, placed in ``world`` (``names``: those of the objects placed before it)."""
    entry = read.table(ctx, key, item, OBJECT_KEYS)
    for required in ("setup", "landblock", "origin"):
        if required not in entry:
            raise ctx.fail(f"{key}.{required}", "missing (every object needs setup, landblock and origin)")
    setup = find_setup(f"{key}.setup", entry["setup"])
    name = read.string(ctx, f"{key}.name", entry["name"]) if "name" in entry else f"{setup.name}-{index}"
    if name in names:
        raise ctx.fail(f"{key}.name", f"two objects are named {name!r}")
    landblock = read.landblock(ctx, f"{key}.landblock", entry["landblock"])
    origin = _landblock_point(ctx, f"{key}.origin", entry["origin"])
    heading = read.float32(ctx, f"{key}.heading", entry.get("heading", 0.0), -360.0, 360.0)
    scale = read.float32(ctx, f"{key}.scale", entry.get("scale", 1.0), 0.0, 1000.0, open_low=True)
    warn_outside_landblocks(ctx, f"{key}.landblock", world, landblock)
    position = Position(cell_at(world, landblock, origin), Frame.from_heading(origin, heading))
    try:
        return add_static_object(world, name, setup, position, scale)
    except ValueError as error:
        raise ctx.fail(key, str(error)) from None


# -- buildings --------------------------------------------------------------------------------

BUILDING_KEYS = ("landblock", "origin", "heading", "wall_thickness", "rooms", "doorways")
OUTSIDE = "outside"


def _turn(point: Vector3, heading: int) -> Vector3:
    """``point`` turned to compass ``heading`` (0, 90, 180 or 270): local +y faces the heading."""
    x, y, z = point.x, point.y, point.z
    if heading == 90:
        return Vector3(y, -x, z)
    if heading == 180:
        return Vector3(-x, -y, z)
    if heading == 270:
        return Vector3(-y, x, z)
    return Vector3(x, y, z)


def _placed_box(lo: Vector3, hi: Vector3, origin: Vector3, heading: int) -> tuple[Vector3, Vector3]:
    a, b = _turn(lo, heading) + origin, _turn(hi, heading) + origin
    return Vector3(min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)), Vector3(
        max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)
    )


def _axes(v: Vector3) -> tuple[float, float, float]:
    return v.x, v.y, v.z


def _walls_holding(lo: Vector3, hi: Vector3, room: tuple[Vector3, Vector3]) -> bool:
    """Whether the flat rectangle ``lo``-``hi`` lies on a wall of the box ``room``."""
    r_lo, r_hi = _axes(room[0]), _axes(room[1])
    d_lo, d_hi = _axes(lo), _axes(hi)
    tol = 1e-6
    for axis in range(3):
        if abs(d_lo[axis] - d_hi[axis]) > tol:
            continue
        if abs(d_lo[axis] - r_lo[axis]) > tol and abs(d_lo[axis] - r_hi[axis]) > tol:
            return False
        return all(r_lo[k] - tol <= d_lo[k] and d_hi[k] <= r_hi[k] + tol for k in range(3) if k != axis)
    return False


def _read_rooms(
    ctx: Ctx, key: str, value: Any, origin: Vector3, heading: int
) -> dict[str, tuple[Vector3, Vector3]]:
    rooms: dict[str, tuple[Vector3, Vector3]] = {}
    entries = read.at_most(ctx, key, read.list_of_tables(ctx, key, value), MAX_ROOMS, "rooms", "MAX_ROOMS")
    for index, item in enumerate(entries):
        room_key = f"{key}[{index}]"
        entry = read.table(ctx, room_key, item, ("name", "min", "max"))
        for required in ("name", "min", "max"):
            if required not in entry:
                raise ctx.fail(f"{room_key}.{required}", "missing (a room needs name, min and max)")
        name = read.string(ctx, f"{room_key}.name", entry["name"])
        if name == OUTSIDE or name in rooms:
            raise ctx.fail(
                f"{room_key}.name", f"room name {name!r} is taken (rooms need distinct names, not 'outside')"
            )
        lo, hi = (
            read.local_point(ctx, f"{room_key}.min", entry["min"]),
            read.local_point(ctx, f"{room_key}.max", entry["max"]),
        )
        if not (lo.x < hi.x and lo.y < hi.y and lo.z < hi.z):
            raise ctx.fail(room_key, f"min {_axes(lo)} must be below max {_axes(hi)} on every axis")
        box = _placed_box(lo, hi, origin, heading)
        for other, other_box in rooms.items():
            if all(
                a_lo < b_hi - 1e-6 and b_lo < a_hi - 1e-6
                for a_lo, a_hi, b_lo, b_hi in zip(
                    _axes(box[0]), _axes(box[1]), _axes(other_box[0]), _axes(other_box[1]), strict=True
                )
            ):
                raise ctx.fail(room_key, f"room {name!r} overlaps room {other!r}")
        rooms[name] = box
    if not rooms:
        raise ctx.fail(key, "missing: a building needs at least one room")
    return rooms


def _read_doorways(
    ctx: Ctx, key: str, value: Any, rooms: dict[str, tuple[Vector3, Vector3]], origin: Vector3, heading: int
) -> list[DoorwaySpec]:
    doorways = []
    entries = read.list_of_tables(ctx, key, value)
    for index, item in enumerate(read.at_most(ctx, key, entries, MAX_DOORWAYS, "doorways", "MAX_DOORWAYS")):
        door_key = f"{key}[{index}]"
        entry = read.table(ctx, door_key, item, ("between", "min", "max"))
        for required in ("between", "min", "max"):
            if required not in entry:
                raise ctx.fail(f"{door_key}.{required}", "missing (a doorway needs between, min and max)")
        between = entry["between"]
        if not isinstance(between, list) or len(between) != 2 or not all(isinstance(n, str) for n in between):
            raise ctx.fail(
                f"{door_key}.between",
                f'expected two names like ["hall", "outside"], got {read.kind(between)}',
            )
        for name in between:
            if name != OUTSIDE and name not in rooms:
                raise ctx.fail(
                    f"{door_key}.between", f"no room named {name!r} (rooms: {', '.join(rooms)}, or 'outside')"
                )
        if between[0] == between[1]:
            raise ctx.fail(
                f"{door_key}.between", f"a doorway joins two different places, got {between[0]!r} twice"
            )
        lo, hi = _placed_box(
            read.local_point(ctx, f"{door_key}.min", entry["min"]),
            read.local_point(ctx, f"{door_key}.max", entry["max"]),
            origin,
            heading,
        )
        flat = sum(abs(a - b) <= 1e-6 for a, b in zip(_axes(lo), _axes(hi), strict=True))
        if flat != 1:
            raise ctx.fail(
                door_key, "a doorway is a rectangle: min and max must be equal on exactly one axis"
            )
        on = [name for name, box in rooms.items() if _walls_holding(lo, hi, box)]
        named = sorted(name for name in between if name != OUTSIDE)
        if sorted(on) != named:
            where = f"on the walls of {', '.join(map(repr, on))}" if on else "on no room's wall"
            raise ctx.fail(door_key, f"the doorway between {between[0]!r} and {between[1]!r} lies {where}")
        doorways.append(DoorwaySpec(lo, hi))
    return doorways


def read_buildings(ctx: Ctx, raw: Any, world: World) -> None:
    """Build each ``[[building]]`` with ``build_house``: its rooms become env cells of the world
    (ids 0x0100 up in their landblock, in order), the building stands in the land cell holding
    its origin. A building with a problem is reported and left out."""
    entries = read.list_of_tables(ctx, "building", raw)
    read.at_most(ctx, "building", entries, MAX_BUILDINGS, "buildings", "MAX_BUILDINGS")
    for index, item in enumerate(entries):
        with ctx.part():
            _read_building(ctx, f"building[{index}]", item, world)


def _read_building(ctx: Ctx, key: str, item: Any, world: World) -> None:
    """One ``[[building]]``: its rooms and shell added to ``world``."""
    entry = read.table(ctx, key, item, BUILDING_KEYS)
    for required in ("landblock", "origin", "rooms", "doorways"):
        if required not in entry:
            raise ctx.fail(
                f"{key}.{required}", "missing (a building needs landblock, origin, rooms and doorways)"
            )
    landblock = read.landblock(ctx, f"{key}.landblock", entry["landblock"])
    origin = _landblock_point(ctx, f"{key}.origin", entry["origin"])
    raw_heading = read.number(ctx, f"{key}.heading", entry.get("heading", 0.0))
    if raw_heading % 90.0 != 0.0:
        raise ctx.fail(
            f"{key}.heading",
            f"rooms are axis-aligned boxes: expected a multiple of 90, got {raw_heading:g}",
        )
    heading = int(raw_heading % 360.0)
    thickness = read.float32(
        ctx, f"{key}.wall_thickness", entry.get("wall_thickness", 0.25), 0.0, 10.0, open_low=True
    )
    rooms = _read_rooms(ctx, f"{key}.rooms", entry["rooms"], origin, heading)
    doorways = _read_doorways(ctx, f"{key}.doorways", entry["doorways"], rooms, origin, heading)
    for lo, hi in rooms.values():
        for x, y in ((lo.x - thickness, lo.y - thickness), (hi.x + thickness, hi.y + thickness)):
            if not (0.0 <= x < BLOCK_LENGTH and 0.0 <= y < BLOCK_LENGTH):
                raise ctx.fail(
                    f"{key}.origin",
                    f"the building reaches ({x:g}, {y:g}), outside its landblock: walls must stay "
                    f"in [0, 192)",
                )
    # Rooms are numbered after the landblock's other env cells (those a cell DAT loaded, then
    # earlier buildings'), so ids never clash.
    first = FIRST_ENV_CELL
    while world.get_cell(cell_of(landblock, first)) is not None:
        first += 1
    specs = [RoomSpec(cell_of(landblock, first + n), lo, hi) for n, (lo, hi) in enumerate(rooms.values())]
    try:
        building, cells = build_house(specs, doorways, wall_thickness=thickness)
    except ValueError as error:
        raise ctx.fail(key, str(error)) from None
    land = world.get_cell(outdoor_cell_id(landblock, building.pos.frame.origin))
    if not isinstance(land, SortCell) or land.has_building():
        raise ctx.fail(f"{key}.origin", "the land cell at the building's centre already holds a building")
    for cell in cells:
        world.add_cell(cell)
    building.add_to_cell(land)
    building.source = world
