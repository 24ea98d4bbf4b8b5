"""``TargetManager``: a body's tracked target and the voyeurs tracking it.

Every body can play two roles. As a *tracker* it holds one ``TargetInfo``
(``SetTarget``): the object it wants reports about, the report radius and
quantum, and the last report received. As a *target* it holds a table of
voyeurs (``AddVoyeur``), one per body tracking it. Setting a target registers
the tracker as a voyeur of the target object, which answers at once with a
report; afterwards, twice a second at most (``HandleTargetting``), the target
predicts each voyeur's view of it ``quantum`` seconds ahead (position +
``cached_velocity`` × quantum) and sends a fresh report when that prediction
has drifted more than the voyeur's radius from the last one sent. A tracker
whose target never answers times out after 10 s of ``Timer::cur_time``.
Reports reach the tracker's movement and position managers through
``CPhysicsObj::HandleUpdateTarget``.

The voyeur table is retail's ``LongNIHash`` (4 buckets, newest first in a
bucket), so voyeurs are visited in retail order.
"""

from __future__ import annotations

import enum
from collections.abc import Iterator
from typing import TYPE_CHECKING, Generic, TypeVar

from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

#: ``HandleTargetting`` runs at most this often (s of ``PhysicsTimer::curr_time``, acclient.c:328468).
TARGETTING_INTERVAL = 0.5
#: An unanswered target times out this long after ``SetTarget`` (s of ``Timer::cur_time``, acclient.c:328471).
TARGET_TIMEOUT = 10.0
#: ``AddVoyeur`` makes the voyeur table with this many buckets (acclient.c:328347).
VOYEUR_TABLE_SIZE = 4


class TargetStatus(enum.IntEnum):
    """Retail ``TargetStatus`` (acclient.h:7264)."""

    UNDEF = 0
    OK = 1
    EXIT_WORLD = 2
    TELEPORTED = 3
    CONTAINED = 4
    PARENTED = 5
    TIMED_OUT = 6


V = TypeVar("V")


class LongNIHash(Generic[V]):
    """Retail ``LongNIHash<T>``: a fixed bucket count, ``(key ^ key >> 16) % size`` buckets, each a
    chain with the newest entry first. Iteration is bucket by bucket, head to tail."""

    __slots__ = ("buckets",)

    def __init__(self, table_size: int) -> None:
        if table_size <= 0:
            raise ValueError(f"a LongNIHash needs at least one bucket, got {table_size}")
        self.buckets: list[list[tuple[int, V]]] = [[] for _ in range(table_size)]

    def _bucket(self, key: int) -> list[tuple[int, V]]:
        return self.buckets[(key ^ (key >> 16)) % len(self.buckets)]

    def add(self, data: V, key: int) -> None:
        """Retail: LongNIHash<ParticleEmitter>::add @ 0x005198C0 (acclient.c:327166)"""
        self._bucket(key).insert(0, (key, data))

    def lookup(self, key: int) -> V | None:
        for k, data in self._bucket(key):
            if k == key:
                return data
        return None

    def remove(self, key: int) -> V | None:
        """Unlink and return the first entry with ``key``, or None.

        Retail: LongNIHash<TargettedVoyeurInfo>::remove @ 0x0051A770 (acclient.c:328228)
        """
        bucket = self._bucket(key)
        for i, (k, data) in enumerate(bucket):
            if k == key:
                del bucket[i]
                return data
        return None

    def __iter__(self) -> Iterator[V]:
        """The entries in retail iteration order. The visit may change the table: retail's loops step
        the iterator before using an entry, so removing the current one is safe; an entry removed
        before its turn is skipped here (in retail the iterator would hold a freed node).

        Retail: LongNIHashIter<TargettedVoyeurInfo>::operator++ @ 0x0051A3D0 (acclient.c:327998)
        """
        for key, data in [entry for bucket in self.buckets for entry in bucket]:
            if self.lookup(key) is data:
                yield data

    def __len__(self) -> int:
        return sum(len(bucket) for bucket in self.buckets)


class TargetInfo:
    """A report about a tracked object, and the tracker's record of its target.

    ``interpolated_heading`` (the unit vector from the tracker to the
    interpolated position) is only written by ``ReceiveUpdate``; retail's
    constructor leaves it (and ``velocity``) uninitialised, acphys zeroes them.

    Retail ``TargetInfo`` (acclient.h:31591).

    Retail: TargetInfo::TargetInfo @ 0x0051A420 (acclient.c:328026)
    """

    __slots__ = (
        "context_id",
        "interpolated_heading",
        "interpolated_position",
        "last_update_time",
        "object_id",
        "quantum",
        "radius",
        "status",
        "target_position",
        "velocity",
    )

    def __init__(
        self,
        object_id: int = 0,
        status: int = TargetStatus.UNDEF,
        target_position: Position | None = None,
        interpolated_position: Position | None = None,
        *,
        context_id: int = 0,
        radius: float = 0.0,
        quantum: float = 0.0,
        velocity: Vector3 | None = None,
        interpolated_heading: Vector3 | None = None,
        last_update_time: float = 0.0,
    ) -> None:
        self.context_id = context_id
        self.object_id = object_id
        self.radius = radius
        self.quantum = quantum
        self.target_position = target_position or Position()
        self.interpolated_position = interpolated_position or Position()
        self.interpolated_heading = interpolated_heading or Vector3()
        self.velocity = velocity or Vector3()
        self.status = status
        self.last_update_time = last_update_time

    def copy(self) -> TargetInfo:
        """A deep copy: retail passes ``TargetInfo`` by value to ``HandleUpdateTarget``.

        Retail: TargetInfo::TargetInfo @ 0x00510630 (acclient.c:317673)
        """
        return TargetInfo(
            self.object_id,
            self.status,
            self.target_position.copy(),
            self.interpolated_position.copy(),
            context_id=self.context_id,
            radius=self.radius,
            quantum=self.quantum,
            velocity=self.velocity.copy(),
            interpolated_heading=self.interpolated_heading.copy(),
            last_update_time=self.last_update_time,
        )

    def __repr__(self) -> str:
        return (
            f"TargetInfo(0x{self.object_id:08X}, status={self.status}, quantum={self.quantum}, "
            f"radius={self.radius})"
        )


class TargettedVoyeurInfo:
    """One body tracking this one: its report radius and quantum and the last position sent to it.

    Retail ``TargettedVoyeurInfo`` (acclient.h:52807).
    """

    __slots__ = ("last_sent_position", "object_id", "quantum", "radius")

    def __init__(self, object_id: int, radius: float, quantum: float) -> None:
        self.object_id = object_id
        self.quantum = quantum
        self.radius = radius
        self.last_sent_position = Position()

    def __repr__(self) -> str:
        return f"TargettedVoyeurInfo(0x{self.object_id:08X}, radius={self.radius}, quantum={self.quantum})"


class TargetManager:
    """Retail ``TargetManager`` (acclient.h:31024).

    Retail: TargetManager::TargetManager @ 0x0051A370 (acclient.c:327973)
    """

    __slots__ = ("last_update_time", "physobj", "target_info", "voyeur_table")

    def __init__(self, physobj: PhysicsObj) -> None:
        self.physobj = physobj
        self.target_info: TargetInfo | None = None
        #: Made by the first ``add_voyeur``.
        self.voyeur_table: LongNIHash[TargettedVoyeurInfo] | None = None
        #: ``PhysicsTimer::curr_time`` of the last ``handle_targetting`` pass.
        self.last_update_time = 0.0

    # -- the tracker's side ----------------------------------------------------------------

    def set_target(self, context_id: int, object_id: int, radius: float, quantum: float) -> None:
        """Drop the current target (leaving its voyeur table), then track ``object_id``: record it as
        not yet answered (``Undef``, stamped with ``Timer::cur_time``) and, when the object exists,
        become its voyeur, which answers at once. Object id 0 instead reports a ``TimedOut`` target
        with ``context_id`` straight to ``HandleUpdateTarget``. ``radius`` is a ``float``
        parameter and field; ``quantum`` is a double.

        Retail: TargetManager::SetTarget @ 0x0051AC30 (acclient.c:328573)
        """
        obj = self.physobj
        radius = f32(radius)
        self._drop_target()
        if not object_id:
            obj.handle_update_target(TargetInfo(0, TargetStatus.TIMED_OUT, context_id=context_id))
            return
        self.target_info = TargetInfo(
            object_id,
            TargetStatus.UNDEF,
            context_id=context_id,
            radius=radius,
            quantum=quantum,
            last_update_time=obj.world.cur_time,
        )
        target = obj.world.get_object(object_id)
        if target is not None:
            target.add_voyeur(obj.id, radius, quantum)

    def clear_target(self) -> None:
        """Stop tracking: leave the target's voyeur table (if it still exists) and forget it.

        Retail: TargetManager::ClearTarget @ 0x0051A7E0 (acclient.c:328270)
        """
        self._drop_target()

    def _drop_target(self) -> None:
        """The body of ClearTarget, which SetTarget repeats inline (acclient.c:328591-328605)."""
        info = self.target_info
        if info is None:
            return
        target = self.physobj.world.get_object(info.object_id)
        if target is not None:
            target.remove_voyeur(self.physobj.id)
        self.target_info = None

    def set_target_quantum(self, new_quantum: float) -> None:
        """Change how far ahead the target should predict for this tracker, and re-register with it
        (``AddVoyeur`` on an existing voyeur only updates radius and quantum: no report).

        Retail: TargetManager::SetTargetQuantum @ 0x0051A4A0 (acclient.c:328067)
        """
        info = self.target_info
        if info is None:
            return
        info.quantum = new_quantum
        target = self.physobj.world.get_object(info.object_id)
        if target is not None:
            target.add_voyeur(self.physobj.id, info.radius, info.quantum)

    def receive_update(self, target_update: TargetInfo) -> None:
        """A report from the tracked object: take its radius, quantum, positions, velocity and status
        (the context id stays), stamp ``Timer::cur_time``, aim ``interpolated_heading`` from this body
        at the interpolated position (+z when they coincide), hand a copy to ``HandleUpdateTarget``;
        an ``ExitWorld`` report then clears the target. Reports about other objects are ignored.

        Retail: TargetManager::ReceiveUpdate @ 0x0051A930 (acclient.c:328384)
        """
        info = self.target_info
        if info is None or target_update.object_id != info.object_id:
            return
        obj = self.physobj
        info.radius = target_update.radius
        info.quantum = target_update.quantum
        info.target_position = target_update.target_position.copy()
        info.interpolated_position = target_update.interpolated_position.copy()
        info.velocity = target_update.velocity.copy()
        info.status = target_update.status
        info.last_update_time = obj.world.cur_time
        heading = obj.position.get_offset(info.interpolated_position)
        if heading.normalize_check_small():
            heading = Vector3(0.0, 0.0, 1.0)
        info.interpolated_heading = heading
        obj.handle_update_target(info.copy())
        if target_update.status == TargetStatus.EXIT_WORLD:
            self.clear_target()

    # -- the target's side -----------------------------------------------------------------

    def add_voyeur(self, object_id: int, radius: float, quantum: float) -> None:
        """Register a tracker. A known one only gets its radius and quantum updated; a new one is
        entered into the table and sent this body's position at once. ``radius`` is a
        ``float`` parameter, ``quantum`` a double (``CPhysicsObj::add_voyeur`` narrows it).

        Retail: TargetManager::AddVoyeur @ 0x0051A830 (acclient.c:328299)
        """
        radius = f32(radius)
        if self.voyeur_table is None:
            self.voyeur_table = LongNIHash(VOYEUR_TABLE_SIZE)
        else:
            known = self.voyeur_table.lookup(object_id)
            if known is not None:
                known.radius = radius
                known.quantum = quantum
                return
        voyeur = TargettedVoyeurInfo(object_id, radius, quantum)
        self.voyeur_table.add(voyeur, object_id)
        self.send_voyeur_update(voyeur, self.physobj.position, TargetStatus.OK)

    def remove_voyeur(self, object_id: int) -> bool:
        """Retail: TargetManager::RemoveVoyeur @ 0x0051AD90 (acclient.c:328643)"""
        return self.voyeur_table is not None and self.voyeur_table.remove(object_id) is not None

    def handle_targetting(self) -> None:
        """The per-tick pass, at most every 0.5 s of physics time: time out a target unanswered for
        10 s of ``Timer::cur_time`` (once: the status becomes ``TimedOut``, reported through
        ``HandleUpdateTarget``; the target is kept), then check every voyeur.

        Retail: TargetManager::HandleTargetting @ 0x0051AA90 (acclient.c:328457)
        """
        obj = self.physobj
        now = obj.world.physics_time
        if now - self.last_update_time < TARGETTING_INTERVAL:
            return
        info = self.target_info
        if (
            info is not None
            and info.status == TargetStatus.UNDEF
            and info.last_update_time + TARGET_TIMEOUT < obj.world.cur_time
        ):
            info.status = TargetStatus.TIMED_OUT
            obj.handle_update_target(info.copy())
        if self.voyeur_table is not None:
            for voyeur in self.voyeur_table:
                self.check_and_update_voyeur(voyeur)
        self.last_update_time = now

    def get_interpolated_position(self, quantum: float) -> Position:
        """This body's position ``quantum`` seconds ahead at ``get_velocity`` (its ``cached_velocity``).

        ``quantum`` is narrowed to a ``float`` local; of the step ``quantum × velocity`` only the
        z term is stored (in a ``Vector3``) before it is added to the origin
        (acclient.c:328147-328154).

        Retail: TargetManager::GetInterpolatedPosition @ 0x0051A5E0 (acclient.c:328130)
        """
        p = self.physobj.position.copy()
        q = f32(quantum)
        v = self.physobj.get_velocity()
        o = p.frame.origin
        o.x, o.y, o.z = unpack3(pack3(q * v.x + o.x, q * v.y + o.y, f32(q * v.z) + o.z))
        return p

    def check_and_update_voyeur(self, voyeur: TargettedVoyeurInfo) -> None:
        """Send an ``Ok`` report when the position predicted ``voyeur.quantum`` ahead is more than
        ``voyeur.radius`` from the last one sent (``Position::distance``, strictly greater).

        Retail: TargetManager::CheckAndUpdateVoyeur @ 0x0051A650 (acclient.c:328157)
        """
        p = self.get_interpolated_position(voyeur.quantum)
        if p.get_offset(voyeur.last_sent_position).length() > voyeur.radius:
            self.send_voyeur_update(voyeur, p, TargetStatus.OK)

    def notify_voyeur_of_event(self, event: TargetStatus) -> None:
        """Send every voyeur a report with ``event`` at this body's current position (``exit_world``
        sends ``ExitWorld``, ``teleport_hook`` ``Teleported``).

        Retail: TargetManager::NotifyVoyeurOfEvent @ 0x0051A6F0 (acclient.c:328180)
        """
        if self.voyeur_table is None:
            return
        for voyeur in self.voyeur_table:
            self.send_voyeur_update(voyeur, self.physobj.position, event)

    def send_voyeur_update(self, voyeur: TargettedVoyeurInfo, p: Position, status: TargetStatus) -> None:
        """Remember ``p`` as sent, then report to the voyeur (if it exists): this body's id, the
        voyeur's radius and quantum, this body's position as ``target_position``, ``p`` as
        ``interpolated_position``, ``get_velocity`` (``cached_velocity``) and ``status`` (context id 0).

        Retail: TargetManager::SendVoyeurUpdate @ 0x0051A4F0 (acclient.c:328091)
        """
        voyeur.last_sent_position = p.copy()
        obj = self.physobj
        info = TargetInfo(
            obj.id,
            status,
            obj.position.copy(),
            p.copy(),
            radius=voyeur.radius,
            quantum=voyeur.quantum,
            velocity=obj.get_velocity(),
        )
        tracker = obj.world.get_object(voyeur.object_id)
        if tracker is not None:
            tracker.receive_target_update(info)
