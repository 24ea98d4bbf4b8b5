"""Damaged DAT data never crashes: every record kind the reader knows, truncated anywhere or with a
few bytes changed, either unpacks or raises a DatError; a damaged DAT file likewise, through
opening, listing and reading every record. (The records are the ones the unit tests build in the
documented layout, tests/dat_support.py.)"""

from __future__ import annotations

import random
import struct
import zlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from acphys.dat import DatError, DatFile
from acphys.dat.env_cell import unpack_env_cell, unpack_environment
from acphys.dat.gfxobj import unpack_gfxobj
from acphys.dat.landblock_info import unpack_landblock_info
from acphys.dat.motion import unpack_animation
from acphys.dat.records import unpack_landblock, unpack_region, unpack_setup
from dat_support import (
    BLOCK,
    Writer,
    animation_record,
    bld_portal_bytes,
    box_gfxobj_record,
    build_info_bytes,
    cell_portal_bytes,
    env_cell_record,
    environment_record,
    frame_bytes,
    hook_bytes,
    landblock_info_record,
    landblock_record,
    parts_setup_record,
    region_record,
    setup_record,
    simple_dat,
    stab_bytes,
)


def _records() -> dict[str, tuple[bytes, Callable[[bytes], Any]]]:
    portals = [bld_portal_bytes(0x1, 0x0105, -1, [0x0100, 0x0101, 0x0102])]
    return {
        "setup": (setup_record(), unpack_setup),
        "parts setup": (
            parts_setup_record(
                0x02000020,
                (0x01000010, 0x01000011),
                ((-3.0, 0.0, 0.0), (3.0, 0.0, 0.0)),
                ((1.0, 1.0, 1.0), (2.0, 2.0, 2.0)),
            ),
            unpack_setup,
        ),
        "region": (region_record(), unpack_region),
        "landblock": (landblock_record(), unpack_landblock),
        "gfxobj": (box_gfxobj_record((-1.0, -1.0, 0.0), (1.0, 1.0, 2.0)), unpack_gfxobj),
        "animation": (
            animation_record(
                0x03000011,
                [[frame_bytes(), frame_bytes()] for _ in range(3)],
                [frame_bytes((0.0, 0.1, 0.0)) for _ in range(3)],
                hooks={1: [hook_bytes(0x4, -1), hook_bytes(0x16, 0, struct.pack("<3f", 0.0, 0.0, 1.5))]},
            ),
            unpack_animation,
        ),
        "landblock info": (
            landblock_info_record(
                objects=[stab_bytes(0x02000010, (1.0, 2.0, 3.0))],
                buildings=[build_info_bytes(0x01000010, (10.0, 10.0, 0.0), 2, portals)],
                restrictions=[(0xA9B40100, 0x7000_0001)],
            ),
            unpack_landblock_info,
        ),
        "environment": (environment_record(), unpack_environment),
        "env cell": (
            env_cell_record(0xA9B40100, (10.0, 10.0, 0.0), [cell_portal_bytes(0, 2, 0xFFFF, 0)]),
            unpack_env_cell,
        ),
    }


RECORDS = _records()


def _damaged(data: bytes, rng: random.Random) -> bytes:
    kind = rng.randrange(4)
    if kind == 0:  # truncated
        return data[: rng.randrange(len(data))]
    raw = bytearray(data)
    if kind == 1:  # a few bytes changed
        for _ in range(rng.randint(1, 4)):
            raw[rng.randrange(len(raw))] = rng.randrange(256)
    elif kind == 2:  # a dword made huge (a count or an id)
        at = rng.randrange(max(1, len(raw) - 4)) & ~3
        raw[at : at + 4] = struct.pack("<I", rng.choice((0xFFFFFFFF, 0x7FFFFFFF, 0x10000, 0x80000000)))
    else:  # bytes inserted
        at = rng.randrange(len(raw))
        raw[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 8)))
    return bytes(raw)


@pytest.mark.parametrize("kind", list(RECORDS))
def test_a_damaged_record_unpacks_or_raises_dat_error(kind: str) -> None:
    data, unpack = RECORDS[kind]
    unpack(data)  # the undamaged record is sound
    rng = random.Random(kind)
    for trial in range(300):
        damaged = _damaged(data, rng)
        try:
            unpack(damaged)
        except DatError:
            pass
        except Exception as error:  # pragma: no cover - the failure message names the case
            raise AssertionError(f"{kind} trial {trial}: {type(error).__name__}: {error}") from error


def test_a_damaged_dat_file_reads_or_raises_dat_error(tmp_path: Path) -> None:
    original = simple_dat(tmp_path, compress=True).read_bytes()
    rng = random.Random(7)
    for trial in range(200):
        path = tmp_path / f"damaged-{trial}.dat"
        path.write_bytes(_damaged(original, rng))
        try:
            with DatFile(path) as dat:
                for entry in list(dat.entries()):
                    dat.read(entry.object_id)
        except DatError as error:
            assert str(path) in str(error)
        except Exception as error:  # pragma: no cover
            raise AssertionError(f"trial {trial}: {type(error).__name__}: {error}") from error


@pytest.mark.parametrize("kind", list(RECORDS))
def test_every_dword_of_a_record_made_absurd_unpacks_or_raises_dat_error(kind: str) -> None:
    """Each dword in turn set to a huge count, a huge float or a NaN: never a crash, a hang or a
    huge allocation (a count is checked against the bytes left before anything is made)."""
    data, unpack = RECORDS[kind]
    for at in range(0, len(data) - 3, 4):
        for value in (0xFFFFFFFF, 0x7FFFFFFF, 0x00100000, 0x7F800000, 0x7FC00000, 0x7E967699):
            damaged = data[:at] + struct.pack("<I", value) + data[at + 4 :]
            try:
                unpack(damaged)
            except DatError:
                pass
            except Exception as error:  # pragma: no cover
                raise AssertionError(
                    f"{kind} at byte {at} = {value:#x}: {type(error).__name__}: {error}"
                ) from error


def _three_level_dat(tmp_path: Path) -> tuple[bytes, list[int], list[int]]:
    """A DAT of 125 records (every third compressed) under a root, two middle nodes and six
    leaves of 20; its bytes, every block offset and every node offset."""
    writer = Writer()
    entries = []
    for index in range(125):
        data = struct.pack("<I", index) * (1 + index % 70)
        if index % 3 == 0:
            data = struct.pack("<I", len(data)) + zlib.compress(data)
        entries.append(writer.entry(0x0A000000 + index, data, bitfield=(2 << 16) | int(index % 3 == 0)))
    leaves = [writer.store(Writer.node([0], entries[i * 21 : i * 21 + 20])) for i in range(6)]
    separators = [entries[i * 21 + 20] for i in range(5)]  # entries 20, 41, 62, 83, 104
    middles = [
        writer.store(Writer.node(leaves[:3], separators[:2])),
        writer.store(Writer.node(leaves[3:], separators[3:])),
    ]
    root = writer.store(Writer.node(middles, [separators[2]]))
    path = writer.write(tmp_path / "tree.dat", root)
    with DatFile(path) as dat:
        assert list(dat.ids()) == [0x0A000000 + i for i in range(125)]
    return path.read_bytes(), sorted(writer.blocks), [*leaves, *middles, root]


def test_a_dat_with_damaged_links_children_and_sizes_reads_or_raises_dat_error(tmp_path: Path) -> None:
    """Block links and node children pointed at other blocks, at themselves, at the header,
    past the end or marked free; header fields, entry sizes and counts changed; blocks moved:
    every damaged file opens, lists and reads or raises a DatError naming it, quickly."""
    image, blocks, nodes = _three_level_dat(tmp_path)
    rng = random.Random(13)
    path = tmp_path / "damaged.dat"
    for trial in range(250):
        raw = bytearray(image)
        for _ in range(rng.randint(1, 3)):
            target = rng.choice(
                (0, 0x10, 0x3FF, len(raw), 0x7FFFFFFF, 0xFFFFFFFF, rng.choice(blocks), rng.choice(nodes))
            ) | rng.choice((0, 0, 0, 0x80000000))
            kind = rng.randrange(5)
            if kind == 0:  # a block's link
                at = rng.choice(blocks)
            elif kind == 1:  # a node's child or entry count (the dwords after its link)
                at = rng.choice(nodes) + 4 + 4 * rng.randrange(63)
            elif kind == 2:  # a header field
                at = 0x140 + 4 * rng.randrange(15)
            elif kind == 3:  # an entry's offset or size, in some node's chain of 252-byte payloads
                byte = 252 + 24 * rng.randrange(20) + rng.choice((8, 12))
                at = rng.choice(nodes) + byte // 252 * BLOCK + 4 + byte % 252
                target = rng.choice((target, rng.randrange(1 << 32)))
            else:  # a block copied over another
                source, dest = rng.choice(blocks), rng.choice(blocks)
                raw[dest : dest + BLOCK] = raw[source : source + BLOCK]
                continue
            if at + 4 <= len(raw):
                struct.pack_into("<I", raw, at, target & 0xFFFFFFFF)
        path.write_bytes(bytes(raw))
        try:
            with DatFile(path) as dat:
                for entry in list(dat.entries()):
                    try:
                        dat.read(entry.object_id)
                    except DatError as error:
                        assert str(path) in str(error)
                dat.lookup(0x0A000040)
        except DatError as error:
            assert str(path) in str(error) and "\n" not in str(error)
        except Exception as error:  # pragma: no cover
            raise AssertionError(f"trial {trial}: {type(error).__name__}: {error}") from error
