"""DetectionManager against the retail decompilation (CDetectionCylsphere.c).

Expected values are worked by hand from the cited acclient.c lines.
"""

from __future__ import annotations

import math

import pytest

from acphys.managers.detection import DetectionInfo, DetectionManager, DetectionType
from acphys.physics_obj import PhysicsObj
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
        (8, 1.0, 0, "global detection"),
        (-1, 1.0, 5, "context id"),
    ],
)
def test_bad_cylinders_are_refused(
    scene: tuple[PhysicsObj, PhysicsObj, DetectionManager], context: int, radius: float, object_id: int,
    message: str,
) -> None:
    _, _, manager = scene
    with pytest.raises(ValueError, match=message):
        manager.create_detection_cylsphere(context, radius, object_id)
