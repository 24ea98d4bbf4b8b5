"""The shadow files of crowded cells (``ObjCell.shadow_tiles``, not retail) change nothing.

A cell with ``SHADOW_INDEX_MIN`` shadows or more files them by place so that a sweep asks only
the bodies within its reach; retail's ``CObjCell::find_obj_collisions`` (acclient.c:347141) asks
every shadow in list order. The files are a faster path of the reference engine, so every
body-step with them must be bit-identical to the same run without them (the threshold raised
past any cell's count): a dense crowd, and a seeded corpus of humans walking, running,
sidestepping, turning and jumping across four cells' corners among cylsphere pillars, balls
dropping onto them and bodies of other scales.
"""

from __future__ import annotations

import random
from collections.abc import Callable

import pytest

from acphys.bench import WORKLOADS
from acphys.scenario import parse_scenario
from acphys.simulation import Simulation
from acphys.world import obj_cell

Step = tuple[str, str, int, int, str]


def _record(sim: Simulation) -> list[Step]:
    """Run ``sim`` to its end; every body-step's exact state (as ``benchmarks/fingerprint.py``)."""
    steps: list[Step] = []

    def record(body: object, _quantum: float) -> None:
        frame = body.position.frame
        values = (*frame.origin, frame.qw, frame.qx, frame.qy, frame.qz, *body.velocity, *body.omega)
        state = " ".join(float(v).hex() for v in values)
        steps.append(
            (body.name, state, body.position.objcell_id, int(body.transient_state), repr(body.step_events))
        )

    for body in sim.bodies:
        body.observer = record
    sim.run()
    return steps


def _both(
    build: Callable[[], Simulation], monkeypatch: pytest.MonkeyPatch
) -> tuple[list[Step], list[Step], int]:
    """The run with the files, the run without, and how many sweeps the files answered."""
    answered = 0
    in_reach = obj_cell.ObjCell._shadows_in_reach

    def counted(cell: obj_cell.ObjCell, *args: object) -> list[obj_cell.ShadowObj]:
        nonlocal answered
        answered += 1
        return in_reach(cell, *args)

    with monkeypatch.context() as patch:
        patch.setattr(obj_cell.ObjCell, "_shadows_in_reach", counted)
        filed = _record(build())
    with monkeypatch.context() as patch:
        patch.setattr(obj_cell, "SHADOW_INDEX_MIN", 10**9)
        patch.setattr(obj_cell.ObjCell, "_shadows_in_reach", None)  # a filed sweep would fail
        plain = _record(build())
    return filed, plain, answered


def _assert_same(filed: list[Step], plain: list[Step]) -> None:
    assert len(filed) == len(plain)
    for index, (a, b) in enumerate(zip(filed, plain, strict=True)):
        assert a == b, f"body-step {index} ({a[0]}) differs with the shadow files"


def test_a_crowd_walking_through_itself_is_the_same_with_and_without_files(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    _description, crowd = WORKLOADS["crowd"]
    filed, plain, answered = _both(lambda: crowd(100, 2.0), monkeypatch)
    assert answered > 1000  # 100 humans 1.5 m apart share a 24-m cell: it files them
    _assert_same(filed, plain)


MOTIONS = ("WalkForward", "RunForward", "WalkBackwards", "SideStepRight", "SideStepLeft", "TurnRight")


def _corpus(seed: int) -> str:
    """Humans, balls and pillars around the corner of four cells (96, 96) of one landblock."""
    rng = random.Random(seed)
    text = [
        f'[scenario]\nname = "files-{seed}"\nduration = 2.0\ndriver_hz = 30.0\n',
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n',
        "[setup.ball]\nspheres = [{ center = [0.0, 0.0, 0.25], radius = 0.25 }]\n",
        "[setup.pillar]\ncylspheres = [{ low_pt = [0.0, 0.0, 0.0], radius = 0.4, height = 3.0 }]\n",
    ]
    for i in range(3):
        x, y = rng.uniform(90.0, 102.0), rng.uniform(90.0, 102.0)
        text.append(
            f'[[object]]\nname = "pillar{i}"\nsetup = "pillar"\nlandblock = "0xA9B4"\n'
            f"origin = [{x}, {y}, 50.0]\n"
        )
    events = []
    for i in range(40):
        x, y = rng.uniform(89.0, 103.0), rng.uniform(89.0, 103.0)
        scale = rng.choice((1.0, 1.0, 1.0, 0.6, 1.7))
        text.append(
            f'[[body]]\nname = "h{i}"\nlandblock = "0xA9B4"\non_ground = true\nscale = {scale}\n'
            f"heading = {rng.uniform(0.0, 360.0)}\norigin = [{x}, {y}, 50.0]\n"
        )
        for _ in range(rng.randint(1, 3)):
            at = round(rng.uniform(0.0, 1.5), 3)
            if rng.random() < 0.2:
                events.append(f'[[event]]\nat = {at}\nbody = "h{i}"\naction = "jump"\nextent = 0.5\n')
            else:
                hold = "true" if rng.random() < 0.5 else "false"
                events.append(
                    f'[[event]]\nat = {at}\nbody = "h{i}"\naction = "motion"\n'
                    f'motion = "{rng.choice(MOTIONS)}"\nhold_run = {hold}\n'
                )
    for i in range(8):
        x, y = rng.uniform(90.0, 102.0), rng.uniform(90.0, 102.0)
        vx, vy = rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0)
        text.append(
            f'[[body]]\nname = "ball{i}"\nsetup = "ball"\nlandblock = "0xA9B4"\n'
            f'origin = [{x}, {y}, {rng.uniform(52.0, 56.0)}]\nstate = ["gravity"]\n'
            f"velocity = [{vx}, {vy}, 0.0]\n"
        )
    return "".join(text + events)


@pytest.mark.parametrize("seed", range(4))
def test_a_seeded_crowd_at_a_cell_corner_is_the_same_with_and_without_files(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    text = _corpus(seed)
    filed, plain, answered = _both(lambda: parse_scenario(text, source=f"<files {seed}>"), monkeypatch)
    assert answered > 100
    moved = {name for name, *_ in filed}
    assert len(moved) == 48  # every human and ball stepped
    _assert_same(filed, plain)


def _filing(cell: obj_cell.ObjCell) -> tuple[dict[tuple[int, int], set[int]], set[int]]:
    """A cell's files as shadow slots: by square, and unfiled."""
    assert cell.shadow_tiles is not None
    squares = {tile: {shadow.index for shadow in square} for tile, square in cell.shadow_tiles.items()}
    return squares, {shadow.index for shadow in cell._unfiled}


@pytest.mark.kernels
def test_the_fast_engine_hands_back_files_a_fresh_filing_would_make() -> None:
    """``ObjCell.replace_shadow_objects`` keeps the files (refiling only what changed): after every
    tick of a crowd on the fast engine, each filed cell's files are those ``_start_files`` makes
    from its list, and every shadow points at its cell and slot."""
    _description, crowd = WORKLOADS["crowd"]
    sim = crowd(100, 1.0, engine="fast")
    compared = 0
    while sim.world.cur_time < 1.0:
        sim.step()
        for cell in {body.cell for body in sim.bodies if body.cell is not None}:
            for index, shadow in enumerate(cell.shadow_objects):
                assert shadow.cell is cell and shadow.index == index
            if cell.shadow_tiles is None:
                continue
            kept = _filing(cell)
            cell._start_files()
            assert kept == _filing(cell), f"{cell} at {sim.world.cur_time}"
            compared += 1
    assert compared > 20
