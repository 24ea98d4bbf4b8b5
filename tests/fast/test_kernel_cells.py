"""The kernel's cell arrays across cell corners and a landblock seam (issue 14).

``CLandCell::add_all_outside_cells`` (acclient.c:355345) adds, for each global sphere, the land
cell under its centre and the neighbours its circle reaches (``check_add_cell_boundary``,
acclient.c:355161). The kernel skips a sphere over the same ground point with the same radius as
an earlier one (an upright human's two spheres): its adds would all find their cells in the array.
Humans walking and running across cell corners, where a circle reaches three neighbours, and
across the seam between two landblocks, must keep the reference's cells in the reference's
order: the traces (cell ids, frames, contact planes) are identical byte for byte.
"""

from __future__ import annotations

import math
import random
from pathlib import Path

import numpy as np

from acphys.fast.differential import compare_engines
from acphys.fast.kernels.cells import cell_clear_of_edges
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.scenario import parse_scenario
from acphys.trace import read_trace
from acphys.world.land_cell import LandCell
from acphys.world.obj_cell import CellArray
from acphys.world.world import World

#: Corners of 24-m cells, each walked through from 1 m away at a compass heading (degrees).
CORNERS = ((24.0, 24.0, 45.0), (48.0, 72.0, 135.0), (96.0, 48.0, 225.0), (144.0, 120.0, 315.0))


def _scenario() -> str:
    text = (
        '[scenario]\nname = "corners"\nduration = 3.0\ndriver_hz = 30.0\n'
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        '[[landblock]]\nid = "0xAAB4"\nheight = 50.0\n'
    )
    bodies = []
    for n, (x, y, heading) in enumerate(CORNERS):
        dx, dy = math.sin(math.radians(heading)), math.cos(math.radians(heading))
        bodies.append((f"corner-{n}", x - dx, y - dy, heading, "WalkForward", 1.0))
    bodies.append(("seam-walker", 190.5, 100.0, 90.0, "WalkForward", 1.0))
    bodies.append(("seam-runner", 189.0, 130.0, 80.0, "RunForward", 1.0))
    bodies.append(("tall", 23.0, 168.0, 45.0, "WalkForward", 1.6))
    for name, x, y, heading, motion, scale in bodies:
        text += (
            f'[[body]]\nname = "{name}"\nlandblock = "0xA9B4"\non_ground = true\nheading = {heading}\n'
            f"origin = [{x}, {y}, 50.0]\nscale = {scale}\n"
            f'[[event]]\nat = 0.0\nbody = "{name}"\naction = "motion"\nmotion = "{motion}"\n'
        )
    return text


def test_walks_across_cell_corners_and_a_seam_keep_the_reference_cells(tmp_path: Path) -> None:
    text = _scenario()
    result = compare_engines(lambda engine: parse_scenario(text, "<corners>", engine=engine), tmp_path)
    assert result.identical, result.divergence
    assert result.kernel_steps > 0.9 * (result.kernel_steps + result.reference_steps)
    cells: dict[str, set[int]] = {}
    for _line, record in read_trace(tmp_path / "fast.jsonl"):
        cells.setdefault(record["body"], set()).add(int(record["cell"], 16))
    assert all(len(seen) > 1 for seen in cells.values()), cells  # every body changed cells
    assert any(cell >> 16 == 0xAAB4 for cell in cells["seam-walker"]), cells["seam-walker"]


# -- a sphere clear of its cell's edges ------------------------------------------------------------

BLOCK = 0xA9B40000
RADII = (0.1, 0.47999998927116394, 0.7, 2.0, 11.5)


def _reference_cells(world: World, cell_id: int, x: float, y: float, radius: float) -> list[int]:
    """``CLandCell::add_all_outside_cells`` (acclient.c:355345) for one sphere, as the reference runs it."""
    cells = CellArray(world)
    where = Position(cell_id, Frame(Vector3(x, y, 0.0)))
    LandCell.add_all_outside_cells(where, [Sphere(Vector3(x, y, 1.0), radius)], cells)
    return cells.cell_ids()


def test_a_sphere_clear_of_its_cell_edges_names_its_cell_alone() -> None:
    # pt1 = x - 24·floor(x / 24) (acclient.c:355390); no neighbour while radius <= pt1 <= 24 - radius
    # (check_add_cell_boundary, acclient.c:355161-355187); the cell of column 1, row 0 is 8·1 + 0 + 1.
    assert cell_clear_of_edges(BLOCK | 0x01, 12.0, 12.0, 0.48) == BLOCK | 0x01
    assert cell_clear_of_edges(BLOCK | 0x01, 30.0, 12.0, 0.48) == BLOCK | 0x09
    assert cell_clear_of_edges(BLOCK | 0x01, 191.0, 190.0, 0.48) == BLOCK | 0x40
    radius = f32(0.48)
    max_rad = f32(24.0 - radius)
    low_x = _first_at_least(24.0 + radius)  # the first float32 x whose pt1 = x - 24 reaches radius
    high_y = _last_at_most(24.0 + max_rad)
    world = World()
    assert cell_clear_of_edges(BLOCK | 0x01, low_x, 12.0, radius) == BLOCK | 0x09
    assert _reference_cells(world, BLOCK | 0x01, low_x, 12.0, radius) == [BLOCK | 0x09]
    assert cell_clear_of_edges(BLOCK | 0x01, _below(low_x), 12.0, radius) == 0
    assert _reference_cells(world, BLOCK | 0x01, _below(low_x), 12.0, radius) == [BLOCK | 0x09, BLOCK | 0x01]
    assert cell_clear_of_edges(BLOCK | 0x01, 12.0, high_y, radius) == BLOCK | 0x02
    assert _reference_cells(world, BLOCK | 0x01, 12.0, high_y, radius) == [BLOCK | 0x02]
    assert cell_clear_of_edges(BLOCK | 0x01, 12.0, _above(high_y), radius) == 0
    assert _reference_cells(world, BLOCK | 0x01, 12.0, _above(high_y), radius) == [BLOCK | 0x02, BLOCK | 0x03]
    # not shortened: off the landblock, a point adjust_to_outside snaps to 0, no number, no land
    # cell, a landblock past the world's edge
    assert cell_clear_of_edges(BLOCK | 0x01, -12.0, 12.0, radius) == 0
    assert cell_clear_of_edges(BLOCK | 0x01, 200.0, 12.0, radius) == 0
    assert cell_clear_of_edges(BLOCK | 0x01, 1e-4, 12.0, 1e-5) == 0
    assert cell_clear_of_edges(BLOCK | 0x01, math.nan, 12.0, radius) == 0
    assert cell_clear_of_edges(BLOCK | 0x01, 12.0, 12.0, math.nan) == 0
    assert cell_clear_of_edges(BLOCK | 0x0100, 12.0, 12.0, radius) == 0
    assert cell_clear_of_edges(0xFFB40001, 12.0, 12.0, radius) == 0
    assert cell_clear_of_edges(0xA9FF0001, 12.0, 12.0, radius) == 0


def test_the_clear_cell_is_the_reference_cell_array_wherever_it_is_given() -> None:
    world = World()
    rng = random.Random(14)
    near = (-12.0, -2.0, -0.7, -0.48, -0.1, 0.0, 0.1, 0.48, 0.7, 2.0)
    edges = [24.0 * k + d for k in range(9) for d in near]

    def coordinate() -> float:  # half of them within a centimetre of an edge, a radius off one
        if rng.random() < 0.5:
            return f32(rng.choice(edges) + rng.uniform(-0.01, 0.01))
        return f32(rng.uniform(-5.0, 197.0))

    given = 0
    for _ in range(20_000):
        radius = f32(rng.choice(RADII))
        x, y = coordinate(), coordinate()
        cell_id = BLOCK | rng.randint(1, 64)
        clear = cell_clear_of_edges(cell_id, x, y, radius)
        if clear:
            given += 1
            assert _reference_cells(world, cell_id, x, y, radius) == [clear], (cell_id, x, y, radius)
    assert given > 5_000


def _first_at_least(value: float) -> float:
    """The least float32 not below ``value``."""
    nearest = f32(value)
    return nearest if nearest >= value else _above(nearest)


def _last_at_most(value: float) -> float:
    """The greatest float32 not above ``value``."""
    nearest = f32(value)
    return nearest if nearest <= value else _below(nearest)


def _above(value: float) -> float:
    return float(np.nextafter(np.float32(value), np.float32(math.inf)))


def _below(value: float) -> float:
    return float(np.nextafter(np.float32(value), np.float32(-math.inf)))
