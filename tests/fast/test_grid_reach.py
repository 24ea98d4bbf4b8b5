"""The broad phase's reach (:mod:`acphys.fast.kernels.grid`): how far a body's spheres reach from
its origin across the ground, upright (``hreach``) or turned any way (``reach``)."""

from __future__ import annotations

import numpy as np
import pytest

import acphys
from acphys.fast.kernels.grid import reach_now, reaches_now

MARGIN = 1e-3  # REACH_MARGIN


def _human_record(sim: acphys.Simulation) -> np.ndarray:
    sim.step()
    sim.step(sync=False)  # the records read
    row = sim.physics._index[id(sim.body("walker"))]
    return sim.physics._records[row : row + 1]


def test_a_humans_reach_upright_and_turned() -> None:
    """The human's spheres: centres (0, 0, 0.475) and (0, 0, 1.35), radius 0.48 (the built-in
    setup): from its origin they reach 1.35 + 0.48 = 1.83 m (the head sphere's top), across the
    ground only their radius while the body stands upright."""
    record = _human_record(acphys.load_scenario(engine="fast"))
    spheres = record["sphere"][0].ravel().tolist()
    assert spheres == pytest.approx([0.0, 0.0, 0.475, 0.48, 0.0, 0.0, 1.35, 0.48])
    assert record["reach"][0] == pytest.approx((1.35 + 0.48) * (1.0 + 1e-6) + MARGIN)
    assert record["hreach"][0] == pytest.approx(0.48 * (1.0 + 1e-6) + MARGIN)
    # Upright: the quaternion turns about z alone (x = y = 0), whatever its heading.
    record["q"][0] = (0.8660254037844387, 0.0, 0.0, 0.5)
    assert reach_now(record[0]) == record["hreach"][0] == reaches_now(record)[0]
    # Tilted by any amount: the head sphere may lean out, the full reach counts.
    record["q"][0] = (0.9999995, 0.001, 0.0, 0.0)
    assert reach_now(record[0]) == record["reach"][0] == reaches_now(record)[0]
    record["q"][0] = (0.9999995, 0.0, -1e-9, 0.0)
    assert reach_now(record[0]) == record["reach"][0] == reaches_now(record)[0]


def test_the_grids_longest_reach_is_the_longest_current_one() -> None:
    """``grid[MAX_REACH]`` bounds every body's reach as it is turned: with upright humans only, the
    humans' reach across the ground, not to their heads."""
    sim = acphys.load_scenario("ladder-09-bodies", engine="fast")
    sim.step()
    sim.step(sync=False)
    physics = sim.physics
    records = physics._records
    assert (records["q"][:, 1] == 0.0).all() and (records["q"][:, 2] == 0.0).all()
    assert physics._grid[0] == records["hreach"].max() < records["reach"].min()
