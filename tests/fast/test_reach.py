"""How far a reference-path update can reach (:mod:`acphys.fast.reach`): the bounds the partial
write-back rests on, against what the reference engine actually does."""

from __future__ import annotations

import math
import random

import pytest

import acphys
from acphys.constants import BLOCK_LENGTH
from acphys.fast.reach import (
    PLACEMENT_MARGIN,
    ROUNDING_SLACK,
    SWEEP_MARGIN,
    cells_under,
    global_xy,
    reads_only_its_sweep,
    root_motion_bound,
    sweep_box,
    update_boxes,
)
from acphys.fast.world_arrays import build_world_arrays
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.sequence import Sequence
from acphys.precision import f32

FLAT = '[scenario]\nname = "r"\nduration = 1.0\n[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
HUMAN = '[[body]]\nname = "h"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 50.0]\non_ground = true\n'


def _animation(steps: list[tuple[float, float, float]]) -> Animation:
    return Animation([AnimFrame([Frame()]) for _ in steps], [Frame(Vector3(*step)) for step in steps])


def test_the_root_motion_bound_by_hand() -> None:
    # One node at 30 frames/s, position frames of 0.1 and 0.2 m, velocity 3 m/s, a 1/30-s quantum:
    # at most 1·30/30 + 2 = 3 advances, 1 + 1 + 2·3 = 8 frames of at most 0.2 + 3/30 m each, and
    # the velocity over the quantum: 8 · 0.3 + 0.1 = 2.5 m (and a thousandth for roundings).
    seq = Sequence()
    seq.append_animation(AnimData(_animation([(0.1, 0.0, 0.0), (0.0, 0.2, 0.0)]), framerate=30.0))
    seq.velocity = Vector3(0.0, 3.0, 0.0)
    assert root_motion_bound(seq, 1 / 30) == pytest.approx(
        (8 * (f32(0.2) + 0.1) + 0.1) * ROUNDING_SLACK, rel=1e-12
    )
    # no animation: the velocity over the quantum
    idle = Sequence()
    idle.velocity = Vector3(0.0, 3.0, 4.0)
    assert root_motion_bound(idle, 0.2) == pytest.approx(ROUNDING_SLACK)


def test_a_turned_over_frame_range_is_not_bounded() -> None:
    seq = Sequence()
    seq.append_animation(AnimData(_animation([(0.1, 0.0, 0.0)] * 4), framerate=30.0))
    seq.anim_list[0].low_frame, seq.anim_list[0].high_frame = 3, 1  # what a negative multiply leaves
    assert root_motion_bound(seq, 0.1) is None


def _random_sequence(rng: random.Random) -> Sequence:
    seq = Sequence()
    for _ in range(rng.randint(1, 4)):
        count = rng.randint(1, 6)
        size = rng.choice((0.0, 0.05, 0.3, 2.0))
        steps = [tuple(f32(rng.uniform(-size, size)) for _ in range(3)) for _ in range(count)]
        animation = _animation(steps) if rng.random() < 0.8 else Animation([AnimFrame([Frame()])] * count)
        rate = rng.choice((30.0, 10.0, 16.0, -10.0, -30.0, 0.0, 2.0, 1e-4, 120.0, f32(rng.uniform(-60, 60))))
        seq.append_animation(AnimData(animation, rng.randint(-1, count), rng.randint(-1, count), rate))
    nodes = seq.anim_list
    seq.first_cyclic = rng.choice(nodes)
    seq.curr_anim = rng.choice(nodes)
    seq.frame_number = float(rng.uniform(seq.curr_anim.low_frame, seq.curr_anim.high_frame + 1))
    seq.velocity = Vector3(*(f32(rng.uniform(-5.0, 5.0)) for _ in range(3)))
    if rng.random() < 0.5:
        seq.omega = Vector3(0.0, 0.0, f32(rng.uniform(-3.0, 3.0)))
    return seq


def test_no_sequence_plays_farther_than_its_bound() -> None:
    """3,000 random sequences (links and cycles, framerates forward, backward, zero and tiny, large
    position frames, turning) each played for a random quantum of one step: the root motion the
    reference's ``update`` composes is never longer than the bound."""
    rng = random.Random(14)
    checked = 0
    for _ in range(3000):
        seq = _random_sequence(rng)
        quantum = rng.choice((1 / 30, 0.2, 0.05, 1e-4, rng.uniform(0.0, 0.2)))
        bound = root_motion_bound(seq, quantum)
        if bound is None:
            continue
        offset = Frame()
        seq.update(quantum, offset)
        assert offset.origin.length() <= bound, (quantum, bound, offset.origin)
        checked += 1
    assert checked > 2500


def test_only_a_body_reading_through_its_sweep_alone_is_bounded() -> None:
    sim = acphys.parse_scenario(FLAT + HUMAN, source="r.toml")
    body = sim.body("h")
    assert reads_only_its_sweep(body, None)
    assert update_boxes(body, 1.0, 1 / 30, None) is not None
    assert update_boxes(body, 1.0, 0.25, None) is None  # more than one quantum
    body.observer = print
    assert not reads_only_its_sweep(body, None) and reads_only_its_sweep(body, print)
    body.observer = None
    body.stick_to_object(body.id)  # a sticky manager reads its target
    assert not reads_only_its_sweep(body, None)
    assert update_boxes(body, 1.0, 1 / 30, None) is None


def test_the_update_box_of_a_standing_human() -> None:
    # At rest (no velocity, no sequence velocity, the idle cycle's position frames are zero):
    # gravity over the quantum (9.8 · q²) alone, widened by the reach and the margin.
    sim = acphys.parse_scenario(FLAT + HUMAN, source="r.toml")
    body = sim.body("h")
    quantum = 1 / 30
    boxes = update_boxes(body, 1.5, quantum, None)
    assert boxes is not None and len(boxes) == 1
    box = boxes[0]
    x, y = 0xA9 * BLOCK_LENGTH + 96.0, 0xB4 * BLOCK_LENGTH + 96.0
    widen = 1.5 + f32(9.8000002) * quantum * quantum + SWEEP_MARGIN
    assert box == pytest.approx((x - widen, y - widen, x + widen, y + widen), abs=1e-6)


def test_a_sweep_box_is_its_path_widened_by_reach_length_and_margin() -> None:
    box = sweep_box((100.0, 200.0), (103.0, 204.0), 0.5)
    widen = 0.5 + 5.0 + SWEEP_MARGIN
    assert box == (100.0 - widen, 200.0 - widen, 103.0 + widen, 204.0 + widen)
    assert sweep_box((100.0, 200.0), (math.nan, 204.0), 0.5) is None
    assert global_xy(0xA9B40001, 1.0, 2.0) == (0xA9 * 192.0 + 1.0, 0xB4 * 192.0 + 2.0)


def test_the_cells_under_a_box_are_the_known_ones() -> None:
    sim = acphys.parse_scenario(FLAT + HUMAN, source="r.toml")
    arrays = build_world_arrays(sim.world, sim.bodies)
    x0, y0 = 0xA9 * BLOCK_LENGTH, 0xB4 * BLOCK_LENGTH
    # local (10..30) x (10..30) m: cells 0xA9B40001, 0002, 0009, 000A, kernel cells 0, 1, 8, 9
    assert cells_under(arrays, [(x0 + 10.0, y0 + 10.0, x0 + 30.0, y0 + 30.0)]) == [0, 1, 8, 9]
    # across the landblock's south-west corner: only its own cell is known
    assert cells_under(arrays, [(x0 - 5.0, y0 - 5.0, x0 + 5.0, y0 + 5.0)]) == [0]
    # more than 64 cells: not a partial write-back
    assert cells_under(arrays, [(x0, y0, x0 + 200.0, y0 + 200.0)]) is None


def test_an_interpolating_body_reaches_along_its_glide_and_to_its_last_node() -> None:
    # Interpolating 3 m east: the glide may take the whole way this step (so the box about the
    # body widens by 3 m more than at rest), and a blip would place it on the node (a box there).
    sim = acphys.parse_scenario(FLAT + HUMAN, source="r.toml")
    body = sim.body("h")
    node = body.position.copy()
    node.frame.origin.x += 3.0
    body.interpolate_to(node, True)
    assert len(body.position_manager.interpolation_manager.position_queue) == 1
    quantum = 1 / 30
    boxes = update_boxes(body, 1.5, quantum, None)
    assert boxes is not None and len(boxes) == 2
    x, y = 0xA9 * BLOCK_LENGTH + 96.0, 0xB4 * BLOCK_LENGTH + 96.0
    widen = 1.5 + f32(9.8000002) * quantum * quantum + 3.0 + SWEEP_MARGIN
    assert boxes[0] == pytest.approx((x - widen, y - widen, x + widen, y + widen), abs=1e-5)
    m = 1.5 + PLACEMENT_MARGIN
    assert boxes[1] == pytest.approx((x + 3.0 - m, y - m, x + 3.0 + m, y + m))
