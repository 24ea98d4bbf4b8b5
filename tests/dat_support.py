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
    lbi_exists: int = 1,
) -> bytes:
    """A landblock record: DID, ``lbi_exists``, 81 terrain words, 81 height bytes, padding."""
    if terrain is None:
        terrain = [(i % 32) << 2 for i in range(81)]
    height_bytes = bytes((i * 3) % 256 for i in range(81)) if heights is None else bytes(heights)
    raw = struct.pack("<II", landblock_id, lbi_exists) + struct.pack("<81H", *terrain) + height_bytes
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


#: A one-part setup whose part is a box GfxObj with a physics BSP.
BOX_SETUP_ID = 0x02000010
BOX_GFXOBJ_ID = 0x01000010


def compressed_u32(value: int) -> bytes:
    """``SB_As32Bit_Compressed``: 1 byte below 0x80, 2 (0x80 | high) below 0x4000, else 4 bytes
    (0xC0 | bits 24-29, bits 16-23, then the low 16 bits as a u16)."""
    if value < 0x80:
        return bytes([value])
    if value < 0x4000:
        return bytes([0x80 | value >> 8, value & 0xFF])
    return bytes([0xC0 | value >> 24, (value >> 16) & 0xFF]) + struct.pack("<H", value & 0xFFFF)


def box_corner(index: int, lo: Sequence[float], hi: Sequence[float]) -> tuple[float, float, float]:
    """Box vertex ``index``: bit 0 picks max x, bit 1 max y, bit 2 max z."""
    return tuple((hi if index >> axis & 1 else lo)[axis] for axis in range(3))  # type: ignore[return-value]


#: The six faces as vertex indices, counter-clockwise seen from outside, with their outward
#: normal axis and sign: +x, -x, +y, -y, +z, -z.
BOX_FACES = (
    ((1, 3, 7, 5), 0, 1.0),
    ((0, 4, 6, 2), 0, -1.0),
    ((2, 6, 7, 3), 1, 1.0),
    ((0, 1, 5, 4), 1, -1.0),
    ((4, 5, 7, 6), 2, 1.0),
    ((0, 2, 3, 1), 2, -1.0),
)


def box_gfxobj_record(
    lo: Sequence[float],
    hi: Sequence[float],
    gfxobj_id: int = BOX_GFXOBJ_ID,
    flags: int = 0x3,
    vertex_type: int = 1,
    bad_poly_ref: bool = False,
) -> bytes:
    """A GfxObj holding a box: 8 vertices (one UV each), 6 one-sided polygons and a physics BSP
    of the retail shape: a chain of ``BPnN`` nodes, one per face plane, each with an empty
    ``LEAF`` on its positive (outside) side, ending in a solid ``LEAF`` holding all 6 faces.
    Flag 2's drawing data (never read by acphys) is stood in for by filler bytes."""
    center = [(a + b) / 2 for a, b in zip(lo, hi, strict=True)]
    radius = sum((b - a) ** 2 for a, b in zip(lo, hi, strict=True)) ** 0.5 / 2
    sphere = struct.pack("<4f", *center, radius)
    raw = struct.pack("<II", gfxobj_id, flags)
    raw += compressed_u32(1) + struct.pack("<I", 0x08000001)  # one surface
    raw += struct.pack("<iI", vertex_type, 8)
    for i in range(8):
        # vert_id, one UV; position; a normal; the UV
        raw += struct.pack("<2H", i, 1) + struct.pack("<3f", *box_corner(i, lo, hi))
        raw += struct.pack("<3f", 0.0, 0.0, 1.0) + struct.pack("<2f", 0.5, 0.5)
    if flags & 1:
        raw += compressed_u32(6)
        for n, (ids, _axis, _sign) in enumerate(BOX_FACES):
            # Face 2 stores no UV indices (stippling 4); the rest store one byte per point.
            stippling = 4 if n == 2 else 0
            raw += struct.pack("<HBBi2H", n, 4, stippling, 0, 0, 0) + struct.pack("<4H", *ids)
            raw += b"" if stippling else bytes(4)
        for n, (_ids, axis, sign) in enumerate(BOX_FACES):
            normal = [0.0, 0.0, 0.0]
            normal[axis] = sign
            d = -(hi[axis] if sign > 0 else -lo[axis])
            raw += struct.pack("<I", type_tag("BPnN")) + struct.pack("<4f", *normal, d)
            raw += struct.pack("<IiI", type_tag("LEAF"), n, 0) + struct.pack("<4f", *center, 0.0)
            raw += struct.pack("<I", 0)  # empty leaf: no polygons
        refs = [0, 1, 2, 3, 4, 9 if bad_poly_ref else 5]
        raw += struct.pack("<IiI", type_tag("LEAF"), 6, 1) + sphere + struct.pack("<I6H", 6, *refs)
        raw += sphere * 6  # the six nodes' spheres, written after their children
    raw += struct.pack("<3f", *center)  # sort centre
    if flags & 2:
        raw += b"\xdd" * 24
    return raw


def type_tag(name: str) -> int:
    """A BSP node tag as the dword the DAT stores (``'LEAF'`` reads 0x4C454146)."""
    return int.from_bytes(name.encode("ascii"), "big")


def box_setup_record(setup_id: int = BOX_SETUP_ID, parts: Sequence[int] = (BOX_GFXOBJ_ID,)) -> bytes:
    """A static object's setup: flags 8 (HAS_PHYSICS_BSP), ``parts``, one identity placement
    frame, no spheres."""
    identity = struct.pack("<7f", 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
    raw = struct.pack("<III", setup_id, 0x8, len(parts)) + struct.pack(f"<{len(parts)}I", *parts)
    raw += struct.pack("<II", 0, 0)  # holding locations, connection points
    raw += struct.pack("<II", 1, 0x65) + identity * len(parts) + struct.pack("<I", 0)
    raw += struct.pack("<II", 0, 0)  # cylspheres, spheres
    raw += struct.pack("<4f", 2.5, 20.0, 0.0, 0.0)
    raw += struct.pack("<8f", 0, 0, 1.25, 20.2, 0, 0, 1.25, 20.2)  # sorting, selection spheres
    raw += struct.pack("<I5I", 0, 0, 0, 0, 0, 0)  # lights, default ids
    return raw


def parts_setup_record(
    setup_id: int,
    parts: Sequence[int],
    origins: Sequence[tuple[float, float, float]],
    scales: Sequence[tuple[float, float, float]] | None = None,
    placement_id: int = 0x65,
) -> bytes:
    """A static object's many-part setup: flags 8 (HAS_PHYSICS_BSP), plus 2 with ``scales`` (one
    default scale a part); placement ``placement_id`` puts part i at ``origins[i]``, unturned."""
    flags = 0x8 | (0x2 if scales is not None else 0)
    raw = struct.pack("<III", setup_id, flags, len(parts)) + struct.pack(f"<{len(parts)}I", *parts)
    if scales is not None:
        raw += b"".join(struct.pack("<3f", *scale) for scale in scales)
    raw += struct.pack("<II", 0, 0)  # holding locations, connection points
    raw += struct.pack("<II", 1, placement_id) + b"".join(frame_bytes(origin) for origin in origins)
    raw += struct.pack("<I", 0)  # no hooks
    raw += struct.pack("<II", 0, 0)  # cylspheres, spheres
    raw += struct.pack("<4f", 2.5, 20.0, 0.0, 0.0)
    raw += struct.pack("<8f", 0, 0, 1.25, 20.2, 0, 0, 1.25, 20.2)  # sorting, selection spheres
    raw += struct.pack("<I5I", 0, 0, 0, 0, 0, 0)  # lights, default ids
    return raw


# -- animations (0x03xxxxxx) and motion tables (0x09xxxxxx) -----------------------------------


def frame_bytes(
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0), quat: tuple[float, ...] = (1, 0, 0, 0)
) -> bytes:
    """An ``AFrame``: origin x y z, then qw qx qy qz."""
    return struct.pack("<7f", *origin, *quat)


def hook_bytes(kind: int, direction: int, body: bytes = b"") -> bytes:
    """A hook: type, direction (signed), the type's fields, zero padding to a dword."""
    raw = struct.pack("<Ii", kind, direction) + body
    return raw + b"\0" * (-len(raw) % 4)


def animation_record(
    anim_id: int,
    part_frames: Sequence[Sequence[bytes]],
    pos_frames: Sequence[bytes] | None = None,
    hooks: dict[int, list[bytes]] | None = None,
    flags: int | None = None,
) -> bytes:
    """A ``CAnimation``: DID, flags (bit 0: position frames present), part count, frame count,
    [one position frame per frame], then per frame its part frames, hook count and hooks."""
    hooks = hooks or {}
    num_parts = len(part_frames[0]) if part_frames else 0
    if flags is None:
        flags = 1 if pos_frames is not None else 0
    raw = struct.pack("<4I", anim_id, flags, num_parts, len(part_frames))
    if pos_frames is not None:
        raw += b"".join(pos_frames)
    for index, parts in enumerate(part_frames):
        frame_hooks = hooks.get(index, [])
        raw += b"".join(parts) + struct.pack("<I", len(frame_hooks)) + b"".join(frame_hooks)
    return raw


def motion_data_bytes(
    key: int,
    anims: Sequence[tuple[int, int, int, float]] = (),
    bitfield: int = 0,
    velocity: tuple[float, float, float] | None = None,
    omega: tuple[float, float, float] | None = None,
) -> bytes:
    """A keyed ``MotionData``: key, anim count, bitfield and vector-flag bytes, one pad byte,
    the AnimData {anim id, low frame, high frame, framerate}, then velocity and omega when
    flagged (flag bits 1 and 2)."""
    flags = (1 if velocity is not None else 0) | (2 if omega is not None else 0)
    raw = struct.pack("<IBBBx", key, len(anims), bitfield, flags)
    raw += b"".join(struct.pack("<Iiif", *anim) for anim in anims)
    if velocity is not None:
        raw += struct.pack("<3f", *velocity)
    if omega is not None:
        raw += struct.pack("<3f", *omega)
    return raw


def motion_table_record(
    table_id: int,
    default_style: int,
    style_defaults: dict[int, int],
    cycles: Sequence[bytes],
    modifiers: Sequence[bytes] = (),
    links: dict[int, Sequence[bytes]] | None = None,
) -> bytes:
    """A ``CMotionTable``: DID, default style, style defaults {style, substate}, cycles and
    modifiers (count + keyed MotionData each), links (count, then {key, count, keyed MotionData})."""
    links = links or {}
    raw = struct.pack("<III", table_id, default_style, len(style_defaults))
    raw += b"".join(struct.pack("<II", style, sub) for style, sub in style_defaults.items())
    raw += struct.pack("<I", len(cycles)) + b"".join(cycles)
    raw += struct.pack("<I", len(modifiers)) + b"".join(modifiers)
    raw += struct.pack("<I", len(links))
    for key, inner in links.items():
        raw += struct.pack("<II", key, len(inner)) + b"".join(inner)
    return raw


# -- landblock info (0xXXYYFFFE, cell DAT) ----------------------------------------------------

LANDBLOCK_INFO_ID = 0xA9B4FFFE


def stab_bytes(
    object_id: int, origin: tuple[float, float, float], quat: tuple[float, ...] = (1, 0, 0, 0)
) -> bytes:
    """One static object of a landblock info: its DID, then its frame (origin, qw qx qy qz)."""
    return struct.pack("<I", object_id) + frame_bytes(origin, quat)


def bld_portal_bytes(flags: int, other_cell: int, other_portal: int, stabs: Sequence[int]) -> bytes:
    """A ``CBldPortal``: u16 flags, u16 other cell number, i16 other portal, u16 stab count,
    the u16 stabs, then zero padding to a dword (2 bytes after an odd stab count)."""
    raw = struct.pack("<HHhH", flags, other_cell, other_portal, len(stabs))
    raw += struct.pack(f"<{len(stabs)}H", *stabs)
    return raw + b"\0" * (-len(raw) % 4)


def build_info_bytes(
    model_id: int, origin: tuple[float, float, float], num_leaves: int, portals: Sequence[bytes]
) -> bytes:
    """A ``BuildInfo``: model DID, frame (identity rotation), leaf count, portal count, portals."""
    raw = struct.pack("<I", model_id) + frame_bytes(origin)
    return raw + struct.pack("<II", num_leaves, len(portals)) + b"".join(portals)


def landblock_info_record(
    info_id: int = LANDBLOCK_INFO_ID,
    num_cells: int = 0,
    objects: Sequence[bytes] = (),
    buildings: Sequence[bytes] = (),
    restrictions: Sequence[tuple[int, int]] | None = None,
    buckets: int = 8,
) -> bytes:
    """A ``CLandBlockInfo``: DID, cell count, object count and objects, one dword of building
    count (low 16 bits) and pack mask (high 16: bit 0 when ``restrictions`` is given), the
    buildings, then the restriction table: a dword of count (low 16) and ``buckets`` (high 16),
    and the {cell id, object iid} pairs in the given order."""
    raw = struct.pack("<III", info_id, num_cells, len(objects)) + b"".join(objects)
    pack_mask = 0 if restrictions is None else 1
    raw += struct.pack("<HH", len(buildings), pack_mask) + b"".join(buildings)
    if restrictions is not None:
        raw += struct.pack("<HH", len(restrictions), buckets)
        raw += b"".join(struct.pack("<II", cell, iid) for cell, iid in restrictions)
    return raw


# -- environments (0x0Dxxxxxx) and env cells (0xXXYY0100 +) -----------------------------------

ENVIRONMENT_ID = 0x0D000123
#: The box room of ``environment_record``: cell-local x 0..6, y 0..6, z 0..3, with a doorway
#: in the west wall (x 0) at y 2.4..3.6, z 0..2.2.
ROOM_SIZE = (6.0, 6.0, 3.0)
DOOR_Y = (2.4, 3.6)
DOOR_TOP = 2.2


def _room_vertices() -> list[tuple[float, float, float]]:
    """Box corners 0-7 (``box_corner`` of the room), then the doorway's four corners 8-11."""
    corners = [box_corner(i, (0.0, 0.0, 0.0), ROOM_SIZE) for i in range(8)]
    y0, y1 = DOOR_Y
    return [*corners, (0.0, y0, 0.0), (0.0, y1, 0.0), (0.0, y1, DOOR_TOP), (0.0, y0, DOOR_TOP)]


def _poly_bytes(poly_id: int, ids: Sequence[int], sides: int = 0, uvs: bool = False) -> bytes:
    """A ``CPolygon``: u16 id, u8 point count, u8 stippling (0 with ``uvs``, else 4 | 8: no UV
    bytes), i32 sides type, u16 pos / neg surface, u16 vertex ids, then with ``uvs`` a UV byte
    per point, and for sides type 2 (both) a second set for the negative side."""
    raw = struct.pack("<HBBi2H", poly_id, len(ids), 0 if uvs else 12, sides, 0, 0)
    raw += struct.pack(f"<{len(ids)}H", *ids)
    return raw + (bytes(len(ids) * (2 if sides == 2 else 1)) if uvs else b"")


def _plane(normal: tuple[float, float, float], d: float) -> bytes:
    return struct.pack("<4f", *normal, d)


def _cell_leaf(index: int) -> bytes:
    """A cell- or drawing-tree leaf: its tag and i32 index only."""
    return struct.pack("<Ii", type_tag("LEAF"), index)


def cell_struct_bytes(start: int, poly_ids: tuple[int, int] = (0, 1), drawing: bool = True) -> bytes:
    """One ``CCellStruct`` of the box room, written at record offset ``start`` (for the padding).

    - vertices: the 12 of ``_room_vertices`` (vertex type 1, no UVs);
    - polygons: [0] the floor (+z up, stored id ``poly_ids[0]``), [1] the doorway (facing +x,
      into the room; stored id ``poly_ids[1]``; double-sided with UV bytes); portals: [1];
    - cell BSP: ``PORT`` on the west plane (x 0, normal +x) whose pos is a chain of ``BPIn``
      nodes (east, south, north, floor) ending in ``BPnn`` (ceiling) with a ``LEAF`` 0, and
      whose neg is ``LEAF`` 1;
    - physics polygons: [0] the floor, [1] the east wall (facing -x);
    - physics BSP: ``BPnN`` (floor plane): pos ``BPnN`` (east plane: pos empty ``LEAF`` 0, neg
      ``LEAF`` 1 with physics polygon 1), neg ``LEAF`` 2 solid with physics polygon 0;
    - drawing BSP (flag dword 1): ``BPIN`` (west plane): pos ``PORT`` (same plane, leaves 0, 1;
      sphere, polygon 0, portal pair (1, 0)), neg ``LEAF`` 2; sphere; polygon 1.
    """
    sx, sy, sz = ROOM_SIZE
    vertices = _room_vertices()
    sphere = struct.pack("<4f", sx / 2, sy / 2, sz / 2, 4.5)
    raw = struct.pack("<4I", 0, 2, 2, 1)  # cellstruct id, polygons, physics polygons, portals
    raw += struct.pack("<iI", 1, len(vertices))
    for i, v in enumerate(vertices):
        raw += struct.pack("<2H", i, 0) + struct.pack("<3f", *v) + struct.pack("<3f", 0.0, 0.0, 1.0)
    floor = (0, 1, 3, 2)  # z 0, counter-clockwise seen from above
    door = (8, 9, 10, 11)  # x 0, counter-clockwise seen from +x
    raw += _poly_bytes(poly_ids[0], floor) + _poly_bytes(poly_ids[1], door, sides=2, uvs=True)
    raw += struct.pack("<H", 1)  # the portal: polygon 1 by position
    raw += b"\0" * (-(start + len(raw)) % 4)
    # cell BSP
    raw += struct.pack("<I", type_tag("PORT")) + _plane((1.0, 0.0, 0.0), 0.0)
    chain = [((-1.0, 0.0, 0.0), sx), ((0.0, 1.0, 0.0), 0.0), ((0.0, -1.0, 0.0), sy), ((0.0, 0.0, 1.0), 0.0)]
    for normal, d in chain:
        raw += struct.pack("<I", type_tag("BPIn")) + _plane(normal, d)
    raw += struct.pack("<I", type_tag("BPnn")) + _plane((0.0, 0.0, -1.0), sz) + _cell_leaf(0)
    raw += _cell_leaf(1)  # the PORT's neg child
    # physics polygons and BSP
    east = (1, 5, 7, 3)  # x 6, counter-clockwise seen from -x (inside)
    raw += _poly_bytes(0, floor) + _poly_bytes(1, east)
    raw += struct.pack("<I", type_tag("BPnN")) + _plane((0.0, 0.0, 1.0), 0.0)
    raw += struct.pack("<I", type_tag("BPnN")) + _plane((-1.0, 0.0, 0.0), sx)
    raw += struct.pack("<IiI", type_tag("LEAF"), 0, 0) + struct.pack("<4f", sx / 2, sy / 2, sz / 2, 0.0)
    raw += struct.pack("<I", 0)
    raw += struct.pack("<IiI", type_tag("LEAF"), 1, 0) + struct.pack("<4f", sx, sy / 2, sz / 2, 3.4)
    raw += struct.pack("<IH", 1, 1)
    raw += sphere  # the east node's sphere
    raw += struct.pack("<IiI", type_tag("LEAF"), 2, 1) + struct.pack("<4f", sx / 2, sy / 2, 0.0, 4.3)
    raw += struct.pack("<IH", 1, 0)
    raw += sphere  # the root's sphere
    # drawing BSP
    raw += struct.pack("<I", 1 if drawing else 0)
    if drawing:
        raw += struct.pack("<I", type_tag("BPIN")) + _plane((1.0, 0.0, 0.0), 0.0)
        raw += struct.pack("<I", type_tag("PORT")) + _plane((1.0, 0.0, 0.0), 0.0)
        raw += _cell_leaf(0) + _cell_leaf(1)
        raw += sphere + struct.pack("<II", 1, 1) + struct.pack("<H", 0) + struct.pack("<Hh", 1, 0)
        raw += _cell_leaf(2)
        raw += sphere + struct.pack("<IH", 1, 1)
    return raw + b"\0" * (-(start + len(raw)) % 4)


def environment_record(env_id: int = ENVIRONMENT_ID, structs: int = 1, **kwargs: object) -> bytes:
    """A ``CEnvironment``: DID, struct count, then ``structs`` copies of the room's cell struct
    (each written at its own offset, so the padding is the record's)."""
    raw = struct.pack("<II", env_id, structs)
    for _ in range(structs):
        raw += cell_struct_bytes(len(raw), **kwargs)  # type: ignore[arg-type]
    return raw


def cell_portal_bytes(flags: int, poly_id: int, other_cell: int, other_portal: int) -> bytes:
    """A ``CCellPortal``: u16 flags, u16 polygon id, u16 other cell number, i16 other portal."""
    return struct.pack("<HHHh", flags, poly_id, other_cell, other_portal)


def env_cell_record(
    cell_id: int,
    origin: tuple[float, float, float],
    portals: Sequence[bytes],
    env_id: int = ENVIRONMENT_ID,
    struct_index: int = 0,
    surfaces: Sequence[int] = (0x0123,),
    stabs: Sequence[int] = (),
    objects: Sequence[bytes] | None = None,
    restriction: int | None = None,
    seen_outside: bool = True,
) -> bytes:
    """A ``CEnvCell``: DID, flags (1 seen outside, 2 ``objects`` given, 8 ``restriction``), the
    cell id again, u8 surface count, u8 portal count, u16 stab count, u16 surfaces, u16
    environment number, u16 struct index, frame (identity rotation), portals, u16 stab numbers,
    [object count and {DID, frame} objects], [restriction dword]. No padding."""
    flags = 1 if seen_outside else 0
    flags |= (2 if objects is not None else 0) | (8 if restriction is not None else 0)
    raw = struct.pack("<III", cell_id, flags, cell_id)
    raw += struct.pack("<BBH", len(surfaces), len(portals), len(stabs))
    raw += struct.pack(f"<{len(surfaces)}H", *surfaces)
    raw += struct.pack("<HH", env_id & 0xFFFF, struct_index) + frame_bytes(origin)
    raw += b"".join(portals) + struct.pack(f"<{len(stabs)}H", *stabs)
    if objects is not None:
        raw += struct.pack("<I", len(objects)) + b"".join(objects)
    if restriction is not None:
        raw += struct.pack("<I", restriction)
    return raw
