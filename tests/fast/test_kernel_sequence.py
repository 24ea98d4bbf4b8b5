"""Differential tests: :func:`acphys.fast.kernels.sequence.sequence_update` against ``Sequence.update``.

Each case builds the same reference ``Sequence`` twice (real ``Animation`` / ``AnimData``
objects, a hook object that records ``add_anim_hook``), plays one with the reference and loads
the other into a body record for the kernel. When the reference queued no hook, the kernel must
return STATUS_DONE with the identical offset frame (origin, quaternion, matrix), frame number,
current node and list (the whole record is compared byte for byte with the reference sequence
loaded afresh, and ``store_sequences`` must give back the reference's sequence). When the
reference queued only AnimDone hooks, the kernel must play the quantum the same way, return
STATUS_ANIM_DONE and count them in ``seq_anim_done``; when it queued any frame hook, the kernel
must return STATUS_REFERENCE and leave the record as it was.
"""

from __future__ import annotations

import math
import os
import random
import signal

import numpy as np
import pytest

from acphys.fast.kernels import sequence as S
from acphys.fast.layout import BODY, MAX_NODES
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.anim_hooks import ANIM_DONE_HOOK, NOOPHook
from acphys.motion.animation import Animation, AnimData, AnimFrame, AnimSequenceNode
from acphys.motion.sequence import Sequence

#: Random cases for the one-quantum comparison; sequences and quanta for the long runs.
N = int(os.environ.get("ACPHYS_SEQUENCE_CASES", "4000"))
RUNS = int(os.environ.get("ACPHYS_SEQUENCE_RUNS", "150"))
STEPS = 40
#: float32 values (built from their bits, not through acphys.precision).
FRAMERATES = (30.0, 10.0, 8.0, 16.0, 12.5, -10.0, -30.0, -8.0, 0.0, 2.0, -2.0, 1e-4, -1e-4)
QUANTA = (1 / 30, 0.05, 0.1, 0.125, 0.25, 0.5, 1.0, 2.0, 0.0, 1e-5, 1 / 60, 0.2)


def f32(value: float) -> float:
    """Narrow with numpy (the unnarrowed run turns acphys.precision's narrowing off)."""
    return float(np.float32(value))


def same(a, b) -> bool:
    """Identical floats (NaN matches NaN; +0.0 and -0.0 differ), or tuples of them."""
    if isinstance(a, tuple) or isinstance(b, tuple):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    a, b = float(a), float(b)
    if a != a or b != b:
        return a != a and b != b
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


class HookRecorder:
    """Stands in for the body: records what the sequence queues."""

    def __init__(self) -> None:
        self.hooks: list = []

    def add_anim_hook(self, hook) -> None:
        self.hooks.append(hook)


def body_record() -> np.record:
    return np.zeros(1, dtype=BODY).view(np.recarray)[0]


def store(record: np.record, sequence: Sequence, table: list[Animation]) -> None:
    """``store_sequences`` for one record."""
    S.store_sequences(np.array([record], dtype=BODY), [sequence], table)


def ft(f: Frame) -> tuple:
    return (f.origin.x, f.origin.y, f.origin.z), f.rotation, tuple(f.m)


# -- building sequences ------------------------------------------------------------------------------


def unit_quaternion(rng: random.Random, angle: float) -> tuple[float, float, float, float]:
    x, y, z = rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)
    n = math.sqrt(x * x + y * y + z * z) or 1.0
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), x * s, y * s, z * s)


def pos_frame(rng: random.Random) -> Frame:
    """A position frame: a small step, turned a little or not at all."""
    origin = Vector3(*(f32(rng.uniform(-0.2, 0.2)) for _ in range(2)), f32(rng.uniform(-0.05, 0.05)))
    if rng.random() < 0.3:
        origin = Vector3(0.0, float(rng.randint(0, 3)), 0.0)
    frame = Frame(origin)
    if rng.random() < 0.6:
        frame = Frame(origin, *(f32(c) for c in unit_quaternion(rng, rng.uniform(-0.3, 0.3))))
    return frame


def animation(rng: random.Random, hook_rate: float) -> Animation:
    frames = rng.randint(1, 7)
    part_frames = []
    for _ in range(frames):
        hooks = []
        if rng.random() < hook_rate:
            hooks = [NOOPHook(direction=rng.choice((-2, -1, 0, 1))) for _ in range(rng.randint(1, 2))]
        part_frames.append(AnimFrame([Frame()], hooks))
    pos = [pos_frame(rng) for _ in range(frames)] if rng.random() < 0.75 else None
    return Animation(part_frames, pos, name=f"a{frames}")


def animations(seed: int, count: int, hook_rate: float) -> list[Animation]:
    rng = random.Random(seed)
    return [animation(rng, hook_rate) for _ in range(count)]


def small_vector(rng: random.Random, scale: float) -> Vector3:
    r = rng.random()
    if r < 0.3:
        return Vector3()
    if r < 0.5:
        v = [0.0, 0.0, 0.0]
        v[rng.randrange(3)] = f32(rng.uniform(-scale, scale))
        return Vector3(*v)
    return Vector3(*(f32(rng.uniform(-scale, scale)) for _ in range(3)))


def build_sequence(rng: random.Random, table: list[Animation], max_nodes: int = MAX_NODES) -> Sequence:
    """A sequence in any state play can leave one in, and some it cannot (a cycle of several
    nodes, ``curr_anim`` anywhere, links not yet dropped, a framerate scaled mid-play)."""
    seq = Sequence()
    for _ in range(rng.randint(1, max_nodes)):
        anim = rng.choice(table)
        count = anim.num_frames
        framerate = rng.choice(FRAMERATES) if rng.random() < 0.7 else f32(rng.uniform(-40.0, 40.0))
        seq.append_animation(AnimData(anim, rng.randint(-1, count), rng.randint(-1, count), framerate))
    nodes = seq.anim_list
    r = rng.random()
    if r < 0.35:
        seq.first_cyclic = nodes[0]  # the whole list cycles
    elif r < 0.5:
        seq.first_cyclic = rng.choice(nodes)
    if rng.random() < 0.6:
        node = rng.choice(nodes)
        seq.curr_anim = node
        low, high = min(node.low_frame, node.high_frame), max(node.low_frame, node.high_frame)
        r = rng.random()
        if r < 0.3:
            seq.frame_number = node.get_starting_frame()
        elif r < 0.45:
            seq.frame_number = node.get_ending_frame()
        elif r < 0.7:
            seq.frame_number = float(rng.randint(low, high))  # on a frame boundary
        else:
            seq.frame_number = rng.uniform(low, high + 1 - 1e-9)
    if rng.random() < 0.15:
        # not negative: the swapped range never finishes (test_a_turned_over_range_never_ends)
        seq.multiply_cyclic_animation_framerate(rng.choice((0.0, 0.5, 2.0, 1.25)))
    seq.set_velocity(small_vector(rng, 5.0))
    seq.set_omega(small_vector(rng, 2.0))
    seq.set_object(HookRecorder())
    return seq


def offset_frame(rng: random.Random) -> Frame:
    if rng.random() < 0.5:
        return Frame()
    return Frame(
        Vector3(*(f32(rng.uniform(-3.0, 3.0)) for _ in range(3))),
        *(f32(c) for c in unit_quaternion(rng, rng.uniform(-3.0, 3.0))),
    )


def quantum(rng: random.Random) -> float:
    r = rng.random()
    if r < 0.5:
        return rng.choice(QUANTA)
    if r < 0.9:
        return rng.uniform(0.0, 0.6)
    if r < 0.95:
        return rng.uniform(0.0, 3.0)
    return -rng.choice((0.05, 0.25, rng.uniform(0.0, 1.0)))


# -- comparing ----------------------------------------------------------------------------------------


def expected_record(seq: Sequence, index: dict[int, int], anim_done: int = 0) -> np.record:
    record = body_record()
    assert S.load_sequence(record, seq, index)
    record["seq_anim_done"] = anim_done
    return record


def expected_status(hooks: list) -> int:
    """The kernel's status for a quantum in which the reference queued ``hooks``."""
    if any(hook is not ANIM_DONE_HOOK for hook in hooks):
        return S.STATUS_REFERENCE
    return S.STATUS_ANIM_DONE if hooks else S.STATUS_DONE


def assert_same_sequence(got: Sequence, want: Sequence) -> None:
    assert len(got.anim_list) == len(want.anim_list)
    for a, b in zip(got.anim_list, want.anim_list, strict=True):
        assert a.animation is b.animation
        assert (a.framerate, a.low_frame, a.high_frame) == (b.framerate, b.low_frame, b.high_frame)
    for name in ("curr_anim", "first_cyclic"):
        g, w = getattr(got, name), getattr(want, name)
        gi = next((i for i, n in enumerate(got.anim_list) if n is g), None)
        wi = next((i for i, n in enumerate(want.anim_list) if n is w), None)
        assert gi == wi, name
    assert same(got.frame_number, want.frame_number)
    assert same(tuple(got.velocity), tuple(want.velocity)) and same(tuple(got.omega), tuple(want.omega))


def without_memo(record: np.record) -> bytes:
    """The record's bytes but its turn memo's (``turn_memo``: a kernel's cache, not the sequence)."""
    copy = record.copy()
    copy["turn_memo"] = 0.0
    return copy.tobytes()


def assert_memo_holds(record: np.record) -> None:
    """The record's turn memo is empty or holds ``Frame::grotate``'s terms of its squared angle
    (acclient.c:357421): 1/angle and the cosine of the half angle narrowed, the sine not."""
    theta2, inv, sine, cosine = (float(x) for x in record["turn_memo"])
    if theta2 == 0.0:
        assert inv == sine == cosine == 0.0
        return
    theta = math.sqrt(theta2)
    assert (inv, sine, cosine) == (f32(1.0 / theta), math.sin(theta * 0.5), f32(math.cos(theta * 0.5)))


def play_one(seed: int, table: list[Animation], tables: tuple, index: dict[int, int]) -> int:
    """Build one case from ``seed``, play it both ways, compare; returns the kernel's status."""
    ref = build_sequence(random.Random(seed), table)
    mine = build_sequence(random.Random(seed), table)
    rng = random.Random(seed + 1)
    offset = offset_frame(rng)
    dt = quantum(rng)

    record = body_record()
    assert S.load_sequence(record, mine, index)
    before = record.copy()
    nodes_before = list(mine.anim_list)

    ref_offset = offset.copy()
    ref.update(dt, ref_offset)
    status, origin, q, m = S.sequence_update(record, *tables, dt, *ft(offset))

    queued = ref.hook_obj.hooks
    assert status == expected_status(queued), (seed, dt, queued)
    assert_memo_holds(record)
    if status == S.STATUS_REFERENCE:
        assert without_memo(record) == without_memo(before), seed
        assert (origin, q, m) == ft(offset)
        return status
    assert same((origin, q, m), ft(ref_offset)), (seed, dt)
    want = expected_record(ref, index, len(queued))
    want["turn_memo"] = record["turn_memo"]
    mismatched = [name for name in BODY.names if record[name].tobytes() != want[name].tobytes()]
    assert not mismatched, (seed, dt, [(name, record[name], want[name]) for name in mismatched])
    assert record.tobytes() == want.tobytes(), seed
    store(record, mine, table)
    assert_same_sequence(mine, ref)
    # the nodes that stay are the same objects, the dropped ones were the head
    kept = nodes_before[len(nodes_before) - len(mine.anim_list) :]
    assert all(a is b for a, b in zip(mine.anim_list, kept, strict=True))
    return status


# -- the tests -----------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def quiet_world():
    """Animations without hooks: only AnimDone sends a quantum back."""
    table = animations(100, 16, hook_rate=0.0)
    return table, S.animation_table(table), S.animation_index(table)


@pytest.fixture(scope="module")
def hooked_world():
    """Animations with hooks on some frames, in every direction."""
    table = animations(200, 16, hook_rate=0.2)
    return table, S.animation_table(table), S.animation_index(table)


def test_animation_table():
    hooks = {0: [NOOPHook(direction=1)], 1: [NOOPHook(direction=-1)], 2: [NOOPHook(direction=0)]}
    hooks[3] = [NOOPHook(direction=-2)]
    hooks[4] = [NOOPHook(direction=1), NOOPHook(direction=-1)]
    moving = Animation(
        [AnimFrame([Frame()], hooks.get(i, [])) for i in range(5)],
        [pos_frame(random.Random(i)) for i in range(5)],
    )
    still = Animation([AnimFrame([Frame()]) for _ in range(3)])
    anims, pos, bits = S.animation_table([still, moving])
    assert anims.dtype == np.int32 and pos.dtype == np.float64 and bits.dtype == np.uint8
    assert anims.tolist() == [[0, 3, 0], [3, 5, 1]]
    assert pos.shape == (8, 7) and not pos[:3].any()
    for i, frame in enumerate(moving.pos_frames):
        assert pos[3 + i].tolist() == [*frame.origin, *frame.rotation]
    assert bits.tolist() == [0, 0, 0, 1, 2, 3, 0, 3]
    assert S.animation_index([still, moving]) == {id(still): 0, id(moving): 1}


def test_load_and_store(quiet_world):
    table, _, index = quiet_world
    rng = random.Random(3)
    for _ in range(300):
        seq = build_sequence(rng, table)
        record = body_record()
        assert S.load_sequence(record, seq, index)
        nodes = len(seq.anim_list)
        assert record.seq_nodes == nodes and not record.seq_anim[nodes:].any()
        fresh = Sequence()
        store(record, fresh, table)  # new nodes, the same fields
        assert_same_sequence(fresh, seq)
        assert all(a is not b for a, b in zip(fresh.anim_list, seq.anim_list, strict=True))
        kept = list(seq.anim_list)
        store(record, seq, table)  # the same nodes, kept
        assert seq.anim_list == kept and all(a is b for a, b in zip(seq.anim_list, kept, strict=True))

    empty = Sequence()
    record = body_record()
    assert S.load_sequence(record, empty, index)
    assert (record.seq_nodes, record.seq_curr, record.seq_first_cyclic) == (0, -1, -1)
    store(record, empty, table)
    assert empty.anim_list == [] and empty.curr_anim is None and empty.first_cyclic is None


def test_load_refuses_what_the_record_cannot_hold(quiet_world):
    table, _, index = quiet_world
    rng = random.Random(4)
    record = body_record()
    untouched = record.tobytes()
    seq = build_sequence(rng, table)
    while len(seq.anim_list) <= MAX_NODES:
        seq.append_animation(AnimData(rng.choice(table)))
    assert not S.load_sequence(record, seq, index)  # too long
    seq = build_sequence(rng, table)
    assert not S.load_sequence(record, seq, {})  # an animation outside the table
    seq = build_sequence(rng, table)
    seq.velocity.x = 0.1  # not a float32
    assert not S.load_sequence(record, seq, index)
    seq = build_sequence(rng, table)
    seq.curr_anim = AnimSequenceNode(AnimData(table[0]))  # not in the list
    assert not S.load_sequence(record, seq, index)
    assert record.tobytes() == untouched


def test_one_quantum_without_hooks(quiet_world):
    table, tables, index = quiet_world
    statuses = [play_one(seed, table, tables, index) for seed in range(0, 2 * N, 2)]
    done = statuses.count(S.STATUS_DONE)
    assert done > N // 2 and statuses.count(S.STATUS_ANIM_DONE) > N // 20, done


def test_one_quantum_with_hooks(hooked_world):
    table, tables, index = hooked_world
    statuses = [play_one(seed, table, tables, index) for seed in range(1, N // 2, 2)]
    assert statuses.count(S.STATUS_DONE) > N // 20 and statuses.count(S.STATUS_REFERENCE) > N // 200
    assert statuses.count(S.STATUS_ANIM_DONE) > N // 200


def test_long_runs_fall_back_exactly_when_the_reference_queues(hooked_world, quiet_world):
    """An engine's loop: the kernel plays each quantum; when it hands one back, the reference
    plays it and the record is loaded again. The offset frame accumulates across quanta."""
    counts = {S.STATUS_DONE: 0, S.STATUS_REFERENCE: 0, S.STATUS_ANIM_DONE: 0}
    for run in range(RUNS):
        table, tables, index = hooked_world if run % 2 else quiet_world
        rng = random.Random(10_000 + run)
        ref = build_sequence(rng, table)
        mine_record = body_record()
        assert S.load_sequence(mine_record, ref, index)
        offset = offset_frame(rng)
        state = ft(offset)
        for _ in range(STEPS):
            dt = rng.choice(QUANTA) if rng.random() < 0.6 else rng.uniform(0.0, 0.4)
            before = without_memo(mine_record)
            status, *result = S.sequence_update(mine_record, *tables, dt, *state)
            ref.hook_obj.hooks.clear()
            ref.update(dt, offset)
            counts[status] += 1
            queued = ref.hook_obj.hooks
            assert status == expected_status(queued), run
            assert_memo_holds(mine_record)
            if status == S.STATUS_REFERENCE:
                assert without_memo(mine_record) == before
                assert S.load_sequence(mine_record, ref, index)
            else:
                want = expected_record(ref, index, len(queued))
                assert without_memo(mine_record) == without_memo(want), run
            state = ft(offset)
            if status != S.STATUS_REFERENCE:
                assert same(tuple(result), state), run
    assert counts[S.STATUS_DONE] > RUNS * STEPS // 2 and counts[S.STATUS_ANIM_DONE] > RUNS // 5, counts
    assert counts[S.STATUS_REFERENCE] > 0, counts


def test_empty_sequence_applies_physics_for_the_whole_quantum():
    rng = random.Random(5)
    anims, pos, hooks = S.animation_table([])
    for _ in range(1000):
        seq = Sequence()
        seq.set_velocity(small_vector(rng, 5.0))
        seq.set_omega(small_vector(rng, 2.0))
        record = body_record()
        assert S.load_sequence(record, seq, {})
        before = without_memo(record)
        offset = offset_frame(rng)
        dt = quantum(rng)
        status, *result = S.sequence_update(record, anims, pos, hooks, dt, *ft(offset))
        seq.update(dt, offset)
        assert status == S.STATUS_DONE and same(tuple(result), ft(offset))
        assert without_memo(record) == before
        assert_memo_holds(record)


def test_apply_physics():
    rng = random.Random(6)
    memo = np.zeros(4)  # the turns' terms, kept from case to case
    for _ in range(2000):
        seq = Sequence()
        seq.set_velocity(small_vector(rng, 10.0))
        seq.set_omega(small_vector(rng, 3.0))
        frame = offset_frame(rng)
        dt = rng.choice((1 / 30, -1 / 30, 0.0, -0.0, rng.uniform(-2.0, 2.0)))
        sign = rng.choice((dt, 1.0, -1.0, 0.0, -0.0))
        got = S.apply_physics(tuple(seq.velocity), tuple(seq.omega), *ft(frame), dt, sign, memo)
        seq.apply_physics(frame, dt, sign)
        assert same(got, ft(frame))


# -- the cases the brief names, one by one ----------------------------------------------------------------


def steps(*ys: float) -> list[Frame]:
    return [Frame(Vector3(0.0, y, 0.0)) for y in ys]


def turning(count: int) -> list[Frame]:
    """Steps forward and a little right, each turning further about z."""
    return [Frame(Vector3(0.1, 0.25, 0.0), *z_turn(0.2 * (i + 1))) for i in range(count)]


def z_turn(angle: float) -> tuple[float, float, float, float]:
    """The float32 quaternion of ``angle`` radians about z."""
    return (f32(math.cos(angle / 2)), 0.0, 0.0, f32(math.sin(angle / 2)))


def compare_case(table: list[Animation], seq_factory, dt: float, offset: Frame | None = None) -> int:
    """Play ``seq_factory()`` both ways for ``dt``; returns the status (asserting the rule)."""
    tables, index = S.animation_table(table), S.animation_index(table)
    ref, mine = seq_factory(), seq_factory()
    ref.set_object(HookRecorder())
    offset = offset or Frame()
    record = body_record()
    assert S.load_sequence(record, mine, index)
    before = record.copy()
    ref_offset = offset.copy()
    ref.update(dt, ref_offset)
    status, *result = S.sequence_update(record, *tables, dt, *ft(offset))
    queued = ref.hook_obj.hooks
    assert status == expected_status(queued)
    assert_memo_holds(record)
    if status == S.STATUS_REFERENCE:
        assert without_memo(record) == without_memo(before)
    else:
        assert same(tuple(result), ft(ref_offset))
        assert without_memo(record) == without_memo(expected_record(ref, index, len(queued)))
    return status


def test_named_cases():
    walk = Animation([AnimFrame([Frame()]) for _ in range(8)], turning(8), name="walk")
    still = Animation([AnimFrame([Frame()]) for _ in range(4)], None, name="still")
    link = Animation([AnimFrame([Frame()]) for _ in range(3)], steps(1.0, 2.0, 4.0), name="link")
    hooked = Animation(
        [
            AnimFrame([Frame()], [NOOPHook(direction=d)] if d is not None else [])
            for d in (None, 1, None, -1, None)
        ],
        steps(1, 1, 1, 1, 1),
        name="hooked",
    )
    table = [walk, still, link, hooked]

    def single(anim, framerate, velocity=(0.0, 1.5, 0.0), omega=(0.0, 0.0, 0.5), frame_number=None):
        def make():
            seq = Sequence()
            seq.append_animation(AnimData(anim, framerate=framerate))
            seq.set_velocity(Vector3(*velocity))
            seq.set_omega(Vector3(*omega))
            if frame_number is not None:
                seq.frame_number = frame_number
            return seq

        return make

    def chain(*datas, cycle_from=None, curr=None, frame_number=None):
        def make():
            seq = Sequence()
            for data in datas:
                seq.append_animation(data)
            if cycle_from is not None:
                seq.first_cyclic = seq.anim_list[cycle_from]
            if curr is not None:
                seq.curr_anim = seq.anim_list[curr]
                seq.frame_number = frame_number
            seq.set_velocity(Vector3(0.0, 2.0, 0.0))
            seq.set_omega(Vector3(0.25, 0.0, 1.0))
            return seq

        return make

    done, back, anim_done = S.STATUS_DONE, S.STATUS_REFERENCE, S.STATUS_ANIM_DONE
    # several frames, then the wrap of a single cycle, several times round in one quantum
    assert compare_case(table, single(walk, 30.0), 0.1) == done
    assert compare_case(table, single(walk, 30.0), 1.7) == done
    # frame numbers landing exactly on integers (8 frames/s, quanta of 1/8 s and 1/4 s)
    assert compare_case(table, single(walk, 8.0, frame_number=3.0), 0.125) == done
    assert compare_case(table, single(walk, 8.0, frame_number=6.0), 0.25) == done
    assert compare_case(table, single(walk, 8.0, frame_number=7.0), 0.125) == done
    # reverse playback: from the top, across frames, through the wrap to the top again
    assert compare_case(table, single(walk, -30.0), 0.1) == done
    assert compare_case(table, single(walk, -8.0, frame_number=4.0), 0.5) == done
    assert compare_case(table, single(walk, -12.5), 2.0) == done
    # zero framerate: physics for the whole quantum; tiny quantum: nothing
    assert compare_case(table, single(walk, 0.0), 0.3) == done
    assert compare_case(table, single(walk, 0.0), 1e-5) == done
    # an animation without position frames: physics only
    assert compare_case(table, single(still, 30.0), 0.45) == done
    assert compare_case(table, single(still, -7.5), 0.45) == done
    # a negative quantum plays backwards
    assert compare_case(table, single(walk, 30.0, frame_number=5.5), -0.3) == done
    # a link then the cycle: the link's end queues AnimDone
    link_then_walk = chain(AnimData(link, framerate=30.0), AnimData(walk, framerate=30.0))
    assert compare_case(table, link_then_walk, 0.05) == done  # still in the link
    assert compare_case(table, link_then_walk, 0.5) == anim_done  # crosses into the cycle
    # a cycle of several nodes (the head is first_cyclic): across animations with no AnimDone
    loop = chain(
        AnimData(walk, framerate=30.0),
        AnimData(still, framerate=-20.0),
        AnimData(link, framerate=16.0),
        cycle_from=0,
    )
    assert compare_case(table, loop, 0.9) == done
    assert compare_case(table, loop, 2.0) == done
    # links not yet dropped while play is already in the cycle: apricot shifts the list down
    late = chain(
        AnimData(link, framerate=30.0),
        AnimData(still, framerate=30.0),
        AnimData(walk, framerate=30.0),
        AnimData(walk, framerate=-10.0),
        cycle_from=2,
        curr=3,
        frame_number=5.25,
    )
    assert compare_case(table, late, 0.1) == done
    # frame hooks: forward play meets the forward hook at frame 1, backward play the backward one at 3
    assert compare_case(table, single(hooked, 10.0, frame_number=0.5), 0.04) == done  # 0.5 -> 0.9
    assert compare_case(table, single(hooked, 10.0, frame_number=0.5), 0.1) == done  # crosses frame 0 only
    assert compare_case(table, single(hooked, 10.0, frame_number=1.0), 0.1) == back  # crosses frame 1
    assert compare_case(table, single(hooked, 10.0, frame_number=3.0), 0.1) == done  # 3 forward: BACKWARD
    assert compare_case(table, single(hooked, -10.0, frame_number=2.5), 0.1) == done  # 2 backward: none
    assert compare_case(table, single(hooked, -10.0, frame_number=3.5), 0.1) == back  # 3 backward


def test_numbers_the_reference_raises_on_go_back():
    walk = Animation([AnimFrame([Frame()]) for _ in range(4)], steps(1, 1, 1, 1))
    tables, index = S.animation_table([walk]), S.animation_index([walk])
    for frame_number, dt in ((math.nan, 0.1), (1.0, math.nan), (1.0, math.inf), (math.inf, 0.1)):
        seq = Sequence()
        seq.append_animation(AnimData(walk, framerate=10.0))
        seq.frame_number = frame_number
        record = body_record()
        assert S.load_sequence(record, seq, index)
        before = record.tobytes()
        with pytest.raises((ValueError, OverflowError)):
            seq.update(dt, Frame())
        status, *_ = S.sequence_update(record, *tables, dt, *ft(Frame()))
        assert status == S.STATUS_REFERENCE and record.tobytes() == before


def test_a_plain_body_row_works_too(quiet_world):
    """The engine passes ``bodies[i]`` of a plain structured array (np.void), not a recarray row."""
    table, tables, index = quiet_world
    bodies = np.zeros(3, dtype=BODY)
    seq = build_sequence(random.Random(7), table)
    seq.first_cyclic = seq.anim_list[0]
    seq.set_object(HookRecorder())
    assert S.load_sequence(bodies[1], seq, index)
    status, *result = S.sequence_update(bodies[1], *tables, 0.05, *ft(Frame()))
    offset = Frame()
    seq.update(0.05, offset)
    if status != S.STATUS_REFERENCE:
        assert same(tuple(result), ft(offset))
        want = expected_record(seq, index, len(seq.hook_obj.hooks))
        assert bodies[1].tobytes() == want.tobytes()
    assert not bodies[0].tobytes().strip(b"\0") and not bodies[2].tobytes().strip(b"\0")


def test_a_turned_over_range_never_ends():
    """A negative ``multiply_framerate`` swaps low and high; the reference's next update then
    never returns (each pass hands back more time than it played). The kernel gives it back."""
    walk = Animation([AnimFrame([Frame()]) for _ in range(6)], steps(1, 1, 1, 1, 1, 1))
    tables, index = S.animation_table([walk]), S.animation_index([walk])
    for multiplier in (-1.0, -0.5):
        seq = Sequence()
        seq.append_animation(AnimData(walk, framerate=30.0))
        seq.update(0.05, Frame())
        seq.multiply_cyclic_animation_framerate(multiplier)
        assert seq.anim_list[0].low_frame > seq.anim_list[0].high_frame
        record = body_record()
        assert S.load_sequence(record, seq, index)
        before = record.tobytes()
        status, *_ = S.sequence_update(record, *tables, 0.05, *ft(Frame()))
        assert status == S.STATUS_REFERENCE and record.tobytes() == before

        class Hung(Exception):
            pass

        def hung(*_):
            raise Hung

        previous = signal.signal(signal.SIGALRM, hung)
        signal.setitimer(signal.ITIMER_REAL, 0.5)
        try:
            with pytest.raises(Hung):
                seq.update(0.05, Frame())
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
