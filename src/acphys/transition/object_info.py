"""``OBJECTINFO``: the moving object's traits a transition reads (state bits, step heights)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import ObjectInfoState

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj


class ObjectInfo:
    """Retail ``OBJECTINFO`` (acclient.h:52284).

    ``state`` holds :class:`acphys.flags.ObjectInfoState` bits. ``OBJECTINFO::init`` (which
    reads the object's step heights and weenie) is not ported yet; a transition fills the
    fields directly.
    """

    __slots__ = ("ethereal", "object", "scale", "state", "step_down", "step_down_height", "step_up_height",
                 "target_id")

    def __init__(
        self,
        obj: PhysicsObj | None = None,
        state: ObjectInfoState = ObjectInfoState.DEFAULT,
        scale: float = 1.0,
        step_up_height: float = 0.0,
        step_down_height: float = 0.0,
        ethereal: bool = False,
        step_down: bool = True,
        target_id: int = 0,
    ) -> None:
        self.object = obj
        self.state = ObjectInfoState(state)
        self.scale = float(scale)
        self.step_up_height = float(step_up_height)
        self.step_down_height = float(step_down_height)
        self.ethereal = ethereal
        self.step_down = step_down
        #: ``targetID``.
        self.target_id = target_id
