"""Plane and Ray: hand-derived from the retail decompilation (acclient.c lines cited)."""

from __future__ import annotations

import math

import pytest

from acphys.constants import EPSILON
from acphys.geometry.plane import Plane, Ray, Sidedness
from acphys.math.vector import Vector3


def test_from_point_sets_d_to_minus_n_dot_point() -> None:
    plane = Plane.from_point(Vector3(0.0, 0.6, 0.8), Vector3(1.0, 2.0, 3.0))
    assert plane.d == pytest.approx(-(1.2 + 2.4))  # acclient.c:358522 d = -(N·point)


def test_time_of_intersection_downward_ray() -> None:
    plane = Plane.horizontal(1.0)
    hit, time = plane.compute_time_of_intersection(Ray(Vector3(0.0, 0.0, 3.0), Vector3(0.0, 0.0, -1.0)))
    # acclient.c:359603 time = (N·pt + d) * (-1 / N·dir) = 2 * 1; 359605 hit when time >= 0
    assert hit is True
    assert time == 2.0


def test_time_of_intersection_behind_start_is_written_but_misses() -> None:
    plane = Plane.horizontal(1.0)
    hit, time = plane.compute_time_of_intersection(Ray(Vector3(0.0, 0.0, 3.0), Vector3(0.0, 0.0, 1.0)))
    assert hit is False  # acclient.c:359605 time -2 < 0
    assert time == -2.0  # acclient.c:359604 the time is stored before the sign test


def test_time_of_intersection_parallel_within_epsilon() -> None:
    plane = Plane.horizontal(0.0)
    # |N·dir| = 0.0001 < EPSILON: acclient.c:359601 no intersection, time untouched
    ray = Ray(Vector3(0, 0, 1), Vector3(1.0, 0.0, -0.0001))
    assert plane.compute_time_of_intersection(ray) == (False, None)
    # |N·dir| = 0.0003 >= EPSILON: accepted, time = 1 / 0.0003
    hit, time = plane.compute_time_of_intersection(Ray(Vector3(0, 0, 1), Vector3(1.0, 0.0, -0.0003)))
    assert hit is True
    assert time == pytest.approx(1.0 / 0.0003)


def test_snap_to_plane_removes_d_and_keeps_offset_in_plane() -> None:
    # 45 degree slope rising in +x: N = (-s, 0, s), d = 7 (d cancels, acclient.c:311532-311533)
    s = math.sqrt(0.5)
    plane = Plane(Vector3(-s, 0.0, s), 7.0)
    offset = Vector3(2.0, 5.0, 99.0)
    plane.snap_to_plane(offset)
    assert offset.z == pytest.approx(2.0)  # -(x·Nx + y·Ny)/Nz = 2s/s
    assert (offset.x, offset.y) == (2.0, 5.0)


def test_snap_to_plane_vertical_plane_untouched() -> None:
    plane = Plane(Vector3(1.0, 0.0, EPSILON), 0.0)  # |N.z| not > EPSILON: acclient.c:311529
    offset = Vector3(2.0, 5.0, 99.0)
    plane.snap_to_plane(offset)
    assert offset.z == 99.0


def test_set_height() -> None:
    s = math.sqrt(0.5)
    plane = Plane(Vector3(-s, 0.0, s), -s)  # z = x + 1
    vc = Vector3(3.0, 4.0, 0.0)
    assert plane.set_height(vc) is True
    assert vc.z == pytest.approx(4.0)  # acclient.c:351348 z = -(y·Ny + x·Nx + d)/Nz
    wall = Plane(Vector3(1.0, 0.0, EPSILON), 0.0)
    assert wall.set_height(vc) is False  # acclient.c:351342 |N.z| <= EPSILON


def test_which_side2_bands() -> None:
    plane = Plane.horizontal(0.0)
    # acclient.c:719922-719928: > eps positive, in [-eps, eps] in-plane, < -eps negative
    assert plane.which_side2(Vector3(0, 0, 0.001), 0.0, EPSILON) == Sidedness.POSITIVE
    assert plane.which_side2(Vector3(0, 0, 0.0001), 0.0, EPSILON) == Sidedness.IN_PLANE
    assert plane.which_side2(Vector3(0, 0, -0.0001), 0.0, EPSILON) == Sidedness.IN_PLANE
    assert plane.which_side2(Vector3(0, 0, -0.001), 0.0, EPSILON) == Sidedness.NEGATIVE
    assert plane.which_side2(Vector3(0, 0, -0.001), 0.002, EPSILON) == Sidedness.POSITIVE  # bias added
