"""The retail DAT container (``client_portal.dat``, ``client_cell_1.dat``, ...): header, block
chains and the B-tree directory.

Layout (``/work/ref/D/07-dat-resources.md`` sections 1-2, checked against the code cited below):

- ``DiskFileInfo_t`` (0x50 bytes, little-endian dwords) at file offset 0x140: magic 0x5442,
  block size (including the 4-byte link), file size, data set (1 portal, 2 cell, 3 local), data
  subset, first free block, last free block, free block count, B-tree root offset, young / old
  LRU, use-LRU flag, master map id, engine / game pack versions, and a 20-byte ``DatIDStamp``.
- Data lives in fixed-size blocks; each block's first dword is the offset of the next block of
  the same file (0 ends the chain, bit 31 marks a free block), the other ``block_size - 4`` bytes
  are payload.
- The directory is an order-62 B-tree keyed by the raw 32-bit id. A node (1716 bytes, stored in
  a block chain like any file) holds 62 child offsets, an entry count and 61 entry slots of 24
  bytes ``{bitfield (bit 0 compressed, bits 16-31 version), id, offset, size, date,
  iteration}``. ``children[0] == 0`` marks a leaf.
- A compressed record is a dword of uncompressed size and a zlib stream.
"""

from __future__ import annotations

import itertools
import struct
import zlib
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import BinaryIO

#: ``DiskFileInfo_t`` file offset and size (acclient.c:651034 reads 0x50 bytes at 320).
HEADER_OFFSET = 0x140
HEADER_SIZE = 0x50
#: ``magic_`` ("BT" little-endian); any other value is error -102 (acclient.c:651035).
MAGIC = 0x5442
#: The first data block (``CreateDataFile`` sets ``firstFree_ = 1024``).
DATA_START = 1024
#: A next-block link with this bit set names a free block (acclient.c:650759).
FREE_BLOCK = 0x80000000
#: ``BTNode``: 62 children, an entry count, 61 entries of 24 bytes = 1716 bytes.
NODE_BRANCHES = 62
NODE_MAX_ENTRIES = 61
ENTRY_SIZE = 24
NODE_SIZE = NODE_BRANCHES * 4 + 4 + NODE_MAX_ENTRIES * ENTRY_SIZE
#: ``DiskController::Decompress`` refuses records shorter than this (acclient.c:647382).
MIN_COMPRESSED_SIZE = 0x10

#: ``data_set_lm`` values (``DATFILE_TYPE``, acclient.h:3116).
DATA_SETS = {1: "portal", 2: "cell", 3: "local"}

_HEADER = struct.Struct("<15I16sI")
_ENTRY = struct.Struct("<6I")
_U32 = struct.Struct("<I")


class DatError(ValueError):
    """A DAT file that cannot be read: names the file and, where there is one, the offset."""


@dataclass(frozen=True)
class DatHeader:
    """``DiskFileInfo_t`` (acclient.h:28231)."""

    magic: int
    block_size: int
    file_size: int
    data_set: int
    data_subset: int
    first_free: int
    final_free: int
    free_blocks: int
    btree_root: int
    young_lru: int
    old_lru: int
    use_lru: bool
    master_map_id: int
    eng_pack_vnum: int
    game_pack_vnum: int
    id_guid: bytes
    id_vnum: int

    @property
    def data_set_name(self) -> str:
        return DATA_SETS.get(self.data_set, f"unknown ({self.data_set})")


@dataclass(frozen=True)
class DatEntry:
    """``BTEntry``: one directory entry."""

    bitfield: int
    object_id: int
    offset: int
    size: int
    date: int
    iteration: int

    @property
    def compressed(self) -> bool:
        """``comp_``, bit 0 of the bitfield."""
        return bool(self.bitfield & 1)

    @property
    def version(self) -> int:
        """``ver_``, bits 16-31: the record's pack version."""
        return self.bitfield >> 16


@dataclass(frozen=True)
class DatNode:
    """``BTNode``: a directory node read from ``offset``."""

    offset: int
    children: tuple[int, ...]
    entries: tuple[DatEntry, ...]

    @property
    def is_leaf(self) -> bool:
        """Retail tests ``NextNode_[0] == 0`` (acclient.c:649586)."""
        return self.children[0] == 0


class DatFile:
    """An open DAT file: its header, directory lookups and record bytes.

    Use as a context manager, or call :meth:`close`. Nodes are read on demand and kept.
    """

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self._file: BinaryIO = open(self.path, "rb")  # noqa: SIM115 - closed by close()/__exit__
        try:
            self._size = self._file.seek(0, 2)
            self.header = self._read_header()
            self._nodes: dict[int, DatNode] = {}
            self.root = self.node(self.header.btree_root)
        except BaseException:
            self._file.close()
            raise

    def __enter__(self) -> DatFile:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, trace: TracebackType | None
    ) -> None:
        self.close()

    def close(self) -> None:
        self._file.close()

    def _error(self, message: str, offset: int | None = None) -> DatError:
        where = f" at offset {offset:#x}" if offset is not None else ""
        return DatError(f"{self.path}{where}: {message}")

    def _read_at(self, offset: int, size: int) -> bytes:
        """``size`` bytes at ``offset``, or a DatError if the file ends first (a failed SyncRead)."""
        if offset + size > self._size:
            raise self._error(f"file truncated: needs {size} bytes, the file ends at {self._size:#x}", offset)
        self._file.seek(offset)
        return self._file.read(size)

    def _read_header(self) -> DatHeader:
        """Read and check ``DiskFileInfo_t``.

        Retail: CLBlockAllocator::OpenDataFile @ 0x00674980 (acclient.c:651003)
        """
        if self._size < HEADER_OFFSET + HEADER_SIZE:
            raise self._error(
                f"file truncated: {self._size} bytes, too short for the header at {HEADER_OFFSET:#x}"
            )
        fields = _HEADER.unpack(self._read_at(HEADER_OFFSET, HEADER_SIZE))
        header = DatHeader(*fields[:11], bool(fields[11] & 0xFF), *fields[12:])  # use_lru_fm: a bool + 3 pad
        if header.magic != MAGIC:
            raise self._error(f"bad magic {header.magic:#06x} (a DAT file has {MAGIC:#06x})", HEADER_OFFSET)
        if header.block_size <= 4:
            raise self._error(f"bad block size {header.block_size} (at most the link)", HEADER_OFFSET)
        return header

    def read_chain(self, offset: int, size: int) -> bytes:
        """The ``size`` bytes of the block chain that starts at ``offset``.

        Each block gives ``block_size - 4`` payload bytes after its link; the chain must end (link
        0) exactly when the bytes do: retail fails the read if the chain is longer or shorter, or
        reaches a free block. A chain that comes back to a block it already visited is a loop.

        Retail: CLBlockAllocator::Load_Data @ 0x006744E0 (acclient.c:650710)
        """
        payload = self.header.block_size - 4
        parts: list[bytes] = []
        remaining = size
        block = offset
        seen: set[int] = set()
        while remaining > 0:
            if block == 0:
                raise self._error(f"block chain ends after {size - remaining} of {size} bytes", offset)
            if block in seen:
                raise self._error(f"loop in the block chain: block {block:#x} comes round again", offset)
            seen.add(block)
            take = min(payload, remaining)
            data = self._read_at(block, 4 + take)
            next_block = _U32.unpack_from(data)[0]
            parts.append(data[4:])
            remaining -= take
            if next_block & FREE_BLOCK:
                raise self._error(f"block chain reaches a free block after block {block:#x}", offset)
            block = next_block
        if block != 0:
            raise self._error(f"block chain continues past the {size} bytes it holds (to {block:#x})", offset)
        return b"".join(parts)

    def node(self, offset: int) -> DatNode:
        """The directory node stored at ``offset``.

        Retail: BTree::FindNode @ 0x00672320 (acclient.c:648770)
        """
        cached = self._nodes.get(offset)
        if cached is not None:
            return cached
        data = self.read_chain(offset, NODE_SIZE)
        children = struct.unpack_from(f"<{NODE_BRANCHES}I", data)
        count = _U32.unpack_from(data, NODE_BRANCHES * 4)[0]
        if count > NODE_MAX_ENTRIES:
            raise self._error(f"directory node has {count} entries (at most {NODE_MAX_ENTRIES})", offset)
        base = NODE_BRANCHES * 4 + 4
        entries = tuple(DatEntry(*_ENTRY.unpack_from(data, base + i * ENTRY_SIZE)) for i in range(count))
        for before, after in itertools.pairwise(entries):
            if before.object_id >= after.object_id:
                raise self._error(
                    f"directory node entries out of order ({before.object_id:#010x} then "
                    f"{after.object_id:#010x})",
                    offset,
                )
        node = DatNode(offset, children, entries)
        self._nodes[offset] = node
        return node

    def lookup(self, object_id: int) -> DatEntry | None:
        """The directory entry of ``object_id``, or None: a binary search in each node, descending
        into the child between the neighbouring keys.

        Retail: BTree::Search @ 0x006731C0 (acclient.c:649568)
        """
        node = self.root
        visited: set[int] = set()
        while True:
            index = _insertion_point(node.entries, object_id)
            if index < len(node.entries) and node.entries[index].object_id == object_id:
                return node.entries[index]
            if node.is_leaf:
                return None
            visited.add(node.offset)
            child = node.children[index]
            if child in visited:
                raise self._error(f"loop in the directory: node {child:#x} comes round again", node.offset)
            node = self.node(child)

    def entry(self, object_id: int) -> DatEntry:
        """The directory entry of ``object_id``, or a DatError naming the missing id."""
        found = self.lookup(object_id)
        if found is None:
            raise self._error(f"no record {object_id:#010x}")
        return found

    def read(self, object_id: int) -> bytes:
        """The bytes of record ``object_id``, decompressed when its entry says so.

        Retail: DiskController::LoadDataEx @ 0x00670BC0 (acclient.c:647425)
        """
        found = self.entry(object_id)
        data = self.read_chain(found.offset, found.size)
        return self._decompress(found, data) if found.compressed else data

    def _decompress(self, found: DatEntry, data: bytes) -> bytes:
        """A dword of uncompressed size, then zlib.

        Retail: DiskController::Decompress @ 0x00670A80 (acclient.c:647366)
        """
        if len(data) < MIN_COMPRESSED_SIZE:
            raise self._error(
                f"compressed record {found.object_id:#010x} is {len(data)} bytes (at least "
                f"{MIN_COMPRESSED_SIZE})",
                found.offset,
            )
        expected = _U32.unpack_from(data)[0]
        try:
            plain = zlib.decompress(data[4:])
        except zlib.error as error:
            message = f"record {found.object_id:#010x} does not decompress: {error}"
            raise self._error(message, found.offset) from None
        if len(plain) != expected:
            raise self._error(
                f"record {found.object_id:#010x} decompresses to {len(plain)} bytes, not {expected}",
                found.offset,
            )
        return plain

    def entries(self) -> Iterator[DatEntry]:
        """Every directory entry, in id order (an in-order walk of the B-tree)."""
        yield from self._walk(self.root, set())

    def _walk(self, node: DatNode, visited: set[int]) -> Iterator[DatEntry]:
        if node.offset in visited:
            raise self._error(f"loop in the directory: node {node.offset:#x} is reached twice", node.offset)
        visited.add(node.offset)
        for index, found in enumerate(node.entries):
            if not node.is_leaf:
                yield from self._walk(self.node(node.children[index]), visited)
            yield found
        if not node.is_leaf:
            yield from self._walk(self.node(node.children[len(node.entries)]), visited)

    def ids(self) -> Iterator[int]:
        """Every record id, in order."""
        return (found.object_id for found in self.entries())


def _insertion_point(entries: tuple[DatEntry, ...], object_id: int) -> int:
    """The index of ``object_id`` in the sorted ``entries``, or where it would go.

    Retail: BTree::HasEntry @ 0x00671D80 (acclient.c:648414)
    """
    low, high = 0, len(entries)
    while low < high:
        middle = (low + high) // 2
        if entries[middle].object_id < object_id:
            low = middle + 1
        else:
            high = middle
    return low
