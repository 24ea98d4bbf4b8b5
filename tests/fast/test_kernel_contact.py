"""The kernel's sphere-sphere contact (:mod:`acphys.fast.kernels.contact`) against the reference.

Bodies that meet take their steps in the kernel once they know each other: the first touch
reports to both bodies and is the reference path's, as are the ends of the records; every step
in between, sliding off the other body (``CSphere::slide_sphere``, acclient.c:358708 and
358898) and stamping its collision record (``CPhysicsObj::track_object_collision``,
acclient.c:321216), is the kernel's, and the traces are identical byte for byte.
"""

from __future__ import annotations

from pathlib import Path

from acphys.fast.differential import compare_engines
from acphys.fast.kernels.cells import BAIL_REASONS, R_CLIMB, R_CONTACT, R_RECORDS
from acphys.scenario import parse_scenario


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
    assert result.reference_steps < 0.03 * result.kernel_steps  # first touches, endings, climbs


def test_the_first_touch_is_the_reference_paths() -> None:
    """What the kernel hands back in a meeting: a first touch (reported to both bodies), a record
    ending, and the climbs it leaves (a taller body's sphere 0 meeting a lower one it can step
    onto); nothing else."""
    sim = parse_scenario(MEETINGS, "<meetings>", engine="fast")
    sim.run()
    reasons = sim.physics.counts.reasons
    allowed = {
        BAIL_REASONS[R_CONTACT],
        BAIL_REASONS[R_RECORDS],
        BAIL_REASONS[R_CLIMB],
        "a motion waiting to complete",
    }
    assert set(reasons) <= allowed, reasons
    assert reasons[BAIL_REASONS[R_CONTACT]] >= 6  # each pair's first touch, and the row's
