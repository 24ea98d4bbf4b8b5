"""The optional per-body managers, as the tick calls them.

``UpdateObjectInternal`` and ``UpdatePositionInternal`` call each manager a
body carries, in retail order, and skip the ones it lacks. These protocols
name exactly the calls the physics makes on the managers that arrive with
the manager issue (the movement and motion-table managers are in ``motion``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from acphys.math.frame import Frame
    from acphys.physics_obj import PhysicsObj


class PositionManager(Protocol):
    """Retail ``PositionManager``: interpolation, sticky and constraint offsets."""

    def adjust_offset(self, offset_frame: Frame, quantum: float) -> None: ...

    def use_time(self) -> None: ...

    def is_fully_constrained(self) -> bool: ...

    def stick_to(self, object_id: int, radius: float, height: float) -> None: ...

    def unstick(self) -> None: ...

    def is_interpolating(self) -> bool: ...


class DetectionManager(Protocol):
    def check_detection(self) -> None: ...


class TargetInfoLike(Protocol):
    quantum: float


class TargetManager(Protocol):
    """Retail ``TargetManager``: tracks the object a move-to or turn-to is aimed at."""

    target_info: TargetInfoLike | None

    def handle_targetting(self) -> None: ...

    def set_target(self, context_id: int, object_id: int, radius: float, quantum: float) -> None: ...

    def clear_target(self) -> None: ...

    def set_target_quantum(self, new_quantum: float) -> None: ...


class ParticleManager(Protocol):
    def update_particles(self) -> None: ...


class ScriptManager(Protocol):
    def update_scripts(self) -> None: ...


class PhysicsObjHook(Protocol):
    """A tween run every tick by ``process_hooks``; ``execute`` returns True when finished."""

    def execute(self, obj: PhysicsObj) -> bool: ...


class AnimHook(Protocol):
    """A one-shot animation hook, fired once by ``process_hooks`` and then dropped."""

    def execute(self, obj: PhysicsObj) -> None: ...
