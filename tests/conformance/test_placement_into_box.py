"""Placing a body whose sphere 0 pokes 5 mm into the top of a static box: retail slides it
sideways onto a ring position, it does not lift it.

Retail never resolves an object overlap during a placement: CObjCell::find_obj_collisions skips
objects for an INITIAL_PLACEMENT insert (acclient.c:347151), and for a PLACEMENT insert
BSPTREE::find_collisions (acclient.c:361295) only asks BSPNODE::sphere_intersects_solid and
answers COLLIDED (acclient.c:361335-361352). BSPTREE::placement_insert (which does push
spheres out along CPolygon::adjust_to_placement_poly) is reached only for INITIAL_PLACEMENT,
from CEnvCell::find_env_collisions and CGfxObj::find_obj_collisions (acclient.c:356514), never
for an object in a land cell. So CTransition::find_placement_pos (acclient.c:313014) tries its
rings of candidates at the requested height until one clears the box.
"""

from __future__ import annotations

import math

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.geometry.bsp_builder import build_box_tree
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.setup import Setup, human_setup
from acphys.world.static_objects import add_static_object
from acphys.world.world import World
from support import LANDBLOCK

GROUND = 50.0
TOP = 51.0
RADIUS = 0.48  # the human's sphere 0: r 0.48 at z 0.475, so its bottom is 0.005 below the origin


def test_a_body_sunk_into_a_box_top_is_placed_on_a_ring_beside_it_not_lifted():
    world = World()
    world.set_flat_ground(LANDBLOCK, GROUND)
    low, high = V(93.0, 93.0, GROUND), V(99.0, 98.0, TOP)
    box = Setup("box", physics_bsp=build_box_tree(V(), high - low))
    add_static_object(world, "box", box, Position(outdoor_cell_id(LANDBLOCK, low), Frame(low)))
    setup = human_setup()
    setup.step_up_height = setup.step_down_height = 0.4
    body = PhysicsObj(world, "sunk", PartArray(setup))
    body.state = PS.GRAVITY
    request = V(94.5, 96.0, TOP)  # sphere 0's bottom at 50.995: 5 mm into the top face
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, request), Frame(request)))

    # find_placement_pos (acclient.c:313014): r 0.48 gives ceil(4 / 0.48) = 9 rings 4/9 m apart;
    # ring k holds 2 * ceil(k * (4/9) / 0.48 * 3.1415999) candidates at even compass headings
    # from 0: 6, 12, 18, 24. The request sits 1.5 m from the west face (x 93) and 3 m from the
    # south face: sphere 0 (5 mm deep) clears the box only with its centre more than
    # sqrt(0.48^2 - 0.475^2) = 0.069 m outside a face, out of reach of rings 1-3 (1.333 m).
    # Ring 4 (1.778 m, 15 degrees apart) first clears it at heading 255 (x 92.783); 240 leaves
    # x at 92.96, still in.
    clear = math.sqrt(RADIUS**2 - 0.475**2)
    distance = 0.0
    per_ring = f32(4.0 / 9)
    for _ in range(4):
        distance = f32(distance + per_ring)
    heading = math.radians(255.0)
    expected_x = request.x + math.sin(heading) * distance
    expected_y = request.y + math.cos(heading) * distance
    assert expected_x < low.x - clear < request.x + math.sin(math.radians(240.0)) * distance
    origin = body.position.frame.origin
    assert abs(origin.x - expected_x) < 1e-5
    assert abs(origin.y - expected_y) < 1e-5
    # The landing step-down (find_placement_position, acclient.c:313340) then rests sphere 0 on
    # the top face's plane (its centre 0.22 m off the edge still reaches the polygon): z 51.005,
    # the float32 nearest it (the origin is a float store; sphere 0's float32 bottom is then a
    # few float32 ulps off the plane, well inside EPSILON).
    assert origin.z == f32(TOP + RADIUS - 0.475)
    assert body.transient_state & TS.CONTACT
    assert body.transient_state & TS.ON_WALKABLE
