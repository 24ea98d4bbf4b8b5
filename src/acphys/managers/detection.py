"""``DetectionManager``: detection cylinders that report objects entering and leaving them, at 1 Hz.

A detection cylinder (``DetectionCylsphere``) around a body watches one other
object. Once a second of physics time the manager measures the straight-line
distance between the two positions: the object is *inside* when that
distance is strictly less than the cylinder radius plus the object's radius.
A change from outside to inside is reported as ``Entered``, from inside to
outside as ``Left``; an object that has vanished from the world is reported
``Left`` at every pass, whatever was reported before. Deletions are queued by
``DestroyDetectionCylsphere`` and applied at the start of the next tick.

The retail client carries this code but never makes a detection manager (the
server does), and its report call lands on a routine with no decompiled body
(the symbol it shows, ``gmPanelUI::ListenToGlobalMessage``, is an
identical-code-folding alias). acphys records each report on the manager, adds
a ``detection:...`` step event to the body, and calls ``on_report`` if set.

Not ported: *global* cylinders (object id 0), which detect every object in
the cells around the body through the cells' voyeur tables
(``CObjCell::add_voyeur``/``remove_voyeur``, not ported in ``world.obj_cell``);
with them go ``InitializeGlobalDetection``, ``UpdateCellList``,
``FindCellList``, ``CleanupGlobalDetection``, ``ReceiveDetectionUpdate`` and
``ReportGlobalDetection``. Creating a global cylinder is refused.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from acphys.constants import float32

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

#: ``CheckDetection`` runs at most this often (s of ``PhysicsTimer::curr_time``, acclient.c:327688).
DETECTION_INTERVAL = 1.0


class DetectionType(enum.IntEnum):
    """Retail ``DetectionType`` (acclient.h:6075)."""

    NO_CHANGE = 0
    ENTERED = 1
    LEFT = 2


class DetectionInfo:
    """An object and its latest detection status. Retail ``DetectionInfo`` (acclient.h:52492)."""

    __slots__ = ("object_id", "object_status")

    def __init__(self, object_id: int, object_status: DetectionType = DetectionType.NO_CHANGE) -> None:
        self.object_id = object_id
        self.object_status = object_status

    def __repr__(self) -> str:
        return f"DetectionInfo(0x{self.object_id:08X}, {self.object_status.name})"


class DetectionCylsphere:
    """A detection cylinder: its context id, radius, the watched object and whether it is inside.

    Retail ``DetectionCylsphere`` (acclient.h:52792).
    """

    __slots__ = ("context_id", "detection_type", "info", "object_detected", "radius")

    def __init__(self, context_id: int, radius: float, object_id: int, detection_type: int = 0) -> None:
        self.context_id = context_id
        self.radius = radius
        self.object_detected = False
        self.info = DetectionInfo(object_id)
        self.detection_type = detection_type

    def __repr__(self) -> str:
        return (
            f"DetectionCylsphere(context={self.context_id}, radius={self.radius}, "
            f"object=0x{self.info.object_id:08X}, detected={self.object_detected})"
        )


#: ``on_report(context_id, info)``: what the body's owner hears of each Entered / Left report.
DetectionCallback = Callable[[int, DetectionInfo], None]


class DetectionManager:
    """Retail ``DetectionManager`` (acclient.h:30996), object cylinders only.

    The retail table is a ``LongNIHash`` whose bucket count is set by a constructor the client
    lacks; acphys visits cylinders in creation order.
    """

    __slots__ = (
        "detection_table",
        "last_update_time",
        "on_report",
        "pending_deletions",
        "physobj",
        "reports",
    )

    def __init__(self, physobj: PhysicsObj) -> None:
        self.physobj = physobj
        #: ``PhysicsTimer::curr_time`` of the last detection pass.
        self.last_update_time = 0.0
        self.detection_table: dict[int, DetectionCylsphere] = {}
        #: Context ids queued by ``destroy_detection_cylsphere``.
        self.pending_deletions: list[int] = []
        #: Every Entered / Left report so far: (physics time, context id, object id, status).
        self.reports: list[tuple[float, int, int, DetectionType]] = []
        self.on_report: DetectionCallback | None = None

    def create_detection_cylsphere(
        self, context_id: int, radius: float, object_id: int, detection_type: int = 0
    ) -> DetectionCylsphere:
        """Watch ``object_id`` with a cylinder of ``radius`` (stored as retail's float32).

        acphys entry point: the client has no code that creates a cylinder.
        """
        if not 0 <= context_id <= 0xFFFFFFFF:
            raise ValueError(f"detection context id must be a 32-bit id, got {context_id:#x}")
        if context_id in self.detection_table:
            raise ValueError(f"detection context {context_id} already has a cylinder")
        if not (math.isfinite(radius) and radius >= 0.0):
            raise ValueError(f"detection radius must be finite and >= 0, got {radius}")
        if not object_id:
            raise ValueError(
                "global detection cylinders (object id 0) need the cells' voyeur tables "
                "(CObjCell::add_voyeur), which are not ported"
            )
        detcyl = DetectionCylsphere(context_id, float32(radius), object_id, detection_type)
        self.detection_table[context_id] = detcyl
        return detcyl

    def destroy_detection_cylsphere(self, context_id: int) -> bool:
        """Queue the cylinder of ``context_id`` for deletion at the next tick; False when there is none.

        Retail: DetectionManager::DestroyDetectionCylsphere @ 0x00519F10 (acclient.c:327643)
        """
        if context_id not in self.detection_table:
            return False
        self.pending_deletions.append(context_id)
        return True

    def clear_pending_deletions(self) -> None:
        """Delete the queued cylinders, last queued first (a context queued twice is deleted once).

        Retail: DetectionManager::ClearPendingDeletions @ 0x00519D70 (acclient.c:327512)
        """
        while self.pending_deletions:
            self.detection_table.pop(self.pending_deletions.pop(), None)

    def check_detection(self) -> None:
        """The per-tick pass: apply queued deletions, then, once a second of physics time, check
        every cylinder.

        Retail: DetectionManager::CheckDetection @ 0x00519F90 (acclient.c:327672)
        """
        self.clear_pending_deletions()
        now = self.physobj.world.physics_time
        if now - self.last_update_time < DETECTION_INTERVAL:
            return
        for detcyl in list(self.detection_table.values()):
            self.check_detection_cylsphere(detcyl)
        self.last_update_time = now

    def check_detection_cylsphere(self, detcyl: DetectionCylsphere) -> None:
        """Measure the watched object and report a change; a vanished object is reported ``Left``
        every time (``object_detected`` is left as it was).

        Retail: DetectionManager::CheckDetection @ 0x00519DD0 (acclient.c:327546)
        """
        obj = self.physobj.world.get_object(detcyl.info.object_id)
        if obj is None:
            detcyl.info.object_status = DetectionType.LEFT
        else:
            detcyl.info.object_status = self.check_object_detection(detcyl, obj)
        if detcyl.info.object_status != DetectionType.NO_CHANGE:
            self.report_detection(detcyl.context_id, detcyl.info)

    def check_object_detection(self, detcyl: DetectionCylsphere, obj: PhysicsObj) -> DetectionType:
        """``Entered`` when the object comes within ``radius + its radius`` (strictly: the distance,
        narrowed to float32 as retail stores it, must be less), ``Left`` when it gets out, else
        ``NoChange``.

        Retail: DetectionManager::CheckDetection @ 0x005196D0 (acclient.c:327020)
        """
        distance = float32(self.physobj.position.get_offset(obj.position).length())
        if obj.get_radius() + detcyl.radius <= distance:
            if detcyl.object_detected:
                detcyl.object_detected = False
                return DetectionType.LEFT
        elif not detcyl.object_detected:
            detcyl.object_detected = True
            return DetectionType.ENTERED
        return DetectionType.NO_CHANGE

    def report_detection(self, context_id: int, info: DetectionInfo) -> None:
        """Record a report (the retail call at acclient.c:327568/327581 has no client-side effect)."""
        body = self.physobj
        status = DetectionType(info.object_status)
        self.reports.append((body.world.physics_time, context_id, info.object_id, status))
        body.step_events.append(f"detection:{status.name.lower()}:{context_id}:0x{info.object_id:08X}")
        if self.on_report is not None:
            self.on_report(context_id, DetectionInfo(info.object_id, status))
