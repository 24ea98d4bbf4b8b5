"""A tour of the Python API: load a scenario, add a body and events while it runs, watch every
step and every collision through callbacks, read the state flags by name, and take every body's
position and velocity as NumPy arrays.

Run it with ``python examples/api_tour.py`` (``--engine fast`` for the compiled engine: the same
output, the bodies with callbacks running on its reference path). Everything here goes through
``import acphys`` alone: no private names, no state bits set by hand.
"""

from __future__ import annotations

import argparse
from collections import Counter

import numpy as np

import acphys
from acphys import CollisionReport, PhysicsObj, PhysicsState, TransientState


def main(engine: str = "reference") -> None:
    # The built-in default scenario: a walker, a runner that jumps, a skydiver, a thrown ball, ...
    sim = acphys.load_scenario(engine=engine)

    steps: Counter[str] = Counter()
    landings: list[str] = []

    @sim.on_step
    def count(body: PhysicsObj, quantum: float) -> None:
        """After every physics step of every body (``step_events`` holds what the step did)."""
        steps[body.name] += 1
        if "hit_ground" in body.step_events:
            landings.append(f"{body.name} at {body.world.physics_time:.2f} s")

    touches: list[str] = []

    @sim.on_collision
    def touched(body: PhysicsObj, report: CollisionReport) -> None:
        """Every collision report a body receives (bodies with report_collisions in their state)."""
        if report.is_start and report.other is not None:
            touches.append(f"{body.name} touched {report.other.name} at {body.world.physics_time:.2f} s")

    sim.run(until=2.0)

    # A ball joins the running world, flying west at 8 m/s with no gravity, into the walker's path
    # (the keys of a scenario's [[body]] table; "ball" is the scenario's own [setup.ball]).
    ball = sim.add_body(
        name="thrown",
        setup="ball",
        landblock="0xA9B4",
        origin=[88.0, 68.0, 51.0],
        state=["report_collisions"],
        velocity=[-8.0, 0.0, 0.0],
    )
    # Events on the running timeline: a scenario action with its keys, and a function of the body.
    sim.add_event(3.5, "walker", "jump", extent=0.5)
    sim.add_event(4.0, "runner", "stop_motion", motion="WalkForward")

    def where(body: PhysicsObj) -> None:
        print(f"at {sim.time:.2f} s {body.name} is at {body.position.frame.origin}")

    sim.add_event(4.5, "runner", where)
    try:
        sim.add_event(1.0, "runner", "jump")
    except ValueError as error:
        print(f"refused: {error}")

    sim.run(until=6.0)

    print(f"steps: {', '.join(f'{name} {count}' for name, count in steps.items())}")
    print(f"landings: {'; '.join(landings)}")
    print(f"touches: {'; '.join(touches)}")

    walker = sim.body("walker")
    print(f"walker transient_state: {walker.transient_state!r}")
    print(f"walker on walkable ground: {TransientState.ON_WALKABLE in walker.transient_state}")
    print(f"thrown state: {ball.state!r}, gravity: {PhysicsState.GRAVITY in ball.state}")

    origin = np.asarray(walker.position.frame.origin)
    print(f"walker origin as an array: {origin} ({origin.dtype}, shape {origin.shape})")

    arrays = sim.arrays()  # every body at once, one row each in sim.bodies order
    speeds = np.linalg.norm(arrays.velocities, axis=1)
    print(f"arrays: {len(arrays)} bodies, positions {arrays.positions.shape} {arrays.positions.dtype}")
    for name, position, speed in zip(arrays.names, arrays.positions, speeds, strict=True):
        x, y, z = position
        print(f"  {name:10s} at ({x:9.2f}, {y:9.2f}, {z:7.2f}) m, {speed:5.2f} m/s")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--engine", choices=("reference", "fast"), default="reference")
    main(parser.parse_args().engine)
