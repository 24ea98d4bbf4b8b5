"""``COLLISIONINFO``: what a sweep found (contact plane, slide and collision normals, objects hit)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import TransitionState
from acphys.geometry.plane import Plane
from acphys.math.vector import Vector3, zero_vector

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj


class CollisionInfo:
    """Retail ``COLLISIONINFO`` (acclient.h:52306)."""

    __slots__ = (
        "adjust_offset",
        "collide_object",
        "collided_with_environment",
        "collision_normal",
        "collision_normal_valid",
        "contact_plane",
        "contact_plane_cell_id",
        "contact_plane_is_water",
        "contact_plane_valid",
        "frames_stationary_fall",
        "last_collided_object",
        "last_known_contact_plane",
        "last_known_contact_plane_cell_id",
        "last_known_contact_plane_is_water",
        "last_known_contact_plane_valid",
        "sliding_normal",
        "sliding_normal_valid",
    )

    def __init__(self) -> None:
        self.last_known_contact_plane_valid = False
        self.last_known_contact_plane = Plane()
        self.last_known_contact_plane_is_water = False
        self.last_known_contact_plane_cell_id = 0
        self.contact_plane_valid = False
        self.contact_plane = Plane()
        self.contact_plane_cell_id = 0
        self.contact_plane_is_water = False
        self.sliding_normal_valid = False
        self.sliding_normal = zero_vector()
        self.collision_normal_valid = False
        self.collision_normal = zero_vector()
        self.adjust_offset = zero_vector()
        #: ``collide_object`` (``num_collide_object`` is its length).
        self.collide_object: list[PhysicsObj] = []
        self.last_collided_object: PhysicsObj | None = None
        self.collided_with_environment = False
        self.frames_stationary_fall = 0

    @property
    def num_collide_object(self) -> int:
        return len(self.collide_object)

    def init(self) -> None:
        """Clear the validity flags, the object list and the per-sweep counters (planes, normals kept).

        Retail: COLLISIONINFO::init @ 0x00509D60 (acclient.c:311566)
        """
        self.last_known_contact_plane_valid = False
        self.contact_plane_valid = False
        self.sliding_normal_valid = False
        self.collision_normal_valid = False
        self.collide_object = []
        self.last_collided_object = None
        self.collided_with_environment = False
        self.contact_plane_cell_id = 0
        self.frames_stationary_fall = 0

    def set_contact_plane(self, plane: Plane, is_water: bool) -> None:
        """Mark the contact plane valid and store a copy of ``plane`` (cell id is the caller's job).

        Retail: COLLISIONINFO::set_contact_plane @ 0x00509D80 (acclient.c:311580)
        """
        self.contact_plane_valid = True
        self.contact_plane = plane.copy()
        self.contact_plane_is_water = is_water

    def set_collision_normal(self, normal: Vector3) -> None:
        """Store ``normal`` normalised; one shorter than EPSILON is stored as zero (still valid).

        Retail: COLLISIONINFO::set_collision_normal @ 0x0050A000 (acclient.c:311725)
        """
        self.collision_normal_valid = True
        self.collision_normal = normal.copy()
        if self.collision_normal.normalize_check_small():
            self.collision_normal = zero_vector()

    def set_sliding_normal(self, normal: Vector3) -> None:
        """Store the horizontal part of ``normal``, normalised; too short is stored as zero.

        Retail: COLLISIONINFO::set_sliding_normal @ 0x0050A060 (acclient.c:311743)
        """
        self.sliding_normal_valid = True
        self.sliding_normal = Vector3(normal.x, normal.y, 0.0)
        if self.sliding_normal.normalize_check_small():
            self.sliding_normal = zero_vector()

    def add_object(self, obj: PhysicsObj, ts: TransitionState) -> None:
        """Record ``obj`` once; a new one becomes ``last_collided_object`` unless ``ts`` is OK.

        Retail: COLLISIONINFO::add_object @ 0x006B4E20 (acclient.c:718728)
        """
        if any(known is obj for known in self.collide_object):
            return
        self.collide_object.append(obj)
        if ts != TransitionState.OK:
            self.last_collided_object = obj
