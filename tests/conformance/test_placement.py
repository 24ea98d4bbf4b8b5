"""Placement: ``CPhysicsObj::SetPosition`` and its helpers, and the placement validations of
``CTransition``; expected values worked by hand from the decompiled CPhysicsObj.c and
CTransition.c (acclient.c lines beside each assertion).

Worlds: flat ground at 50 m on landblocks 0xA9B4 and 0xAAB4; two rooms in 0xA9B4, room A
0xA9B40100 = box (100,100,10)-(104,104,13), room B 0xA9B40101 = box (104,100,10)-(108,104,13),
joined by a doorway on x = 104 (a room without portals holds no point, CEnvCell::point_in_cell).
"""

from __future__ import annotations

import pytest

from acphys.flags import PhysicsState, TransientState
from acphys.flags import TransitionState as TS
from acphys.geometry.plane import Plane
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj, SetPositionError, SetPositionFlags, SetPositionStruct
from acphys.precision import f32
from acphys.setup import human_setup
from acphys.transition.placement import validate_placement, validate_placement_transition
from acphys.transition.transition import Transition
from acphys.world.rooms import DoorwaySpec, RoomSpec, build_rooms
from acphys.world.world import World

A, B = 0xA9B40100, 0xA9B40101
LOW_PT = V(0.0, 0.0, 0.475)  # the human's sphere 0 centre


@pytest.fixture
def world() -> World:
    w = World()
    w.set_flat_ground(0xA9B4, 50.0)
    w.set_flat_ground(0xAAB4, 50.0)
    rooms = [RoomSpec(A, V(100, 100, 10), V(104, 104, 13)), RoomSpec(B, V(104, 100, 10), V(108, 104, 13))]
    for room in build_rooms(rooms, [DoorwaySpec(V(104, 101, 10), V(104, 102, 12))]):
        w.add_cell(room)
    return w


def human(world: World) -> PhysicsObj:
    body = PhysicsObj(world, "human", PartArray(human_setup()))
    body.state = PhysicsState.GRAVITY
    return body


class TestAdjustPosition:
    def test_outdoors_rehomes_across_the_seam(self, world: World) -> None:
        p = Position(0xA9B40001, Frame(V(200.0, 10.0, 50.0)))
        cell = human(world).adjust_position(p, LOW_PT, search_cells=True)
        # LandDefs::adjust_to_outside (acclient.c:319161-319166): x 200 is block 0xAA, x 8 in it; cell 1.
        assert p.objcell_id == 0xAAB40001
        assert p.frame.origin.x == 8.0
        assert cell is world.get_cell(0xAAB40001)

    @pytest.mark.parametrize("low_word", [0x0000, 0x0041, 0x00FF, 0xFFFE])
    def test_an_invalid_cell_index_has_no_cell(self, world: World, low_word: int) -> None:
        p = Position(0xA9B40000 | low_word, Frame(V(10.0, 10.0, 50.0)))
        # Outside 1..0x40, 0x100..0xFFFD and 0xFFFF: return 0 (acclient.c:319130-319131).
        assert human(world).adjust_position(p, LOW_PT, search_cells=True) is None
        assert p.objcell_id == 0xA9B40000 | low_word

    def test_indoors_the_room_holding_the_low_point(self, world: World) -> None:
        p = Position(A, Frame(V(102.0, 102.0, 10.0)))
        # find_visible_child_cell: the cell itself holds (102,102,10.475) (acclient.c:349708).
        assert human(world).adjust_position(p, LOW_PT, search_cells=True) is world.get_cell(A)
        assert p.objcell_id == A

    def test_indoors_a_stab_list_room(self, world: World) -> None:
        world.get_cell(A).stab_list = [B]
        p = Position(A, Frame(V(106.0, 102.0, 10.0)))
        # Not in A; searching the stab list finds B (acclient.c:349713-349730, 319143-319145).
        assert human(world).adjust_position(p, LOW_PT, search_cells=True) is world.get_cell(B)
        assert p.objcell_id == B

    def test_indoors_nowhere_and_not_seeing_outside_has_no_cell(self, world: World) -> None:
        p = Position(A, Frame(V(110.0, 102.0, 10.0)))
        # No child cell and seen_outside clear: new_cell stays 0 (acclient.c:319147, 319169).
        assert human(world).adjust_position(p, LOW_PT, search_cells=True) is None
        assert p.objcell_id == A

    def test_indoors_nowhere_but_seeing_outside_hands_over_to_the_land(self, world: World) -> None:
        world.get_cell(A).seen_outside = True
        p = Position(A, Frame(V(110.0, 102.0, 10.0)))
        # Position::adjust_to_outside (acclient.c:319147-319154): cx 4, cy 4 -> 1 + 8*4 + 4 = 0x25.
        cell = human(world).adjust_position(p, LOW_PT, search_cells=True)
        assert p.objcell_id == 0xA9B40025
        assert cell is world.get_cell(0xA9B40025)


class TestSetPosition:
    def test_no_scatter_tries_is_a_general_failure(self, world: World) -> None:
        body = human(world)
        sps = SetPositionStruct(
            Position(0xA9B40025, Frame(V(96.0, 96.0, 50.0))), SetPositionFlags.RANDOM_SCATTER
        )
        # RANDOMSCATTER goes straight to SetScatterPositionInternal (acclient.c:323268), whose
        # result starts at 1 and no try changes it (acclient.c:323196-323198).
        assert body.set_position(sps) == SetPositionError.GENERAL_FAILURE
        assert body.cell is None

    def test_a_position_with_no_cell_goes_to_the_lost_cell_and_is_ok(self, world: World) -> None:
        body = human(world)
        # A room nobody added: adjust_position finds no cell, the body is stored and lost, ACTIVE
        # cleared, and the result is OK (acclient.c:323072-323077).
        sps = SetPositionStruct(Position(0xA9B40200, Frame(V(5.0, 5.0, 5.0))), SetPositionFlags.PLACEMENT)
        body.transient_state |= TransientState.ACTIVE
        assert body.set_position(sps) == SetPositionError.OK
        assert body.cell is None
        assert body.position.objcell_id == 0xA9B40200
        assert not body.transient_state & TransientState.ACTIVE

    def test_enter_world_with_no_cell_still_enters(self, world: World) -> None:
        body = human(world)
        # SetPosition returned OK, so enter_world activates the body (acclient.c:323369-323384).
        assert body.enter_world(Position(0xA9B40200, Frame(V(5.0, 5.0, 5.0))))
        assert body.cell is None
        assert body.transient_state & TransientState.ACTIVE

    def test_a_parented_body_cannot_enter(self, world: World) -> None:
        body = human(world)
        body.parent = human(world)
        # enter_world(slide) returns 0 for a parented body (acclient.c:323358-323359).
        assert not body.enter_world(Position(0xA9B40025, Frame(V(96.0, 96.0, 50.0))))


class TestValidatePlacement:
    def transition(self, world: World) -> Transition:
        transit = Transition(world, human(world))
        transit.init_sphere(human_setup().spheres, 1.0)
        return transit

    def test_no_check_cell_is_collided(self, world: World) -> None:
        transit = self.transition(world)
        transit.sphere_path.check_cell = None
        # acclient.c:312609-312610
        assert validate_placement(transit, TS.OK, True) == TS.COLLIDED

    def test_ok_takes_the_candidate(self, world: World) -> None:
        transit = self.transition(world)
        path = transit.sphere_path
        cell = world.get_cell(0xA9B40025)
        path.set_check_pos(Position(0xA9B40025, Frame(V(96.0, 96.0, 51.0))), cell)
        # curr_pos and curr_cell take check_pos and check_cell (acclient.c:312614-312618).
        assert validate_placement(transit, TS.OK, False) == TS.OK
        assert path.curr_cell is cell
        assert path.curr_pos.frame.origin.z == 51.0
        # cache_global_curr_center stores the centre as float: 51 + f32(0.475), narrowed
        # (acclient.c:313732-313741).
        assert path.global_curr_center[0].z == f32(51.0 + f32(0.475))

    def test_collided_is_passed_through(self, world: World) -> None:
        transit = self.transition(world)
        transit.sphere_path.check_cell = world.get_cell(0xA9B40025)
        # Only ADJUSTED and SLID re-insert (acclient.c:312620); COLLIDED comes back unchanged.
        assert validate_placement(transit, TS.COLLIDED, True) == TS.COLLIDED

    def test_a_failed_try_resets_the_collision_info_when_sliding(self, world: World) -> None:
        transit = self.transition(world)
        transit.sphere_path.check_cell = world.get_cell(0xA9B40025)
        transit.object_info.target_id = 7  # ACE skips the reset with a target; retail does not
        info = transit.collision_info
        info.set_contact_plane(Plane.horizontal(50.0), False)
        info.collision_normal_valid = True
        # COLLIDED with placement_allows_sliding: COLLISIONINFO::init (acclient.c:312372-312374).
        assert validate_placement_transition(transit, TS.COLLIDED) == TS.COLLIDED
        assert not info.contact_plane_valid
        assert not info.collision_normal_valid

    def test_a_failed_try_keeps_the_collision_info_without_sliding(self, world: World) -> None:
        transit = self.transition(world)
        transit.sphere_path.check_cell = world.get_cell(0xA9B40025)
        transit.sphere_path.placement_allows_sliding = False
        info = transit.collision_info
        info.set_contact_plane(Plane.horizontal(50.0), False)
        # acclient.c:312372: no sliding, no reset.
        assert validate_placement_transition(transit, TS.ADJUSTED) == TS.ADJUSTED
        assert info.contact_plane_valid
