"""The optional per-body managers, as the tick calls them.

``UpdateObjectInternal`` and ``UpdatePositionInternal`` call each manager a
body carries, in retail order, and skip the ones it lacks. These protocols
name exactly the calls the physics makes on the managers that arrive with
the manager issue (the movement and motion-table managers are in ``motion``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from acphys.managers.detection import DetectionInfo
    from acphys.managers.target import TargetInfo
    from acphys.math.frame import Frame
    from acphys.math.position import Position
    from acphys.physics_obj import PhysicsObj


class PositionManager(Protocol):
    """Retail ``PositionManager``: interpolation, sticky and constraint offsets."""

    def adjust_offset(self, offset_frame: Frame, quantum: float) -> None: ...

    def use_time(self) -> None: ...

    def is_fully_constrained(self) -> bool: ...

    def stick_to(self, object_id: int, radius: float, height: float) -> None: ...

    def unstick(self) -> None: ...

    def is_interpolating(self) -> bool: ...

    def interpolate_to(self, p: Position, keep_heading: bool) -> None: ...

    def stop_interpolating(self) -> None: ...

    def get_sticky_object_id(self) -> int: ...

    def constrain_to(self, p: Position, start_distance: float, max_distance: float) -> None: ...

    def unconstrain(self) -> None: ...

    def handle_update_target(self, target_info: TargetInfo) -> None: ...


class DetectionManager(Protocol):
    def check_detection(self) -> None: ...

    def destroy_detection_cylsphere(self, context_id: int) -> bool: ...

    def receive_detection_update(self, incoming_info: DetectionInfo) -> None: ...


class TargetInfoLike(Protocol):
    quantum: float


class TargetManager(Protocol):
    """Retail ``TargetManager``: the object this body tracks, and the bodies tracking it."""

    target_info: TargetInfoLike | None

    def handle_targetting(self) -> None: ...

    def set_target(self, context_id: int, object_id: int, radius: float, quantum: float) -> None: ...

    def clear_target(self) -> None: ...

    def set_target_quantum(self, new_quantum: float) -> None: ...

    def add_voyeur(self, object_id: int, radius: float, quantum: float) -> None: ...

    def remove_voyeur(self, object_id: int) -> bool: ...

    def receive_update(self, target_update: TargetInfo) -> None: ...

    def notify_voyeur_of_event(self, event: int) -> None: ...


class ParticleManager(Protocol):
    """Retail ``ParticleManager``: the body's particle emitters by id."""

    def update_particles(self) -> None: ...

    def create_particle_emitter(
        self, physobj: PhysicsObj, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int: ...

    def create_blocking_particle_emitter(
        self, physobj: PhysicsObj, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int: ...

    def destroy_particle_emitter(self, emitter_id: int) -> bool: ...

    def stop_particle_emitter(self, emitter_id: int) -> bool: ...

    def get_num_emitters(self) -> int: ...


class ScriptManager(Protocol):
    """Retail ``ScriptManager``: the body's queue of physics scripts."""

    def update_scripts(self) -> None: ...

    def add_script(self, script_id: int) -> bool: ...


class PhysicsObjHook(Protocol):
    """A tween run every tick by ``process_hooks``; ``execute`` returns True when finished."""

    def execute(self, obj: PhysicsObj) -> bool: ...


class AnimHook(Protocol):
    """A one-shot animation hook, fired once by ``process_hooks`` and then dropped."""

    def execute(self, obj: PhysicsObj) -> None: ...
