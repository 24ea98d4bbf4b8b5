"""Writing the fast engine's records back into the bodies' objects (:mod:`acphys.fast.sync`): the
objects are the reference engine's, to the types of their numbers."""

from __future__ import annotations

import numpy as np

import acphys
from acphys.body.reports import CollisionRecord, CollisionTable
from acphys.fast.layout import BODY
from acphys.fast.sync import load_body, store_bodies, vector_column
from acphys.math.vector import Vector3
from acphys.motion.animation import AnimSequenceNode


def _node(node: AnimSequenceNode) -> tuple[str, float, int, int]:
    return repr(node.animation), node.framerate, node.low_frame, node.high_frame


def test_the_written_back_objects_are_the_references() -> None:
    """A second of the default scenario on each engine: every body object the same afterwards,
    down to the types of its numbers."""
    reference = acphys.load_scenario()
    fast = acphys.load_scenario(engine="fast")
    reference.run(until=1.0)
    fast.run(until=1.0)
    assert fast.physics.counts.kernel > 0
    for mine, theirs in zip(fast.bodies, reference.bodies, strict=True):
        frame, want = mine.position.frame, theirs.position.frame
        assert (frame.origin, frame.rotation, list(frame.m)) == (want.origin, want.rotation, list(want.m))
        for name in ("velocity", "acceleration", "omega", "cached_velocity", "sliding_normal"):
            assert getattr(mine, name) == getattr(theirs, name), (mine.name, name)
        plane, want_plane = mine.contact_plane, theirs.contact_plane
        assert (plane.N, plane.d) == (want_plane.N, want_plane.d)
        assert type(mine.update_time) is type(theirs.update_time) is float
        assert (mine._state, mine._transient_state) == (theirs._state, theirs._transient_state)
        assert type(mine._state) is type(theirs._state) is int
        assert mine.position.objcell_id == theirs.position.objcell_id
        if mine.part_array is not None:
            ours, ref = mine.part_array.sequence, theirs.part_array.sequence
            assert ours.frame_number == ref.frame_number and type(ours.frame_number) is float
            assert [_node(n) for n in ours.anim_list] == [_node(n) for n in ref.anim_list]
            assert all(type(n.low_frame) is int and type(n.framerate) is float for n in ours.anim_list)


def test_collision_records_go_over_oldest_first_and_come_back_so() -> None:
    """The kernel keeps a body's collision records oldest first and derives retail's iteration
    order from that (bucket ``(id ^ (id >> 8)) & 3``, the newest first in a bucket); they are read
    in the order they were stored, not in that iteration order, and written back as the kernel
    holds them (a record it ended and made again is a new one)."""
    sim = acphys.load_scenario(engine="fast")
    sim.step()
    body = sim.bodies[0]
    table = CollisionTable()
    for object_id in (0x50000004, 0x50000008, 0x50000001):  # buckets 0, 0 and 1
        table.clobber(object_id, CollisionRecord(1.0, False))
    assert table.ids() == [0x50000008, 0x50000004, 0x50000001] != table.oldest_first()
    body.collision_table = table
    record = np.zeros(1, dtype=BODY)[0]
    load_body(record, body, -1, True)
    assert record["record_obj"][: record["num_records"]].tolist() == [0x50000004, 0x50000008, 0x50000001]
    # the kernel ended 0x50000004 and made it again: now the newest
    record["record_obj"][:3] = (0x50000008, 0x50000001, 0x50000004)
    store_bodies(np.array([record]), [body])
    assert body.collision_table.oldest_first() == [0x50000008, 0x50000001, 0x50000004]
    assert body.collision_table.ids() == [0x50000004, 0x50000008, 0x50000001]


def test_vector_columns_narrow_as_the_constructor_does() -> None:
    """``vector_column`` narrows a whole field at once in NumPy; each component is the one
    ``Vector3(x, y, z)`` stores (ties to even, subnormals, past the float32 range an infinity,
    signed zeros, NaN)."""
    rng = np.random.default_rng(3)
    rows = np.concatenate(
        (
            rng.normal(0.0, 100.0, (300, 3)),
            rng.uniform(-1e-40, 1e-40, (50, 3)),
            rng.uniform(-1e39, 1e39, (50, 3)),
            np.array(
                [[0.5 + 2.0**-25, 1.0 + 2.0**-24, -0.0], [np.nan, np.inf, -np.inf], [3.4e38, 3.5e38, 1e-46]]
            ),
        )
    )
    mine = vector_column(rows)
    for vector, row in zip(mine, rows.tolist(), strict=True):
        want = Vector3(*row)
        for got, expected in zip(vector, want, strict=True):
            assert type(got) is float
            assert got.hex() == expected.hex() or (got != got and expected != expected), (row, got, expected)
