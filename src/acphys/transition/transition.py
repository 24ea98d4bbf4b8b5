"""``CTransition``: one sweep of a body from where it is to where it wants to be.

This issue ports the transition's shape (object, spheres, path, collision
info) and the body side that drives it. Until the collision-sweep issue
brings the CTransition machine (sub-steps, insertion, slides, steps,
validation), :meth:`Transition.find_valid_position` is a placeholder: it
accepts the candidate, places it in the outdoor cell that holds it, and
rests it on the landblock's flat ground, if any.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import adjust_to_outside, is_outdoor
from acphys.math.position import Position
from acphys.transition.collision_info import CollisionInfo

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj
    from acphys.world.world import ObjCell, World


class SpherePath:
    """Retail ``SPHEREPATH`` (acclient.h:32625): the path and the spheres swept along it."""

    __slots__ = ("begin_cell", "begin_pos", "curr_cell", "curr_pos", "end_pos", "local_sphere")

    def __init__(self) -> None:
        self.local_sphere: list[Sphere] = []
        self.begin_cell: ObjCell | None = None
        self.begin_pos = Position()
        self.end_pos = Position()
        self.curr_pos = Position()
        self.curr_cell: ObjCell | None = None


class Transition:
    """Retail ``CTransition`` (acclient.h:52329)."""

    __slots__ = ("collision_info", "object", "sphere_path", "world")

    def __init__(self, world: World, obj: PhysicsObj) -> None:
        self.world = world
        self.object = obj
        self.sphere_path = SpherePath()
        self.collision_info = CollisionInfo()

    def init_sphere(self, spheres: list[Sphere], scale: float) -> None:
        """Copy the first two of the body's spheres, scaled, as the local spheres to sweep.

        Retail: CTransition::init_sphere @ 0x00509E50 (acclient.c:311619), which is
        SPHEREPATH::init_sphere @ 0x0050C670 (acclient.c:313646)
        """
        self.sphere_path.local_sphere = [
            Sphere(sphere.center * scale, sphere.radius * scale) for sphere in spheres[:2]
        ]

    def init_path(self, begin_cell: ObjCell | None, begin_pos: Position, end_pos: Position) -> None:
        """Set the path from ``begin_pos`` (in ``begin_cell``) to ``end_pos``.

        Retail: CTransition::init_path @ 0x00509E60 (acclient.c:311625), which is
        SPHEREPATH::init_path @ 0x0050CE20 (acclient.c:314042)
        """
        path = self.sphere_path
        path.begin_cell = begin_cell
        path.begin_pos = begin_pos.copy()
        path.end_pos = end_pos.copy()
        path.curr_pos = begin_pos.copy()
        path.curr_cell = begin_cell

    def find_valid_position(self) -> bool:
        """Sweep the path; True with ``curr_pos``/``curr_cell`` set when a valid position is found.

        Placeholder until the collision sweep: every candidate is valid. The
        end position is re-homed into the outdoor cell under it (crossing
        landblock seams); one at or below its landblock's flat ground is
        lifted onto it and gets that ground as its contact plane, which is
        where retail's sweep leaves a body on flat walkable ground. A
        candidate off the edge of the world has no cell and fails, so the
        body keeps its origin.

        Retail: CTransition::find_valid_position @ 0x0050C310 (acclient.c:313418)
        """
        path = self.sphere_path
        pos = path.end_pos.copy()
        if is_outdoor(pos.objcell_id):
            pos.objcell_id = adjust_to_outside(pos.objcell_id, pos.frame.origin)
        cell = self.world.get_cell(pos.objcell_id) if pos.objcell_id else None
        if cell is None:
            return False
        ground = self.world.ground_height(pos.objcell_id)
        if ground is not None and pos.frame.origin.z <= ground:
            pos.frame.origin.z = ground
            info = self.collision_info
            info.contact_plane_valid = True
            info.contact_plane = Plane.horizontal(ground)
            info.contact_plane_cell_id = pos.objcell_id
        path.curr_pos = pos
        path.curr_cell = cell
        return True
