"""The collision sweep: the transition state and the CTransition machine."""

from acphys.transition.collision_info import CollisionInfo
from acphys.transition.transition import SpherePath, Transition

__all__ = ["CollisionInfo", "SpherePath", "Transition"]
