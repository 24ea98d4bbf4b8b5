"""Which bodies the kernel may step: those whose state outside their record is idle.

A body's record (:data:`acphys.fast.layout.BODY`) holds what a step of a body reads and writes
while nothing else about the body is going on: no manager at work but the movement manager's
motion interpreter (which only acts when the body lands, leaves the ground or an animation
ends: the kernel hands the first two back, and retires the motions an AnimDone hook completes in
the record's copy of the queues, :mod:`acphys.fast.kernels.motion_queues`), the position
manager's interpolation (its queue a row of the interpolation table) and the motion table's
manager with no motion to complete, no hooks waiting, a sequence the kernel can play
(:func:`acphys.fast.kernels.sequence.load_sequence`).
:func:`uncovered_reason` names the first thing that is going on (a manager at work, a hook
waiting, a shape the kernel does not sweep, ...); such a body runs on the reference path until
it is idle again. The kernel itself hands a step back when it meets something it does not cover
mid-step (see :mod:`acphys.fast.kernels.tick`).
"""

from __future__ import annotations

from collections.abc import Callable

from acphys.fast.layout import MAX_CELLS, MAX_GLIDE_NODES, MAX_RECORDS, MAX_SPHERES
from acphys.flags import PhysicsState, TransientState
from acphys.physics_obj import PhysicsObj
from acphys.world.obj_cell import ObjCell

_SHAPE_STATES = PhysicsState.PARTICLE_EMITTER | PhysicsState.HAS_PHYSICS_BSP
#: Physics-state bits whose handling the kernel leaves to the reference path.
_UNCOVERED_STATES = _SHAPE_STATES | PhysicsState.HIDDEN | PhysicsState.SLEDDING


def _position_manager_reason(body: PhysicsObj) -> str | None:
    """Why the kernel cannot run ``body``'s position manager, or None: it runs an interpolation
    manager alone (:mod:`acphys.fast.kernels.interpolation`) of at most ``MAX_GLIDE_NODES`` nodes,
    gliding with the motion interpreter's speed."""
    manager = body.position_manager
    if manager is None:
        return None
    if manager.sticky_manager is not None or manager.constraint_manager is not None:
        return "a sticky or constraint manager"
    glide = manager.interpolation_manager
    if glide is None or not glide.position_queue:
        return None
    if len(glide.position_queue) > MAX_GLIDE_NODES:
        return "an interpolation queue past its bound"
    movement = body.movement_manager
    if movement is None or movement.motion_interpreter is None:
        return "interpolation without a motion interpreter"
    return None


def uncovered_reason(
    body: PhysicsObj, land_cell: Callable[[int], ObjCell | None], observer: object | None = None
) -> str | None:
    """Why the kernel cannot step ``body`` now, or None when it can. ``land_cell`` gives the cell
    the kernel knows by an id (None: unknown): the body's cell and every cell it shadows into must
    be that very cell (a landblock loaded since leaves the world's terrain-less stand-ins for its
    cells in the lists of the bodies that reached them); ``observer`` is the engine's own step
    observer."""
    if body.parent is not None or (body.children is not None and body.children.objects):
        return "held or holding"
    parts = body.part_array
    if parts is None:
        return "no part array"
    setup = parts.setup
    if setup.parts is not None or setup.cylspheres or setup.physics_bsp is not None:
        return "shape: parts, cylspheres or a BSP"
    if len(setup.spheres) > MAX_SPHERES:
        return "shape: more than two spheres"
    if body._state & _UNCOVERED_STATES or body._transient_state & TransientState.CHECK_ETHEREAL:
        return "state"
    managers = (body.detection_manager, body.target_manager, body.particle_manager, body.script_manager)
    if any(manager is not None for manager in managers):
        return "managers"
    reason = _position_manager_reason(body)
    if reason is not None:
        return reason
    movement = body.movement_manager
    if movement is not None and movement.moveto_manager is not None:
        return "a move-to manager"
    table = parts.motion_table_manager
    if table is not None and table.pending_animations and not table.pending_animations[0].num_anims:
        return "a motion waiting to complete"
    if body.hooks or body.anim_hooks:
        return "hooks waiting"
    if body.weenie_obj is not None or body.on_collision is not None:
        return "a weenie or a collision callback"
    if body.collision_table is not None and len(body.collision_table) > MAX_RECORDS:
        return "collision records"
    if body.observer is not None and body.observer != observer:
        return "an observer"
    if body.on_step is not None:
        return "a step callback"
    if body.cell is not None and land_cell(body.position.objcell_id) is not body.cell:
        return "not in a known land cell"
    shadows = body.shadow_objects
    if len(shadows) > MAX_CELLS or any(
        shadow.cell is not None and land_cell(shadow.cell_id) is not shadow.cell for shadow in shadows
    ):
        return "shadows in cells the kernel does not know"
    return None
