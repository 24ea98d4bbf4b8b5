"""Differential tests: the kernel's sphere responses (:mod:`acphys.fast.kernels.contact`) against
:class:`acphys.geometry.sphere.Sphere`'s, one call at a time.

Each case is a random transition record (two moving spheres near an obstacle sphere, a step since
the current position, sometimes across a landblock edge, a contact plane or only a last known
one) written into a reference pool transition (:func:`acphys.fast.pool.transition_to_pool`). The
reference routine runs on the pool's path and collision record, the kernel's on the record; the
answers must be the same and so must every field either one may write (read back through
:func:`acphys.fast.pool.transition_from_pool`), bit for bit. The reference routines' own tests
pin their values to the decompilation (tests/conformance/test_sphere.py).
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
from numba import njit

from acphys.constants import EPSILON
from acphys.fast.kernels import contact
from acphys.fast.kernels.cells import BAIL
from acphys.fast.layout import TRANSITION
from acphys.fast.pool import transition_from_pool, transition_to_pool
from acphys.flags import ObjectInfoState
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.scenario import load_scenario
from acphys.transition.transition import Transition
from acphys.world.world import World

CASES = 400
#: The fields the routines may write.
WRITTEN = (
    "check_origin",
    "check_cell_id",
    "global_sphere",
    "global_low_point",
    "collision_normal_valid",
    "collision_normal",
    "contact_plane_valid",
    "contact_n",
    "contact_d",
    "contact_plane_is_water",
    "contact_plane_cell_id",
    "walk_interp",
    "cell_array_valid",
)


def f32(value: float) -> float:
    return float(np.float32(value))


@njit
def _skid(tr_array, ox, oy, oz, dx, dy, dz, s):
    return contact.slide_sphere_skid(tr_array[0], ox, oy, oz, dx, dy, dz, s)


@njit
def _slide(tr_array, ox, oy, oz, s):
    return contact.slide_sphere(tr_array[0], ox, oy, oz, s)


@njit
def _point(tr_array, ox, oy, oz, s):
    return contact.collide_with_point(tr_array[0], ox, oy, oz, s)


@njit
def _down(tr_array, ox, oy, oz, radius, dx, dy, dz, radsum):
    return contact.step_sphere_down(tr_array[0], ox, oy, oz, radius, dx, dy, dz, radsum)


@pytest.fixture(scope="module")
def world() -> World:
    """A world for the pool's transitions."""
    return load_scenario("ladder-01-fall").world


def _unit(rng: random.Random, z_low: float) -> tuple[float, float, float]:
    while True:
        x, y, z = rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(z_low, 1)
        n = math.sqrt(x * x + y * y + z * z)
        if n > 0.1:
            return f32(x / n), f32(y / n), f32(z / n)


def _case(rng: random.Random) -> tuple[np.ndarray, tuple[float, float, float, float]]:
    """A transition record and an obstacle sphere ``(x, y, z, r)`` near its spheres."""
    tr_array = np.zeros(1, dtype=TRANSITION)
    tr = tr_array[0]
    tr["num_sphere"] = 2
    tr["curr_cell"] = tr["check_cell"] = tr["backup_cell"] = -1  # no cell: the pool needs none
    radius = f32(rng.choice((0.48, 0.2, 0.75)))
    tr["local_sphere"][0] = (0.0, 0.0, f32(0.475), radius)
    tr["local_sphere"][1] = (0.0, 0.0, f32(1.35), radius)
    tr["local_low_point"] = (0.0, 0.0, f32(0.475 - radius))
    ox, oy = f32(rng.uniform(10, 182)), f32(rng.uniform(10, 182))
    oz = f32(rng.uniform(40, 60))
    tr["check_cell_id"] = tr["curr_cell_id"] = 0xA9B4000A
    if rng.random() < 0.2:  # the current position in the next landblock west
        tr["curr_cell_id"] = 0xA8B4000A
    tr["check_origin"] = (ox, oy, oz)
    for name in ("check_q", "curr_q", "backup_q"):
        tr[name] = (1.0, 0.0, 0.0, 0.0)
    for name in ("check_m", "curr_m", "backup_m"):
        tr[name] = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    shift = 192.0 if tr["curr_cell_id"] != tr["check_cell_id"] else 0.0
    step = (f32(rng.uniform(-0.3, 0.3)), f32(rng.uniform(-0.3, 0.3)), f32(rng.uniform(-0.1, 0.1)))
    tr["curr_origin"] = (f32(ox + shift - step[0]), f32(oy - step[1]), f32(oz - step[2]))
    for s in range(2):
        z = float(tr["local_sphere"][s][2])
        tr["global_sphere"][s] = (ox, oy, f32(oz + z), radius)
        tr["global_curr_center"][s] = tuple(
            f32(c) for c in (ox + shift - step[0], oy - step[1], oz + z - step[2])
        )
    tr["global_low_point"] = (ox, oy, f32(oz + 0.475 - radius))
    n = _unit(rng, 0.3) if rng.random() < 0.8 else (0.0, 0.0, 1.0)
    tr["contact_plane_valid"] = rng.random() < 0.6
    tr["contact_n"] = n
    tr["contact_d"] = f32(-oz)
    tr["last_known_contact_n"] = _unit(rng, 0.0) if rng.random() < 0.5 else n
    tr["last_known_contact_d"] = f32(-oz + 0.01)
    tr["oi_state"] = int(ObjectInfoState.CONTACT | ObjectInfoState.ON_WALKABLE)
    tr["walk_interp"] = f32(rng.choice((1.0, 0.5, 0.25)))
    tr["step_down_amt"] = f32(rng.choice((0.6, 0.04, 0.3, 0.0)))
    tr["walkable_allowance"] = f32(rng.choice((0.6642, 0.0872)))
    tr["step_down"] = True
    # the obstacle: beside, above or below a moving sphere, mostly within reach
    s = rng.randrange(2)
    centre = tr["global_sphere"][s]
    r = f32(rng.choice((0.48, 0.2, 0.1)))
    if rng.random() < 0.2:  # straight above or below the sphere's current centre
        curr = tr["global_curr_center"][s]
        obstacle = (
            f32(curr[0] - shift),
            f32(curr[1]),
            f32(curr[2] + rng.choice((-1, 1)) * (r + radius) * 0.9),
            r,
        )
    else:
        u = _unit(rng, -1.0)
        d = (r + radius) * rng.uniform(0.5, 1.1)
        obstacle = (f32(centre[0] + u[0] * d), f32(centre[1] + u[1] * d), f32(centre[2] + u[2] * d), r)
    return tr_array, obstacle


def _compare(got: np.ndarray, want: np.ndarray, label: str) -> None:
    for name in WRITTEN:
        a, b = np.asarray(got[0][name]), np.asarray(want[0][name])
        assert a.tobytes() == b.tobytes(), f"{label}: {name} {a} != {b}"


def _run(world: World, seed: int, kernel_call, reference_call) -> str:
    """One case both ways; the answer it got (for the branch census)."""
    rng = random.Random(seed)
    tr_array, obstacle = _case(rng)
    transition_to_pool(tr_array, None, world)  # type: ignore[arg-type]
    transit = Transition.pool(world)[0]
    ox, oy, oz, r = obstacle
    sphere = Sphere(Vector3(ox, oy, oz), r)
    answer = kernel_call(tr_array, obstacle)
    if answer == BAIL:
        return "bail"
    expected = reference_call(transit, sphere)
    assert answer == int(expected), f"seed {seed}: kernel {answer}, reference {expected!r}"
    want = np.zeros(1, dtype=TRANSITION)
    want[0] = tr_array[0]
    transition_from_pool(want, None, world)  # type: ignore[arg-type]
    _compare(tr_array, want, f"seed {seed}")
    return str(int(expected))


def _disp(tr_array: np.ndarray, obstacle: tuple[float, ...], s: int) -> tuple[float, float, float]:
    c = tr_array[0]["global_sphere"][s]
    return f32(c[0] - obstacle[0]), f32(c[1] - obstacle[1]), f32(c[2] - obstacle[2])


def _radsum(tr_array: np.ndarray, obstacle: tuple[float, ...]) -> float:
    return f32(obstacle[3] + tr_array[0]["global_sphere"][0][3] - EPSILON)


def test_slide_sphere_skid(world: World) -> None:
    """``CSphere::slide_sphere`` (acclient.c:358708), sphere 0 or 1, every branch."""
    answers = set()
    for seed in range(CASES):
        s = seed % 2

        def kernel(tr_array, o, s=s):
            return _skid(tr_array, o[0], o[1], o[2], *_disp(tr_array, o, 0), s)

        def reference(transit, sphere, s=s):
            path, info, obj = transit.sphere_path, transit.collision_info, transit.object_info
            disp = path.global_sphere[0].center - sphere.center
            return sphere.slide_sphere_skid(obj, path, info, disp, f32(sphere.radius + 0.48), s)

        answers.add(_run(world, seed, kernel, reference))
    assert {"2", "4"} <= answers  # COLLIDED and SLID both reached


def test_slide_sphere_normal(world: World) -> None:
    """``CSphere::slide_sphere`` (acclient.c:359138) for sphere 1, and its slide (acclient.c:358898)."""
    answers = set()
    for seed in range(CASES):

        def kernel(tr_array, o):
            return _slide(tr_array, o[0], o[1], o[2], 1)

        def reference(transit, sphere):
            path, info, obj = transit.sphere_path, transit.collision_info, transit.object_info
            second = path.global_sphere[1]
            disp = second.center - sphere.center
            return sphere.slide_sphere(obj, path, info, second, disp, _radsum_of(path, sphere), 1)

        answers.add(_run(world, seed, kernel, reference))
    assert {"2", "4"} <= answers


def _radsum_of(path, sphere: Sphere) -> float:
    return f32(sphere.radius + path.global_sphere[0].radius - EPSILON)


def test_collide_with_point(world: World) -> None:
    """``CSphere::collide_with_point`` (acclient.c:358807) without a perfect clip."""
    for seed in range(CASES // 4):
        s = seed % 2

        def kernel(tr_array, o, s=s):
            return _point(tr_array, o[0], o[1], o[2], s)

        def reference(transit, sphere, s=s):
            path, info, obj = transit.sphere_path, transit.collision_info, transit.object_info
            moving = path.global_sphere[s]
            disp = moving.center - sphere.center
            return sphere.collide_with_point(obj, path, info, moving, disp, _radsum_of(path, sphere), s)

        assert _run(world, seed, kernel, reference) == "2"


def test_step_sphere_down(world: World) -> None:
    """``CSphere::step_sphere_down`` (acclient.c:358615): missing, rewinding too far, or landing
    on a walkable top (ADJUSTED, with the contact plane set)."""
    answers = set()
    for seed in range(CASES):

        def kernel(tr_array, o):
            return _down(tr_array, o[0], o[1], o[2], o[3], *_disp(tr_array, o, 0), _radsum(tr_array, o))

        def reference(transit, sphere):
            path, info, obj = transit.sphere_path, transit.collision_info, transit.object_info
            moving = path.global_sphere[0]
            disp = moving.center - sphere.center
            return sphere.step_sphere_down(obj, path, info, moving, disp, _radsum_of(path, sphere))

        answers.add(_run(world, seed, kernel, reference))
    assert {"1", "2", "3"} <= answers  # OK, COLLIDED and ADJUSTED all reached
