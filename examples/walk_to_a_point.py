"""Drive the tick yourself: a human walks to a point, turns east, runs, and jumps.

Run it with ``python examples/walk_to_a_point.py``. Every command goes through
the retail entry points (MoveToPosition, TurnToHeading, DoMotion,
CMotionInterp::jump); the body moves by animation root motion, one frame's
worth at each frame boundary, and its ``velocity`` only changes for the jump.
"""

from __future__ import annotations

import acphys
from acphys.geometry.plane import Plane
from acphys.math.cell_id import outdoor_cell_id
from acphys.setup import human_setup

LANDBLOCK = 0xA9B4
QUANTUM = 1.0 / 30.0


def main() -> None:
    world = acphys.World()
    world.set_flat_ground(LANDBLOCK, 50.0)

    body = acphys.PhysicsObj(world, "walker", acphys.PartArray(human_setup()))
    start = acphys.Vector3(96.0, 96.0, 50.0)
    body.enter_world(acphys.Position(outdoor_cell_id(LANDBLOCK, start), acphys.Frame(start)))
    body.transient_state |= acphys.TransientState.CONTACT | acphys.TransientState.ON_WALKABLE
    body.contact_plane = Plane.horizontal(50.0)
    body.calc_acceleration()
    body.set_motion_table(acphys.builtin_motion_table("humanoid"))

    def run(seconds: float) -> None:
        for _ in range(round(seconds / QUANTUM)):
            world.cur_time += QUANTUM
            body.update_object()

    target = acphys.Vector3(96.0, 108.0, 50.0)
    body.move_to_position(
        acphys.Position(outdoor_cell_id(LANDBLOCK, target), acphys.Frame(target)), acphys.MovementParameters()
    )
    run(6.0)
    print(f"arrived at {body.position.frame.origin}, still moving to: {body.is_moving_to()}")

    body.turn_to_heading(acphys.MovementParameters(desired_heading=90.0))
    run(2.0)
    print(f"facing {body.position.frame.get_heading():.1f} degrees")

    body.do_motion(
        acphys.commands.WALK_FORWARD, acphys.MovementParameters(hold_key_to_apply=acphys.HoldKey.RUN)
    )
    run(1.0)
    error, _stamina = body.get_minterp().jump(1.0)
    print(f"jump: error {error:#x}, launch velocity {body.velocity}")
    run(3.0)
    print(
        f"landed at {body.position.frame.origin}, on walkable ground: "
        f"{bool(body.transient_state & acphys.TransientState.ON_WALKABLE)}"
    )


if __name__ == "__main__":
    main()
