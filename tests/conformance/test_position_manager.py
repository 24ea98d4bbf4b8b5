"""PositionManager: the order of its sub-managers and the body glue, against retail.

Decompiled: cpmanager/CPositionManager.c (adjust_offset acclient.c:388286, UseTime 388266) and
cphysobj/CPhysicsObj.c (MakePositionManager 317430, InterpolateTo 317580, ConstrainTo 317590).
"""

from __future__ import annotations

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.managers.constraint import ConstraintManager
from acphys.managers.interpolation import InterpolationManager
from acphys.managers.position import PositionManager
from acphys.managers.sticky import StickyManager
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32
from support import LANDBLOCK, place

DT = 1.0 / 30.0
GROUND = 50.0


def _recording(base: type, name: str, log: list[str]) -> type:
    """A subclass of a real manager that logs its adjust_offset/use_time calls, then runs them."""

    class Recording(base):
        __slots__ = ()

        def adjust_offset(self, offset: Frame, quantum: float) -> None:
            log.append(f"{name}.adjust_offset")
            super().adjust_offset(offset, quantum)

        def use_time(self) -> None:
            log.append(f"{name}.use_time")
            super().use_time()

    return Recording


@pytest.fixture
def body(world):
    world.set_flat_ground(LANDBLOCK, GROUND)
    return place(world, on_ground=True, origin=(40.0, 100.0, GROUND))


class TestOrder:
    def test_adjust_offset_runs_interpolation_then_sticky_then_constraint(self, body):
        # acclient.c:388295-388303.
        log: list[str] = []
        manager = body.make_position_manager()
        manager.constraint_manager = _recording(ConstraintManager, "constraint", log)(body)
        manager.sticky_manager = _recording(StickyManager, "sticky", log)(body)
        manager.interpolation_manager = _recording(InterpolationManager, "interpolation", log)(body)
        body.update_object_internal(DT)
        assert log[:3] == ["interpolation.adjust_offset", "sticky.adjust_offset", "constraint.adjust_offset"]

    def test_use_time_runs_interpolation_then_sticky(self, body):
        # acclient.c:388274-388283; the constraint manager's UseTime (388278) is an empty function.
        log: list[str] = []
        manager = body.make_position_manager()
        manager.sticky_manager = _recording(StickyManager, "sticky", log)(body)
        manager.interpolation_manager = _recording(InterpolationManager, "interpolation", log)(body)
        manager.use_time()
        assert log == ["interpolation.use_time", "sticky.use_time"]

    def test_the_order_shows_in_the_offset(self, world, body):
        # Interpolation writes a glide east; sticky then overwrites the origin with a step north to
        # its target; constraint then scales the sticky step. Any other order gives another result.
        body.interpolate_to(_moved(body, 3.0, 0.0), False)
        manager = body.position_manager
        manager.stick_to(0x7FFF0000, 0.0, 0.0)
        manager.sticky_manager.handle_update_target(_ok(0x7FFF0000, _moved(body, 0.0, 5.0)))
        body.constrain_to(_moved(body, 0.0, 11.0), 5.0, 20.0)  # scale (20 - 11) / 15 = 0.6
        offset = Frame()
        manager.adjust_offset(offset, DT)
        # sticky: 20 m/s * DT north, stored once (acclient.c:388589), then times the float scale
        # f32(0.6) (389493-389495), stored again.
        assert offset.origin.x == 0.0
        assert offset.origin.y == f32(f32(20.0 * DT) * f32(9.0 / 15.0))
        assert offset.origin.y == pytest.approx(20.0 * DT * 0.6, abs=1e-7)


def _moved(body, dx: float, dy: float):
    p = body.position.copy()
    p.frame.origin.set(p.frame.origin + Vector3(dx, dy, 0.0))
    return p


def _ok(object_id: int, p):
    from acphys.managers.target import TargetInfo, TargetStatus

    return TargetInfo(object_id, TargetStatus.OK, p)


class TestBody:
    def test_get_position_manager_makes_one_and_wakes_the_body(self, body):
        # MakePositionManager: create, and a non-static body becomes ACTIVE (acclient.c:317436-317448).
        body.transient_state &= ~TS.ACTIVE
        manager = body.get_position_manager()
        assert isinstance(manager, PositionManager)
        assert body.transient_state & TS.ACTIVE
        assert body.get_position_manager() is manager

    def test_a_static_body_stays_asleep(self, body):
        body.state |= PS.STATIC
        body.transient_state &= ~TS.ACTIVE
        body.make_position_manager()
        assert not body.transient_state & TS.ACTIVE

    def test_sub_managers_are_made_on_first_use(self, body):
        manager = body.make_position_manager()
        assert manager.interpolation_manager is None
        assert manager.get_sticky_object_id() == 0  # acclient.c:388358-388361
        assert not manager.is_interpolating()  # 388478-388481
        manager.unstick()
        manager.unconstrain()
        manager.stop_interpolating()
        assert manager.sticky_manager is None and manager.constraint_manager is None
        body.interpolate_to(_moved(body, 3.0, 0.0), False)
        assert manager.interpolation_manager is not None and body.is_interpolating()
        body.stop_interpolating()
        assert not body.is_interpolating()

    @pytest.mark.parametrize(
        ("cell", "is_player", "start", "limit"),
        [
            (0x0004, False, 10.0, 50.0),
            (0x0004, True, 10.0, 50.0),
            (0x0100, False, 5.0, 20.0),
            (0x0100, True, 5.0, 20.0),
        ],
    )
    def test_constraint_distances(self, world, body, cell, is_player, start, limit):
        # GetStartConstraintDistance (acclient.c:315884) and GetMaxConstraintDistance (315908).
        body.position.objcell_id = (LANDBLOCK << 16) | cell
        if is_player:
            world.player = body
        assert body.get_start_constraint_distance() == start
        assert body.get_max_constraint_distance() == limit
