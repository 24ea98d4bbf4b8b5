"""Sweeps near a building, in the kernel while they stay out of its reach (issue 14).

A land cell with a building asks the building's shell (``CBuildingObj::find_building_collisions``,
acclient.c:719115: its part's bounding sphere first, ``CGfxObj::find_obj_collisions``,
acclient.c:356514) and lets the cells behind its doors take the spheres
(``CEnvCell::check_building_transit``, acclient.c:348109, through
``BSPNODE::sphere_intersects_cell_bsp``, acclient.c:362979: a centre more than ``radius + 0.01``
behind a plane of the cell BSP's chain is outside). The kernel keeps the shell's ball and the
doors' planes (:mod:`acphys.fast.buildings`) and leaves to the reference path only the steps that
come within their reach; the runs stay the reference's byte for byte.
"""

from __future__ import annotations

import math
import random
from pathlib import Path

import pytest

from acphys.bench import _HOUSE
from acphys.fast.buildings import MARGIN, building_reach
from acphys.fast.differential import compare_engines
from acphys.geometry.bsp import CELL_SPHERE_SLACK, _cell_plane_dist
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.scenario import parse_scenario
from acphys.simulation import Simulation
from acphys.world.env_cell import EnvCell
from acphys.world.obj_cell import CellArray

pytestmark = pytest.mark.kernels

BLOCK = 0xA9B40000
#: The house's cell: (156, 156) lies in column 6, row 6 (8·6 + 6 + 1 = 0x37).
HOUSE_CELL = BLOCK | 0x37


def _around_the_house(engine: str, seconds: float = 4.0) -> Simulation:
    """Walkers circling in the house's cell (some clear of the house, some brushing its walls), one
    walking up to its door (x 150, y 155.4 to 156.6, its frame stops a human) and one into its wall
    beside the door."""
    text = [
        f'[scenario]\nname = "house"\nduration = {seconds}\ndriver_hz = 30.0\n',
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n',
        f'[[building]]\nlandblock = "0xA9B4"\n{_HOUSE}',
    ]
    circles = ((146.0, 146.0), (166.0, 146.0), (146.0, 166.0), (166.0, 166.0), (149.0, 156.0), (163.0, 159.0))
    for n, (x, y) in enumerate(circles):
        text.append(
            f'[[body]]\nname = "c{n}"\nlandblock = "0xA9B4"\norigin = [{x}, {y}, 50.0]\non_ground = true\n'
            f"heading = {n * 60}\n"
            f'[[event]]\nat = 0.0\nbody = "c{n}"\naction = "motion"\nmotion = "WalkForward"\n'
            f'[[event]]\nat = 0.0\nbody = "c{n}"\naction = "motion"\nmotion = "TurnRight"\n'
        )
    for n, y in enumerate((156.0, 153.0)):  # due east
        text.append(
            f'[[body]]\nname = "in{n}"\nlandblock = "0xA9B4"\norigin = [144.0, {y}, 50.0]\non_ground = true\n'
            "heading = 90\n"
            f'[[event]]\nat = 0.0\nbody = "in{n}"\naction = "motion"\nmotion = "WalkForward"\n'
        )
    return parse_scenario("".join(text), source="<house>", engine=engine)


def test_walkers_around_a_house_run_as_on_the_reference(tmp_path: Path) -> None:
    comparison = compare_engines(_around_the_house, tmp_path)
    assert comparison.identical, comparison.divergence
    near = comparison.reasons.get("a cell the kernel does not know (indoors, a building or watchers)", 0)
    steps = comparison.kernel_steps + comparison.reference_steps
    assert near >= 60  # the one at the door, the one at the wall, and the circles brushing the walls
    assert comparison.kernel_steps >= 0.6 * steps  # every step in the house's cell went back before


def test_the_doors_planes_measure_as_the_cell_bsp_does() -> None:
    """A door's planes in the landblock frame give a landblock point the distance
    ``_cell_plane_dist`` gives its local point (acclient.c:362952), to float32 roundings."""
    sim = _around_the_house("reference")
    building = sim.world.get_cell(HOUSE_CELL).building
    ball, doors = building_reach(building)
    assert ball is not None and len(doors) == 1  # the hall's door; the parlour lies behind the hall
    hall = next(
        portal.get_other_cell(sim.world) for portal in building.portals if portal.other_portal_id >= 0
    )
    chain = []
    node = hall.structure.cell_bsp.root_node
    while node is not None:
        chain.append(node.splitting_plane)
        node = node.pos_node
    assert len(chain) == len(doors[0])
    rng = random.Random(5)
    for _ in range(2_000):
        p = Vector3(rng.uniform(130.0, 180.0), rng.uniform(130.0, 180.0), rng.uniform(45.0, 56.0))
        local = hall.pos.frame.globaltolocal(p)
        for plane, (nx, ny, nz, d) in zip(chain, doors[0], strict=True):
            assert abs(_cell_plane_dist(plane, local) - (nx * p.x + ny * p.y + nz * p.z + d)) < 1e-4


def test_a_sphere_behind_a_door_plane_by_the_margin_is_outside_its_cell() -> None:
    """Where the kernel passes the doors by, the reference's ``check_building_transit`` adds no
    cell: 20,000 spheres about the house, half of them within a metre of its walls."""
    sim = _around_the_house("reference")
    building = sim.world.get_cell(HOUSE_CELL).building
    _, doors = building_reach(building)
    hall = next(
        portal
        for portal in building.portals
        if portal.other_portal_id >= 0 and portal.get_other_cell(sim.world)
    )
    cell = hall.get_other_cell(sim.world)
    assert isinstance(cell, EnvCell)
    rng = random.Random(9)
    passed = 0
    for _ in range(20_000):
        radius = rng.choice((0.1, 0.48, 1.2))
        near = rng.random() < 0.5
        x = rng.uniform(148.5, 151.5) if near else rng.uniform(140.0, 172.0)
        p = Vector3(x, rng.uniform(150.0, 162.0), rng.uniform(49.0, 54.0))
        slack = radius + CELL_SPHERE_SLACK + MARGIN
        if not all(
            any(nx * p.x + ny * p.y + nz * p.z + d <= -slack for nx, ny, nz, d in door) for door in doors
        ):
            continue
        passed += 1
        cells = CellArray(sim.world)
        where = Position(HOUSE_CELL, Frame(p.copy()))
        cell.check_building_transit(hall.other_portal_id, where, [Sphere(p, radius)], cells, None)
        assert cells.cell_ids() == [], (p, radius)
    assert passed > 8_000


def test_the_shell_ball_holds_the_house() -> None:
    """The shell's ball (its physics BSP's bounding sphere, at the building's frame) holds every
    corner of the two rooms: a sphere out of its reach is out of the walls' reach."""
    sim = _around_the_house("reference")
    ball, _ = building_reach(sim.world.get_cell(HOUSE_CELL).building)
    x, y, z, radius, _ = ball
    x, y = x - 0xA9 * 192.0, y - 0xB4 * 192.0
    for cx in (150.0, 156.0, 162.0):
        for cy in (152.0, 160.0):
            for cz in (50.0, 53.0):
                assert math.dist((x, y, z), (cx, cy, cz)) <= radius
