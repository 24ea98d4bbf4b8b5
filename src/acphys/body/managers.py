"""What the motion code and the managers ask of a body: size, targets, position-manager requests."""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.attachments import PositionManager, TargetManager
from acphys.flags import PhysicsState, TransientState
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.managers.detection import DetectionInfo
    from acphys.managers.target import TargetInfo

#: The error ``teleport_hook`` cancels a move-to with (acclient.c:322249; ACE's ``WeenieError.ITeleported``).
TELEPORT_MOVETO_ERROR = 0x3C


class ManagerRequests:
    """Target, sticky, interpolation and constraint requests (part of :class:`PhysicsObj`)."""

    # -- what the motion code asks of the body and its managers ----------------------------

    def get_velocity(self) -> Vector3:
        """The velocity the last step actually moved at (``cached_velocity``, a copy), not ``velocity``.

        Retail: CPhysicsObj::get_velocity @ 0x005113C0 (acclient.c:318565)
        """
        return self.cached_velocity.copy()

    def get_radius(self) -> float:
        """Retail: CPhysicsObj::GetRadius @ 0x0050E9C0 (acclient.c:315672)"""
        return self.part_array.get_radius() if self.part_array is not None else 0.0

    def get_height(self) -> float:
        """Retail: CPhysicsObj::GetHeight @ 0x0050E9E0 (acclient.c:315686)"""
        return self.part_array.get_height() if self.part_array is not None else 0.0

    def is_interpolating(self) -> bool:
        """Retail: CPhysicsObj::IsInterpolating @ 0x0050EB50 (acclient.c:315846)"""
        return self.position_manager is not None and bool(self.position_manager.is_interpolating())

    def _make_target_manager(self) -> TargetManager:
        """The target manager, created first when the body has none (inline in set_target and
        add_voyeur, acclient.c:315999-316006 and 316064-316071)."""
        if self.target_manager is None:
            from acphys.managers.target import TargetManager as RetailTargetManager

            self.target_manager = RetailTargetManager(self)
        return self.target_manager

    def set_target(self, context_id: int, object_id: int, radius: float, quantum: float) -> None:
        """Track ``object_id`` through the target manager (made here when the body has none).

        ``radius`` is a ``float`` parameter (``quantum`` a double).

        Retail: CPhysicsObj::set_target @ 0x0050ED30 (acclient.c:315991)
        """
        self._make_target_manager().set_target(context_id, object_id, f32(radius), quantum)

    def clear_target(self) -> None:
        """Retail: CPhysicsObj::clear_target @ 0x0050ED90 (acclient.c:316011)"""
        if self.target_manager is not None:
            self.target_manager.clear_target()

    def get_target_quantum(self) -> float:
        """Retail: CPhysicsObj::get_target_quantum @ 0x0050EDC0 (acclient.c:316031)"""
        manager = self.target_manager
        if manager is None or manager.target_info is None:
            return 0.0
        return manager.target_info.quantum

    def set_target_quantum(self, new_quantum: float) -> None:
        """Retail: CPhysicsObj::set_target_quantum @ 0x0050EDA0 (acclient.c:316021)"""
        if self.target_manager is not None:
            self.target_manager.set_target_quantum(new_quantum)

    def add_voyeur(self, object_id: int, radius: float, quantum: float) -> None:
        """Let ``object_id`` track this body (the target manager is made here when missing).
        Retail's parameters are floats, so ``radius`` and ``quantum`` reach the voyeur table
        narrowed to float32.

        Retail: CPhysicsObj::add_voyeur @ 0x0050EE00 (acclient.c:316056)
        """
        self._make_target_manager().add_voyeur(object_id, f32(radius), f32(quantum))

    def remove_voyeur(self, object_id: int) -> bool:
        """Retail: CPhysicsObj::remove_voyeur @ 0x0050EE50 (acclient.c:316076)"""
        return self.target_manager is not None and self.target_manager.remove_voyeur(object_id)

    def receive_target_update(self, info: TargetInfo) -> None:
        """Retail: CPhysicsObj::receive_target_update @ 0x0050EDE0 (acclient.c:316046)"""
        if self.target_manager is not None:
            self.target_manager.receive_update(info)

    def receive_detection_update(self, info: DetectionInfo) -> None:
        """A cell's voyeur report for this body's global detection cylinder; a body with a detection
        manager wakes up (non-static: made active, ``update_time`` resynced to ``Timer::cur_time``
        when it was not).

        Retail: CPhysicsObj::receive_detection_update @ 0x005105D0 (acclient.c:317646)
        """
        if self.detection_manager is None:
            return
        self.detection_manager.receive_detection_update(info)
        if not self._state & PhysicsState.STATIC:
            if not self._transient_state & TransientState.ACTIVE:
                self.update_time = self.world.cur_time
            self._transient_state |= TransientState.ACTIVE

    def handle_update_target(self, target_info: TargetInfo) -> None:
        """Pass a target report (a copy each) to the movement and position managers; reports with a
        non-zero context id are not for them.

        Retail: CPhysicsObj::HandleUpdateTarget @ 0x00512BC0 (acclient.c:319966)
        """
        if target_info.context_id:
            return
        if self.movement_manager is not None:
            self.movement_manager.handle_update_target(target_info.copy())
        if self.position_manager is not None:
            self.position_manager.handle_update_target(target_info.copy())

    def exit_world(self) -> None:
        """Leaving the world: pending motions retire (part array, then movement manager), the stick
        ends, the target is cleared and voyeurs hear ``ExitWorld``, the global detection cylinder
        (context 0) is queued for deletion, and every object collision ends.

        Retail: CPhysicsObj::exit_world @ 0x00514E60 (acclient.c:322204)
        """
        from acphys.managers.target import TargetStatus

        if self.part_array is not None:
            self.part_array.handle_exit_world()
        if self.movement_manager is not None:
            self.movement_manager.handle_exit_world()
        if self.position_manager is not None:
            self.position_manager.unstick()
        if self.target_manager is not None:
            self.target_manager.clear_target()
            self.target_manager.notify_voyeur_of_event(TargetStatus.EXIT_WORLD)
        if self.detection_manager is not None:
            self.detection_manager.destroy_detection_cylsphere(0)
        self.report_collision_end(True)

    def teleport_hook(self, hide: bool) -> None:
        """A teleport: the move-to is cancelled (error 0x3C), the stick, interpolation and constraint
        end, the target is cleared and voyeurs hear ``Teleported``, and every object collision ends.
        ``hide`` is unused, as in retail.

        Retail: CPhysicsObj::teleport_hook @ 0x00514ED0 (acclient.c:322236)
        """
        from acphys.managers.target import TargetStatus

        if self.movement_manager is not None:
            self.movement_manager.cancel_move_to(TELEPORT_MOVETO_ERROR)
        if self.position_manager is not None:
            self.position_manager.unstick()
            self.position_manager.stop_interpolating()
            self.position_manager.unconstrain()
        if self.target_manager is not None:
            self.target_manager.clear_target()
            self.target_manager.notify_voyeur_of_event(TargetStatus.TELEPORTED)
        self.report_collision_end(True)

    def make_position_manager(self) -> PositionManager:
        """Create the position manager if the body has none; a non-static body becomes active.

        Retail: CPhysicsObj::MakePositionManager @ 0x00510210 (acclient.c:317430)
        """
        if self.position_manager is None:
            from acphys.managers.position import PositionManager as RetailPositionManager

            self.position_manager = RetailPositionManager(self)
        self._activate_for_movement()
        return self.position_manager

    def get_position_manager(self) -> PositionManager:
        """The body's position manager, made first when the body has none.

        Retail: CPhysicsObj::get_position_manager @ 0x00512130 (acclient.c:319308)
        """
        return self.make_position_manager()

    def unstick_from_object(self) -> None:
        """Let go of a sticky target (through the position manager, if any).

        Retail: CPhysicsObj::unstick_from_object @ 0x0050EAE0 (acclient.c:315797)
        """
        if self.position_manager is not None:
            self.position_manager.unstick()

    def interpolate_to(self, p: Position, keep_heading: bool) -> None:
        """Glide to a server position (``keep_heading``: keep facing as now).

        Retail: CPhysicsObj::InterpolateTo @ 0x005104F0 (acclient.c:317580)
        """
        self.make_position_manager().interpolate_to(p, keep_heading)

    def stop_interpolating(self) -> None:
        """Retail: CPhysicsObj::StopInterpolating @ 0x0050EB40 (acclient.c:315836)"""
        if self.position_manager is not None:
            self.position_manager.stop_interpolating()

    def stick_to_object(self, object_id: int) -> None:
        """Stick to ``object_id``'s top-level object (its parent, if parented), with its radius and
        height (both passed as ``float``); an unknown id only makes the position manager.

        Retail: CPhysicsObj::stick_to_object @ 0x005127E0 (acclient.c:319724)
        """
        manager = self.make_position_manager()
        target = self.world.get_object(object_id)
        if target is None:
            return
        if target.parent is not None:
            target = target.parent
        manager.stick_to(target.id, f32(target.get_radius()), f32(target.get_height()))

    def get_sticky_object_id(self) -> int:
        """Retail: CPhysicsObj::get_sticky_object_id @ 0x0050EAF0 (acclient.c:315807)"""
        return self.position_manager.get_sticky_object_id() if self.position_manager is not None else 0

    def constrain_to(self, p: Position, start_distance: float, max_distance: float) -> None:
        """Leash the body to ``p`` (offsets damped from ``start_distance``, none past ``max_distance``).

        Both distances are ``float`` parameters.

        Retail: CPhysicsObj::ConstrainTo @ 0x00510520 (acclient.c:317590)
        """
        self.make_position_manager().constrain_to(p, f32(start_distance), f32(max_distance))

    def _distance_for_place(
        self, player_indoors: float, player_outdoors: float, indoors: float, outdoors: float
    ) -> float:
        """The four-way choice shared by the distance getters: player or not, env cell or not."""
        inside = (self.position.objcell_id & 0xFFFF) >= 0x100
        if self is self.world.player:
            return player_indoors if inside else player_outdoors
        return indoors if inside else outdoors

    def get_autonomy_blip_distance(self) -> float:
        """How far a server position may be and still be glided to: 25 m (player) or 20 m indoors,
        100 m outdoors.

        Retail: CPhysicsObj::GetAutonomyBlipDistance @ 0x0050EB70 (acclient.c:315860)
        """
        return self._distance_for_place(25.0, 100.0, 20.0, 100.0)

    def get_start_constraint_distance(self) -> float:
        """5 m indoors, 10 m outdoors (player or not).

        Retail: CPhysicsObj::GetStartConstraintDistance @ 0x0050EBC0 (acclient.c:315884)
        """
        return self._distance_for_place(5.0, 10.0, 5.0, 10.0)

    def get_max_constraint_distance(self) -> float:
        """20 m indoors, 50 m outdoors (player or not).

        Retail: CPhysicsObj::GetMaxConstraintDistance @ 0x0050EC10 (acclient.c:315908)
        """
        return self._distance_for_place(20.0, 50.0, 20.0, 50.0)
