"""The world's cells: landblocks with terrain, the terrain-less empty world around them, env cells."""

from __future__ import annotations

import pytest

from acphys.math.vector import Vector3
from acphys.world.land_cell import LandCell
from acphys.world.world import World, flat_landblock


def test_a_flat_landblock_has_terrain_cells_at_its_height() -> None:
    world = World()
    world.set_flat_ground(0xA9B4, 50.0)
    cell = world.get_cell(0xA9B40025)
    assert isinstance(cell, LandCell)
    assert len(cell.polygons) == 2
    assert all(v.z == 50.0 for poly in cell.polygons for v in poly.vertices)
    assert world.ground_height(0xA9B40025, Vector3(100.0, 100.0, 0.0)) == 50.0
    assert world.ground_normal(0xA9B40025, Vector3(100.0, 100.0, 0.0)) == Vector3(0.0, 0.0, 1.0)
    # The same cell object every time: bodies and shadows live in it.
    assert world.get_cell(0xA9B40025) is cell


def test_outside_declared_landblocks_the_cells_exist_without_terrain() -> None:
    world = World()
    world.set_flat_ground(0xA9B4, 50.0)
    void = world.get_cell(0xAAB40001)
    assert isinstance(void, LandCell) and len(void.polygons) == 0
    assert world.get_cell(0xAAB40001) is void
    assert world.ground_height(0xAAB40001, Vector3(1.0, 1.0, 0.0)) is None
    # Off the map, a bad land cell index, or an env cell nobody added: no cell.
    assert world.get_cell(0xFFFF0001) is None
    assert world.get_cell(0xA9B40041) is None
    assert world.get_cell(0xA9B40100) is None


@pytest.mark.parametrize("height", [-0.5, 800.5, float("nan")])
def test_flat_ground_outside_the_retail_height_range_is_refused(height: float) -> None:
    with pytest.raises(ValueError, match="ground height must be in"):
        flat_landblock(0xA9B4, height)


def test_a_landblock_is_added_once() -> None:
    world = World()
    world.set_flat_ground(0xA9B4, 10.0)
    with pytest.raises(ValueError, match="already in the landscape"):
        world.set_flat_ground(0xA9B4, 20.0)
