"""``DetectionManager``: detection cylinders that report objects entering and leaving them, at 1 Hz.

A detection cylinder (``DetectionCylsphere``) around a body watches one other
object. Once a second of physics time the manager measures the straight-line
distance between the two positions: the object is *inside* when that
distance is strictly less than the cylinder radius plus the object's radius.
A change from outside to inside is reported as ``Entered``, from inside to
outside as ``Left``; an object that has vanished from the world is reported
``Left`` at every pass, whatever was reported before. Deletions are queued by
``DestroyDetectionCylsphere`` and applied at the start of the next tick.

A *global* cylinder (object id 0) watches every object in the cells around
the body instead: the body registers as a voyeur of each cell a sphere of the
cylinder's radius overlaps (only cells already loaded), and those cells report
objects entering, leaving, hiding and unhiding there
(``CObjCell::add_object``/``remove_object``/``hide_object``/``unhide_object``)
through ``receive_detection_update``. There is no radius test per object: an
object anywhere in a watched cell is in range. Reports that cancel out before
the next pass (a Left then an Entered, as a body crossing between two watched
cells sends) are dropped; the 1 Hz pass reports the rest. The cell list is
refreshed when the body has moved 5 m or more since it was last made. All
global cylinders of a manager share one cell list and one table of detected
objects (the first to be checked reports them all), as in retail.

The retail client carries this code but never makes a detection manager (the
server does), and its report call lands on a routine with no decompiled body
(the symbol it shows, ``gmPanelUI::ListenToGlobalMessage``, is an
identical-code-folding alias). acphys records each report on the manager, adds
a ``detection:...`` step event to the body, and calls ``on_report`` if set.

The detected objects of global detection are kept, as in retail, in a
``LongNIHash`` of 32 buckets (``InitializeGlobalDetection``, acclient.c:327214):
an object id goes to bucket ``(id ^ id >> 16) % 32``, at the head of its chain
(``LongNIHash::add``, acclient.c:327173-327183), so the 1 Hz pass reports them
bucket by bucket, newest first within a bucket, not in the order they arrived.
The cylinder table is a ``LongNIHash`` too, but its bucket count is set by a
constructor the client lacks: acphys visits cylinders in creation order.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from acphys.geometry.sphere import Sphere
from acphys.managers.target import LongNIHash
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.world.obj_cell import CellArray, ObjCell

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

#: ``CheckDetection`` runs at most this often (s of ``PhysicsTimer::curr_time``, acclient.c:327688).
DETECTION_INTERVAL = 1.0
#: ``InitializeGlobalDetection`` makes the detected-object table with this many buckets
#: (acclient.c:327214).
DETECTION_OBJECTS_TABLE_SIZE = 32
#: ``UpdateCellList`` remakes the cell list once the body is this far from where it was last made
#: (``Position::distance >= 5.0``, acclient.c:327344).
GLOBAL_UPDATE_DISTANCE = 5.0


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
        "cell_array",
        "detection_objects",
        "detection_table",
        "last_global_update",
        "last_update_time",
        "num_pending_global_detect_updates",
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
        #: Global detection: the objects detected (by id, with their pending status), the cells
        #: watched and where the body was when that list was made; None until the first pass.
        self.detection_objects: LongNIHash[DetectionInfo] | None = None
        self.num_pending_global_detect_updates = 0
        self.cell_array: CellArray | None = None
        self.last_global_update = Position()

    def create_detection_cylsphere(
        self, context_id: int, radius: float, object_id: int, detection_type: int = 0
    ) -> DetectionCylsphere:
        """Watch ``object_id`` with a cylinder of ``radius`` (stored as retail's float32); object id 0
        makes a global cylinder, which starts watching cells at the next detection pass.

        acphys entry point: the client has no code that creates a cylinder.
        """
        if not 0 <= context_id <= 0xFFFFFFFF:
            raise ValueError(f"detection context id must be a 32-bit id, got {context_id:#x}")
        if context_id in self.detection_table:
            raise ValueError(f"detection context {context_id} already has a cylinder")
        if not (math.isfinite(radius) and radius >= 0.0):
            raise ValueError(f"detection radius must be finite and >= 0, got {radius}")
        if not 0 <= object_id <= 0xFFFFFFFF:
            raise ValueError(f"detection object id must be a 32-bit id, got {object_id:#x}")
        detcyl = DetectionCylsphere(context_id, f32(radius), object_id, detection_type)
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
        """Delete the queued cylinders, last queued first (a context queued twice is deleted once);
        a global cylinder's cell list and detected objects go with it.

        Retail: DetectionManager::ClearPendingDeletions @ 0x00519D70 (acclient.c:327512)
        """
        while self.pending_deletions:
            detcyl = self.detection_table.pop(self.pending_deletions.pop(), None)
            if detcyl is not None and not detcyl.info.object_id:
                self.cleanup_global_detection(detcyl)

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
        every time (``object_detected`` is left as it was). A global cylinder refreshes its cell
        list and reports what the cells sent since the last pass.

        Retail: DetectionManager::CheckDetection @ 0x00519DD0 (acclient.c:327546)
        """
        if not detcyl.info.object_id:
            self.update_cell_list(detcyl)
            self.report_global_detection(detcyl.context_id)
            self.num_pending_global_detect_updates = 0
            return
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
        distance = f32(self.physobj.position.get_offset(obj.position).length())
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

    # -- global detection (object id 0) ----------------------------------------------------------

    def find_cell_list(self, detcyl: DetectionCylsphere, new_cell_array: CellArray) -> None:
        """The loaded cells a sphere of the cylinder's radius around the body overlaps.

        Retail: DetectionManager::FindCellList @ 0x00519850 (acclient.c:327153)
        """
        new_cell_array.do_not_load_cells = True
        sphere = Sphere(Vector3(), detcyl.radius)
        ObjCell.find_cell_list_for_sphere(self.physobj.position, sphere, new_cell_array)

    def initialize_global_detection(self, detcyl: DetectionCylsphere) -> bool:
        """Make the detected-object table and the cell list, and become a voyeur of every loaded
        cell in it; False when already made.

        Retail: DetectionManager::InitializeGlobalDetection @ 0x00519910 (acclient.c:327193)
        """
        if self.detection_objects is not None or self.cell_array is not None:
            return False
        self.detection_objects = LongNIHash(DETECTION_OBJECTS_TABLE_SIZE)
        self.cell_array = CellArray(self.physobj.world)
        self.find_cell_list(detcyl, self.cell_array)
        for info in self.cell_array.cells:
            if info.cell is not None:
                info.cell.add_voyeur(self.physobj.id, detcyl)
        return True

    def update_cell_list(self, detcyl: DetectionCylsphere) -> None:
        """Initialize on first use; then, once the body is 5 m or more from where the list was last
        made, watch the new cells before leaving the old ones (so cells in both keep their objects
        without a report) and keep the new ids.

        Retail: DetectionManager::UpdateCellList @ 0x00519AB0 (acclient.c:327327)
        """
        if self.cell_array is None:
            self.initialize_global_detection(detcyl)
            if self.cell_array is None:
                return
        body = self.physobj
        # Position::distance (acclient.c:467031): the straight-line distance across landblocks.
        if self.last_global_update.get_offset(body.position).length() < GLOBAL_UPDATE_DISTANCE:
            return
        self.last_global_update = body.position.copy()
        new_cell_array = CellArray(body.world)
        self.find_cell_list(detcyl, new_cell_array)
        for info in new_cell_array.cells:
            if info.cell is not None:
                info.cell.add_voyeur(body.id, detcyl)
        for cell_id in self.cell_array.cell_ids():
            cell = body.world.get_cell(cell_id)
            if cell is not None:
                cell.remove_voyeur(body.id, detcyl)
        self.cell_array.clear()
        self.cell_array.do_not_load_cells = False
        for cell_id in new_cell_array.cell_ids():
            self.cell_array.add_cell(cell_id, None)

    def receive_detection_update(self, incoming_info: DetectionInfo) -> None:
        """A cell's report. Entered: new objects are added pending Entered, a pending Left is
        cancelled, anything else is marked Entered again. Left: a pending Entered is dropped (the
        object is forgotten), anything else is marked Left; an unknown object is added with the
        incoming status. Ignored before global detection is initialized.

        Retail: DetectionManager::ReceiveDetectionUpdate @ 0x005199C0 (acclient.c:327242)
        """
        table = self.detection_objects
        if table is None:
            return
        object_id = incoming_info.object_id
        known = table.lookup(object_id)
        if known is None:
            table.add(DetectionInfo(object_id, DetectionType(incoming_info.object_status)), object_id)
            self.num_pending_global_detect_updates += 1
            return
        if incoming_info.object_status == DetectionType.ENTERED:
            if known.object_status == DetectionType.LEFT:
                known.object_status = DetectionType.NO_CHANGE
                self._one_less_pending()
            else:
                known.object_status = DetectionType.ENTERED
                self.num_pending_global_detect_updates += 1
        elif known.object_status == DetectionType.ENTERED:
            table.remove(object_id)
            self._one_less_pending()
        else:
            known.object_status = DetectionType.LEFT
            self.num_pending_global_detect_updates += 1

    def _one_less_pending(self) -> None:
        if self.num_pending_global_detect_updates:
            self.num_pending_global_detect_updates -= 1

    def report_global_detection(self, context_id: int) -> None:
        """Report every detected object with a pending Entered or Left; Left ones are forgotten,
        the others settle to NoChange.

        The objects are visited in the table's order: bucket by bucket, each newest first
        (``LongNIHashIter``, acclient.c:327054, 327406-327423).

        Retail: DetectionManager::ReportGlobalDetection @ 0x00519BF0 (acclient.c:327394)
        """
        table = self.detection_objects
        if table is None:
            return
        for info in table:
            if info.object_status in (DetectionType.ENTERED, DetectionType.LEFT):
                self.report_detection(context_id, info)
            if info.object_status == DetectionType.LEFT:
                table.remove(info.object_id)
            else:
                info.object_status = DetectionType.NO_CHANGE

    def cleanup_global_detection(self, detcyl: DetectionCylsphere) -> None:
        """Forget the detected objects, then stop watching every cell of the list (the Left reports
        that brings find no table) and drop the list.

        Retail: DetectionManager::CleanupGlobalDetection @ 0x00519CC0 (acclient.c:327456)
        """
        if self.detection_objects is not None:
            self.detection_objects = None
            self.num_pending_global_detect_updates = 0
        if self.cell_array is None:
            return
        body = self.physobj
        for cell_id in self.cell_array.cell_ids():
            cell = body.world.get_cell(cell_id)
            if cell is not None:
                cell.remove_voyeur(body.id, detcyl)
        self.cell_array = None
