"""The body side of object collisions: a sweep meets a body through the cells it shadows.

CObjCell::find_obj_collisions (acclient.c:347141) asks each shadowed body's
CPhysicsObj::FindObjCollisions (316158), which dispatches to the physics BSP through
CPartArray::FindObjCollisions (325463) → CPhysicsPart::find_obj_collisions (314655) →
CGfxObj::find_obj_collisions (356514), else to CCylSphere::intersects_sphere (362243), else to
CSphere::intersects_sphere (359389), and records the answer (316291-316314).

The world: flat ground at z 0 in landblock 0xA9B4; the obstacles stand on the corner (48, 48) of
the outdoor cells 0x0A (1,1), 0x0B (1,2), 0x12 (2,1), 0x13 (2,2) (low word = 1 + 8·cx + cy). The
mover is one sphere of r 0.5, 0.5 above its origin, swept in cell 0x0A; all in one landblock, so
every block offset is zero.
"""

from __future__ import annotations

import math

import pytest

from acphys.constants import EPSILON, FLOOR_Z, LANDING_Z
from acphys.flags import ObjectInfoState as OIS
from acphys.flags import PhysicsState as PS
from acphys.flags import TransitionState as TS
from acphys.geometry.bsp_builder import build_box_tree
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.motion.weenie import Weenie
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.physics_part import PhysicsPart, gfx_find_obj_collisions
from acphys.precision import f32
from acphys.setup import Setup
from acphys.transition.transition import InsertType, Transition
from acphys.world.static_objects import add_static_object
from acphys.world.world import World

BLOCK = 0xA9B4
CORNER = V(48.0, 48.0, 0.0)
SHADOWED = {0xA9B4000A, 0xA9B4000B, 0xA9B40012, 0xA9B40013}
ELSEWHERE = 0xA9B40001  # cell (0,0): no shadow of anything here
SWEEP_CELL = 0xA9B4000A


@pytest.fixture
def ground() -> World:
    world = World()
    world.set_flat_ground(BLOCK, 0.0)
    return world


def sweep(
    world: World, curr: V, check: V, state: OIS = OIS.DEFAULT, mover: PhysicsObj | None = None
) -> Transition:
    """A real transition of the mover's sphere (r 0.5, centre 0.5 up) from origin ``curr`` to ``check``."""
    if mover is None:
        mover = PhysicsObj(world, "mover")
    t = Transition(world, mover)
    t.object_info.state = state
    path = t.sphere_path
    path.local_sphere = [Sphere(V(0, 0, 0.5), 0.5)]
    path.curr_pos = Position(SWEEP_CELL, Frame(curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(SWEEP_CELL, Frame(check)), None)
    path.walk_interp = 1.0
    return t


def pillar(world: World, origin: V = CORNER) -> PhysicsObj:
    setup = Setup("pillar", cylspheres=[CylSphere(V(), 1.0, 3.0)])
    return add_static_object(world, "pillar", setup, Position(outdoor_cell_id(BLOCK, origin), Frame(origin)))


def box(world: World, scale: float = 1.0) -> PhysicsObj:
    setup = Setup("box", physics_bsp=build_box_tree(V(-1, -1, 0), V(1, 1, 2)))
    where = Position(outdoor_cell_id(BLOCK, CORNER), Frame(CORNER))
    return add_static_object(world, "box", setup, where, scale)


def ball(world: World, state: PS = PS.GRAVITY, weenie: Weenie | None = None, z: float = 1.0) -> PhysicsObj:
    """A moving (non-static) body: one sphere r 0.5 at (48, 48, z + 0.5), shadowed by its sorting sphere."""
    sphere = Sphere(V(0, 0, 0.5), 0.5)
    body = PhysicsObj(world, "ball", PartArray(Setup("ball", spheres=[sphere], sorting_sphere=sphere)))
    body.state = state
    body.weenie_obj = weenie
    origin = V(48.0, 48.0, z)
    assert body.enter_world(Position(outdoor_cell_id(BLOCK, origin), Frame(origin)))
    body.calc_cross_cells()
    return body


def shadow_cells(body: PhysicsObj) -> set[int]:
    cells = set()
    for shadow in body.shadow_objects:
        assert shadow.cell is not None and any(s is shadow for s in shadow.cell.shadow_objects)
        cells.add(shadow.cell.id)
    return cells


#: One float32 ulp of a coordinate between 32 and 64 m: the sweep's positions, and the local
#: centres taken from them, are floats, so a geometric expectation is met to within this.
ULP_48 = 2.0**-18


def close(a: V, b: V, tol: float = ULP_48) -> bool:
    return all(abs(p - q) <= tol for p, q in zip(a, b, strict=True))


# --- found in every cell it shadows, and only there ---------------------------------------------


def test_a_static_pillar_is_found_in_its_four_cells_and_nowhere_else(ground) -> None:
    obj = pillar(ground)
    assert shadow_cells(obj) == SHADOWED
    for cell_id in sorted(SHADOWED):
        # Airborne sphere from x 46 to 46.6 (centre z 1.5): radsum 1.4998 against |disp.xy| 1.4
        # (acclient.c:361501), no contact, not path-clipped -> land_on_cylinder (362014): the side
        # normal from the old centre (-2, 0, 0) normalised becomes step_up_normal via set_collide
        # (359049), walkable_allowance = LANDING_Z, ADJUSTED.
        t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
        assert ground.get_cell(cell_id).find_obj_collisions(t) == TS.ADJUSTED, hex(cell_id)
        path, info = t.sphere_path, t.collision_info
        assert path.collide and path.step_up_normal.exactly_equals(V(-1, 0, 0))
        assert path.walkable_allowance == LANDING_Z
        # A static body answering other than OK flags the environment (mover not in contact) and is
        # not added to the collision objects (acclient.c:316294-316297).
        assert info.collided_with_environment and info.collide_object == []
        assert not path.obstruction_ethereal  # cleared on the way out (316314)
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    assert ground.get_cell(ELSEWHERE).find_obj_collisions(t) == TS.OK
    assert not t.sphere_path.collide and not t.collision_info.collided_with_environment


def test_a_static_box_collides_through_its_part_and_physics_bsp_in_every_cell(ground) -> None:
    obj = box(ground)
    assert obj.state & PS.HAS_PHYSICS_BSP
    assert shadow_cells(obj) == SHADOWED
    part = obj.part_array.parts[0]
    for cell_id in sorted(SHADOWED):
        # HAS_PHYSICS_BSP -> CPartArray::FindObjCollisions (acclient.c:316288) -> the part caches the
        # spheres in its frame at gfxobj_scale.z (314669); sphere (-1.4, 0, 1.5) r 0.5 overlaps the
        # root sphere, so BSPTREE::find_collisions (356554): airborne, sphere 0 reaches the x = -1
        # face (0.4 < 0.5) -> set_collide with its global normal, LANDING_Z, ADJUSTED (361295).
        t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
        assert ground.get_cell(cell_id).find_obj_collisions(t) == TS.ADJUSTED, hex(cell_id)
        path = t.sphere_path
        assert path.localspace_pos.frame.origin.exactly_equals(part.pos.frame.origin)
        assert close(path.localspace_sphere[0].center, V(-1.4, 0.0, 1.5))
        assert path.collide and close(path.step_up_normal, V(-1, 0, 0))
        assert path.walkable_allowance == LANDING_Z
        assert t.collision_info.collided_with_environment and t.collision_info.collide_object == []
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    assert ground.get_cell(ELSEWHERE).find_obj_collisions(t) == TS.OK and not t.sphere_path.collide


def test_a_scaled_box_is_met_at_its_scaled_face(ground) -> None:
    obj = box(ground, scale=2.0)
    assert obj.part_array.parts[0].gfxobj_scale.z == 2.0
    # At scale 2 the face is x = 46: centre 45.6 is 0.4 from it. The part divides by
    # gfxobj_scale.z (acclient.c:314669): localspace centre (-1.2, 0, 0.75), r 0.25.
    t = sweep(ground, V(45.0, 48.0, 1.0), V(45.6, 48.0, 1.0))
    assert obj.find_obj_collisions(t) == TS.ADJUSTED
    assert close(t.sphere_path.localspace_sphere[0].center, V(-1.2, 0.0, 0.75))
    assert t.sphere_path.localspace_sphere[0].radius == 0.25
    # The same sweep misses the unscaled box (1.4 from its face).
    t = sweep(ground, V(45.0, 48.0, 1.0), V(45.6, 48.0, 1.0))
    assert box(World(), 1.0).find_obj_collisions(t) == TS.OK


def test_a_sphere_object_is_found_in_its_four_cells_and_recorded(ground) -> None:
    obj = ball(ground)
    assert shadow_cells(obj) == SHADOWED
    for cell_id in sorted(SHADOWED):
        # No weenie, not a missile: is_creature 0 (acclient.c:316227). radsum 0.9998 against
        # |disp| 0.8; airborne -> land_on_sphere (359114): normal (46.5 - 48, 0, 0) normalised.
        t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
        assert ground.get_cell(cell_id).find_obj_collisions(t) == TS.ADJUSTED, hex(cell_id)
        info = t.collision_info
        assert t.sphere_path.collide and t.sphere_path.step_up_normal.exactly_equals(V(-1, 0, 0))
        # Not static: COLLISIONINFO::add_object with the answer (acclient.c:316307, 718728).
        assert info.collide_object == [obj] and info.last_collided_object is obj
        assert not info.collided_with_environment
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
    assert ground.get_cell(ELSEWHERE).find_obj_collisions(t) == TS.OK
    assert t.collision_info.collide_object == []


def test_a_path_clipped_mover_is_collided_and_the_body_recorded(ground) -> None:
    obj = ball(ground)
    # PATH_CLIPPED without PERFECT_CLIP: collide_with_point sets the normal from the old centre and
    # answers COLLIDED (acclient.c:358807); add_object(COLLIDED) (316307).
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.PATH_CLIPPED)
    assert ground.get_cell(SWEEP_CELL).find_obj_collisions(t) == TS.COLLIDED
    info = t.collision_info
    assert info.collision_normal_valid and info.collision_normal.exactly_equals(V(-1, 0, 0))
    assert info.collide_object == [obj] and info.last_collided_object is obj


def test_a_mover_in_contact_slides_along_the_pillar_without_the_environment_flag(ground) -> None:
    pillar(ground)
    # In contact, too high to step (step_up_height 0 < r + h - disp.z = 2, acclient.c:361983):
    # slide. Normal (-1, 0, 0) from the old centre; contact plane z up; direction N x plane.N =
    # (0, 1, 0); step (0.6, 0.4, 0) keeps (0, 0.4, 0): offset (-0.6, 0, 0), SLID (358898).
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.4, 1.0), OIS.CONTACT | OIS.ON_WALKABLE)
    t.collision_info.set_contact_plane(Plane.horizontal(1.0), False)
    assert ground.get_cell(SWEEP_CELL).find_obj_collisions(t) == TS.SLID
    assert close(t.sphere_path.check_pos.frame.origin, V(46.0, 48.4, 1.0))
    # Static but the mover is in contact: no environment flag (acclient.c:316296).
    assert not t.collision_info.collided_with_environment


# --- skipped bodies ------------------------------------------------------------------------------


def test_the_mover_does_not_collide_with_its_own_shadow(ground) -> None:
    mover = ball(ground)
    assert shadow_cells(mover) == SHADOWED
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), mover=mover)
    # CObjCell::find_obj_collisions skips the transition's own object (acclient.c:347159).
    for cell_id in SHADOWED:
        assert ground.get_cell(cell_id).find_obj_collisions(t) == TS.OK
    assert not t.sphere_path.collide and t.collision_info.collide_object == []
    # The body itself has no such test: asked directly, it collides with the sweep.
    assert mover.find_obj_collisions(t) == TS.ADJUSTED


def test_an_ethereal_body_that_ignores_collisions_is_skipped_at_once(ground) -> None:
    obj = ball(ground, PS.ETHEREAL | PS.IGNORE_COLLISIONS)
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
    t.sphere_path.obstruction_ethereal = True
    # state & 4 && state & 0x10 -> 1 before anything is touched (acclient.c:316194-316195).
    assert obj.find_obj_collisions(t) == TS.OK
    assert t.sphere_path.obstruction_ethereal and t.collision_info.collide_object == []


def test_a_viewer_passes_creatures(ground) -> None:
    obj = ball(ground, weenie=Weenie(creature=True, the_player=False))
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IS_VIEWER)
    # IS_VIEWER (4) and the weenie's IsCreature (slot 11) -> 1 (acclient.c:316199-316200).
    assert obj.find_obj_collisions(t) == TS.OK
    assert not t.sphere_path.collide and t.collision_info.collide_object == []
    # A non-creature weenie is collided with.
    obj.weenie_obj = Weenie(creature=False, the_player=False)
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IS_VIEWER)
    assert obj.find_obj_collisions(t) == TS.ADJUSTED


# --- ethereal obstructions -----------------------------------------------------------------------


def test_an_ethereal_body_only_reports_overlap_and_is_recorded_as_ok(ground) -> None:
    obj = ball(ground, PS.ETHEREAL)
    for cell_id in sorted(SHADOWED):
        t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
        t.collision_info.collision_normal_valid = True
        # obstruction_ethereal = 1 (acclient.c:316214): intersects_sphere only reports overlap,
        # COLLIDED (359211-359215), no landing; the tail turns it into OK, invalidates the normal and
        # adds the body as OK (316299-316303): collide_object holds it, last_collided_object not.
        assert ground.get_cell(cell_id).find_obj_collisions(t) == TS.OK
        info = t.collision_info
        assert not t.sphere_path.collide and not t.sphere_path.obstruction_ethereal
        assert not info.collision_normal_valid
        assert info.collide_object == [obj] and info.last_collided_object is None


def test_an_ethereal_mover_passes_moving_bodies_but_not_static_ones(ground) -> None:
    obj = ball(ground)
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
    t.object_info.ethereal = True
    # object_info.ethereal && !(state & STATIC) -> ethereal (acclient.c:316203).
    assert obj.find_obj_collisions(t) == TS.OK
    assert t.collision_info.collide_object == [obj] and not t.sphere_path.collide
    post = pillar(World())
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    t.object_info.ethereal = True
    assert post.find_obj_collisions(t) == TS.ADJUSTED and t.sphere_path.collide


def test_an_ethereal_static_body_still_blocks(ground) -> None:
    obj = pillar(ground)
    obj.state |= PS.ETHEREAL
    # Quirk (ACE agrees): the tail tests STATIC before the ethereal branch (acclient.c:316294-316299),
    # so the overlap report COLLIDED (362083) is returned, with the environment flag.
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    assert obj.find_obj_collisions(t) == TS.COLLIDED
    assert t.collision_info.collided_with_environment and not t.sphere_path.collide
    assert not t.sphere_path.obstruction_ethereal


def test_step_down_ignores_ethereal_bodies_and_records_nothing(ground) -> None:
    # Mover centre (48, 48, 2.4) over the ball's (48, 48, 1.5); stepping down 0.5.
    def stepping() -> Transition:
        t = sweep(ground, V(48.0, 48.0, 1.9), V(48.0, 48.0, 1.9))
        t.sphere_path.step_down = True
        t.sphere_path.step_down_amt = 0.5
        t.sphere_path.walkable_allowance = FLOOR_Z
        return t

    ghost = ball(ground, PS.ETHEREAL)
    t = stepping()
    t.sphere_path.obstruction_ethereal = True
    # Ethereal while stepping down: 1 before obstruction_ethereal is written (acclient.c:316207-316208).
    assert ghost.find_obj_collisions(t) == TS.OK
    assert t.sphere_path.obstruction_ethereal and not t.collision_info.contact_plane_valid
    solid = ball(World())
    t = stepping()
    # Solid: CSphere::step_sphere_down (358615): reach 1.0, t = (1 - 0.9)/0.5 = 0.2, interp 0.8,
    # drop 0.1, contact plane z = 2.0. No record while stepping down (acclient.c:316292).
    assert solid.find_obj_collisions(t) == TS.ADJUSTED
    assert t.collision_info.contact_plane_valid and t.sphere_path.walk_interp == pytest.approx(0.8)
    assert t.collision_info.contact_plane.d == pytest.approx(-2.0)
    assert t.collision_info.collide_object == [] and not t.collision_info.collided_with_environment
    # A creature is not stepped onto: is_creature reaches intersects_sphere (acclient.c:316249, 359384).
    creature = ball(World(), weenie=Weenie(creature=True, the_player=False))
    t = stepping()
    assert creature.find_obj_collisions(t) == TS.OK and not t.collision_info.contact_plane_valid


# --- weenie checks -------------------------------------------------------------------------------


def test_players_pass_through_players_unless_pk_impenetrable(ground) -> None:
    other = ball(ground, weenie=Weenie(player=True, the_player=False))
    # IsPlayer (slot 4) and the mover's IS_PLAYER (0x100), nothing else: exempt, no shape is tried
    # (acclient.c:316216-316224, 316229-316235).
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IS_PLAYER)
    assert other.find_obj_collisions(t) == TS.OK and not t.sphere_path.collide
    for state, weenie in (
        (OIS.IS_PLAYER | OIS.IS_IMPENETRABLE, Weenie(player=True, the_player=False)),  # 316219
        (OIS.IS_PLAYER, Weenie(player=True, the_player=False, impenetrable=True)),  # slot 10, 316220
        (OIS.IS_PLAYER | OIS.IS_PK, Weenie(player=True, the_player=False, pk=True)),  # slot 8, 316221
        (OIS.IS_PLAYER | OIS.IS_PKLITE, Weenie(player=True, the_player=False, pk_lite=True)),  # 9, 316222
        (OIS.DEFAULT, Weenie(player=True, the_player=False)),  # the mover is no player (316218)
    ):
        other.weenie_obj = weenie
        t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), state)
        assert other.find_obj_collisions(t) == TS.ADJUSTED, state
    # Only one PK side is not enough: mover PK, body PK-lite.
    other.weenie_obj = Weenie(player=True, the_player=False, pk_lite=True)
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IS_PLAYER | OIS.IS_PK)
    assert other.find_obj_collisions(t) == TS.OK


def test_a_mover_ignoring_creatures_is_answered_ok_but_keeps_the_shapes_response(ground) -> None:
    obj = ball(ground, weenie=Weenie(creature=True, the_player=False))
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IGNORE_CREATURES)
    # is_creature (slot 11, acclient.c:316227) and IGNORE_CREATURES (0x400): the ADJUSTED answer
    # becomes OK, added as OK (316299-316303); land_on_sphere's set_collide stays done.
    assert obj.find_obj_collisions(t) == TS.OK
    assert t.sphere_path.collide
    assert t.collision_info.collide_object == [obj] and t.collision_info.last_collided_object is None
    # A non-creature is recorded with its answer.
    obj.weenie_obj = Weenie(creature=False, the_player=False)
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IGNORE_CREATURES)
    assert obj.find_obj_collisions(t) == TS.ADJUSTED and t.collision_info.last_collided_object is obj


# --- missiles ------------------------------------------------------------------------------------


def test_a_missile_obstacle_is_always_ignored(ground) -> None:
    obj = ball(ground, PS.MISSILE)
    player = PhysicsObj(ground, "player")
    player.weenie_obj = Weenie(player=True)
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), OIS.IS_PLAYER, mover=player)
    # OBJECTINFO::missile_ignore: collideobject->state & 0x40 -> 1 (acclient.c:314078-314080).
    # ACE ("modified for 2-way") would collide a player with an untargeted missile (divergence).
    assert t.object_info.missile_ignore(obj)
    assert obj.find_obj_collisions(t) == TS.OK and t.collision_info.collide_object == []


def test_a_missile_mover_passes_all_but_its_target(ground) -> None:
    creature = ball(ground, weenie=Weenie(creature=True, the_player=False))
    arrow = PhysicsObj(ground, "arrow")
    arrow.state = PS.MISSILE
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), mover=arrow)
    # With a target, a creature other than the target is ignored (acclient.c:314085-314092).
    t.object_info.target_id = 0x7777
    assert creature.find_obj_collisions(t) == TS.OK and t.collision_info.collide_object == []
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), mover=arrow)
    t.object_info.target_id = creature.id  # the target itself is hit (314088)
    assert creature.find_obj_collisions(t) == TS.ADJUSTED
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), mover=arrow)
    assert creature.find_obj_collisions(t) == TS.ADJUSTED  # no target: creatures are hit (314091)
    # An ethereal body with a weenie is ignored even without a target: not even recorded (314090).
    creature.state = PS.ETHEREAL
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), mover=arrow)
    assert creature.find_obj_collisions(t) == TS.OK and t.collision_info.collide_object == []
    creature.weenie_obj = None  # ... but without a weenie it is an ordinary ethereal obstruction
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0), mover=arrow)
    assert creature.find_obj_collisions(t) == TS.OK and t.collision_info.collide_object == [creature]


def test_missile_ignore_needs_the_moving_object(ground) -> None:
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
    t.object_info.object = None
    with pytest.raises(ValueError, match="no moving object"):
        t.object_info.missile_ignore(ball(ground))


# --- the dispatch --------------------------------------------------------------------------------


def test_cylspheres_win_over_spheres(ground) -> None:
    # A body with a cylsphere (far off) and a sphere (in the path): only the cylspheres are tried
    # (acclient.c:316232, 316259-316279).
    setup = Setup("post", spheres=[Sphere(V(0, 0, 0.5), 0.5)], cylspheres=[CylSphere(V(10, 0, 0), 0.5, 1.0)])
    body = PhysicsObj(ground, "post", PartArray(setup))
    body.position = Position(SWEEP_CELL, Frame(V(48.0, 48.0, 1.0)))
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
    assert body.find_obj_collisions(t) == TS.OK and not t.sphere_path.collide
    setup.cylspheres.clear()
    t = sweep(ground, V(46.5, 48.0, 1.0), V(47.2, 48.0, 1.0))
    assert body.find_obj_collisions(t) == TS.ADJUSTED


def test_part_array_stops_at_the_first_part_that_answers(ground) -> None:
    obj = box(ground)
    parts = obj.part_array.parts
    far = PhysicsPart(obj.part_array.setup)
    far.pos = Position(SWEEP_CELL, Frame(V(10.0, 10.0, 0.0)))
    parts.append(far)
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    # Part 0 answers ADJUSTED; the loop breaks before part 1 caches its frame (acclient.c:325481-325483).
    assert obj.part_array.find_obj_collisions(t) == TS.ADJUSTED
    assert t.sphere_path.localspace_pos.frame.origin.exactly_equals(CORNER)
    parts.reverse()
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    assert obj.part_array.find_obj_collisions(t) == TS.ADJUSTED  # part "far" OK, then the box
    # A part without a physics BSP is OK and caches nothing (acclient.c:314663-314667).
    bare = PhysicsPart(Setup("bare"))
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    assert bare.find_obj_collisions(t) == TS.OK and t.sphere_path.localspace_sphere == []


def test_initial_placement_goes_to_placement_insert(ground) -> None:
    part = box(ground).part_array.parts[0]
    # The sphere overlaps the x = -1 face by 0.2: placement_insert pushes it out (ADJUSTED, check_pos
    # moved, no collide) where a transition sets collide (acclient.c:356551-356554).
    t = sweep(ground, V(46.3, 48.0, 1.0), V(46.8, 48.0, 1.0))
    t.sphere_path.insert_type = InsertType.INITIAL_PLACEMENT
    assert part.find_obj_collisions(t) == TS.ADJUSTED
    assert not t.sphere_path.collide and t.sphere_path.check_pos.frame.origin.x < 46.8
    t = sweep(ground, V(46.3, 48.0, 1.0), V(46.8, 48.0, 1.0))
    assert part.find_obj_collisions(t) == TS.ADJUSTED
    # Unmoved: the check position as set (a float32 origin).
    assert t.sphere_path.collide and t.sphere_path.check_pos.frame.origin.x == f32(46.8)


def test_gfx_bound_test_is_strict_where_ace_allows_epsilon(ground) -> None:
    part = box(ground).part_array.parts[0]
    t = sweep(ground, V(46.0, 48.0, 1.0), V(46.6, 48.0, 1.0))
    t.sphere_path.cache_localspace_sphere(part.pos, 1.0)
    # Localspace sphere (-1.4, 0, 1.5) r 0.5; a physics_sphere (DAT data in retail) at (0, 0, 1.5)
    # whose radius sum leaves |d|² - (r1 + r2)² = 0.0001 < EPSILON. Retail reads the lost compare
    # as |d|² < (r1 + r2)² (acclient.c:356539-356544): a miss, OK. ACE's "< EPSILON" would go on
    # to the BSP and answer ADJUSTED (divergence).
    reach = math.sqrt(1.96 - 0.5 * EPSILON)
    part.physics_sphere = Sphere(V(0, 0, 1.5), reach - 0.5)
    assert gfx_find_obj_collisions(part, t, 1.0) == TS.OK and not t.sphere_path.collide
    part.physics_sphere = Sphere(V(0, 0, 1.5), math.sqrt(1.96 + 0.5 * EPSILON) - 0.5)
    assert gfx_find_obj_collisions(part, t, 1.0) == TS.ADJUSTED and t.sphere_path.collide


def test_the_building_shell_uses_the_shared_part() -> None:
    from acphys.world.building import BuildingObj

    tree = build_box_tree(V(-1, -1, 0), V(1, 1, 2))
    building = BuildingObj(tree, Frame(CORNER), scale=2.0)
    # CBuildingObj::find_building_collisions -> CPhysicsPart::find_obj_collisions of its part
    # (acclient.c:719115); the part sits at the building's position and scale.
    assert building.part.pos is building.pos and building.part.physics_bsp is tree
    assert building.scale == 2.0 and building.physics_bsp is tree
    building.pos.objcell_id = SWEEP_CELL
    t = sweep(World(), V(45.0, 48.0, 1.0), V(45.6, 48.0, 1.0))
    assert building.find_building_collisions(t) == TS.ADJUSTED
    assert t.collision_info.collided_with_environment and not t.sphere_path.bldg_check
