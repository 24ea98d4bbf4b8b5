"""Collision reports: the collision table and its dedup, object/environment/attack/end reports, and
``set_ethereal``'s overlap check.

Values come from the decompiled ``CPhysicsObj`` (acclient.c lines cited beside each assertion).
``CollisionInfo`` is built by hand with the collided objects, as the sweep leaves it, and handed to
``handle_all_collisions`` / the report functions directly.

Divergences from ACE's ``PhysicsObj.cs`` pinned here (the decompilation wins):

- ACE's ``track_object_collision`` reports every touch; retail reports only when
  ``LongNIValHash::clobber`` found no record for the object (acclient.c:321249-321252).
- ACE's reverse report (``obj.build_collision_profile(this, obj contact, ...)``) fills the missile
  and in-contact bits from this body's MISSILE and CONTACT; retail passes ``prev_has_contact`` as
  the missile bit and this body's MISSILE as the in-contact bit (acclient.c:320310-320316).
- ACE's ``report_environment_collision`` clears only MISSILE; retail also ALIGN_PATH and
  PATH_CLIPPED (mask 0xFFFFFCBF, acclient.c:320215).
- ACE iterates its ``Dictionary`` in insertion order; retail ends records in hash order (bucket
  ``(id ^ id >> 8) & 3``, newest first in a bucket).
"""

from __future__ import annotations

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.flags import TransitionState
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import CollisionKind, CollisionRecord, CollisionReport, PhysicsObj
from acphys.setup import Setup
from acphys.transition.collision_info import CollisionInfo
from acphys.world.static_objects import add_static_object
from acphys.world.world import World
from support import LANDBLOCK, place

T0 = 10.0


@pytest.fixture
def world() -> World:
    w = World()  # no terrain: nothing underfoot, so placing a body reports nothing
    w.physics_time = T0
    return w


def hit(*objects: PhysicsObj) -> CollisionInfo:
    info = CollisionInfo()
    for obj in objects:
        info.add_object(obj, TransitionState.OK)
    return info


def listen(body: PhysicsObj) -> list[CollisionReport]:
    got: list[CollisionReport] = []

    def on_collision(receiver: PhysicsObj, report: CollisionReport) -> None:
        assert receiver is body
        got.append(report)

    body.on_collision = on_collision
    return got


def post(world: World, name: str, origin: tuple[float, float, float], state: PS, height: float) -> PhysicsObj:
    """A body with one sphere and a setup ``height`` (what ``determine_quadrant`` divides in thirds)."""
    sphere = Sphere(V(0.0, 0.0, 0.5), 0.5)
    setup = Setup(name, spheres=[sphere], height=height, sorting_sphere=sphere)
    body = PhysicsObj(world, name, PartArray(setup))
    body.state = state
    point = V(*origin)
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, point), Frame(point)))
    assert body.position.frame.origin.exactly_equals(point)  # placed where asked
    return body


def pillar(world: World, origin: tuple[float, float, float]) -> PhysicsObj:
    point = V(*origin)
    setup = Setup("pillar", cylspheres=[CylSphere(V(), 1.0, 3.0)])
    where = Position(outdoor_cell_id(LANDBLOCK, point), Frame(point))
    return add_static_object(world, "pillar", setup, where)


# --- the first touch is reported, to both bodies ------------------------------------------------


def test_a_first_contact_is_reported_once_to_each_body(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    a.velocity = V(2.0, 0.0, 0.0)
    b.velocity = V(-1.0, 0.5, 0.0)
    b.transient_state |= TS.CONTACT
    got_a, got_b = listen(a), listen(b)

    # handle_all_collisions tracks each collided object (acclient.c:321835-321841).
    assert a.handle_all_collisions(hit(b), True, False) is True
    assert a.step_events == ["collision:b"] and b.step_events == ["collision:a"]
    # The record: PhysicsTimer::curr_time and the other's ETHEREAL bit (acclient.c:321246-321248).
    assert a.collision_table is not None and a.collision_table.get(b.id) == CollisionRecord(T0, False)
    assert b.collision_table is None  # only the tracking body keeps a table

    # To a: ObjCollisionProfile of b, velocity a - b, me-in-contact = prev_has_contact, b's MISSILE
    # and CONTACT bits (acclient.c:320257-320259, 320278-320285).
    [ra] = got_a
    assert (ra.kind, ra.other, ra.other_id) == (CollisionKind.OBJECT, b, b.id)
    assert ra.velocity is not None and ra.velocity.exactly_equals(V(3.0, -0.5, 0.0))
    assert (ra.me_in_contact, ra.other_is_missile, ra.other_in_contact) == (True, False, True)
    assert ra.is_start and not ra.is_environment and not ra.is_end

    # To b: the same velocity (not negated), me-in-contact = b's CONTACT, and the swapped bits:
    # missile = a's prev_has_contact, in-contact = a's MISSILE (acclient.c:320310-320316).
    [rb] = got_b
    assert (rb.kind, rb.other, rb.other_id) == (CollisionKind.OBJECT, a, a.id)
    assert rb.velocity is not None and rb.velocity.exactly_equals(V(3.0, -0.5, 0.0))
    assert (rb.me_in_contact, rb.other_is_missile, rb.other_in_contact) == (True, True, False)


def test_repeated_contacts_refresh_the_record_without_reporting_again(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    a.handle_all_collisions(hit(b), False, False)
    a.step_events.clear()
    b.step_events.clear()
    for step in range(1, 30):
        world.physics_time = T0 + 0.5 * step
        # clobber finds the record: no report, result 0 (acclient.c:321249-321250).
        assert a.handle_all_collisions(hit(b), False, False) is False
        assert a.collision_table is not None
        assert a.collision_table.get(b.id) == CollisionRecord(world.physics_time, False)
    assert a.step_events == [] and b.step_events == []


def test_a_solid_record_ends_only_after_more_than_a_second_untouched(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    a.handle_all_collisions(hit(b), False, False)
    got_a, got_b = listen(a), listen(b)
    world.physics_time = T0 + 0.5
    a.handle_all_collisions(hit(b), False, False)  # last touch at 10.5

    # curr_time - touched_time > 1.0 is strict (acclient.c:321768): at exactly 1.0 it lives on.
    world.physics_time = T0 + 1.5
    a.handle_all_collisions(CollisionInfo(), False, False)
    assert got_a == [] and a.collision_table is not None and b.id in a.collision_table
    world.physics_time = T0 + 1.5625
    a.handle_all_collisions(CollisionInfo(), False, False)
    assert b.id not in a.collision_table
    # report_object_collision_end: DoCollisionEnd to both (acclient.c:317884-317894).
    assert got_a == [CollisionReport(CollisionKind.END, b.id, b)]
    assert got_b == [CollisionReport(CollisionKind.END, a.id, a)]
    assert a.step_events[-1] == "collision_end:b" and b.step_events[-1] == "collision_end:a"
    assert got_a[0].is_end and not got_a[0].is_start

    # A new touch after the end is a new collision, reported again (acclient.c:321252).
    world.physics_time = T0 + 2.0
    assert a.handle_all_collisions(hit(b), False, False) is True
    assert got_a[-1].kind is CollisionKind.OBJECT


def test_an_ethereal_record_ends_on_the_first_later_step_without_a_touch(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    ghost = place(world, name="ghost", state=PS.REPORT_COLLISIONS | PS.ETHEREAL, origin=(97.0, 96.0, 0.0))
    wall = place(world, name="wall", state=PS.REPORT_COLLISIONS, origin=(95.0, 96.0, 0.0))
    # Passing through an ethereal body is still reported (report_object_collision has no ethereal test).
    assert a.handle_all_collisions(hit(ghost, wall), False, False) is True
    assert a.step_events == ["collision:ghost", "collision:wall"]
    assert a.collision_table is not None and a.collision_table.get(ghost.id) == CollisionRecord(T0, True)
    # The end check in the same call: age 0 is not > 0 (acclient.c:321769).
    assert ghost.id in a.collision_table
    # Touched again each step, it lives on without a new report.
    world.physics_time = T0 + 0.03125
    assert a.handle_all_collisions(hit(ghost), False, False) is False
    assert ghost.id in a.collision_table
    # The first later step without the touch ends it; the solid wall's record lives (321768-321770).
    world.physics_time = T0 + 0.0625
    a.step_events.clear()
    a.handle_all_collisions(CollisionInfo(), False, False)
    assert ghost.id not in a.collision_table and wall.id in a.collision_table
    assert a.step_events == ["collision_end:ghost"]


# --- the environment, and objects reporting as it -----------------------------------------------


def test_a_static_object_reports_as_the_environment_and_is_not_tracked(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    a.velocity = V(0.0, 3.0, -1.0)
    post_ = pillar(world, (96.0, 98.0, 0.0))
    got = listen(a)
    # STATIC -> report_environment_collision, no table made (acclient.c:321228-321230).
    assert a.track_object_collision(post_, True) is True
    assert a.collision_table is None
    assert a.step_events == ["collision:environment"] and post_.step_events == []
    # EnvCollisionProfile: own velocity, me-in-contact bit from prev_has_contact (acclient.c:320205-320210).
    [report] = got
    assert report.is_environment and report.other is None and report.me_in_contact
    assert report.velocity is not None and report.velocity.exactly_equals(V(0.0, 3.0, -1.0))
    # Once colliding with the environment, no second report (acclient.c:320201).
    assert a.track_object_collision(post_, True) is False and len(got) == 1


def test_an_object_reporting_as_environment_is_tracked_but_ends_silently(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    door = place(
        world,
        name="door",
        state=PS.REPORT_COLLISIONS | PS.REPORT_COLLISIONS_AS_ENVIRONMENT,
        origin=(97.0, 96.0, 0.0),
    )
    assert a.handle_all_collisions(hit(door), False, False) is True
    # report_object_collision: REPORT_COLLISIONS_AS_ENVIRONMENT -> environment (acclient.c:320249-320251).
    assert a.step_events == ["collision:environment"] and door.step_events == []
    assert a.collision_table is not None and door.id in a.collision_table
    world.physics_time = T0 + 2.0
    a.step_events.clear()
    a.handle_all_collisions(CollisionInfo(), False, False)
    # The record is dropped with no end report to either (acclient.c:317882).
    assert door.id not in a.collision_table
    assert a.step_events == [] and door.step_events == []


# --- missiles ---------------------------------------------------------------------------------


def test_a_missile_gets_an_attack_report_with_the_quadrant_and_stops_being_a_missile(world) -> None:
    target = post(world, "target", (96.0, 96.0, 0.0), PS.REPORT_COLLISIONS, height=3.0)
    arrow = post(
        world,
        "arrow",
        (95.0, 97.0, 2.5),
        PS.REPORT_COLLISIONS | PS.MISSILE | PS.ALIGN_PATH | PS.PATH_CLIPPED | PS.GRAVITY,
        height=0.2,
    )
    got_arrow, got_target = listen(arrow), listen(target)
    assert arrow.handle_all_collisions(hit(target), False, False) is True
    # AtkCollisionProfile: part -1, location = determine_quadrant(target pos, target height, arrow pos)
    # (acclient.c:320264-320273). Arrow at (-1, 1, 2.5) in the target's frame: x < 0 -> 0x8,
    # y >= 0 -> 0x20, z >= 3 * 0.66666667 -> 0x1 (acclient.c:467079-467093).
    assert got_arrow == [CollisionReport(CollisionKind.ATTACK, target.id, target, location=0x29)]
    assert got_arrow[0].part == -1 and got_arrow[0].velocity is None
    # The missile bits go (mask 0xFFFFFCBF, acclient.c:320289-320290); GRAVITY and reporting stay.
    assert arrow.state == PS.REPORT_COLLISIONS | PS.GRAVITY
    # The target hears of a body whose in-contact bit is the arrow's MISSILE (swapped, 320316).
    [rt] = got_target
    assert rt.kind is CollisionKind.OBJECT and rt.other is arrow
    assert (rt.other_in_contact, rt.other_is_missile) == (True, False)
    assert arrow.step_events == ["collision:target"] and target.step_events == ["collision:arrow"]


def test_a_missile_met_by_a_body_reports_the_quadrant_of_that_body(world) -> None:
    walker = post(world, "walker", (96.0, 96.0, 0.0), PS.REPORT_COLLISIONS, height=3.0)
    bolt = post(world, "bolt", (96.5, 95.0, 1.5), PS.REPORT_COLLISIONS | PS.MISSILE, height=0.2)
    got_walker, got_bolt = listen(walker), listen(bolt)
    assert walker.handle_all_collisions(hit(bolt), False, False) is True
    # To the walker: an object that is a missile (acclient.c:320283).
    [rw] = got_walker
    assert rw.kind is CollisionKind.OBJECT and rw.other_is_missile
    # To the bolt: determine_quadrant(walker pos, walker height, bolt pos) (acclient.c:320295-320304):
    # (0.5, -1, 1.5): 0x10 | 0x40 | middle third 0x2.
    assert got_bolt == [CollisionReport(CollisionKind.ATTACK, walker.id, walker, location=0x52)]
    # Only the reporting body's missile bits are cleared, never the other's (acclient.c:320289).
    assert bolt.state & PS.MISSILE


def test_a_missile_stops_being_one_even_unreported_unless_the_target_ignores_collisions(world) -> None:
    target = post(world, "target", (96.0, 96.0, 0.0), PS(0), height=3.0)
    arrow = post(world, "arrow", (95.0, 96.0, 1.0), PS.MISSILE | PS.ALIGN_PATH, height=0.2)
    # Neither reports: nothing delivered, but the bits are cleared outside the report test (320289).
    assert arrow.report_object_collision(target, False) is False
    assert not arrow.state & (PS.MISSILE | PS.ALIGN_PATH)
    ghost = post(world, "ghost", (97.0, 96.0, 0.0), PS.IGNORE_COLLISIONS | PS.REPORT_COLLISIONS, height=3.0)
    dart = post(world, "dart", (95.0, 97.0, 1.0), PS.MISSILE | PS.REPORT_COLLISIONS, height=0.2)
    # An other that ignores collisions skips the whole first block (acclient.c:320260), yet it hears
    # of the dart, whose IGNORE_COLLISIONS bit is clear (acclient.c:320293).
    assert dart.report_object_collision(ghost, False) is True
    assert dart.state & PS.MISSILE and dart.step_events == []
    assert ghost.step_events == ["collision:dart"]


def test_a_body_that_ignores_collisions_is_not_reported_to_the_other(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS | PS.IGNORE_COLLISIONS, origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    assert a.report_object_collision(b, False) is True
    assert a.step_events == ["collision:b"] and b.step_events == []  # acclient.c:320293


# --- ends: objects gone, leaving the world, hiding, the table order -------------------------------


def test_the_end_of_a_collision_with_a_vanished_object_reaches_only_this_body(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    a.handle_all_collisions(hit(b), False, False)
    gone = b.id
    world.remove_object(b)
    got = listen(a)
    world.physics_time = T0 + 1.25
    a.handle_all_collisions(CollisionInfo(), False, False)
    # GetObjectA finds nothing: DoCollisionEnd(object_id) to this body only (acclient.c:317899-317907).
    assert got == [CollisionReport(CollisionKind.END, gone)]
    assert a.step_events[-1] == f"collision_end:0x{gone:08X}"
    assert a.report_object_collision_end(gone) is False


def test_leaving_the_world_ends_every_collision_at_once(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    a.handle_all_collisions(hit(b), False, False)
    got_b = listen(b)
    # leave_world starts with report_collision_end(1): force_end, age 0 (acclient.c:322663, 321770).
    a.leave_world()
    assert a.collision_table is not None and len(a.collision_table) == 0
    assert got_b == [CollisionReport(CollisionKind.END, a.id, a)]
    assert a.step_events[-1] == "collision_end:b"


def test_hiding_ends_collisions_and_unhiding_reports_the_table_again(world) -> None:
    quiet = place(world, name="quiet", state=PS(0), origin=(96.0, 96.0, 0.0))
    b = place(world, name="b", state=PS.REPORT_COLLISIONS, origin=(97.0, 96.0, 0.0))
    quiet.handle_all_collisions(hit(b), True, False)
    assert b.step_events == ["collision:quiet"]  # quiet does not report, b does (acclient.c:320293)
    # Hiding a body that does not report leaves its table alone (acclient.c:322121-322125).
    quiet.set_hidden(True)
    assert quiet.collision_table is not None and b.id in quiet.collision_table
    assert quiet.state & PS.IGNORE_COLLISIONS and not quiet.state & PS.REPORT_COLLISIONS
    # Unhiding turns reporting on and reports every live record (acclient.c:322154-322160), with
    # this body's CONTACT as prev_has_contact (acclient.c:321282).
    quiet.transient_state |= TS.CONTACT
    got = listen(quiet)
    quiet.set_hidden(False)
    [report] = got
    assert report.kind is CollisionKind.OBJECT and report.other is b and report.me_in_contact
    # Hiding a reporting body ends every record (force) and stops reporting.
    quiet.set_hidden(True)
    assert len(quiet.collision_table) == 0 and got[-1] == CollisionReport(CollisionKind.END, b.id, b)


def test_records_end_in_hash_order(world) -> None:
    a = place(world, name="a", state=PS.REPORT_COLLISIONS, origin=(96.0, 96.0, 0.0))
    ids = [0x13, 0x10, 0x12, 0x14, 0x11, 0x101]
    others = {i: PhysicsObj(world, f"o{i:x}", object_id=i) for i in ids}
    for i in ids:
        a.track_object_collision(others[i], False)
    a.track_object_collision(others[0x10], False)  # clobbered in place: keeps its chain position
    got = listen(a)
    a.report_collision_end(True)
    # Bucket (id ^ id >> 8) & 3 over 4 buckets (HashBase::InternalInit, acclient.c:290595: mask 3,
    # shift 8), newest first in a chain (HashBase::clobber, acclient.c:319390): bucket 0 holds
    # 0x101 (0x101 ^ 0x1 = 0x100), 0x14, 0x10; then 0x11, 0x12, 0x13.
    assert [r.other_id for r in got] == [0x101, 0x14, 0x10, 0x11, 0x12, 0x13]


# --- set_ethereal: becoming solid again needs room --------------------------------------------------


def shadowed(world: World, name: str, origin: tuple[float, float, float], state: PS) -> PhysicsObj:
    body = place(world, name=name, state=state, origin=origin)
    assert body.position.frame.origin.exactly_equals(V(*origin))  # placed where asked
    body.calc_cross_cells()
    assert body.shadow_objects
    return body


def test_turning_solid_fails_while_another_body_overlaps(world) -> None:
    ghost = shadowed(world, "ghost", (100.0, 100.0, 0.0), PS.ETHEREAL)
    shadowed(world, "blocker", (100.5, 100.0, 0.0), PS(0))
    # The blocker's spheres (r 0.48, 0.5 apart) overlap the ghost's at the blocker's own position:
    # check_collision -> placement overlap (acclient.c:320144-320181, 347188).
    assert ghost.set_ethereal(False) is False
    # Still ethereal, CHECK_ETHEREAL asks the next step to retry (acclient.c:319067-319070).
    assert ghost.state & PS.ETHEREAL and ghost.transient_state & TS.CHECK_ETHEREAL


def test_turning_solid_succeeds_beside_a_body_that_does_not_overlap(world) -> None:
    ghost = shadowed(world, "ghost", (100.0, 100.0, 0.0), PS.ETHEREAL)
    blocker = shadowed(world, "blocker", (101.0, 100.0, 0.0), PS(0))
    # Same cells (the check runs), 1.0 apart > 0.96 - EPSILON: no overlap.
    assert {s.cell_id for s in blocker.shadow_objects} & {s.cell_id for s in ghost.shadow_objects}
    ghost.transient_state |= TS.CHECK_ETHEREAL
    assert ghost.set_ethereal(False) is True
    assert not ghost.state & PS.ETHEREAL and not ghost.transient_state & TS.CHECK_ETHEREAL  # 319059-319061


def test_static_and_ethereal_bodies_do_not_keep_a_body_ethereal(world) -> None:
    ghost = shadowed(world, "ghost", (100.0, 100.0, 0.0), PS.ETHEREAL)
    other_ghost = shadowed(world, "other", (100.25, 100.0, 0.0), PS.ETHEREAL)
    pillar(world, (100.0, 100.0, 0.0))  # added last: placing the bodies would step them out of it
    # A static shadow owner never overlaps (acclient.c:320144-320146); an ethereal one is an
    # ethereal obstruction whose overlap turns into OK (OBJECTINFO::init ethereal, acclient.c:314117).
    assert ghost.set_ethereal(False) is True
    # The other way round the ghost, now solid, blocks the other ghost.
    assert other_ghost.set_ethereal(False) is False


def test_a_parented_shadow_owner_is_skipped(world) -> None:
    ghost = shadowed(world, "ghost", (100.0, 100.0, 0.0), PS.ETHEREAL)
    carried = shadowed(world, "carried", (100.5, 100.0, 0.0), PS(0))
    carried.parent = ghost
    assert ghost.set_ethereal(False) is True  # !v4->parent (acclient.c:347188)
