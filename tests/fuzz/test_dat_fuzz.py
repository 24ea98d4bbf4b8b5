"""Damaged DAT data never crashes: every record kind the reader knows, truncated anywhere or with a
few bytes changed, either unpacks or raises a DatError; a damaged DAT file likewise, through
opening, listing and reading every record. (The records are the ones the unit tests build in the
documented layout, tests/dat_support.py.)"""

from __future__ import annotations

import random
import struct
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
