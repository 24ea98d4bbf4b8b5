"""Physics-object hooks: the tweens ``process_hooks`` runs every tick."""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj


class HookType(enum.IntEnum):
    """``PhysicsObjHook::HookType``: what ``process_fp_hook`` does with the value."""

    SCALE = 0
    TRANSLUCENCY = 1
    PART_TRANSLUCENCY = 2
    LUMINOSITY = 3
    DIFFUSION = 4
    PART_LUMINOSITY = 5
    PART_DIFFUSION = 6
    CALL_PES = 7


class FPHook:
    """A float tween from ``start_value`` to ``end_value`` over ``interpolation_time`` seconds.

    The two values are ``float`` fields; the creation and interpolation times are doubles.

    Retail: FPHook::FPHook @ 0x0051BA50 (acclient.c:329679)
    """

    __slots__ = (
        "end_value",
        "hook_type",
        "interpolation_time",
        "start_value",
        "time_created",
        "user_data",
    )

    def __init__(
        self,
        hook_type: HookType,
        time_created: float,
        interpolation_time: float,
        start_value: float,
        end_value: float,
        user_data: int = 0,
    ) -> None:
        self.hook_type = hook_type
        self.time_created = time_created
        self.interpolation_time = interpolation_time
        self.start_value = f32(start_value)
        self.end_value = f32(end_value)
        self.user_data = user_data

    def execute(self, obj: PhysicsObj) -> bool:
        """Apply the value for the current physics time; True once the tween has reached its end.

        The fraction is ``(curr_time - time_created) / interpolation_time``
        clamped to [0, 1], with ``curr_time`` the physics timer of the slice. The fraction is a
        ``float`` local and the value a ``float`` argument (acclient.c:329705-329713).

        Retail: FPHook::Execute @ 0x0051BAA0 (acclient.c:329694)
        """
        elapsed = obj.world.physics_time - self.time_created
        if elapsed <= 0.0:
            fraction = 0.0
        elif elapsed < self.interpolation_time:
            fraction = f32(elapsed / self.interpolation_time)
        else:
            fraction = 1.0
        value = f32((self.end_value - self.start_value) * fraction + self.start_value)
        obj.process_fp_hook(self.hook_type, value, self.user_data)
        return fraction == 1.0
