"""``acphys bench``: the suite runs its workloads and reports rates and ratios (never checks a time)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from acphys.bench import LANDBLOCK_RATE, WORKLOADS, run_suite
from acphys.cli import main
from acphys.flags import TransientState
from acphys.world.env_cell import EnvCell
from support import walk_tolerance


def test_the_suite_reports_every_workload_against_the_baseline() -> None:
    results = run_suite(bodies=4, seconds=0.5)
    assert [r.workload for r in results] == ["baseline", *WORKLOADS]
    baseline = results[0]
    assert baseline.vs_baseline == 1.0
    for result in results:
        assert result.body_steps > 0 and result.seconds > 0.0
        assert result.steps_per_s == pytest.approx(result.body_steps / result.seconds)
        assert result.vs_baseline == pytest.approx(result.steps_per_s / baseline.steps_per_s)
        assert result.vs_realtime == pytest.approx(result.steps_per_s / LANDBLOCK_RATE)
    # 4 walkers stay active: one step per body per 1/30 s at a 30-Hz driver, the first tick's untimed.
    walkers = next(r for r in results if r.workload == "walkers")
    assert walkers.body_steps == 4 * 14


@pytest.mark.kernels
def test_both_engines_take_the_same_steps_and_the_fast_row_says_how() -> None:
    """With both engines each workload is measured on each; the fast engine's row gives its rate
    over the reference's in the same run, its compile time, fallback share, memory per body and
    the time its write-back took after the stepping."""
    results = run_suite(bodies=6, seconds=0.5, engine="both", workloads=["fallers", "hills"])
    assert [(r.workload, r.engine) for r in results] == [
        ("baseline", "python"),
        ("fallers", "reference"),
        ("fallers", "fast"),
        ("hills", "reference"),
        ("hills", "fast"),
    ]
    for reference, fast in ((results[1], results[2]), (results[3], results[4])):
        assert fast.body_steps == reference.body_steps > 0
        assert fast.fast_vs_reference == pytest.approx(fast.steps_per_s / reference.steps_per_s)
        assert fast.compile_seconds is not None and fast.compile_seconds > 0.0
        assert 0.0 <= fast.fallback_share < 1.0
        assert sum(fast.fallback_reasons.values()) <= fast.body_steps
        assert fast.memory_per_body is not None and fast.memory_per_body > 0.0
        # the records written back into the objects after the last tick, timed apart from stepping
        assert fast.write_back_seconds > 0.0
        assert reference.fast_vs_reference is None and reference.fallback_share is None


@pytest.mark.kernels
def test_the_hills_walkers_circle_on_their_own_ground() -> None:
    """Every hills walker circles within its own 8-m square: nobody meets anybody, so the fast
    engine covers every step (the AnimDone that ends each walker's start-up link pauses its step
    for the reference path's hooks, and the kernel finishes it)."""
    sim = WORKLOADS["hills"][1](30, 3.0, "fast")
    start = {body.name: body.position.frame.origin.copy() for body in sim.bodies}
    sim.run()
    for body in sim.bodies:
        offset = body.position.frame.origin - start[body.name]
        assert 0.1 < (offset.x**2 + offset.y**2) ** 0.5 < 4.0, body.name
        assert body.transient_state & TransientState.ON_WALKABLE
    counts = sim.physics.counts
    assert counts.reasons == {}
    assert counts.reference == 0 and counts.kernel == 30 * 90


def test_the_walkers_actually_walk() -> None:
    sim = WORKLOADS["walkers"][1](2, 1.0)
    sim.run()
    moved = [body.position.frame.origin.y - 20.0 for body in sim.bodies]
    assert all(distance > 2.0 for distance in moved)
    assert all(body.velocity.is_zero() for body in sim.bodies)


def test_the_crowd_walks_into_itself() -> None:
    # Columns 1.5 m apart walk north and east by turns at 3.12 m/s: unhindered, each body would
    # walk 6.24 m in 2 s; the east walkers run into the north walkers' paths and are held short.
    sim = WORKLOADS["crowd"][1](16, 2.0)
    start = {body.name: body.position.frame.origin.copy() for body in sim.bodies}
    sim.run()
    walked = [(body.position.frame.origin - start[body.name]).length() for body in sim.bodies]
    # (60 float32 position stores near 85 m: each 0.104-m step rounds the same way there)
    assert max(walked) == pytest.approx(6.24, abs=walk_tolerance(86.0, 60))
    assert sum(distance < 5.7 for distance in walked) >= 4


def test_the_mixed_workload_takes_a_landblock_for_each_hundred_bodies() -> None:
    # 100 bodies a landblock (25 of each kind), each landblock with its house and pillars: 250
    # bodies stand on three landblocks, nobody where another stands. (One landblock for all of
    # them stacked the house walkers five deep, and the fifth's drop found no ground.)
    sim = WORKLOADS["mixed"][1](250, 0.1)
    assert len(sim.bodies) == 250
    blocks: dict[int, list[tuple[float, float]]] = {}
    for body in sim.bodies:
        if body.name.startswith("m"):
            origin = body.position.frame.origin
            blocks.setdefault(body.position.objcell_id >> 16, []).append((origin.x, origin.y))
    assert sorted(len(spots) for spots in blocks.values()) == [50, 100, 100]
    assert min(blocks) == 0xA9B4
    for block, spots in blocks.items():
        assert len(set(spots)) == len(spots)
        assert isinstance(sim.world.get_cell(block << 16 | 0x100), EnvCell)  # the house's hall


@pytest.mark.kernels
def test_the_server_workload_glides_its_remote_bodies_and_turns_its_told_ones() -> None:
    # h50 of 100 is a remote body: no motion of its own, interpolation nodes round a 2-m circle
    # ten times a second (the kernel glides it); h25 is told to turn left and right by turns, so
    # it ends elsewhere than in the plain hills workload.
    sim, plain = WORKLOADS["server"][1](100, 2.0, "fast"), WORKLOADS["hills"][1](100, 2.0, "fast")
    remote = sim.body("h50")
    start = remote.position.frame.origin.copy()
    sim.run()
    plain.run()
    here = remote.position.frame.origin
    assert (here - start).length() > 1.0
    assert (
        abs(((here.x - (start.x - 2.0)) ** 2 + (here.y - start.y) ** 2) ** 0.5 - 2.0) < 0.5
    )  # on its circle
    told, untold = sim.body("h25").position.frame.origin, plain.body("h25").position.frame.origin
    assert (told - untold).length() > 0.5
    counts = sim.physics.counts
    assert not any("manager" in reason or "interpolation" in reason for reason in counts.reasons)
    assert counts.kernel >= 100 * 60 - 5  # the remote body's steps too


@pytest.mark.kernels
def test_the_command_prints_a_table_and_writes_json(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out_file = tmp_path / "bench.json"
    assert main(["bench", "--bodies", "3", "--seconds", "0.2", "--json", str(out_file)]) == 0  # both engines
    out = capsys.readouterr().out
    assert "baseline" in out and "walkers" in out and "fallers" in out and "crowd" in out
    figures = json.loads(out_file.read_text(encoding="utf-8"))
    assert {f["workload"] for f in figures["results"]} == {"baseline", *WORKLOADS}
    assert {f["engine"] for f in figures["results"]} == {"python", "reference", "fast"}
    for row in figures["results"]:
        assert {"workload", "engine", "bodies", "steps_per_s"} <= set(row)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--bodies", "0"], "--bodies"),
        (["--seconds", "-1"], "--seconds"),
        (["--engine", "warp"], "--engine"),
        (["--workload", "nope"], "--workload"),
        (["--engine", "reference", "--bodies", "100000", "--seconds", "10"], "body-seconds"),
    ],
)
def test_bad_arguments_are_one_line_errors(
    args: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["bench", *args]) == 2
    err = capsys.readouterr().err
    assert err.startswith("acphys: error:") and message in err and len(err.splitlines()) == 1
