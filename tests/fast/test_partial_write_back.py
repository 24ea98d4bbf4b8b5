"""An update on the reference path writes back only what it can read
(:meth:`acphys.fast.engine.FastPhysics._write_back_for`, :mod:`acphys.fast.reach`): a covered
body's handed back mid-sweep, or an uncovered body's that reads others only through its sweep,
the cells its step can reach with the stale bodies shadowed or standing there (whole those
within its reach, the places of the others), its collision partners and the player; an event
that changes only its own body writes back that body alone. The rest of the world stays in the
records until a later write-back, every kernel slot stays right, and the run is still the
reference's."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from acphys.bench import HILLS_SPACING, _hill_heights
from acphys.fast.differential import compare_engines
from acphys.fast.engine import FastPhysics
from acphys.scenario import build_scenario, parse_scenario
from acphys.simulation import Simulation

pytestmark = pytest.mark.kernels

#: Walkers circling on a 10 x 10 grid 8 m apart over rolling hills (the bench's hills), some
#: straddling cell edges; a pillar stands where walker 66's circle (about (62, 62), in the
#: cell from 48 to 72 m each way) keeps meeting it.
SIDE = 10
BUMPER = 66


def _hills_with_a_pillar(
    engine: str, seconds: float = 3.0, commands: list[dict[str, Any]] | None = None
) -> Simulation:
    bodies: list[dict[str, Any]] = []
    events: list[dict[str, Any]] = list(commands or [])
    for i in range(SIDE * SIDE):
        row, column = divmod(i, SIDE)
        name = f"h{i}"
        bodies.append(
            {
                "name": name,
                "landblock": "0x8080",
                "origin": [14.0 + HILLS_SPACING * column, 14.0 + HILLS_SPACING * row, 0.0],
                "heading": float((i * 47) % 360),
                "on_ground": True,
            }
        )
        events.append(
            {"at": 0.0, "body": name, "action": "motion", "motion": "WalkForward", "hold_run": i % 2 == 1}
        )
        events.append({"at": 0.0, "body": name, "action": "motion", "motion": "TurnRight"})
    middle = bodies[BUMPER]["origin"]
    document: dict[str, Any] = {
        "scenario": {"name": "hills-and-a-pillar", "duration": seconds, "driver_hz": 30.0},
        "landblock": [{"id": "0x8080", "heights": _hill_heights(0, 0)}],
        "setup": {"pillar": {"cylspheres": [{"low_pt": [0, 0, 0], "radius": 1.5, "height": 4.0}]}},
        "object": [
            {
                "name": "pillar",
                "setup": "pillar",
                "landblock": "0x8080",
                "origin": [middle[0] - 1.5, middle[1] + 1.0, 0.0],
            }
        ],
        "body": bodies,
        "event": events,
    }
    return build_scenario(document, source="<hills and a pillar>", engine=engine)


def _written(monkeypatch: pytest.MonkeyPatch) -> list[tuple[int, bool, int]]:
    """Record each write-back: how many bodies it wrote whole, whether it was the whole world's,
    and how many bodies it wrote the places of only."""
    calls: list[tuple[int, bool, int]] = []
    write_back = FastPhysics._write_back

    def recording(
        self: FastPhysics, stale: np.ndarray, cells: list[int] | None = None, places: np.ndarray | None = None
    ) -> None:
        calls.append((len(stale), cells is None, 0 if places is None else len(places)))
        write_back(self, stale, cells, places)

    monkeypatch.setattr(FastPhysics, "_write_back", recording)
    return calls


def _clean_cells_are_current(physics: FastPhysics) -> None:
    """Every cell neither dirty nor pending lists in its object the kernel's shadows, each the very
    shadow object of a body whose object is written (the invariant a partial write-back keeps)."""
    arrays, records = physics.world_arrays, physics._records
    index = physics._index
    for k, cell in enumerate(arrays.land_cells):
        if arrays.cells[k]["dirty"] or k in physics._pending:
            continue
        entries = arrays.shadow_list(k).tolist()
        listed = [index.get(id(shadow.physobj), None) for shadow in cell.shadow_objects]
        assert [e for e in entries if e >= 0] == [j for j in listed if j is not None], hex(cell.id)
        for shadow in cell.shadow_objects:
            j = index.get(id(shadow.physobj))
            if j is not None and not records[j]["stale"]:
                assert any(own is shadow for own in shadow.physobj.shadow_objects), (hex(cell.id), j)


def _kernel_slots_agree(physics: FastPhysics) -> None:
    """Every body's record says where each of its shadows stands in the kernel's lists."""
    arrays, records = physics.world_arrays, physics._records
    for j in range(len(records)):
        record = records[j]
        for s in range(record["num_shadow"]):
            k = int(record["shadow_cell"][s])
            if k >= 0:
                assert arrays.shadow_list(k)[record["shadow_slot"][s]] == j, (
                    j,
                    hex(int(record["shadow_cell_id"][s])),
                )


def _checking_each_reference_update(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """After each reference update, mid-run: the cells left clean are current and every kernel
    slot is right. Returns the list of pending cell counts seen, one per update."""
    pending: list[int] = []
    reference_update = FastPhysics._reference_update

    def checked(self: FastPhysics, i: int) -> None:
        reference_update(self, i)
        _clean_cells_are_current(self)
        _kernel_slots_agree(self)
        pending.append(len(self._pending))

    monkeypatch.setattr(FastPhysics, "_reference_update", checked)
    return pending


def test_a_body_bumping_a_pillar_runs_as_on_the_reference(tmp_path: Path) -> None:
    comparison = compare_engines(_hills_with_a_pillar, tmp_path)
    assert comparison.identical, comparison.divergence
    assert comparison.reasons.get("a static object within reach", 0) >= 10
    assert comparison.reference_steps >= 10


def test_only_what_the_reference_step_reads_is_written_back(monkeypatch: pytest.MonkeyPatch) -> None:
    """Each reference update of the pillar's walker writes the bodies around it (those shadowed in
    the cells within 2 m of its reach: its own cell and at times the next; whole those within its
    reach, the places only of the others), never the world's 100; after it, mid-run, every cell
    the write-backs left clean is current, every kernel slot right, and some cells wait (pending)
    for a later write-back."""
    calls = _written(monkeypatch)
    pending = _checking_each_reference_update(monkeypatch)
    sim = _hills_with_a_pillar("fast")
    sim.run()
    partial = [count for count, whole, _ in calls if not whole]
    assert len(partial) >= 10 and len(pending) == len(partial)
    assert max(partial) <= 40
    assert max(pending) > 0
    # the walkers in those cells but out of the sweep's reach: their places only
    assert sum(placed for _, whole, placed in calls if not whole) > sum(partial)


def _shadows_are_consistent(sim: Simulation) -> None:
    """Every cell's shadows point at it and their slots, each is its body's own object, and every
    body's shadows stand in their cells' lists."""
    physics = sim.physics
    assert isinstance(physics, FastPhysics)
    for cell in physics.world_arrays.land_cells:
        for index, shadow in enumerate(cell.shadow_objects):
            assert shadow.cell is cell and shadow.index == index
            assert any(own is shadow for own in shadow.physobj.shadow_objects), (hex(cell.id), shadow)
    for body in sim.bodies:
        for shadow in body.shadow_objects:
            assert shadow.cell is not None and shadow.cell.shadow_objects[shadow.index] is shadow


def test_the_world_written_back_after_each_tick_is_the_references() -> None:
    """A public step ends with a whole write-back: the cells a partial one left wait no longer, and
    the bodies it wrote earlier in the tick are written into them with their new shadow objects
    (not the old ones in the same slots). Every cell then lists the reference's bodies in its
    order."""
    fast, reference = _hills_with_a_pillar("fast"), _hills_with_a_pillar("reference")
    physics = fast.physics
    assert isinstance(physics, FastPhysics)
    left_behind = 0
    write_back = physics._write_back

    def counting(stale: np.ndarray, cells: list[int] | None = None, places: np.ndarray | None = None) -> None:
        nonlocal left_behind
        if cells is None:
            left_behind += len(physics._pending)
        write_back(stale, cells, places)

    physics._write_back = counting  # type: ignore[method-assign]
    while fast.world.cur_time < 3.0:
        fast.step()
        reference.step()
        assert not physics._pending and not physics.world_arrays.cells["dirty"].any()
        _shadows_are_consistent(fast)
        for mine, theirs in zip(physics.world_arrays.land_cells, _land_cells(reference), strict=True):
            assert [s.physobj.name for s in mine.shadow_objects] == [
                s.physobj.name for s in theirs.shadow_objects
            ]
    assert left_behind > 0  # whole write-backs found cells waiting


def _land_cells(sim: Simulation) -> list[Any]:
    block = sim.world.landscape.get_landblock(0x8080 << 16)
    assert block is not None
    return list(block.lcell)


def test_a_step_reaching_past_what_was_written_is_an_error_not_a_silent_divergence(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Were the reach wrong (here: no cell at all), the reference step would touch cells still
    behind: the engine says so instead of reading them back into the kernel."""
    monkeypatch.setattr(FastPhysics, "_reach_of_update", lambda self, i: [])
    sim = _hills_with_a_pillar("fast")
    with pytest.raises(RuntimeError, match=r"the reference step of h66 reached past what was written back"):
        sim.run()


def _walkers_a_drifter_and_a_remote(engine: str, seconds: float = 3.0) -> Simulation:
    """100 walkers circling on flat ground 8 m apart and, among them, a body of three spheres (the
    kernel does not cover it) gliding at 2 m/s across their circles at their height, with no
    gravity, a remote human interpolated among them on a long leash (its constraint manager
    keeps it on the reference path; the kernel glides bodies that only interpolate) and one
    running to a point across them (a move-to manager): their updates run there every tick, and
    bump walkers."""
    text = [
        f'[scenario]\nname = "drifter"\nduration = {seconds}\ndriver_hz = 30.0\n',
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n',
        "[setup.tri]\nspheres = [{ center = [0, 0, 0.3], radius = 0.3 },"
        " { center = [0, 0, 0.9], radius = 0.3 }, { center = [0, 0, 1.5], radius = 0.3 }]\n",
        '[[body]]\nname = "drifter"\nsetup = "tri"\nlandblock = "0xA9B4"\norigin = [20.0, 61.0, 50.1]\n'
        'state = ["report_collisions"]\nvelocity = [2.0, 0.0, 0.0]\n',
    ]
    text.append(
        '[[body]]\nname = "remote"\nlandblock = "0xA9B4"\norigin = [40.0, 40.0, 50.0]\non_ground = true\n'
    )
    text.append(
        '[[body]]\nname = "errand"\nlandblock = "0xA9B4"\norigin = [70.0, 20.0, 50.0]\non_ground = true\n'
    )
    text.append(  # a leash that never pulls: the constraint starts 60 m out
        '[[event]]\nat = 0.1\nbody = "remote"\naction = "constrain_to"\norigin = [40.0, 40.0, 50.0]\n'
        "start = 60.0\nmax = 90.0\n"
    )
    text.append(  # a move to a point across the walkers' circles
        '[[event]]\nat = 0.1\nbody = "errand"\naction = "move_to"\norigin = [30.0, 80.0, 50.0]\n'
        "hold_run = true\n"
    )
    events = [  # glides among the walkers, then a node beyond the blip distance: a blip
        f'[[event]]\nat = {at}\nbody = "remote"\naction = "interpolate_to"\norigin = [{x}, {y}, 50.005]\n'
        for at, x, y in ((0.2, 44.0, 46.0), (0.9, 52.0, 50.0), (1.6, 170.0, 150.0), (2.2, 60.0, 62.0))
    ]
    for i in range(100):
        row, column = divmod(i, 10)
        name = f"w{i}"
        x, y = 14.0 + 8.0 * column, 14.0 + 8.0 * row
        text.append(
            f'[[body]]\nname = "{name}"\nlandblock = "0xA9B4"\norigin = [{x}, {y}, 50.0]\n'
            f"on_ground = true\nheading = {(i * 47) % 360}\n"
        )
        events.append(f'[[event]]\nat = 0.0\nbody = "{name}"\naction = "motion"\nmotion = "WalkForward"\n')
        events.append(f'[[event]]\nat = 0.0\nbody = "{name}"\naction = "motion"\nmotion = "TurnRight"\n')
    return parse_scenario("".join(text + events), source="<drifter>", engine=engine)


def test_uncovered_bodies_among_walkers_run_as_on_the_reference(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The drifter's, the remote body's and the errand's updates read other bodies only through
    their sweeps (and the remote body's blip): each write-back before one writes the bodies
    around it (and around its nodes), not the 100 walkers; they bump some walkers (collision
    partners the kernel hands back), and every step is the reference's."""
    calls = _written(monkeypatch)
    _checking_each_reference_update(monkeypatch)
    comparison = compare_engines(_walkers_a_drifter_and_a_remote, tmp_path)
    assert comparison.identical, comparison.divergence
    assert comparison.reasons.get("shape: more than two spheres", 0) >= 85  # the drifter, every tick
    assert comparison.reasons.get("a sticky or constraint manager", 0) >= 80  # the remote body
    assert comparison.reasons.get("a move-to manager", 0) >= 30  # the errand, until it arrives
    assert comparison.reasons.get("a body the kernel cannot collide with", 0) >= 1  # walkers they met
    partial = [count for count, whole, _ in calls if not whole]
    assert len(partial) >= 250 and max(partial) <= 60 and sum(partial) / len(partial) < 20


def _commands() -> list[dict[str, Any]]:
    """What a server keeps telling its bodies: turn this way and that, jump, go there, glide
    (interpolation nodes), on four of the walkers, ten times a second."""
    commands: list[dict[str, Any]] = []
    for k in range(1, 25):
        at = 0.5 + 0.1 * k
        commands.append(
            {"at": at, "body": "h12", "action": "motion", "motion": "TurnLeft" if k % 2 else "TurnRight"}
        )
        commands.append(
            {"at": at, "body": "h57", "action": "interpolate_to", "origin": [70.0 + 0.3 * k, 54.0, 0.0]}
        )
    commands.append({"at": 0.8, "body": "h33", "action": "jump", "extent": 0.6})
    commands.append({"at": 1.2, "body": "h81", "action": "move_to", "origin": [30.0, 20.0, 0.0]})
    commands.append({"at": 1.5, "body": "h45", "action": "set_velocity", "velocity": [0.0, 0.0, 4.0]})
    return commands


def test_commands_to_bodies_write_back_those_bodies_alone(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Events that change only their body's own state (OWN_STATE_ACTIONS) write back that body
    alone (its shadows stay the kernel's) and read it again, not the world; every step is still
    the reference's."""
    calls = _written(monkeypatch)
    _checking_each_reference_update(monkeypatch)
    apply_events = FastPhysics.apply_events

    def checked(self: FastPhysics, events: list[Any], body_named: Any) -> None:
        apply_events(self, events, body_named)
        if self._arrays is not None and not self._reload:
            _clean_cells_are_current(self)
            _kernel_slots_agree(self)

    monkeypatch.setattr(FastPhysics, "apply_events", checked)
    comparison = compare_engines(lambda engine: _hills_with_a_pillar(engine, commands=_commands()), tmp_path)
    assert comparison.identical, comparison.divergence
    whole = [count for count, all_of_it, _ in calls if all_of_it]
    assert len(whole) == 1  # the run's end (the first events, at 0 s, came before any step)
    # the others are the reference updates' (the pillar's walker, the interpolated and moving
    # bodies): the events wrote back their bodies alone, through no write-back of cells; an
    # update whose glide gave a node up writes its body first (its reach is measured on it)
    given_up = comparison.reasons.get("an interpolation node given up (a failed audit or a blip)", 0)
    assert given_up >= 1
    assert len(calls) == sum(comparison.reasons.values()) + given_up + 1
