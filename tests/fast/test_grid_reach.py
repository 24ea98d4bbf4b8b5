"""The broad phase's reach (:mod:`acphys.fast.kernels.grid`): how far a body's spheres reach from
its origin across the ground, upright (``hreach``) or turned any way (``reach``)."""

from __future__ import annotations

import numpy as np
import pytest

import acphys
from acphys.fast.kernels.grid import bucket_of, heads_for, reach_now, reaches_now

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


def test_the_hash_grows_with_the_population() -> None:
    """Four buckets a body or more, a power of four from 65,536 to 4,194,304."""
    for count, bits in ((0, 8), (16_384, 8), (16_385, 9), (100_000, 10), (10**7, 11)):
        heads, got = heads_for(count)
        assert got == bits and len(heads) == 4**bits and (heads == -1).all()


def test_squares_side_by_side_share_lines_of_heads() -> None:
    """Within a block of ``2 ** bits`` squares a side, a square's bucket is its place in the block
    (rows of x) with its run of 16 moved by the block's hash: squares along x in one run sit in
    neighbouring buckets, every bucket is in range (negative squares too), and the squares of one
    block fill every bucket once."""
    for bits in (8, 9):
        side = 1 << bits
        for tx0, ty in ((0, 0), (16 * 5, 7), (side * 3 + 32, side * 2 + 9), (-side, -1)):
            buckets = [bucket_of(tx0 + k, ty, bits) for k in range(16)]
            assert buckets == list(range(buckets[0], buckets[0] + 16)), (bits, tx0, ty)
            assert all(0 <= b < side * side for b in buckets)
    side = 1 << 8
    block = {bucket_of(side * 2 + x, side + y, 8) for x in range(side) for y in range(side)}
    assert len(block) == side * side


def test_a_crowd_on_a_larger_hash(monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    """The hash's size changes where bodies are filed, not what a search finds: a crowd walking
    through itself on the hash a quarter of a million bodies would get (1,048,576 buckets) runs
    as on the reference engine."""
    from acphys.fast.differential import compare_engines
    from acphys.fast.kernels import grid
    from acphys.scenario import parse_scenario

    from .test_kernel_statics import _crowd_by_a_pillar

    wide = grid.heads_for(250_000)
    monkeypatch.setattr(grid, "heads_for", lambda count: (wide[0].copy(), wide[1]))
    text = _crowd_by_a_pillar(6)
    result = compare_engines(lambda engine: parse_scenario(text, "<wide>", engine=engine), tmp_path)
    assert wide[1] == 10
    assert result.identical, result.divergence
    assert result.touching > 50 and result.kernel_steps > 2800, result
