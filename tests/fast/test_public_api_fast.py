"""The public API on the fast engine (issue 15): bodies and events added to a running simulation,
and step and collision callbacks, give the reference engine's trace byte for byte."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.fast.differential import same_run


def _drive(engine: str, folder: Path, callbacks: str = "") -> tuple[list[Path], Any, list[Any]]:
    """The default scenario to 1 s, then a thrown ball and a walker added, events added, to 4 s;
    ``callbacks``: "step", "collision" or "both"."""
    sim = acphys.load_scenario(engine=engine)
    seen: list[Any] = []
    if callbacks in ("step", "both"):
        sim.on_step(lambda body, quantum: seen.append(("step", body.name, quantum, list(body.step_events))))
    if callbacks in ("collision", "both"):
        sim.on_collision(lambda body, report: seen.append(("hit", body.name, report.kind.value)))
    first, second = folder / f"{engine}-1.jsonl", folder / f"{engine}-2.jsonl"
    sim.run(until=1.0, trace=first)
    sim.add_body(
        name="thrown",
        setup="ball",
        landblock="0xA9B4",
        origin=[88.0, 64.0, 51.0],
        state=["gravity", "report_collisions"],
        velocity=[-8.0, 0.0, 2.0],
    )
    sim.add_body(name="late", landblock="0xA9B4", origin=[140.0, 60.0, 50.0], on_ground=True)
    sim.add_event(1.5, "late", "motion", motion="WalkForward", hold_run=True)
    sim.add_event(2.5, "late", "jump")
    sim.add_event(3.0, "runner", "stop_motion", motion="WalkForward")
    sim.run(until=4.0, trace=second)
    arrays = sim.arrays()
    return [first, second], (sim, arrays), seen


def test_bodies_and_events_added_while_running_agree(tmp_path: Path) -> None:
    ref_traces, (_, ref_arrays), _ = _drive("reference", tmp_path, callbacks="")
    fast_traces, (fast_sim, fast_arrays), _ = _drive("fast", tmp_path, callbacks="")
    for a, b in zip(ref_traces, fast_traces, strict=True):
        assert same_run(a, b), f"{a.name} and {b.name} differ"
    assert fast_sim.physics.counts.kernel > 0, "the kernel stepped the added bodies' neighbours"
    assert ref_arrays.names == fast_arrays.names
    assert (ref_arrays.positions == fast_arrays.positions).all()
    assert (ref_arrays.velocities == fast_arrays.velocities).all()


@pytest.mark.parametrize("callbacks", ["step", "both"])
def test_callbacks_agree_and_run_on_the_reference_path(callbacks: str, tmp_path: Path) -> None:
    ref_traces, _, ref_seen = _drive("reference", tmp_path, callbacks)
    fast_traces, (fast_sim, _), fast_seen = _drive("fast", tmp_path, callbacks)
    for a, b in zip(ref_traces, fast_traces, strict=True):
        assert same_run(a, b), f"{a.name} and {b.name} differ"
    assert ref_seen == fast_seen
    assert len([entry for entry in fast_seen if entry[0] == "step"]) == 7 * 30 + 9 * 90
    counts = fast_sim.physics.counts
    assert counts.kernel == 0, "every body has a callback: none is the kernel's"
    reason = "a step callback" if callbacks == "step" else "a weenie or a collision callback"
    assert counts.reasons.get(reason, 0) > 0, counts.reasons
    if callbacks == "both":
        assert any(entry[0] == "hit" for entry in fast_seen)


def test_the_kernel_takes_the_bodies_back_when_their_callbacks_go() -> None:
    sim = acphys.load_scenario(engine="fast")
    steps: list[str] = []

    def count(body: acphys.PhysicsObj, _quantum: float) -> None:
        steps.append(body.name)

    sim.on_step(count)
    sim.run(until=1.0)
    counts = sim.physics.counts
    assert counts.kernel == 0 and len(steps) == 7 * 30
    sim.remove_callback(count)
    sim.run(until=2.0)
    assert counts.kernel > 0 and len(steps) == 7 * 30
