"""Retail DAT records acphys reads: ``CSetup`` (0x02xxxxxx), ``CRegionDesc`` (0x13000000, as far
as its height table) and the ``CLandBlock`` terrain record (0xXXYYFFFF).

Every record starts with its DID (``DBObj::Serialize``; none of these types is "categorized", so
no data-category dword follows), then the class's ``UnPack`` body. Multi-byte values are
little-endian; floats are IEEE single precision (read exactly, as Python floats).

:class:`Reader`, which every record reader here and in the sibling modules uses, refuses what
only a damaged record holds and the engine could not survive: a float that is NaN or infinite,
a coordinate or length beyond :data:`MAX_COORDINATE`, a frame whose quaternion is no rotation
(:data:`MAX_QUATERNION_NORM2`), and a count larger than the bytes left could hold.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass

from acphys.dat.container import DatError
from acphys.geometry.bsp import BSPTree
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.setup import LocationType, Setup, SetupPart
from acphys.world.terrain import HEIGHT_TABLE_SIZE, NUM_VERTICES, LandBlockStruct, set_height_table

#: ``CSetup`` flag bits, the first dword of ``CSetup::UnPack``'s body.
SETUP_HAS_PARENT = 0x1
SETUP_HAS_DEFAULT_SCALE = 0x2
SETUP_ALLOW_FREE_HEADING = 0x4
SETUP_HAS_PHYSICS_BSP = 0x8
#: The only ``CRegionDesc`` version this client loads (checked in ``CRegionDesc::UnPack``).
REGION_VERSION = 3
#: The region record's id.
REGION_ID = 0x13000000
#: The largest coordinate or length a record may store, in metres. Positions are model-, cell- or
#: landblock-local (a landblock is 192 m, the whole world 255 of them), so no retail value comes
#: near 10 km; a damaged exponent (1e38) would make a body's or object's box span the world and
#: the land cells it covers past counting.
MAX_COORDINATE = 10_000.0
#: The largest squared norm of a stored frame's quaternion. A rotation's is 1 (to float32
#: rounding); retail's ``Frame::IsValid`` allows 1 +- 0.001 but unpacking ignores its answer, so
#: acphys refuses only quaternions that are no rotation at all: ``Frame.cache``'s matrix grows
#: with the squared norm, and past 2 it would stretch what the frame places (a damaged exponent
#: makes that a box kilometres across).
MAX_QUATERNION_NORM2 = 2.0


class Reader:
    """Sequential little-endian reads over one record, with DatErrors naming record and byte."""

    __slots__ = ("data", "pos", "what")

    def __init__(self, data: bytes, what: str) -> None:
        self.data = data
        self.pos = 0
        self.what = what

    def take(self, size: int) -> bytes:
        if self.pos + size > len(self.data):
            raise DatError(
                f"{self.what}: record truncated at byte {self.pos} (needs {size} more, has "
                f"{len(self.data) - self.pos})"
            )
        chunk = self.data[self.pos : self.pos + size]
        self.pos += size
        return chunk

    def unpack(self, fmt: str) -> tuple[int | float, ...]:
        """Values of struct format ``fmt``; a float that is NaN or infinite is a DatError (no
        physics quantity is, and the engine would only spread it)."""
        start = self.pos
        values = struct.unpack("<" + fmt, self.take(struct.calcsize("<" + fmt)))
        if "f" in fmt and not all(map(math.isfinite, values)):
            bad = next(v for v in values if not math.isfinite(v))
            raise DatError(f"{self.what}: the values at byte {start} hold {bad}; a DAT's floats are finite")
        return values

    def u32(self) -> int:
        return int(self.unpack("I")[0])

    def f32(self) -> float:
        return float(self.unpack("f")[0])

    def count(self, size_each: int, name: str) -> int:
        """A dword count, checked against the bytes left (a bad count is not a huge allocation)."""
        value = self.u32()
        if value * size_each > len(self.data) - self.pos:
            raise DatError(f"{self.what}: {name} count {value} at byte {self.pos - 4} overruns the record")
        return value

    def coordinates(self, count: int) -> list[float]:
        """``count`` floats that are positions or lengths: each within :data:`MAX_COORDINATE`."""
        start = self.pos
        values = [float(v) for v in self.unpack(f"{count}f")]
        if any(abs(v) > MAX_COORDINATE for v in values):
            bad = next(v for v in values if abs(v) > MAX_COORDINATE)
            raise DatError(
                f"{self.what}: the coordinates at byte {start} hold {bad:.6g}, beyond the "
                f"{MAX_COORDINATE:g} m a DAT stores (MAX_COORDINATE)"
            )
        return values

    def coordinate(self) -> float:
        """One position or length (:meth:`coordinates`)."""
        return self.coordinates(1)[0]

    def vector(self) -> Vector3:
        """A position, a direction or an extent (:meth:`coordinates`)."""
        x, y, z = self.coordinates(3)
        return Vector3(x, y, z)

    def sphere(self) -> Sphere:
        """Retail: CSphere::UnPack @ 0x0051FD20 (acclient.c:334267)"""
        center = self.vector()
        return Sphere(center, self.coordinate())

    def frame(self) -> Frame:
        """Origin, then qw qx qy qz (28 bytes).

        Retail: AFrame::UnPack @ 0x005A9FB0 (acclient.c:467618)
        """
        origin = self.vector()
        start = self.pos
        qw, qx, qy, qz = (float(v) for v in self.unpack("4f"))
        norm2 = qw * qw + qx * qx + qy * qy + qz * qz
        if norm2 > MAX_QUATERNION_NORM2:
            raise DatError(
                f"{self.what}: the quaternion at byte {start} has squared norm {norm2:.6g}, over "
                f"{MAX_QUATERNION_NORM2} (MAX_QUATERNION_NORM2): not a rotation"
            )
        return Frame(origin, qw, qx, qy, qz)

    def align(self) -> None:
        """Skip to the next multiple of 4 (records start 4-aligned in retail's buffers)."""
        self.pos += -self.pos % 4


@dataclass
class LightInfo:
    """``LIGHTINFO`` as stored in a setup."""

    frame: Frame
    color: int
    intensity: float
    falloff: float
    cone_angle: float


@dataclass
class SetupRecord:
    """A ``CSetup`` record (acclient.h:31119), every field of the stored layout."""

    did: int
    flags: int
    parts: list[int]
    parent_index: list[int]
    default_scale: list[Vector3]
    holding_locations: dict[int, LocationType]
    connection_points: dict[int, LocationType]
    #: placement id -> one frame per part (placement frames carrying animation hooks are refused).
    placement_frames: dict[int, list[Frame]]
    cylspheres: list[CylSphere]
    spheres: list[Sphere]
    height: float
    radius: float
    step_up_height: float
    step_down_height: float
    sorting_sphere: Sphere
    selection_sphere: Sphere
    lights: dict[int, LightInfo]
    default_anim_id: int
    default_script_id: int
    default_mtable_id: int
    default_stable_id: int
    default_phstable_id: int

    @property
    def allow_free_heading(self) -> bool:
        return bool(self.flags & SETUP_ALLOW_FREE_HEADING)

    @property
    def has_physics_bsp(self) -> bool:
        return bool(self.flags & SETUP_HAS_PHYSICS_BSP)

    def to_setup(
        self,
        name: str | None = None,
        physics_bsp: BSPTree | None = None,
        parts: list[SetupPart] | None = None,
    ) -> Setup:
        """The physics view of this record as an :class:`acphys.setup.Setup`.

        The physics BSP lives on the part's GfxObj (read it with
        :func:`acphys.dat.gfxobj.setup_physics_bsp` and pass it in), or, for a many-part setup,
        on the parts (read them with :func:`acphys.dat.gfxobj.setup_parts`); the motion table is
        a separate record, left unset here.
        """
        return Setup(
            name=name if name is not None else f"{self.did:#010x}",
            spheres=[s.copy() for s in self.spheres],
            cylspheres=[c.copy() for c in self.cylspheres],
            height=self.height,
            radius=self.radius,
            step_up_height=self.step_up_height,
            step_down_height=self.step_down_height,
            allow_free_heading=self.allow_free_heading,
            sorting_sphere=self.sorting_sphere.copy(),
            physics_bsp=physics_bsp,
            parts=list(parts) if parts is not None else None,
            holding_locations={
                key: LocationType(loc.part_id, loc.frame.copy())
                for key, loc in self.holding_locations.items()
            },
        )


def _locations(reader: Reader, name: str) -> dict[int, LocationType]:
    """A ``LongHash<LocationType>``: a count, then {key, part id, frame} each."""
    result: dict[int, LocationType] = {}
    for _ in range(reader.count(36, name)):
        key = reader.u32()
        part_id = reader.u32()
        result[key] = LocationType(part_id, reader.frame())
    return result


def unpack_setup(data: bytes) -> SetupRecord:
    """Parse a ``CSetup`` record.

    Order (the decompiled body's field names are shifted by its ``PackObj`` base; mapped back
    through acclient.h:31119 they read): flags; part count and ids; parent indices (flag 1);
    default scales (flag 2); holding locations; connection points; placement frames; cylspheres;
    spheres; height, radius, step-up height, step-down height; sorting sphere; selection sphere;
    lights; default animation, script, motion table, sound table and physics-script-table ids.

    Retail: CSetup::UnPack @ 0x00520C50 (acclient.c:335520)
    """
    reader = Reader(data, "setup")
    did = reader.u32()
    reader.what = f"setup {did:#010x}"
    flags = reader.u32()
    num_parts = reader.count(4, "part")
    parts = [reader.u32() for _ in range(num_parts)]
    parent_index = [reader.u32() for _ in range(num_parts)] if flags & SETUP_HAS_PARENT else []
    default_scale = [reader.vector() for _ in range(num_parts)] if flags & SETUP_HAS_DEFAULT_SCALE else []
    holding = _locations(reader, "holding location")
    connections = _locations(reader, "connection point")
    placements: dict[int, list[Frame]] = {}
    for _ in range(reader.count(8 + 28 * num_parts, "placement frame")):
        key = reader.u32()
        frames = [reader.frame() for _ in range(num_parts)]
        hooks = reader.u32()
        if hooks:
            raise DatError(
                f"{reader.what}: placement frame {key} has {hooks} animation hooks; acphys does not "
                "read animation hooks yet"
            )
        placements[key] = frames
    cylspheres = []
    for _ in range(reader.count(20, "cylsphere")):
        low_pt = reader.vector()
        radius, height = reader.coordinates(2)
        cylspheres.append(CylSphere(low_pt, radius, height))
    spheres = [reader.sphere() for _ in range(reader.count(16, "sphere"))]
    height, radius, step_up, step_down = reader.coordinates(4)
    sorting = reader.sphere()
    selection = reader.sphere()
    lights: dict[int, LightInfo] = {}
    for _ in range(reader.count(48, "light")):
        key = reader.u32()
        frame = reader.frame()
        color = reader.u32()
        intensity, falloff, cone = (float(v) for v in reader.unpack("3f"))
        lights[key] = LightInfo(frame, color, intensity, falloff, cone)
    defaults = [reader.u32() for _ in range(5)]
    return SetupRecord(
        did, flags, parts, parent_index, default_scale, holding, connections, placements,
        cylspheres, spheres, height, radius, step_up, step_down, sorting, selection, lights, *defaults,
    )  # fmt: skip


@dataclass
class RegionRecord:
    """The start of a ``CRegionDesc`` record: up to and including ``LandDefs``' height table."""

    did: int
    region_number: int
    version: int
    name: str
    #: The eight ``LandDefs`` scalars stored before the table (ACE's names: block length and
    #: width, square length, lblock length, vertices per cell, max object height, sky height,
    #: road width). Retail skips them and uses ``LandDefs::get_vars``' constants.
    land_defs_words: tuple[int, ...]
    height_table: tuple[float, ...]


def _pstring(reader: Reader) -> str:
    """A u16 length (0xFFFF: a u32 length follows), the bytes, then 4-byte alignment.

    Retail: AC1Legacy::PStringBase<char>::UnPack @ 0x004FC8C0 (acclient.c:296508)
    """
    length = int(reader.unpack("H")[0])
    if length == 0xFFFF:
        length = reader.u32()
    text = reader.take(length)
    reader.align()
    return text.decode("latin-1")


def unpack_region(data: bytes) -> RegionRecord:
    """Parse ``CRegionDesc`` as far as ``LandDefs::Land_Height_Table``.

    Retail refuses any version but 3 (with a "data files newer / older than the executable"
    popup) and passes the 256 floats to ``set_height_table``, which rejects entries outside
    [0, 800]; both raise DatError here.

    Retail: CRegionDesc::UnPack @ 0x004FF440 (acclient.c:299775)
    """
    reader = Reader(data, "region")
    did = reader.u32()
    reader.what = f"region {did:#010x}"
    region_number = reader.u32()
    version = reader.u32()
    if version != REGION_VERSION:
        newer = "newer" if version > REGION_VERSION else "older"
        raise DatError(f"{reader.what}: version {version} is {newer} than the {REGION_VERSION} retail reads")
    name = _pstring(reader)
    land_defs_words = tuple(reader.u32() for _ in range(8))
    raw = reader.unpack(f"{HEIGHT_TABLE_SIZE}f")
    try:
        table = set_height_table(float(v) for v in raw)
    except ValueError as error:
        raise DatError(f"{reader.what}: {error}") from None
    return RegionRecord(did, region_number, version, name, land_defs_words, table)


@dataclass
class LandBlockRecord:
    """A ``CLandBlock`` record: the landblock's terrain words and height bytes."""

    did: int
    #: ``CLandBlock::lbi_exists``: whether a 0xXXYYFFFE ``CLandBlockInfo`` record exists.
    lbi_exists: int
    terrain: tuple[int, ...]
    height: bytes

    def to_struct(self, height_table: tuple[float, ...] | list[float]) -> LandBlockStruct:
        """The landblock's terrain as a :class:`LandBlockStruct`, given the region's heights."""
        return LandBlockStruct(self.did, self.height, self.terrain, height_table)


def unpack_landblock(data: bytes) -> LandBlockRecord:
    """Parse a landblock: DID, ``lbi_exists``, 81 u16 terrain words, 81 height bytes, padding
    to a dword (252 bytes in all).

    Retail: CLandBlock::UnPack @ 0x0052F310 (acclient.c:351520)
    """
    reader = Reader(data, "landblock")
    did = reader.u32()
    reader.what = f"landblock {did:#010x}"
    if did & 0xFFFF != 0xFFFF:
        raise DatError(f"{reader.what}: a landblock id ends in 0xFFFF")
    lbi_exists = reader.u32()
    terrain = tuple(int(v) for v in reader.unpack(f"{NUM_VERTICES}H"))
    height = reader.take(NUM_VERTICES)
    reader.align()
    return LandBlockRecord(did, lbi_exists, terrain, height)


def landblock_terrain(data: bytes, height_table: tuple[float, ...] | list[float]) -> LandBlockStruct:
    """Parse a landblock record and build its terrain with ``height_table``.

    Retail: CLandBlockStruct::UnPack @ 0x00531FD0 (acclient.c:354108)
    """
    return unpack_landblock(data).to_struct(height_table)
