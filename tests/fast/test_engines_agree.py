"""The fast engine writes the reference engine's trace, byte for byte (issue 14).

Every bundled scenario and a seeded corpus of random worlds run on both engines; a body-step that
differs fails the test, naming the record, body and field. Each scenario must also have been
stepped by the kernel where the kernel covers its bodies, so that agreement is not just the
reference path agreeing with itself.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from acphys.bench import WORKLOADS
from acphys.fast import engine as engine_module
from acphys.fast.differential import Comparison, compare_engines
from acphys.fast.kernels.cells import BAIL_REASONS, R_DEEP
from acphys.scenario import builtin_scenarios, load_scenario, parse_scenario
from engine_corpus import random_scenarios


def _nests_no_deeper(result: Comparison) -> bool:
    """No update was handed back for nesting below the kernel's two compiled levels of
    ``transitional_insert`` (:mod:`acphys.fast.kernels.sweep`): the levels are chosen so that
    none is, and a world that nests deeper shows here (its traces would still agree)."""
    return BAIL_REASONS[R_DEEP] not in result.reasons


@pytest.mark.parametrize("name", builtin_scenarios())
def test_bundled_scenarios_agree(name: str, tmp_path: Path) -> None:
    result = compare_engines(lambda engine: load_scenario(name, engine=engine), tmp_path)
    assert result.identical, f"{name}: {result.divergence}"
    assert result.records > 0
    assert _nests_no_deeper(result), result.reasons


@pytest.mark.parametrize("seed", range(12))
def test_random_worlds_agree(seed: int, tmp_path: Path) -> None:
    text = random_scenarios(seed)
    result = compare_engines(lambda engine: parse_scenario(text, f"<corpus {seed}>", engine=engine), tmp_path)
    assert result.identical, f"seed {seed}: {result.divergence}"
    assert result.kernel_steps > 0, f"seed {seed}: the kernel took no step"
    assert _nests_no_deeper(result), result.reasons


def test_the_kernel_steps_what_it_covers(tmp_path: Path) -> None:
    """Balls dropped and thrown on open terrain are the kernel's from the first step to the last."""
    result = compare_engines(lambda engine: load_scenario("ladder-01-fall", engine=engine), tmp_path)
    assert result.identical
    assert result.kernel_steps > 0


@pytest.mark.parametrize("workload", list(WORKLOADS))
def test_bench_workloads_agree(workload: str, tmp_path: Path) -> None:
    """The bench's populations, small: walkers, fallers, a crowd walking into itself, walkers
    circling over hills, and the mixed landblock with its pillars and house."""
    build = WORKLOADS[workload][1]
    result = compare_engines(lambda engine: build(24, 2.0, engine), tmp_path)
    assert result.identical, f"{workload}: {result.divergence}"
    assert result.kernel_steps > 0
    assert _nests_no_deeper(result), result.reasons


def test_a_cell_that_fills_up_agrees(tmp_path: Path) -> None:
    """Forty balls thrown from a ring 40 m across into the landblock's middle cell: its shadow
    list outgrows the room it started with (the engine gives it more, the kernel goes on), and
    the balls land among each other and touch (in the kernel: first touches, reports, slides)."""
    ring = [(math.cos(i * 0.157), math.sin(i * 0.157)) for i in range(40)]
    balls = "".join(
        f'[[body]]\nname = "b{i}"\nsetup = "ball"\nlandblock = "0xA9B4"\n'
        f"origin = [{84.0 + 20.0 * x:.3f}, {84.0 + 20.0 * y:.3f}, 52.0]\n"
        f'state = ["gravity", "report_collisions"]\nvelocity = [{-9.0 * x:.3f}, {-9.0 * y:.3f}, 6.0]\n'
        for i, (x, y) in enumerate(ring)
    )
    text = (
        '[scenario]\nname = "fill"\nduration = 3.0\ndriver_hz = 30.0\n'
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        "[setup.ball]\nspheres = [{ center = [0, 0, 0.25], radius = 0.25 }]\n" + balls
    )
    result = compare_engines(lambda engine: parse_scenario(text, "<fill>", engine=engine), tmp_path)
    assert result.identical, result.divergence
    assert result.kernel_steps > 0 and result.touching > 0


def test_full_logs_are_written_out_and_the_run_goes_on(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With room for only a few trace rows and cell moves, the kernel stops again and again to
    have them written out (the trace, and the bodies' moves into their cells' object lists); the
    run is the reference's all the same."""
    monkeypatch.setattr(engine_module, "LOG_ROWS", 24)
    build = WORKLOADS["hills"][1]
    result = compare_engines(lambda engine: build(60, 3.0, engine), tmp_path)
    assert result.identical, result.divergence
    assert result.reference_steps == 0 and result.kernel_steps == 60 * 90


def test_runs_that_differ_are_told_apart(tmp_path: Path) -> None:
    """The comparison can fail: two different scenarios behind the two engines give a divergence
    naming the first record and field that differ, with the fast run's counts."""
    names = {"reference": "ladder-01-fall", "fast": "ladder-07-bounce"}
    result = compare_engines(lambda engine: load_scenario(names[engine], engine=engine), tmp_path, until=1.0)
    assert not result.identical
    assert result.divergence.startswith("first divergence at line 2, t=0, body 'ball': id:")
    # The missile of ladder-07 flies at a wall, a static object: the kernel's while out of the
    # wall's reach, the reference path's at the wall.
    assert result.kernel_steps > 0 and result.reference_steps > 0
    assert set(result.reasons) == {"a static object within reach"}
