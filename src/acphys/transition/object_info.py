"""``OBJECTINFO``: the moving object's traits a transition reads (state bits, step heights).

Divergence from ACE's ``ObjectInfo.MissileIgnore`` (the decompilation wins): ACE lets a missile
obstacle hit a player it targets ("modified for 2-way"); retail ignores every missile obstacle
(acclient.c:314078-314080).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import ObjectInfoState, PhysicsState

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

    def missile_ignore(self, collideobject: PhysicsObj) -> bool:
        """Whether the sweep passes through ``collideobject`` because one of the two is a missile.

        A missile obstacle is always ignored. A missile mover ignores anything but its target
        (``target_id``) that has a weenie and is either ethereal or, when the missile has a
        target, a creature.

        Retail: OBJECTINFO::missile_ignore @ 0x0050CEB0 (acclient.c:314069)
        """
        if collideobject.state & PhysicsState.MISSILE:
            return True
        mover = self.object
        if mover is None:
            raise ValueError("OBJECTINFO.missile_ignore: the transition has no moving object")
        if not mover.state & PhysicsState.MISSILE or collideobject.id == self.target_id:
            return False
        weenie = collideobject.weenie_obj
        if weenie is None:
            return False
        if collideobject.state & PhysicsState.ETHEREAL:
            return True
        return self.target_id != 0 and weenie.is_creature()
