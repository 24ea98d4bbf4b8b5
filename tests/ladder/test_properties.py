"""Property tests for the collision sweep: random terrain, random obstacles, random throws and walks.

A seeded generator builds scenarios of one landblock of random height bytes (through an explicit
height table), random static boxes and pillars standing on it, and bodies thrown or walking with
random velocities. Every physics step of every body is checked: no NaN in position or velocity,
no body sphere inside a box's physics BSP (``BSPNode.sphere_intersects_solid`` in the box's frame)
or a pillar's cylinder, and no sphere's lowest point below the terrain under its centre
(``World.ground_height``).

Tolerance (``TOL``, 1 mm). Retail resolves contacts to within ``EPSILON`` (0.0002 m):
``BSPNODE::sphere_intersects_solid`` (acclient.c:363573) already lets a sphere sit ``EPSILON``
deep, sphere-vs-plane tests in ``CPolygon`` compare against ``radius - EPSILON``, and a body
resting on a polygon is adjusted to touch it exactly in float32 coordinates. ``TOL`` is five
times EPSILON, enough for those contact slops and the float32 constants (landblock coordinates
near 100 m carry about 1e-5 m of float32 resolution), and two orders of magnitude below any real
tunnelling (a 0.1-m sphere stepping by its radius would penetrate by centimetres).

Why the terrain check is exact geometry: a sphere that does not overlap the (height-field)
terrain has the terrain point straight below its centre outside it, so that point lies at or
below the sphere's lowest point ``center.z - r``, whatever the slopes around it.
"""

from __future__ import annotations

import math
import random

import acphys
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj

TOL = 0.001
LANDBLOCK = 0xA9B4
#: The acphys "1 m per step" height table: entry i is i metres.
HEIGHT_TABLE = [float(i) for i in range(256)]
SEED = 0x6AC
SCENARIOS = 8
DURATION = 4.0
#: Where things are put: a 40-m square in the middle of the landblock, so they meet often.
LOW, HIGH = 76.0, 116.0


def _heights(rng: random.Random) -> list[int]:
    """81 height bytes: 40 m plus 0-6 m of noise, and a spike of up to 20 m at one vertex in ten
    (slopes from gentle to steeper than ``floor_z`` allows)."""
    return [40 + rng.randint(0, 20 if rng.random() < 0.1 else 6) for _ in range(81)]


def _ground(heights: list[int], x: float, y: float) -> float:
    """A rough ground height for placing things (the nearest vertex): only used to seed positions."""
    return HEIGHT_TABLE[heights[round(x / 24.0) * 9 + round(y / 24.0)]]


def _scenario_text(rng: random.Random, index: int) -> tuple[str, list[dict]]:
    """A random scenario's TOML text and its obstacles (name, kind, size) for the checks."""
    heights = _heights(rng)
    lines = [
        "[scenario]",
        f'name = "property-{index}"',
        f"duration = {DURATION}",
        "driver_hz = 60.0",
        "[[landblock]]",
        f'id = "0x{LANDBLOCK:04X}"',
        f"heights = {heights}",
        f"height_table = {HEIGHT_TABLE}",
        "[setup.walker]",
        "spheres = [{ center = [0.0, 0.0, 0.475], radius = 0.48 }, "
        "{ center = [0.0, 0.0, 1.35], radius = 0.48 }]",
        "step_up_height = 0.4",
        "step_down_height = 0.4",
        'motion_table = "humanoid"',
    ]
    obstacles: list[dict] = []
    for k in range(10):
        x, y = rng.uniform(LOW, HIGH), rng.uniform(LOW, HIGH)
        z = _ground(heights, x, y) - 0.5
        name = f"obstacle-{k}"
        if rng.random() < 0.5:
            hx, hy, hz = rng.uniform(0.3, 3.0), rng.uniform(0.3, 3.0), rng.uniform(0.5, 2.5)
            lines += [
                f"[setup.{name}]",
                f"boxes = [{{ min = [{-hx}, {-hy}, 0.0], max = [{hx}, {hy}, {hz + 0.5}] }}]",
            ]
            obstacles.append({"name": name, "kind": "box"})
        else:
            radius, height = rng.uniform(0.3, 1.5), rng.uniform(1.0, 4.0)
            lines += [
                f"[setup.{name}]",
                f"cylspheres = [{{ low_pt = [0.0, 0.0, 0.0], radius = {radius}, height = {height} }}]",
            ]
            obstacles.append({"name": name, "kind": "pillar", "radius": radius, "height": height})
        lines += [
            "[[object]]",
            f'name = "{name}"',
            f'setup = "{name}"',
            f'landblock = "0x{LANDBLOCK:04X}"',
            f"origin = [{x}, {y}, {z}]",
            f"heading = {rng.choice([0.0, 30.0, 90.0, 135.0])}",
        ]
    for k in range(6):
        radius = rng.uniform(0.1, 0.5)
        x, y = rng.uniform(LOW, HIGH), rng.uniform(LOW, HIGH)
        z = _ground(heights, x, y) + rng.uniform(2.0, 8.0)
        velocity = [rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0), rng.uniform(-5.0, 8.0)]
        state = '["gravity", "report_collisions"]'
        if k == 0:
            state = '["gravity", "report_collisions", "missile"]'
        lines += [
            f"[setup.ball-{k}]",
            f"spheres = [{{ center = [0.0, 0.0, {radius}], radius = {radius} }}]",
            'motion_table = "none"',
            "[[body]]",
            f'name = "ball-{k}"',
            f'setup = "ball-{k}"',
            f'landblock = "0x{LANDBLOCK:04X}"',
            f"origin = [{x}, {y}, {z}]",
            f"state = {state}",
            f"velocity = {velocity}",
            f"elasticity = {rng.uniform(0.0, 0.1)}",
            "on_ground = false",
        ]
    for k in range(4):
        x, y = rng.uniform(LOW, HIGH), rng.uniform(LOW, HIGH)
        lines += [
            "[[body]]",
            f'name = "walker-{k}"',
            'setup = "walker"',
            f'landblock = "0x{LANDBLOCK:04X}"',
            f"origin = [{x}, {y}, {_ground(heights, x, y) + 1.0}]",
            f"heading = {rng.uniform(0.0, 360.0)}",
            'state = ["gravity", "report_collisions", "edge_slide"]',
            "on_ground = false",
            "[[event]]",
            f"at = {rng.uniform(0.5, 1.5)}",
            f'body = "walker-{k}"',
            'action = "motion"',
            f'motion = "{rng.choice(["WalkForward", "RunForward", "SideStepRight"])}"',
        ]
    return "\n".join(lines) + "\n", obstacles


def _static_objects(sim: acphys.Simulation, obstacles: list[dict]) -> list[tuple[PhysicsObj, dict]]:
    """The static objects of ``sim`` (found in the land cells they stand in) with their descriptions."""
    by_name = {}
    for cell_index in range(1, 65):
        cell = sim.world.get_cell((LANDBLOCK << 16) | cell_index)
        assert cell is not None
        for obj in cell.objects:
            by_name[obj.name] = obj
    return [(by_name[o["name"]], o) for o in obstacles]


def _finite(v: Vector3) -> bool:
    return all(math.isfinite(c) for c in (v.x, v.y, v.z))


def _pillar_overlap(obj: PhysicsObj, desc: dict, center: Vector3, radius: float) -> bool:
    """Whether a sphere overlaps a pillar's solid cylinder by more than TOL."""
    local = obj.position.frame.globaltolocal(center)
    horizontal = max(0.0, math.hypot(local.x, local.y) - desc["radius"])
    vertical = max(0.0, -local.z, local.z - desc["height"])
    return math.hypot(horizontal, vertical) < radius - TOL


class _Checker:
    """Checks every step of every body; collects the violations."""

    def __init__(self, sim: acphys.Simulation, obstacles: list[dict]) -> None:
        self.sim = sim
        self.statics = _static_objects(sim, obstacles)
        self.failures: list[str] = []
        self.steps = 0

    def __call__(self, body: PhysicsObj, quantum: float) -> None:
        self.steps += 1
        where = f"{body.name} at t={body.world.physics_time:.4f}"
        frame = body.position.frame
        if not (_finite(frame.origin) and _finite(body.velocity)):
            self.failures.append(f"{where}: NaN/inf origin {frame.origin} velocity {body.velocity}")
            return
        if body.position.objcell_id >> 16 != LANDBLOCK:
            self.failures.append(f"{where}: left the landblock: {body.position.objcell_id:#x}")
            return
        for sphere in body.part_array.get_sphere():
            center = frame.localtoglobal(sphere.center * body.scale)
            radius = sphere.radius * body.scale
            ground = body.world.ground_height(body.position.objcell_id, center)
            assert ground is not None
            if center.z - radius < ground - TOL:
                self.failures.append(
                    f"{where}: below the terrain by {ground - (center.z - radius):.5f} m at {center}"
                )
            for obj, desc in self.statics:
                if desc["kind"] == "box":
                    local = obj.position.frame.globaltolocal(center)
                    bsp = obj.part_array.setup.physics_bsp
                    if bsp.root_node.sphere_intersects_solid(Sphere(local, radius - TOL), True):
                        self.failures.append(f"{where}: inside {desc['name']} at {center}")
                elif _pillar_overlap(obj, desc, center, radius):
                    self.failures.append(f"{where}: inside {desc['name']} at {center}")


def test_random_worlds_never_end_a_step_inside_solid_or_below_ground() -> None:
    rng = random.Random(SEED)
    for index in range(SCENARIOS):
        text, obstacles = _scenario_text(rng, index)
        sim = acphys.parse_scenario(text, source=f"<property {index}>")
        checker = _Checker(sim, obstacles)
        for body in sim.bodies:
            body.observer = checker
        sim.run()
        # 30 steps a second per body: the check really ran on every step.
        assert checker.steps >= len(sim.bodies) * 30 * (DURATION - 0.1)
        assert not checker.failures, f"scenario {index}:\n" + "\n".join(checker.failures[:20])
