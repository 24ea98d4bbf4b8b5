"""Unit tests for cell ids, the ``LandDefs`` conversions and ``Position::get_offset``.

Expected values are worked out by hand from the decompiled retail functions
cited beside each test (build 11.4186). Reminders used throughout:

* a cell id is ``0xXXYYnnnn``; an outdoor cell has ``nnnn = 1 + 8·cx + cy``;
* lcoord ``x = 8·XX + cx``, ``y = 8·YY + cy``; landblock 0xA9B4 has XX = 0xA9 = 169
  and YY = 0xB4 = 180, so its south-west cell is lcoord (1352, 1440);
* a land cell is 24 m, a landblock 8 cells = 192 m.
"""

from __future__ import annotations

import math

import pytest

from acphys.constants import EPSILON
from acphys.math.cell_id import (
    adjust_to_outside,
    blockid_to_lcoord,
    cell_of,
    format_cell_id,
    get_block_offset,
    get_outside_lcoord,
    gid_to_lcoord,
    inbound_valid_cellid,
    is_outdoor,
    landblock_of,
    lcoord_to_gid,
    outdoor_cell_id,
)
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32

TOL = 1e-12
C45 = math.cos(math.pi / 4)
S45 = math.sin(math.pi / 4)


def assert_vec(v, expected, tol: float = TOL) -> None:
    assert tuple(v) == pytest.approx(tuple(expected), abs=tol)


# -- lcoord_to_gid / gid_to_lcoord -----------------------------------------------------------


class TestLcoordGid:
    def test_lcoord_to_gid_hand_value(self):
        # LandDefs::lcoord_to_gid @ 0x004A19A0 (acclient.c:218181):
        #   (((y >> 3) | 32 * (x & ~7)) << 16) | ((y & 7) + 8 * (x & 7) + 1)
        # x = 0xA9·8 + 3 = 1355, y = 0xB4·8 + 5 = 1445:
        #   y >> 3 = 180 = 0xB4; 32·(1355 & ~7) = 32·1352 = 0xA900 → high word 0xA9B4;
        #   low = 5 + 8·3 + 1 = 30 = 0x1E  → 0xA9B4001E.
        assert lcoord_to_gid(0xA9 * 8 + 3, 0xB4 * 8 + 5) == 0xA9B4001E

    def test_lcoord_to_gid_corners(self):
        # Same line: (0, 0) → high 0, low 0 + 0 + 1 = 1; (2039, 2039): 2039 >> 3 = 254 = 0xFE,
        # 32·2032 = 0xFE00, low = 7 + 56 + 1 = 64 = 0x40.
        assert lcoord_to_gid(0, 0) == 0x00000001
        assert lcoord_to_gid(2039, 2039) == 0xFEFE0040

    @pytest.mark.parametrize(("x", "y"), [(-1, 0), (0, -1), (2040, 0), (0, 2040), (5000, 5000)])
    def test_lcoord_to_gid_outside_world(self, x, y):
        # Same line: x < 0 || y < 0 || x >= 2040 || y >= 2040 → 0.
        assert lcoord_to_gid(x, y) == 0

    def test_gid_to_lcoord_hand_value(self):
        # LandDefs::gid_to_lcoord @ 0x00497A90 (acclient.c:209520):
        #   x = ((id >> 21) & 0x7F8) + ((nnnn - 1) >> 3); y = 8·BYTE2(id) + ((nnnn - 1) & 7)
        # 0xA9B4001E: nnnn - 1 = 29 → x = 1352 + 3 = 1355, y = 1440 + 5 = 1445.
        assert gid_to_lcoord(0xA9B4001E) == (1355, 1445)
        # 0xA9B40001 (south-west) and 0xA9B40040 (north-east, 63 → cx = 7, cy = 7).
        assert gid_to_lcoord(0xA9B40001) == (1352, 1440)
        assert gid_to_lcoord(0xA9B40040) == (1359, 1447)

    @pytest.mark.parametrize("cell", [0xA9B40100, 0xA9B4FFFF, 0xA9B40041, 0xA9B40000, 0xFFB40001])
    def test_gid_to_lcoord_rejects_non_land_cells(self, cell):
        # Same line: needs LandDefs::inbound_valid_cellid and (unsigned short)id < 0x100; env cells
        # (0x100), the block id (0xFFFF), 0x41, 0 and the x = 2040 column all return 0 (None).
        assert gid_to_lcoord(cell) is None

    def test_round_trip_lcoord_gid_lcoord(self):
        # lcoord_to_gid (acclient.c:218181) and gid_to_lcoord (acclient.c:209520) are inverse on
        # [0, 2040)²: a grid with coprime strides plus the world's edges.
        xs = [*range(0, 2040, 7), 2039]
        ys = [*range(0, 2040, 13), 2039]
        for x in xs:
            for y in ys:
                assert gid_to_lcoord(lcoord_to_gid(x, y)) == (x, y), (x, y)

    @pytest.mark.parametrize("block", [0x0000, 0xA9B4, 0x7F01, 0xFEFE])
    def test_round_trip_gid_lcoord_gid(self, block):
        # Every land cell 1..0x40 of a block survives gid → lcoord → gid.
        for low in range(1, 0x41):
            cell = (block << 16) | low
            assert lcoord_to_gid(*gid_to_lcoord(cell)) == cell, hex(cell)


class TestInboundValidCellid:
    @pytest.mark.parametrize(
        ("cell", "valid"),
        [
            (0xA9B40000, False),  # nnnn = 0
            (0xA9B40001, True),  # first land cell
            (0xA9B40040, True),  # last land cell
            (0xA9B40041, False),  # between land and env cells
            (0xA9B400FF, False),
            (0xA9B40100, True),  # first env cell
            (0xA9B4FFFD, True),  # last env cell
            (0xA9B4FFFE, False),
            (0xA9B4FFFF, True),  # the landblock itself
            (0xFEFE0001, True),  # x = y = 2032 < 2040
            (0xFFB40001, False),  # x = (id >> 21) & 0x7F8 = 2040
            (0xA9FF0001, False),  # y = (id >> 13) & 0x7F8 = 2040
            (0xFFFFFFFF, False),
        ],
    )
    def test_edges(self, cell, valid):
        # LandDefs::inbound_valid_cellid @ 0x004979A0 (acclient.c:209467):
        #   nnnn in [1, 0x40] or [0x100, 0xFFFD] or == 0xFFFF, and
        #   (id >> 21) & 0x7F8 < 2040 and (id >> 13) & 0x7F8 < 2040.
        assert inbound_valid_cellid(cell) is valid


class TestBlockidToLcoord:
    def test_values(self):
        # LandDefs::blockid_to_lcoord @ 0x0043D680 (acclient.c:122259): 0 if block_id == 0;
        # x = (id >> 21) & 0x7F8, y = 8·(unsigned char)(id >> 16); valid if both < 2040.
        # The cell part is ignored: 0xA9B4001E → (1352, 1440).
        assert blockid_to_lcoord(0) is None
        assert blockid_to_lcoord(0xA9B40000) == (1352, 1440)
        assert blockid_to_lcoord(0xA9B4001E) == (1352, 1440)
        assert blockid_to_lcoord(0x0000FFFF) == (0, 0)  # non-zero id in block 0x0000
        assert blockid_to_lcoord(0xFFB40000) is None  # x = 2040
        assert blockid_to_lcoord(0xA9FF0000) is None  # y = 2040


class TestCellHelpers:
    def test_layout_helpers(self):
        # The id layout lcoord_to_gid (acclient.c:218181) builds: high word 0xXXYY, low word nnnn;
        # outdoor when nnnn < 0x100 (gid_to_lcoord, acclient.c:209520).
        assert landblock_of(0xA9B4001E) == 0xA9B4
        assert cell_of(0xA9B4, 0x1E) == 0xA9B4001E
        assert cell_of(0x1A9B4, 0x1001E) == 0xA9B4001E  # both masked to 16 bits
        assert is_outdoor(0xA9B40040)
        assert is_outdoor(0xA9B400FF)
        assert not is_outdoor(0xA9B40100)
        assert format_cell_id(0xA9B4001E) == "0xA9B4001E"
        assert format_cell_id(0x1E) == "0x0000001E"

    def test_outdoor_cell_id(self):
        # nnnn = 1 + 8·cx + cy as in lcoord_to_gid (acclient.c:218181), cx = ⌊x/24⌋, cy = ⌊y/24⌋.
        # (72.5, 143.9): cx = 3, cy = 5 → 1 + 24 + 5 = 30 = 0x1E.
        assert outdoor_cell_id(0xA9B4, Vector3(72.5, 143.9, 50.0)) == 0xA9B4001E
        assert outdoor_cell_id(0xA9B4, Vector3(0.0, 0.0, 0.0)) == 0xA9B40001
        assert outdoor_cell_id(0xA9B4, Vector3(191.99, 191.99, 0.0)) == 0xA9B40040
        # cx = 7 ends at x < 192; cy boundary at exactly 24 is cy = 1.
        assert outdoor_cell_id(0xA9B4, Vector3(0.0, 24.0, 0.0)) == 0xA9B40002
        assert outdoor_cell_id(0xA9B4, Vector3(24.0, 0.0, 0.0)) == 0xA9B40009

    @pytest.mark.parametrize("point", [(192.0, 0.0), (0.0, 192.0), (-0.1, 5.0), (5.0, -0.1)])
    def test_outdoor_cell_id_rejects_points_outside_the_block(self, point):
        # Not a retail function: points outside [0, 192)² belong to LandDefs::adjust_to_outside
        # (acclient.c:467433), so the helper refuses them.
        with pytest.raises(ValueError):
            outdoor_cell_id(0xA9B4, Vector3(point[0], point[1], 0.0))


# -- get_block_offset ------------------------------------------------------------------------


class TestGetBlockOffset:
    def test_same_block_is_zero(self):
        # LandDefs::get_block_offset @ 0x0043E630 (acclient.c:123109):
        # cell_from >> 16 == cell_to >> 16 → Legacy_Vector3_ZeroVector, whatever the cells are.
        assert get_block_offset(0xA9B40001, 0xA9B40001).exactly_equals(Vector3(0, 0, 0))
        assert get_block_offset(0xA9B40001, 0xA9B40150).exactly_equals(Vector3(0, 0, 0))

    @pytest.mark.parametrize(
        ("cell_from", "cell_to", "expected"),
        [
            (0xA9B40001, 0xAAB40001, (192.0, 0.0, 0.0)),  # Δx = 8 lcoords × 24
            (0xA9B40001, 0xA9B30040, (0.0, -192.0, 0.0)),  # one block south
            (0xA9B4001E, 0xA7B60100, (-384.0, 384.0, 0.0)),  # two west, two north, env cell
            (0xAAB40005, 0xA9B40005, (-192.0, 0.0, 0.0)),
        ],
    )
    def test_block_deltas(self, cell_from, cell_to, expected):
        # Same function: v5 = (from >> 21) & 0x7F8, v6 = 8·BYTE2(from), v7/v8 likewise for to;
        # result = ((int)(v7 - v5)·24, (int)(v8 - v6)·24, 0). 0xA9B4 → 0xAAB4: (1360 - 1352)·24 = 192.
        got = get_block_offset(cell_from, cell_to)
        assert got.exactly_equals(Vector3(*expected))

    def test_from_zero_uses_origin_block(self):
        # Same function: cell_from == 0 → v5 = v6 = 0, so the offset is to's absolute block corner:
        # 0xA9B4 → (1352·24, 1440·24) = (32448, 34560).
        assert get_block_offset(0, 0xA9B40001).exactly_equals(Vector3(32448.0, 34560.0, 0.0))

    def test_destination_zero_raises(self):
        # Same function: cell_to == 0 → v7 = v8 = cell_from (the raw id used as an lcoord), a
        # meaningless result; acphys raises ValueError instead (documented deviation).
        with pytest.raises(ValueError):
            get_block_offset(0xA9B40001, 0)
        # The same-block test runs first: block 0x0000 to id 0 is the zero vector, as in retail.
        assert get_block_offset(0x00000005, 0).exactly_equals(Vector3(0, 0, 0))


# -- get_outside_lcoord / adjust_to_outside --------------------------------------------------


class TestOutside:
    def test_get_outside_lcoord(self):
        # LandDefs::get_outside_lcoord @ 0x005A9B00 (acclient.c:467410): blockid_to_lcoord, then
        # x += ⌊loc.x/24⌋, y += ⌊loc.y/24⌋; valid if both in [0, 2040).
        # 0xA9B40001, (193.5, -0.5): x = 1352 + 8 = 1360, y = 1440 - 1 = 1439.
        assert get_outside_lcoord(0xA9B40001, Vector3(193.5, -0.5, 0.0)) == (1360, 1439)
        assert get_outside_lcoord(0xA9B40041, Vector3(10.0, 10.0, 0.0)) is None  # bad nnnn
        assert get_outside_lcoord(0x00000001, Vector3(-0.5, 10.0, 0.0)) is None  # x = -1

    def test_adjust_east_into_next_block(self):
        # LandDefs::adjust_to_outside @ 0x005A9BC0 (acclient.c:467433):
        # lcoord = (1352 + ⌊193.5/24⌋ = 1360, 1440 + ⌊10/24⌋ = 1440) → lcoord_to_gid:
        #   1360 >> 3 = 0xAA, 1440 >> 3 = 0xB4, low = 0 + 0 + 1 → 0xAAB40001;
        # loc.x -= ⌊193.5/192⌋·192 → 1.5 (flt_8EDE44 is the 192-m block length); y, z unchanged.
        loc = Vector3(193.5, 10.0, 4.0)
        assert adjust_to_outside(0xA9B40001, loc) == 0xAAB40001
        assert loc.exactly_equals(Vector3(1.5, 10.0, 4.0))

    def test_adjust_negative_y_goes_south(self):
        # Same function: y = 1440 + ⌊-3/24⌋ = 1439 → block 1439 >> 3 = 0xB3, cy = 1439 & 7 = 7;
        # x = 1352 → 0xA9, cx = 0; low = 7 + 0 + 1 = 8 → 0xA9B30008; loc.y = -3 - (-1)·192 = 189.
        loc = Vector3(10.0, -3.0, 0.0)
        assert adjust_to_outside(0xA9B40001, loc) == 0xA9B30008
        assert loc.exactly_equals(Vector3(10.0, 189.0, 0.0))

    def test_adjust_snaps_tiny_coordinates_to_zero(self):
        # Same function: if fabs(loc->x) < 0.00019999999, LODWORD(loc->x) = 0 (+0.0); same for y.
        # Without the snap ⌊-1e-4/24⌋ = -1 would move the point to block 0xA8B4.
        loc = Vector3(-1e-4, 1.5e-4, 2.0)
        assert adjust_to_outside(0xA9B40001, loc) == 0xA9B40001
        assert loc.exactly_equals(Vector3(0.0, 0.0, 2.0))
        assert math.copysign(1.0, loc.x) == 1.0

    def test_adjust_does_not_snap_at_or_beyond_epsilon(self):
        # Same function, strict <: |x| = 3e-4 is kept, so lcoord x = 1352 - 1 = 1351 → block 0xA8,
        # cx = 7; y = 1440 + ⌊5/24⌋ = 1440 → cy = 0; low = 0 + 56 + 1 = 0x39 → 0xA8B40039,
        # loc.x = f32(x + 192), x = f32(-3e-4): the moved x is stored into the float field
        # (acclient.c:467457).
        loc = Vector3(-3e-4, 5.0, 0.0)
        assert adjust_to_outside(0xA9B40001, loc) == 0xA8B40039
        assert loc.x == f32(f32(-3e-4) + 192.0)
        # x = -EPSILON exactly is not < EPSILON: not snapped either.
        loc = Vector3(-EPSILON, 5.0, 0.0)
        assert adjust_to_outside(0xA9B40001, loc) == 0xA8B40039

    def test_adjust_env_and_block_ids(self):
        # Same function accepts env cells and the 0xFFFF block id (same nnnn test as
        # inbound_valid_cellid). 0xA9B40100, (30, 50): cx = 1, cy = 2 → 2 + 8 + 1 = 11 = 0x0B.
        # 0xA9B4FFFF, (100, 100): cx = cy = 4 → 4 + 32 + 1 = 37 = 0x25.
        assert adjust_to_outside(0xA9B40100, Vector3(30.0, 50.0, 0.0)) == 0xA9B4000B
        assert adjust_to_outside(0xA9B4FFFF, Vector3(100.0, 100.0, 0.0)) == 0xA9B40025

    def test_adjust_off_world_returns_zero(self):
        # Same function: get_outside_lcoord fails → *cell_id = 0. Block 0x0000, x = -1 → lcoord -1;
        # block 0xFEFE at x = 200 → lcoord 2032 + 8 = 2040. The snap (none here) is all loc gets.
        loc = Vector3(-1.0, 5.0, 0.0)
        assert adjust_to_outside(0x00000001, loc) == 0
        assert loc.exactly_equals(Vector3(-1.0, 5.0, 0.0))
        assert adjust_to_outside(0xFEFE0040, Vector3(200.0, 5.0, 0.0)) == 0
        # An invalid nnnn (0x41) fails before anything else (goto LABEL_15).
        loc = Vector3(1e-4, 5.0, 0.0)
        assert adjust_to_outside(0xA9B40041, loc) == 0
        assert loc.exactly_equals(Vector3(1e-4, 5.0, 0.0))


# -- Position::get_offset --------------------------------------------------------------------


class TestPositionOffset:
    def test_get_offset_across_landblocks(self):
        # Position::get_offset @ 0x00509F60 (acclient.c:311690):
        #   get_block_offset(this, p) + p.origin - this.origin.
        # 0xA9B4 (190, 10, 5) → 0xAAB4 (2, 12, 7): (192, 0, 0) + (2, 12, 7) - (190, 10, 5) = (4, 2, 2).
        a = Position(0xA9B40001, Frame(Vector3(190.0, 10.0, 5.0)))
        b = Position(0xAAB40001, Frame(Vector3(2.0, 12.0, 7.0)))
        assert_vec(a.get_offset(b), (4.0, 2.0, 2.0))
        # Reverse: (-192, 0, 0) + (190, 10, 5) - (2, 12, 7) = (-4, -2, -2).
        assert_vec(b.get_offset(a), (-4.0, -2.0, -2.0))

    def test_get_offset_north_and_same_block(self):
        # Same function. 0xA9B3 (10, 189) → 0xA9B4 (10, 1): (0, 192, 0) + (10, 1, 0) - (10, 189, 0)
        # = (0, 4, 0). Same block, env cell: the plain origin difference.
        s = Position(0xA9B30008, Frame(Vector3(10.0, 189.0, 0.0)))
        n = Position(0xA9B40001, Frame(Vector3(10.0, 1.0, 0.0)))
        assert_vec(s.get_offset(n), (0.0, 4.0, 0.0))
        inside = Position(0xA9B40105, Frame(Vector3(15.0, 3.0, -2.0)))
        assert_vec(n.get_offset(inside), (5.0, 2.0, -2.0))

    def test_localtoglobal_offset(self):
        # Position::get_offset @ 0x0050D920 (acclient.c:314676):
        #   block offset + p.frame.m·v + p.origin - this.origin.
        # p at (2, 12, 7) in 0xAAB4 turned 90° about z (local x → +y); v = (1, 0, 0) → (0, 1, 0);
        # (192, 0, 0) + (2, 13, 7) - (190, 10, 5) = (4, 3, 2).
        a = Position(0xA9B40001, Frame(Vector3(190.0, 10.0, 5.0)))
        b = Position(0xAAB40001, Frame(Vector3(2.0, 12.0, 7.0), C45, 0.0, 0.0, S45))
        assert_vec(a.localtoglobal_offset(b, Vector3(1.0, 0.0, 0.0)), (4.0, 3.0, 2.0))
