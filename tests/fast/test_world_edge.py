"""Bodies at the edge of the loaded world stay in the kernel: the world makes up land cells
without terrain past its landblocks (``World.get_cell``), and the engine reads their landblocks
into the kernel's arrays when a body first reaches one (``UNREAD``), so the step runs again in
the kernel instead of on the reference path, and every step after it too."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from acphys.fast.differential import compare_engines
from acphys.fast.world_arrays import BLOCK_CELLS, build_world_arrays
from acphys.scenario import parse_scenario
from acphys.simulation import Simulation
from acphys.world.land_cell import LandCell

#: One flat landblock and, heading out of it: a walker west (it stops a few centimetres short
#: of the edge, where the reference's sweep leaves it), a walker south-west into the corner, a
#: runner north over the edge, and a ball thrown east over the edge, falling where there is no
#: ground.
EDGE = """
[scenario]
name = "edge"
duration = 5.0
driver_hz = 30.0
[[landblock]]
id = "0x8080"
height = 50.0
[setup.ball]
spheres = [{ center = [0, 0, 0.2], radius = 0.2 }]
[[body]]
name = "west"
landblock = "0x8080"
origin = [3.0, 45.0, 50.0]
heading = 270.0
on_ground = true
[[body]]
name = "corner"
landblock = "0x8080"
origin = [4.0, 4.0, 50.0]
heading = 225.0
on_ground = true
[[body]]
name = "north"
landblock = "0x8080"
origin = [100.0, 186.0, 50.0]
heading = 0.0
on_ground = true
[[body]]
name = "ball"
setup = "ball"
landblock = "0x8080"
origin = [189.0, 100.0, 51.0]
state = ["gravity"]
velocity = [4.0, 0.0, 3.0]
[[event]]
at = 0.0
body = "west"
action = "motion"
motion = "WalkForward"
[[event]]
at = 0.0
body = "corner"
action = "motion"
motion = "WalkForward"
[[event]]
at = 0.0
body = "north"
action = "motion"
motion = "WalkForward"
hold_run = true
"""


def _edge(engine: str) -> Simulation:
    return parse_scenario(EDGE, "<edge>", engine=engine)


def test_bodies_past_the_edge_stay_in_the_kernel(tmp_path: Path) -> None:
    result = compare_engines(_edge, tmp_path)
    assert result.identical, result.divergence
    assert result.reference_steps == 0, result.reasons
    assert result.kernel_steps == 4 * 5 * 30


def test_the_landblocks_past_the_edge_are_read_when_reached() -> None:
    sim = _edge("fast")
    sim.run()
    arrays = sim.physics.world_arrays
    known = {int(key) for key in np.flatnonzero(arrays.landblock_index >= 0)}
    # the corner walker's three neighbours, the north runner's and the ball's; the west walker's
    # sweep also re-homes a check position into 0x7F80 and asks for its western neighbour
    assert {0x7F80, 0x7F7F, 0x807F, 0x8081, 0x8180} <= known
    for key in known - {0x8080}:
        b = int(arrays.landblock_index[key])
        cells = arrays.land_cells[BLOCK_CELLS * b : BLOCK_CELLS * (b + 1)]
        assert [cell.id for cell in cells] == [(key << 16) | low for low in range(1, BLOCK_CELLS + 1)]
        assert all(cell is sim.world.get_cell(cell.id) and not cell.polygons for cell in cells)
        records = arrays.cells[BLOCK_CELLS * b : BLOCK_CELLS * (b + 1)]
        assert records["num_polys"].tolist() == [0] * BLOCK_CELLS
        assert records["cell_id"].tolist() == [cell.id for cell in cells]


def test_reading_a_landblock_keeps_the_cells_known_and_lists_its_shadows() -> None:
    """``add_landblocks`` puts the new cells after the others (indices given stay) with the shadow
    lists of the world's cells, bodies by their number and other objects as ``-1 - k``."""
    sim = _edge("reference")
    sim.run()  # the bodies now shadow into cells past the edge
    bodies = sim.bodies
    arrays = build_world_arrays(sim.world, bodies)
    before = arrays.cells.copy()
    index = {id(body): i for i, body in enumerate(bodies)}
    void = [sim.world.get_cell(0x7F800000 | low) for low in range(1, BLOCK_CELLS + 1)]
    assert all(isinstance(cell, LandCell) for cell in void)
    arrays.add_landblocks([(void, 0)], index)
    assert arrays.cells[: len(before)].tobytes() == before.tobytes()
    assert arrays.cell_index(0x7F80003A) == len(before) + 0x3A - 1
    listed = 0
    for cell in void:
        k = arrays.cell_index(cell.id)
        want = [index[id(shadow.physobj)] for shadow in cell.shadow_objects]
        assert arrays.shadow_list(k).tolist() == want
        listed += len(want)
    assert listed > 0  # the west walker's shadow, at least
