"""Builders shared by the tests: bodies placed in a world."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from acphys.constants import GRAVITY
from acphys.flags import PhysicsState, TransientState
from acphys.geometry.plane import Plane
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.motion_table import MotionTable
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.setup import Setup, human_setup
from acphys.trace import read_trace
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
    setup: Setup | None = None,
) -> PhysicsObj:
    """A body entered into ``world`` at ``origin`` (landblock 0xA9B4), active, with its acceleration set.

    The body is the built-in human (``setup`` for another shape; no spheres at all without
    ``spheres``). With a ``motion_table`` the body also gets a movement manager in its default state.
    """
    if setup is None:
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


def ulp32(x: float) -> float:
    """The spacing of float32 values at ``x`` (acphys stores positions as float32)."""
    return 2.0 ** (math.frexp(abs(x))[1] - 24) if x else 2.0**-149


def walk_tolerance(where: float, steps: int) -> float:
    """How far ``steps`` float32 position stores near ``where`` can drift from the double sum:
    half a float32 spacing each, plus one for the start. Far below any step a test counts."""
    return (steps / 2 + 1) * ulp32(where)


#: A unit quantity (a normal, a quaternion component) computed through float32 stores: good to a
#: few float32 ulps of 1.
UNIT_TOL = 2.0**-21


def fall(z0: float, dt: float, n: int, v0: float = 0.0) -> tuple[float, float]:
    """Origin z and velocity z after ``n`` free-fall steps, as retail's float stores make them.

    CPhysicsObj::UpdatePhysicsInternal (acclient.c:317700): only with v² > 0 does the origin move
    (so step 1 from rest does not), by ``w.z = result.z + w.z·dt·dt`` where ``result.z = dt·v.z``
    and ``w.z = a.z·0.5`` are float locals, then ``origin.z = w.z + origin.z`` (a float field);
    then ``v.z = result.z + v.z`` with ``result.z = dt·a.z`` spilled (acclient.c:317760-317775).
    In double arithmetic step k would move (k-1)·g·dt² + g·dt²/2 and n steps g·dt²·(n² - 1)/2.
    """
    z, v = f32(z0), v0
    for _ in range(n):
        if v * v > 0.0:
            z = f32(f32(f32(dt * v) + f32(GRAVITY * 0.5) * dt * dt) + z)
        v = f32(f32(dt * GRAVITY) + v)
    return z, v


def step_records(trace: Path) -> list[dict[str, Any]]:
    """The records of a trace's steps, in order: its header and the records of where the run
    started (``quantum`` 0) left out."""
    return [record for _, record in read_trace(trace) if record["quantum"] > 0]
