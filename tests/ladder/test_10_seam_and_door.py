"""Ladder rung 10: across a landblock seam, through a doorway into a room and back; the cell id follows.

The body's cell is the one holding its sphere 0 centre (``CObjCell::find_cell_list``,
acclient.c:346960): the room's env cell 0xAAB40100 while the centre is inside the room's cell BSP
(x 3..9, y 105..111 in 0xAAB4), else the land cell ``1 + 8·cx + cy`` of the landblock the origin
is in (cell ids: acphys.math.cell_id, retail ``LandDefs``). Sphere 0 sits straight above the
origin, so its centre has the origin's x and y.
"""

from __future__ import annotations

import itertools

import pytest

import acphys
from acphys.precision import f32
from support import step_records, ulp32

ROOM = 0xAAB40100
WEST, EAST = 0xA9B4, 0xAAB4


def _expected_cell(landblock: int, x: float, y: float) -> int:
    if landblock == EAST and 3.0 < x < 9.0 and 105.0 < y < 111.0:
        return ROOM
    return (landblock << 16) | (1 + 8 * int(x // 24.0) + int(y // 24.0))


@pytest.fixture(scope="module")
def records(tmp_path_factory: pytest.TempPathFactory) -> list[dict]:
    sim = acphys.load_scenario("ladder-10-seam-and-door")
    trace = tmp_path_factory.mktemp("ladder10") / "walk.jsonl"
    sim.run(trace=trace)
    return step_records(trace)


def test_the_cell_id_follows_the_body(records: list[dict]) -> None:
    visited: list[int] = []
    for record in records:
        cell = int(record["cell"], 16)
        x, y, _ = record["origin"]
        # Positions are local to the landblock named by the cell: x stays in [0, 192).
        assert 0.0 <= x < 192.0
        assert cell == _expected_cell(cell >> 16, x, y), record
        if not visited or visited[-1] != cell:
            visited.append(cell)
    # Out of 0xA9B4's land cell (7, 4), across the seam into 0xAAB4's (0, 4), into the room,
    # and back the same way.
    assert visited == [0xA9B4003D, 0xAAB40005, ROOM, 0xAAB40005, 0xA9B4003D]


#: Two steps of the same gait differ by the rounding of their float32 stores: one spacing at each
#: end, at most 2⁻¹⁶ m near the seam (x up to 192).
STEP_TOL = 2 * ulp32(192.0)


def _global_x(record: dict) -> float:
    landblock = int(record["cell"], 16) >> 16
    return (landblock >> 8) * 192.0 + record["origin"][0]


def test_the_seam_and_the_doorway_do_not_hold_the_walker_up(records: list[dict]) -> None:
    # Running east from 0.5 s to 3.0 s: every step moves the same distance, across the seam
    # (step 30) and the doorway (step 52) alike; on a flat floor at the terrain's height the
    # walker never leaves the ground, never slides sideways and never changes height.
    moves = [_global_x(b) - _global_x(a) for a, b in itertools.pairwise(records)]
    running = moves[16:88]
    assert min(running) == pytest.approx(max(running), abs=STEP_TOL)
    assert running[0] > 0.1
    for record in records:
        assert record["origin"][1] == 108.0
        assert record["origin"][2] == f32(50.005)
        assert {"contact", "on_walkable"} <= set(record["transient"])
        assert "collision:environment" not in record["events"] or record["t"] < 0.05


def test_the_seam_crossing_keeps_the_global_position(records: list[dict]) -> None:
    # The walker's global x is continuous across the seam: the step that changes landblock
    # (landblock-local x wraps from ~192 to ~0 and back) moves it as far as a step of the same
    # gait elsewhere. Running east every step is the same; running backwards, root motion comes
    # per animation frame crossed, so steps take one of a few sizes.
    moves = [_global_x(b) - _global_x(a) for a, b in itertools.pairwise(records)]
    crossings = [
        i
        for i, (a, b) in enumerate(itertools.pairwise(records))
        if int(a["cell"], 16) >> 16 != int(b["cell"], 16) >> 16
    ]
    assert len(crossings) == 2
    east, west = crossings
    assert moves[east] == pytest.approx(moves[east - 1], abs=STEP_TOL)
    back_moves = [m for m in moves[100:] if m < 0.0 and abs(m - moves[west]) < STEP_TOL]
    assert moves[west] < 0.0 and len(back_moves) > 10
