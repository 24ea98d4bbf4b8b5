"""The kernel's sphere-sphere contact (:mod:`acphys.fast.kernels.contact`) against the reference.

Bodies that meet take their steps in the kernel: the first touch (a new collision record, a
report to both bodies), every step after it, sliding off the other body (``CSphere::slide_sphere``,
acclient.c:358708 and 358898) and stamping its record (``CPhysicsObj::track_object_collision``,
acclient.c:321216); the ends of the records (reported to both) are the reference path's. The
traces are identical byte for byte.
"""

from __future__ import annotations

from pathlib import Path

from acphys.fast.differential import compare_engines
from acphys.fast.kernels.cells import BAIL_REASONS, R_CLIMB, R_RECORDS
from acphys.scenario import parse_scenario
from acphys.trace import read_trace


def _human(name: str, x: float, y: float, heading: float, scale: float = 1.0) -> str:
    return (
        f'[[body]]\nname = "{name}"\nlandblock = "0xA9B4"\non_ground = true\nheading = {heading}\n'
        f"origin = [{x}, {y}, 50.0]\nscale = {scale}\n"
    )


def _walk(name: str, motion: str = "WalkForward") -> str:
    return f'[[event]]\nat = 0.0\nbody = "{name}"\naction = "motion"\nmotion = "{motion}"\n'


MEETINGS = (
    '[scenario]\nname = "meetings"\nduration = 4.0\ndriver_hz = 30.0\n'
    '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
    + _human("head-on-a", 40, 40, 0)
    + _human("head-on-b", 40, 43, 180)
    + _human("sideways", 80, 40, 15)
    + "".join(_human(f"row-{n}", 81.0, 42.0 + n, 90) for n in range(6))
    + _human("tall", 120, 40, 0, 1.6)
    + _human("runner", 120.3, 42.5, 180)
    + _walk("head-on-a")
    + _walk("head-on-b")
    + _walk("sideways")
    + _walk("tall")
    + _walk("runner", "RunForward")
)


def test_bodies_pushing_into_each_other_slide_in_the_kernel(tmp_path: Path) -> None:
    """Two humans walking into each other head on (held there, pushing, for over three seconds),
    one sliding along a row of six standers, and a tall one into a runner: the kernel's."""
    result = compare_engines(lambda engine: parse_scenario(MEETINGS, "<meetings>", engine=engine), tmp_path)
    assert result.identical, result.divergence
    assert result.touching >= 10  # pressing into the row, slid off one stander after another
    assert result.reference_steps < 0.02 * result.kernel_steps  # climbs, a motion waiting


def test_first_touches_are_reported_in_the_kernel(tmp_path: Path) -> None:
    """A first touch gives each body a ``collision:NAME`` event (``report_object_collision``,
    acclient.c:320227): the kernel logs them and the engine names them in the trace, the mover's in
    its own row and the other's in that body's next. What the kernel hands back in a meeting: the
    climbs it leaves (a taller body's sphere 0 meeting a lower one it can step onto) and a motion
    waiting at the start; nothing else."""
    result = compare_engines(lambda engine: parse_scenario(MEETINGS, "<meetings>", engine=engine), tmp_path)
    assert result.identical, result.divergence
    reports = [
        event
        for _, record in read_trace(tmp_path / "fast.jsonl")
        for event in record["events"]
        if event.startswith("collision:") and event != "collision:environment"
    ]
    assert len(reports) >= 12  # each pair's first touch, and the row's, heard on both sides
    sim = parse_scenario(MEETINGS, "<meetings>", engine="fast")
    sim.run()
    reasons = sim.physics.counts.reasons
    allowed = {BAIL_REASONS[R_CLIMB], "a motion waiting to complete"}
    assert set(reasons) <= allowed, reasons


def test_record_ends_are_reported_in_the_kernel(tmp_path: Path) -> None:
    """A record untouched for over a second ends (``report_collision_end``, acclient.c:321712):
    the kernel drops it and both bodies hear ``collision_end:NAME``
    (``report_object_collision_end``, acclient.c:317868), in the table's order. The slider leaves
    the standers of the row behind one after another, each end heard by both."""
    result = compare_engines(lambda engine: parse_scenario(MEETINGS, "<meetings>", engine=engine), tmp_path)
    assert result.identical, result.divergence
    ends = [
        (record["body"], event)
        for _, record in read_trace(tmp_path / "fast.jsonl")
        for event in record["events"]
        if event.startswith("collision_end:")
    ]
    assert len(ends) >= 4, ends  # two at least, each heard on both sides
    assert ("sideways", "collision_end:row-0") in ends and ("row-0", "collision_end:sideways") in ends
    sim = parse_scenario(MEETINGS, "<meetings>", engine="fast")
    sim.run()
    assert BAIL_REASONS[R_RECORDS] not in sim.physics.counts.reasons


def test_reports_reach_the_objects_without_a_trace() -> None:
    """Untraced, a report of another body's step waits in the receiver's ``step_events`` as on the
    reference engine: after every driver tick, every body's pending events and position agree."""
    sims = {engine: parse_scenario(MEETINGS, "<meetings>", engine=engine) for engine in ("reference", "fast")}
    pending = 0
    while sims["reference"].world.cur_time < 4.0:
        state = {}
        for engine, sim in sims.items():
            sim.step()
            state[engine] = [
                (b.name, list(b.step_events), tuple(b.position.frame.origin)) for b in sim.bodies
            ]
        assert state["reference"] == state["fast"], f"at {sims['reference'].world.cur_time}"
        pending += sum(1 for _, events, _ in state["fast"] if events)
    assert pending > 0  # some reports were waiting for their receivers' steps at a tick's end
