"""How far a body's update on the reference path can reach, so that the write-back before it
(:meth:`acphys.fast.engine.FastPhysics._write_back_for`) writes only the land cells whose
shadow lists it may read and the bodies shadowed there, not the whole world. Not retail: the
fast engine's bookkeeping.

A body's update reads other bodies through the cells its sweep reaches (their shadow lists),
through its collision partners, through the player (activity), and through whatever its
managers and callbacks look at. Two bounds, each a box of landblock-global metres:

* :func:`sweep_box`, a covered body handed back during its sweep: the kernel kept the path's two
  ends (``tick.HB_*``). The sweep keeps the spheres within the box around them widened by the
  body's reach and the path's length (steps are bent, never lengthened; rollbacks and slides go
  back or along; lifts and steps are vertical: the argument of the kernel's ``_lonely_sweep``).
* :func:`update_boxes`, an uncovered body whose update reads nothing of other bodies but through
  its sweep (:func:`reads_only_its_sweep`): its candidate lies within the quantum's velocity,
  acceleration and root motion (:func:`root_motion_bound`) or interpolation glide of where it
  stands, and an interpolation's blip places it at a node it holds.

A sweep's box is widened by :data:`SWEEP_MARGIN` more (what the reference path's shapes do
within it: slides along a wall or a static object's faces go along the path, steps up are
vertical, a building's cells never list a body the kernel stepped); a placement's (a blip) by
:data:`PLACEMENT_MARGIN`, past the rings ``find_placement_pos`` tries up to 4 m out. A body
shadowed in those cells whose own reach misses every box (:func:`within_reach`) is one the
update finds out of its reach from where it stands (``PhysicsObj.out_of_reach``, the shadow
files) and reads no more of: only its place need be written.
"""

from __future__ import annotations

import math

import numpy as np

from acphys.constants import BLOCK_LENGTH, CELL_LENGTH, GRAVITY, MAX_LCOORD, MAX_QUANTUM, MAX_VELOCITY
from acphys.fast.sync import interpolation_of
from acphys.fast.world_arrays import WorldArrays
from acphys.math.cell_id import lcoord_to_gid
from acphys.math.position import Position
from acphys.motion.animation import F_EPSILON
from acphys.motion.sequence import Sequence
from acphys.physics_obj import PhysicsObj

#: Metres past a sweep's bound within which the reference step may still read other bodies'
#: shadows (the kernel's own "lonely" bound takes half a metre).
SWEEP_MARGIN = 2.0
#: Metres past a placement's target within which it may read them (its rings reach 4 m).
PLACEMENT_MARGIN = 8.0
#: The most cells a partial write-back writes; an update reaching further writes the whole world.
MAX_CELLS_REACHED = 64

#: A thousandth more than the sum of the root motion's steps, for its float32 roundings.
ROUNDING_SLACK = 1.001
#: A box of landblock-global metres: ``(x0, y0, x1, y1)``.
Box = tuple[float, float, float, float]


def global_xy(cell_id: int, x: float, y: float) -> tuple[float, float]:
    """Landblock-global metres of the point ``(x, y)`` of cell ``cell_id``'s landblock."""
    return ((cell_id >> 24) & 0xFF) * BLOCK_LENGTH + x, ((cell_id >> 16) & 0xFF) * BLOCK_LENGTH + y


def _around(x0: float, y0: float, x1: float, y1: float, widen: float) -> Box | None:
    box = (x0 - widen, y0 - widen, x1 + widen, y1 + widen)
    return box if all(math.isfinite(value) for value in box) else None


def sweep_box(begin: tuple[float, float], end: tuple[float, float], reach: float) -> Box | None:
    """Where a sweep from ``begin`` to ``end`` (global xy) of a body reaching ``reach`` can read
    shadow lists (None: not a number)."""
    (bx, by), (ex, ey) = begin, end
    widen = reach + math.hypot(ex - bx, ey - by) + SWEEP_MARGIN
    return _around(min(bx, ex), min(by, ey), max(bx, ex), max(by, ey), widen)


def reads_only_its_sweep(body: PhysicsObj, observer: object | None) -> bool:
    """Whether ``body``'s update reads other bodies only through its sweep (and a blip's
    placement), its collision partners and the player: no manager but the motion interpreter, a
    move to a position and a position manager's interpolation and constraint (a sticky manager,
    a move to an object, target and detection managers read their targets, scripts run hooks),
    no tween waiting (a scale tween grows its reach), no callback of the user's (``observer`` is
    the engine's own), neither held nor holding. A move to a position acts through the motion
    interpreter after the sweep, for the steps after."""
    if body.parent is not None or (body.children is not None and body.children.objects):
        return False
    managers = (body.detection_manager, body.target_manager, body.particle_manager, body.script_manager)
    if any(manager is not None for manager in managers):
        return False
    if body.position_manager is not None and body.position_manager.sticky_manager is not None:
        return False
    moveto = body.movement_manager.moveto_manager if body.movement_manager is not None else None
    if moveto is not None and (moveto.top_level_object_id or moveto.sought_object_id):
        return False  # moving to an object: it reads the object (and aims through a target manager)
    if body.weenie_obj is not None or body.on_collision is not None or body.on_step is not None:
        return False
    return not body.hooks and (body.observer is None or body.observer == observer)


def root_motion_bound(sequence: Sequence, quantum: float) -> float | None:
    """The longest root motion ``sequence`` can play in ``quantum`` seconds (unscaled), or None
    for a sequence whose play is not bounded so (a frame range turned over, a number that is not
    finite).

    ``update_internal`` crosses at most ``quantum · max|framerate| + 1`` frames of its nodes and
    advances at most ``quantum · max|framerate| + 2`` times (each advance past the first plays a
    whole node, a frame or more), composing up to two more frames at each advance (leaving one
    node, entering the next); each frame moves it by at most its animation's longest position
    frame and ``|velocity| / |framerate|``; a node too slow to advance moves it by the velocity
    over what is left of the quantum. The float32 stores and turns along the way may lengthen
    the sum by a few parts in a million: ``ROUNDING_SLACK``.
    """
    speed = sequence.velocity.length()
    nodes = sequence.anim_list
    if not nodes:
        return speed * quantum * ROUNDING_SLACK
    longest, fastest, slowest = 0.0, 0.0, math.inf
    for node in nodes:
        if node.low_frame > node.high_frame:
            return None
        rate = abs(node.framerate)
        fastest = max(fastest, rate)
        if rate > F_EPSILON:
            slowest = min(slowest, rate)
        animation = node.animation
        if animation is not None and animation.pos_frames is not None:
            for frame in animation.pos_frames:
                longest = max(longest, frame.origin.length())
    advances = quantum * fastest + 2.0
    frames = quantum * fastest + 1.0 + 2.0 * advances
    per_frame = longest + (speed / slowest if math.isfinite(slowest) else 0.0)
    bound = (frames * per_frame + speed * quantum) * ROUNDING_SLACK
    return bound if math.isfinite(bound) else None


def _position_xy(position: Position) -> tuple[float, float]:
    origin = position.frame.origin
    return global_xy(position.objcell_id, origin.x, origin.y)


def update_boxes(body: PhysicsObj, reach: float, quantum: float, observer: object | None) -> list[Box] | None:
    """Where the update of a body reaching ``reach`` (from its origin, turned any way) for
    ``quantum`` seconds (one step: no more than ``MAX_QUANTUM``) can read shadow lists, or None
    when that is not bounded here (see :func:`reads_only_its_sweep`).

    Its candidate lies within its velocity (at most ``MAX_VELOCITY``), its acceleration and
    gravity over the quantum and its root motion of where it stands; an interpolation's glide
    replaces the root motion by a step no longer than the way to the head node (a constraint
    only shortens it), and its blip places the body at the last node or ``blipto_position``:
    a box about each."""
    if not 0.0 <= quantum <= MAX_QUANTUM or not reads_only_its_sweep(body, observer):
        return None
    travel = min(body.velocity.length(), MAX_VELOCITY) * quantum
    travel += (body.acceleration.length() + abs(GRAVITY)) * quantum * quantum
    if body.part_array is not None:
        played = root_motion_bound(body.part_array.sequence, quantum)
        if played is None:
            return None
        travel += played * abs(body.scale)
    x, y = _position_xy(body.position)
    places = []
    interpolation = interpolation_of(body)
    if interpolation is not None:
        queue = interpolation.position_queue
        if queue:
            hx, hy = _position_xy(queue[0])
            travel += math.hypot(hx - x, hy - y)
            places.append(_position_xy(queue[-1]))
        if interpolation.blipto_position.objcell_id:
            places.append(_position_xy(interpolation.blipto_position))
    boxes = [_around(x, y, x, y, reach + travel + SWEEP_MARGIN)]
    boxes += [_around(px, py, px, py, reach + PLACEMENT_MARGIN) for px, py in places]
    return None if any(box is None for box in boxes) else boxes  # type: ignore[misc]


def cells_under(arrays: WorldArrays, boxes: list[Box]) -> list[int] | None:
    """The kernel cells under any of ``boxes`` (in index order), or None when they span more
    than :data:`MAX_CELLS_REACHED` cells."""
    cells: set[int] = set()
    spanned = 0
    for x0, y0, x1, y1 in boxes:
        gx0, gx1 = math.floor(x0 / CELL_LENGTH), math.floor(x1 / CELL_LENGTH)
        gy0, gy1 = math.floor(y0 / CELL_LENGTH), math.floor(y1 / CELL_LENGTH)
        spanned += (gx1 - gx0 + 1) * (gy1 - gy0 + 1)
        if spanned > MAX_CELLS_REACHED:
            return None
        for gx in range(max(0, gx0), min(MAX_LCOORD - 1, gx1) + 1):
            for gy in range(max(0, gy0), min(MAX_LCOORD - 1, gy1) + 1):
                k = arrays.cell_index(lcoord_to_gid(gx, gy))
                if k >= 0:
                    cells.add(k)
    return sorted(cells)


def within_reach(records: np.ndarray, boxes: list[Box]) -> np.ndarray:
    """Per body record, whether its spheres (its ``reach`` about its origin, turned any way) may
    come within any of ``boxes``; a body that cannot is out of the reach of whatever stays in
    them (``PhysicsObj.out_of_reach``). Not a number is within."""
    cell_id = records["cell_id"].astype(np.int64)
    x = ((cell_id >> 24) & 0xFF) * BLOCK_LENGTH + records["origin"][:, 0]
    y = ((cell_id >> 16) & 0xFF) * BLOCK_LENGTH + records["origin"][:, 1]
    reach = records["reach"]
    near = ~(np.isfinite(x) & np.isfinite(y) & np.isfinite(reach))
    for x0, y0, x1, y1 in boxes:
        near |= (x + reach >= x0) & (x - reach <= x1) & (y + reach >= y0) & (y - reach <= y1)
    return near
