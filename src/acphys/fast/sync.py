"""Hand-off between a body's record and its reference ``PhysicsObj``, both ways, exactly.

:func:`load_body` copies what a step reads and writes from the object into the record (every
value is already a float32 or a double there, so the copy is exact); :func:`store_bodies` copies
it back. Cells, shadows and the objects lists of cells are handed over by the engine, which knows
the order they changed in (:mod:`acphys.fast.engine`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from acphys.body.reports import REACH_MARGIN, CollisionRecord, CollisionTable
from acphys.fast.layout import MAX_PENDING
from acphys.flags import PhysicsState
from acphys.geometry.plane import Plane
from acphys.managers.interpolation import InterpolationManager
from acphys.math.vector import Vector3, vectors_of_float32
from acphys.motion.commands import ACTION_MASK
from acphys.motion.interp import MotionInterp
from acphys.motion.movement_manager import MovementManager
from acphys.motion.table_manager import MotionTableManager
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj


def _vec(v: Vector3) -> tuple[float, float, float]:
    return (v.x, v.y, v.z)


def _reach(extents: list[float], scale: float) -> float:
    """The broad phase's reach of a body whose spheres extend ``extents`` (unscaled) from its
    origin: the longest, scaled, with a millionth and :data:`REACH_MARGIN` to spare."""
    return max((extent * scale for extent in extents), default=0.0) * (1.0 + 1e-6) + REACH_MARGIN


def load_body(record: np.void, body: PhysicsObj, cell_index: int, covered: bool) -> None:
    """Copy ``body`` into ``record`` (``cell_index``: the kernel index of its cell, -1 for none)."""
    record["covered"] = covered
    record["stale"] = False
    record["obj_id"] = body.id
    record["state"] = body._state  # the plain ints behind the public flags
    record["transient"] = body._transient_state
    record["update_time"] = body.update_time
    record["player_distance"] = body.player_distance
    record["player_vector"] = _vec(body.player_vector)
    record["cell_id"] = body.position.objcell_id
    record["cell"] = cell_index if body.cell is not None else -1
    frame = body.position.frame
    record["origin"] = _vec(frame.origin)
    record["q"] = frame.rotation
    record["m"] = frame.m
    record["velocity"] = _vec(body.velocity)
    record["acceleration"] = _vec(body.acceleration)
    record["omega"] = _vec(body.omega)
    record["cached_velocity"] = _vec(body.cached_velocity)
    record["friction"] = body.friction
    record["elasticity"] = body.elasticity
    record["scale"] = body.scale
    record["contact_n"] = _vec(body.contact_plane.N)
    record["contact_d"] = body.contact_plane.d
    record["contact_cell_id"] = body.contact_plane_cell_id
    record["sliding_normal"] = _vec(body.sliding_normal)
    record["jumped_this_frame"] = body.jumped_this_frame
    record["step_events"] = bool(body.step_events)
    record["colliding_with_environment"] = body.colliding_with_environment
    record["has_movement_manager"] = body.movement_manager is not None
    record["glide"] = -1  # the engine gives a covered body with a position manager its row
    table = body.collision_table
    # Oldest first, as the kernel keeps them (it derives retail's iteration order from that).
    ids = table.oldest_first()[: record["record_time"].size] if table is not None else []
    record["num_records"] = len(ids)
    for r, object_id in enumerate(ids):
        kept = table.get(object_id)
        record["record_obj"][r] = object_id
        record["record_time"][r] = kept.touched_time
        record["record_ethereal"][r] = kept.ethereal
    record["has_parent"] = body.parent is not None
    record["on_collision"] = body.on_collision is not None
    parts = body.part_array
    spheres = parts.setup.spheres if parts is not None else []
    record["collider"] = (
        parts is not None
        and body.weenie_obj is None
        and not body._state & PhysicsState.HAS_PHYSICS_BSP
        and not parts.setup.cylspheres
        and len(spheres) <= 2
    )
    record["num_sphere"] = min(len(spheres), 2)
    for s, sphere in enumerate(spheres[:2]):
        c = sphere.center
        record["sphere"][s] = (c.x, c.y, c.z, sphere.radius)
    record["reach"] = _reach([s.center.length() + s.radius for s in spheres], body.scale)
    across = [(s.center.x**2 + s.center.y**2) ** 0.5 + s.radius for s in spheres]  # from the z axis
    record["hreach"] = _reach(across, body.scale)
    if parts is not None:
        record["step_up_height"] = parts.setup.step_up_height
        record["step_down_height"] = parts.setup.step_down_height
        record["free_heading"] = parts.allows_free_heading()
    load_motion_queues(record, body)


#: The methods an AnimDone hook runs through, on the classes the kernel ports them from.
_HOOK_CHAIN = (PhysicsObj.process_hooks, PhysicsObj.hook_anim_done, PhysicsObj.motion_done)


def motion_queues(body: PhysicsObj) -> tuple[MotionTableManager | None, MotionInterp | None] | None:
    """What ``body``'s AnimDone hooks act on: its motion table's manager (None: they do nothing)
    and the motion interpreter its completed motions reach (None: none); None when the hooks may
    do something else (a subclass's methods on the way, or another body's managers), which the
    kernel then leaves to the reference path
    (:func:`acphys.fast.kernels.motion_queues.retire_motions`)."""
    parts = body.part_array
    if parts is None:
        return None, None
    kind = type(body)
    chain = (kind.process_hooks, kind.hook_anim_done, kind.motion_done)
    if chain != _HOOK_CHAIN or type(parts) is not PartArray:
        return None
    table = parts.motion_table_manager
    if table is None:
        return None, None
    owner = table.physics_obj
    if type(table) is not MotionTableManager or (owner is not None and owner is not body):
        return None
    movement = body.movement_manager if owner is not None else None
    if movement is None:
        return table, None
    interp = movement.motion_interpreter
    if type(movement) is not MovementManager or (interp is not None and type(interp) is not MotionInterp):
        return None
    return table, interp if interp is not None and interp.physics_obj is not None else None


def load_motion_queues(record: np.void, body: PhysicsObj) -> None:
    """Copy the motion queues ``body``'s AnimDone hooks retire into its record (``table_*``,
    ``interp_*``): lengths of -1 when the kernel leaves them to the reference path (see
    :func:`motion_queues`; more nodes than the record holds, or counts past its integers)."""
    record["motions_owed"] = False
    record["table_len"] = record["interp_len"] = -1
    queues = motion_queues(body)
    if queues is None:
        return
    table, interp = queues
    nodes = table.pending_animations if table is not None else []
    counter = table.animation_counter if table is not None else 0
    counts = [node.num_anims for node in nodes]
    if len(nodes) > MAX_PENDING or not all(0 <= count < 2**31 for count in (*counts, counter)):
        return
    record["table_len"] = len(nodes)
    record["table_counter"] = counter
    for n, node in enumerate(nodes):
        record["table_anims"][n] = counts[n]
        record["table_plain"][n] = not node.motion & ACTION_MASK
    motions = interp.pending_motions if interp is not None else []
    if len(motions) <= MAX_PENDING:
        record["interp_len"] = len(motions)
        for n, motion in enumerate(motions):
            record["interp_plain"][n] = not motion.motion & ACTION_MASK


def store_motion_queues(values: Any, body: PhysicsObj) -> None:
    """Write the motion queues of ``values`` (a body's record, or its fields) back into ``body``:
    the kernel only retires head nodes, so each queue loses its head down to the record's length
    (again: nothing) and the table's counter is the record's."""
    if values["table_len"] < 0:
        return
    queues = motion_queues(body)
    if queues is None:
        return
    table, interp = queues
    if table is not None:
        _retire_to(table.pending_animations, int(values["table_len"]))
        table.animation_counter = int(values["table_counter"])
    if interp is not None and values["interp_len"] >= 0:
        _retire_to(interp.pending_motions, int(values["interp_len"]))


def _retire_to(queue: list[Any], length: int) -> None:
    """Drop the head of ``queue`` down to ``length`` nodes."""
    if len(queue) < length:
        raise RuntimeError(
            f"fast engine: a motion queue of {len(queue)} nodes behind a record of {length}: "
            "a bug in acphys, please report it"
        )
    del queue[: len(queue) - length]


def interpolation_of(body: PhysicsObj) -> InterpolationManager | None:
    """The interpolation manager of ``body``'s position manager, if it has both."""
    return body.position_manager.interpolation_manager if body.position_manager is not None else None


def load_glide(row: np.void, body: PhysicsObj) -> None:
    """Copy ``body``'s interpolation manager (none: an empty queue) into its
    :data:`~acphys.fast.layout.INTERPOLATION` row. The motion interpreter's adjusted max speed is
    read once: a covered body's steps leave what it depends on (the interpreted state and the
    speed factor; an AnimDone hook only retires pending motions)."""
    manager = interpolation_of(body)
    queue = list(manager.position_queue) if manager is not None else []
    row["loaded"] = row["num_nodes"] = len(queue)
    row["first"] = 0
    row["keep_heading"] = manager is not None and manager.keep_heading
    row["frame_counter"] = manager.frame_counter if manager is not None else 0
    row["node_fail_counter"] = manager.node_fail_counter if manager is not None else 0
    row["original_distance"] = manager.original_distance if manager is not None else 0.0
    row["progress_quantum"] = manager.progress_quantum if manager is not None else 0.0
    interpreter = body.movement_manager.motion_interpreter if body.movement_manager is not None else None
    row["max_speed"] = interpreter.get_adjusted_max_speed() if queue and interpreter is not None else 0.0
    for n, node in enumerate(queue):
        frame = node.frame
        row["node_cell_id"][n] = node.objcell_id
        row["node_origin"][n] = _vec(frame.origin)
        row["node_q"][n] = frame.rotation
        row["node_m"][n] = frame.m


def store_glide(row: np.void, body: PhysicsObj) -> None:
    """Copy an :data:`~acphys.fast.layout.INTERPOLATION` row back into ``body``'s interpolation
    manager: the kernel only drops nodes from the head of the queue and moves the audit on."""
    manager = interpolation_of(body)
    if manager is None:
        return
    for _ in range(int(row["loaded"]) - int(row["num_nodes"])):
        manager.position_queue.popleft()
    row["loaded"] = row["num_nodes"]
    manager.frame_counter = int(row["frame_counter"])
    manager.node_fail_counter = int(row["node_fail_counter"])
    manager.original_distance = float(row["original_distance"])
    manager.progress_quantum = float(row["progress_quantum"])


#: The fields :func:`store_bodies` hands back.
_STORED = (
    "state",
    "transient",
    "update_time",
    "player_distance",
    "player_vector",
    "origin",
    "q",
    "m",
    "velocity",
    "acceleration",
    "omega",
    "cached_velocity",
    "contact_n",
    "contact_d",
    "contact_cell_id",
    "sliding_normal",
    "jumped_this_frame",
    "step_events",
    "colliding_with_environment",
    "num_records",
    "record_obj",
    "record_time",
    "record_ethereal",
    "table_len",
    "table_counter",
    "interp_len",
)


#: The ``Vector3`` fields among them.
_VECTORS = (
    "player_vector",
    "origin",
    "velocity",
    "acceleration",
    "omega",
    "cached_velocity",
    "contact_n",
    "sliding_normal",
)


def vector_column(column: np.ndarray) -> list[Vector3]:
    """The rows of a records' ``(n, 3)`` float field as ``Vector3``s, narrowed to float32 all at
    once as the constructor narrows each (beyond the float32 range an infinity, as ``f32``)."""
    with np.errstate(over="ignore"):
        return _vectors(column)


def _vectors(column: np.ndarray) -> list[Vector3]:
    """:func:`vector_column` inside a caller's ``np.errstate(over="ignore")``."""
    return vectors_of_float32(column.astype(np.float32).tolist())


def rows_of(records: np.ndarray, rows: np.ndarray | list[int]) -> np.ndarray:
    """``records[rows]``, a copy, made as raw bytes: NumPy copies a structured record field by
    field (about 20 µs a body record), a record of plain bytes at once."""
    raw = records.view(np.dtype((np.void, records.dtype.itemsize)))
    return raw[rows].view(records.dtype)


def store_bodies(records: np.ndarray, bodies: list[PhysicsObj]) -> None:
    """Copy what kernel steps change from ``records`` back into ``bodies``, one record each (not
    their cells, shadows or sequences, which the engine hands back; their parts are placed at the
    frames). Each field is read for all of them at once, as Python values."""
    columns = {name: records[name].tolist() for name in _STORED if name not in _VECTORS}
    with np.errstate(over="ignore"):
        columns.update({name: _vectors(records[name]) for name in _VECTORS})
    for j, body in enumerate(bodies):
        values = {name: column[j] for name, column in columns.items()}
        body._state = values["state"]
        body._transient_state = values["transient"]
        body.update_time = values["update_time"]
        body.player_distance = values["player_distance"]
        body.player_vector = values["player_vector"]
        frame = body.position.frame
        frame.origin = values["origin"]
        frame.qw, frame.qx, frame.qy, frame.qz = values["q"]
        frame.m[:] = values["m"]
        body.velocity = values["velocity"]
        body.acceleration = values["acceleration"]
        body.omega = values["omega"]
        body.cached_velocity = values["cached_velocity"]
        body.contact_plane = Plane(values["contact_n"], values["contact_d"])
        body.contact_plane_cell_id = values["contact_cell_id"]
        body.sliding_normal = values["sliding_normal"]
        body.jumped_this_frame = bool(values["jumped_this_frame"])
        if not values["step_events"]:
            body.step_events.clear()  # the kernel's step recorded them
        body.colliding_with_environment = bool(values["colliding_with_environment"])
        _store_records(body, values)
        store_motion_queues(values, body)
        if body.part_array is not None:
            body.part_array.update_parts(frame)


def _store_records(body: PhysicsObj, values: dict[str, Any]) -> None:
    """The body's collision records as the kernel left them (``values``: its record's fields): the
    first ``num_records``, oldest first (a record the kernel's steps ended and made again is a new
    one, as in the reference's table); the table is stored afresh in that order."""
    count = values["num_records"]
    if count and body.collision_table is None:
        body.collision_table = CollisionTable()
    table = body.collision_table
    if table is None:
        return
    times, ethereal = values["record_time"], values["record_ethereal"]
    for object_id in table.oldest_first():
        table.remove(object_id)
    for r, object_id in enumerate(values["record_obj"][:count]):
        table.clobber(object_id, CollisionRecord(times[r], bool(ethereal[r])))
