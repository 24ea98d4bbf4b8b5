"""DAT files built from the documented layout (07-dat-resources.md sections 1-2, acclient.h),
shared by the DAT reader's tests and the scenario ``[data]`` tests.

The writer is independent of the reader: it lays blocks, nodes and records out from the layout
description, so a reader that agreed with a wrong writer by construction is not possible.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Sequence
from pathlib import Path

BLOCK = 256
SETUP_ID = 0x02000001
REGION_ID = 0x13000000
LANDBLOCK_ID = 0xA9B4FFFF
#: ``DATFILE_TYPE`` data sets (acclient.h:3116).
PORTAL = 1
CELL = 2


def f32(value: float) -> float:
    """``value`` rounded to float32, as the DAT stores it."""
    return float(struct.unpack("<f", struct.pack("<f", value))[0])


class Writer:
    """Lays out a DAT: header at 0x140, blocks from 1024 linked by their first dword, B-tree nodes
    of 62 children + count + 61 entries of 24 bytes."""

    def __init__(self, block_size: int = BLOCK) -> None:
        self.block_size = block_size
        self.blocks: dict[int, bytes] = {}
        self.next = 1024

    def alloc(self) -> int:
        offset = self.next
        self.next += self.block_size
        return offset

    def store(self, data: bytes, reverse: bool = False) -> int:
        """Write ``data`` over a chain of blocks (allocated backwards if ``reverse``)."""
        payload = self.block_size - 4
        chunks = [data[i : i + payload] for i in range(0, len(data), payload)] or [b""]
        offsets = [self.alloc() for _ in chunks]
        if reverse:
            offsets.reverse()
        for i, (offset, chunk) in enumerate(zip(offsets, chunks, strict=True)):
            link = offsets[i + 1] if i + 1 < len(offsets) else 0
            self.blocks[offset] = struct.pack("<I", link) + chunk.ljust(payload, b"\0")
        return offsets[0]

    @staticmethod
    def node(children: list[int], entries: list[tuple[int, ...]]) -> bytes:
        assert len(entries) <= 61
        raw = struct.pack("<62I", *(children + [0] * (62 - len(children))))
        raw += struct.pack("<I", len(entries))
        raw += b"".join(struct.pack("<6I", *e) for e in entries)
        return raw.ljust(62 * 4 + 4 + 61 * 24, b"\0")

    def entry(self, object_id: int, data: bytes, bitfield: int = 0) -> tuple[int, ...]:
        """Store a record; its directory entry {bitfield, id, offset, size, date, iteration}."""
        return (bitfield, object_id, self.store(data), len(data), 0x5F000000, 7)

    def write(self, path: Path, root: int, magic: int = 0x5442, data_set: int = PORTAL) -> Path:
        size = self.next
        image = bytearray(size)
        image[:0x100] = b"\nFile Header Structure Default Constructor v1.3\n".ljust(255, b"\0") + b"\x1a"
        header = struct.pack(
            "<15I16sI", magic, self.block_size, size, data_set, 0, 0, 0, 0, root, 0, 0, 0,
            0x25000000, 0xFFFFFFFF, 0, bytes(range(16)), 982,
        )  # fmt: skip
        image[0x140 : 0x140 + len(header)] = header
        for offset, block in self.blocks.items():
            image[offset : offset + len(block)] = block
        path.write_bytes(bytes(image))
        return path


def setup_record(
    flags: int = 0x7,
    hooks: int = 0,
    setup_id: int = SETUP_ID,
    steps: tuple[float, float] = (0.6, 0.4),
) -> bytes:
    """A human-shaped setup: 2 parts, two spheres r 0.48 at z 0.475 and 1.35, step heights
    ``steps`` (up, down)."""
    frame = struct.pack("<7f", 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0)
    raw = struct.pack("<II", setup_id, flags)
    raw += struct.pack("<I2I", 2, 0x01000001, 0x01000002)  # parts
    if flags & 1:
        raw += struct.pack("<2I", 0xFFFFFFFF, 0)  # parent indices
    if flags & 2:
        raw += struct.pack("<6f", 1, 1, 1, 0.5, 0.5, 0.5)  # default scales
    raw += struct.pack("<III", 1, 2, 1) + frame  # holding locations: {2: part 1, frame}
    raw += struct.pack("<I", 0)  # connection points
    raw += struct.pack("<II", 1, 0x65) + frame + frame + struct.pack("<I", hooks)  # placement 0x65
    raw += struct.pack("<I5f", 1, 0.1, 0.2, 0.3, 0.25, 2.0)  # one cylsphere
    raw += struct.pack("<I8f", 2, 0, 0, 0.475, 0.48, 0, 0, 1.35, 0.48)  # spheres
    raw += struct.pack("<4f", 1.83, 0.48, *steps)  # height, radius, step up, step down
    raw += struct.pack("<4f", 0, 0, 0.9125, 0.9525)  # sorting sphere
    raw += struct.pack("<4f", 0, 0, 0.9, 1.0)  # selection sphere
    raw += struct.pack("<II", 1, 3) + frame + struct.pack("<I3f", 0xFFFFEECC, 2.0, 5.0, 0.5)  # a light
    raw += struct.pack("<5I", 0x03000001, 0x33000001, 0x09000001, 0x20000001, 0x34000001)
    return raw


def height_table() -> list[float]:
    return [f32(i * 2.5) for i in range(256)]


def region_record(version: int = 3, name: bytes = b"Dereth!", table: list[float] | None = None) -> bytes:
    raw = struct.pack("<III", REGION_ID, 1, version)
    raw += struct.pack("<H", len(name)) + name
    raw += b"\0" * (-len(raw) % 4)
    raw += struct.pack("<8I", 255, 255, 0x41C00000, 8, 1, 0x43480000, 0x447A0000, 0x40A00000)
    raw += struct.pack("<256f", *(height_table() if table is None else table))
    return raw + b"\xee" * 40  # GameTime and the rest, which acphys does not read


def landblock_record(
    landblock_id: int = LANDBLOCK_ID,
    terrain: Sequence[int] | None = None,
    heights: Sequence[int] | None = None,
) -> bytes:
    """A landblock record: DID, lbi_exists 1, 81 terrain words, 81 height bytes, padding."""
    if terrain is None:
        terrain = [(i % 32) << 2 for i in range(81)]
    height_bytes = bytes((i * 3) % 256 for i in range(81)) if heights is None else bytes(heights)
    raw = struct.pack("<II", landblock_id, 1) + struct.pack("<81H", *terrain) + height_bytes
    return raw + b"\0" * (-len(raw) % 4)


def simple_dat(
    tmp_path: Path,
    records: dict[int, bytes] | None = None,
    compress: bool = False,
    name: str = "client_portal.dat",
    data_set: int = PORTAL,
) -> Path:
    """A one-node DAT ``tmp_path / name`` holding ``records`` (default: a setup and the region)."""
    records = records or {SETUP_ID: setup_record(), REGION_ID: region_record()}
    writer = Writer()
    entries = []
    for object_id in sorted(records):
        data = records[object_id]
        if compress:
            data = struct.pack("<I", len(data)) + zlib.compress(data, 9)
        entries.append(writer.entry(object_id, data, bitfield=(2 << 16) | int(compress)))
    root = writer.store(Writer.node([0], entries))
    return writer.write(tmp_path / name, root, data_set=data_set)
