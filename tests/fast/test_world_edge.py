"""Bodies at the edge of the loaded world stay in the kernel: the world makes up land cells
without terrain past its landblocks (``World.get_cell``), and the engine reads their landblocks
into the kernel's arrays when a body first reaches one (``UNREAD``), so the step runs again in
the kernel instead of on the reference path, and every step after it too."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from acphys.fast.differential import compare_engines, same_run
from acphys.fast.world_arrays import BLOCK_CELLS, build_world_arrays
from acphys.scenario import parse_scenario
from acphys.simulation import Simulation
from acphys.world.land_cell import LandCell

#: One flat landblock and, heading out of it: a walker west (it stops a few centimetres short
#: of the edge, where the reference's sweep leaves it), a walker south-west into the corner, a
#: runner north over the edge, a ball thrown east over the edge, falling where there is no
#: ground, and a ball falling there from the start.
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
[[body]]
name = "beyond"
setup = "ball"
landblock = "0x8180"
origin = [10.0, 20.0, 60.0]
state = ["gravity"]
velocity = [1.0, 0.0, 0.0]
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
    """Every step of the five bodies in the kernel, the traces the reference's."""
    result = compare_engines(_edge, tmp_path)
    assert result.identical, result.divergence
    assert result.reference_steps == 0, result.reasons
    assert result.kernel_steps == 5 * 5 * 30


def test_the_landblocks_past_the_edge_are_read_when_reached() -> None:
    """The landblocks read are the world's terrain-less stand-ins, all 64 cells of each in order."""
    sim = _edge("fast")
    sim.run()
    arrays = sim.physics.world_arrays
    known = {int(key) for key in np.flatnonzero(arrays.landblock_index >= 0)}
    # the corner walker's three neighbours, the north runner's and the ball's; the west walker's
    # sweep also re-homes a check position into 0x7F80 and asks for its western neighbour
    assert {0x7F80, 0x7F7F, 0x807F, 0x8081, 0x8180} <= known
    assert arrays.void_blocks == known - {0x8080}
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


def test_a_landblock_loaded_where_the_kernel_read_none() -> None:
    """A server loads the landblock a walker stands at the edge of: the kernel's arrays, which
    held terrain-less cells there, are made again, the walker (still shadowed in the world's old
    stand-ins for those cells) takes one step on the reference path, and both engines walk it on
    into the new landblock, step for step."""
    sims = {engine: _edge(engine) for engine in ("reference", "fast")}
    crossed = False
    for tick in range(120):
        for sim in sims.values():
            if tick == 45:  # the west walker has stood at the edge for a second
                sim.world.set_flat_ground(0x7F80, 50.0)
            sim.step()
        states = [sim.physics.body_arrays(sim.bodies) for sim in sims.values()]
        for name in ("cell_ids", "origins", "orientations", "velocities", "transient_states"):
            want, got = (getattr(state, name) for state in states)
            assert np.array_equal(want, got), (tick, name, want, got)
        crossed |= int(states[1].cell_ids[0]) >> 16 == 0x7F80
    fast = sims["fast"].physics
    assert crossed
    assert 0x7F80 not in fast.world_arrays.void_blocks
    assert fast.counts.reasons == {"shadows in cells the kernel does not know": 1}


def test_a_landblock_loaded_renumbers_the_cells() -> None:
    """Loading a landblock the arrays held as stand-ins makes the arrays again, landblocks in id
    order, so the cells' indices change (and the transition's remembered cell list, of the old
    indices, is dropped): a walker pressing into a stander in the middle of the landblock and a
    body standing at the edge go on as on the reference engine, shadows, lists and all."""
    text = EDGE[: EDGE.index("[setup.ball]")]
    for name, x in (("edge", 0.3), ("pusher", 98.0), ("stander", 100.0)):
        text += f'[[body]]\nname = "{name}"\nlandblock = "0x8080"\norigin = [{x}, 45.0, 50.0]\n'
        text += "on_ground = true\nheading = 90.0\n"
    text += '[[event]]\nat = 0.0\nbody = "pusher"\naction = "motion"\nmotion = "WalkForward"\n'
    sims = {engine: parse_scenario(text, "<pushers>", engine=engine) for engine in ("reference", "fast")}
    for tick in range(60):
        for sim in sims.values():
            if tick == 40:
                sim.world.set_flat_ground(0x7F80, 50.0)
            sim.step()
    lists = []
    for sim in sims.values():
        for body in sim.bodies:
            for shadow in body.shadow_objects:
                names = [s.physobj.name for s in shadow.cell.shadow_objects]
                lists.append((body.name, shadow.cell_id, body.position.frame.origin.x, names))
    half = len(lists) // 2
    assert lists[:half] == lists[half:]
    assert ("pusher", 0x80800022) in [entry[:2] for entry in lists]


def test_a_landblock_added_between_runs_replaces_its_stand_in(tmp_path: Path) -> None:
    """Two landblocks the bodies reached are added to the world after 2 s (the runner's to the
    north, the falling balls' to the east, flat at the ground's height): the fast engine makes its
    arrays again over them (the stand-ins were void), the balls land there as on the reference
    engine, and both runs' traces are the reference's. Adding a landblock no body reached leaves
    the arrays as they are."""
    runs = {}
    for engine in ("reference", "fast"):
        sim = _edge(engine)
        sim.run(until=2.0, trace=tmp_path / f"{engine}-before.jsonl")
        if engine == "fast":
            arrays = sim.physics.world_arrays
            assert {0x8081, 0x8180} <= arrays.void_blocks
            sim.world.set_flat_ground(0x9090, 50.0)  # far from every body: nothing to make again
            sim.step()
            assert sim.physics.world_arrays is arrays
        else:
            sim.step()
        sim.world.set_flat_ground(0x8081, 50.0)
        sim.world.set_flat_ground(0x8180, 50.0)
        sim.run(trace=tmp_path / f"{engine}-after.jsonl")
        runs[engine] = sim
    for part in ("before", "after"):
        assert same_run(tmp_path / f"reference-{part}.jsonl", tmp_path / f"fast-{part}.jsonl"), part
    arrays = runs["fast"].physics.world_arrays
    assert not {0x8081, 0x8180} & arrays.void_blocks
    b = int(arrays.landblock_index[0x8180])
    assert arrays.cells[BLOCK_CELLS * b : BLOCK_CELLS * (b + 1)]["num_polys"].tolist() == [2] * BLOCK_CELLS
    beyond = next(body for body in runs["fast"].bodies if body.name == "beyond")
    assert beyond.position.frame.origin.z == pytest.approx(50.0, abs=0.5)  # landed on the new ground
    # the bodies standing in (or shadowed into) a stand-in cell take one step on the reference
    # path, which moves them into the landblock's own cells (coverage.uncovered_reason)
    counts = runs["fast"].physics.counts
    assert set(counts.reasons) <= {"not in a known land cell", "shadows in cells the kernel does not know"}
    assert counts.reference <= 3 and counts.kernel >= 5 * 5 * 30 - 3
