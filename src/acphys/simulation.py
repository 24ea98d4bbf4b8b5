"""The clock: ``CPhysics::UseTime`` and a driver that advances it at a fixed rate."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from acphys.constants import HUGE_QUANTUM, MIN_QUANTUM
from acphys.physics_obj import PhysicsObj
from acphys.world.world import World

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
        #: What the scenario reader found odd but loaded (one line each), for the user to see.
        self.warnings: list[str] = []
        self.tick = 0
        self._bodies: dict[str, PhysicsObj] = {}
        for body in bodies:
            self.add_body(body)
        self._events = sorted(events)
        self._next_event = 0

    def add_body(self, body: PhysicsObj) -> None:
        if body.name in self._bodies:
            raise ValueError(f"two bodies are named {body.name!r}")
        self._bodies[body.name] = body
        self.physics.add(body)

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

    def step(self) -> None:
        """One driver tick: advance the clock, apply due events, run ``CPhysics::UseTime``; every
        body's object is current afterwards."""
        self._tick()
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
        self.physics.use_time()

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
        from acphys.trace import TraceWriter

        with TraceWriter(trace) as writer:
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
