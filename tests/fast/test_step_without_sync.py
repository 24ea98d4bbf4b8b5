"""``Simulation.step(sync=False)``: the fast engine steps without writing every body's object back
and reading it again, ``arrays()`` reads its records, ``sync()`` brings the objects up to date."""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import pytest

import acphys
from acphys.arrays import BodyArrays
from acphys.bench import WORKLOADS

TICKS = 45  # 1.5 s at the default scenario's 30 Hz: the walker and the runner under way


def _assert_same(a: BodyArrays, b: BodyArrays) -> None:
    assert a.names == b.names
    for column in fields(BodyArrays):
        if column.name != "names":
            mine, theirs = getattr(a, column.name), getattr(b, column.name)
            assert mine.dtype == theirs.dtype and mine.shape == theirs.shape, column.name
            assert np.array_equal(mine, theirs), column.name


def test_unsynced_fast_steps_give_the_reference_arrays_and_sync_catches_the_objects_up() -> None:
    reference = acphys.load_scenario()
    fast = acphys.load_scenario(engine="fast")
    for _ in range(TICKS):
        reference.step()
        fast.step(sync=False)
    _assert_same(fast.arrays(), reference.arrays())
    walker = fast.body("walker")
    row = fast.arrays().index("walker")
    # The kernel stepped the walker: its object still holds where the first tick left it.
    assert fast.physics.counts.kernel > 0
    assert not np.array_equal(np.asarray(walker.position.frame.origin), fast.arrays().origins[row])
    fast.sync()
    assert np.array_equal(np.asarray(walker.position.frame.origin), fast.arrays().origins[row])
    for body in fast.bodies:
        mine, theirs = body.position, reference.body(body.name).position
        assert (mine.objcell_id, mine.frame.to_numpy().tolist()) == (
            theirs.objcell_id,
            theirs.frame.to_numpy().tolist(),
        ), body.name
        assert body.velocity.to_numpy().tolist() == reference.body(body.name).velocity.to_numpy().tolist()
    # Synced and unsynced steps mix: the next ticks read the objects again and go on alike.
    for tick in range(10):
        reference.step()
        fast.step(sync=tick % 2 == 0)
    _assert_same(fast.arrays(), reference.arrays())


def test_a_synced_step_leaves_every_object_current() -> None:
    fast = acphys.load_scenario(engine="fast")
    for _ in range(TICKS):
        fast.step()
    arrays = fast.arrays()
    for row, body in enumerate(fast.bodies):
        assert np.array_equal(np.asarray(body.position.frame.origin), arrays.origins[row]), body.name


def test_unsynced_steps_of_a_kernel_population_read_the_records() -> None:
    """Hills walkers, every step the kernel's: the arrays after unsynced steps are the reference
    engine's, and the objects are not written back until the run's end asks."""
    reference = WORKLOADS["hills"][1](12, 1.0, "reference")
    fast = WORKLOADS["hills"][1](12, 1.0, "fast")
    for _ in range(20):
        reference.step()
        fast.step(sync=False)
    assert fast.physics.counts.reference == 0
    _assert_same(fast.arrays(), reference.arrays())
    assert fast.physics._records["stale"].all()  # nothing written back yet


def test_sync_is_refused_from_a_callback_during_a_step() -> None:
    sim = acphys.load_scenario(engine="fast")
    calls: list[str] = []

    def during(body: acphys.PhysicsObj, quantum: float) -> None:
        calls.append(body.name)
        sim.sync()

    sim.on_step(during)
    with pytest.raises(RuntimeError, match="between steps"):
        for _ in range(3):  # the first tick starts the clock: its bodies take no step
            sim.step()
    assert len(calls) == 1


def test_arrays_from_a_callback_are_the_objects_the_step_is_changing() -> None:
    """A body with a callback steps on the reference path, after the fast engine wrote every
    object back: ``arrays()`` read from a callback holds the stepping body as it is after that
    step, on either engine alike."""
    seen: dict[str, list[list[float]]] = {}
    for engine in ("reference", "fast"):
        sim = acphys.load_scenario(engine=engine)
        rows = seen[engine] = []

        def during(
            body: acphys.PhysicsObj, quantum: float, sim: acphys.Simulation = sim, rows: list = rows
        ) -> None:
            if body.name == "walker":
                arrays = sim.arrays()
                row = arrays.index("walker")
                assert arrays.origins[row].tolist() == np.asarray(body.position.frame.origin).tolist()
                rows.append(arrays.positions.ravel().tolist())

        sim.on_step(during)
        for _ in range(TICKS):
            sim.step(sync=False)
    assert seen["fast"] == seen["reference"]
    assert len(seen["fast"]) > 10  # the walker's steps (at most 30 a second)
