"""acphys.dat: DAT files built here from the documented layout (07-dat-resources.md sections 1-2,
acclient.h), read back through the container and the record parsers.

The writer (``tests/dat_support.py``) is independent of the reader: it lays blocks, nodes and
records out from the layout description, so a reader that agreed with a wrong writer by
construction is not possible.
"""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

from acphys.cli import main
from acphys.dat import DatError, DatFile, unpack_landblock, unpack_region, unpack_setup
from dat_support import (
    BLOCK,
    LANDBLOCK_ID,
    REGION_ID,
    SETUP_ID,
    Writer,
    f32,
    height_table,
    landblock_record,
    region_record,
    setup_record,
    simple_dat,
)

# --- container ---------------------------------------------------------------------------------


def test_header_and_lookup(tmp_path: Path) -> None:
    with DatFile(simple_dat(tmp_path)) as dat:
        assert dat.header.magic == 0x5442 and dat.header.block_size == BLOCK
        assert dat.header.data_set_name == "portal"
        assert dat.header.master_map_id == 0x25000000 and dat.header.id_vnum == 982
        assert list(dat.ids()) == [SETUP_ID, REGION_ID]
        entry = dat.entry(SETUP_ID)
        # ver_ is bits 16-31 of the bitfield, comp_ bit 0 (acclient.c:654068-654074 per the doc)
        assert (entry.version, entry.compressed, entry.iteration) == (2, False, 7)
        assert dat.read(SETUP_ID) == setup_record()
        assert dat.lookup(0x02000002) is None


def test_multi_block_record_in_a_scattered_chain(tmp_path: Path) -> None:
    """A 1,300-byte record over six 252-byte payloads, laid out backwards; the node spans 7 blocks."""
    data = bytes(range(256)) * 5 + b"tail"
    writer = Writer()
    offset = writer.store(data, reverse=True)
    root = writer.store(Writer.node([0], [(0, 0x0A000001, offset, len(data), 0, 0)]))
    with DatFile(writer.write(tmp_path / "a.dat", root)) as dat:
        assert dat.read(0x0A000001) == data


def test_btree_with_three_nodes(tmp_path: Path) -> None:
    """A root with one entry and two leaves: lookups descend left and right (BTree::Search)."""
    writer = Writer()
    ids = [0x01000000 + i for i in range(0, 200, 2)]
    entries = [writer.entry(i, struct.pack("<I", i) * 3) for i in ids]
    left = writer.store(Writer.node([0], entries[:50]))
    right = writer.store(Writer.node([0], entries[51:]))
    root = writer.store(Writer.node([left, right], [entries[50]]), reverse=True)
    with DatFile(writer.write(tmp_path / "tree.dat", root)) as dat:
        assert list(dat.ids()) == ids
        for object_id in (ids[0], ids[49], ids[50], ids[51], ids[-1]):
            assert dat.read(object_id) == struct.pack("<I", object_id) * 3
        assert dat.lookup(ids[10] + 1) is None
        assert dat.lookup(ids[70] + 1) is None
        assert dat.lookup(0xFFFFFFFF) is None


def test_compressed_record(tmp_path: Path) -> None:
    with DatFile(simple_dat(tmp_path, compress=True)) as dat:
        assert dat.entry(SETUP_ID).compressed
        assert dat.read(SETUP_ID) == setup_record()


def _expect(path: Path, match: str, object_id: int = SETUP_ID) -> None:
    with pytest.raises(DatError, match=match) as caught, DatFile(path) as dat:
        dat.read(object_id)
    assert str(path) in str(caught.value)


def test_bad_magic(tmp_path: Path) -> None:
    writer = Writer()
    root = writer.store(Writer.node([0], []))
    _expect(writer.write(tmp_path / "m.dat", root, magic=0x4254), r"at offset 0x140: bad magic 0x4254")


def test_truncated_files(tmp_path: Path) -> None:
    short = tmp_path / "short.dat"
    short.write_bytes(b"\0" * 300)
    _expect(short, "too short for the header")
    path = simple_dat(tmp_path)
    data = path.read_bytes()
    setup_offset = 1024  # the first record stored
    path.write_bytes(data[: setup_offset + 100])
    _expect(path, "file truncated")


def test_chain_errors(tmp_path: Path) -> None:
    """Load_Data fails on a free block, a chain longer or shorter than the record; a loop is caught."""
    data = b"x" * 600  # three blocks: first, first + BLOCK, first + 2 * BLOCK
    for name, block, link, match in (
        ("loop", 1, 0, "loop in the block chain: block 0x400 comes round again"),
        ("free", 1, 2 | 0x80000000, "reaches a free block after block 0x500"),
        ("long", 2, 1, "continues past the 600 bytes it holds"),
        ("short", 0, None, "ends after 252 of 600 bytes"),
    ):
        writer = Writer()
        first = writer.store(data)
        root = writer.store(Writer.node([0], [(0, SETUP_ID, first, len(data), 0, 0)]))
        path = writer.write(tmp_path / f"{name}.dat", root)
        image = bytearray(path.read_bytes())
        target = 0 if link is None else first + (link & 3) * BLOCK | (link & 0x80000000)
        struct.pack_into("<I", image, first + block * BLOCK, target)
        path.write_bytes(bytes(image))
        _expect(path, match)


def test_missing_id(tmp_path: Path) -> None:
    _expect(simple_dat(tmp_path), "no record 0x02000099", 0x02000099)


# --- records -----------------------------------------------------------------------------------


def test_setup_record() -> None:
    record = unpack_setup(setup_record())
    assert record.did == SETUP_ID and record.parts == [0x01000001, 0x01000002]
    assert record.parent_index == [0xFFFFFFFF, 0] and record.default_scale[1].x == 0.5
    assert record.holding_locations[2].part_id == 1 and record.holding_locations[2].frame.origin.z == 1.0
    assert list(record.placement_frames) == [0x65] and len(record.placement_frames[0x65]) == 2
    assert record.lights[3].color == 0xFFFFEECC and record.lights[3].falloff == 5.0
    assert record.default_mtable_id == 0x09000001 and record.default_phstable_id == 0x34000001
    # CSetup::UnPack reads height, radius, then step_up_height before step_down_height
    # (acclient.c:335520; the garbled PackObj-relative names map to acclient.h:31119 offsets)
    setup = record.to_setup()
    assert (setup.step_up_height, setup.step_down_height) == (f32(0.6), f32(0.4))
    spheres = [(s.center.z, s.radius) for s in setup.spheres]
    assert spheres == [(f32(0.475), f32(0.48)), (f32(1.35), f32(0.48))]
    assert (setup.height, setup.radius) == (f32(1.83), f32(0.48))
    assert setup.sorting_sphere.radius == f32(0.9525) and setup.sorting_sphere.center.z == f32(0.9125)
    assert setup.cylspheres[0].height == 2.0 and setup.cylspheres[0].low_pt.y == f32(0.2)
    assert setup.allow_free_heading  # flag bit 2
    assert not unpack_setup(setup_record(flags=0)).to_setup().allow_free_heading


def test_setup_record_errors() -> None:
    with pytest.raises(DatError, match=r"setup 0x02000001: record truncated at byte"):
        unpack_setup(setup_record()[:-3])
    with pytest.raises(DatError, match="placement frame 101 has 1 animation hooks"):
        unpack_setup(setup_record(hooks=1))
    huge = setup_record()[:8] + struct.pack("<I", 0x40000000) + setup_record()[12:]
    with pytest.raises(DatError, match="part count 1073741824 at byte 8 overruns"):
        unpack_setup(huge)


def test_region_height_table() -> None:
    record = unpack_region(region_record())
    assert record.name == "Dereth!" and record.version == 3 and record.region_number == 1
    assert record.height_table == tuple(height_table())
    assert record.land_defs_words[0] == 255


def test_region_errors() -> None:
    # CRegionDesc::UnPack refuses any version but 3 (acclient.c:299775)
    with pytest.raises(DatError, match="version 4 is newer"):
        unpack_region(region_record(version=4))
    with pytest.raises(DatError, match="version 2 is older"):
        unpack_region(region_record(version=2))
    # set_height_table rejects entries outside [0, 1000 - 200] (acclient.c:467321)
    bad = height_table()
    bad[17] = 800.5
    with pytest.raises(DatError, match="entry 17"):
        unpack_region(region_record(table=bad))


def test_landblock_record_to_terrain() -> None:
    record = unpack_landblock(landblock_record())
    assert len(landblock_record()) == 252  # DID + lbi_exists + 81*2 + 81 + 1 pad
    assert record.lbi_exists == 1 and record.terrain[5] == 5 << 2 and record.height[80] == (80 * 3) % 256
    terrain = record.to_struct(height_table())
    # vertex (x, y) is record index 9x + y; its z is the height table entry of its byte
    assert terrain.vertex(2, 3).z == pytest.approx(f32((21 * 3) * 2.5))
    assert terrain.vertex(8, 8).z == pytest.approx(f32(((80 * 3) % 256) * 2.5))
    with pytest.raises(DatError, match="ends in 0xFFFF"):
        unpack_landblock(struct.pack("<I", 0xA9B40001) + landblock_record()[4:])


def test_records_through_the_container(tmp_path: Path) -> None:
    records = {SETUP_ID: setup_record(), REGION_ID: region_record(), LANDBLOCK_ID: landblock_record()}
    path = simple_dat(tmp_path, records)
    with DatFile(path) as dat:
        table = unpack_region(dat.read(REGION_ID)).height_table
        block = unpack_landblock(dat.read(LANDBLOCK_ID)).to_struct(table)
        assert block.block_id == LANDBLOCK_ID
        assert unpack_setup(dat.read(SETUP_ID)).to_setup().step_up_height == f32(0.6)


# --- command line ------------------------------------------------------------------------------


def invoke(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_info_and_list(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = str(simple_dat(tmp_path))
    code, out, _ = invoke(["dat", "info", path], capsys)
    assert code == 0 and "data set: portal" in out and "records: 2" in out and "block size: 256" in out
    code, out, _ = invoke(["dat", "list", path, "--type", "0x02"], capsys)
    assert code == 0 and out.split() == ["0x02000001", str(len(setup_record()))]
    code, out, _ = invoke(["dat", "list", path], capsys)
    assert code == 0 and "0x13000000" in out


def test_cli_setup_and_heights(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = str(simple_dat(tmp_path))
    code, out, _ = invoke(["dat", "setup", path, "0x02000001"], capsys)
    assert code == 0
    assert "sphere: center 0 0 0.475, radius 0.48" in out and "sphere: center 0 0 1.35, radius 0.48" in out
    assert "step up 0.6, step down 0.4" in out and "motion table 0x09000001" in out
    code, out, _ = invoke(["dat", "heights", path], capsys)
    lines = out.splitlines()
    assert code == 0 and len(lines) == 32
    assert lines[1].split()[:3] == ["8:", "20.00", "22.50"]


def test_cli_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = str(simple_dat(tmp_path))
    code, _, err = invoke(["dat", "setup", path, "0x02000002"], capsys)
    assert code == 2 and err.startswith("acphys: error:") and "no record 0x02000002" in err
    assert len(err.strip().splitlines()) == 1
    code, _, err = invoke(["dat", "list", path, "--type", "0x0200"], capsys)
    assert code == 2 and "one byte" in err
    code, _, err = invoke(["dat", "info", str(tmp_path / "none.dat")], capsys)
    assert code == 2 and "none.dat" in err
    bad = tmp_path / "bad.dat"
    bad.write_bytes(b"\0" * 2048)
    code, _, err = invoke(["dat", "heights", str(bad)], capsys)
    assert code == 2 and "bad magic" in err
