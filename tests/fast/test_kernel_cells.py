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
from pathlib import Path

from acphys.fast.differential import compare_engines
from acphys.scenario import parse_scenario
from acphys.trace import read_trace

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
