"""Builders shared by the tests: bodies placed in a world."""

from __future__ import annotations

from acphys.flags import PhysicsState, TransientState
from acphys.geometry.plane import Plane
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.motion_table import MotionTable
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.setup import Setup, human_setup
from acphys.world.world import World

LANDBLOCK = 0xA9B4


def place(
    world: World,
    *,
    name: str = "body",
    spheres: bool = True,
    state: PhysicsState = PhysicsState.GRAVITY,
    origin: tuple[float, float, float] = (96.0, 96.0, 50.0),
    heading: float = 0.0,
    on_ground: bool = False,
    motion_table: MotionTable | None = None,
) -> PhysicsObj:
    """A body entered into ``world`` at ``origin`` (landblock 0xA9B4), active, with its acceleration set.

    With a ``motion_table`` the body also gets a movement manager in its default state.
    """
    setup = human_setup() if spheres else Setup(name="marker", spheres=[])
    body = PhysicsObj(world, name, PartArray(setup))
    body.state = state
    point = Vector3(*origin)
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, point), Frame.from_heading(point, heading)))
    if on_ground:
        body.transient_state |= TransientState.CONTACT | TransientState.ON_WALKABLE
        body.contact_plane = Plane.horizontal(origin[2])
    body.calc_acceleration()
    if motion_table is not None:
        body.set_motion_table(motion_table)
    return body
