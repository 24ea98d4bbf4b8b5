"""DetectionManager against the retail decompilation (CDetectionCylsphere.c).

Expected values are worked by hand from the cited acclient.c lines.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState, TransientState
from acphys.managers.detection import DetectionInfo, DetectionManager, DetectionType
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.world.world import World
from support import LANDBLOCK, place

ENTERED, LEFT = DetectionType.ENTERED, DetectionType.LEFT
CONTEXT = 7


def prop(world: World, x: float, y: float, radius: float) -> PhysicsObj:
    """A sphere-less body at (x, y, 50) whose setup radius is ``radius`` (what GetRadius reads)."""
    b = place(world, name="prop", spheres=False, origin=(x, y, 50.0), on_ground=True)
    b.part_array.setup.radius = radius
    return b


def move(b: PhysicsObj, x: float, y: float) -> None:
    b.position.frame.origin.x = x
    b.position.frame.origin.y = y


@pytest.fixture
def scene(world: World) -> tuple[PhysicsObj, PhysicsObj, DetectionManager]:
    """A watcher at (96, 96) with a 2.5-m cylinder on a 0.5-m prop 5 m north: in range below 3 m."""
    world.set_flat_ground(LANDBLOCK, 50.0)
    watcher = place(world, name="watcher", spheres=False, origin=(96.0, 96.0, 50.0), on_ground=True)
    thing = prop(world, 96.0, 101.0, 0.5)
    manager = DetectionManager(watcher)
    watcher.detection_manager = manager
    manager.create_detection_cylsphere(CONTEXT, 2.5, thing.id)
    return watcher, thing, manager


def check_at(manager: DetectionManager, t: float) -> None:
    manager.physobj.world.physics_time = t
    manager.check_detection()


def statuses(manager: DetectionManager) -> list[tuple[float, DetectionType]]:
    return [(t, status) for t, _, _, status in manager.reports]


def test_enter_and_leave_at_one_hertz(scene: tuple[PhysicsObj, PhysicsObj, DetectionManager]) -> None:
    _, thing, manager = scene
    move(thing, 96.0, 98.0)  # 2 m < 3 m: inside
    # curr_time - last_update_time >= 1.0 gates the pass (acclient.c:327688): 0.99 is too early.
    check_at(manager, 0.99)
    assert manager.reports == []
    # First pass: not yet detected and inside -> Entered, object_detected = 1 (acclient.c:327046-327048).
    check_at(manager, 1.0)
    assert manager.reports == [(1.0, CONTEXT, thing.id, ENTERED)]
    # Out again at 1.5: no pass until 2.0 (last_update_time restamped to 1.0, acclient.c:327722-327723).
    move(thing, 96.0, 100.0)
    check_at(manager, 1.5)
    check_at(manager, 1.99)
    assert len(manager.reports) == 1
    check_at(manager, 2.0)
    assert statuses(manager) == [(1.0, ENTERED), (2.0, LEFT)]
    # Still out: NoChange, nothing reported (acclient.c:327051).
    check_at(manager, 3.0)
    assert len(manager.reports) == 2


def test_in_range_is_strictly_inside(scene: tuple[PhysicsObj, PhysicsObj, DetectionManager]) -> None:
    _, thing, manager = scene
    # radius_obj + radius <= distance is out of range (acclient.c:327037): exactly 3 m is out.
    move(thing, 96.0, 99.0)
    check_at(manager, 1.0)
    assert manager.reports == []
    move(thing, 96.0, 98.999)
    check_at(manager, 2.0)
    assert statuses(manager) == [(2.0, ENTERED)]


def test_distance_is_narrowed_to_float32(scene: tuple[PhysicsObj, PhysicsObj, DetectionManager]) -> None:
    # The distance is stored to a float before the compare (acclient.c:327034): 3 - 1e-9 m rounds to 3.0f,
    # which is out of range, although the double distance is inside.
    _, thing, manager = scene
    move(thing, 96.0, 99.0 - 1e-9)
    check_at(manager, 1.0)
    assert manager.reports == []


def test_object_radius_counts(world: World) -> None:
    # GetRadius of the object is added to the cylinder radius (acclient.c:327035-327037): a 1.0-m prop
    # 3.2 m away is inside a 2.5-m cylinder (3.5 > 3.2), a 0.5-m one is not.
    world.set_flat_ground(LANDBLOCK, 50.0)
    watcher = place(world, name="watcher", spheres=False, origin=(96.0, 96.0, 50.0), on_ground=True)
    big = prop(world, 96.0, 99.2, 1.0)
    small = prop(world, 99.2, 96.0, 0.5)
    manager = DetectionManager(watcher)
    manager.create_detection_cylsphere(1, 2.5, big.id)
    manager.create_detection_cylsphere(2, 2.5, small.id)
    check_at(manager, 1.0)
    assert manager.reports == [(1.0, 1, big.id, ENTERED)]


def test_vanished_object_is_reported_left_every_pass(
    scene: tuple[PhysicsObj, PhysicsObj, DetectionManager],
) -> None:
    # GetObjectA fails -> status LeftDetection and a report, every pass, whether or not it was ever detected;
    # object_detected is not touched (acclient.c:327574-327581).
    _, thing, manager = scene
    detcyl = manager.detection_table[CONTEXT]
    thing.world.remove_object(thing)
    check_at(manager, 1.0)
    check_at(manager, 2.0)
    assert statuses(manager) == [(1.0, LEFT), (2.0, LEFT)]
    assert detcyl.object_detected is False


def test_report_reaches_the_body_and_the_callback(
    scene: tuple[PhysicsObj, PhysicsObj, DetectionManager],
) -> None:
    watcher, thing, manager = scene
    heard: list[tuple[int, DetectionInfo]] = []
    manager.on_report = lambda context, info: heard.append((context, info))
    move(thing, 96.0, 97.0)
    check_at(manager, 1.0)
    assert [(c, i.object_id, i.object_status) for c, i in heard] == [(CONTEXT, thing.id, ENTERED)]
    assert f"detection:entered:{CONTEXT}:0x{thing.id:08X}" in watcher.step_events


def test_destroy_waits_for_the_next_tick(scene: tuple[PhysicsObj, PhysicsObj, DetectionManager]) -> None:
    # DestroyDetectionCylsphere only queues the context (acclient.c:327643); CheckDetection clears the queue
    # first, every tick, gate or not (acclient.c:327687).
    _, thing, manager = scene
    assert manager.destroy_detection_cylsphere(CONTEXT) is True
    assert manager.destroy_detection_cylsphere(CONTEXT) is True  # queued twice; removed once
    assert manager.destroy_detection_cylsphere(99) is False
    assert CONTEXT in manager.detection_table
    move(thing, 96.0, 97.0)
    check_at(manager, 0.5)
    assert manager.detection_table == {} and manager.pending_deletions == []
    check_at(manager, 1.0)
    assert manager.reports == []


def test_the_tick_runs_detection(world: World) -> None:
    # UpdateObjectInternal ticks the detection manager of an active body (acclient.c:322873); with 1/8-s
    # steps the physics timer reaches 1.0 exactly on the eighth step. (A body at rest without a movement
    # manager goes inactive and then ticks no managers at all, so the watcher gets a motion table.)
    world.set_flat_ground(LANDBLOCK, 50.0)
    humanoid = builtin_motion_table("humanoid")
    watcher = place(world, name="watcher", origin=(96.0, 96.0, 50.0), on_ground=True, motion_table=humanoid)
    thing = prop(world, 96.0, 97.0, 0.5)
    watcher.detection_manager = DetectionManager(watcher)
    watcher.detection_manager.create_detection_cylsphere(CONTEXT, 2.5, thing.id)
    for _ in range(12):
        world.cur_time += 0.125
        watcher.update_object()
    assert statuses(watcher.detection_manager) == [(1.0, ENTERED)]


@pytest.mark.parametrize(
    ("context", "radius", "object_id", "message"),
    [
        (CONTEXT, 1.0, 5, "already has a cylinder"),
        (8, -1.0, 5, "radius"),
        (8, math.nan, 5, "radius"),
        (8, 1.0, -5, "object id"),
        (-1, 1.0, 5, "context id"),
    ],
)
def test_bad_cylinders_are_refused(
    scene: tuple[PhysicsObj, PhysicsObj, DetectionManager],
    context: int,
    radius: float,
    object_id: int,
    message: str,
) -> None:
    _, _, manager = scene
    with pytest.raises(ValueError, match=message):
        manager.create_detection_cylsphere(context, radius, object_id)


# -- global cylinders (object id 0): the cells' voyeur tables --------------------------------------

GLOBAL = 9


def cell_at(x: float, y: float) -> int:
    return outdoor_cell_id(LANDBLOCK, Vector3(x, y, 50.0))


@pytest.fixture
def lookout(world: World) -> tuple[PhysicsObj, DetectionManager]:
    """A watcher at (96, 96) (kept active by a motion table) with a 10-m global cylinder."""
    world.set_flat_ground(LANDBLOCK, 50.0)
    watcher = place(
        world,
        name="watcher",
        origin=(96.0, 96.0, 50.0),
        on_ground=True,
        motion_table=builtin_motion_table("humanoid"),
    )
    watcher.detection_manager = DetectionManager(watcher)
    watcher.detection_manager.create_detection_cylsphere(GLOBAL, 10.0, 0)
    return watcher, watcher.detection_manager


def test_global_cylinder_reports_a_body_crossing_its_cells(
    world: World, lookout: tuple[PhysicsObj, DetectionManager]
) -> None:
    watcher, manager = lookout
    walker = place(world, name="walker", state=PhysicsState(0), origin=(35.0, 90.0, 55.0))
    walker.set_velocity(Vector3(10.0, 0.0, 0.0))  # no gravity, no contact: 1.25 m per 1/8 s
    entered_at = None
    for k in range(1, 81):
        world.cur_time = k * 0.125
        watcher.update_object()
        walker.update_object()
        if entered_at is None and walker.cell.id == cell_at(72.0, 90.0):
            entered_at = walker.position.frame.origin.copy()
    # FindCellList: a 10-m sphere at the body, loaded cells only (acclient.c:327163-327166): the four
    # 24-m land cells meeting at (96, 96).
    assert sorted(manager.cell_array.cell_ids()) == sorted(
        cell_at(x, y) for x in (80.0, 100.0) for y in (80.0, 100.0)
    )
    # add_object reports Entered when the walker enters cell (72..96, 72..96) at t = 3.75
    # (acclient.c:347750); the next 1-Hz pass (327688) reports it (327428-327431). Crossing from that cell
    # to (96..120) at t = 6.125 sends Left then Entered, which cancel (327268-327274); leaving the watched
    # cells at t = 8.5 (x = 120) is reported Left at t = 9 (327432-327435).
    assert statuses(manager) == [(4.0, ENTERED), (9.0, LEFT)]
    assert [object_id for _, _, object_id, _ in manager.reports] == [walker.id, walker.id]
    assert len(manager.detection_objects) == 0
    # No radius test per object: entering the watched cell 23.8 m from the watcher is enough.
    assert watcher.position.get_offset(position_of(entered_at)).length() > 20.0


def position_of(origin: Vector3) -> Position:
    return Position(outdoor_cell_id(LANDBLOCK, origin), Frame(origin))


def test_an_entered_then_left_object_is_never_reported(
    world: World, lookout: tuple[PhysicsObj, DetectionManager]
) -> None:
    _, manager = lookout
    check_at(manager, 1.0)  # initializes (acclient.c:327331)
    visitor = prop(world, 100.0, 100.0, 0.5)  # enters a watched cell: Entered pending
    assert manager.detection_objects.lookup(visitor.id).object_status == ENTERED
    visitor.leave_world()
    # Left on a pending Entered drops the object (acclient.c:327278-327284).
    assert len(manager.detection_objects) == 0
    check_at(manager, 2.0)
    assert manager.reports == []


def test_voyeurs_are_reference_counted(world: World, lookout: tuple[PhysicsObj, DetectionManager]) -> None:
    watcher, manager = lookout
    check_at(manager, 1.0)
    far = prop(world, 30.0, 30.0, 0.5)  # in an unwatched cell
    cell = far.cell
    detcyl = manager.detection_table[GLOBAL]
    # A new voyeur hears Entered for every object already there (acclient.c:347466-347489) ...
    assert cell.add_voyeur(watcher.id, detcyl) is True
    assert cell.add_voyeur(watcher.id, detcyl) is True  # ... a known one only counts (347456-347461)
    assert cell.voyeur_table[watcher.id].ref_count == 2
    assert manager.detection_objects.lookup(far.id).object_status == ENTERED
    check_at(manager, 2.0)
    assert cell.remove_voyeur(watcher.id, detcyl) is True  # 2 -> 1: kept, nobody told (347549-347554)
    assert manager.detection_objects.lookup(far.id).object_status == DetectionType.NO_CHANGE
    assert cell.remove_voyeur(watcher.id, detcyl) is True  # 1 -> 0: gone, Left for each object (347528)
    assert watcher.id not in cell.voyeur_table
    assert cell.remove_voyeur(watcher.id, detcyl) is False
    assert cell.add_voyeur(0, detcyl) is False  # voyeur id 0 is refused (347441)
    check_at(manager, 3.0)
    assert statuses(manager) == [(2.0, ENTERED), (3.0, LEFT)]


def test_hiding_reports_left_and_unhiding_entered(
    world: World, lookout: tuple[PhysicsObj, DetectionManager]
) -> None:
    _, manager = lookout
    check_at(manager, 1.0)
    thing = prop(world, 100.0, 100.0, 0.5)
    check_at(manager, 2.0)
    thing.set_hidden(True)  # hide_object: Left (acclient.c:322129, 347618)
    check_at(manager, 3.0)
    thing.set_hidden(False)  # unhide_object: Entered (322167, 347650)
    check_at(manager, 4.0)
    assert statuses(manager) == [(2.0, ENTERED), (3.0, LEFT), (4.0, ENTERED)]
    # A hidden object entering a watched cell is not reported (add_object, acclient.c:347730).
    ghost = place(world, name="ghost", spheres=False, state=PhysicsState.HIDDEN, origin=(100.0, 90.0, 50.0))
    assert manager.detection_objects.lookup(ghost.id) is None


def test_moving_five_metres_remakes_the_cell_list(
    world: World, lookout: tuple[PhysicsObj, DetectionManager]
) -> None:
    watcher, manager = lookout
    check_at(manager, 1.0)
    west = prop(world, 80.0, 80.0, 0.5)  # in a cell the list will drop
    check_at(manager, 2.0)
    # 4.9 m: Position::distance < 5, no change (acclient.c:327344).
    watcher.position.frame.origin.x = f32(100.9)
    check_at(manager, 3.0)
    assert cell_at(80.0, 80.0) in manager.cell_array.cell_ids()
    watcher.position.frame.origin.x = 107.0  # 11 m: remade around (107, 96): x 97..117 -> cells 96..120 only
    check_at(manager, 4.0)
    assert sorted(manager.cell_array.cell_ids()) == sorted([cell_at(100.0, 80.0), cell_at(100.0, 100.0)])
    # The dropped cell's remove_voyeur reports its objects Left (acclient.c:327370-327378, 347528-347545);
    # the kept cells were added before they were removed, so they never lost the voyeur (327352-327365).
    assert statuses(manager) == [(2.0, ENTERED), (4.0, LEFT)]
    assert world.get_cell(cell_at(100.0, 100.0)).voyeur_table[watcher.id].ref_count == 1
    assert watcher.id not in world.get_cell(cell_at(80.0, 80.0)).voyeur_table
    assert west.cell.id == cell_at(80.0, 80.0)


def test_destroying_a_global_cylinder_leaves_its_cells(
    world: World, lookout: tuple[PhysicsObj, DetectionManager]
) -> None:
    watcher, manager = lookout
    check_at(manager, 1.0)
    prop(world, 100.0, 100.0, 0.5)
    cells = [world.get_cell(cell_id) for cell_id in manager.cell_array.cell_ids()]
    assert manager.destroy_detection_cylsphere(GLOBAL)
    check_at(manager, 2.0)
    # ClearPendingDeletions -> CleanupGlobalDetection for object id 0 (acclient.c:327527-327528): the table
    # goes first, so remove_voyeur's Left reports land nowhere (327465-327472, 327246-327247).
    assert manager.detection_objects is None and manager.cell_array is None
    assert all(watcher.id not in cell.voyeur_table for cell in cells)
    assert manager.reports == []


def test_a_detection_report_wakes_the_body(
    world: World, lookout: tuple[PhysicsObj, DetectionManager]
) -> None:
    watcher, manager = lookout
    check_at(manager, 1.0)
    watcher.transient_state &= ~TransientState.ACTIVE
    world.cur_time = 7.5
    watcher.receive_detection_update(DetectionInfo(12345, ENTERED))
    # receive_detection_update: a non-static body becomes active, update_time = Timer::cur_time when it
    # was inactive (acclient.c:317660-317668).
    assert watcher.transient_state & TransientState.ACTIVE
    assert watcher.update_time == 7.5
    assert manager.detection_objects.lookup(12345).object_status == ENTERED
