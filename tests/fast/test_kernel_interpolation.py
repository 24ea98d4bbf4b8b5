"""Remote bodies gliding to the positions a server sends, in the kernel (issue 14).

A body whose position manager runs only its interpolation manager is covered: the kernel takes
each step's offset towards the head node (``InterpolationManager::adjust_offset``,
acclient.c:389177), completes nodes within 0.05 m (``NodeCompleted``, acclient.c:388881), stops
when the queue empties, and audits the glide every fifth step. A failed audit and a blip
(``UseTime``, acclient.c:389277) are the reference path's: the step is handed back whole. Every
case must run as on the reference engine byte for byte, and the managers must end in the same
state.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from numba import njit

from acphys.bench import _hill_heights
from acphys.fast.differential import compare_engines
from acphys.fast.kernels.frame import IDENTITY_M
from acphys.fast.kernels.interpolation import GIVE_UP
from acphys.fast.kernels.interpolation import adjust_offset as glide_offset
from acphys.fast.layout import BODY, INTERPOLATION
from acphys.flags import TransientState
from acphys.managers.interpolation import BIG_DISTANCE, InterpolationManager
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.scenario import build_scenario
from acphys.simulation import Simulation

pytestmark = pytest.mark.kernels

GIVEN_UP = "an interpolation node given up (a failed audit or a blip)"
BLOCK = 0x80800000
#: Remote bodies on hills: (name, centre x, y, radius of its circle, keep_heading).
GLIDERS = (("g0", 30.0, 30.0, 2.0, False), ("g1", 60.0, 40.0, 3.0, True), ("g2", 100.0, 90.0, 1.0, False))


def _on_ground(sim: Simulation, x: float, y: float) -> list[float]:
    """A server's position over the hills at ``(x, y)``: 5 mm above the ground."""
    ground = sim.world.ground_height(BLOCK | 1, Vector3(x, y, 0.0))
    assert ground is not None
    return [x, y, ground + 0.005]


def _gliders(
    engine: str, seconds: float = 4.0, edit: Callable[[dict[str, Any]], None] | None = None
) -> Simulation:
    """Three remote bodies sent nodes round circles ten times a second for two seconds (one keeping
    its heading, the nodes facing along the circle), then left to finish their queues, among
    walkers on hills; ``edit`` changes the scenario's document first."""
    bodies: list[dict[str, Any]] = [
        {"name": name, "landblock": "0x8080", "origin": [x + radius, y, 0.0], "on_ground": True}
        for name, x, y, radius, _ in GLIDERS
    ]
    events: list[dict[str, Any]] = []
    for i in range(12):
        name = f"w{i}"
        bodies.append(
            {"name": name, "landblock": "0x8080", "origin": [20.0 + 12.0 * i, 140.0, 0.0], "on_ground": True}
        )
        events.append({"at": 0.0, "body": name, "action": "motion", "motion": "WalkForward"})
        events.append({"at": 0.0, "body": name, "action": "motion", "motion": "TurnRight"})
    document: dict[str, Any] = {
        "scenario": {"name": "gliders", "duration": seconds, "driver_hz": 30.0},
        "landblock": [{"id": "0x8080", "heights": _hill_heights(0, 0)}],
        "body": bodies,
        "event": events,
    }
    if edit is not None:
        edit(document)
    sim = build_scenario(document, source="<gliders>", engine=engine)
    for name, x, y, radius, keep in GLIDERS:
        for k in range(1, 21):
            angle = 0.3 * k
            where = _on_ground(sim, x + radius * math.cos(angle), y + radius * math.sin(angle))
            sim.add_event(
                0.1 * k, name, "interpolate_to", origin=where, heading=math.degrees(angle), keep_heading=keep
            )
    return sim


def _manager(sim: Simulation, name: str) -> InterpolationManager | None:
    body = sim.body(name)
    return body.position_manager.interpolation_manager if body.position_manager is not None else None


def _state(manager: InterpolationManager | None) -> tuple[Any, ...]:
    """What an interpolation manager holds: its queue (cell, origin, rotation) and the audit."""
    if manager is None:
        return ()
    queue = [(node.objcell_id, *node.frame.origin, *node.frame.rotation) for node in manager.position_queue]
    counters = (manager.frame_counter, manager.node_fail_counter, manager.keep_heading)
    return (queue, *counters, manager.original_distance, manager.progress_quantum)


def _same_managers(load: Any, names: list[str], until: float) -> None:
    """Both engines' interpolation managers alike at ``until`` (the fast engine's written back)."""
    states = []
    for engine in ("reference", "fast"):
        sim = load(engine)
        sim.run(until=until)
        states.append([_state(_manager(sim, name)) for name in names])
    assert states[0] == states[1]


def test_gliders_glide_in_the_kernel_as_on_the_reference(tmp_path: Path) -> None:
    comparison = compare_engines(_gliders, tmp_path)
    assert comparison.identical, comparison.divergence
    # the gliders' steps run in the kernel: none is uncovered for its manager, few are handed back
    assert not any("manager" in reason for reason in comparison.reasons), comparison.reasons
    assert comparison.reference_steps <= 0.02 * (comparison.kernel_steps + comparison.reference_steps)
    names = [name for name, *_ in GLIDERS]
    for until in (0.75, 1.55, 2.2, 4.0):  # mid-glide (audits every fifth step), after the last node
        _same_managers(_gliders, names, until)


def test_a_glider_reaching_its_last_node_stops_interpolating() -> None:
    sim = _gliders("fast")
    sim.run()
    for name, *_ in GLIDERS:
        manager = _manager(sim, name)
        assert manager is not None and not manager.position_queue and manager.node_fail_counter == 0


def _blocked(engine: str) -> Simulation:
    """g0's last nodes lie inside a pillar: it pushes against the pillar, its audits fail (the
    reference path counts the failed nodes) until it blips; a fourth body is sent a node 150 m off (beyond the
    blip distance outdoors, 100 m): it blips at once."""

    pillar = _on_ground(_gliders("reference"), 26.0, 36.0)

    def edit(document: dict[str, Any]) -> None:
        document["setup"] = {"pillar": {"cylspheres": [{"low_pt": [0, 0, -1], "radius": 1.5, "height": 5.0}]}}
        document["object"] = [{"name": "pillar", "setup": "pillar", "landblock": "0x8080", "origin": pillar}]
        document["body"].append(
            {"name": "far", "landblock": "0x8080", "origin": [150.0, 20.0, 0.0], "on_ground": True}
        )

    sim = _gliders(engine, seconds=5.0, edit=edit)
    for k in range(1, 4):
        sim.add_event(2.0 + 0.1 * k, "g0", "interpolate_to", origin=_on_ground(sim, 26.0, 36.0 + 0.1 * k))
    sim.add_event(0.5, "far", "interpolate_to", origin=_on_ground(sim, 150.0, 170.0))
    return sim


def test_failed_audits_and_blips_are_handed_back(tmp_path: Path) -> None:
    comparison = compare_engines(_blocked, tmp_path)
    assert comparison.identical, comparison.divergence
    assert comparison.reasons.get(GIVEN_UP, 0) >= 2, comparison.reasons
    _same_managers(_blocked, ["g0", "far"], 5.0)


# -- the kernel's adjust_offset, by hand ---------------------------------------------------------


@njit(cache=False)
def _adjust(bodies: np.ndarray, glides: np.ndarray, quantum: float) -> tuple[Any, ...]:
    return glide_offset(bodies[0], glides[0], quantum, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), IDENTITY_M)


def _glider_at(
    x: float, y: float, node: tuple[float, float], max_speed: float
) -> tuple[np.ndarray, np.ndarray]:
    """An upright body in contact at ``(x, y, 0)`` of cell 0x80800001 with one node, facing north."""
    bodies = np.zeros(1, dtype=BODY)
    bodies["cell_id"] = BLOCK | 1
    bodies["origin"] = (x, y, 0.0)
    bodies["q"] = (1.0, 0.0, 0.0, 0.0)
    bodies["m"] = IDENTITY_M
    bodies["transient"] = int(TransientState.CONTACT)
    glides = np.zeros(1, dtype=INTERPOLATION)
    glides["loaded"] = glides["num_nodes"] = 1
    glides["node_cell_id"][0, 0] = BLOCK | 1
    glides["node_origin"][0, 0] = (*node, 0.0)
    glides["node_q"][0, 0] = (1.0, 0.0, 0.0, 0.0)
    glides["node_m"][0, 0] = IDENTITY_M
    glides["max_speed"] = max_speed
    glides["original_distance"] = BIG_DISTANCE
    return bodies, glides


def test_a_glide_step_is_cut_to_twice_the_adjusted_speed() -> None:
    # A node 5 m off (3, 4): no audit on the first step (frame_counter 1 < 5, acclient.c:389244);
    # the adjustment is the node's origin seen from the body (Position::subtract2, acclient.c:388972),
    # (3, 4, 0) with the identity rotation; max_step = float(2 * 3 * dt) (acclient.c:389255); the
    # origin is scaled by the float max_step / 5 (acclient.c:389262), each product a float store.
    quantum = f32(1.0 / 30.0)
    bodies, glides = _glider_at(10.0, 10.0, (13.0, 14.0), 3.0)
    status, origin, q, _ = _adjust(bodies, glides, quantum)
    max_step = f32(f32(3.0 * 2.0) * quantum)
    scale = f32(max_step / 5.0)
    assert status == 0
    assert origin == (f32(3.0 * scale), f32(4.0 * scale), 0.0)
    assert q == (1.0, 0.0, 0.0, 0.0)
    row = glides[0]
    assert (row["frame_counter"], row["progress_quantum"], row["num_nodes"]) == (1, quantum, 1)


def test_the_fifth_step_audits_the_glide() -> None:
    quantum = f32(1.0 / 30.0)
    # closing 0.5 m in 5/30 s at 6 m/s: 0.5 / (5/30) / 6 = 0.5 >= 0.3 (acclient.c:389248): the
    # audit restarts at the current distance (acclient.c:389250-389253) and the glide goes on
    bodies, glides = _glider_at(10.0, 10.0, (13.0, 14.0), 3.0)
    glides["frame_counter"] = 4
    glides["progress_quantum"] = f32(4.0 * quantum)
    glides["original_distance"] = 5.5
    status, origin, _, _ = _adjust(bodies, glides, quantum)
    assert status == 0 and origin != (0.0, 0.0, 0.0)
    row = glides[0]
    assert (row["frame_counter"], row["progress_quantum"], row["original_distance"]) == (0, 0.0, 5.0)
    # closing 1 cm: the audit fails 5 m from the node (not within 0.2, acclient.c:389270): the
    # node fails, which the kernel leaves to the reference path (GIVE_UP, the row unchanged)
    bodies, glides = _glider_at(10.0, 10.0, (13.0, 14.0), 3.0)
    glides["frame_counter"] = 4
    glides["progress_quantum"] = f32(4.0 * quantum)
    glides["original_distance"] = 5.01
    status, origin, _, _ = _adjust(bodies, glides, quantum)
    assert status == GIVE_UP and origin == (0.0, 0.0, 0.0)
    assert (glides[0]["frame_counter"], glides[0]["num_nodes"]) == (4, 1)


def test_a_node_within_five_centimetres_completes_and_ends_the_glide() -> None:
    # distance 0.04 < 0.05 (acclient.c:389215): NodeCompleted(1) pops it; the queue empty, the
    # manager stops interpolating (acclient.c:388881-388910) and the offset is left as it was
    bodies, glides = _glider_at(10.0, 10.0, (10.0, 10.04), 3.0)
    glides["node_fail_counter"] = 2
    status, origin, _, _ = _adjust(bodies, glides, f32(1.0 / 30.0))
    row = glides[0]
    assert status == 0 and origin == (0.0, 0.0, 0.0)
    assert (row["num_nodes"], row["node_fail_counter"], row["original_distance"]) == (0, 0, BIG_DISTANCE)
