"""``COLLISIONINFO``: what a sweep found, as the commit reads it."""

from __future__ import annotations

from acphys.geometry.plane import Plane
from acphys.math.vector import Vector3


class CollisionInfo:
    """Retail ``COLLISIONINFO`` (acclient.h:52306), the fields the commit reads."""

    __slots__ = (
        "collided_with_environment",
        "collision_normal",
        "collision_normal_valid",
        "contact_plane",
        "contact_plane_cell_id",
        "contact_plane_is_water",
        "contact_plane_valid",
        "frames_stationary_fall",
        "sliding_normal",
        "sliding_normal_valid",
    )

    def __init__(self) -> None:
        self.contact_plane_valid = False
        self.contact_plane = Plane()
        self.contact_plane_cell_id = 0
        self.contact_plane_is_water = False
        self.sliding_normal_valid = False
        self.sliding_normal = Vector3()
        self.collision_normal_valid = False
        self.collision_normal = Vector3()
        self.collided_with_environment = False
        self.frames_stationary_fall = 0
