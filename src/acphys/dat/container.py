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

Damaged files are refused with a DatError naming the file and the offset: non-regular files
before any read, block chains that loop or leave the file, directories that loop, nest deeper or
hold more nodes than a real DAT can, and records larger than :data:`MAX_RECORD_SIZE` or than
they declare (inflated with that bound, never in full first).
"""

from __future__ import annotations

import errno
import itertools
import struct
import zlib
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import BinaryIO

from acphys.inputs import InputError, one_line, open_regular

#: ``DiskFileInfo_t`` file offset and size (acclient.c:651034 reads 0x50 bytes at 320).
HEADER_OFFSET = 0x140
HEADER_SIZE = 0x50
#: ``magic_`` ("BT" little-endian); any other value is error -102 (acclient.c:651035).
MAGIC = 0x5442
#: The first data block (``CreateDataFile`` sets ``firstFree_ = 1024``).
DATA_START = 1024
#: The smallest block size read. Retail's DATs use 256-byte (cell) and 1,024-byte (portal, local)
#: blocks; a few bytes a block would make every record a chain of millions of reads (and the
#: chain's loop check as large), so a header under 64 is taken as damaged.
MIN_BLOCK_SIZE = 64
#: A next-block link with this bit set names a free block (acclient.c:650759).
FREE_BLOCK = 0x80000000
#: ``BTNode``: 62 children, an entry count, 61 entries of 24 bytes = 1716 bytes.
NODE_BRANCHES = 62
NODE_MAX_ENTRIES = 61
ENTRY_SIZE = 24
NODE_SIZE = NODE_BRANCHES * 4 + 4 + NODE_MAX_ENTRIES * ENTRY_SIZE
#: ``DiskController::Decompress`` refuses records shorter than this (acclient.c:647382).
MIN_COMPRESSED_SIZE = 0x10
#: The deepest directory read. The node layout is a textbook B-tree of minimum degree 31 (62
#: children, 61 entries), which keeps every node but the root at least half full, so level k
#: holds at least 2 * 31**(k - 2) nodes of 1,716 bytes. The 32-bit offsets cap a DAT at 4 GiB,
#: some 2.5 million nodes: enough for depth 6 (1.8 million at level 6), not 7 (57 million).
#: 16 leaves room for a writer that balances less well and stops a damaged chain of nodes.
MAX_DIRECTORY_DEPTH = 16
#: The largest record read, stored or inflated: 16 MiB. The records acphys reads (setups,
#: GfxObjs, animations, motion tables, environments, cells, landblocks, the region) are far
#: smaller (a landblock is 252 bytes); the bound keeps a damaged size, or a small zlib stream that
#: inflates a thousandfold, from taking gigabytes (parsed, a record takes up to some 25 times its
#: bytes in Python objects, so 16 MiB stays well under 1 GB).
MAX_RECORD_SIZE = 16 * 1024 * 1024

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
        self._file: BinaryIO = _open_dat(self.path)
        try:
            self._size = self._file.seek(0, 2)
            self.header = self._read_header()
            self._nodes: dict[int, DatNode] = {}
            #: Distinct nodes take distinct bytes: more than this many is a damaged directory.
            self._max_nodes = self._size // NODE_SIZE
            self.root = self._root()
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
        return DatError(f"{one_line(str(self.path))}{where}: {message}")

    def _read_at(self, offset: int, size: int, lead: str = "") -> bytes:
        """``size`` bytes at ``offset``, or a DatError (``lead`` first) if the file ends first (a
        failed SyncRead)."""
        if offset + size > self._size:
            raise self._error(
                f"{lead}file truncated: needs {size} bytes, the file ends at {self._size:#x}", offset
            )
        self._file.seek(offset)
        data = self._file.read(size)
        if len(data) < size:  # the file shrank since it was opened
            raise self._error(f"{lead}file truncated: needs {size} bytes, read {len(data)}", offset)
        return data

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
        if header.block_size < MIN_BLOCK_SIZE:
            raise self._error(
                f"bad block size {header.block_size} (under {MIN_BLOCK_SIZE}, MIN_BLOCK_SIZE)", HEADER_OFFSET
            )
        return header

    def _root(self) -> DatNode:
        """The directory's root node, at the header's ``btree_root``."""
        self._check_node_offset(self.header.btree_root, "the directory root", HEADER_OFFSET)
        return self.node(self.header.btree_root)

    def _check_node_offset(self, offset: int, what: str, at: int) -> None:
        """A DatError (at offset ``at``) unless ``offset``, where ``what`` is, is in a data block."""
        if offset < DATA_START:
            message = f"{what} is at {offset:#x}, inside the header (data starts at {DATA_START:#x})"
            raise self._error(message, at)
        if offset >= self._size:
            message = f"file truncated: {what} is at {offset:#x}, past its end at {self._size:#x}"
            raise self._error(message, at)

    def read_chain(self, offset: int, size: int, what: str = "") -> bytes:
        """The ``size`` bytes of the block chain that starts at ``offset``; ``what`` (a record, a
        directory node) starts the error messages.

        Each block gives ``block_size - 4`` payload bytes after its link; the chain must end (link
        0) exactly when the bytes do: retail fails the read if the chain is longer or shorter, or
        reaches a free block. A chain that comes back to a block it already visited is a loop;
        one that links into the header or past the end of the file is damaged.

        Retail: CLBlockAllocator::Load_Data @ 0x006744E0 (acclient.c:650710)
        """
        lead = f"{what}: " if what else ""
        if size > self._size:
            raise self._error(f"{lead}{size} bytes, more than the whole file ({self._size})", offset)
        payload = self.header.block_size - 4
        parts: list[bytes] = []
        remaining = size
        block = offset
        seen: set[int] = set()
        while remaining > 0:
            if block == 0:
                raise self._error(f"{lead}block chain ends after {size - remaining} of {size} bytes", offset)
            if block < DATA_START:
                raise self._error(
                    f"{lead}block chain reaches block {block:#x}, inside the header (data blocks "
                    f"start at {DATA_START:#x})",
                    offset,
                )
            if block >= self._size:
                raise self._error(
                    f"{lead}file truncated: the block chain reaches block {block:#x}, the file ends at "
                    f"{self._size:#x}",
                    offset,
                )
            if block in seen:
                message = f"{lead}loop in the block chain: block {block:#x} comes round again"
                raise self._error(message, offset)
            seen.add(block)
            take = min(payload, remaining)
            data = self._read_at(block, 4 + take, lead)
            next_block = _U32.unpack_from(data)[0]
            parts.append(data[4:])
            remaining -= take
            if next_block & FREE_BLOCK:
                raise self._error(f"{lead}block chain reaches a free block after block {block:#x}", offset)
            block = next_block
        if block != 0:
            raise self._error(
                f"{lead}block chain continues past the {size} bytes it holds (to {block:#x})", offset
            )
        return b"".join(parts)

    def node(self, offset: int) -> DatNode:
        """The directory node stored at ``offset`` (read once, then kept).

        Retail: BTree::FindNode @ 0x00672320 (acclient.c:648770)
        """
        cached = self._nodes.get(offset)
        if cached is None:
            cached = self._nodes[offset] = self._read_node(offset)
        return cached

    def _read_node(self, offset: int) -> DatNode:
        """Read and check the directory node at ``offset``."""
        data = self.read_chain(offset, NODE_SIZE, f"directory node {offset:#x}")
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
        return DatNode(offset, children, entries)

    def _child(self, node: DatNode, index: int, depth: int, visited: set[int], cache: bool) -> DatNode:
        """Child ``index`` of ``node``, which is at ``depth`` (the root is 1); ``visited`` holds
        the nodes reached so far, which the child must not be one of (a loop, or a node shared by
        two parents). Past :data:`MAX_DIRECTORY_DEPTH`, or past as many nodes as the file can
        hold, the directory is damaged. ``cache`` keeps the node (lookups do; walks read the
        whole directory, which need not stay in memory)."""
        offset = node.children[index]
        if depth >= MAX_DIRECTORY_DEPTH:
            raise self._error(
                f"directory deeper than {MAX_DIRECTORY_DEPTH} levels (MAX_DIRECTORY_DEPTH): node "
                f"{node.offset:#x} at depth {depth} has children",
                node.offset,
            )
        if offset in visited:
            raise self._error(
                f"loop in the directory: node {node.offset:#x} names node {offset:#x} (child {index}), "
                "which is reached twice",
                node.offset,
            )
        if len(visited) >= self._max_nodes:
            raise self._error(
                f"directory has more than the {self._max_nodes} nodes of {NODE_SIZE} bytes a file of "
                f"{self._size} bytes holds",
                node.offset,
            )
        self._check_node_offset(offset, f"child {index} of directory node {node.offset:#x}", node.offset)
        visited.add(offset)
        return self.node(offset) if cache else self._nodes.get(offset) or self._read_node(offset)

    def lookup(self, object_id: int) -> DatEntry | None:
        """The directory entry of ``object_id``, or None: a binary search in each node, descending
        into the child between the neighbouring keys.

        Retail: BTree::Search @ 0x006731C0 (acclient.c:649568)
        """
        node = self.root
        visited = {node.offset}
        while True:
            index = _insertion_point(node.entries, object_id)
            if index < len(node.entries) and node.entries[index].object_id == object_id:
                return node.entries[index]
            if node.is_leaf:
                return None
            node = self._child(node, index, len(visited), visited, cache=True)

    def entry(self, object_id: int) -> DatEntry:
        """The directory entry of ``object_id``, or a DatError naming the missing id."""
        found = self.lookup(object_id)
        if found is None:
            raise self._error(f"no record {object_id:#010x}")
        return found

    def read(self, object_id: int) -> bytes:
        """The bytes of record ``object_id``, decompressed when its entry says so; a record over
        :data:`MAX_RECORD_SIZE`, stored or inflated, is refused.

        Retail: DiskController::LoadDataEx @ 0x00670BC0 (acclient.c:647425)
        """
        found = self.entry(object_id)
        what = f"record {object_id:#010x}"
        if found.size > MAX_RECORD_SIZE:
            raise self._error(
                f"{what} is {found.size} bytes, over the {MAX_RECORD_SIZE}-byte limit (MAX_RECORD_SIZE)",
                found.offset,
            )
        data = self.read_chain(found.offset, found.size, what)
        return self._decompress(found, data) if found.compressed else data

    def _decompress(self, found: DatEntry, data: bytes) -> bytes:
        """A dword of uncompressed size, then zlib, inflated to at most that size (one byte more
        shows a stream that would go on).

        Retail: DiskController::Decompress @ 0x00670A80 (acclient.c:647366)
        """
        what = f"record {found.object_id:#010x}"
        if len(data) < MIN_COMPRESSED_SIZE:
            raise self._error(
                f"compressed {what} is {len(data)} bytes (at least {MIN_COMPRESSED_SIZE})", found.offset
            )
        expected = _U32.unpack_from(data)[0]
        if expected > MAX_RECORD_SIZE:
            raise self._error(
                f"{what} declares {expected} bytes uncompressed, over the {MAX_RECORD_SIZE}-byte limit "
                "(MAX_RECORD_SIZE)",
                found.offset,
            )
        inflater = zlib.decompressobj()
        try:
            plain = inflater.decompress(memoryview(data)[4:], expected + 1)
        except zlib.error as error:
            raise self._error(f"{what} does not decompress: {error}", found.offset) from None
        if len(plain) > expected:
            message = f"{what} decompresses to more than the {expected} bytes it declares"
            raise self._error(message, found.offset)
        if not inflater.eof:
            raise self._error(
                f"{what} does not decompress: its zlib stream ends early ({len(plain)} of {expected} bytes)",
                found.offset,
            )
        if len(plain) != expected:
            raise self._error(f"{what} decompresses to {len(plain)} bytes, not {expected}", found.offset)
        return plain

    def entries(self) -> Iterator[DatEntry]:
        """Every directory entry, in id order: an in-order walk of the B-tree with a stack of
        (node, next child, depth), each node reached once (see :meth:`_child`); ids that do not
        rise from one entry to the next are a damaged directory."""
        visited = {self.root.offset}
        stack: list[tuple[DatNode, int, int]] = [(self.root, 0, 1)]
        previous: DatEntry | None = None
        while stack:
            node, index, depth = stack.pop()
            if node.is_leaf:
                following: tuple[DatEntry, ...] = node.entries
            else:
                following = node.entries[index - 1 : index] if index else ()
                if index < len(node.entries):
                    stack.append((node, index + 1, depth))
                stack.append((self._child(node, index, depth, visited, cache=False), 0, depth + 1))
            for found in following:
                if previous is not None and found.object_id <= previous.object_id:
                    raise self._error(
                        f"directory out of order: {found.object_id:#010x} in node {node.offset:#x} "
                        f"follows {previous.object_id:#010x}",
                        node.offset,
                    )
                previous = found
                yield found

    def ids(self) -> Iterator[int]:
        """Every record id, in order."""
        return (found.object_id for found in self.entries())


def _open_dat(path: Path) -> BinaryIO:
    """``path`` opened for reading by :func:`acphys.inputs.open_regular`, which refuses a path that
    is not a regular file before any read (a FIFO would block until something writes to it, a
    device such as /dev/zero never ends); a refusal is a DatError, a missing file
    ``FileNotFoundError`` as from ``open``."""
    try:
        return open_regular(path)
    except InputError as error:
        if error.errno == errno.ENOENT:
            raise FileNotFoundError(errno.ENOENT, error.strerror, str(path)) from None
        raise DatError(str(error)) from None


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
