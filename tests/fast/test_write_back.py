"""Writing the fast engine's records back into the bodies' objects (:mod:`acphys.fast.sync`): the
objects are the reference engine's, to the types of their numbers."""

from __future__ import annotations

import acphys
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
