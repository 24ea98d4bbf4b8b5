"""Bodies of no spheres and bodies that face along their path, in the kernel (issue 14).

``CPhysicsObj::UpdateObjectInternal`` (acclient.c:322718) sweeps only a body with spheres: one
with none keeps its origin and takes its new rotation (and, with no movement manager, on walkable
ground, goes inactive); before a sweep, an ``ALIGN_PATH`` body turns to face along its step
(``Frame::set_vector_heading`` of the normalised offset, acclient.c:357667). The kernel covers both;
their runs stay the reference's byte for byte, none of their steps on the reference path.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from acphys.fast.differential import compare_engines
from acphys.scenario import parse_scenario
from acphys.simulation import Simulation

pytestmark = pytest.mark.kernels

SCENARIO = """
[scenario]
name = "markers-and-aligners"
duration = 4.0
driver_hz = 30.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[setup.marker]
spheres = []

[setup.dart]
spheres = [{ center = [0.0, 0.0, 0.2], radius = 0.2 }]

[[body]]
name = "spinning-marker"    # no spheres, turning, drifting: keeps its origin
setup = "marker"
landblock = "0xA9B4"
origin = [40.0, 40.0, 51.0]
omega = [0.0, 0.0, 60.0]
velocity = [1.0, 0.5, 0.0]

[[body]]
name = "falling-marker"     # no spheres under gravity: its velocity grows, its origin stays
setup = "marker"
landblock = "0xA9B4"
origin = [60.0, 40.0, 55.0]
state = ["gravity"]

[[body]]
name = "arrow"              # faces along a falling arc, lands and slides
setup = "dart"
landblock = "0xA9B4"
origin = [80.0, 40.0, 52.0]
state = ["gravity", "align_path"]
velocity = [4.0, 3.0, 5.0]

[[body]]
name = "curving-arrow"      # faces along a path its spin does not turn (grotate turns the frame)
setup = "dart"
landblock = "0xA9B4"
origin = [100.0, 60.0, 53.0]
state = ["align_path"]
velocity = [-2.0, 1.0, 0.0]
omega = [0.0, 0.0, 45.0]

[[event]]
at = 1.5
body = "curving-arrow"
action = "set_velocity"
velocity = [1.0, 2.0, 0.0]
"""


def _load(engine: str) -> Simulation:
    return parse_scenario(SCENARIO, source="<markers and aligners>", engine=engine)


def test_markers_and_aligners_run_in_the_kernel_as_on_the_reference(tmp_path: Path) -> None:
    comparison = compare_engines(_load, tmp_path)
    assert comparison.identical, comparison.divergence
    assert comparison.reference_steps == 0, comparison.reasons
    assert comparison.kernel_steps >= 4 * 100  # the four bodies, though a marker may go inactive


def test_an_arrow_faces_along_its_path() -> None:
    sim = _load("fast")
    sim.run(until=0.3)
    arrow = sim.body("arrow")
    facing = arrow.position.frame.get_vector_heading()
    velocity = arrow.velocity
    # Frame::set_vector_heading: yaw from the step's bearing, pitch from its z (acclient.c:357667)
    assert facing.x * velocity.x + facing.y * velocity.y > 0.0
    assert abs(facing.x * velocity.y - facing.y * velocity.x) < 0.05 * (velocity.x**2 + velocity.y**2)
