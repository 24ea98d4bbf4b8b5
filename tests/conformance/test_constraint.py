"""ConstraintManager: the leash that damps a body's offsets, against retail.

Decompiled: cpmanager/CConstraintManager.c (adjust_offset acclient.c:389477, ConstrainTo 389513,
IsFullyConstrained 389416, UnConstrain 389410).
"""

from __future__ import annotations

import pytest

from acphys.flags import TransientState as TS
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32
from support import LANDBLOCK, place

DT = 1.0 / 30.0


@pytest.fixture
def body(world):
    world.set_flat_ground(LANDBLOCK, 50.0)
    return place(world, on_ground=True, origin=(40.0, 100.0, 50.0))


def _anchor(body, dx: float) -> Position:
    """The body's position moved ``dx`` along +x (stored float32, as a Vector3 component is)."""
    p = body.position.copy()
    p.frame.origin.x = f32(p.frame.origin.x + dx)
    return p


def _step(body, x: float) -> Frame:
    """Run one offset of ``x`` metres along +x through the position manager; return it."""
    offset = Frame()
    offset.origin.set(Vector3(x, 0.0, 0.0))
    body.position_manager.adjust_offset(offset, DT)
    return offset


class TestDamping:
    def test_constrain_to_starts_from_the_distance_to_the_anchor(self, body):
        # constraint_pos_offset = Position::distance(p, body) (acclient.c:389526).
        body.constrain_to(_anchor(body, 3.0), 5.0, 20.0)
        assert body.position_manager.constraint_manager.constraint_pos_offset == pytest.approx(3.0)

    def test_below_start_the_offset_passes_and_counts(self, body):
        # 3 <= start 5: no scaling (389491); the length is added (389506-389509).
        body.constrain_to(_anchor(body, 3.0), 5.0, 20.0)
        assert _step(body, 1.0).origin.x == 1.0
        assert body.position_manager.constraint_manager.constraint_pos_offset == pytest.approx(4.0)

    def test_between_start_and_max_the_offset_shrinks_linearly(self, body):
        # travelled 8, start 5, max 20: scale (20 - 8) / (20 - 5) = 0.8 (389493-389495); the
        # total then grows by the *scaled* length, 0.8.
        body.constrain_to(_anchor(body, 8.0), 5.0, 20.0)
        assert _step(body, 1.0).origin.x == pytest.approx(0.8)
        assert body.position_manager.constraint_manager.constraint_pos_offset == pytest.approx(8.8)
        # Next: (20 - 8.8) / 15 = 0.74666...
        assert _step(body, 1.0).origin.x == pytest.approx(11.2 / 15.0)

    @pytest.mark.parametrize(("travelled", "expected"), [(5.0, 1.0), (11.0, 0.6), (17.0, 0.2), (19.7, 0.02)])
    def test_the_scale_is_linear_in_the_distance_travelled(self, body, travelled, expected):
        # (max - travelled) / (max - start), start exclusive (389491).
        body.constrain_to(_anchor(body, travelled), 5.0, 20.0)
        # The anchor sits at float32(40 + travelled), the distance is a float field (389526) and
        # the scale a float argument (389493-389495): for 19.7 the total is f32(19.7) and the
        # scale 0.0199999..., not 0.02.
        total = f32(f32(40.0 + travelled) - 40.0)
        scale = f32((20.0 - total) / 15.0)
        assert _step(body, 1.0).origin.x == scale == pytest.approx(expected, abs=1e-7)

    @pytest.mark.parametrize("travelled", [20.0, 35.0])
    def test_at_or_beyond_max_the_offset_vanishes(self, body, travelled):
        # Not below max: the origin is zeroed (389489, 389500-389503).
        body.constrain_to(_anchor(body, travelled), 5.0, 20.0)
        offset = _step(body, 1.0)
        assert offset.origin.exactly_equals(Vector3())

    def test_the_rotation_is_never_damped(self, body):
        body.constrain_to(_anchor(body, 30.0), 5.0, 20.0)
        offset = Frame()
        offset.set_heading(90.0)
        body.position_manager.adjust_offset(offset, DT)
        assert offset.get_heading() == pytest.approx(90.0)

    def test_airborne_offsets_pass_in_full_but_still_count(self, body):
        # Contact gates only the damping (389487); the accumulation is outside it (389506).
        body.transient_state &= ~TS.CONTACT
        body.constrain_to(_anchor(body, 30.0), 5.0, 20.0)
        assert _step(body, 1.0).origin.x == 1.0
        assert body.position_manager.constraint_manager.constraint_pos_offset == pytest.approx(31.0)

    def test_the_total_measures_distance_travelled_not_distance_from_the_anchor(self, body):
        # Walking back towards the anchor still adds length: the leash only tightens.
        body.constrain_to(_anchor(body, 3.0), 5.0, 20.0)
        _step(body, 1.0)
        _step(body, -1.0)
        assert body.position_manager.constraint_manager.constraint_pos_offset == pytest.approx(5.0)

    def test_a_constrained_body_walking_in_the_world_slows_and_stops(self, world, body):
        # End to end through UpdatePositionInternal: root motion of 30 m/s (1 m a step).
        body.get_minterp()  # a movement manager keeps the grounded body active
        body.constrain_to(body.position, 0.0, 3.0)
        body.part_array.sequence.set_velocity(Vector3(0.0, 30.0, 0.0))
        start = body.position.frame.origin.y
        moved = []
        for _ in range(6):
            before = body.position.frame.origin.y
            body.update_object_internal(DT)
            moved.append(body.position.frame.origin.y - before)
        # 1 m at scale 1 (travelled 0), then (3-1)/3, then (3 - 1 - 2/3)/3 ... never past 3 m.
        # The body's origin is float32 (an ulp is 7.6e-6 near y = 100) and the transition stores
        # its sub-steps, so each move is the scaled offset within a few ulps.
        assert moved[0] == pytest.approx(1.0, abs=2e-5)
        assert moved[1] == pytest.approx(2.0 / 3.0, abs=2e-5)
        assert moved[2] == pytest.approx(4.0 / 9.0, abs=2e-5)
        assert body.position.frame.origin.y - start < 3.0


class TestFullyConstrained:
    def test_fully_constrained_above_nine_tenths_of_max(self, body):
        # max * 0.9 < constraint_pos_offset (acclient.c:389418).
        body.constrain_to(_anchor(body, 18.0), 5.0, 20.0)
        assert not body.is_fully_constrained()
        _step(body, 0.5)  # scale (20 - 18) / 15: +0.0667
        assert body.is_fully_constrained()

    def test_no_constraint_manager_is_not_constrained(self, body):
        # PositionManager::IsFullyConstrained without one: 0 (acclient.c:388390).
        assert not body.is_fully_constrained()

    def test_unconstrain_stops_the_damping_but_keeps_the_total(self, body):
        # UnConstrain only clears is_constrained (389412); IsFullyConstrained ignores it.
        body.constrain_to(_anchor(body, 25.0), 5.0, 20.0)
        body.position_manager.unconstrain()
        assert _step(body, 1.0).origin.x == 1.0
        assert body.is_fully_constrained()


def test_non_finite_distances_are_refused(body):
    with pytest.raises(ValueError, match="max_distance"):
        body.constrain_to(body.position, 5.0, float("inf"))
