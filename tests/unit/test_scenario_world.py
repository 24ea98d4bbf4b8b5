"""Scenario world data (contract 1, issue 5): landblock terrain and water, solid setups,
static objects, buildings, and the example worlds shipped with acphys.

Not retail behaviour: the scenario keys are acphys's. Expected values follow from the keys
as README "Scenarios" documents them and from the retail structures they build.
"""

from __future__ import annotations

import pytest

import acphys
from acphys.flags import PhysicsState, TransientState
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.scenario import builtin_scenarios
from acphys.scenario.world_data import WATER_WORD, _turn
from acphys.simulation import Simulation
from acphys.world.env_cell import OUTSIDE_CELL_ID, EnvCell
from acphys.world.land_cell import LandCell
from acphys.world.terrain import WaterType

BLOCK = 0xA9B4
LAND = 0xA9B40001
BODY = """
[[body]]
name = "a"
landblock = "0xA9B4"
origin = [10.0, 10.0, 50.0]
"""
TABLE = "height_table = [" + ", ".join(str(2.0 * i) for i in range(256)) + "]\n"
#: Vertex (x, y) holds byte x + y: the ground rises 2 m per vertex north and east.
RAMP = "heights = [" + ", ".join(str(x + y) for x in range(9) for y in range(9)) + "]\n"
FLAT = '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
HOUSE = """
[[building]]
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
rooms = [
    { name = "hall", min = [-4.0, -3.0, 0.0], max = [0.0, 3.0, 3.0] },
    { name = "parlour", min = [0.0, -3.0, 0.0], max = [4.0, 3.0, 3.0] },
]
doorways = [
    { between = ["outside", "hall"], min = [-4.0, -0.6, 0.0], max = [-4.0, 0.6, 2.2] },
    { between = ["hall", "parlour"], min = [0.0, -0.6, 0.0], max = [0.0, 0.6, 2.2] },
]
"""


def load(text: str) -> Simulation:
    return acphys.parse_scenario(text + BODY, source="world.toml")


def fails(text: str, key: str, problem: str) -> None:
    with pytest.raises(acphys.ScenarioError) as caught:
        load(text)
    message = str(caught.value)
    assert f"world.toml: {key}: " in message, message
    assert problem in message, message


# -- landblocks -------------------------------------------------------------------------------


def test_flat_height_builds_flat_dry_terrain() -> None:
    world = load(FLAT).world
    block = world.landscape.get_landblock(LAND)
    assert block is not None
    assert {v.z for v in block.terrain.vertices} == {50.0}
    assert block.water_type == WaterType.NOT_WATER
    assert world.ground_height(LAND, Vector3(33.0, 150.0, 0.0)) == 50.0


def test_heights_index_the_height_table_vertex_x_times_9_plus_y() -> None:
    world = load('[[landblock]]\nid = "0xA9B4"\n' + RAMP + TABLE).world
    terrain = world.landscape.get_landblock(LAND).terrain
    assert terrain.height[3 * 9 + 5] == 8
    assert terrain.vertex(3, 5).z == 16.0  # byte 3 + 5 = 8, table entry 8 = 16 m
    assert terrain.vertex(8, 0).z == 16.0
    assert terrain.vertex(0, 8).z == 16.0
    # Half-way between vertices (1, 1) (byte 2, 4 m) and (2, 1) (byte 3, 6 m): the ramp is one plane,
    # so either triangle gives 5 m.
    assert world.ground_height(LAND, Vector3(36.0, 24.0, 0.0)) == pytest.approx(5.0)


def test_water_all_and_raw_words() -> None:
    world = load(FLAT + 'water = "all"\n').world
    assert world.landscape.get_landblock(LAND).water_type == WaterType.ENTIRELY_WATER
    assert WATER_WORD >> 2 == 16  # terrain type 16, the first water type
    # Water at vertices x 0-1, y 0-1: cell (0, 0) is entirely water, its neighbours partially.
    words = [WATER_WORD if x <= 1 and y <= 1 else 4 for x in range(9) for y in range(9)]
    world = load(FLAT + f"water = {words}\n").world
    block = world.landscape.get_landblock(LAND)
    assert block.water_type == WaterType.PARTIALLY_WATER
    assert block.lcell[0].water_type == WaterType.ENTIRELY_WATER
    assert block.lcell[1].water_type == WaterType.PARTIALLY_WATER  # cell (0, 1)
    assert block.lcell[8].water_type == WaterType.PARTIALLY_WATER  # cell (1, 0)
    assert block.lcell[9].water_type == WaterType.PARTIALLY_WATER  # cell (1, 1): one water corner
    assert block.lcell[2].water_type == WaterType.NOT_WATER


@pytest.mark.parametrize(
    ("text", "key", "problem"),
    [
        ('[[landblock]]\nid = "0xA9B4"\n', "landblock[0].height", "missing"),
        (FLAT + RAMP, "landblock[0].heights", "not both"),
        (
            '[[landblock]]\nid = "0xA9B4"\n' + RAMP.replace("[0, ", "[201, "),
            "landblock[0].heights[0]",
            "height byte 201 is past the part of retail's height table acphys ships (bytes 0-200",
        ),
        ('[[landblock]]\nid = "0xA9B4"\nheights = [0, 1]\n' + TABLE, "landblock[0].heights", "expected 81"),
        (
            '[[landblock]]\nid = "0xA9B4"\nheights = [' + "0, " * 80 + "256]\n" + TABLE,
            "landblock[0].heights[80]",
            "[0, 255]",
        ),
        (
            '[[landblock]]\nid = "0xA9B4"\n' + RAMP + "height_table = [1.0]\n",
            "landblock[0].height_table",
            "256",
        ),
        (
            '[[landblock]]\nid = "0xA9B4"\n' + RAMP + "height_table = [" + "0.0, " * 255 + "801.0]\n",
            "landblock[0].height_table[255]",
            "[0, 800]",
        ),
        (
            '[[landblock]]\nid = "0xA9B4"\n' + RAMP + "height_table = [" + "0.0, " * 255 + "nan]\n",
            "landblock[0].height_table[255]",
            "finite",
        ),
        (FLAT + TABLE, "landblock[0].height_table", "only with heights"),
        (FLAT + 'water = "some"\n', "landblock[0].water", '"none", "all"'),
        (FLAT + "water = [4, 4]\n", "landblock[0].water", "81 terrain words"),
        (FLAT + "water = [" + "0, " * 80 + "65536]\n", "landblock[0].water[80]", "65535"),
        (FLAT + "slope = 1\n", "landblock[0].slope", "unknown key"),
    ],
)
def test_bad_landblocks(text: str, key: str, problem: str) -> None:
    fails(text, key, problem)


def test_a_table_with_decreasing_entries_is_accepted() -> None:
    table = "height_table = [" + ", ".join(str(510.0 - 2.0 * i) for i in range(256)) + "]\n"
    world = load('[[landblock]]\nid = "0xA9B4"\n' + RAMP + table).world
    assert world.landscape.get_landblock(LAND).terrain.vertex(0, 0).z == 510.0


# -- solid setups -----------------------------------------------------------------------------


def setup_of(text: str) -> object:
    sim = acphys.parse_scenario(FLAT + text + BODY.replace('name = "a"', 'name = "a"\nsetup = "s"'), "w")
    return sim.body("a").part_array.setup


def test_boxes_build_a_physics_bsp_of_their_union() -> None:
    setup = setup_of(
        "[setup.s]\nboxes = [{ min = [0, 0, 0], max = [1, 1, 1] }, { min = [2, 0, 0], max = [3, 1, 2] }]\n"
    )
    root = setup.physics_bsp.root_node
    assert root.point_intersects_solid(Vector3(0.5, 0.5, 0.5))
    assert root.point_intersects_solid(Vector3(2.5, 0.5, 1.5))
    assert not root.point_intersects_solid(Vector3(1.5, 0.5, 0.5))
    assert not root.point_intersects_solid(Vector3(0.5, 0.5, 1.5))


def tetrahedron(shift: float = 0.0) -> str:
    """The unit corner tetrahedron moved by ``shift`` on every axis, faces counter-clockwise from outside."""
    faces = [
        [(0, 0, 0), (0, 1, 0), (1, 0, 0)],
        [(0, 0, 0), (1, 0, 0), (0, 0, 1)],
        [(0, 0, 0), (0, 0, 1), (0, 1, 0)],
        [(1, 0, 0), (0, 1, 0), (0, 0, 1)],
    ]
    return str([[[c + shift for c in point] for point in face] for face in faces])


def test_polygons_and_solids_build_convex_solids() -> None:
    root = setup_of(f"[setup.s]\npolygons = {tetrahedron()}\n").physics_bsp.root_node
    assert root.point_intersects_solid(Vector3(0.2, 0.2, 0.2))
    assert not root.point_intersects_solid(Vector3(0.5, 0.5, 0.5))  # beyond the slanted face
    root = setup_of(f"[setup.s]\nsolids = [{tetrahedron()}, {tetrahedron(3.0)}]\n").physics_bsp.root_node
    assert root.point_intersects_solid(Vector3(0.2, 0.2, 0.2))
    assert root.point_intersects_solid(Vector3(3.2, 3.2, 3.2))
    assert not root.point_intersects_solid(Vector3(2.0, 2.0, 2.0))


def test_a_setup_without_solids_has_no_physics_bsp() -> None:
    assert setup_of("[setup.s]\nspheres = [{ center = [0, 0, 0.5], radius = 0.5 }]\n").physics_bsp is None


@pytest.mark.parametrize(
    ("text", "key", "problem"),
    [
        ("boxes = [{ min = [0, 0, 0], max = [1, 0, 1] }]", "setup.s.boxes[0]", "below max"),
        ("boxes = [{ min = [0, 0, 0] }]", "setup.s.boxes[0]", "needs min"),
        ("boxes = [{ min = [0, 0, 0], max = [1, 1, 1], size = 2 }]", "setup.s.boxes[0].size", "unknown key"),
        ("polygons = [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]]", "setup.s.polygons", "at least 4 faces"),
        ("polygons = [[[0, 0, 0], [1, 0, 0]]]", "setup.s.polygons[0]", "at least 3 points"),
        ("polygons = [[[0, 0, 0], [1, 0, 0], [2, 0, 0]]]", "setup.s.polygons[0]", "collinear"),
        (
            # the tetrahedron with one face turned inward
            "solids = [[[[0, 0, 0], [0, 1, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "
            "[[0, 0, 0], [0, 0, 1], [0, 1, 0]], [[1, 0, 0], [0, 0, 1], [0, 1, 0]]]]",
            "setup.s.solids[0]",
            "not a convex solid",
        ),
        ('solids = "cube"', "setup.s.solids", "list of solids"),
    ],
)
def test_bad_solids(text: str, key: str, problem: str) -> None:
    fails(f"{FLAT}[setup.s]\n{text}\n", key, problem)


# -- static objects ---------------------------------------------------------------------------

PILLAR = "[setup.pillar]\ncylspheres = [{ low_pt = [0, 0, 0], radius = 1.0, height = 3.0 }]\n"


def test_objects_are_static_and_stand_in_the_cell_under_their_origin() -> None:
    text = (
        FLAT
        + PILLAR
        + '[[object]]\nname = "p"\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [30.0, 40.0, 50.0]\n'
        + "heading = 90.0\nscale = 2.0\n"
        + '[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [100.0, 100.0, 50.0]\n'
    )
    world = load(text).world
    cell = world.get_cell(0xA9B4000A)  # x 30 -> column 1, y 40 -> row 1: 1 + 8*1 + 1
    (pillar,) = [obj for obj in cell.objects if obj.name == "p"]
    assert pillar.state & PhysicsState.STATIC
    assert pillar.position.objcell_id == 0xA9B4000A
    assert pillar.position.frame.origin.exactly_equals(Vector3(30.0, 40.0, 50.0))
    assert pillar.position.frame.get_heading() == pytest.approx(90.0)
    assert pillar.scale == 2.0
    assert any(obj.name == "pillar-1" for obj in world.get_cell(0xA9B40025).objects)  # unnamed: setup-index


def test_an_object_inside_a_room_stands_in_the_room() -> None:
    text = (
        FLAT
        + HOUSE
        + PILLAR
        + '[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [98.0, 96.0, 50.0]\n'
    )
    world = load(text).world
    assert any(obj.name == "pillar-0" for obj in world.get_cell(0xA9B40101).objects)


@pytest.mark.parametrize(
    ("text", "key", "problem"),
    [
        (
            '[[object]]\nsetup = "rock"\nlandblock = "0xA9B4"\norigin = [1, 1, 50]\n',
            "object[0].setup",
            "no setup named 'rock'",
        ),
        (
            '[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [192, 1, 50]\n',
            "object[0].origin",
            "[0, 192)",
        ),
        (
            '[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [1, -0.5, 50]\n',
            "object[0].origin",
            "[0, 192)",
        ),
        ('[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\n', "object[0].origin", "missing"),
        (
            '[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [1, 1, 50]\nscale = 0\n',
            "object[0].scale",
            "(0",
        ),
        (
            '[[object]]\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [1, 1, 50]\nmass = 1\n',
            "object[0].mass",
            "unknown key",
        ),
        (
            '[[object]]\nname = "a"\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [1, 1, 50]\n',
            "body[0].name",
            "both named 'a'",
        ),
        (
            '[[object]]\nname = "o"\nsetup = "pillar"\nlandblock = "0xA9B4"\norigin = [1, 1, 50]\n' * 2,
            "object[1].name",
            "two objects are named 'o'",
        ),
    ],
)
def test_bad_objects(text: str, key: str, problem: str) -> None:
    fails(FLAT + PILLAR + text, key, problem)


# -- buildings --------------------------------------------------------------------------------


def test_a_building_makes_env_cells_joined_by_portals_and_stands_in_its_land_cell() -> None:
    world = load(FLAT + HOUSE).world
    hall, parlour = world.get_cell(0xA9B40100), world.get_cell(0xA9B40101)
    assert isinstance(hall, EnvCell) and isinstance(parlour, EnvCell)
    assert hall.pos.frame.origin.exactly_equals(Vector3(92.0, 93.0, 50.0))  # the room's min, placed
    assert [p.other_cell_id for p in hall.portals] == [OUTSIDE_CELL_ID, 0xA9B40101]
    assert [p.other_cell_id for p in parlour.portals] == [0xA9B40100]
    assert hall.point_in_cell(Vector3(94.0, 96.0, 51.0))
    assert parlour.point_in_cell(Vector3(98.0, 96.0, 51.0))
    land = world.get_cell(0xA9B40025)  # the house's centre (96, 96): column 4, row 4
    assert isinstance(land, LandCell)
    building = land.building
    assert building is not None and building.source is world and building.cell is land
    assert building.pos.objcell_id == 0xA9B40025
    assert [portal.other_cell_id for portal in building.portals] == [0xA9B40100]


def test_a_turned_building_turns_its_rooms_and_numbering_continues_in_the_landblock() -> None:
    second = HOUSE.replace("[96.0, 96.0, 50.0]", "[40.0, 40.0, 50.0]\nheading = 90.0")
    world = load(FLAT + HOUSE + second).world
    hall = world.get_cell(0xA9B40102)
    # Heading 90 faces local +y east: the hall's local x -4..0, y -3..3 becomes x -3..3, y 0..4.
    assert hall.pos.frame.origin.exactly_equals(Vector3(37.0, 40.0, 50.0))
    assert hall.point_in_cell(Vector3(40.0, 42.0, 51.0))
    assert world.get_cell(0xA9B40103).point_in_cell(Vector3(40.0, 38.0, 51.0))


@pytest.mark.parametrize("heading", [0, 90, 180, 270])
def test_turning_by_a_right_angle_matches_the_heading_frame(heading: int) -> None:
    point = Vector3(1.5, -2.0, 0.7)
    expected = Frame.from_heading(Vector3(), float(heading)).localtoglobal(point)
    assert _turn(point, heading) == expected


def test_a_body_in_a_room_starts_in_its_env_cell() -> None:
    text = FLAT + HOUSE + BODY.replace("[10.0, 10.0, 50.0]", "[98.0, 97.0, 50.0]").replace('"a"', '"in"')
    assert load(text).body("in").position.objcell_id == 0xA9B40101


@pytest.mark.parametrize(
    ("change", "key", "problem"),
    [
        (
            ('"hall", "parlour"]', '"hall", "attic"]'),
            "building[0].doorways[1].between",
            "no room named 'attic'",
        ),
        (("[0.0, 3.0, 3.0] }", "[0.5, 3.0, 3.0] }"), "building[0].rooms[1]", "overlaps room 'hall'"),
        (("[96.0, 96.0, 50.0]", "[3.0, 96.0, 50.0]"), "building[0].origin", "outside its landblock"),
        (("[96.0, 96.0, 50.0]", "[200.0, 96.0, 50.0]"), "building[0].origin", "[0, 192)"),
        (
            ('["outside", "hall"]', '["outside", "parlour"]'),
            "building[0].doorways[0]",
            "on the walls of 'hall'",
        ),
        (('["hall", "parlour"]', '["hall", "outside"]'), "building[0].doorways[1]", "'hall', 'parlour'"),
        (('["hall", "parlour"]', '["hall", "hall"]'), "building[0].doorways[1].between", "twice"),
        (("max = [0.0, 0.6, 2.2]", "max = [0.5, 0.6, 2.2]"), "building[0].doorways[1]", "exactly one axis"),
        (
            ("max = [-4.0, 0.6, 2.2]", "max = [-4.0, 3.6, 2.2]"),
            "building[0].doorways[0]",
            "on no room's wall",
        ),
        (('name = "parlour"', 'name = "hall"'), "building[0].rooms[1].name", "distinct names"),
        (("[4.0, 3.0, 3.0]", "[4.0, 2.0, 3.0]"), "building[0]", "fill their bounding box"),
        (
            ("origin = [96.0, 96.0, 50.0]", "origin = [96.0, 96.0, 50.0]\nheading = 45.0"),
            "building[0].heading",
            "90",
        ),
        (("rooms = [", "floors = 2\nrooms = ["), "building[0].floors", "unknown key"),
    ],
)
def test_bad_buildings(change: tuple[str, str], key: str, problem: str) -> None:
    old, new = change
    assert old in HOUSE
    fails(FLAT + HOUSE.replace(old, new, 1), key, problem)


def test_two_buildings_in_one_land_cell_are_refused() -> None:
    fails(FLAT + HOUSE + HOUSE.replace("96.0, 96.0", "97.0, 97.0"), "building[1].origin", "already holds")


def test_a_house_without_an_outside_door_is_refused() -> None:
    inner = HOUSE.replace(
        '{ between = ["outside", "hall"], min = [-4.0, -0.6, 0.0], max = [-4.0, 0.6, 2.2] },', ""
    )
    fails(FLAT + inner, "building[0]", "doorway to the outside")


# -- the example worlds -----------------------------------------------------------------------


@pytest.mark.parametrize("name", ["hills", "yard", "house", "seam"])
def test_the_example_worlds_ship(name: str) -> None:
    assert name in builtin_scenarios()


@pytest.mark.parametrize("name", builtin_scenarios())
def test_every_built_in_scenario_loads_and_runs_for_a_second(name: str) -> None:
    sim = acphys.load_scenario(name)
    sim.run(until=1.0)
    assert sim.time == pytest.approx(1.0, abs=1.0 / sim.driver_hz)
    for body in sim.bodies:
        assert body.cell is not None, body.name


def test_the_hills_have_a_lake_and_the_seam_walker_crosses() -> None:
    hills = acphys.load_scenario("hills").world.landscape.get_landblock(LAND)
    assert hills.lcell[8 * 0 + 7].water_type == WaterType.ENTIRELY_WATER  # cell (0, 7)
    assert hills.lcell[8 * 4 + 4].water_type == WaterType.NOT_WATER
    seam = acphys.load_scenario("seam")
    assert seam.body("walker").position.objcell_id >> 16 == 0xA9B4
    seam.run()
    assert seam.body("walker").position.objcell_id >> 16 == 0xAAB4


def test_on_ground_keeps_the_contact_plane_placement_found_on_a_slope() -> None:
    # enter_world places the body through SetPosition (acclient.c:323440), which commits the terrain
    # triangle under it as the contact plane; on_ground only fills in a level plane where there is none.
    heights = [[x * 2 for _y in range(9)] for x in range(9)]
    flat = [h for column in heights for h in column]
    text = (
        '[[landblock]]\nid = "0xA9B4"\n'
        f"heights = {flat}\n"
        f"height_table = {[float(i) for i in range(256)]}\n"
        '[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [30.0, 30.0, 2.5]\non_ground = true\n'
    )
    body = acphys.parse_scenario(text).body("a")
    normal = body.contact_plane.N
    # The terrain rises 2 m per 24 m along x: the normal leans back against +x.
    assert normal.x < 0.0 and normal.z == pytest.approx(24.0 / (24.0**2 + 2.0**2) ** 0.5, abs=1e-6)


def test_heights_without_a_table_index_retails_height_table() -> None:
    # data/land_height_table.toml: byte i is 2·i m for bytes 0-200 (Region 0x13000000's
    # LandDefs.land_height_table as public sources give it). A ramp of bytes x + y: the vertex at
    # (96, 96) is vertex (4, 4), byte 8: 16 m; a human put on the ground there rests on it.
    text = (
        '[scenario]\nname = "ramp"\n[[landblock]]\nid = "0xA9B4"\n'
        + RAMP
        + '[[body]]\nname = "h"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 17.0]\non_ground = true\n'
    )
    sim = acphys.parse_scenario(text)
    assert sim.world.ground_height(0xA9B40024, Vector3(96.0, 96.0, 0.0)) == 16.0
    body = sim.body("h")
    assert body.transient_state & TransientState.ON_WALKABLE
    # the low point of sphere 0 (centre 0.475, radius 0.48) on the sloped plane through (96, 96, 16)
    assert 16.0 < body.position.frame.origin.z < 16.5
