"""The quick reject of sphere bodies in ``find_obj_collisions`` (``CollisionReports.out_of_reach``).

Not a retail routine: it may only skip pairs the exact test would find apart. These tests put a
human (two spheres, any heading and scale, in this or the next landblock) and a moving pair of
spheres at random, many of them within a few millimetres of touching, and check the reject
against the exact test CSphere::intersects_sphere makes (``|disp|² <= radsum²`` with radsum the
radius sum less EPSILON, acclient.c:358508): whenever the reject says "apart", every pair is.
"""

from __future__ import annotations

import math
import random

import pytest

from acphys.body.reports import REACH_MARGIN
from acphys.constants import EPSILON
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import get_block_offset, outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.transition.sphere_path import SpherePath
from acphys.world.world import World
from support import place


def _exact_apart(body, path: SpherePath) -> bool:
    scale = body.scale
    block = get_block_offset(path.check_pos.objcell_id, body.position.objcell_id)
    for sphere in body.part_array.get_sphere():
        center = body.position.frame.localtoglobal(sphere.center * scale) + block
        for moving in path.global_sphere:
            radsum = sphere.radius * scale + moving.radius - EPSILON
            if (moving.center - center).length_squared() <= radsum * radsum:
                return False
    return True


def _path(cell_id: int, centers: list[V], radius: float) -> SpherePath:
    path = SpherePath()
    path.check_pos = Position(cell_id, Frame())
    path.global_sphere = [Sphere(center, radius) for center in centers]
    return path


@pytest.mark.parametrize("seed", range(5))
def test_the_reject_only_skips_what_the_exact_test_finds_apart(seed: int) -> None:
    rng = random.Random(seed)
    world = World()
    rejected = kept = 0
    for trial in range(400):
        body = place(world, name=f"b{trial}", origin=(100.0, 100.0, 50.0), heading=rng.uniform(0.0, 360.0))
        body.set_scale_static(rng.choice((1.0, 0.5, 2.0)))
        sphere = body.part_array.get_sphere()[rng.randrange(2)]
        target = body.position.frame.localtoglobal(sphere.center * body.scale)
        # A moving sphere at a random direction, about touching distance from one of the body's spheres.
        radius = rng.uniform(0.05, 1.0)
        theta, phi = rng.uniform(0.0, 2 * math.pi), rng.uniform(-1.0, 1.0)
        direction = V(
            math.cos(theta) * math.sqrt(1 - phi * phi), math.sin(theta) * math.sqrt(1 - phi * phi), phi
        )
        gap = rng.choice(
            (rng.uniform(-0.01, 0.01), rng.uniform(-1.0, 3.0), REACH_MARGIN * rng.uniform(0.5, 1.5))
        )
        distance = max(0.0, sphere.radius * body.scale + radius + gap)
        center = target + direction * distance
        check_cell = body.position.objcell_id
        if trial % 3 == 0:
            # The check position in the landblock to the west: the same point is 192 m further east there.
            check_cell = outdoor_cell_id(0xA8B4, V(191.0, 100.0, 50.0))
            center = center + get_block_offset(body.position.objcell_id, check_cell) * -1.0
        path = _path(check_cell, [center, center + V(0.0, 0.0, 0.875)], radius)
        if body.out_of_reach(path):
            rejected += 1
            assert _exact_apart(body, path)
        else:
            kept += 1
        world.remove_object(body)
    assert rejected > 50 and kept > 50


def test_touching_spheres_are_never_rejected() -> None:
    world = World()
    body = place(world, origin=(100.0, 100.0, 50.0))
    # Sphere 0 is at z 50.475 with r 0.48; a sphere of r 0.5 centred 0.98 m east touches it.
    path = _path(body.position.objcell_id, [V(100.98, 100.0, 50.475)], 0.5)
    assert not body.out_of_reach(path)
    path = _path(body.position.objcell_id, [V(100.98 + 2 * REACH_MARGIN, 100.0, 50.475)], 0.5)
    assert body.out_of_reach(path)


def test_a_nan_centre_is_never_rejected() -> None:
    world = World()
    body = place(world, origin=(100.0, 100.0, 50.0))
    path = _path(body.position.objcell_id, [V(math.nan, 100.0, 50.0)], 0.5)
    assert not body.out_of_reach(path)
