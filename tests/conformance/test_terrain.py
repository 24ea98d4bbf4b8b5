"""Landblock terrain: vertices, cut directions, height/normal, terrain types and water.

Expected values are derived by hand from the decompiled ``CLandBlockStruct`` / ``CLandCell`` /
``CLandBlock`` code (acclient.c lines cited), or computed independently in this file.
"""

from __future__ import annotations

import ctypes
import math
import random

import pytest

from acphys.geometry.polygon import Polygon, SidesType
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.world.terrain import (
    ENTIRELY_WATER_DEPTH,
    TERRAIN_SURF_CHAR,
    LandBlockStruct,
    SurfChar,
    WaterType,
    cut_from_hash,
    set_height_table,
    split_hash,
    sw_to_ne_cut,
    terrain_type,
)

HOLTBURG = 0xA9B4FFFF
#: A synthetic height table (not retail's): strictly inside [0, 800], not monotonic on purpose.
TABLE = [float((37 * i) % 256) * 3.0 + 0.25 for i in range(256)]
WATER_WORD = 16 << 2  # terrain type 16, the first water type (acclient_data.h:2356)
GRASS_WORD = 1 << 2


def _rng_heights(rng: random.Random) -> list[int]:
    return [rng.randrange(256) for _ in range(81)]


def _block(
    block_id: int = HOLTBURG,
    height: list[int] | None = None,
    terrain: list[int] | None = None,
    table: list[float] | None = None,
) -> LandBlockStruct:
    return LandBlockStruct(
        block_id,
        height if height is not None else list(range(81)),
        terrain if terrain is not None else [GRASS_WORD] * 81,
        table if table is not None else TABLE,
    )


def _c_split(x: int, y: int) -> bool:
    """Independent 32-bit cut test: the product expanded, each step wrapped by ctypes int32;
    a negative int32 means the top bit is set."""
    acc = ctypes.c_int32(x * y)
    acc = ctypes.c_int32(acc.value * 214614067)
    acc = ctypes.c_int32(acc.value + ctypes.c_int32(1813693831 * y).value)
    acc = ctypes.c_int32(acc.value - ctypes.c_int32(1109124029 * x).value)
    acc = ctypes.c_int32(acc.value - 1369149221)
    return acc.value < 0


# --- the split hash -----------------------------------------------------------------------


def test_split_hash_known_cells() -> None:
    # acclient.c:354046 h = y*(214614067x + 1813693831) - 1109124029x - 1369149221 (mod 2^32)
    # (0,0): -1369149221 + 2^32 = 2925818075 >= 2^31 -> SW-NE cut (acclient.c:354050-354052)
    assert split_hash(0, 0) == 2925818075
    assert sw_to_ne_cut(0, 0) is True
    # (1,0): -1109124029 - 1369149221 = -2478273250 + 2^32 = 1816694046 < 2^31 -> SE-NW (354068)
    assert split_hash(1, 0) == 1816694046
    assert sw_to_ne_cut(1, 0) is False
    # (0,1): 1813693831 - 1369149221 = 444544610
    assert split_hash(0, 1) == 444544610
    assert sw_to_ne_cut(0, 1) is False
    # (1,1): 214614067 + 1813693831 - 1109124029 - 1369149221 = -449965352 + 2^32 = 3845001944
    assert split_hash(1, 1) == 3845001944
    assert sw_to_ne_cut(1, 1) is True
    # Holtburg's SW cell (1352, 1440): 1440*(214614067*1352 + 1813693831) - 1109124029*1352
    # - 1369149221 = 418938649041171 = 97541*2^32 + 3244022035
    assert split_hash(1352, 1440) == 3244022035
    assert sw_to_ne_cut(1352, 1440) is True


def test_split_property_against_independent_int32() -> None:
    rng = random.Random(4186)
    points = [(rng.randrange(2048), rng.randrange(2048)) for _ in range(4000)]
    points += [(0, 0), (2047, 2047), (2039, 0), (0, 2039)]
    cuts = [sw_to_ne_cut(x, y) for x, y in points]
    assert cuts == [_c_split(x, y) for x, y in points]
    assert any(cuts) and not all(cuts)  # both directions exercised


def test_cut_threshold_is_the_top_bit_ace_diverges() -> None:
    # acclient.c:354050: (double)(u32)h * 2.3283064e-10 >= 0.5; the literal is float32 2^-32
    assert f32(2.3283064e-10) == 2.0**-32
    assert cut_from_hash(0x7FFFFFFF) is False
    assert cut_from_hash(0x80000000) is True
    # ACE tests h * 2.3283064e-10 < 0.5 with a float64 literal just below 2^-32: it leaves
    # 0x80000000 uncut. Retail (float32 literal) cuts it.
    assert 0x80000000 * 2.3283064e-10 < 0.5


def test_block_cut_flags_use_global_cell_coordinates() -> None:
    for block_id in (HOLTBURG, 0x0000FFFF, 0x7F3AFFFF, 0xFEFEFFFF):
        lb = _block(block_id)
        bx, by = (block_id >> 24) * 8, ((block_id >> 16) & 0xFF) * 8  # acclient.c:354033-354034
        for cx in range(8):
            for cy in range(8):
                assert lb.sw_to_ne_cut[8 * cx + cy] is _c_split(bx + cx, by + cy)


# --- vertices and triangles ---------------------------------------------------------------


def test_vertices_index_x_times_9_plus_y() -> None:
    lb = _block()
    for x in range(9):
        for y in range(9):
            v = lb.vertex(x, y)
            # acclient.c:354653 z = Land_Height_Table[height[v4]], v4 += 1 per y (354662), 9 per x (354664)
            assert (v.x, v.y, v.z) == (24.0 * x, 24.0 * y, TABLE[9 * x + y])


def test_triangle_corners_for_both_cuts() -> None:
    lb = _block()
    bx, by = 0xA9 * 8, 0xB4 * 8
    seen = set()
    for cx in range(8):
        for cy in range(8):
            sw, se = lb.vertex(cx, cy), lb.vertex(cx + 1, cy)
            nw, ne = lb.vertex(cx, cy + 1), lb.vertex(cx + 1, cy + 1)
            first, second = lb.cell_polygons(cx, cy)
            cut = _c_split(bx + cx, by + cy)
            seen.add(cut)
            # acclient.c:354054 cut: (SW, SE, NE), (SW, NE, NW); 354070/354080: (SW, SE, NW), (NE, NW, SE)
            want = ((sw, se, ne), (sw, ne, nw)) if cut else ((sw, se, nw), (ne, nw, se))
            for poly, corners in zip((first, second), want, strict=True):
                assert isinstance(poly, Polygon) and poly.sides_type == SidesType.SINGLE  # 353211
                assert all(v.exactly_equals(c) for v, c in zip(poly.vertices, corners, strict=True))
                assert poly.plane.N.z > 0.0  # counter-clockwise from above
    assert seen == {True, False}


# --- height and normal against brute force -------------------------------------------------


def _brute(block_id: int, height: list[int], table: list[float], x: float, y: float) -> tuple[float, Vector3]:
    """Height and normal from the raw record: pick the triangle by the local (u, v) in the cell
    and interpolate on it."""
    cx, cy = int(x // 24), int(y // 24)
    u, v = x / 24.0 - cx, y / 24.0 - cy

    def h(ix: int, iy: int) -> float:
        return table[height[9 * ix + iy]]

    hsw, hse, hnw, hne = h(cx, cy), h(cx + 1, cy), h(cx, cy + 1), h(cx + 1, cy + 1)
    if _c_split((block_id >> 24) * 8 + cx, ((block_id >> 16) & 0xFF) * 8 + cy):
        if u >= v:  # (SW, SE, NE)
            du, dv = hse - hsw, hne - hse
        else:  # (SW, NE, NW)
            du, dv = hne - hnw, hnw - hsw
        z = hsw + u * du + v * dv
    elif u + v <= 1.0:  # (SW, SE, NW)
        du, dv = hse - hsw, hnw - hsw
        z = hsw + u * du + v * dv
    else:  # (NE, NW, SE)
        du, dv = hne - hnw, hne - hse
        z = hne - (1.0 - u) * du - (1.0 - v) * dv
    n = Vector3(-du / 24.0, -dv / 24.0, 1.0)
    return z, n * (1.0 / n.length())


#: The terrain planes are float32 (``make_plane`` stores ``N`` and ``d``, acclient.c:359627), so a
#: height read back from a plane is off by a few float32 ulps of the heights involved (at most
#: 800 m), amplified by the slope (divided by ``N.z``); the unit normal by an ulp or two of 1.
#: A wrong triangle or a wrong interpolation is off by far more.
_F32_HEIGHT_SPAN = 1000.0 * 2.0**-22
_F32_NORMAL_TOL = 4 * 2.0**-24


def test_height_and_normal_match_brute_force() -> None:
    rng = random.Random(11)
    seen_cuts = set()
    for block_id in (HOLTBURG, 0x0000FFFF, 0x12EFFFFF, 0xFE01FFFF, 0x5A5AFFFF):
        height = _rng_heights(rng)
        table = sorted(rng.uniform(0.0, 800.0) for _ in range(256))
        lb = LandBlockStruct(block_id, height, [GRASS_WORD] * 81, table)
        # the table is float (LandDefs::set_height_table, acclient.c:467321): the brute force
        # works from the float32 heights and the float32 query point
        table32 = [f32(h) for h in table]
        seen_cuts.update(lb.sw_to_ne_cut)
        for _ in range(300):
            x, y = rng.uniform(0.0, 191.999), rng.uniform(0.0, 191.999)
            p = Vector3(x, y, 1234.0)
            z, n = _brute(block_id, height, table32, p.x, p.y)
            assert lb.get_height(p) == pytest.approx(z, rel=0.0, abs=_F32_HEIGHT_SPAN / n.z)
            got = lb.get_normal(p)
            assert (got.x, got.y, got.z) == pytest.approx((n.x, n.y, n.z), rel=0.0, abs=_F32_NORMAL_TOL)
            assert p.z == 1234.0  # the query point is not moved
    assert seen_cuts == {True, False}


def test_height_at_vertices_and_flat_block() -> None:
    lb = _block()
    for x, y in ((0, 0), (3, 5), (8, 8), (7, 1)):
        if x < 8 and y < 8:
            p = Vector3(24.0 * x, 24.0 * y, 0.0)
            # float32 planes: see _F32_HEIGHT_SPAN
            tol = _F32_HEIGHT_SPAN / lb.get_normal(p).z
            assert lb.get_height(p) == pytest.approx(TABLE[9 * x + y], rel=0.0, abs=tol)
    flat = _block(height=[7] * 81)
    assert flat.get_height(Vector3(100.3, 17.9, 0.0)) == pytest.approx(TABLE[7])
    assert flat.get_normal(Vector3(100.3, 17.9, 0.0)).exactly_equals(Vector3(0.0, 0.0, 1.0))


def test_find_terrain_poly_diagonal_takes_first_triangle() -> None:
    lb = _block()
    # Holtburg (0,0) is cut SW-NE (hash 3244022035 above); its diagonal is u == v.
    first, second = lb.cell_polygons(0, 0)
    # acclient.c:354869 polygons[0] is tested first; an on-edge point is inside (value 0 is not > 0)
    assert lb.find_terrain_poly(Vector3(10.0, 10.0, 0.0)) is first
    assert lb.find_terrain_poly(Vector3(10.0, 3.0, 0.0)) is first
    assert lb.find_terrain_poly(Vector3(3.0, 10.0, 0.0)) is second
    # The cell named by the caller is searched, not the one under the point (acclient.c:354873)
    assert lb.find_terrain_poly(Vector3(30.0, 3.0, 0.0), cell_id=0xA9B40001) is None
    assert lb.find_terrain_poly(Vector3(30.0, 3.0, 0.0), cell_id=0xA9B40009) is lb.find_terrain_poly(
        Vector3(30.0, 3.0, 0.0)
    )


# --- terrain types and water ------------------------------------------------------------


def test_terrain_surf_char_table() -> None:
    # acclient_data.h:2356: types 16..20 WATER, the rest SOLID
    assert [t for t in range(32) if TERRAIN_SURF_CHAR[t] == SurfChar.WATER] == [16, 17, 18, 19, 20]
    # bits 2..6 only (acclient.c:353629): road bits 0-1 and scenery bits 11-15 are ignored
    assert terrain_type(0xF800 | (20 << 2) | 3) == 20
    assert terrain_type(21 << 2) == 21


def _terrain_with_water(vertices: set[tuple[int, int]]) -> list[int]:
    return [WATER_WORD | 2 if (i // 9, i % 9) in vertices else GRASS_WORD for i in range(81)]


def test_calc_water_cell_and_block_types() -> None:
    dry = _block()
    assert dry.water_type == WaterType.NOT_WATER
    assert set(dry.cell_water_types) == {WaterType.NOT_WATER}

    # Water at the four corners of cell (2, 5) and one corner (the SW) of cell (6, 0).
    lb = _block(terrain=_terrain_with_water({(2, 5), (3, 5), (2, 6), (3, 6), (6, 0)}))
    # acclient.c:353630/353632: any water corner -> has_water; any solid corner -> not all water
    assert lb.calc_cell_water(2, 5) == (True, True)
    assert lb.calc_cell_water(6, 0) == (True, False)
    assert lb.calc_cell_water(0, 0) == (False, False)
    assert lb.cell_water_type(0xA9B40000 | (1 + 8 * 2 + 5)) == WaterType.ENTIRELY_WATER  # 354592
    assert lb.cell_water_type(0xA9B40000 | (1 + 8 * 6 + 0)) == WaterType.PARTIALLY_WATER
    # (5, 0) has (6, 0) as its SE corner; (2, 4) shares the (2,5)-(3,5) edge
    assert lb.cell_water_type(0xA9B40000 | (1 + 8 * 5)) == WaterType.PARTIALLY_WATER
    assert lb.cell_water_type(0xA9B40000 | (1 + 8 * 2 + 4)) == WaterType.PARTIALLY_WATER
    assert lb.cell_water_type(0xA9B40000 | (1 + 8 * 7 + 7)) == WaterType.NOT_WATER
    assert lb.water_type == WaterType.PARTIALLY_WATER  # acclient.c:354610 (v3 == 0) + 1

    sea = _block(terrain=[(18 << 2)] * 81)
    assert sea.water_type == WaterType.ENTIRELY_WATER  # every cell all water: (v3 != 0) + 1 = 2
    assert set(sea.cell_water_types) == {WaterType.ENTIRELY_WATER}


def test_water_depth_none_partial_full() -> None:
    lb = _block(terrain=_terrain_with_water({(2, 5), (3, 5), (2, 6), (3, 6), (6, 0)}))
    # NOT_WATER cell: 0.0 (acclient.c:347241)
    assert lb.get_water_depth(0xA9B40001, Vector3(5.0, 5.0, 0.0)) == 0.0
    # ENTIRELY_WATER cell: 0.89999998 (acclient.c:347247)
    full = 0xA9B40000 | (1 + 8 * 2 + 5)
    assert lb.get_water_depth(full, Vector3(60.0, 130.0, 0.0)) == ENTIRELY_WATER_DEPTH == f32(0.9)
    # PARTIALLY cell (6, 0): nearest corner decides (acclient.c:353679-353707)
    part = 0xA9B40000 | (1 + 8 * 6)
    assert lb.get_water_depth(part, Vector3(145.0, 3.0, 0.0)) == f32(0.45)  # SW corner is water
    assert lb.get_water_depth(part, Vector3(160.0, 3.0, 0.0)) == f32(0.1)  # SE corner is solid
    assert lb.get_water_depth(part, Vector3(145.0, 20.0, 0.0)) == f32(0.1)  # NW corner is solid
    assert lb.calc_water_depth(part, Vector3(145.0, 3.0, 0.0)) == f32(0.44999999)


def test_centre_lines_take_west_and_south_ace_diverges() -> None:
    # Water only at the SW corner of cell (6, 0), whose centre is (156, 12).
    lb = _block(terrain=_terrain_with_water({(6, 0)}))
    part = 0xA9B40000 | (1 + 8 * 6)
    on_both = Vector3(156.0, 12.0, 0.0)
    # acclient.c:352030 (2x+1)*12 >= vc.x -> west; the y branch with c0|c3 (equal included) -> south
    assert lb.get_terrain(part, on_both) == 16
    assert lb.find_terrain(part, on_both) == SurfChar.WATER
    assert lb.calc_water_depth(part, on_both) == f32(0.45)
    # ACE: 156 % 24 = 12 >= 12 -> east; it would read vertex (7, 1) and answer 0.1.
    assert lb.calc_water_depth(part, Vector3(156.001, 12.0, 0.0)) == f32(0.1)
    assert lb.calc_water_depth(part, Vector3(156.0, 12.001, 0.0)) == f32(0.1)


def test_walkable_surface_type() -> None:
    lb = _block(terrain=_terrain_with_water({(0, 0)}))
    cell = 0xA9B40001
    own = lb.find_terrain_poly(Vector3(2.0, 1.0, 0.0))
    assert own is not None
    # acclient.c:355121: one of the cell's polygons -> find_terrain (nearest corner (0,0) is water)
    assert lb.walkable_surface_type(cell, own, Vector3(2.0, 1.0, 0.0)) == SurfChar.WATER
    assert lb.walkable_surface_type(cell, own, Vector3(20.0, 1.0, 0.0)) == SurfChar.SOLID
    # a polygon of another cell, or an equal copy, is not the cell's: SOLID (acclient.c:355134)
    other = lb.cell_polygons(1, 0)[0]
    assert lb.walkable_surface_type(cell, other, Vector3(2.0, 1.0, 0.0)) == SurfChar.SOLID
    twin = Polygon(own.vertices)
    assert lb.walkable_surface_type(cell, twin, Vector3(2.0, 1.0, 0.0)) == SurfChar.SOLID


# --- bad input ----------------------------------------------------------------------------


def test_height_table_validation() -> None:
    # acclient.c:467329: each entry must satisfy v >= 0 and 1000 - 200 >= v; 256 entries (467334)
    assert set_height_table([0.0] * 255 + [800.0])[-1] == 800.0
    with pytest.raises(ValueError, match="256 entries, got 255"):
        set_height_table([0.0] * 255)
    with pytest.raises(ValueError, match="entry 3"):
        set_height_table([0.0] * 3 + [math.nan] + [0.0] * 252)
    with pytest.raises(ValueError, match="entry 255"):
        set_height_table([0.0] * 255 + [800.5])
    with pytest.raises(ValueError, match="entry 0"):
        set_height_table([-0.1] + [0.0] * 255)
    with pytest.raises(ValueError, match="not a number"):
        set_height_table(["1"] + [0.0] * 255)
    with pytest.raises(ValueError, match="height table"):
        _block(table=TABLE[:-1])


def test_record_validation() -> None:
    with pytest.raises(ValueError, match="81 height bytes, got 80"):
        _block(height=list(range(80)))
    with pytest.raises(ValueError, match=r"height bytes\[4\] = 256"):
        _block(height=[0, 0, 0, 0, 256] + [0] * 76)
    with pytest.raises(ValueError, match=r"height bytes\[0\] = -1"):
        _block(height=[-1] + [0] * 80)
    with pytest.raises(ValueError, match=r"height bytes\[1\] = 2.0"):
        _block(height=[0, 2.0] + [0] * 79)
    with pytest.raises(ValueError, match="81 terrain words, got 82"):
        _block(terrain=[0] * 82)
    with pytest.raises(ValueError, match=r"terrain words\[80\] = 65536"):
        _block(terrain=[0] * 80 + [0x10000])
    with pytest.raises(ValueError, match="block_id"):
        _block(block_id=0)
    assert _block(height=bytes(81)).vertex(8, 8).z == TABLE[0]


def test_query_validation() -> None:
    lb = _block()
    with pytest.raises(ValueError, match="finite"):
        lb.get_height(Vector3(math.nan, 5.0, 0.0))
    with pytest.raises(ValueError, match="outside the 192-m landblock"):
        lb.get_height(Vector3(192.0, 5.0, 0.0))
    with pytest.raises(ValueError, match="outside the 192-m landblock"):
        lb.get_normal(Vector3(-0.001, 5.0, 0.0))
    for bad in (0xA9B40000, 0xA9B40041, 0xA9B40100, 0xA9B4FFFF):
        with pytest.raises(ValueError, match="not a valid outdoor land cell"):
            lb.calc_water_depth(bad, Vector3(1.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="finite"):
        lb.get_terrain(0xA9B40001, Vector3(1.0, math.inf, 0.0))
    with pytest.raises(ValueError, match="9x9"):
        lb.vertex(9, 0)
    with pytest.raises(ValueError, match="8x8"):
        lb.cell_polygons(0, 8)
