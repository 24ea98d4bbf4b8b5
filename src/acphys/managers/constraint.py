"""``ConstraintManager``: the leash between a body and its last server-confirmed position.

``ConstrainTo`` records how far the body already is from the anchor; every
step afterwards adds the length of the step's offset. While the body is in
contact, offsets pass in full up to the start distance, shrink linearly to
nothing between start and max, and are zeroed beyond max. The accumulated
length never shrinks (only a new ``ConstrainTo`` resets it), so the leash
measures distance travelled, not distance from the anchor.

Retail's ``ConstraintManager::UseTime`` is an empty function (its address is
shared with other empty functions); ``PositionManager.use_time`` therefore
has nothing to call here.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.flags import TransientState as TS
from acphys.math.position import Position
from acphys.motion.move_to import position_distance
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.math.frame import Frame
    from acphys.physics_obj import PhysicsObj

#: ``IsFullyConstrained`` once the accumulated offset passes this fraction of max (acclient.c:389418).
FULLY_CONSTRAINED_FRACTION: float = 0.9


class ConstraintManager:
    """Retail ``ConstraintManager``: anchor, start and max distance, and the offset travelled.

    Retail: ConstraintManager::Create @ 0x00556110 (acclient.c:389432)
    """

    __slots__ = (
        "constraint_distance_max",
        "constraint_distance_start",
        "constraint_pos",
        "constraint_pos_offset",
        "is_constrained",
        "physics_obj",
    )

    def __init__(self, physics_obj: PhysicsObj) -> None:
        self.physics_obj = physics_obj
        self.is_constrained = False
        #: The anchor's distance at ``constrain_to`` plus every offset length since.
        self.constraint_pos_offset = 0.0
        #: The anchor; recorded but never read by the physics.
        self.constraint_pos = Position()
        self.constraint_distance_start = 0.0
        self.constraint_distance_max = 0.0

    def constrain_to(self, p: Position, start_distance: float, max_distance: float) -> None:
        """Leash the body to ``p``: damping from ``start_distance``, nothing past ``max_distance``.

        The distances are ``float`` parameters and, like the starting distance, ``float`` fields.

        Retail: ConstraintManager::ConstrainTo @ 0x00556240 (acclient.c:389513)
        """
        for name, value in (("start_distance", start_distance), ("max_distance", max_distance)):
            if not math.isfinite(value):
                raise ValueError(f"constraint {name} must be finite, got {value}")
        self.is_constrained = True
        self.constraint_pos = p.copy()
        self.constraint_distance_start = f32(start_distance)
        self.constraint_distance_max = f32(max_distance)
        self.constraint_pos_offset = f32(position_distance(p, self.physics_obj.position))

    def unconstrain(self) -> None:
        """Drop the leash (the distances and the accumulated offset stay).

        Retail: ConstraintManager::UnConstrain @ 0x005560C0 (acclient.c:389410)
        """
        self.is_constrained = False

    def is_fully_constrained(self) -> bool:
        """The accumulated offset is beyond 0.9 × max (even when no longer constrained).

        Retail: ConstraintManager::IsFullyConstrained @ 0x005560D0 (acclient.c:389416)
        """
        return self.constraint_distance_max * FULLY_CONSTRAINED_FRACTION < self.constraint_pos_offset

    def adjust_offset(self, offset: Frame, quantum: float) -> None:
        """Damp the offset's origin (in contact only), then add its length to the running total.

        In contact: below start unchanged; strictly between start and max
        scaled by ``(max - total) / (max - start)``; at or past max zeroed.
        Airborne offsets pass unchanged but still count. The scale is a ``float``
        argument and the running total a ``float`` field (acclient.c:389493-389495, 389506).

        Retail: ConstraintManager::adjust_offset @ 0x00556180 (acclient.c:389477)
        """
        if not self.is_constrained:
            return
        travelled = self.constraint_pos_offset
        start = self.constraint_distance_start
        limit = self.constraint_distance_max
        if self.physics_obj._transient_state & TS.CONTACT:
            if travelled >= limit:
                offset.origin.x = offset.origin.y = offset.origin.z = 0.0
            elif travelled > start:
                offset.origin.set(offset.origin * f32((limit - travelled) / (limit - start)))
        self.constraint_pos_offset = f32(offset.origin.length() + travelled)
