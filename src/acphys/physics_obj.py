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

This module holds the tick, the commit and the state setters. The rest of
``CPhysicsObj`` lives in :mod:`acphys.body`, one module per concern, mixed
into :class:`PhysicsObj`: collision reports (``reports``), cells, shadows and
placement (``cells``), hooks, scripts and particles (``effects``), movement
and motion-table requests (``motion``), and what the managers ask of a body
(``managers``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
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
from acphys.body.cells import (
    NUM_PHYSICS_TS,
    CellMembership,
    SetPositionError,
    SetPositionFlags,
    SetPositionStruct,
)
from acphys.body.children import ChildList, Children
from acphys.body.effects import Effects
from acphys.body.managers import ManagerRequests
from acphys.body.motion import Motion
from acphys.body.reports import (
    CollisionCallback,
    CollisionKind,
    CollisionRecord,
    CollisionReport,
    CollisionReports,
    CollisionTable,
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
)
from acphys.flags import (
    DEFAULT_PHYSICS_STATE,
    STATIONARY_MASK,
    ObjectInfoState,
    PhysicsState,
    TransientState,
    member_namespace,
)
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import DUMMY_SPHERE
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3, zero_vector
from acphys.part_array import PartArray
from acphys.precision import f32, pack3, pack4, unpack3, unpack4
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.transition import Transition
from acphys.world.obj_cell import ObjCell, ShadowObj

if TYPE_CHECKING:
    from acphys.managers.scripts import PhysicsScriptTable
    from acphys.motion.movement_manager import MovementManager
    from acphys.motion.weenie import Weenie
    from acphys.world.world import World

_new = object.__new__

PS = member_namespace(PhysicsState)
TS = member_namespace(TransientState)
OI = member_namespace(ObjectInfoState)

#: The flag of a value already made (``PhysicsState(value)`` looks there too, at four times the
#: cost): the public ``state`` and ``transient_state`` are read once a record by the trace writer.
_PHYSICS_STATES = PhysicsState._value2member_map_.get
_TRANSIENT_STATES = TransientState._value2member_map_.get

#: Called after every ``update_object_internal`` with the body and the quantum integrated.
StepObserver = Callable[["PhysicsObj", float], None]


class PhysicsObj(CollisionReports, CellMembership, Children, Effects, Motion, ManagerRequests):
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
        #: ``children``: the objects this body holds (``CHILDLIST``), made on the first.
        self.children: ChildList | None = None

        #: ``state`` and ``transient_state`` as the tick keeps them: plain ints (bit tests on an
        #: ``IntFlag`` cost more); the public :attr:`state` and :attr:`transient_state` are the flags.
        self._state: int = int(DEFAULT_PHYSICS_STATE)
        self._transient_state: int = 0
        self.position = Position()
        self.cell: ObjCell | None = None

        self.velocity = zero_vector()
        self.acceleration = zero_vector()
        self.omega = zero_vector()
        self.cached_velocity = zero_vector()

        self.friction = DEFAULT_FRICTION
        self.elasticity = DEFAULT_ELASTICITY
        self.scale = 1.0
        self.translucency = 0.0
        #: ``translucencyOriginal``: the floor ``SetTranslucencyInternal`` keeps translucency above.
        self.translucency_original = 0.0
        self.update_time = 0.0
        #: ``update_times``: the latest 16-bit server stamp per ``PhysicsTimeStamp`` slot.
        self.update_times = [0] * NUM_PHYSICS_TS
        self.jumped_this_frame = False
        self.colliding_with_environment = False

        self.contact_plane = Plane()
        self.contact_plane_cell_id = 0
        self.sliding_normal = zero_vector()

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
        #: The user's step callback, called after ``observer`` with the same arguments (the step's
        #: ``step_events`` still there); ``Simulation.on_step`` hangs its callbacks here.
        self.on_step: StepObserver | None = None
        #: ``collision_table``: the objects touched lately; made by the first object collision.
        self.collision_table: CollisionTable | None = None
        #: Receives this body's collision reports (retail's weenie ``DoCollision*`` callbacks).
        self.on_collision: CollisionCallback | None = None

    def __repr__(self) -> str:
        return f"PhysicsObj({self.name!r}, {self.position!r})"

    # -- the state flags ------------------------------------------------------------------

    @property
    def state(self) -> PhysicsState:
        """``CPhysicsObj::state``, a :class:`PhysicsState` (``<PhysicsState.REPORT_COLLISIONS|...>``).

        Set it to a ``PhysicsState`` or an int of its bits; :meth:`set_state` is retail's way to
        change it (it also hides or unhides the body). Bit operators on it give plain ints.
        """
        value = self._state
        flag = _PHYSICS_STATES(value)
        return flag if flag is not None else PhysicsState(value)

    @state.setter
    def state(self, value: int) -> None:
        self._state = int(value)

    @property
    def transient_state(self) -> TransientState:
        """``CPhysicsObj::transient_state``, a :class:`TransientState`
        (``<TransientState.CONTACT|ON_WALKABLE|ACTIVE: 131>``). The tick sets it; bit operators on
        it give plain ints (``body.transient_state & TransientState.CONTACT``).
        """
        value = self._transient_state
        flag = _TRANSIENT_STATES(value)
        return flag if flag is not None else TransientState(value)

    @transient_state.setter
    def transient_state(self, value: int) -> None:
        self._transient_state = int(value)

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

        ``player_distance`` is a ``float`` field, but the cull tests the unrounded
        length still in the register (acclient.c:323112-323114); ``update_time``
        and the physics timer are doubles.

        Retail: CPhysicsObj::update_object @ 0x00515D10 (acclient.c:323080)
        """
        world = self.world
        if self.parent is not None or self.cell is None or self._state & PS.FROZEN:
            self._transient_state &= ~TS.ACTIVE
            return
        player = world.player
        if player is not None:
            self.player_vector = player.position.get_offset(self.position)
            distance = self.player_vector.length()
            self.player_distance = f32(distance)
            if distance > ACTIVITY_DISTANCE and world.activity_cull:
                self._transient_state &= ~TS.ACTIVE
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
        step = f32(quantum)
        self.update_object_internal(step)
        if self.observer is not None:
            self.observer(self, step)
        if self.on_step is not None:
            self.on_step(self, step)
        self.step_events.clear()

    # -- one step: update_object_internal --------------------------------------------------

    def update_object_internal(self, quantum: float) -> None:
        """One physics step: candidate frame, sweep, commit, then the managers.

        An inactive body only ticks its particles and scripts. ``cached_velocity`` is the swept
        offset over the quantum, divided as retail's ``Vector3::operator/`` does (by the
        reciprocal; see :meth:`Vector3.__truediv__`), acclient.c:322816-322828.

        Retail: CPhysicsObj::UpdateObjectInternal @ 0x005156B0 (acclient.c:322718)
        """
        if self._transient_state & TS.ACTIVE:
            if self.cell is None:
                return
            if self._transient_state & TS.CHECK_ETHEREAL:
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
                if self.movement_manager is None and self._transient_state & TS.ON_WALKABLE:
                    self._transient_state &= ~TS.ACTIVE
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
        self.cached_velocity = zero_vector()

    def _align_heading(self, candidate: Frame) -> None:
        """``ALIGNPATH``: face the path; else ``SLEDDING`` with velocity: face the velocity.

        Part of UpdateObjectInternal (acclient.c:322800-322810).
        """
        if self._state & PS.ALIGN_PATH:
            candidate.set_vector_heading((candidate.origin - self.position.frame.origin).normalized())
        elif self._state & PS.SLEDDING and not self.velocity.is_zero():
            candidate.set_heading(self.velocity.get_heading())

    # -- the candidate frame ---------------------------------------------------------------

    def update_position_internal(self, quantum: float, new_frame: Frame) -> None:
        """Build the candidate frame: root motion, manager offset, combine, integrate, hooks.

        Root motion is scaled by ``scale`` on walkable ground and by 0
        otherwise (its rotation always applies). ``HIDDEN`` skips root motion
        and integration. ``new_frame`` becomes ``position.frame ∘ offset``. The scaled
        offset is stored back into the frame's ``float`` origin (acclient.c:320016-320025).

        Retail: CPhysicsObj::UpdatePositionInternal @ 0x00512C30 (acclient.c:319988)
        """
        offset = Frame()
        if not self._state & PS.HIDDEN:
            if self.part_array is not None:
                self.part_array.update(quantum, offset)
            factor = self.scale if self._transient_state & TS.ON_WALKABLE else 0.0
            o = offset.origin
            o.x, o.y, o.z = unpack3(pack3(o.x * factor, o.y * factor, o.z * factor))
        if self.position_manager is not None:
            self.position_manager.adjust_offset(offset, quantum)
        new_frame.combine(self.position.frame, offset)
        if not self._state & PS.HIDDEN:
            self.update_physics_internal(quantum, new_frame)
        self.process_hooks()

    def update_physics_internal(self, quantum: float, frame: Frame) -> None:
        """Euler-integrate velocity, acceleration and omega into ``frame``.

        With any velocity: clamp to 50 m/s, apply friction, zero it when the
        (clamped, pre-friction) speed is within the 0.25 m/s deadband, then
        move by ``v·dt + a·dt²/2``. With none, a body with no movement
        manager on walkable ground is deactivated. Always ``v += a·dt`` and
        ``frame.grotate(omega·dt)``.

        ``velocity_mag2`` is a ``float`` local; the displacement terms are summed in retail's
        order with its 4-byte spills (acclient.c:317756-317769), and the ``a·dt`` of z is
        spilled before it is added (acclient.c:317771-317776).

        Retail: CPhysicsObj::UpdatePhysicsInternal @ 0x00510700 (acclient.c:317700)
        """
        v = self.velocity
        a = self.acceleration
        velocity_mag2 = f32(v.x * v.x + v.y * v.y + v.z * v.z)
        if velocity_mag2 <= 0.0:
            if self.movement_manager is None and self._transient_state & TS.ON_WALKABLE:
                self._transient_state &= ~TS.ACTIVE
        else:
            if velocity_mag2 > MAX_VELOCITY * MAX_VELOCITY:
                v = self.velocity = v.normalized() * MAX_VELOCITY
                velocity_mag2 = MAX_VELOCITY * MAX_VELOCITY
            self.calc_friction(quantum, velocity_mag2)
            v = self.velocity
            if velocity_mag2 - SMALL_VELOCITY * SMALL_VELOCITY < EPSILON:
                v.x = v.y = v.z = 0.0
            # The spills: x's half-acceleration term twice (after each dt), y's once, z's velocity
            # term and half acceleration (the float vectors ``result`` and ``w``); the x and z sums.
            ax_half_dt, ay_term, vz_term, half_az = unpack4(
                pack4(a.x * 0.5 * quantum, a.y * 0.5 * quantum * quantum, quantum * v.z, a.z * 0.5)
            )
            move_x = f32(quantum * v.x + f32(ax_half_dt * quantum))
            move_z = f32(vz_term + half_az * quantum * quantum)
            origin = frame.origin
            origin.x, origin.y, origin.z = unpack3(
                pack3(move_x + origin.x, quantum * v.y + ay_term + origin.y, move_z + origin.z)
            )
        dvz = f32(quantum * a.z)
        v.x, v.y, v.z = unpack3(pack3(quantum * a.x + v.x, quantum * a.y + v.y, dvz + v.z))
        frame.grotate(self.omega * quantum)

    def calc_friction(self, quantum: float, velocity_mag2: float) -> None:
        """Ground friction: on walkable ground, unless moving away from the contact plane.

        Velocity with a normal component of 0.25 m/s or more is left alone.
        Otherwise the normal component is removed and the rest scaled by
        ``(1 - f)^dt``. ``f`` is the body's friction; a ``SLEDDING`` body
        stops dead under 1.25 m/s (f = 1) and, at 2.5 m/s or more on a
        contact plane steeper than 10°, slides with f = 0.2.

        The normal speed is summed z first; its z component is spilled before it is taken
        off, and every velocity component is stored after each of the two steps
        (acclient.c:316111-316154).

        Retail: CPhysicsObj::calc_friction @ 0x0050EE70 (acclient.c:316090)
        """
        if not self._transient_state & TS.ON_WALKABLE:
            return
        n = self.contact_plane.N
        v = self.velocity
        normal_speed = v.z * n.z + v.y * n.y + v.x * n.x
        if normal_speed >= 0.25:
            return
        dz = f32(normal_speed * n.z)
        v.x, v.y, v.z = unpack3(pack3(v.x - normal_speed * n.x, v.y - normal_speed * n.y, v.z - dz))
        friction = self.friction
        if self._state & PS.SLEDDING:
            if velocity_mag2 < SLEDDING_STOP_SPEED2:
                friction = 1.0
            elif velocity_mag2 >= SLEDDING_FAST_SPEED2 and n.z < SLEDDING_STEEP_Z:
                friction = SLEDDING_FRICTION
        factor = math.pow(1.0 - friction, quantum)
        v.x, v.y, v.z = unpack3(pack3(factor * v.x, factor * v.y, factor * v.z))

    def calc_acceleration(self) -> None:
        """Standing on walkable ground (and not sledding): no acceleration and no omega.

        Otherwise gravity when ``GRAVITY`` is set, else nothing.

        Retail: CPhysicsObj::calc_acceleration @ 0x00510950 (acclient.c:317786)
        """
        ts = self._transient_state
        if ts & TS.CONTACT and ts & TS.ON_WALKABLE and not self._state & PS.SLEDDING:
            self.acceleration = zero_vector()
            self.omega = zero_vector()
        elif self._state & PS.GRAVITY:
            self.acceleration = Vector3(0.0, 0.0, GRAVITY)
        else:
            self.acceleration = zero_vector()

    def set_on_walkable(self, is_on_walkable: bool) -> None:
        """Set ``ON_WALKABLE``; tell the movement manager on landing and leaving; recompute acceleration.

        Retail: CPhysicsObj::set_on_walkable @ 0x00511310 (acclient.c:318501)
        """
        was_on_walkable = bool(self._transient_state & TS.ON_WALKABLE)
        if is_on_walkable:
            self._transient_state |= TS.ON_WALKABLE
        else:
            self._transient_state &= ~TS.ON_WALKABLE
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

    # -- the commit ------------------------------------------------------------------------

    def set_frame(self, frame: Frame) -> None:
        """Make ``frame`` the body's frame, and carry its children along.

        A frame whose origin is sound but whose quaternion has a NaN is
        committed with an all-zero quaternion (the next ``combine`` then
        falls back to the identity rotation).

        Retail: CPhysicsObj::set_frame @ 0x00514090 (acclient.c:321327)
        """
        committed = frame
        if not frame.is_valid() and frame.is_valid_except_for_heading():
            committed = frame.copy()  # only this case changes it, and the caller's frame stays as it was
            committed.qw = committed.qx = committed.qy = committed.qz = 0.0
        self.position.frame.assign(committed)
        if not self._state & PS.PARTICLE_EMITTER and self.part_array is not None:
            self.part_array.set_frame(self.position.frame)
        if self.children is not None:
            self.update_children_internal()

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
            ts = self._transient_state
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
        state = OI.EDGE_SLIDE if self._state & PS.EDGE_SLIDE else OI.DEFAULT
        if not admin_move:
            if self._transient_state & TS.CONTACT:
                is_water = bool(self._transient_state & TS.WATER_CONTACT)
                if self.check_contact(True):
                    transit.init_contact_plane(self.contact_plane_cell_id, self.contact_plane, is_water)
                    state |= OI.CONTACT
                    if self._transient_state & TS.ON_WALKABLE:
                        state |= OI.ON_WALKABLE
                else:
                    transit.init_last_known_contact_plane(
                        self.contact_plane_cell_id, self.contact_plane, is_water
                    )
            if self._transient_state & TS.SLIDING:
                transit.init_sliding_normal(self.sliding_normal)
        if self.part_array is not None and self.part_array.allows_free_heading():
            state |= OI.FREE_ROTATE
        if self._state & PS.MISSILE:
            state |= OI.PATH_CLIPPED
        return state

    def check_contact(self, contact: bool) -> bool:
        """``contact``, unless the body is in contact and moving off its contact plane
        (velocity · N > EPSILON).

        The dot product is summed z, y, x, as retail sums it (acclient.c:316541-316543).

        Retail: CPhysicsObj::check_contact @ 0x0050F5B0 (acclient.c:316535)
        """
        if self._transient_state & TS.CONTACT:
            v, n = self.velocity, self.contact_plane.N
            if v.z * n.z + v.y * n.y + v.x * n.x > EPSILON:
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
        prev_on_walkable = bool(self._transient_state & TS.ON_WALKABLE)
        prev_contact = bool(self._transient_state & TS.CONTACT)
        path = transit.sphere_path
        info = transit.collision_info
        if path.curr_cell is None:
            self.prepare_to_leave_visibility()
            self.store_position(path.curr_pos)
            self.world.goto_lost_cell(self)
            self._transient_state &= ~TS.ACTIVE
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
        if self._transient_state & TS.CONTACT:
            self.set_on_walkable(self.contact_plane.N.z >= FLOOR_Z)
        else:
            was_on_walkable = bool(self._transient_state & TS.ON_WALKABLE)
            self._transient_state &= ~TS.ON_WALKABLE
            if was_on_walkable:
                self._leave_ground()
            self.calc_acceleration()

        self.sliding_normal = info.sliding_normal.copy()
        self._set_transient(TS.SLIDING, info.sliding_normal_valid)
        self.handle_all_collisions(info, prev_contact, prev_on_walkable)
        if self.cell is not None:
            if self._state & PS.HAS_PHYSICS_BSP:
                self.calc_cross_cells()
            elif transit.cell_array.num_cells:
                self.remove_shadows_from_cells()
                self.add_shadows_to_cells(transit.cell_array)

    def _set_transient(self, flag: TransientState, on: bool) -> None:
        if on:
            self._transient_state |= flag
        else:
            self._transient_state &= ~flag

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
        an environment collision. True when anything was reported. In the bounce the y and z
        terms of the impulse are spilled to ``float`` before they are added, the x term is not
        (acclient.c:321876-321886).

        Retail: CPhysicsObj::handle_all_collisions @ 0x00514780 (acclient.c:321807)
        """
        on_walkable = bool(self._transient_state & TS.ON_WALKABLE)
        apply_bounce = not (prev_on_walkable and on_walkable) or bool(self._state & PS.SLEDDING)
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
                if self._state & PS.INELASTIC:
                    self.velocity = zero_vector()
                else:
                    n = collisions.collision_normal
                    v = self.velocity
                    approach = v.z * n.z + v.y * n.y + n.x * v.x
                    if approach < 0.0:
                        impulse = -(approach * (self.elasticity + 1.0))
                        dy = f32(impulse * n.y)
                        dz = f32(impulse * n.z)
                        v.x, v.y, v.z = unpack3(pack3(impulse * n.x + v.x, dy + v.y, dz + v.z))
        else:
            self.velocity = zero_vector()
        if frames in (0, 3):
            self._transient_state &= ~STATIONARY_MASK
        elif frames == 1:
            self._transient_state |= TS.STATIONARY_FALL
        elif frames == 2:
            self._transient_state |= TS.STATIONARY_STOP
        else:
            self._transient_state |= TS.STATIONARY_STUCK
        return reported

    # -- state setters ---------------------------------------------------------------------

    def set_active(self, active: bool) -> bool:
        """Activate (not a ``STATIC`` body; resyncs ``update_time`` if it was inactive) or deactivate.

        Retail: CPhysicsObj::set_active @ 0x0050FC40 (acclient.c:316979)
        """
        if not active:
            self._transient_state &= ~TS.ACTIVE
            return True
        if self._state & PS.STATIC:
            return False
        if not self._transient_state & TS.ACTIVE:
            self.update_time = self.world.cur_time
        self._transient_state |= TS.ACTIVE
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

        Retail inlines the rotation, summing x, y, z in that order (not ``localtoglobalvec``'s
        z, x, y) into a ``Vector3`` local (acclient.c:318622-318630).

        Retail: CPhysicsObj::set_local_velocity @ 0x005114D0 (acclient.c:318617)
        """
        m = self.position.frame.m
        x, y, z = local_velocity.x, local_velocity.y, local_velocity.z
        self.set_velocity(
            Vector3(
                m[0] * x + m[3] * y + m[6] * z,
                m[1] * x + m[4] * y + m[7] * z,
                m[2] * x + m[5] * y + m[8] * z,
            )
        )

    def set_omega(self, new_omega: Vector3) -> None:
        """Take ``new_omega`` (rad/s). Retail takes any value; a component past float32 range is
        an infinity once stored (a ``Vector3``), which would turn the frame to NaN in ``grotate``,
        so acphys refuses a non-finite omega. (Any finite float32 omega squares to a finite
        double, so ``grotate`` can always rotate by it.)

        Retail: CPhysicsObj::set_omega @ 0x0050F6D0 (acclient.c:316612)
        """
        _require_finite("omega", new_omega)
        self.omega = new_omega.copy()

    def set_heading(self, degrees: float) -> None:
        """Retail: CPhysicsObj::set_heading @ 0x00514160 (acclient.c:321376)"""
        frame = self.position.frame.copy()
        frame.set_heading(degrees)
        self.set_frame(frame)

    def set_elasticity(self, elasticity: float) -> None:
        """Clamp the ``float`` argument to [0, 0.1]; one that is not ``>= 0`` (a NaN too) is 0.

        Retail: CPhysicsObj::set_elasticity @ 0x0050FD40 (acclient.c:317060)
        """
        elasticity = f32(elasticity)
        if not elasticity >= 0.0:
            self.elasticity = 0.0
        else:
            self.elasticity = min(elasticity, MAX_ELASTICITY)

    def set_state(self, new_state: PhysicsState) -> None:
        """Replace ``state``; toggling ``HIDDEN`` goes through :meth:`set_hidden`.

        Retail: CPhysicsObj::set_state @ 0x00514DD0 (acclient.c:322171)
        """
        changed = new_state ^ self._state
        self._state = int(new_state)
        if changed & PS.HIDDEN:
            self.set_hidden(bool(new_state & PS.HIDDEN))

    def set_hidden(self, hidden: bool) -> None:
        """Hide: end every collision and stop reporting them, and ignore them. Unhide: the reverse,
        re-reporting the objects still in the collision table when reporting is switched back on.
        Either way the voyeurs of the body's cell hear it (``hide_object`` / ``unhide_object``).

        The retail hide scripts, child no-draw and cell visibility belong to
        rendering and are not ported.

        Retail: CPhysicsObj::set_hidden @ 0x00514C60 (acclient.c:322077)
        """
        if hidden:
            self._state |= PS.HIDDEN
            if self._state & PS.REPORT_COLLISIONS:
                self.report_collision_end(True)
                self._state &= ~PS.REPORT_COLLISIONS
            self._state |= PS.IGNORE_COLLISIONS
            if self.cell is not None:
                self.cell.hide_object(self)
        else:
            self._state &= ~(PS.HIDDEN | PS.IGNORE_COLLISIONS)
            if not self._state & PS.REPORT_COLLISIONS:
                self._state |= PS.REPORT_COLLISIONS
                self.report_collision_start()
            if self.cell is not None:
                self.cell.unhide_object(self)

    def set_ethereal(self, ethereal: bool, send_event: bool = False) -> bool:
        """Become ethereal, or try to become solid again.

        Turning solid fails while the body overlaps another (it stays
        ethereal and ``CHECK_ETHEREAL`` asks the next step to retry).

        Retail: CPhysicsObj::set_ethereal @ 0x00511C40 (acclient.c:319046)
        """
        if ethereal:
            self._state |= PS.ETHEREAL
            self._transient_state &= ~TS.CHECK_ETHEREAL
            return True
        self._state &= ~PS.ETHEREAL
        if self.parent is not None or self.cell is None or not self.ethereal_check_for_collisions():
            self._transient_state &= ~TS.CHECK_ETHEREAL
            return True
        self._transient_state |= TS.CHECK_ETHEREAL
        self._state |= PS.ETHEREAL
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


def _require_finite(what: str, v: Vector3) -> None:
    if not v.is_finite():
        raise ValueError(f"{what} must be finite, got ({v.x}, {v.y}, {v.z})")


__all__ = [
    "CollisionKind",
    "CollisionRecord",
    "CollisionReport",
    "CollisionTable",
    "PhysicsObj",
    "SetPositionError",
    "SetPositionFlags",
    "SetPositionStruct",
]
