"""SPHEREPATH and COLLISIONINFO helpers the sphere routines call."""

from __future__ import annotations

from acphys.flags import TransitionState as TS
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.transition import SpherePath
from acphys.world.world import World
from support import place


def test_sphere_path_defaults() -> None:
    path = SpherePath()
    # SPHEREPATH::init clears everything but placement_allows_sliding (acclient.c:313450).
    assert path.placement_allows_sliding and not path.collide and not path.step_down
    assert path.walkable_allowance == 0.0 and path.num_sphere == 0


def test_cache_and_offset_global_spheres() -> None:
    path = SpherePath()
    path.local_sphere = [Sphere(Vector3(1, 0, 0.5), 0.5)]
    path.local_low_point = Vector3(1, 0, 0)
    frame = Frame(origin=Vector3(10, 20, 0))
    frame.set_heading(90.0)
    path.set_check_pos(Position(0xA9B40001, frame), None)
    # cache_global_sphere(0) places centre and low point in check_pos's frame (acclient.c:313790-313845).
    # Heading 90 (facing +x) turns local +x to global -y, so (1,0,0.5) lands at (10,19,0.5).
    assert path.global_sphere[0].center == Vector3(10, 19, 0.5)
    assert path.global_low_point == Vector3(10, 19, 0)
    before = path.global_sphere[0].center.copy()
    path.cell_array_valid = True
    path.add_offset_to_check_pos(Vector3(0, 0, 2), 0.5)
    # The offset moves origin, spheres and low point; the cell array goes stale (acclient.c:358527-358532).
    assert not path.cell_array_valid
    assert path.global_sphere[0].center.exactly_equals(before + Vector3(0, 0, 2))
    assert path.check_pos.frame.origin.exactly_equals(Vector3(10, 20, 2))


def test_set_collide_and_restore() -> None:
    path = SpherePath()
    path.local_sphere = [Sphere(Vector3(0, 0, 0.5), 0.5)]
    path.set_check_pos(Position(0xA9B40001, Frame(origin=Vector3(1, 2, 3))), None)
    path.walk_interp = 0.3
    path.set_collide(Vector3(0, 0, 1))
    # set_collide saves check_pos, stores the normal and resets walk_interp to 1.0 (acclient.c:359058-359067).
    assert path.collide and path.walk_interp == 1.0 and path.step_up_normal.exactly_equals(Vector3(0, 0, 1))
    path.add_offset_to_check_pos(Vector3(5, 0, 0))
    path.restore_check_pos()
    assert path.check_pos.frame.origin.exactly_equals(Vector3(1, 2, 3))  # acclient.c:312533-312537
    assert path.global_sphere[0].center.exactly_equals(Vector3(1, 2, 3.5))


def test_neg_poly_hit_reverses_normal() -> None:
    path = SpherePath()
    path.set_neg_poly_hit(True, Vector3(0, 1, 0))
    assert path.neg_poly_hit and path.neg_step_up  # acclient.c:360750-360751
    assert path.neg_collision_normal.exactly_equals(Vector3(0, -1, 0))


def test_block_offset_between_curr_and_check() -> None:
    path = SpherePath()
    path.curr_pos = Position(0xA9B40001)
    path.check_pos = Position(0xA9B50001)
    assert path.get_curr_pos_check_pos_block_offset().exactly_equals(Vector3(0, 192.0, 0))  # 311720


def test_collision_normals() -> None:
    info = CollisionInfo()
    info.set_collision_normal(Vector3(0, 3, 4))
    assert info.collision_normal_valid and info.collision_normal == Vector3(0, 0.6, 0.8)
    # Too small: still valid, stored as zero (acclient.c:311733-311738).
    info.set_collision_normal(Vector3(0.0001, 0, 0))
    assert info.collision_normal_valid and info.collision_normal.exactly_equals(Vector3())
    # Sliding normal keeps only x, y (acclient.c:311750-311752).
    info.set_sliding_normal(Vector3(3, 4, 9))
    assert info.sliding_normal == Vector3(0.6, 0.8, 0)


def test_add_object_once_and_last_collided() -> None:
    world_obj = place(World())
    info = CollisionInfo()
    info.add_object(world_obj, TS.OK)
    # OK does not make it the last collided object (acclient.c:718749); duplicates are skipped.
    assert info.num_collide_object == 1 and info.last_collided_object is None
    info.add_object(world_obj, TS.COLLIDED)
    assert info.num_collide_object == 1 and info.last_collided_object is None
    info.init()
    info.add_object(world_obj, TS.COLLIDED)
    assert info.last_collided_object is world_obj
