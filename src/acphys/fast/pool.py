"""Hand-off of retail's pooled transition between the kernel and the reference path.

Retail sweeps with a transition from a static pool (``CTransition::makeTransition``) whose
fields outlive a sweep: what ``init`` does not reset carries over to the next body's sweep, and
a few carried-over values are read (the contact plane a sweep without contact leaves on the body,
the last known plane a cliff slide reads). The kernel's transition record is that pool slot; it
is written into the reference pool's first slot before a reference step and read back after, so
the two paths carry over the same values.
"""

from __future__ import annotations

import numpy as np

from acphys.fast.world_arrays import WorldArrays
from acphys.flags import ObjectInfoState
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.transition.sphere_path import InsertType
from acphys.transition.transition import Transition
from acphys.world.world import World

#: SPHEREPATH and COLLISIONINFO fields copied as they are, by attribute name: flags, then numbers.
_PATH_FLAGS = (
    "step_up",
    "step_down",
    "collide",
    "neg_poly_hit",
    "check_walkable",
    "cell_array_valid",
    "hits_interior_cell",
)
_PATH_NUMBERS = ("walkable_allowance", "walk_interp", "step_down_amt")
_INFO_FLAGS = (
    "last_known_contact_plane_valid",
    "last_known_contact_plane_is_water",
    "contact_plane_valid",
    "contact_plane_is_water",
    "sliding_normal_valid",
    "collision_normal_valid",
    "collided_with_environment",
)
_INFO_NUMBERS = ("last_known_contact_plane_cell_id", "contact_plane_cell_id", "frames_stationary_fall")
#: Positions: record prefix → SPHEREPATH attribute.
_POSITIONS = {"curr": "curr_pos", "check": "check_pos", "backup": "backup_check_pos"}


def _vector(values: np.ndarray) -> Vector3:
    x, y, z = values.tolist()
    return Vector3(x, y, z)


def _position(tr: np.void, prefix: str) -> Position:
    frame = Frame()
    frame.origin = _vector(tr[f"{prefix}_origin"])
    frame.qw, frame.qx, frame.qy, frame.qz = tr[f"{prefix}_q"].tolist()
    frame.m[:] = tr[f"{prefix}_m"].tolist()
    return Position(int(tr[f"{prefix}_cell_id"]), frame)


def _cell(arrays: WorldArrays, k: int) -> object:
    return arrays.land_cells[k] if k >= 0 else None


def _index(arrays: WorldArrays, cell: object) -> int:
    return arrays.cell_index(cell.id) if cell is not None else -1  # type: ignore[attr-defined]


def transition_to_pool(tr_array: np.ndarray, arrays: WorldArrays, world: World) -> None:
    """Write the kernel's transition into the first slot of ``world``'s pool (made if need be)."""
    transit = Transition.pool(world)[0]
    tr = tr_array[0]
    path, info, obj = transit.sphere_path, transit.collision_info, transit.object_info
    obj.state = ObjectInfoState(int(tr["oi_state"]))
    spheres = tr["local_sphere"][: tr["num_sphere"]].tolist()
    path.local_sphere = [Sphere(Vector3(x, y, z), r) for x, y, z, r in spheres]
    path.global_sphere = [
        Sphere(Vector3(x, y, z), r) for x, y, z, r in tr["global_sphere"][: tr["num_sphere"]].tolist()
    ]
    path.global_curr_center = [Vector3(*c) for c in tr["global_curr_center"][: tr["num_sphere"]].tolist()]
    path.local_low_point = _vector(tr["local_low_point"])
    path.global_low_point = _vector(tr["global_low_point"])
    path.global_offset = _vector(tr["global_offset"])
    for prefix, name in _POSITIONS.items():
        setattr(path, name, _position(tr, prefix))
    path.curr_cell = _cell(arrays, int(tr["curr_cell"]))
    path.check_cell = _cell(arrays, int(tr["check_cell"]))
    path.backup_cell = _cell(arrays, int(tr["backup_cell"]))
    path.insert_type = InsertType(int(tr["insert_type"]))
    path.backup = InsertType(int(tr["backup"]))
    for name in _PATH_FLAGS:
        setattr(path, name, bool(tr[name]))
    for name in (*_PATH_NUMBERS, *_INFO_NUMBERS):
        setattr(path if name in _PATH_NUMBERS else info, name, tr[name].item())
    for name in _INFO_FLAGS:
        setattr(info, name, bool(tr[name]))
    last_known = Plane(_vector(tr["last_known_contact_n"]), float(tr["last_known_contact_d"]))
    info.last_known_contact_plane = last_known
    info.contact_plane = Plane(_vector(tr["contact_n"]), float(tr["contact_d"]))
    info.sliding_normal = _vector(tr["sliding_normal"])
    info.collision_normal = _vector(tr["collision_normal"])


def transition_from_pool(tr_array: np.ndarray, arrays: WorldArrays, world: World) -> None:
    """Read the first slot of ``world``'s pool back into the kernel's transition (nothing before
    its first sweep)."""
    if not world.transition_pool:
        return
    transit = world.transition_pool[0]
    tr = tr_array[0]
    path, info, obj = transit.sphere_path, transit.collision_info, transit.object_info
    tr["oi_state"] = int(obj.state)
    count = min(len(path.local_sphere), 2)
    tr["num_sphere"] = count
    for s in range(count):
        local = path.local_sphere[s]
        tr["local_sphere"][s] = (local.center.x, local.center.y, local.center.z, local.radius)
    for s, sphere in enumerate(path.global_sphere[:2]):
        tr["global_sphere"][s] = (sphere.center.x, sphere.center.y, sphere.center.z, sphere.radius)
    for s, center in enumerate(path.global_curr_center[:2]):
        tr["global_curr_center"][s] = (center.x, center.y, center.z)
    tr["local_low_point"] = tuple(path.local_low_point)
    tr["global_low_point"] = tuple(path.global_low_point)
    tr["global_offset"] = tuple(path.global_offset)
    for prefix, name in _POSITIONS.items():
        pos = getattr(path, name)
        tr[f"{prefix}_cell_id"] = pos.objcell_id
        tr[f"{prefix}_origin"] = tuple(pos.frame.origin)
        tr[f"{prefix}_q"] = pos.frame.rotation
        tr[f"{prefix}_m"] = pos.frame.m
    tr["curr_cell"] = _index(arrays, path.curr_cell)
    tr["check_cell"] = _index(arrays, path.check_cell)
    tr["backup_cell"] = _index(arrays, path.backup_cell)
    tr["insert_type"] = int(path.insert_type)
    tr["backup"] = int(path.backup)
    tr["walkable"] = path.walkable is not None
    for name in (*_PATH_FLAGS, *_PATH_NUMBERS):
        tr[name] = getattr(path, name)
    for name in (*_INFO_FLAGS, *_INFO_NUMBERS):
        tr[name] = getattr(info, name)
    tr["last_known_contact_n"] = tuple(info.last_known_contact_plane.N)
    tr["last_known_contact_d"] = info.last_known_contact_plane.d
    tr["contact_n"] = tuple(info.contact_plane.N)
    tr["contact_d"] = info.contact_plane.d
    tr["sliding_normal"] = tuple(info.sliding_normal)
    tr["collision_normal"] = tuple(info.collision_normal)
