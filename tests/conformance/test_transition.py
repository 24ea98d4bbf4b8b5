"""The collision sweep, CTransition, on real worlds: flat terrain, static boxes (physics BSPs).

Bodies carry the retail human's spheres (r 0.48 at z 0.475 and 1.35); sphere 0 reaches 5 mm
below the origin, so a body resting on ground at height h has its origin at h + 0.005. Walkers
get step heights of 0.4 (their setup's ``step_up_height``/``step_down_height``).
"""

from __future__ import annotations

import pytest

from acphys.constants import EPSILON, FLOOR_Z
from acphys.flags import ObjectInfoState as OI
from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.flags import TransitionState
from acphys.geometry.bsp_builder import build_box_tree
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.scenario import load_scenario
from acphys.setup import Setup, human_setup
from acphys.transition.transition import MAX_TRANSITION_LEVEL, Transition
from acphys.world.static_objects import add_static_object
from acphys.world.world import World
from support import LANDBLOCK, place

GROUND = 50.0
#: The human's sphere 0 bottom is 0.475 - 0.48 below the origin.
SINK = 0.48 - 0.475
STEP = 0.4


def rest(height: float) -> float:
    """The origin z of a human resting on ground at ``height``: the float32 nearest
    ``height + SINK`` (origins are float stores; sphere 0's float32 bottom is then within a few
    ulps of the plane, inside EPSILON)."""
    return f32(height + SINK)


def walker(world: World, origin: tuple[float, float, float], state: PS = PS.GRAVITY) -> PhysicsObj:
    """A human with 0.4-m step heights, entered into ``world`` (placement steps it onto the ground)."""
    setup = human_setup()
    setup.step_up_height = STEP
    setup.step_down_height = STEP
    body = PhysicsObj(world, "walker", PartArray(setup))
    body.state = state
    point = V(*origin)
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, point), Frame(point)))
    return body


def box(world: World, lo: tuple[float, float, float], hi: tuple[float, float, float]) -> PhysicsObj:
    """A static solid box from ``lo`` to ``hi`` (landblock-local)."""
    low, high = V(*lo), V(*hi)
    setup = Setup("box", physics_bsp=build_box_tree(V(), high - low))
    return add_static_object(world, "box", setup, Position(outdoor_cell_id(LANDBLOCK, low), Frame(low)))


def sweep(body: PhysicsObj, dx: float, dy: float, dz: float = 0.0) -> Transition | None:
    """``CPhysicsObj::transition`` from where the body is to that plus the offset."""
    target = body.position.copy()
    target.frame.origin = target.frame.origin + V(dx, dy, dz)
    return body.transition(body.position, target)


@pytest.fixture
def ground() -> World:
    world = World()
    world.set_flat_ground(LANDBLOCK, GROUND)
    return world


# --- calc_num_steps -------------------------------------------------------------------------------


class TestCalcNumSteps:
    def path(self, world: World, offset: V, state: OI = OI.DEFAULT) -> Transition:
        body = place(world, state=PS(0), origin=(96.0, 96.0, 60.0))
        t = Transition(world, body)
        t.init_object(body, state)
        t.init_sphere(body.part_array.get_sphere(), 1.0)
        end = body.position.copy()
        end.frame.origin = end.frame.origin + offset
        t.init_path(body.cell, body.position, end)
        return t

    def test_a_path_longer_than_a_radius_takes_ceil_dist_over_radius_steps(self) -> None:
        offset, per_step, steps = self.path(World(), V(1.0, 0.0, 0.0)).calc_num_steps()
        # 1.0 / 0.48 = 2.08 > 1: ceil -> 3 steps of a third each (acclient.c:311835).
        assert steps == 3
        assert per_step.x == pytest.approx(1.0 / 3.0) and offset.x == pytest.approx(1.0)

    def test_a_short_path_is_one_step_and_no_path_none(self) -> None:
        _, per_step, steps = self.path(World(), V(0.0, 0.3, 0.0)).calc_num_steps()
        # The end is stored at f32(96 + f32(0.3)) and get_offset narrows the difference
        # (acclient.c:311704-311714): 0.30000305, one step of all of it (acclient.c:311840).
        assert steps == 1 and per_step.y == f32(f32(96.0 + f32(0.3)) - 96.0)
        _, per_step, steps = self.path(World(), V()).calc_num_steps()
        assert steps == 0 and per_step.exactly_equals(V())  # acclient.c:311847

    def test_a_viewer_takes_full_radius_steps_floor_plus_one(self) -> None:
        _, per_step, steps = self.path(World(), V(1.0, 0.0, 0.0), OI.IS_VIEWER).calc_num_steps()
        # floor(2.08) + 1 = 3 steps of one radius (offset / (dist / radius)), acclient.c:311817.
        assert steps == 3 and per_step.x == pytest.approx(0.48)

    def test_a_placement_is_one_step_of_nothing(self) -> None:
        world = World()
        body = place(world, state=PS(0))
        t = Transition(world, body)
        t.init_sphere(body.part_array.get_sphere(), 1.0)
        t.init_path(body.cell, None, body.position)
        assert t.calc_num_steps()[2] == 1  # begin_pos null: acclient.c:311859


# --- landing and standing ---------------------------------------------------------------------------


class TestTerrain:
    def test_a_falling_body_lands_on_the_terrain_with_its_sphere_on_the_plane(self, ground: World) -> None:
        # A human without step heights: with its step-down height of 1.5 m, placement would already
        # have put it on the ground (CTransition::find_placement_position, acclient.c:313340).
        still_up = human_setup()
        still_up.step_up_height = still_up.step_down_height = 0.0
        body = place(ground, origin=(96.0, 96.0, 50.3), setup=still_up)
        assert not body.transient_state & TS.CONTACT
        t = sweep(body, 0.0, 0.0, -0.4)
        assert t is not None
        path, info = t.sphere_path, t.collision_info
        # One step (0.4 < r). The land cell's validate_walkable finds sphere 0's bottom 0.105 under the
        # plane z = 50 and lifts it onto it (ADJUSTED, acclient.c:314257-314270); the re-insert touches it
        # and sets the contact plane again (acclient.c:314237).
        assert path.curr_pos.frame.origin.z == rest(GROUND)
        assert info.contact_plane_valid and info.contact_plane.N.exactly_equals(V(0.0, 0.0, 1.0))
        assert info.contact_plane.d == pytest.approx(-GROUND)
        # Not in contact before: the plane is also an environment collision (acclient.c:314276),
        # which becomes the sliding normal's source (acclient.c:312271) and sets CONTACT | ON_WALKABLE.
        assert info.collided_with_environment and info.collision_normal == V(0.0, 0.0, 1.0)
        assert t.object_info.state & OI.CONTACT and t.object_info.state & OI.ON_WALKABLE  # 312332

    def test_standing_and_walking_on_flat_ground_keeps_the_contact(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        assert body.position.frame.origin.z == rest(GROUND)
        assert body.transient_state & TS.CONTACT and body.transient_state & TS.ON_WALKABLE
        t = sweep(body, 0.3, 0.0)
        assert t is not None
        assert t.sphere_path.curr_pos.frame.origin == V(96.3, 96.0, GROUND + SINK)
        assert t.collision_info.contact_plane_valid and t.object_info.state & OI.ON_WALKABLE

    def test_a_body_hovering_over_the_ground_steps_down_onto_it(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        body.position.frame.origin.z += 0.02
        t = sweep(body, 0.3, 0.0)
        assert t is not None
        # The moved sphere is 2 cm over the plane (OK, no contact plane); the body was in contact on
        # walkable ground, so transitional_insert steps down by its step_down_height (0.4 <= 2r, one
        # try, acclient.c:312964-312986); the step lands on the plane and sticks.
        assert t.sphere_path.curr_pos.frame.origin.z == rest(GROUND)
        assert t.collision_info.contact_plane_valid


# --- walls and steps ----------------------------------------------------------------------------


class TestWalls:
    def test_walking_into_a_wall_stops_at_the_last_clear_step(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        box(ground, (100.0, 90.0, 50.0), (101.0, 102.0, 53.0))
        t = sweep(body, 3.8, 0.0)
        assert t is not None
        # 3.8 / 0.48 -> 8 steps of 0.475. The eighth (x 99.8) puts sphere 0 into the wall's face:
        # the BSP steps up (too high, 3 m) and slides along cross(normal, contact N) = +y, which keeps
        # nothing of a head-on step: COLLIDED, and validate_transition rolls back to the seventh
        # step, 99.325, killing the velocity (acclient.c:312227) with the face as the collision
        # normal.
        assert t.sphere_path.curr_pos.frame.origin == V(96.0 + 7 * 0.475, 96.0, GROUND + SINK)
        assert t.collision_info.collision_normal == V(-1.0, 0.0, 0.0)
        assert t.collision_info.sliding_normal_valid  # acclient.c:312271

    def test_at_an_angle_the_body_slides_along_the_wall(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        box(ground, (100.0, 90.0, 50.0), (101.0, 102.0, 53.0))
        t = sweep(body, 3.8, 1.0)
        assert t is not None
        # |(3.8, 1)| / 0.48 = 8.19 -> 9 steps of (0.4222, 0.1111). The ninth hits the wall; the slide
        # keeps its +y part only, so the body ends 8 x-steps along and the full 1.0 along y.
        end = t.sphere_path.curr_pos.frame.origin
        assert end == V(96.0 + 8 * 3.8 / 9.0, 97.0, GROUND + SINK)

    def test_a_step_lower_than_the_step_up_height_is_climbed(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        box(ground, (97.0, 90.0, 50.0), (99.0, 102.0, 50.3))
        t = sweep(body, 2.0, 0.0)
        assert t is not None
        # 0.3 < step_up_height 0.4: CTransition::step_up steps down by 0.4 from above onto the top
        # (acclient.c:312793): the body ends standing on it.
        assert t.sphere_path.curr_pos.frame.origin == V(98.0, 96.0, 50.3 + SINK)
        assert t.collision_info.contact_plane_valid

    def test_a_step_higher_than_the_step_up_height_blocks(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        box(ground, (97.0, 90.0, 50.0), (99.0, 102.0, 50.7))
        t = sweep(body, 2.0, 0.0)
        assert t is not None
        # Five steps of 0.4: the second (96.8) reaches the face and the 0.7 rise is too high, so it
        # rolls back to 96.4; the sliding normal then turns the third step's offset to nothing, and
        # the sweep stops there, valid (acclient.c:313271-313273). "Too high" is the step-down
        # from step_up: CPolygon::adjust_sphere_to_plane accepts a rise up to 1.5 step heights
        # (walk_interp >= -0.5, acclient.c:359575), 0.6 m here. A 0.6 box sits on that limit: with
        # float32 stores its top f32(50.6) is 1.5e-6 under 50.6 and it is climbed, so the box
        # is 0.7 m high.
        assert t.sphere_path.curr_pos.frame.origin == V(96.4, 96.0, GROUND + SINK)


class TestLedges:
    def test_without_edge_slide_a_body_walks_off_the_ledge(self, ground: World) -> None:
        box(ground, (90.0, 90.0, 50.0), (97.0, 102.0, 52.0))
        body = walker(ground, (95.0, 96.0, 52.2))
        assert body.position.frame.origin.z == rest(52.0)
        t = sweep(body, 3.0, 0.0)
        assert t is not None
        # Past the edge the 0.4 step-down finds nothing and edge_slide, without EDGE_SLIDE, accepts
        # the step with no contact (acclient.c:312777-312787): the body is in the air at x 98.
        assert t.sphere_path.curr_pos.frame.origin == V(98.0, 96.0, 52.0 + SINK)
        assert not t.collision_info.contact_plane_valid
        assert not t.object_info.state & OI.CONTACT

    def test_with_edge_slide_it_stops_at_the_edge(self, ground: World) -> None:
        box(ground, (90.0, 90.0, 50.0), (97.0, 102.0, 52.0))
        body = walker(ground, (95.0, 96.0, 52.2), state=PS.GRAVITY | PS.EDGE_SLIDE)
        t = sweep(body, 3.0, 0.0)
        assert t is not None
        # EDGE_SLIDE and on walkable ground: the step that would leave the top is slid back by
        # edge_slide (acclient.c:312707) and the body keeps its footing on the box, 5 of 7 steps on.
        end = t.sphere_path.curr_pos.frame.origin
        assert end == V(95.0 + 5 * 3.0 / 7.0, 96.0, 52.0 + SINK)
        assert t.collision_info.contact_plane_valid and t.object_info.state & OI.ON_WALKABLE


# --- validate_transition: the stationary-fall counter ---------------------------------------------


class TestStationaryFall:
    def transition(self, world: World, state: PS = PS.GRAVITY) -> Transition:
        body = place(world, state=state, origin=(96.0, 96.0, 60.0))
        t = Transition(world, body)
        t.init_object(body, OI.DEFAULT)
        t.init_sphere(body.part_array.get_sphere(), 1.0)
        t.init_path(body.cell, body.position, body.position)
        t.sphere_path.set_check_pos(t.sphere_path.curr_pos, t.sphere_path.curr_cell)
        return t

    def test_unchanged_steps_count_to_three_and_fabricate_a_floor(self) -> None:
        t = self.transition(World())
        info = t.collision_info
        assert t.validate_transition(TransitionState.OK) == TransitionState.OK
        assert info.frames_stationary_fall == 1  # acclient.c:312312
        t.validate_transition(TransitionState.OK)
        assert info.frames_stationary_fall == 2 and not info.contact_plane_valid  # 312288
        t.validate_transition(TransitionState.OK)
        assert info.frames_stationary_fall == 3  # acclient.c:312293
        # The floor: N = +z, d = radius - centre z, i.e. z = 60.475 - 0.48 (acclient.c:312295-312300).
        assert info.contact_plane_valid and info.contact_plane.N.exactly_equals(V(0.0, 0.0, 1.0))
        assert info.contact_plane.d == pytest.approx(0.48 - 60.475)
        # Out of contact it is also an environment collision (acclient.c:312301-312306), and the
        # contact makes the object state CONTACT | ON_WALKABLE (acclient.c:312332).
        assert info.collided_with_environment and info.collision_normal == V(0.0, 0.0, 1.0)
        assert t.object_info.state & OI.CONTACT and t.object_info.state & OI.ON_WALKABLE

    def test_a_step_that_moves_resets_the_counter_and_no_gravity_never_counts(self) -> None:
        t = self.transition(World())
        t.collision_info.frames_stationary_fall = 2
        t.sphere_path.add_offset_to_check_pos(V(0.1, 0.0, 0.0))
        t.validate_transition(TransitionState.OK)
        assert t.collision_info.frames_stationary_fall == 0  # moved: redo stays 1 (acclient.c:312279)
        t = self.transition(World(), state=PS(0))
        t.validate_transition(TransitionState.OK)
        assert t.collision_info.frames_stationary_fall == 0  # GRAVITY gate (acclient.c:312272-312275)

    def test_a_stuck_falling_body_ends_on_the_fabricated_floor(self) -> None:
        world = World()
        body = place(world, origin=(96.0, 96.0, 60.0))
        # Two stationary frames already (STATIONARY_STOP seeds 2, acclient.c:320111) and a step that
        # moves less than EPSILON on every axis (but more than EPSILON in length, so it is taken):
        # the frame is "equal" and the third stationary frame fabricates the floor.
        body.transient_state |= TS.STATIONARY_STOP
        t = sweep(body, 0.00015, 0.00015, 0.00015)
        assert t is not None
        info = t.collision_info
        assert info.frames_stationary_fall == 3 and info.contact_plane_valid
        centre_z = t.sphere_path.global_sphere[0].center.z
        assert info.contact_plane.d == pytest.approx(0.48 - centre_z)


# --- body side and pool ----------------------------------------------------------------------------


class TestBodySide:
    def test_get_object_info_hands_over_contact_and_edge_slide(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0), state=PS.GRAVITY | PS.EDGE_SLIDE)
        body.state |= PS.MISSILE
        t = Transition(ground)
        state = body.get_object_info(t, admin_move=False)
        # EDGE_SLIDE_PS -> 0x200 (acclient.c:319086); in contact, not leaving the plane: CONTACT and
        # ON_WALKABLE with the contact plane handed over (acclient.c:319095-319098); MISSILE -> PATH_CLIPPED.
        assert state == OI.EDGE_SLIDE | OI.CONTACT | OI.ON_WALKABLE | OI.PATH_CLIPPED
        assert t.collision_info.contact_plane_valid and t.collision_info.last_known_contact_plane_valid
        # An admin move hands over nothing.
        t = Transition(ground)
        assert body.get_object_info(t, admin_move=True) == OI.EDGE_SLIDE | OI.PATH_CLIPPED
        assert not t.collision_info.contact_plane_valid

    def test_moving_off_the_contact_plane_keeps_it_only_as_the_last_known_one(self, ground: World) -> None:
        body = walker(ground, (96.0, 96.0, 50.0))
        body.velocity = V(0.0, 0.0, 1.0)
        t = Transition(ground)
        # v . N = 1 > EPSILON: check_contact fails (acclient.c:316535); retail then stores the cell id
        # as the contact plane's, not the last known one's (acclient.c:315617).
        assert body.get_object_info(t, admin_move=False) == OI.DEFAULT
        assert t.collision_info.last_known_contact_plane_valid and not t.collision_info.contact_plane_valid
        assert t.collision_info.contact_plane_cell_id == body.contact_plane_cell_id
        assert t.collision_info.last_known_contact_plane_cell_id == 0

    def test_the_pool_refuses_an_eleventh_nested_transition(self) -> None:
        world = World()
        made = 0
        try:
            for _ in range(MAX_TRANSITION_LEVEL):
                Transition.make_transition(world)
                made += 1
            with pytest.raises(RuntimeError, match="nested"):  # acclient.c:312564
                Transition.make_transition(world)
        finally:
            for _ in range(made):
                Transition.cleanup_transition()
        assert Transition.transition_level == 0

    def test_the_pool_reuses_each_level_and_init_resets_only_its_fields(self) -> None:
        # makeTransition builds ten transitions once and hands out transit[level] after
        # CTransition::init (acclient.c:312548-312571); init clears the object, the path's
        # SPHEREPATH::init fields and the cell array (311595), nothing else.
        world = World()
        first = Transition.make_transition(world)
        try:
            inner = Transition.make_transition(world)
            Transition.cleanup_transition()
            first.sphere_path.begin_cell = world.get_cell(0xA9B40001)
            first.sphere_path.global_offset = V(1.0, 2.0, 3.0)
            first.sphere_path.walk_interp = 0.25
            first.object_info.object = place(world, name="mover")
        finally:
            Transition.cleanup_transition()
        again = Transition.make_transition(world)
        try:
            assert again is first
            assert inner is not first
            assert again.object_info.object is None
            assert again.sphere_path.begin_cell is None
            # Not SPHEREPATH::init's (acclient.c:313430): left from the last sweep in this slot.
            assert again.sphere_path.global_offset == V(1.0, 2.0, 3.0)
            assert again.sphere_path.walk_interp == 0.25
        finally:
            Transition.cleanup_transition()

    def test_each_world_has_a_pool_of_its_own(self) -> None:
        # Retail's pool is the client's; a world is one simulation, so each has its own: what the
        # sweeps of one simulation leave in a slot never reaches another's.
        first, second = World(), World()
        mine = Transition.make_transition(first)
        Transition.cleanup_transition()
        mine.sphere_path.walk_interp = 0.25
        theirs = Transition.make_transition(second)
        Transition.cleanup_transition()
        assert theirs is not mine and theirs.sphere_path.walk_interp != 0.25
        assert (mine.world, theirs.world) == (first, second)
        assert Transition.pool(first)[0] is mine and Transition.pool(second)[0] is theirs
        assert len(Transition.pool(first)) == MAX_TRANSITION_LEVEL and first.transition_pool[0] is mine

    def test_a_scenario_loads_the_same_after_another_ran(self) -> None:
        # The spinner hangs in the air: entering the world sweeps it in place, and SetPositionInternal
        # copies the collision record's contact plane, which CollisionInfo::init leaves as the last
        # sweep in the slot had it (acclient.c:311566). In a new world that is the all-zero plane,
        # whatever another simulation in this process swept before.
        before = load_scenario().body("spinner").contact_plane
        other = load_scenario("hills")
        other.run(until=0.5)
        left = Transition.pool(other.world)[0].collision_info.contact_plane.N
        assert (left.x, left.y, left.z) != (0.0, 0.0, 0.0)
        after = load_scenario().body("spinner").contact_plane
        assert (before.N, before.d) == (after.N, after.d) == (V(0.0, 0.0, 0.0), 0.0)

    def test_walkable_is_floor_z(self) -> None:
        assert PhysicsObj.is_valid_walkable(V(0.0, 0.0, FLOOR_Z))
        assert not PhysicsObj.is_valid_walkable(V(0.0, 0.0, FLOOR_Z - EPSILON))
