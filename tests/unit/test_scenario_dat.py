"""Scenario ``[data]``: setups, the region's height table and landblock terrain from the user's
retail DAT files, here small portal and cell DATs built in ``tmp_path`` (``tests/dat_support.py``).

The keys are acphys's (README "Scenarios"); the expected values are the records written below,
as the record parsers read them (float32, CSetup::UnPack's field order).
"""

from __future__ import annotations

from pathlib import Path

import pytest

import acphys
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.vector import Vector3
from acphys.simulation import Simulation
from acphys.world.terrain import WaterType
from dat_support import (
    CELL,
    LANDBLOCK_ID,
    REGION_ID,
    SETUP_ID,
    f32,
    landblock_record,
    region_record,
    setup_record,
    simple_dat,
)

LAND = 0xA9B40001
#: A second setup in the portal, with its own step heights.
OTHER_SETUP = 0x02000123
#: Cell DAT terrain: vertex (x, y) (index 9x + y) holds height byte x + y; vertex (0, 0) is water
#: (terrain type 16 in bits 2..6), the rest type 0.
HEIGHTS = [x + y for x in range(9) for y in range(9)]
TERRAIN = [16 << 2] + [0] * 80
BODY = """
[[body]]
name = "a"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
"""
PORTAL_DATA = '[data]\nportal = "client_portal.dat"\n'
BOTH_DATA = '[data]\nportal = "client_portal.dat"\ncell = "client_cell_1.dat"\n'
CELL_LANDBLOCK = '[[landblock]]\nid = "0xA9B4"\n'
FLAT = CELL_LANDBLOCK + "height = 50.0\n"


@pytest.fixture
def dats(tmp_path: Path) -> Path:
    """A portal DAT (human setup, another setup, the region) and a cell DAT (landblock 0xA9B4)."""
    portal = {
        SETUP_ID: setup_record(steps=(0.6, 0.4)),
        OTHER_SETUP: setup_record(flags=0, setup_id=OTHER_SETUP, steps=(0.25, 0.15)),
        REGION_ID: region_record(),  # entry i is 2.5 i metres
    }
    simple_dat(tmp_path, portal)
    cell = {LANDBLOCK_ID: landblock_record(terrain=TERRAIN, heights=HEIGHTS)}
    simple_dat(tmp_path, cell, name="client_cell_1.dat", data_set=CELL)
    return tmp_path


def load(folder: Path, text: str, name: str = "world.toml") -> Simulation:
    path = folder / name
    path.write_text(text + BODY, encoding="utf-8")
    return acphys.load_scenario(path)


def fails(folder: Path, text: str, key: str, problem: str) -> None:
    with pytest.raises(acphys.ScenarioError) as caught:
        load(folder, text)
    # The problem at ``key`` is among those found (a scenario reports each independent one),
    # each of them one line.
    problems = caught.value.problems
    at_key = [p for p in problems if p.startswith(f"{folder / 'world.toml'}: {key}: ")]
    assert at_key, problems
    assert problem in at_key[0], problems
    assert all("\n" not in p for p in problems)


# -- setups -----------------------------------------------------------------------------------


def test_human_takes_the_portal_setup_step_heights_and_keeps_humanoid(dats: Path) -> None:
    body = load(dats, PORTAL_DATA + FLAT).body("a")
    setup = body.part_array.setup
    # CSetup::UnPack reads height, radius, step_up_height, then step_down_height (acclient.c:335520)
    assert (setup.step_up_height, setup.step_down_height) == (f32(0.6), f32(0.4))
    assert body.part_array.get_step_up_height() == f32(0.6)
    assert (setup.height, setup.radius) == (f32(1.83), f32(0.48))
    assert [(s.center.z, s.radius) for s in setup.spheres] == [
        (f32(0.475), f32(0.48)),
        (f32(1.35), f32(0.48)),
    ]
    # the DAT's sorting sphere, not the one acphys derives around the spheres (radius 0.9175)
    assert (setup.sorting_sphere.center.z, setup.sorting_sphere.radius) == (f32(0.9125), f32(0.9525))
    assert setup.name == "human" and setup.motion_table is not None
    assert body.movement_manager is not None


def test_human_without_data_has_the_public_dumps_step_heights(tmp_path: Path) -> None:
    # setup 0x02000001 as public DAT dumps give it (acphys.setup.human_setup): 0.6 up, 1.5 down
    setup = load(tmp_path, FLAT).body("a").part_array.setup
    assert (setup.step_up_height, setup.step_down_height) == (f32(0.6), 1.5)


def test_a_dat_setup_id_loads_that_setup_for_bodies_and_objects(dats: Path) -> None:
    obj = '[[object]]\nsetup = "0x02000123"\nlandblock = "0xA9B4"\norigin = [20.0, 20.0, 50.0]\n'
    text = PORTAL_DATA + FLAT + obj
    sim = load(dats, text + BODY.replace('name = "a"', 'name = "b"\nsetup = "0x02000123"'))
    setup = sim.body("b").part_array.setup
    assert (setup.step_up_height, setup.step_down_height) == (f32(0.25), f32(0.15))
    assert setup.name == "0x02000123" and setup.motion_table is None
    assert not setup.allow_free_heading  # flags 0: bit 2 clear
    assert sim.body("a").part_array.setup.step_up_height == f32(0.6)  # the human is 0x02000001
    cell = sim.world.get_cell(outdoor_cell_id(0xA9B4, Vector3(20.0, 20.0, 50.0)))
    objects = [obj for obj in cell.objects if obj.name == "0x02000123-0"]  # unnamed: setup-index
    assert len(objects) == 1 and objects[0].part_array.setup.step_down_height == f32(0.15)


def test_scenario_setups_come_before_dat_ids(dats: Path) -> None:
    text = PORTAL_DATA + '[setup."0x02000123"]\nstep_up_height = 0.5\n'
    sim = load(dats, text + BODY.replace('name = "a"', 'name = "b"\nsetup = "0x02000123"'))
    assert sim.body("b").part_array.setup.step_up_height == 0.5


# -- terrain ----------------------------------------------------------------------------------


def test_landblock_with_only_id_takes_the_cell_terrain_through_the_portal_table(dats: Path) -> None:
    world = load(dats, BOTH_DATA + CELL_LANDBLOCK).world
    block = world.landscape.get_landblock(LAND)
    assert block is not None
    terrain = block.terrain
    assert bytes(terrain.height) == bytes(HEIGHTS) and tuple(terrain.terrain) == tuple(TERRAIN)
    # vertex (x, y) is byte x + y; the region's table entry i is 2.5 i m
    assert terrain.vertex(3, 5).z == f32(8 * 2.5)
    assert terrain.vertex(8, 8).z == f32(16 * 2.5)
    # only vertex (0, 0) is water: the landblock is partly water
    assert block.water_type == WaterType.PARTIALLY_WATER
    point = Vector3(24.0, 48.0, 0.0)  # vertex (1, 2): byte 3
    assert world.ground_height(outdoor_cell_id(0xA9B4, point), point) == pytest.approx(7.5)


def test_heights_without_table_use_the_portal_region_table(dats: Path) -> None:
    ramp = "heights = [" + ", ".join(map(str, HEIGHTS)) + "]\n"
    terrain = load(dats, PORTAL_DATA + CELL_LANDBLOCK + ramp).world.landscape.get_landblock(LAND).terrain
    assert terrain.vertex(2, 4).z == f32(6 * 2.5)
    assert tuple(terrain.terrain) == (0,) * 81  # water = "none"


def test_flat_and_explicit_landblocks_ignore_the_cell(dats: Path) -> None:
    world = load(dats, BOTH_DATA + CELL_LANDBLOCK + "height = 12.0\n").world
    assert {v.z for v in world.landscape.get_landblock(LAND).terrain.vertices} == {12.0}


def test_relative_paths_resolve_against_the_scenario_folder(
    dats: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    nested = dats / "scenarios"
    nested.mkdir()
    text = '[data]\nportal = "../client_portal.dat"\ncell = "../client_cell_1.dat"\n' + CELL_LANDBLOCK
    assert load(nested, text).body("a").part_array.setup.step_up_height == f32(0.6)
    # parse_scenario: against ``folder``, else the current directory
    sim = acphys.parse_scenario(text + BODY, source="mem.toml", folder=nested)
    assert sim.world.landscape.get_landblock(LAND) is not None
    monkeypatch.chdir(nested)
    assert acphys.parse_scenario(text + BODY).world.landscape.get_landblock(LAND) is not None
    absolute = f'[data]\nportal = "{dats / "client_portal.dat"}"\n'
    assert acphys.parse_scenario(absolute + BODY).body("a").part_array.setup.step_up_height == f32(0.6)


# -- errors -----------------------------------------------------------------------------------


def test_missing_dat_files(dats: Path) -> None:
    fails(dats, '[data]\nportal = "none.dat"\n', "data.portal", f"no such file {dats / 'none.dat'}")
    fails(dats, '[data]\ncell = "gone/cell.dat"\n', "data.cell", "no such file")
    fails(dats, "[data]\nportal = 3\n", "data.portal", "expected a non-empty string")
    fails(dats, '[data]\nlocal = "x.dat"\n', "data.local", "unknown key (expected one of: portal, cell)")


def test_dat_errors_are_wrapped(dats: Path) -> None:
    (dats / "bad.dat").write_bytes(b"\0" * 2048)
    fails(dats, '[data]\nportal = "bad.dat"\n', "data.portal", "bad.dat at offset 0x140: bad magic 0x0000")
    # the cell DAT given as the portal: data set 2, not 1 (DATFILE_TYPE, acclient.h:3116)
    fails(dats, '[data]\nportal = "client_cell_1.dat"\n', "data.portal", "is a cell DAT (data set 2)")
    # a damaged record: the setup's last bytes cut off
    simple_dat(dats, {SETUP_ID: setup_record()[:-3]}, name="short.dat")
    fails(dats, '[data]\nportal = "short.dat"\n', "body[0].setup", "setup 0x02000001: record truncated")


def test_ids_not_in_the_dat(dats: Path) -> None:
    body = BODY.replace('name = "a"', 'name = "b"\nsetup = "0x02000999"')
    fails(dats, PORTAL_DATA + body, "body[0].setup", "no setup 0x02000999 in")
    fails(dats, BOTH_DATA + '[[landblock]]\nid = "0xA9B5"\n', "landblock[0].id", "no landblock 0xa9b5ffff in")
    # a portal without the region record cannot give heights their table
    simple_dat(dats, {SETUP_ID: setup_record()}, name="setups.dat")
    ramp = "heights = [" + ", ".join(map(str, HEIGHTS)) + "]\n"
    text = '[data]\nportal = "setups.dat"\n' + CELL_LANDBLOCK + ramp
    fails(dats, text, "landblock[0].heights", "no region 0x13000000 in")
    object_text = '[[object]]\nsetup = "0x01000001"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 0.0]\n'
    fails(dats, PORTAL_DATA + object_text, "object[0].setup", "0x01000001 is not a setup id")


def test_data_needed_but_not_given(dats: Path) -> None:
    steep = "heights = [" + ", ".join(str(250 - h) for h in HEIGHTS) + "]\n"
    fails(dats, CELL_LANDBLOCK + steep, "landblock[0].heights[0]", "give height_table, or a [data] portal")
    fails(dats, CELL_LANDBLOCK, "landblock[0].height", "or a [data] cell")
    fails(
        dats,
        '[data]\ncell = "client_cell_1.dat"\n' + CELL_LANDBLOCK,
        "landblock[0].id",
        "needs a [data] portal too (for the region's height table)",
    )
    body = BODY.replace('name = "a"', 'name = "b"\nsetup = "0x02000001"')
    fails(dats, body, "body[0].setup", "setup 0x02000001 is a DAT setup: it needs a [data] portal")
    fails(dats, BOTH_DATA + CELL_LANDBLOCK + 'water = "all"\n', "landblock[0].water", "only with height")


def test_a_setup_with_a_physics_bsp_it_cannot_place_is_refused(dats: Path) -> None:
    """``CSetup`` flag 8 (HAS_PHYSICS_BSP) on a setup whose parts acphys cannot place as one physics
    tree in the body frame (here: no single GfxObj part) is refused by name."""
    simple_dat(dats, {SETUP_ID: setup_record(flags=0x8)}, name="bsp.dat")
    fails(dats, '[data]\nportal = "bsp.dat"\n', "body[0].setup", "has a physics BSP")


def test_the_region_record_is_checked(dats: Path) -> None:
    simple_dat(dats, {REGION_ID: region_record(version=4)}, name="new.dat")
    ramp = "heights = [" + ", ".join(map(str, HEIGHTS)) + "]\n"
    text = '[data]\nportal = "new.dat"\n' + CELL_LANDBLOCK + ramp
    # CRegionDesc::UnPack refuses any version but 3 (acclient.c:299775)
    fails(dats, text, "landblock[0].heights", "version 4 is newer")
