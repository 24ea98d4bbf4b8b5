"""The clock: ``CPhysics::UseTime`` and a driver that advances it at a fixed rate."""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from acphys.arrays import BodyArrays, body_arrays
from acphys.constants import HUGE_QUANTUM, MIN_QUANTUM
from acphys.physics_obj import PhysicsObj
from acphys.world.world import World

if TYPE_CHECKING:
    from acphys.scenario.live import ScenarioParts

#: ``CObjectMaint::object_table``, the table ``CPhysics::UseTime`` walks, is a
#: ``LongHash`` of 128 buckets with a key shift of 8; it never grows.
#: Retail: CObjectMaint::CObjectMaint @ 0x005085D0 (acclient.c:310011)
OBJECT_TABLE_BUCKETS = 128
OBJECT_TABLE_KEY_SHIFT = 8


def object_table_bucket(object_id: int) -> int:
    """The object-table bucket of ``object_id``: ``(id ^ (id >> 8)) & 127``.

    Retail: CObjectMaint::AddObject @ 0x00507CE0 (acclient.c:309355)
    """
    return (object_id ^ (object_id >> OBJECT_TABLE_KEY_SHIFT)) & (OBJECT_TABLE_BUCKETS - 1)


class Physics:
    """Retail ``CPhysics``: the bodies the clock updates, in the order of retail's object table.

    ``CPhysics::UseTime`` walks ``CObjectMaint::object_table`` bucket by
    bucket (``HashBaseIter::Next``, acclient.c:263092), and ``AddObject``
    puts a new object at the head of its bucket's chain. So bodies run in
    ascending bucket order and, within a bucket, newest first. Which body
    moves first decides who sees whom where bodies meet; with ids counting up
    from 0x80000001, the first 127 bodies run in the order they were added.
    """

    def __init__(self, world: World) -> None:
        self.world = world
        #: Each bucket's chain, oldest first: the head of retail's chain is the last entry.
        self._buckets: list[list[PhysicsObj]] = [[] for _ in range(OBJECT_TABLE_BUCKETS)]
        #: The walk order, made again (once) by the first walk after an ``add``.
        self._order: list[PhysicsObj] | None = []
        #: ``last_update``: when the bodies were last run.
        self.last_update = world.cur_time

    def add(self, obj: PhysicsObj) -> None:
        """Put ``obj`` at the head of its bucket (retail ``CObjectMaint::AddObject``).

        Constant time: the chain keeps its head last, and the walk order is made again only
        when it is next needed, so adding N bodies costs O(N), not O(N²).
        """
        self._buckets[object_table_bucket(obj.id)].append(obj)
        self._order = None

    def _walk_order(self) -> list[PhysicsObj]:
        """Bucket by bucket, each chain from its head (the newest) back (``HashBaseIter::Next``)."""
        if self._order is None:
            self._order = [body for bucket in self._buckets for body in reversed(bucket)]
        return self._order

    @property
    def objects(self) -> list[PhysicsObj]:
        """The bodies in the order ``use_time`` runs them."""
        return list(self._walk_order())

    def use_time(self) -> bool:
        """Run every body's ``update_object`` once at least MIN_QUANTUM has passed.

        A clock that went backwards resyncs ``last_update``. Returns whether
        the bodies ran. (Retail also animates static objects and texture
        velocities here; neither moves a body.)

        Retail: CPhysics::UseTime @ 0x00509950 (acclient.c:311334)
        """
        elapsed = self.world.cur_time - self.last_update
        if elapsed < 0.0:
            self.last_update = self.world.cur_time
            return False
        if elapsed < MIN_QUANTUM:
            return False
        for obj in self._walk_order():
            if self.world.has_object(obj):  # a removed object is no longer in the table
                obj.update_object()
        self.last_update = self.world.cur_time
        return True

    def apply_events(self, events: list[Event], body_named: Callable[[str], PhysicsObj]) -> None:
        """Apply ``events`` in order, each to the body it names (before this tick's ``use_time``)."""
        for event in events:
            event.apply(body_named(event.body))

    def sync_objects(self) -> None:
        """Make every body's object current (the reference path's always are)."""

    def body_arrays(self, bodies: list[PhysicsObj]) -> BodyArrays:
        """The state of ``bodies`` as :class:`~acphys.arrays.BodyArrays`, current whether or not
        their objects are (the reference path's objects are the state)."""
        return body_arrays(bodies)

    def set_trace_writer(self, writer: Any) -> None:
        """The trace being written, if any (the reference path's bodies write their own records)."""


#: A scheduled change to a body: applied when the driver clock reaches ``at``.
@dataclass(order=True)
class Event:
    at: float
    body: str = field(compare=False)
    action: str = field(compare=False)
    apply: Callable[[PhysicsObj], None] = field(compare=False, repr=False)
    source: str = field(compare=False, default="")


class Callbacks(list[Callable[[PhysicsObj, Any], Any]]):
    """The callbacks a simulation calls for every body, in the order they were registered
    (:meth:`Simulation.on_step`, :meth:`Simulation.on_collision`): hung on each body's hook
    (``on_step``, ``on_collision``) as one callable."""

    def __call__(self, body: PhysicsObj, value: Any) -> None:
        for callback in tuple(self):  # a callback may remove itself
            callback(body, value)


C = TypeVar("C", bound=Callable[..., Any])


#: The engines a simulation can run on (``Simulation(engine=...)``).
ENGINES = ("reference", "fast")


def make_physics(world: World, engine: str) -> Physics:
    """The ``CPhysics`` of ``engine``: the plain-Python reference, or the compiled fast engine
    (:mod:`acphys.fast`) that falls back to it body-step by body-step."""
    if engine == "reference":
        return Physics(world)
    if engine == "fast":
        from acphys.fast.engine import FastPhysics

        return FastPhysics(world)
    raise ValueError(f"engine must be one of {', '.join(ENGINES)}, got {engine!r}")


#: The driver clock ticks on a grid of 2^-30 s (about a nanosecond).
CLOCK_GRID = 2.0**30
#: The slowest driver, a tick every ``HUGE_QUANTUM`` (2 s): on a slower one every quantum would be
#: longer than that, which ``update_object`` discards, so no body would ever move.
MIN_DRIVER_HZ = 1.0 / HUGE_QUANTUM
#: The fastest driver (a tick every 0.1 ms; bodies still run at most at 30 Hz).
MAX_DRIVER_HZ = 1e4
#: The most driver ticks one run may take: a scenario's longest duration (10^6 s, 11.6 days) at
#: the usual 60 Hz. Even an empty world takes about a microsecond a tick and a body some 0.2 ms
#: a step, so a run past this would take days: a mistake, refused rather than started.
MAX_DRIVER_TICKS = 60_000_000


def driver_tick_seconds(driver_hz: float) -> float:
    """The driver's tick: 1/driver_hz rounded *up* to the 2^-30-s grid.

    On that grid every tick time ``k · tick`` is exact in binary, so the time
    between ticks never rounds below its nominal value: two ticks of a 60-Hz
    driver always make MIN_QUANTUM and the bodies run at a steady 30 Hz.
    (With ``k / 60`` the difference of two tick times rounds below 1/30 most
    of the time and the bodies would mostly run every third tick.)
    """
    return math.ceil(CLOCK_GRID / driver_hz) / CLOCK_GRID


class Simulation:
    """A world, its bodies, a timeline of events, and a driver clock at ``driver_hz``.

    Each driver tick ``k`` sets ``world.cur_time = k · tick`` (see
    :func:`driver_tick_seconds`), applies the events due by then (in file
    order), and calls :meth:`Physics.use_time`, which runs the bodies only
    when at least 1/30 s has passed since they last ran.
    """

    def __init__(
        self,
        world: World,
        bodies: Iterable[PhysicsObj] = (),
        events: Iterable[Event] = (),
        driver_hz: float = 60.0,
        duration: float = 10.0,
        name: str = "",
        engine: str = "reference",
    ) -> None:
        if not MIN_DRIVER_HZ <= driver_hz <= MAX_DRIVER_HZ:
            raise ValueError(
                f"driver_hz must be in [{MIN_DRIVER_HZ:g}, {MAX_DRIVER_HZ:g}] Hz, got {driver_hz}"
            )
        self.world = world
        self.engine = engine
        self.physics = make_physics(world, engine)
        self.driver_hz = driver_hz
        self.tick_seconds = driver_tick_seconds(driver_hz)
        self.duration = duration
        self.name = name
        #: The SHA-256 of the scenario the simulation was built from (its text), for trace headers.
        self.scenario_sha256: str | None = None
        #: What the scenario reader found odd but loaded (one line each), for the user to see.
        self.warnings: list[str] = []
        self.tick = 0
        #: What the simulation's scenario declared, for :meth:`add_body` and :meth:`add_event`
        #: (set by the scenario reader; None: only the built-in setups and motion tables).
        self.scenario_parts: ScenarioParts | None = None
        self._step_callbacks = Callbacks()
        self._collision_callbacks = Callbacks()
        #: True while ``use_time`` runs the bodies: no body or callback may be added then.
        self._in_use_time = False
        self._bodies: dict[str, PhysicsObj] = {}
        for body in bodies:
            self.add_body(body)
        self._events = sorted(events)
        self._next_event = 0

    def add_body(self, body: PhysicsObj | Mapping[str, Any] | None = None, **keys: Any) -> PhysicsObj:
        """Add a body, before the first step or between steps (it runs from the next tick on, in
        its place in the object table's order), and return it.

        ``body`` is a :class:`PhysicsObj` made in this simulation's world, or the keys of a
        scenario ``[[body]]`` table, as a mapping or as keyword arguments::

            sim.add_body(name="crate-2", setup="crate", landblock="0xA9B4", origin=[60, 90, 50],
                         on_ground=True)

        read and placed as the scenario reader does (``setup`` and ``motion_table`` may name the
        scenario's own, :mod:`acphys.scenario.live`); a bad key is a ``ScenarioError`` (a
        ValueError) naming it, and leaves nothing in the world. A name another body has is a
        ValueError. The simulation's step and collision callbacks reach the new body too.
        From inside a step (a step or collision callback) it is a RuntimeError: add bodies
        between steps, or from an event (:meth:`add_event`).
        """
        self._refuse_in_step("add a body")
        if body is None or isinstance(body, Mapping):
            if body is not None and keys:
                raise TypeError("add_body takes a body's keys as a mapping or as keyword arguments, not both")
            table = dict(body) if body is not None else keys
            name = table.get("name")
            if isinstance(name, str) and name in self._bodies:
                raise ValueError(f"two bodies are named {name!r}")
            self.physics.sync_objects()  # the world the new body is placed in is current
            body, warnings = self._scenario_parts().read_body(self.world, table)
            self.warnings.extend(warnings)
        elif keys:
            raise TypeError("add_body takes keys only to make a body, not with a PhysicsObj")
        elif not isinstance(body, PhysicsObj):
            raise TypeError(f"add_body takes a PhysicsObj or a body's keys, got {type(body).__name__}")
        elif body.world is not self.world:
            raise ValueError(f"body {body.name!r} was made in another world than the simulation's")
        if body.name in self._bodies:
            raise ValueError(f"two bodies are named {body.name!r}")
        self._check_hooks([body])
        self._bodies[body.name] = body
        self.physics.add(body)
        self._hang_callbacks(body)
        return body

    def add_event(
        self,
        at: float,
        body: str | PhysicsObj,
        action: str | Callable[[PhysicsObj], Any],
        **keys: Any,
    ) -> Event:
        """Schedule ``action`` on ``body`` (a name or the body) at ``at`` seconds, and return the
        event. Any time: before the run, between steps, from a callback.

        ``action`` is a scenario event action (``"motion"``, ``"jump"``, ``"set_velocity"``,
        ``"move_to"``, ... the ``[[event]]`` actions) with its keys as keyword arguments, checked
        as a scenario file's are (a ``ScenarioError``, a ValueError, naming the key)::

            sim.add_event(2.0, "runner", "motion", motion="RunForward", hold_run=True)

        or a function of the body, called then (``sim.add_event(2.0, "ball", lambda b: ...)``).
        The event is applied at the first driver tick at or after ``at`` that has not run yet,
        after the events already due then (an event at the current time: the next tick). A time
        already past is a ValueError.
        """
        if isinstance(at, bool) or not isinstance(at, int | float) or not math.isfinite(at):
            raise ValueError(f"an event's time must be a finite number of seconds, got {at!r}")
        if at < self.time:
            raise ValueError(
                f"an event at {at:g} s is in the past: the simulation is at {self.time:g} s "
                f"(driver tick {self.tick}); give a time of at least {self.time:g} s"
            )
        if isinstance(body, PhysicsObj):
            if self._bodies.get(body.name) is not body:
                raise ValueError(f"body {body.name!r} is not one of this simulation's")
            body = body.name
        if callable(action):
            if keys:
                raise TypeError("an event whose action is a function takes no keys")
            self.body(body)  # a KeyError naming the bodies when there is none of that name
            name = getattr(action, "__name__", type(action).__name__)
            event = Event(at=float(at), body=body, action=name, apply=action, source="add_event")
        else:
            event = self._scenario_parts().read_event(float(at), body, action, keys, self._bodies)
        place = bisect.bisect_right(self._events, event.at, lo=self._next_event, key=lambda e: e.at)
        self._events.insert(place, event)
        return event

    # -- callbacks --------------------------------------------------------------------------

    def on_step(self, callback: C) -> C:
        """Call ``callback(body, quantum)`` after every physics step of every body (bodies added
        later too), ``quantum`` the seconds the step integrated; the body is as the step left it,
        its ``step_events`` (``"hit_ground"``, ``"collision:NAME"``, ...) still there. Callbacks run
        in the order registered, after a trace's record of the step. Returns ``callback`` (so it
        can decorate). On the fast engine a body with callbacks runs on the reference path.

        It hangs on each body's ``on_step`` hook: a body whose ``on_step`` was set by hand is a
        ValueError. Register callbacks before the first step or between steps (from inside one:
        RuntimeError); :meth:`remove_callback` takes one away at any time.
        """
        self._register(self._step_callbacks, "on_step", callback)
        return callback

    def on_collision(self, callback: C) -> C:
        """Call ``callback(body, report)`` for every collision report a body receives (bodies
        added later too): a :class:`~acphys.physics_obj.CollisionReport` of the environment, of
        another object, of a missile's hit, or of a collision's end (``report.kind``,
        ``report.other``, ``report.velocity``, ...), as retail hands them to the body's weenie. A body
        receives reports only with ``REPORT_COLLISIONS`` in its ``state``. Returns ``callback``.
        On the fast engine a body with callbacks runs on the reference path.

        It hangs on each body's ``on_collision`` hook, under the same rules as :meth:`on_step`.
        """
        self._register(self._collision_callbacks, "on_collision", callback)
        return callback

    def remove_callback(self, callback: Callable[..., Any]) -> None:
        """Stop calling ``callback`` (every registration of it, by :meth:`on_step` or
        :meth:`on_collision`); a callback that is neither is a ValueError. Allowed at any time,
        from inside the callback too."""
        found = False
        for callbacks in (self._step_callbacks, self._collision_callbacks):
            while callback in callbacks:
                callbacks.remove(callback)
                found = True
        if not found:
            raise ValueError(f"{callback!r} is not a step or collision callback of this simulation")
        for body in self._bodies.values():
            self._hang_callbacks(body)
        if not self._in_use_time:
            self.physics.sync_objects()  # the fast engine may take the bodies back into its kernel

    def _register(self, callbacks: Callbacks, hook: str, callback: Callable[..., Any]) -> None:
        if not callable(callback):
            raise TypeError(f"a callback must be callable, got {type(callback).__name__}")
        self._refuse_in_step("register a callback")
        for body in self._bodies.values():
            own = getattr(body, hook)
            if own is not None and own is not callbacks:
                raise ValueError(
                    f"body {body.name!r} has its own {hook} ({own!r}): the simulation's callbacks "
                    f"would replace it; set body.{hook} = None first"
                )
        callbacks.append(callback)
        self.physics.sync_objects()  # the fast engine sees the bodies' new hooks
        for body in self._bodies.values():
            self._hang_callbacks(body)

    def _check_hooks(self, bodies: Iterable[PhysicsObj]) -> None:
        """Refuse (ValueError) a body whose own hook the simulation's callbacks would replace."""
        for body in bodies:
            for hook, callbacks in self._hooks():
                own = getattr(body, hook)
                if callbacks and own is not None and own is not callbacks:
                    raise ValueError(
                        f"body {body.name!r} has its own {hook} ({own!r}), and the simulation has "
                        f"{hook} callbacks that would replace it"
                    )

    def _hooks(self) -> tuple[tuple[str, Callbacks], ...]:
        """Each body hook the simulation's callbacks hang on, with those callbacks."""
        return (("on_step", self._step_callbacks), ("on_collision", self._collision_callbacks))

    def _hang_callbacks(self, body: PhysicsObj) -> None:
        """Point ``body``'s hooks at the simulation's callbacks, or clear them when there are none."""
        for hook, callbacks in self._hooks():
            own = getattr(body, hook)
            if callbacks and own is None:
                setattr(body, hook, callbacks)
            elif not callbacks and own is callbacks:
                setattr(body, hook, None)

    def _refuse_in_step(self, what: str) -> None:
        if self._in_use_time:
            raise RuntimeError(
                f"cannot {what} while the bodies are being stepped (from a step or collision "
                "callback): do it between steps, or from an event (add_event)"
            )

    def _scenario_parts(self) -> ScenarioParts:
        if self.scenario_parts is None:
            from acphys.scenario.live import ScenarioParts

            self.scenario_parts = ScenarioParts()
        return self.scenario_parts

    # -- state as arrays ----------------------------------------------------------------------

    def arrays(self) -> BodyArrays:
        """Every body's state as NumPy arrays in one call, a row per body in :attr:`bodies`
        order (``names``): ``positions`` (map-wide, (N, 3)), ``origins`` (landblock-local) and
        ``cell_ids``, ``orientations`` ((N, 4), w first), ``velocities``, ``cached_velocities``,
        ``omegas`` and ``transient_states``; see :class:`acphys.arrays.BodyArrays`."""
        bodies = list(self._bodies.values())
        if self._in_use_time:  # a callback: the engine wrote every object back before the step
            return body_arrays(bodies)
        return self.physics.body_arrays(bodies)

    def positions(self) -> Any:
        """Every body's origin in the map-wide frame, an (N, 3) array in :attr:`bodies` order
        (``arrays().positions``)."""
        return self.arrays().positions

    def velocities(self) -> Any:
        """Every body's ``velocity``, an (N, 3) array in :attr:`bodies` order (``arrays().velocities``)."""
        return self.arrays().velocities

    def body(self, name: str) -> PhysicsObj:
        try:
            return self._bodies[name]
        except KeyError:
            raise KeyError(f"no body named {name!r} (bodies: {', '.join(self._bodies)})") from None

    @property
    def bodies(self) -> list[PhysicsObj]:
        return list(self._bodies.values())

    @property
    def events(self) -> list[Event]:
        """The timeline, in firing order."""
        return list(self._events)

    @property
    def time(self) -> float:
        return self.world.cur_time

    def step(self, sync: bool = True) -> None:
        """One driver tick: advance the clock, apply due events, run ``CPhysics::UseTime``; every
        body's object is current afterwards.

        With ``sync=False`` on the fast engine, the objects of the bodies its kernel stepped lag
        behind until :meth:`sync` (or a call that needs them: an event, a new body, ``run``'s
        end); :meth:`arrays` stays current. Writing every object back and reading it again costs
        about as much as a hundred kernel steps a body, so a loop of many fast steps reads
        :meth:`arrays` and syncs only when it needs the objects. Change a body's object only
        after a sync: a change to a lagging object is overwritten. The reference engine's
        objects are always current.
        """
        self._tick()
        if sync:
            self.physics.sync_objects()

    def sync(self) -> None:
        """Bring every body's object up to date (after ``step(sync=False)`` on the fast engine)."""
        if self._in_use_time:
            raise RuntimeError("sync() is called between steps, not from a callback during one")
        self.physics.sync_objects()

    def _tick(self) -> None:
        self.tick += 1
        self.world.cur_time = self.tick * self.tick_seconds
        first = self._next_event
        while (
            self._next_event < len(self._events) and self._events[self._next_event].at <= self.world.cur_time
        ):
            self._next_event += 1
        if self._next_event > first:
            self.physics.apply_events(self._events[first : self._next_event], self.body)
        self._in_use_time = True
        try:
            self.physics.use_time()
        finally:
            self._in_use_time = False

    def check_until(self, until: float) -> None:
        """Refuse (ValueError) a time to run to that is not a finite number of seconds, or that
        lies more than ``MAX_DRIVER_TICKS`` driver ticks ahead."""
        if not math.isfinite(until):
            raise ValueError(f"until must be a finite number of seconds, got {until}")
        ticks = (until - self.time) * self.driver_hz
        if ticks > MAX_DRIVER_TICKS:
            raise ValueError(
                f"running to {until:g} s at {self.driver_hz:g} Hz is {ticks:.3g} driver ticks, "
                f"more than the {MAX_DRIVER_TICKS:,} a run may take (MAX_DRIVER_TICKS)"
            )

    def run(
        self,
        until: float | None = None,
        trace: str | Path | None = None,
        progress: Callable[[float, float], Any] | None = None,
    ) -> None:
        """Run the driver until ``until`` seconds (default: the duration), writing a trace if asked.

        ``progress(now, end)`` is called after every tick when given. An ``until`` that is not
        finite, or more than ``MAX_DRIVER_TICKS`` ticks away, is a ValueError (:meth:`check_until`).
        """
        end = self.duration if until is None else until
        self.check_until(end)
        if trace is None:
            self._run_until(end, progress)
            return
        from acphys.trace import TraceWriter, trace_header

        header = trace_header(self.name, self.scenario_sha256, self.driver_hz, self.engine)
        with TraceWriter(trace, header) as writer:
            self.physics.sync_objects()
            mine = {id(body) for body in self.bodies}
            writer.write_start(body for body in self.physics.objects if id(body) in mine)
            writer.attach(self.bodies)
            self.physics.set_trace_writer(writer)
            try:
                self._run_until(end, progress)
            finally:
                self.physics.set_trace_writer(None)
                writer.detach(self.bodies)

    def _run_until(self, end: float, progress: Callable[[float, float], Any] | None) -> None:
        try:
            while self.world.cur_time < end:
                self._tick()
                if progress is not None:
                    progress(self.world.cur_time, end)
        finally:
            self.physics.sync_objects()
