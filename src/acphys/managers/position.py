"""``PositionManager``: the three offset managers behind ``UpdatePositionInternal``.

The body hands each step's offset frame to ``adjust_offset``, which lets the
interpolation, sticky and constraint managers rewrite it, in that order. Each
sub-manager is created by the first request that needs it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.managers.constraint import ConstraintManager
from acphys.managers.interpolation import InterpolationManager
from acphys.managers.sticky import StickyManager

if TYPE_CHECKING:
    from acphys.managers.target import TargetInfo
    from acphys.math.frame import Frame
    from acphys.math.position import Position
    from acphys.physics_obj import PhysicsObj


class PositionManager:
    """Retail ``PositionManager``: owns the interpolation, sticky and constraint managers.

    Retail: PositionManager::Create @ 0x005552D0 (acclient.c:388404)
    """

    __slots__ = ("constraint_manager", "interpolation_manager", "physics_obj", "sticky_manager")

    def __init__(self, physics_obj: PhysicsObj) -> None:
        self.physics_obj = physics_obj
        self.interpolation_manager: InterpolationManager | None = None
        self.sticky_manager: StickyManager | None = None
        self.constraint_manager: ConstraintManager | None = None

    def use_time(self) -> None:
        """Tick interpolation, then sticky (the constraint manager's UseTime is empty).

        Retail: PositionManager::UseTime @ 0x00555160 (acclient.c:388266)
        """
        if self.interpolation_manager is not None:
            self.interpolation_manager.use_time()
        if self.sticky_manager is not None:
            self.sticky_manager.use_time()

    def adjust_offset(self, offset: Frame, quantum: float) -> None:
        """Let interpolation, then sticky, then constraint rewrite the step's offset.

        Retail: PositionManager::adjust_offset @ 0x00555190 (acclient.c:388286)
        """
        if self.interpolation_manager is not None:
            self.interpolation_manager.adjust_offset(offset, quantum)
        if self.sticky_manager is not None:
            self.sticky_manager.adjust_offset(offset, quantum)
        if self.constraint_manager is not None:
            self.constraint_manager.adjust_offset(offset, quantum)

    def interpolate_to(self, p: Position, keep_heading: bool) -> None:
        """Retail: PositionManager::InterpolateTo @ 0x005551F0 (acclient.c:388316)"""
        if self.interpolation_manager is None:
            self.interpolation_manager = InterpolationManager(self.physics_obj)
        self.interpolation_manager.interpolate_to(p, keep_heading)

    def stop_interpolating(self) -> None:
        """Retail: PositionManager::StopInterpolating @ 0x00555220 (acclient.c:388331)"""
        if self.interpolation_manager is not None:
            self.interpolation_manager.stop_interpolating()

    def is_interpolating(self) -> bool:
        """Retail: PositionManager::IsInterpolating @ 0x005553B0 (acclient.c:388475)"""
        return self.interpolation_manager is not None and self.interpolation_manager.is_interpolating()

    def stick_to(self, object_id: int, radius: float, height: float) -> None:
        """Retail: PositionManager::StickTo @ 0x00555230 (acclient.c:388341)"""
        if self.sticky_manager is None:
            self.sticky_manager = StickyManager(self.physics_obj)
        self.sticky_manager.stick_to(object_id, radius, height)

    def unstick(self) -> None:
        """Let go of the sticky target (the sticky manager's exit-world handling).

        Retail: PositionManager::UnStick @ 0x005551E0 (acclient.c:388306)
        """
        if self.sticky_manager is not None:
            self.sticky_manager.handle_exit_world()

    def get_sticky_object_id(self) -> int:
        """The id the body is stuck to, 0 for none.

        Retail: PositionManager::GetStickyObjectID @ 0x00555270 (acclient.c:388352)
        """
        return self.sticky_manager.target_id if self.sticky_manager is not None else 0

    def constrain_to(self, p: Position, start_distance: float, max_distance: float) -> None:
        """Retail: PositionManager::ConstrainTo @ 0x00555280 (acclient.c:388366)"""
        if self.constraint_manager is None:
            self.constraint_manager = ConstraintManager(self.physics_obj)
        self.constraint_manager.constrain_to(p, start_distance, max_distance)

    def unconstrain(self) -> None:
        """Retail: PositionManager::UnConstrain @ 0x005552B0 (acclient.c:388380)"""
        if self.constraint_manager is not None:
            self.constraint_manager.unconstrain()

    def is_fully_constrained(self) -> bool:
        """Retail: PositionManager::IsFullyConstrained @ 0x005552C0 (acclient.c:388390)"""
        return self.constraint_manager is not None and self.constraint_manager.is_fully_constrained()

    def handle_update_target(self, target_info: TargetInfo) -> None:
        """Pass a target-manager report to the sticky manager, if any.

        Retail: PositionManager::HandleUpdateTarget @ 0x005553D0 (acclient.c:388487)
        """
        if self.sticky_manager is not None:
            self.sticky_manager.handle_update_target(target_info)
