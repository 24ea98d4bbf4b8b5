"""``CPhysicsObj``: a physics body and its per-tick update, in retail order.

The tick, top to bottom, as :meth:`PhysicsObj.update_object` runs it:

1. ``update_object`` gates the body (parent, cell, frozen), applies the
   96-m activity cull, and slices the elapsed time into quanta.
2. ``update_object_internal`` runs one quantum on an active body:
   ``update_position_internal`` builds the candidate frame (root motion,
   position-manager offset, ``Frame::combine``, ``update_physics_internal``,
   hooks); the candidate is swept by ``transition`` and committed by
   ``set_position_internal`` (or kept in place by ``set_frame``); then the
   managers tick in retail order.
"""

from __future__ import annotations

import enum
import math
import random
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from acphys.attachments import (
    AnimHook,
    DetectionManager,
    ParticleManager,
    PhysicsObjHook,
    PositionManager,
    ScriptManager,
    TargetManager,
)
from acphys.constants import (
    ACTIVITY_DISTANCE,
    DEFAULT_ELASTICITY,
    DEFAULT_FRICTION,
    EPSILON,
    FLOOR_Z,
    GRAVITY,
    HUGE_QUANTUM,
    MAX_ELASTICITY,
    MAX_QUANTUM,
    MAX_VELOCITY,
    MIN_QUANTUM,
    SLEDDING_FAST_SPEED2,
    SLEDDING_FRICTION,
    SLEDDING_STEEP_Z,
    SLEDDING_STOP_SPEED2,
    SMALL_VELOCITY,
    float32,
)
from acphys.flags import (
    DEFAULT_PHYSICS_STATE,
    STATIONARY_MASK,
    ObjectInfoState,
    PhysicsState,
    TransientState,
    TransitionState,
)
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import DUMMY_SPHERE
from acphys.hooks import FPHook, HookType
from acphys.math.cell_id import adjust_to_outside, is_outdoor
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.movement import MovementError, MovementParameters, MovementStruct, MovementType
from acphys.part_array import PartArray
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.transition import Transition
from acphys.world.obj_cell import CellArray, ObjCell, ShadowObj

if TYPE_CHECKING:
    from acphys.geometry.sphere import SphereTransition
    from acphys.managers.scripts import PhysicsScriptTable
    from acphys.managers.target import TargetInfo
    from acphys.motion.interp import MotionInterp
    from acphys.motion.motion_table import MotionTable
    from acphys.motion.movement_manager import MovementManager
    from acphys.motion.weenie import Weenie
    from acphys.world.env_cell import EnvCell
    from acphys.world.world import World

PS = PhysicsState
TS = TransientState

#: Called after every ``update_object_internal`` with the body and the quantum integrated.
StepObserver = Callable[["PhysicsObj", float], None]


class CollisionKind(enum.Enum):
    """Which weenie callback retail makes for a collision report (``CWeenieObject`` vtable slot)."""

    #: ``DoCollision(EnvCollisionProfile)`` (slot 19): the environment, or an object reporting as it.
    ENVIRONMENT = "environment"
    #: ``DoCollision(ObjCollisionProfile)`` (slot 20): another object.
    OBJECT = "object"
    #: ``DoCollision(AtkCollisionProfile)`` (slot 21): a missile learns where it hit an object.
    ATTACK = "attack"
    #: ``DoCollisionEnd(object_id)`` (slot 22): the collision record with that object expired.
    END = "end"


@dataclass(frozen=True, slots=True)
class CollisionReport:
    """One collision report as retail's collision profiles carry it.

    ``velocity`` is the receiver's own velocity for ENVIRONMENT and the reporting body's
    velocity minus the other's for OBJECT (the same vector for both sides of a pair, as retail
    passes it); None for ATTACK and END. ``me_in_contact`` / ``other_is_missile`` /
    ``other_in_contact`` are the profiles' bits (0x20 / 0x8 / 0x10 of ``ObjCollisionProfile``,
    0x1 of ``EnvCollisionProfile``). ``part`` and ``location`` are the ``AtkCollisionProfile``'s
    (``part`` is always -1 here; ``location`` is ``Position::determine_quadrant``'s bits).
    ``other`` is None for the environment and for an END whose object no longer exists.
    """

    kind: CollisionKind
    other_id: int = 0
    other: PhysicsObj | None = None
    velocity: Vector3 | None = None
    me_in_contact: bool = False
    other_is_missile: bool = False
    other_in_contact: bool = False
    part: int = -1
    location: int = 0

    @property
    def is_environment(self) -> bool:
        return self.kind is CollisionKind.ENVIRONMENT

    @property
    def is_end(self) -> bool:
        return self.kind is CollisionKind.END

    @property
    def is_start(self) -> bool:
        return self.kind is not CollisionKind.END


#: ``PhysicsObj.on_collision``: called with the receiving body and each report it receives.
CollisionCallback = Callable[["PhysicsObj", CollisionReport], None]


@dataclass(slots=True)
class CollisionRecord:
    """Retail ``CPhysicsObj::CollisionRecord`` (acclient.h:52277): when an object was last touched."""

    touched_time: float
    ethereal: bool


class CollisionTable:
    """Retail ``collision_table``: a ``LongNIValHash<CollisionRecord>`` of 4 buckets keyed by object id.

    Iteration follows the hash: bucket ``(id ^ (id >> 8)) & 3`` in order 0..3
    (``HashBase::InternalInit``: mask 3, key shift 8), and within a bucket the
    newest key first (``HashBase::clobber`` pushes a new key at the chain head and
    replaces a known one in place).
    """

    __slots__ = ("_records",)

    TABLE_MASK = 3
    KEY_SHIFT = 8

    def __init__(self) -> None:
        #: Insertion order is first-insertion order: a clobbered key keeps its place.
        self._records: dict[int, CollisionRecord] = {}

    def __len__(self) -> int:
        return len(self._records)

    def __contains__(self, object_id: object) -> bool:
        return object_id in self._records

    def get(self, object_id: int) -> CollisionRecord | None:
        return self._records.get(object_id)

    def clobber(self, object_id: int, record: CollisionRecord) -> bool:
        """Store ``record`` under ``object_id``; True when a record was already there (and is replaced).

        Retail: LongNIValHash<CPhysicsObj::CollisionRecord>::clobber @ 0x00513830 (acclient.c:320726)
        """
        known = object_id in self._records
        self._records[object_id] = record
        return known

    def remove(self, object_id: int) -> None:
        del self._records[object_id]

    def ids(self) -> list[int]:
        """The keys in retail iteration order (``HashBaseIter::Next``)."""
        newest_first = list(reversed(self._records))
        return [
            key
            for bucket in range(self.TABLE_MASK + 1)
            for key in newest_first
            if (key ^ (key >> self.KEY_SHIFT)) & self.TABLE_MASK == bucket
        ]


class PhysicsObj:
    """Retail ``CPhysicsObj`` (acclient.h:30689): one body, its state and its tick.

    ``velocity`` is ``m_velocityVector`` (what physics integrates),
    ``cached_velocity`` is the displacement actually achieved last quantum
    divided by the quantum, and root motion never touches either.
    """

    def __init__(
        self,
        world: World,
        name: str = "",
        part_array: PartArray | None = None,
        object_id: int | None = None,
    ) -> None:
        """Retail defaults: CPhysicsObj::CPhysicsObj @ 0x005123F0 (acclient.c:319489).

        The body is registered with ``world`` under ``object_id`` (the next free id by default).
        """
        self.world = world
        self.name = name
        self.id = world.add_object(self, object_id)
        self.part_array = part_array
        if part_array is not None:
            part_array.set_owner(self)
        self.parent: PhysicsObj | None = None

        self.state: PhysicsState = DEFAULT_PHYSICS_STATE
        self.transient_state: TransientState = TS(0)
        self.position = Position()
        self.cell: ObjCell | None = None

        self.velocity = Vector3()
        self.acceleration = Vector3()
        self.omega = Vector3()
        self.cached_velocity = Vector3()

        self.friction = DEFAULT_FRICTION
        self.elasticity = DEFAULT_ELASTICITY
        self.scale = 1.0
        self.translucency = 0.0
        #: ``translucencyOriginal``: the floor ``SetTranslucencyInternal`` keeps translucency above.
        self.translucency_original = 0.0
        self.update_time = 0.0
        self.jumped_this_frame = False
        self.colliding_with_environment = False

        self.contact_plane = Plane()
        self.contact_plane_cell_id = 0
        self.sliding_normal = Vector3()

        self.player_vector = Vector3(0.0, 0.0, 1.0)
        self.player_distance = math.inf

        self.weenie_obj: Weenie | None = None
        self.last_move_was_autonomous = False
        self.movement_manager: MovementManager | None = None
        self.position_manager: PositionManager | None = None
        self.detection_manager: DetectionManager | None = None
        self.target_manager: TargetManager | None = None
        self.particle_manager: ParticleManager | None = None
        self.script_manager: ScriptManager | None = None
        #: ``physics_script_table``, ``default_script`` (a PScriptType) and ``default_script_intensity``:
        #: what ``play_default_script`` plays (acphys: a ``managers.scripts.PhysicsScriptTable``).
        self.physics_script_table: PhysicsScriptTable | None = None
        self.default_script = 0
        self.default_script_intensity = 0.0

        #: ``shadow_objects``: this body's entry in every cell it overlaps (CShadowObj).
        self.shadow_objects: list[ShadowObj] = []

        #: ``hooks``: the PhysicsObjHook list, newest first.
        self.hooks: list[PhysicsObjHook] = []
        #: ``anim_hooks``: one-shot hooks queued by the sequence, fired by ``process_hooks``.
        self.anim_hooks: list[AnimHook] = []

        #: What happened since the last step was recorded ("hit_ground", "motion:RunForward", ...);
        #: cleared after each step's observer has seen it.
        self.step_events: list[str] = []
        #: Called after every physics step; the simulation's tracer hangs here.
        self.observer: StepObserver | None = None
        #: ``collision_table``: the objects touched lately; made by the first object collision.
        self.collision_table: CollisionTable | None = None
        #: Receives this body's collision reports (retail's weenie ``DoCollision*`` callbacks).
        self.on_collision: CollisionCallback | None = None

    def __repr__(self) -> str:
        return f"PhysicsObj({self.name!r}, {self.position!r})"

    # -- the clock: update_object --------------------------------------------------------

    def update_object(self) -> None:
        """Bring the body up to ``world.cur_time``, one or more quanta at a time.

        Gated off (and deactivated) when parented, cell-less or ``FROZEN``.
        Measured from the player, a body beyond 96 m is deactivated and one
        within is activated. The elapsed time since ``update_time`` is then:
        at most EPSILON, a resync; above 2 s, dropped; at most MAX_QUANTUM,
        one step; otherwise MAX_QUANTUM steps while more than MAX_QUANTUM
        remains, then the remainder only if it exceeds MIN_QUANTUM.
        ``update_time`` advances only by the time integrated.

        Retail: CPhysicsObj::update_object @ 0x00515D10 (acclient.c:323080)
        """
        world = self.world
        if self.parent is not None or self.cell is None or self.state & PS.FROZEN:
            self.transient_state &= ~TS.ACTIVE
            return
        player = world.player
        if player is not None:
            self.player_vector = player.position.get_offset(self.position)
            self.player_distance = self.player_vector.length()
            if self.player_distance > ACTIVITY_DISTANCE and world.activity_cull:
                self.transient_state &= ~TS.ACTIVE
            else:
                self.set_active(True)

        quantum = world.cur_time - self.update_time
        world.physics_time = self.update_time
        if quantum <= EPSILON or quantum > HUGE_QUANTUM:
            self.update_time = world.cur_time
            return
        if quantum > MAX_QUANTUM:
            while True:
                self._run_quantum(MAX_QUANTUM)
                quantum -= MAX_QUANTUM
                if quantum <= MAX_QUANTUM:
                    break
            if quantum > MIN_QUANTUM:
                self._run_quantum(quantum)
        else:
            self._run_quantum(quantum)
        self.update_time = world.physics_time

    def _run_quantum(self, quantum: float) -> None:
        """Advance the physics timer by ``quantum`` and run one step (update_object's slice).

        The timer advances by the double quantum; the step receives it as a
        float32, as ``UpdateObjectInternal(float quantum)`` does in retail.
        """
        self.world.physics_time += quantum
        step = float32(quantum)
        self.update_object_internal(step)
        if self.observer is not None:
            self.observer(self, step)
        self.step_events.clear()

    # -- one step: update_object_internal --------------------------------------------------

    def update_object_internal(self, quantum: float) -> None:
        """One physics step: candidate frame, sweep, commit, then the managers.

        An inactive body only ticks its particles and scripts.

        Retail: CPhysicsObj::UpdateObjectInternal @ 0x005156B0 (acclient.c:322718)
        """
        if self.transient_state & TS.ACTIVE:
            if self.cell is None:
                return
            if self.transient_state & TS.CHECK_ETHEREAL:
                self.set_ethereal(False, send_event=False)
            self.jumped_this_frame = False

            new_pos = Position(self.position.objcell_id)
            self.update_position_internal(quantum, new_pos.frame)

            if self.part_array is not None and self.part_array.get_num_sphere():
                if new_pos.frame.origin == self.position.frame.origin:
                    self._keep_origin(new_pos.frame)
                else:
                    self._align_heading(new_pos.frame)
                    transit = self.transition(self.position, new_pos)
                    if transit is not None:
                        offset = self.position.get_offset(transit.sphere_path.curr_pos)
                        self.cached_velocity = offset / quantum
                        self.set_position_internal(transit)
                    else:
                        self._keep_origin(new_pos.frame)
            else:
                if self.movement_manager is None and self.transient_state & TS.ON_WALKABLE:
                    self.transient_state &= ~TS.ACTIVE
                self._keep_origin(new_pos.frame)

            if self.detection_manager is not None:
                self.detection_manager.check_detection()
            if self.target_manager is not None:
                self.target_manager.handle_targetting()
            if self.movement_manager is not None:
                self.movement_manager.use_time()
            if self.part_array is not None:
                self.part_array.handle_movement()
            if self.position_manager is not None:
                self.position_manager.use_time()
        if self.particle_manager is not None:
            self.particle_manager.update_particles()
        if self.script_manager is not None:
            self.script_manager.update_scripts()

    def _keep_origin(self, candidate: Frame) -> None:
        """Commit only the candidate's rotation and zero ``cached_velocity``.

        The no-sweep branches of UpdateObjectInternal: unchanged origin, no
        spheres, or a failed transition.
        """
        candidate.origin.set(self.position.frame.origin)
        self.set_frame(candidate)
        self.cached_velocity = Vector3()

    def _align_heading(self, candidate: Frame) -> None:
        """``ALIGNPATH``: face the path; else ``SLEDDING`` with velocity: face the velocity.

        Part of UpdateObjectInternal (acclient.c:322800-322810).
        """
        if self.state & PS.ALIGN_PATH:
            candidate.set_vector_heading((candidate.origin - self.position.frame.origin).normalized())
        elif self.state & PS.SLEDDING and not self.velocity.is_zero():
            candidate.set_heading(self.velocity.get_heading())

    # -- the candidate frame ---------------------------------------------------------------

    def update_position_internal(self, quantum: float, new_frame: Frame) -> None:
        """Build the candidate frame: root motion, manager offset, combine, integrate, hooks.

        Root motion is scaled by ``scale`` on walkable ground and by 0
        otherwise (its rotation always applies). ``HIDDEN`` skips root motion
        and integration. ``new_frame`` becomes ``position.frame ∘ offset``.

        Retail: CPhysicsObj::UpdatePositionInternal @ 0x00512C30 (acclient.c:319988)
        """
        offset = Frame()
        if not self.state & PS.HIDDEN:
            if self.part_array is not None:
                self.part_array.update(quantum, offset)
            factor = self.scale if self.transient_state & TS.ON_WALKABLE else 0.0
            offset.origin.x *= factor
            offset.origin.y *= factor
            offset.origin.z *= factor
        if self.position_manager is not None:
            self.position_manager.adjust_offset(offset, quantum)
        new_frame.combine(self.position.frame, offset)
        if not self.state & PS.HIDDEN:
            self.update_physics_internal(quantum, new_frame)
        self.process_hooks()

    def update_physics_internal(self, quantum: float, frame: Frame) -> None:
        """Euler-integrate velocity, acceleration and omega into ``frame``.

        With any velocity: clamp to 50 m/s, apply friction, zero it when the
        (clamped, pre-friction) speed is within the 0.25 m/s deadband, then
        move by ``v·dt + a·dt²/2``. With none, a body with no movement
        manager on walkable ground is deactivated. Always ``v += a·dt`` and
        ``frame.grotate(omega·dt)``.

        Retail: CPhysicsObj::UpdatePhysicsInternal @ 0x00510700 (acclient.c:317700)
        """
        v = self.velocity
        a = self.acceleration
        velocity_mag2 = v.x * v.x + v.y * v.y + v.z * v.z
        if velocity_mag2 <= 0.0:
            if self.movement_manager is None and self.transient_state & TS.ON_WALKABLE:
                self.transient_state &= ~TS.ACTIVE
        else:
            if velocity_mag2 > MAX_VELOCITY * MAX_VELOCITY:
                v = self.velocity = v.normalized() * MAX_VELOCITY
                velocity_mag2 = MAX_VELOCITY * MAX_VELOCITY
            self.calc_friction(quantum, velocity_mag2)
            v = self.velocity
            if velocity_mag2 - SMALL_VELOCITY * SMALL_VELOCITY < EPSILON:
                v = self.velocity = Vector3()
            origin = frame.origin
            origin.x = (quantum * v.x + a.x * 0.5 * quantum * quantum) + origin.x
            origin.y = (quantum * v.y + a.y * 0.5 * quantum * quantum) + origin.y
            origin.z = (quantum * v.z + a.z * 0.5 * quantum * quantum) + origin.z
        v.x += quantum * a.x
        v.y += quantum * a.y
        v.z += quantum * a.z
        frame.grotate(self.omega * quantum)

    def calc_friction(self, quantum: float, velocity_mag2: float) -> None:
        """Ground friction: on walkable ground, unless moving away from the contact plane.

        Velocity with a normal component of 0.25 m/s or more is left alone.
        Otherwise the normal component is removed and the rest scaled by
        ``(1 - f)^dt``. ``f`` is the body's friction; a ``SLEDDING`` body
        stops dead under 1.25 m/s (f = 1) and, at 2.5 m/s or more on a
        contact plane steeper than 10°, slides with f = 0.2.

        Retail: CPhysicsObj::calc_friction @ 0x0050EE70 (acclient.c:316090)
        """
        if not self.transient_state & TS.ON_WALKABLE:
            return
        n = self.contact_plane.N
        v = self.velocity
        normal_speed = v.x * n.x + v.y * n.y + v.z * n.z
        if normal_speed >= 0.25:
            return
        v.x -= normal_speed * n.x
        v.y -= normal_speed * n.y
        v.z -= normal_speed * n.z
        friction = self.friction
        if self.state & PS.SLEDDING:
            if velocity_mag2 < SLEDDING_STOP_SPEED2:
                friction = 1.0
            elif velocity_mag2 >= SLEDDING_FAST_SPEED2 and n.z < SLEDDING_STEEP_Z:
                friction = SLEDDING_FRICTION
        factor = math.pow(1.0 - friction, quantum)
        v.x *= factor
        v.y *= factor
        v.z *= factor

    def calc_acceleration(self) -> None:
        """Standing on walkable ground (and not sledding): no acceleration and no omega.

        Otherwise gravity when ``GRAVITY`` is set, else nothing.

        Retail: CPhysicsObj::calc_acceleration @ 0x00510950 (acclient.c:317786)
        """
        ts = self.transient_state
        if ts & TS.CONTACT and ts & TS.ON_WALKABLE and not self.state & PS.SLEDDING:
            self.acceleration = Vector3()
            self.omega = Vector3()
        elif self.state & PS.GRAVITY:
            self.acceleration = Vector3(0.0, 0.0, GRAVITY)
        else:
            self.acceleration = Vector3()

    def set_on_walkable(self, is_on_walkable: bool) -> None:
        """Set ``ON_WALKABLE``; tell the movement manager on landing and leaving; recompute acceleration.

        Retail: CPhysicsObj::set_on_walkable @ 0x00511310 (acclient.c:318501)
        """
        was_on_walkable = bool(self.transient_state & TS.ON_WALKABLE)
        if is_on_walkable:
            self.transient_state |= TS.ON_WALKABLE
        else:
            self.transient_state &= ~TS.ON_WALKABLE
        if was_on_walkable and not is_on_walkable:
            self._leave_ground()
        elif not was_on_walkable and is_on_walkable:
            self.step_events.append("hit_ground")
            if self.movement_manager is not None:
                self.movement_manager.hit_ground()
        self.calc_acceleration()

    def _leave_ground(self) -> None:
        """Record leaving walkable ground and tell the movement manager, if any."""
        self.step_events.append("leave_ground")
        if self.movement_manager is not None:
            self.movement_manager.leave_ground()

    # -- hooks -----------------------------------------------------------------------------

    def process_hooks(self) -> None:
        """Run every PhysicsObjHook (dropping those that finish), then fire and clear the anim hooks.

        Retail: CPhysicsObj::process_hooks @ 0x00511550 (acclient.c:318640)
        """
        for hook in list(self.hooks):
            if hook.execute(self):
                self.hooks.remove(hook)
        index = 0
        while index < len(self.anim_hooks):
            self.anim_hooks[index].execute(self)
            index += 1
        self.anim_hooks.clear()

    def add_anim_hook(self, hook: AnimHook) -> None:
        """Queue a one-shot animation hook for the next ``process_hooks``.

        Retail: CPhysicsObj::add_anim_hook @ 0x00514C20 (acclient.c:322062)
        """
        self.anim_hooks.append(hook)

    def hook_anim_done(self) -> None:
        """An AnimDone hook fired: tell the part array (and so the motion-table manager).

        Retail: CPhysicsObj::Hook_AnimDone @ 0x0050FDA0 (acclient.c:317086)
        """
        if self.part_array is not None:
            self.part_array.animation_done(True)

    def record_event(self, event: str) -> None:
        """Note in this step's events something the physics does not act on (a sound, a particle)."""
        self.step_events.append(event)

    def process_fp_hook(self, hook_type: HookType, value: float, user_data: int) -> None:
        """Apply one tween value: scale, translucency, a part-array look, or a delayed script.

        ``user_data`` is the part index of the per-part looks and the script id
        of CALL_PES. The part array's lighting and per-part translucency are
        render state acphys does not keep: with a part array they are recorded
        as ``fp_hook:<KIND>:<user_data>=<value>`` events.

        Retail: CPhysicsObj::process_fp_hook @ 0x005135C0 (acclient.c:320571)
        """
        if hook_type == HookType.SCALE:
            self.set_scale_static(value)
        elif hook_type == HookType.TRANSLUCENCY:
            self.set_translucency_internal(value)
        elif hook_type == HookType.CALL_PES:
            self.call_pes_internal(user_data, value)
        elif self.part_array is not None:
            self.record_event(f"fp_hook:{hook_type.name}:{user_data}={value:.6g}")

    def _tween(self, hook_type: HookType, start: float, end: float, delta: float, user_data: int = 0) -> None:
        """Tween from ``start`` to ``end`` over ``delta`` s (≥ EPSILON; newest hook first), else set ``end``.

        The shared shape of SetTranslucency(2), SetPartTranslucency, SetLuminosity,
        SetPartLuminosity, SetDiffusion and SetPartDiffusion: each one's immediate
        branch is the ``process_fp_hook`` case of its kind.
        """
        if delta >= EPSILON:
            self.hooks.insert(0, FPHook(hook_type, self.world.physics_time, delta, start, end, user_data))
        else:
            self.process_fp_hook(hook_type, end, user_data)

    def set_translucency_internal(self, translucency: float) -> None:
        """Set translucency, never below ``translucency_original``.

        Retail: CPhysicsObj::SetTranslucencyInternal @ 0x0050F960 (acclient.c:316802)
        """
        self.translucency = max(translucency, self.translucency_original)

    def set_translucency(self, translucency: float, delta: float = 0.0) -> None:
        """Translucency to ``translucency`` now, or over ``delta`` s tweened from 0.0 (not from the
        current value: retail's hook starts at 0).

        Retail: CPhysicsObj::SetTranslucency @ 0x005115F0 (acclient.c:318693)
        """
        self._tween(HookType.TRANSLUCENCY, 0.0, translucency, delta)

    def set_translucency2(self, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetTranslucency2 @ 0x0050FB50 (acclient.c:316920)"""
        self._tween(HookType.TRANSLUCENCY, start, end, delta)

    def set_part_translucency(self, part_index: int, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetPartTranslucency @ 0x00511730 (acclient.c:318758)"""
        self._tween(HookType.PART_TRANSLUCENCY, start, end, delta, part_index)

    def set_luminosity(self, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetLuminosity @ 0x00511890 (acclient.c:318826)"""
        self._tween(HookType.LUMINOSITY, start, end, delta)

    def set_part_luminosity(self, part_index: int, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetPartLuminosity @ 0x005117E0 (acclient.c:318792)"""
        self._tween(HookType.PART_LUMINOSITY, start, end, delta, part_index)

    def set_diffusion(self, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetDiffusion @ 0x005119E0 (acclient.c:318894)"""
        self._tween(HookType.DIFFUSION, start, end, delta)

    def set_part_diffusion(self, part_index: int, start: float, end: float, delta: float) -> None:
        """Retail: CPhysicsObj::SetPartDiffusion @ 0x00511930 (acclient.c:318860)"""
        self._tween(HookType.PART_DIFFUSION, start, end, delta, part_index)

    # -- scripts and particles -------------------------------------------------------------

    def call_pes(self, pes: int, delta: float) -> None:
        """Play script ``pes`` now, or after a random pause in [0, ``delta``] (a CALL_PES hook).

        Retail: CPhysicsObj::CallPES @ 0x00511AF0 (acclient.c:318972)
        """
        if delta >= EPSILON:
            pause = random.uniform(0.0, delta)
            self.hooks.insert(0, FPHook(HookType.CALL_PES, self.world.physics_time, pause, 0.0, 1.0, pes))
        elif self.cell is not None:
            self.play_script_internal(pes)

    def call_pes_internal(self, pes: int, cur_value: float) -> None:
        """The CALL_PES hook's tick: play ``pes`` once the tween has reached 1 (body in a cell).

        Retail: CPhysicsObj::CallPESInternal @ 0x00511AC0 (acclient.c:318962)
        """
        if cur_value >= 1.0 and self.cell is not None:
            self.play_script_internal(pes)

    def play_script_internal(self, script_id: int) -> bool:
        """Queue script ``script_id`` on the script manager (made here when missing); False for id 0.

        Retail: CPhysicsObj::play_script_internal @ 0x00510CD0 (acclient.c:318034)
        """
        if not script_id:
            return False
        if self.script_manager is None:
            from acphys.managers.scripts import ScriptManager as RetailScriptManager

            self.script_manager = RetailScriptManager(self)
        return self.script_manager.add_script(script_id)

    def play_script(self, script_id: int) -> bool:
        """Play script ``script_id``; a body outside the world only answers True.

        Retail: CPhysicsObj::play_script @ 0x00510D30 (acclient.c:318069)
        """
        if self.cell is None:
            return True
        return self.play_script_internal(script_id)

    def play_script_type(self, script_type: int, mod: float) -> bool:
        """Play the ``physics_script_table``'s script for ``script_type`` at intensity ``mod``
        (retail's ``play_script(PScriptType, float)`` overload).

        Retail: CPhysicsObj::play_script @ 0x00513260 (acclient.c:320325)
        """
        if self.cell is None:
            return True
        if self.physics_script_table is None:
            return False
        return self.play_script_internal(self.physics_script_table.get_script(script_type, mod))

    def play_default_script(self) -> bool:
        """Play ``default_script`` at ``default_script_intensity`` from the script table.

        Retail: CPhysicsObj::play_default_script @ 0x005132B0 (acclient.c:320350)
        """
        return self.play_script_type(self.default_script, self.default_script_intensity)

    def _make_particle_manager(self) -> ParticleManager:
        """The particle manager, made first when the body has none (inline in the create calls)."""
        if self.particle_manager is None:
            from acphys.managers.particles import ParticleManager as RetailParticleManager

            self.particle_manager = RetailParticleManager()
        return self.particle_manager

    def create_particle_emitter(
        self, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int:
        """Start an emitter (replacing one with the same non-zero ``emitter_id``); its id, or 0.

        Retail: CPhysicsObj::create_particle_emitter @ 0x0050F360 (acclient.c:316329)
        """
        manager = self._make_particle_manager()
        return manager.create_particle_emitter(self, emitter_info_id, part_index, offset, emitter_id)

    def create_blocking_particle_emitter(
        self, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int:
        """Start an emitter unless ``emitter_id`` is already playing; its id, or 0.

        Retail: CPhysicsObj::create_blocking_particle_emitter @ 0x0050F3B0 (acclient.c:316355)
        """
        manager = self._make_particle_manager()
        return manager.create_blocking_particle_emitter(self, emitter_info_id, part_index, offset, emitter_id)

    def destroy_particle_emitter(self, emitter_id: int) -> bool:
        """Retail: CPhysicsObj::destroy_particle_emitter @ 0x0050F400 (acclient.c:316381)"""
        manager = self.particle_manager
        return manager is not None and manager.destroy_particle_emitter(emitter_id)

    def stop_particle_emitter(self, emitter_id: int) -> bool:
        """Retail: CPhysicsObj::stop_particle_emitter @ 0x0050F420 (acclient.c:316395)"""
        return self.particle_manager is not None and self.particle_manager.stop_particle_emitter(emitter_id)

    def get_num_emitters(self) -> int:
        """Retail: CPhysicsObj::get_num_emitters @ 0x0050F440 (acclient.c:316409)"""
        return self.particle_manager.get_num_emitters() if self.particle_manager is not None else 0

    def set_scale(self, new_scale: float, delta: float = 0.0) -> None:
        """Scale the body now, or tween to ``new_scale`` over ``delta`` seconds (≥ EPSILON).

        Retail: CPhysicsObj::SetScale @ 0x005136A0 (acclient.c:320621)
        """
        if delta >= EPSILON:
            hook = FPHook(HookType.SCALE, self.world.physics_time, delta, self.scale, new_scale)
            self.hooks.insert(0, hook)
        else:
            self.set_scale_static(new_scale)

    def set_scale_static(self, new_scale: float) -> None:
        """Scale the body and its part array now.

        Retail: CPhysicsObj::SetScaleStatic @ 0x00511BB0 (acclient.c:319007)
        """
        self.scale = new_scale
        if self.part_array is not None:
            self.part_array.set_scale_internal(new_scale)

    # -- the commit ------------------------------------------------------------------------

    def set_frame(self, frame: Frame) -> None:
        """Make ``frame`` the body's frame.

        A frame whose origin is sound but whose quaternion has a NaN is
        committed with an all-zero quaternion (the next ``combine`` then
        falls back to the identity rotation).

        Retail: CPhysicsObj::set_frame @ 0x00514090 (acclient.c:321327)
        """
        committed = frame.copy()
        if not committed.is_valid() and committed.is_valid_except_for_heading():
            committed.qw = committed.qx = committed.qy = committed.qz = 0.0
        self.position.frame.assign(committed)
        if not self.state & PS.PARTICLE_EMITTER and self.part_array is not None:
            self.part_array.set_frame(self.position.frame)

    def transition(self, old_pos: Position, new_pos: Position, admin_move: bool = False) -> Transition | None:
        """Sweep the body's spheres from ``old_pos`` to ``new_pos``; None when no valid position exists.

        A transition from the pool gets the body's object info (``get_object_info``, which
        also hands over the contact plane and sliding normal unless ``admin_move``), its first
        two spheres scaled (the dummy sphere without any), the path from the body's cell, and
        ``frames_stationary_fall`` seeded from the STATIONARY bits (STUCK → 3, STOP → 2,
        FALL → 1).

        Retail: CPhysicsObj::transition @ 0x00512DC0 (acclient.c:320060)
        """
        transit = Transition.make_transition(self.world)
        try:
            transit.init_object(self, self.get_object_info(transit, admin_move))
            if self.part_array is not None and self.part_array.get_num_sphere():
                transit.init_sphere(self.part_array.get_sphere(), self.scale)
            else:
                transit.init_sphere([DUMMY_SPHERE], 1.0)
            transit.init_path(self.cell, old_pos, new_pos)
            ts = self.transient_state
            if ts & TS.STATIONARY_STUCK:
                transit.collision_info.frames_stationary_fall = 3
            elif ts & TS.STATIONARY_STOP:
                transit.collision_info.frames_stationary_fall = 2
            elif ts & TS.STATIONARY_FALL:
                transit.collision_info.frames_stationary_fall = 1
            found = transit.find_valid_position()
        finally:
            Transition.cleanup_transition()
        return transit if found else None

    def get_object_info(self, transit: Transition, admin_move: bool) -> ObjectInfoState:
        """The object-info state for a sweep, handing ``transit`` the body's contact on the way.

        EDGE_SLIDE from the state. Unless ``admin_move``: a body in contact that is not moving
        off its contact plane (``check_contact``) starts on it (CONTACT, and ON_WALKABLE if on
        walkable ground), one moving off only remembers it as the last known plane; a sliding
        body starts with its sliding normal. FREE_ROTATE when the setup allows a free heading;
        PATH_CLIPPED for a MISSILE.

        Retail: CPhysicsObj::get_object_info @ 0x00511CC0 (acclient.c:319073)
        """
        state = ObjectInfoState.EDGE_SLIDE if self.state & PS.EDGE_SLIDE else ObjectInfoState.DEFAULT
        if not admin_move:
            if self.transient_state & TS.CONTACT:
                is_water = bool(self.transient_state & TS.WATER_CONTACT)
                if self.check_contact(True):
                    transit.init_contact_plane(self.contact_plane_cell_id, self.contact_plane, is_water)
                    state |= ObjectInfoState.CONTACT
                    if self.transient_state & TS.ON_WALKABLE:
                        state |= ObjectInfoState.ON_WALKABLE
                else:
                    transit.init_last_known_contact_plane(
                        self.contact_plane_cell_id, self.contact_plane, is_water
                    )
            if self.transient_state & TS.SLIDING:
                transit.init_sliding_normal(self.sliding_normal)
        if self.part_array is not None and self.part_array.allows_free_heading():
            state |= ObjectInfoState.FREE_ROTATE
        if self.state & PS.MISSILE:
            state |= ObjectInfoState.PATH_CLIPPED
        return state

    def check_contact(self, contact: bool) -> bool:
        """``contact``, unless the body is in contact and moving off its contact plane
        (velocity · N > EPSILON).

        Retail: CPhysicsObj::check_contact @ 0x0050F5B0 (acclient.c:316535)
        """
        if self.transient_state & TS.CONTACT and self.velocity.dot(self.contact_plane.N) > EPSILON:
            return False
        return contact

    @staticmethod
    def is_valid_walkable(normal: Vector3) -> bool:
        """A normal a body may stand on: ``z >= floor_z``.

        Retail: CPhysicsObj::is_valid_walkable @ 0x0050F530 (acclient.c:316499)
        """
        return normal.z >= FLOOR_Z

    def set_position_internal(self, transit: Transition) -> None:
        """Commit a successful sweep: cell, frame, contact, walkable, water, sliding, collisions.

        Retail: CPhysicsObj::SetPositionInternal @ 0x00515330 (acclient.c:322503)
        """
        prev_on_walkable = bool(self.transient_state & TS.ON_WALKABLE)
        prev_contact = bool(self.transient_state & TS.CONTACT)
        path = transit.sphere_path
        info = transit.collision_info
        if path.curr_cell is None:
            self.prepare_to_leave_visibility()
            self.store_position(path.curr_pos)
            self.world.goto_lost_cell(self)
            self.transient_state &= ~TS.ACTIVE
            return
        if self.cell is path.curr_cell:
            self.position.objcell_id = path.curr_pos.objcell_id
        else:
            self.change_cell(path.curr_cell)
        self.set_frame(path.curr_pos.frame)

        self.contact_plane_cell_id = info.contact_plane_cell_id
        self.contact_plane = info.contact_plane.copy()
        self._set_transient(TS.CONTACT, info.contact_plane_valid)
        self.calc_acceleration()
        self._set_transient(TS.WATER_CONTACT, info.contact_plane_is_water)
        if self.transient_state & TS.CONTACT:
            self.set_on_walkable(self.contact_plane.N.z >= FLOOR_Z)
        else:
            was_on_walkable = bool(self.transient_state & TS.ON_WALKABLE)
            self.transient_state &= ~TS.ON_WALKABLE
            if was_on_walkable:
                self._leave_ground()
            self.calc_acceleration()

        self.sliding_normal = info.sliding_normal.copy()
        self._set_transient(TS.SLIDING, info.sliding_normal_valid)
        self.handle_all_collisions(info, prev_contact, prev_on_walkable)
        if self.cell is not None:
            if self.state & PS.HAS_PHYSICS_BSP:
                self.calc_cross_cells()
            elif transit.cell_array.num_cells:
                self.remove_shadows_from_cells()
                self.add_shadows_to_cells(transit.cell_array)

    def _set_transient(self, flag: TransientState, on: bool) -> None:
        if on:
            self.transient_state |= flag
        else:
            self.transient_state &= ~flag

    def handle_all_collisions(
        self, collisions: CollisionInfo, prev_has_contact: bool, prev_on_walkable: bool
    ) -> bool:
        """Respond to what the sweep hit: report it, bounce or stop, and track stationary frames.

        A bounce ``v -= (1 + e)(v·n) n`` (or a dead stop for ``INELASTIC``)
        happens only with at most one stationary-fall frame, a valid
        collision normal and ``v·n < 0``, and not when the body was and is on
        walkable ground (unless sledding). Two or more stationary-fall frames
        zero the velocity. A count of 1 or 2 then adds STATIONARY_FALL or
        STATIONARY_STOP to the bits already set; 0 and 3 clear all three.
        Reports come first: every collided object is tracked (and reported
        once while its record lives), expired records are ended, then
        touching the environment, or landing on walkable ground, reports as
        an environment collision. True when anything was reported.

        Retail: CPhysicsObj::handle_all_collisions @ 0x00514780 (acclient.c:321807)
        """
        on_walkable = bool(self.transient_state & TS.ON_WALKABLE)
        apply_bounce = not (prev_on_walkable and on_walkable) or bool(self.state & PS.SLEDDING)
        reported = False
        for obj in list(collisions.collide_object):
            if obj is not None and self.track_object_collision(obj, prev_has_contact):
                reported = True
        self.report_collision_end(False)
        if self.colliding_with_environment:
            self.colliding_with_environment = collisions.collided_with_environment
        elif (
            collisions.collided_with_environment or (not prev_on_walkable and on_walkable)
        ) and self.report_environment_collision(prev_has_contact):
            reported = True

        frames = collisions.frames_stationary_fall
        if frames <= 1:
            if apply_bounce and collisions.collision_normal_valid:
                if self.state & PS.INELASTIC:
                    self.velocity = Vector3()
                else:
                    n = collisions.collision_normal
                    v = self.velocity
                    approach = v.z * n.z + v.y * n.y + n.x * v.x
                    if approach < 0.0:
                        impulse = -(approach * (self.elasticity + 1.0))
                        v.x = impulse * n.x + v.x
                        v.y = impulse * n.y + v.y
                        v.z = impulse * n.z + v.z
        else:
            self.velocity = Vector3()
        if frames in (0, 3):
            self.transient_state &= ~STATIONARY_MASK
        elif frames == 1:
            self.transient_state |= TS.STATIONARY_FALL
        elif frames == 2:
            self.transient_state |= TS.STATIONARY_STOP
        else:
            self.transient_state |= TS.STATIONARY_STUCK
        return reported

    def report_environment_collision(self, prev_has_contact: bool) -> bool:
        """Report the first frame of touching the environment; a missile stops aligning to its path.

        The report, made when ``REPORT_COLLISIONS`` is set, carries the body's velocity and
        ``prev_has_contact`` (retail's ``EnvCollisionProfile``).

        Retail: CPhysicsObj::report_environment_collision @ 0x00512FC0 (acclient.c:320193)
        """
        if self.colliding_with_environment:
            return False
        reported = bool(self.state & PS.REPORT_COLLISIONS)
        if reported:
            self._receive_collision(
                CollisionReport(
                    CollisionKind.ENVIRONMENT, velocity=self.velocity.copy(), me_in_contact=prev_has_contact
                )
            )
        self.colliding_with_environment = True
        if self.state & PS.MISSILE:
            self.state &= ~(PS.MISSILE | PS.ALIGN_PATH | PS.PATH_CLIPPED)
        return reported

    def _receive_collision(self, report: CollisionReport) -> None:
        """Deliver ``report`` to this body: a step event, then ``on_collision``.

        Retail hands the profile to the body's weenie (``DoCollision``, ``DoCollisionEnd``); acphys
        gates on ``REPORT_COLLISIONS`` alone (every body answers as if it had a weenie), records
        ``collision:environment``, ``collision:NAME`` or ``collision_end:NAME``, and calls the hook.
        """
        if report.kind is CollisionKind.ENVIRONMENT:
            self.step_events.append("collision:environment")
        else:
            other = report.other
            name = other.name if other is not None and other.name else f"0x{report.other_id:08X}"
            prefix = "collision_end:" if report.kind is CollisionKind.END else "collision:"
            self.step_events.append(prefix + name)
        if self.on_collision is not None:
            self.on_collision(self, report)

    def track_object_collision(self, obj: PhysicsObj, prev_has_contact: bool) -> bool:
        """Touch ``obj``: a static one reports as the environment; any other is stamped in the table
        with the physics time and its ``ETHEREAL`` bit, and reported only if it was not there yet.

        Retail: CPhysicsObj::track_object_collision @ 0x00513F10 (acclient.c:321216)
        """
        if obj.state & PS.STATIC:
            return self.report_environment_collision(prev_has_contact)
        if self.collision_table is None:
            self.collision_table = CollisionTable()
        record = CollisionRecord(self.world.physics_time, bool(obj.state & PS.ETHEREAL))
        if self.collision_table.clobber(obj.id, record):
            return False
        return self.report_object_collision(obj, prev_has_contact)

    def report_object_collision(self, obj: PhysicsObj, prev_has_contact: bool) -> bool:
        """Tell both bodies about a collision between them; True when a report was made.

        An ``obj`` with ``REPORT_COLLISIONS_AS_ENVIRONMENT`` is the environment. Otherwise, unless
        ``obj`` ignores collisions, this body (with ``REPORT_COLLISIONS``) hears of ``obj`` (an
        ATTACK with the quadrant it hit if this body is a missile, else an OBJECT), and a missile
        stops being one (MISSILE, ALIGN_PATH, PATH_CLIPPED cleared). Then ``obj`` (with
        ``REPORT_COLLISIONS``) hears of this body unless this body ignores collisions. Both OBJECT
        reports carry this body's velocity minus ``obj``'s. Retail quirk kept: in the report to
        ``obj`` the missile bit is this body's ``prev_has_contact`` and the in-contact bit is
        whether this body was a missile (``build_collision_profile`` arguments swapped,
        acclient.c:320293-320299).

        Retail: CPhysicsObj::report_object_collision @ 0x00513060 (acclient.c:320227)
        """
        if obj.state & PS.REPORT_COLLISIONS_AS_ENVIRONMENT:
            return self.report_environment_collision(prev_has_contact)
        reported = False
        was_missile = bool(self.state & PS.MISSILE)
        relative = self.velocity - obj.velocity
        if not obj.state & PS.IGNORE_COLLISIONS:
            if self.state & PS.REPORT_COLLISIONS:
                if was_missile:
                    location = obj.position.determine_quadrant(obj.get_height(), self.position)
                    report = CollisionReport(CollisionKind.ATTACK, obj.id, obj, location=location)
                else:
                    report = CollisionReport(
                        CollisionKind.OBJECT,
                        obj.id,
                        obj,
                        velocity=relative.copy(),
                        me_in_contact=prev_has_contact,
                        other_is_missile=bool(obj.state & PS.MISSILE),
                        other_in_contact=bool(obj.transient_state & TS.CONTACT),
                    )
                self._receive_collision(report)
                reported = True
            if was_missile:
                self.state &= ~(PS.MISSILE | PS.ALIGN_PATH | PS.PATH_CLIPPED)
        if obj.state & PS.REPORT_COLLISIONS and not self.state & PS.IGNORE_COLLISIONS:
            if obj.state & PS.MISSILE:
                location = self.position.determine_quadrant(self.get_height(), obj.position)
                report = CollisionReport(CollisionKind.ATTACK, self.id, self, location=location)
            else:
                report = CollisionReport(
                    CollisionKind.OBJECT,
                    self.id,
                    self,
                    velocity=relative.copy(),
                    me_in_contact=bool(obj.transient_state & TS.CONTACT),
                    other_is_missile=prev_has_contact,
                    other_in_contact=was_missile,
                )
            obj._receive_collision(report)
            reported = True
        return reported

    def report_object_collision_end(self, object_id: int) -> bool:
        """Tell both bodies a collision with ``object_id`` ended; False when that object is gone.

        No report when the object reports as the environment. When it no longer exists, only
        this body hears of the end.

        Retail: CPhysicsObj::report_object_collision_end @ 0x00510A90 (acclient.c:317868)
        """
        obj = self.world.get_object(object_id)
        if obj is None:
            if self.state & PS.REPORT_COLLISIONS:
                self._receive_collision(CollisionReport(CollisionKind.END, object_id))
            return False
        if not obj.state & PS.REPORT_COLLISIONS_AS_ENVIRONMENT:
            if self.state & PS.REPORT_COLLISIONS:
                self._receive_collision(CollisionReport(CollisionKind.END, object_id, obj))
            if obj.state & PS.REPORT_COLLISIONS:
                obj._receive_collision(CollisionReport(CollisionKind.END, self.id, self))
        return True

    def report_collision_start(self) -> None:
        """Report again a collision with every object still in the table (used on unhiding).

        Retail: CPhysicsObj::report_collision_start @ 0x00513FD0 (acclient.c:321262)
        """
        if self.collision_table is None:
            return
        for object_id in self.collision_table.ids():
            obj = self.world.get_object(object_id)
            if obj is not None:
                self.report_object_collision(obj, bool(self.transient_state & TS.CONTACT))

    def report_collision_end(self, force_end: bool) -> None:
        """Drop and end-report the records untouched for over 1 s, ethereal ones untouched for any
        time at all, or (``force_end``) every record.

        All expired records are taken out first, in table order, then reported in that order.

        Retail: CPhysicsObj::report_collision_end @ 0x00514620 (acclient.c:321712)
        """
        table = self.collision_table
        if table is None:
            return
        now = self.world.physics_time
        ended = []
        for object_id in table.ids():
            record = table.get(object_id)
            assert record is not None
            age = now - record.touched_time
            if age > 1.0 or (record.ethereal and age > 0.0) or force_end:
                table.remove(object_id)
                ended.append(object_id)
        for object_id in ended:
            self.report_object_collision_end(object_id)

    def check_collision(self, obj: PhysicsObj) -> bool:
        """Whether this body, where it stands, overlaps ``obj`` (never for a static body).

        A transition with this body's object info (``get_object_info``, not an admin move), its
        spheres (the dummy sphere without any) and a path from its position to itself asks
        ``CTransition::check_collisions``: a placement test against ``obj`` alone.

        Retail: CPhysicsObj::check_collision @ 0x00512ED0 (acclient.c:320127)
        """
        if self.state & PS.STATIC:
            return False
        transit = Transition.make_transition(self.world)
        try:
            transit.init_object(self, self.get_object_info(transit, False))
            if self.part_array is not None and self.part_array.get_num_sphere():
                transit.init_sphere(self.part_array.get_sphere(), self.scale)
            else:
                transit.init_sphere([DUMMY_SPHERE], 1.0)
            transit.init_path(self.cell, self.position, self.position)
            return transit.check_collisions(obj)
        finally:
            Transition.cleanup_transition()

    # -- cells and placement ---------------------------------------------------------------

    def change_cell(self, new_cell: ObjCell | None) -> None:
        """Leave the current cell and enter ``new_cell`` (or none).

        Retail: CPhysicsObj::change_cell @ 0x00513390 (acclient.c:320421)
        """
        if self.cell is not None:
            self.leave_cell()
        if new_cell is not None:
            self.enter_cell(new_cell)
        else:
            self.position.objcell_id = 0
            self.cell = None

    def enter_cell(self, new_cell: ObjCell) -> None:
        """Join ``new_cell``'s object list and take its id (bodies without parts cannot).

        Retail: CPhysicsObj::enter_cell @ 0x00510ED0 (acclient.c:318201)
        """
        if self.part_array is None:
            return
        new_cell.add_object(self)
        self.position.objcell_id = new_cell.id
        if not self.state & PS.PARTICLE_EMITTER:
            self.part_array.set_cell_id(new_cell.id)
        self.cell = new_cell

    def leave_cell(self) -> None:
        """Retail: CPhysicsObj::leave_cell @ 0x00510F50 (acclient.c:318243)"""
        if self.cell is not None:
            self.cell.remove_object(self)
            self.cell = None

    def store_position(self, pos: Position) -> None:
        """Take ``pos`` as the position without touching cells, re-homing outdoor origins.

        Retail: CPhysicsObj::store_position @ 0x005141A0 (acclient.c:321388)
        """
        stored = pos.copy()
        if is_outdoor(stored.objcell_id):
            stored.objcell_id = adjust_to_outside(stored.objcell_id, stored.frame.origin)
        self.position.objcell_id = stored.objcell_id
        self.set_frame(stored.frame)

    def leave_world(self) -> None:
        """Take the body out of the world: out of the lost cell, its shadows and its cell, off the
        ground (telling the movement manager), inactive, with no contact, sliding or stationary state.

        First every object collision is ended (``report_collision_end(True)``).

        Retail: CPhysicsObj::leave_world @ 0x005155A0 (acclient.c:322653)
        """
        self.report_collision_end(True)
        self.world.remove_from_lost_cell(self)
        self.transient_state &= ~TS.ACTIVE
        self.remove_shadows_from_cells()
        self.leave_cell()
        self.position.objcell_id = 0
        if self.part_array is not None and not self.state & PS.PARTICLE_EMITTER:
            self.part_array.set_cell_id(0)
        self.transient_state &= ~TS.CONTACT
        self.calc_acceleration()
        was_on_walkable = bool(self.transient_state & TS.ON_WALKABLE)
        self.transient_state &= ~(TS.ON_WALKABLE | TS.WATER_CONTACT)
        if was_on_walkable and self.movement_manager is not None:
            self.movement_manager.leave_ground()
        self.calc_acceleration()
        self.transient_state &= ~(
            TS.SLIDING
            | TS.STATIONARY_FALL
            | TS.STATIONARY_STOP
            | TS.STATIONARY_STUCK
            | TS.ACTIVE
            | TS.CHECK_ETHEREAL
        )

    def prepare_to_leave_visibility(self) -> None:
        """Take the body out of every cell (its shadows, the lost cell, its own cell).

        Retail also queues the body for destruction by the object maintainer,
        which is client bookkeeping, not physics.

        Retail: CPhysicsObj::prepare_to_leave_visibility @ 0x00511F40 (acclient.c:319195)
        """
        self.remove_shadows_from_cells()
        self.world.remove_from_lost_cell(self)
        self.leave_cell()

    def enter_world(self, pos: Position) -> bool:
        """Put the body into the world at ``pos``: store it, then place it sliding.

        Retail: CPhysicsObj::enter_world @ 0x00516310 (acclient.c:323440), which calls
        CPhysicsObj::enter_world @ 0x00516170 (acclient.c:323345): a parented body cannot;
        ``update_time`` resyncs; ``set_position`` with PLACEMENT | SLIDE at the stored position
        must return OK; then a non-static body is activated and the part array and movement
        manager handle entering the world.
        """
        self.store_position(pos)
        if self.parent is not None:
            return False
        self.update_time = self.world.cur_time
        sps = SetPositionStruct(self.position.copy(), SetPositionFlags.PLACEMENT | SetPositionFlags.SLIDE)
        if self.set_position(sps) != SetPositionError.OK:
            return False
        self.set_active(True)
        if self.part_array is not None:
            self.part_array.handle_enter_world()
        if self.movement_manager is not None:
            self.movement_manager.handle_enter_world()
        return True

    def set_position_simple(self, pos: Position, sliding: bool) -> int:
        """``set_position`` with TELEPORT | SEND_POSITION_EVENT (and SLIDE when ``sliding``).

        Retail: CPhysicsObj::SetPositionSimple @ 0x005162B0 (acclient.c:323420)
        """
        flags = SetPositionFlags.TELEPORT | SetPositionFlags.SEND_POSITION_EVENT
        if sliding:
            flags |= SetPositionFlags.SLIDE
        return self.set_position(SetPositionStruct(pos.copy(), flags))

    def set_position(self, sps: SetPositionStruct) -> int:
        """Place the body as ``sps`` asks; a :class:`SetPositionError` code (0 is OK).

        A fresh transition (object state 0) carries the body's spheres, scaled (the dummy
        sphere without any). Retail's pool of ten nested transitions is not modelled: placement
        never nests here.

        Retail: CPhysicsObj::SetPosition @ 0x005160C0 (acclient.c:323289)
        """
        transit = Transition(self.world, self)
        transit.object_info.init(self, ObjectInfoState.DEFAULT)
        if self.part_array is not None and self.part_array.get_num_sphere():
            transit.init_sphere(self.part_array.get_sphere(), self.scale)
        else:
            transit.init_sphere([DUMMY_SPHERE], 1.0)
        return self.set_position_from_struct(sps, transit)

    def set_position_from_struct(self, sps: SetPositionStruct, transit: Transition) -> int:
        """RANDOM_SCATTER goes straight to the scatter tries; otherwise ``sps.pos`` is tried and,
        failing that with SCATTER, the scatter tries.

        Retail: CPhysicsObj::SetPositionInternal @ 0x00516040 (acclient.c:323257)
        """
        if sps.flags & SetPositionFlags.RANDOM_SCATTER:
            return self.set_scatter_position_internal(sps, transit)
        result = self.set_position_with_struct(sps.pos.copy(), sps, transit)
        if result != SetPositionError.OK and sps.flags & SetPositionFlags.SCATTER:
            result = self.set_scatter_position_internal(sps, transit)
        return result

    def set_scatter_position_internal(self, sps: SetPositionStruct, transit: Transition) -> int:
        """Up to ``num_tries`` placements at ``sps.pos`` moved by ``RollDice(-1, 1)`` times
        ``xrad`` and ``yrad`` (x then y); the first OK wins. No tries is GENERAL_FAILURE.

        Retail: CPhysicsObj::SetScatterPositionInternal @ 0x00515F00 (acclient.c:323166)
        """
        result = SetPositionError.GENERAL_FAILURE
        for _ in range(sps.num_tries):
            pos = sps.pos.copy()
            dx = random.uniform(-1.0, 1.0) * sps.xrad
            dy = random.uniform(-1.0, 1.0) * sps.yrad
            pos.frame.origin.x += dx
            pos.frame.origin.y += dy
            result = self.set_position_with_struct(pos, sps, transit)
            if result == SetPositionError.OK:
                break
        return result

    def set_position_with_struct(self, p: Position, sps: SetPositionStruct, transit: Transition) -> int:
        """Place the body at ``p`` through a placement transition and commit it.

        A body with no cell prepares to enter the world. ``adjust_position`` finds the cell
        under sphere 0's centre; with none the body goes to the lost cell, inactive, and the
        result is OK. Otherwise DONT_CREATE_CELLS keeps the cell array to loaded cells, and
        ``check_position_internal`` must succeed (else COLLIDED when ``handle_all_collisions``
        reports, NO_VALID_POSITION if not), with a cell (else NO_CELL), before the commit.
        Retail first forces storage and corpse weenies into the cell (``ForceIntoCell``); acphys
        weenies are never either.

        Retail: CPhysicsObj::SetPositionInternal @ 0x00515BD0 (acclient.c:323034)
        """
        if self.cell is None:
            self.prepare_to_enter_world()
        new_cell = self.adjust_position(p, transit.sphere_path.local_sphere[0].center, search_cells=True)
        if new_cell is None:
            self.prepare_to_leave_visibility()
            self.store_position(p)
            self.world.goto_lost_cell(self)
            self.transient_state &= ~TS.ACTIVE
            return SetPositionError.OK
        if sps.flags & SetPositionFlags.DONT_CREATE_CELLS:
            transit.cell_array.do_not_load_cells = True
        if not self.check_position_internal(new_cell, p, transit, sps):
            reported = self.handle_all_collisions(transit.collision_info, False, False)
            return SetPositionError.COLLIDED if reported else SetPositionError.NO_VALID_POSITION
        if transit.sphere_path.curr_cell is None:
            return SetPositionError.NO_CELL
        self.set_position_internal(transit)
        return SetPositionError.OK

    def check_position_internal(
        self, new_cell: ObjCell, new_pos: Position, transit: Transition, sps: SetPositionStruct
    ) -> bool:
        """Run the placement; without SLIDE it must stay put: ``new_pos`` takes the placed
        origin when it moved less than 0.05 m in x and in y (signed, as retail compares) and
        stayed in ``new_cell``.

        Retail: CPhysicsObj::CheckPositionInternal @ 0x00511E90 (acclient.c:319172)
        """
        transit.init_path(new_cell, None, new_pos)
        slide = bool(sps.flags & SetPositionFlags.SLIDE)
        if not slide:
            transit.sphere_path.placement_allows_sliding = False
        if not transit.find_valid_position():
            return False
        if slide:
            return True
        placed = transit.sphere_path.curr_pos
        if (
            placed.frame.origin.x - new_pos.frame.origin.x < PLACEMENT_TOLERANCE
            and placed.frame.origin.y - new_pos.frame.origin.y < PLACEMENT_TOLERANCE
            and placed.objcell_id == new_cell.id
        ):
            new_pos.frame.origin.set(placed.frame.origin)
            return True
        return False

    def adjust_position(self, p: Position, low_pt: Vector3, search_cells: bool) -> ObjCell | None:
        """The cell for ``p`` (re-homing ``p.objcell_id``), None for an invalid cell id or none.

        Outdoors, the land cell under the origin. Indoors, the room holding ``low_pt`` (placed
        by ``p``): the room itself or, with ``search_cells``, one in its stab list (else one
        through its portals); failing that, a room that sees outside hands over to the land
        cell under the origin. (Retail's unused ``bDontCreateCells`` argument is dropped.)

        Retail: CPhysicsObj::AdjustPosition @ 0x00511D80 (acclient.c:319116)
        """
        index = p.objcell_id & 0xFFFF
        if not (1 <= index <= 0x40 or 0x100 <= index <= 0xFFFD or index == 0xFFFF):
            return None
        world = self.world
        if index < 0x100:
            p.objcell_id = adjust_to_outside(p.objcell_id, p.frame.origin)
            return world.get_cell(p.objcell_id) if p.objcell_id else None
        visible = world.get_cell(p.objcell_id)
        if visible is None:
            return None
        child = _find_visible_child_cell(visible, p.frame.localtoglobal(low_pt), search_cells, world)
        if child is not None:
            p.objcell_id = child.id
            return child
        if not visible.seen_outside:
            return None
        p.objcell_id = adjust_to_outside(p.objcell_id, p.frame.origin)
        return world.get_cell(p.objcell_id) if p.objcell_id else None

    def prepare_to_enter_world(self) -> None:
        """Resync ``update_time``, leave the lost cell and activate a non-static body.

        Retail also takes the body and its children off the destroy list (object maintenance).

        Retail: CPhysicsObj::prepare_to_enter_world @ 0x00511FA0 (acclient.c:319217)
        """
        self.update_time = self.world.cur_time
        self.world.remove_from_lost_cell(self)
        self.set_active(True)

    # -- state setters ---------------------------------------------------------------------

    def set_active(self, active: bool) -> bool:
        """Activate (not a ``STATIC`` body; resyncs ``update_time`` if it was inactive) or deactivate.

        Retail: CPhysicsObj::set_active @ 0x0050FC40 (acclient.c:316979)
        """
        if not active:
            self.transient_state &= ~TS.ACTIVE
            return True
        if self.state & PS.STATIC:
            return False
        if not self.transient_state & TS.ACTIVE:
            self.update_time = self.world.cur_time
        self.transient_state |= TS.ACTIVE
        return True

    def set_velocity(self, new_velocity: Vector3) -> None:
        """Set ``m_velocityVector`` (clamped to 50 m/s) and activate the body.

        Retail: CPhysicsObj::set_velocity @ 0x005113F0 (acclient.c:318577)
        """
        _require_finite("velocity", new_velocity)
        if new_velocity != self.velocity:
            self.velocity = new_velocity.copy()
            if self.velocity.length_squared() > MAX_VELOCITY * MAX_VELOCITY:
                self.velocity = self.velocity.normalized() * MAX_VELOCITY
            self.jumped_this_frame = True
        self.set_active(True)

    def set_local_velocity(self, local_velocity: Vector3) -> None:
        """Set the velocity given in the body's own frame.

        Retail: CPhysicsObj::set_local_velocity @ 0x005114D0 (acclient.c:318617)
        """
        self.set_velocity(self.position.frame.localtoglobalvec(local_velocity))

    def set_omega(self, new_omega: Vector3) -> None:
        """Retail: CPhysicsObj::set_omega @ 0x0050F6D0 (acclient.c:316612)"""
        _require_finite("omega", new_omega)
        self.omega = new_omega.copy()

    def set_heading(self, degrees: float) -> None:
        """Retail: CPhysicsObj::set_heading @ 0x00514160 (acclient.c:321376)"""
        frame = self.position.frame.copy()
        frame.set_heading(degrees)
        self.set_frame(frame)

    def set_elasticity(self, elasticity: float) -> None:
        """Clamp to [0, 0.1].

        Retail: CPhysicsObj::set_elasticity @ 0x0050FD40 (acclient.c:317060)
        """
        self.elasticity = min(max(elasticity, 0.0), MAX_ELASTICITY)

    def set_state(self, new_state: PhysicsState) -> None:
        """Replace ``state``; toggling ``HIDDEN`` goes through :meth:`set_hidden`.

        Retail: CPhysicsObj::set_state @ 0x00514DD0 (acclient.c:322171)
        """
        changed = new_state ^ self.state
        self.state = new_state
        if changed & PS.HIDDEN:
            self.set_hidden(bool(new_state & PS.HIDDEN))

    def set_hidden(self, hidden: bool) -> None:
        """Hide: end every collision and stop reporting them, and ignore them. Unhide: the reverse,
        re-reporting the objects still in the collision table when reporting is switched back on.

        The retail hide scripts, child no-draw and cell visibility belong to
        rendering and are not ported.

        Retail: CPhysicsObj::set_hidden @ 0x00514C60 (acclient.c:322077)
        """
        if hidden:
            self.state |= PS.HIDDEN
            if self.state & PS.REPORT_COLLISIONS:
                self.report_collision_end(True)
                self.state &= ~PS.REPORT_COLLISIONS
            self.state |= PS.IGNORE_COLLISIONS
        else:
            self.state &= ~(PS.HIDDEN | PS.IGNORE_COLLISIONS)
            if not self.state & PS.REPORT_COLLISIONS:
                self.state |= PS.REPORT_COLLISIONS
                self.report_collision_start()

    def set_ethereal(self, ethereal: bool, send_event: bool = False) -> bool:
        """Become ethereal, or try to become solid again.

        Turning solid fails while the body overlaps another (it stays
        ethereal and ``CHECK_ETHEREAL`` asks the next step to retry).

        Retail: CPhysicsObj::set_ethereal @ 0x00511C40 (acclient.c:319046)
        """
        if ethereal:
            self.state |= PS.ETHEREAL
            self.transient_state &= ~TS.CHECK_ETHEREAL
            return True
        self.state &= ~PS.ETHEREAL
        if self.parent is not None or self.cell is None or not self.ethereal_check_for_collisions():
            self.transient_state &= ~TS.CHECK_ETHEREAL
            return True
        self.transient_state |= TS.CHECK_ETHEREAL
        self.state |= PS.ETHEREAL
        return False

    def ethereal_check_for_collisions(self) -> bool:
        """Whether another body overlaps this one in any cell this body shadows.

        Each shadowed cell in turn asks its other shadowed bodies (``ObjCell.check_collisions``);
        the first overlap answers True. Static bodies never overlap here.

        Retail: CPhysicsObj::ethereal_check_for_collisions @ 0x00510A40 (acclient.c:317831)
        """
        return any(
            shadow.cell is not None and shadow.cell.check_collisions(self) for shadow in self.shadow_objects
        )

    # -- motion: commands in, animation out ------------------------------------------------

    def set_motion_table(self, table: MotionTable | None) -> None:
        """Give the body a motion table; with one comes a movement manager in its default state.

        acphys passes the table where retail passes its DAT id.

        Retail: CPhysicsObj::SetMotionTableID @ 0x00512780 (acclient.c:319692)
        """
        if self.part_array is None:
            raise ValueError(f"body {self.name!r} has no part array to hold a motion table")
        self.part_array.set_motion_table(table)
        self.movement_manager = None
        if table is not None:
            self.make_movement_manager(init_motion=True)

    def make_movement_manager(self, init_motion: bool) -> MovementManager:
        """Create the movement manager if the body has none; a non-static body becomes active.

        Retail: CPhysicsObj::MakeMovementManager @ 0x00510270 (acclient.c:317453)
        """
        if self.movement_manager is None:
            from acphys.motion.movement_manager import MovementManager

            self.movement_manager = MovementManager(self, self.weenie_obj)
            if init_motion:
                self.movement_manager.enter_default_state()
            self._activate_for_movement()
        return self.movement_manager

    def _activate_for_movement(self) -> None:
        """The tail of MakeMovementManager and get_minterp: wake a non-static body."""
        if not self.state & PS.STATIC:
            if not self.transient_state & TS.ACTIVE:
                self.update_time = self.world.cur_time
            self.transient_state |= TS.ACTIVE

    def get_minterp(self) -> MotionInterp:
        """The motion interpreter, creating the movement manager (in its default state) if needed.

        Retail: CPhysicsObj::get_minterp @ 0x005120C0 (acclient.c:319279)
        """
        return self.make_movement_manager(init_motion=True).get_minterp()

    def perform_movement(self, ms: MovementStruct) -> int:
        """Hand a movement request to the movement manager (error 7 without one).

        The common body of DoMotion, StopMotion and StopCompletely, which also
        mark the move as autonomous.

        Retail: CPhysicsObj::DoMotion @ 0x00510020 (acclient.c:317314)
        """
        self.last_move_was_autonomous = True
        if self.movement_manager is None:
            return MovementError.NO_ANIMATION_TABLE
        return self.movement_manager.perform_movement(ms)

    def do_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPhysicsObj::DoMotion @ 0x00510020 (acclient.c:317314)"""
        return self.perform_movement(MovementStruct(MovementType.RAW_COMMAND, motion, params=params))

    def stop_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPhysicsObj::StopMotion @ 0x005100D0 (acclient.c:317353)"""
        return self.perform_movement(MovementStruct(MovementType.STOP_RAW_COMMAND, motion, params=params))

    def stop_completely(self) -> None:
        """Retail: CPhysicsObj::StopCompletely @ 0x00510180 (acclient.c:317392)"""
        if self.movement_manager is not None:
            self.movement_manager.perform_movement(MovementStruct(MovementType.STOP_COMPLETELY))

    def turn_to_heading(self, params: MovementParameters) -> None:
        """Turn to ``params.desired_heading``, creating the movement manager if needed.

        Retail: CPhysicsObj::TurnToHeading @ 0x00512980 (acclient.c:319850)
        """
        manager = self.make_movement_manager(init_motion=True)
        manager.perform_movement(MovementStruct(MovementType.TURN_TO_HEADING, params=params))

    def move_to_position(self, pos: Position, params: MovementParameters) -> int:
        """Walk or run to ``pos``: a MoveToPosition request to the movement manager.

        Retail has no CPhysicsObj wrapper for this request; it is the
        ``MovementStruct`` of type 7 that MovementManager::PerformMovement
        hands to the move-to manager, made the way TurnToHeading makes its own.
        """
        manager = self.make_movement_manager(init_motion=True)
        request = MovementStruct(MovementType.MOVE_TO_POSITION, pos=pos.copy(), params=params)
        return manager.perform_movement(request)

    def cancel_moveto(self) -> None:
        """Retail: CPhysicsObj::cancel_moveto @ 0x005101F0 (acclient.c:317420)"""
        if self.movement_manager is not None:
            self.movement_manager.cancel_move_to(MovementError.ACTION_CANCELLED)

    def is_moving_to(self) -> bool:
        """Retail: CPhysicsObj::IsMovingTo @ 0x0050EB10 (acclient.c:315821)"""
        return self.movement_manager is not None and self.movement_manager.is_moving_to()

    def motions_pending(self) -> bool:
        """Retail: CPhysicsObj::motions_pending @ 0x0050EAB0 (acclient.c:315778)"""
        return self.movement_manager is not None and self.movement_manager.motions_pending()

    def movement_is_autonomous(self) -> bool:
        """Retail: CPhysicsObj::movement_is_autonomous @ 0x0050EB30 (acclient.c:315830)"""
        return self.last_move_was_autonomous

    def is_fully_constrained(self) -> bool:
        """Retail: CPhysicsObj::IsFullyConstrained @ 0x0050EC60 (acclient.c:315932)"""
        manager = self.position_manager
        return manager is not None and manager.is_fully_constrained()

    def do_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Play ``motion`` through the part array's motion table (error 0x47 without a part array).

        Retail: CPhysicsObj::DoInterpretedMotion @ 0x0050EA70 (acclient.c:315752)
        """
        if self.part_array is None:
            return MovementError.GENERAL_MOVEMENT_FAILURE
        return self.part_array.do_interpreted_motion(motion, params)

    def stop_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPhysicsObj::StopInterpretedMotion @ 0x0050EA90 (acclient.c:315765)"""
        if self.part_array is None:
            return MovementError.GENERAL_MOVEMENT_FAILURE
        return self.part_array.stop_interpreted_motion(motion, params)

    def stop_completely_internal(self) -> None:
        """Retail: CPhysicsObj::StopCompletely_Internal @ 0x0050EAD0 (acclient.c:315787)"""
        if self.part_array is not None:
            self.part_array.stop_completely_internal()

    def initialize_motion_tables(self) -> None:
        """Retail: CPhysicsObj::InitializeMotionTables @ 0x0050EA60 (acclient.c:315742)"""
        if self.part_array is not None:
            self.part_array.initialize_motion_tables()

    def remove_link_animations(self) -> None:
        """Drop the sequence's link animations (through ``CPartArray::HandleEnterWorld``).

        Retail: CPhysicsObj::RemoveLinkAnimations @ 0x0050FE20 (acclient.c:317144)
        """
        if self.part_array is not None:
            self.part_array.handle_enter_world()

    def check_for_completed_motions(self) -> None:
        """Retail: CPhysicsObj::CheckForCompletedMotions @ 0x0050FE30 (acclient.c:317154)"""
        if self.part_array is not None:
            self.part_array.check_for_completed_motions()

    def motion_done(self, motion: int, success: bool) -> None:
        """A queued motion finished: tell the movement manager.

        Retail: CPhysicsObj::MotionDone @ 0x0050FDB0 (acclient.c:317096)
        """
        if self.movement_manager is not None:
            self.movement_manager.motion_done(motion, success)

    def set_nodraw(self, no_draw: bool, send_event: bool = False) -> bool:
        """Set or clear ``NODRAW`` (drawing itself is not ported).

        Retail: CPhysicsObj::set_nodraw @ 0x0050FCA0 (acclient.c:317008)
        """
        if no_draw:
            self.state |= PS.NODRAW
        else:
            self.state &= ~PS.NODRAW
        return True

    # -- collisions: a sweep meets this body --------------------------------------------------

    def find_obj_collisions(self, transition: SphereTransition) -> TransitionState:
        """Collide the transition's moving spheres with this body (found through a cell's shadow).

        OK at once for an ethereal body that ignores collisions, and for a creature (by its
        weenie) when the mover is a viewer. An ethereal body, or any non-static one when the mover
        is ethereal, is an ethereal obstruction: skipped (OK) while stepping down, else tested with
        ``sphere_path.obstruction_ethereal`` set, so the shapes only report overlap. Two players
        pass through each other (the exemption) unless the mover is impenetrable, this body is, or
        both are PK or both PK-lite. Unless exempt or ``OBJECTINFO.missile_ignore``, the body's
        physics BSP is tried through its parts (``HAS_PHYSICS_BSP``), else its cylspheres, else its
        spheres, each placed at ``position`` and ``scale``, until one answers other than OK.

        Such an answer, outside a step-down, is recorded: a static body flags
        ``collided_with_environment`` (unless the mover is in contact) and is not added to the
        collision objects; an ethereal obstruction, or a creature (a missile body or a creature
        weenie) met by a mover that ignores creatures, becomes OK with the collision normal
        invalidated and is added as OK; any other body is added with the answer.
        ``obstruction_ethereal`` is cleared on the way out.

        Retail: CPhysicsObj::FindObjCollisions @ 0x0050F050 (acclient.c:316158)
        """
        state = self.state
        if state & PS.ETHEREAL and state & PS.IGNORE_COLLISIONS:
            return TransitionState.OK
        path = transition.sphere_path
        info = transition.object_info
        weenie = self.weenie_obj
        if weenie is not None and info.state & ObjectInfoState.IS_VIEWER and weenie.is_creature():
            return TransitionState.OK
        ethereal = bool(state & PS.ETHEREAL or (info.ethereal and not state & PS.STATIC))
        if ethereal and path.step_down:
            return TransitionState.OK
        path.obstruction_ethereal = ethereal
        exempt = (
            weenie is not None
            and weenie.is_player()
            and bool(info.state & ObjectInfoState.IS_PLAYER)
            and not info.state & ObjectInfoState.IS_IMPENETRABLE
            and not weenie.is_impenetrable()
            and not (info.state & ObjectInfoState.IS_PK and weenie.is_pk())
            and not (info.state & ObjectInfoState.IS_PKLITE and weenie.is_pk_lite())
        )
        is_creature = bool(state & PS.MISSILE) or (weenie is not None and weenie.is_creature())
        parts = self.part_array
        result = TransitionState.OK
        if state & PS.HAS_PHYSICS_BSP and not exempt and not info.missile_ignore(self):
            if parts is not None:
                result = parts.find_obj_collisions(transition)
        elif parts is not None and parts.get_num_cylsphere() and not exempt and not info.missile_ignore(self):
            for cylsphere in parts.get_cylsphere():
                result = cylsphere.intersects_sphere_placed(self.position, self.scale, transition)
                if result != TransitionState.OK:
                    break
        elif parts is not None and parts.get_num_sphere() and not exempt and not info.missile_ignore(self):
            for sphere in parts.get_sphere():
                result = sphere.intersects_sphere_placed(self.position, self.scale, transition, is_creature)
                if result != TransitionState.OK:
                    break
        if result != TransitionState.OK and not path.step_down:
            collisions = transition.collision_info
            if state & PS.STATIC:
                if not info.state & ObjectInfoState.CONTACT:
                    collisions.collided_with_environment = True
            elif ethereal or (is_creature and info.state & ObjectInfoState.IGNORE_CREATURES):
                result = TransitionState.OK
                collisions.collision_normal_valid = False
                collisions.add_object(self, TransitionState.OK)
            else:
                collisions.add_object(self, result)
        path.obstruction_ethereal = False
        return result

    # -- shadows: the cells a body overlaps ---------------------------------------------------

    def add_obj_to_cell(self, new_cell: ObjCell, new_frame: Frame) -> None:
        """Put a static object into ``new_cell`` at ``new_frame`` and shadow it into every cell it overlaps.

        Retail: CPhysicsObj::add_obj_to_cell @ 0x005159E0 (acclient.c:322896)
        """
        self.enter_cell(new_cell)
        self.position.frame.assign(new_frame)
        if not self.state & PS.PARTICLE_EMITTER and self.part_array is not None:
            self.part_array.set_frame(self.position.frame)
        self.calc_cross_cells_static()

    def calc_cross_cells_static(self) -> None:
        """A static object's shadows: its cylspheres' cells, else its parts' bounding boxes; cells not
        yet loaded are left out.

        Retail: CPhysicsObj::calc_cross_cells_static @ 0x00515160 (acclient.c:322404)
        """
        cell_array = CellArray(self.world)
        cell_array.do_not_load_cells = True
        parts = self.part_array
        if not self.state & PS.HAS_PHYSICS_BSP and parts is not None and parts.get_num_cylsphere():
            ObjCell.find_cell_list_for_cylspheres(self.position, parts.get_cylsphere(), cell_array)
        else:
            self.find_bbox_cell_list(cell_array)
        self.remove_shadows_from_cells()
        self.add_shadows_to_cells(cell_array)

    def calc_cross_cells(self) -> None:
        """A body's shadows: its bounding boxes (physics-BSP objects), its cylspheres, else its
        sorting sphere.

        Retail: CPhysicsObj::calc_cross_cells @ 0x00515230 (acclient.c:322446)
        """
        cell_array = CellArray(self.world)
        parts = self.part_array
        if self.state & PS.HAS_PHYSICS_BSP:
            self.find_bbox_cell_list(cell_array)
        elif parts is not None and parts.get_num_cylsphere():
            ObjCell.find_cell_list_for_cylspheres(self.position, parts.get_cylsphere(), cell_array)
        else:
            sphere = parts.get_sorting_sphere() if parts is not None else DUMMY_SPHERE
            ObjCell.find_cell_list_for_sphere(self.position, sphere, cell_array)
        self.remove_shadows_from_cells()
        self.add_shadows_to_cells(cell_array)

    def find_bbox_cell_list(self, cell_array: CellArray) -> None:
        """The body's own cell, then every cell its parts' bounding boxes reach from there.

        Retail: CPhysicsObj::find_bbox_cell_list @ 0x00510FC0 (acclient.c:318275)
        """
        cell_array.clear()
        if self.cell is None:
            return
        cell_array.add_cell(self.cell.id, self.cell)
        if self.part_array is None:
            return
        index = 0
        while index < cell_array.num_cells:
            cell = cell_array.cells[index].cell
            if cell is not None:
                self.part_array.calc_cross_cells_static(cell, cell_array)
            index += 1

    def add_shadows_to_cells(self, cell_array: CellArray) -> None:
        """Make one shadow per cell of ``cell_array`` and enter it into that cell (if loaded).

        Retail: CPhysicsObj::add_shadows_to_cells @ 0x00514AE0 (acclient.c:321977)
        """
        self.shadow_objects = [ShadowObj(self, info.cell_id) for info in cell_array.cells]
        for shadow, info in zip(self.shadow_objects, cell_array.cells, strict=True):
            if info.cell is not None:
                info.cell.add_shadow_object(shadow, cell_array.num_cells)

    def remove_shadows_from_cells(self) -> None:
        """Take every shadow out of its cell.

        Retail: CPhysicsObj::remove_shadows_from_cells @ 0x00511230 (acclient.c:318417)
        """
        for shadow in self.shadow_objects:
            if shadow.cell is not None:
                shadow.cell.remove_shadow_object(shadow)
        self.shadow_objects = []

    # -- what the motion code asks of the body and its managers ----------------------------

    def get_velocity(self) -> Vector3:
        """The velocity the last step actually moved at (``cached_velocity``, a copy), not ``velocity``.

        Retail: CPhysicsObj::get_velocity @ 0x005113C0 (acclient.c:318565)
        """
        return self.cached_velocity.copy()

    def get_radius(self) -> float:
        """Retail: CPhysicsObj::GetRadius @ 0x0050E9C0 (acclient.c:315672)"""
        return self.part_array.get_radius() if self.part_array is not None else 0.0

    def get_height(self) -> float:
        """Retail: CPhysicsObj::GetHeight @ 0x0050E9E0 (acclient.c:315686)"""
        return self.part_array.get_height() if self.part_array is not None else 0.0

    def is_interpolating(self) -> bool:
        """Retail: CPhysicsObj::IsInterpolating @ 0x0050EB50 (acclient.c:315846)"""
        return self.position_manager is not None and bool(self.position_manager.is_interpolating())

    def _make_target_manager(self) -> TargetManager:
        """The target manager, created first when the body has none (inline in set_target and
        add_voyeur, acclient.c:315999-316006 and 316064-316071)."""
        if self.target_manager is None:
            from acphys.managers.target import TargetManager as RetailTargetManager

            self.target_manager = RetailTargetManager(self)
        return self.target_manager

    def set_target(self, context_id: int, object_id: int, radius: float, quantum: float) -> None:
        """Track ``object_id`` through the target manager (made here when the body has none).

        Retail: CPhysicsObj::set_target @ 0x0050ED30 (acclient.c:315991)
        """
        self._make_target_manager().set_target(context_id, object_id, radius, quantum)

    def clear_target(self) -> None:
        """Retail: CPhysicsObj::clear_target @ 0x0050ED90 (acclient.c:316011)"""
        if self.target_manager is not None:
            self.target_manager.clear_target()

    def get_target_quantum(self) -> float:
        """Retail: CPhysicsObj::get_target_quantum @ 0x0050EDC0 (acclient.c:316031)"""
        manager = self.target_manager
        if manager is None or manager.target_info is None:
            return 0.0
        return manager.target_info.quantum

    def set_target_quantum(self, new_quantum: float) -> None:
        """Retail: CPhysicsObj::set_target_quantum @ 0x0050EDA0 (acclient.c:316021)"""
        if self.target_manager is not None:
            self.target_manager.set_target_quantum(new_quantum)

    def add_voyeur(self, object_id: int, radius: float, quantum: float) -> None:
        """Let ``object_id`` track this body (the target manager is made here when missing).
        Retail's parameter is a float, so ``quantum`` reaches the voyeur table narrowed to float32.

        Retail: CPhysicsObj::add_voyeur @ 0x0050EE00 (acclient.c:316056)
        """
        self._make_target_manager().add_voyeur(object_id, radius, float32(quantum))

    def remove_voyeur(self, object_id: int) -> bool:
        """Retail: CPhysicsObj::remove_voyeur @ 0x0050EE50 (acclient.c:316076)"""
        return self.target_manager is not None and self.target_manager.remove_voyeur(object_id)

    def receive_target_update(self, info: TargetInfo) -> None:
        """Retail: CPhysicsObj::receive_target_update @ 0x0050EDE0 (acclient.c:316046)"""
        if self.target_manager is not None:
            self.target_manager.receive_update(info)

    def handle_update_target(self, target_info: TargetInfo) -> None:
        """Pass a target report (a copy each) to the movement and position managers; reports with a
        non-zero context id are not for them.

        Retail: CPhysicsObj::HandleUpdateTarget @ 0x00512BC0 (acclient.c:319966)
        """
        if target_info.context_id:
            return
        if self.movement_manager is not None:
            self.movement_manager.handle_update_target(target_info.copy())
        if self.position_manager is not None:
            self.position_manager.handle_update_target(target_info.copy())

    def make_position_manager(self) -> PositionManager:
        """Create the position manager if the body has none; a non-static body becomes active.

        Retail: CPhysicsObj::MakePositionManager @ 0x00510210 (acclient.c:317430)
        """
        if self.position_manager is None:
            from acphys.managers.position import PositionManager as RetailPositionManager

            self.position_manager = RetailPositionManager(self)
        self._activate_for_movement()
        return self.position_manager

    def get_position_manager(self) -> PositionManager:
        """The body's position manager, made first when the body has none.

        Retail: CPhysicsObj::get_position_manager @ 0x00512130 (acclient.c:319308)
        """
        return self.make_position_manager()

    def unstick_from_object(self) -> None:
        """Let go of a sticky target (through the position manager, if any).

        Retail: CPhysicsObj::unstick_from_object @ 0x0050EAE0 (acclient.c:315797)
        """
        if self.position_manager is not None:
            self.position_manager.unstick()

    def interpolate_to(self, p: Position, keep_heading: bool) -> None:
        """Glide to a server position (``keep_heading``: keep facing as now).

        Retail: CPhysicsObj::InterpolateTo @ 0x005104F0 (acclient.c:317580)
        """
        self.make_position_manager().interpolate_to(p, keep_heading)

    def stop_interpolating(self) -> None:
        """Retail: CPhysicsObj::StopInterpolating @ 0x0050EB40 (acclient.c:315836)"""
        if self.position_manager is not None:
            self.position_manager.stop_interpolating()

    def stick_to_object(self, object_id: int) -> None:
        """Stick to ``object_id``'s top-level object (its parent, if parented), with its radius and
        height; an unknown id only makes the position manager.

        Retail: CPhysicsObj::stick_to_object @ 0x005127E0 (acclient.c:319724)
        """
        manager = self.make_position_manager()
        target = self.world.get_object(object_id)
        if target is None:
            return
        if target.parent is not None:
            target = target.parent
        manager.stick_to(target.id, target.get_radius(), target.get_height())

    def get_sticky_object_id(self) -> int:
        """Retail: CPhysicsObj::get_sticky_object_id @ 0x0050EAF0 (acclient.c:315807)"""
        return self.position_manager.get_sticky_object_id() if self.position_manager is not None else 0

    def constrain_to(self, p: Position, start_distance: float, max_distance: float) -> None:
        """Leash the body to ``p`` (offsets damped from ``start_distance``, none past ``max_distance``).

        Retail: CPhysicsObj::ConstrainTo @ 0x00510520 (acclient.c:317590)
        """
        self.make_position_manager().constrain_to(p, start_distance, max_distance)

    def _distance_for_place(self, player_indoors: float, player_outdoors: float, indoors: float,
                            outdoors: float) -> float:
        """The four-way choice shared by the distance getters: player or not, env cell or not."""
        inside = (self.position.objcell_id & 0xFFFF) >= 0x100
        if self is self.world.player:
            return player_indoors if inside else player_outdoors
        return indoors if inside else outdoors

    def get_autonomy_blip_distance(self) -> float:
        """How far a server position may be and still be glided to: 25 m (player) or 20 m indoors,
        100 m outdoors.

        Retail: CPhysicsObj::GetAutonomyBlipDistance @ 0x0050EB70 (acclient.c:315860)
        """
        return self._distance_for_place(25.0, 100.0, 20.0, 100.0)

    def get_start_constraint_distance(self) -> float:
        """5 m indoors, 10 m outdoors (player or not).

        Retail: CPhysicsObj::GetStartConstraintDistance @ 0x0050EBC0 (acclient.c:315884)
        """
        return self._distance_for_place(5.0, 10.0, 5.0, 10.0)

    def get_max_constraint_distance(self) -> float:
        """20 m indoors, 50 m outdoors (player or not).

        Retail: CPhysicsObj::GetMaxConstraintDistance @ 0x0050EC10 (acclient.c:315908)
        """
        return self._distance_for_place(20.0, 50.0, 20.0, 50.0)


def _require_finite(what: str, v: Vector3) -> None:
    if not v.is_finite():
        raise ValueError(f"{what} must be finite, got ({v.x}, {v.y}, {v.z})")


def _find_visible_child_cell(
    cell: EnvCell, origin: Vector3, search_cells: bool, world: World
) -> ObjCell | None:
    """The room holding the landblock-local ``origin``: ``cell`` itself, else (``search_cells``)
    the first loaded cell of its stab list that holds it, else (not searching) the first
    portal neighbour that does.

    Retail: CEnvCell::find_visible_child_cell @ 0x0052DC50 (acclient.c:349697)
    """
    if cell.point_in_cell(origin):
        return cell
    if search_cells:
        candidates = (world.get_cell(cell_id) for cell_id in cell.stab_list)
    else:
        candidates = (portal.get_other_cell(world) for portal in cell.portals)
    for other in candidates:
        if other is not None and other.point_in_cell(origin):
            return other
    return None


#: ``CheckPositionInternal``: how far (signed, in x and in y) a placement without SLIDE may move
#: the body (acclient.c:319180-319181).
PLACEMENT_TOLERANCE = float32(0.050000001)


class SetPositionFlags(enum.IntFlag):
    """``SetPositionFlag`` (acclient.h:6123): what ``SetPosition`` may do."""

    PLACEMENT = 0x1
    TELEPORT = 0x2
    RESTORE = 0x4
    SLIDE = 0x10
    DONT_CREATE_CELLS = 0x20
    SCATTER = 0x100
    RANDOM_SCATTER = 0x200
    LINE = 0x400
    SEND_POSITION_EVENT = 0x1000


class SetPositionError(enum.IntEnum):
    """``SetPositionError`` (acclient.h:6111): what ``SetPosition`` returns."""

    OK = 0x0
    GENERAL_FAILURE = 0x1
    NO_VALID_POSITION = 0x2
    NO_CELL = 0x3
    COLLIDED = 0x4


@dataclass(slots=True)
class SetPositionStruct:
    """Retail ``SetPositionStruct`` (acclient.h:52398): a position and how to place a body there.

    Retail: SetPositionStruct::SetPositionStruct @ 0x0051BB50 (acclient.c:329731)
    """

    pos: Position = field(default_factory=Position)
    flags: SetPositionFlags = field(default_factory=SetPositionFlags)
    line: Vector3 = field(default_factory=Vector3)
    xrad: float = 0.0
    yrad: float = 0.0
    num_tries: int = 0
