"""Scenario ``[data]``: the user's retail DAT files, as a source of setups, the region's land
height table, landblock terrain and landblock static objects.

Not retail routines: the scenario keys are acphys's (README "Scenarios"); the records are read
with :mod:`acphys.dat`. Every problem, including a damaged DAT file, is a one-line
:class:`ScenarioError` naming the file and the key that needed the record.
"""

from __future__ import annotations

from pathlib import Path
from types import TracebackType
from typing import Any

from acphys.dat import REGION_ID, DatError, DatFile, unpack_landblock, unpack_region, unpack_setup
from acphys.dat.env_cell import (
    ENVIRONMENT_ID_TYPE,
    EnvCellRecord,
    EnvironmentRecord,
    make_env_cell,
    unpack_env_cell,
    unpack_environment,
)
from acphys.dat.gfxobj import GfxObjRecord, needs_setup_parts, setup_parts, setup_physics_bsp, unpack_gfxobj
from acphys.dat.landblock_info import LandBlockInfoRecord, unpack_landblock_info
from acphys.dat.motion import unpack_animation, unpack_motion_table
from acphys.dat.records import SetupRecord
from acphys.geometry.bsp import BSPTree
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.motion.animation import Animation
from acphys.motion.motion_table import MotionTable
from acphys.scenario import values as read
from acphys.scenario.values import Ctx
from acphys.setup import Setup, SetupPart
from acphys.world.env_cell import EnvCell, Environment
from acphys.world.terrain import LandBlockStruct

DATA_KEYS = ("portal", "cell")
#: ``data_set_lm`` each ``[data]`` key expects (``DATFILE_TYPE``, acclient.h:3116).
DATA_SETS = {"portal": 1, "cell": 2}
#: The retail human's setup, which the built-in ``human`` becomes with a portal DAT.
HUMAN_SETUP_ID = 0x02000001
#: The id high byte of setup records.
SETUP_ID_TYPE = 0x02
#: The id high bytes of motion-table and animation records.
MOTION_TABLE_ID_TYPE = 0x09
ANIMATION_ID_TYPE = 0x03
#: ``MasterDBMap::DivineType`` ranges of the two record types a static object's DID may name.
GFXOBJ_IDS = range(0x01000000, 0x01010000)
SETUP_IDS = range(0x02000000, 0x02010000)


class RetailData:
    """The DAT files a scenario's ``[data]`` names, open while it loads (use as a context manager).

    Records are read on first use and kept: the region's height table, setup records (each
    :meth:`setup` call returns a fresh :class:`Setup`).
    """

    def __init__(self, ctx: Ctx, portal: DatFile | None = None, cell: DatFile | None = None) -> None:
        self.ctx = ctx
        self.portal = portal
        self.cell = cell
        self._height_table: tuple[float, ...] | None = None
        self._setups: dict[int, SetupRecord] = {}
        #: Each setup's physics BSP (from its part's GfxObj), shared by the setups built from it.
        self._physics_bsps: dict[int, BSPTree | None] = {}
        #: The part descriptions of the setups ``needs_setup_parts`` picks (instead of a physics BSP).
        self._setup_parts: dict[int, list[SetupPart]] = {}
        self._animations: dict[int, Animation] = {}
        self._motion_tables: dict[int, MotionTable] = {}
        self._gfxobjs: dict[int, GfxObjRecord] = {}
        #: Each read landblock's ``lbi_exists``.
        self._lbi_exists: dict[int, int] = {}
        #: Environments as read and as made, shared by the env cells that use them.
        self._environments: dict[int, tuple[EnvironmentRecord, Environment]] = {}

    def __enter__(self) -> RetailData:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, trace: TracebackType | None
    ) -> None:
        self.close()

    def close(self) -> None:
        for dat in (self.portal, self.cell):
            if dat is not None:
                dat.close()

    def _record(self, key: str, dat: DatFile, object_id: int, what: str) -> bytes:
        """The bytes of record ``object_id``, or a ScenarioError naming ``key``."""
        try:
            if dat.lookup(object_id) is None:
                raise self.ctx.fail(key, f"no {what} {object_id:#010x} in {dat.path}")
            return dat.read(object_id)
        except DatError as error:
            raise self.ctx.fail(key, str(error)) from None

    def height_table(self, key: str) -> tuple[float, ...]:
        """The land height table of the portal's region record (0x13000000)."""
        if self.portal is None:
            raise self.ctx.fail(key, "the region's height table needs a [data] portal")
        if self._height_table is None:
            data = self._record(key, self.portal, REGION_ID, "region")
            try:
                self._height_table = unpack_region(data).height_table
            except DatError as error:
                raise self.ctx.fail(key, f"{self.portal.path}: {error}") from None
        return self._height_table

    def setup(self, key: str, setup_id: int, name: str | None = None) -> Setup:
        """The physics view of the portal's setup ``setup_id`` (named ``name``, else its id)."""
        if self.portal is None:
            raise self.ctx.fail(key, f"setup {setup_id:#010x} is a DAT setup: it needs a [data] portal")
        record = self._setups.get(setup_id)
        if record is None:
            data = self._record(key, self.portal, setup_id, "setup")
            try:
                record = unpack_setup(data)
            except DatError as error:
                raise self.ctx.fail(key, f"{self.portal.path}: {error}") from None
            if record.did != setup_id:
                raise self.ctx.fail(
                    key, f"{self.portal.path}: record {setup_id:#010x} holds setup {record.did:#010x}"
                )
            try:
                if needs_setup_parts(record):
                    self._setup_parts[setup_id] = setup_parts(record, self.portal)
                else:
                    self._physics_bsps[setup_id] = setup_physics_bsp(record, self.portal)
            except DatError as error:
                raise self.ctx.fail(key, f"{self.portal.path}: {error}") from None
            self._setups[setup_id] = record
        return record.to_setup(name, self._physics_bsps.get(setup_id), self._setup_parts.get(setup_id))

    def motion_table(self, key: str, table_id: int) -> MotionTable:
        """The portal's motion table ``table_id`` with its animations (both kept once read;
        bodies share the table, as retail bodies share the cached ``CMotionTable``)."""
        if self.portal is None:
            raise self.ctx.fail(
                key, f"motion table {table_id:#010x} is a DAT table: it needs a [data] portal"
            )
        if table_id >> 24 != MOTION_TABLE_ID_TYPE:
            raise self.ctx.fail(key, f"{table_id:#010x} is not a motion table id (they are 0x09xxxxxx)")
        table = self._motion_tables.get(table_id)
        if table is None:
            portal = self.portal
            data = self._record(key, portal, table_id, "motion table")

            def load_animation(anim_id: int) -> Animation:
                animation = self._animations.get(anim_id)
                if animation is None:
                    if anim_id >> 24 != ANIMATION_ID_TYPE:
                        raise DatError(
                            f"motion table {table_id:#010x}: {anim_id:#010x} is not an animation id"
                        )
                    if portal.lookup(anim_id) is None:
                        raise DatError(f"motion table {table_id:#010x}: no animation {anim_id:#010x}")
                    animation = unpack_animation(portal.read(anim_id))
                    self._animations[anim_id] = animation
                return animation

            try:
                table = unpack_motion_table(data, load_animation)
            except DatError as error:
                raise self.ctx.fail(key, f"{portal.path}: {error}") from None
            self._motion_tables[table_id] = table
        return table

    def default_motion_table(self, key: str, setup_id: int) -> MotionTable | None:
        """The motion table setup ``setup_id`` names (``default_mtable_id``), or None when it
        names none (id 0) or the portal holds no such record."""
        self.setup(key, setup_id)
        table_id = self._setups[setup_id].default_mtable_id
        assert self.portal is not None  # self.setup needs it
        try:
            if table_id == 0 or self.portal.lookup(table_id) is None:
                return None
        except DatError as error:
            raise self.ctx.fail(key, str(error)) from None
        return self.motion_table(key, table_id)

    def landblock(self, key: str, landblock: int) -> LandBlockStruct:
        """Landblock ``0xXXYY``'s terrain: record 0xXXYYFFFF of the cell DAT, its height bytes
        through the portal's height table."""
        if self.cell is None:
            raise self.ctx.fail(key, "terrain from the DAT needs a [data] cell")
        if self.portal is None:
            raise self.ctx.fail(
                key, "terrain from the cell DAT needs a [data] portal too (for the region's height table)"
            )
        table = self.height_table(key)
        block_id = (landblock << 16) | 0xFFFF
        data = self._record(key, self.cell, block_id, "landblock")
        try:
            record = unpack_landblock(data)
            terrain = record.to_struct(table)
        except DatError as error:
            raise self.ctx.fail(key, f"{self.cell.path}: {error}") from None
        if terrain.block_id != block_id:
            raise self.ctx.fail(
                key, f"{self.cell.path}: record {block_id:#010x} holds landblock {terrain.block_id:#010x}"
            )
        self._lbi_exists[landblock] = record.lbi_exists
        return terrain

    def landblock_info(self, key: str, landblock: int) -> LandBlockInfoRecord | None:
        """Landblock ``0xXXYY``'s objects and buildings (record 0xXXYYFFFE), or None when its
        landblock record says there is none (``lbi_exists`` 0, as ``CLandBlock::InitLoad``
        reads it) or the cell DAT holds no such record. Retail fails to load a landblock whose
        ``lbi_exists`` names a missing record; acphys loads its terrain without objects."""
        if self.cell is None:
            raise self.ctx.fail(key, "landblock objects from the DAT need a [data] cell")
        if landblock not in self._lbi_exists:
            self.landblock(key, landblock)
        info_id = (landblock << 16) | 0xFFFE
        try:
            missing = self.cell.lookup(info_id) is None
        except DatError as error:
            raise self.ctx.fail(key, str(error)) from None
        if not self._lbi_exists[landblock] or missing:
            return None
        data = self._record(key, self.cell, info_id, "landblock info")
        try:
            info = unpack_landblock_info(data)
        except DatError as error:
            raise self.ctx.fail(key, f"{self.cell.path}: {error}") from None
        if info.did != info_id:
            raise self.ctx.fail(
                key, f"{self.cell.path}: record {info_id:#010x} holds landblock info {info.did:#010x}"
            )
        return info

    def environment(self, key: str, env_id: int) -> tuple[EnvironmentRecord, Environment]:
        """The portal's environment ``env_id`` (0x0Dxxxxxx), as read and as made (kept once read)."""
        if self.portal is None:
            raise self.ctx.fail(key, f"environment {env_id:#010x} of an env cell needs a [data] portal")
        if env_id >> 24 != ENVIRONMENT_ID_TYPE:
            raise self.ctx.fail(key, f"{env_id:#010x} is not an environment id (they are 0x0Dxxxxxx)")
        found = self._environments.get(env_id)
        if found is None:
            data = self._record(key, self.portal, env_id, "environment")
            try:
                record = unpack_environment(data)
            except DatError as error:
                raise self.ctx.fail(key, f"{self.portal.path}: {error}") from None
            if record.did != env_id:
                raise self.ctx.fail(
                    key, f"{self.portal.path}: record {env_id:#010x} holds environment {record.did:#010x}"
                )
            found = (record, record.to_environment())
            self._environments[env_id] = found
        return found

    def env_cell(self, key: str, cell_id: int) -> tuple[EnvCellRecord, EnvCell]:
        """The cell DAT's env cell ``cell_id`` (0xXXYY0100 and up), as read and as made, with its
        environment from the portal DAT."""
        if self.cell is None:
            raise self.ctx.fail(key, "env cells from the DAT need a [data] cell")
        data = self._record(key, self.cell, cell_id, "env cell")
        try:
            record = unpack_env_cell(data)
        except DatError as error:
            raise self.ctx.fail(key, f"{self.cell.path}: {error}") from None
        if record.did != cell_id or record.cell_id != cell_id:
            raise self.ctx.fail(
                key,
                f"{self.cell.path}: record {cell_id:#010x} holds env cell {record.did:#010x} "
                f"(cell id {record.cell_id:#010x})",
            )
        env_record, environment = self.environment(key, record.environment_id)
        try:
            return record, make_env_cell(record, env_record, environment)
        except DatError as error:
            raise self.ctx.fail(key, f"{self.cell.path}: {error}") from None

    def object_setup(self, key: str, object_id: int) -> Setup | None:
        """The physics view of a static object's DID, as ``CPhysicsObj::InitPartArrayObject``
        makes it: a setup record (0x02000000-0x0200FFFF), or a GfxObj (0x01000000-0x0100FFFF)
        in a one-part setup (``CSetup::makeSimpleSetup``). None for DIDs of other types, of
        which retail's ``makeObject`` makes nothing. A DID with a zero high byte (retail's
        translucent ethereal "anim object" of setup ``0x02000000 | id``) is refused."""
        if object_id in SETUP_IDS:
            return self.setup(key, object_id)
        if object_id in GFXOBJ_IDS:
            return self.gfxobj_setup(key, object_id)
        if object_id >> 24 == 0:
            raise self.ctx.fail(
                key,
                f"static object {object_id:#010x} is an anim object (setup {object_id | 0x02000000:#010x} "
                "made translucent and ethereal); acphys does not make anim objects",
            )
        return None

    def gfxobj_setup(self, key: str, gfxobj_id: int) -> Setup:
        """GfxObj ``gfxobj_id`` of the portal DAT as a one-part setup: its physics BSP, and its
        physics sphere as the sorting sphere. Retail falls back to the drawing sphere for a
        GfxObj without physics data; acphys does not read drawing data, so such an object gets
        a zero sorting sphere at the origin (it has no collision shape either way).

        Retail: CSetup::makeSimpleSetup @ 0x00520090 (acclient.c:334455)
        """
        if self.portal is None:
            raise self.ctx.fail(key, f"gfxobj {gfxobj_id:#010x} is a DAT model: it needs a [data] portal")
        record = self._gfxobjs.get(gfxobj_id)
        if record is None:
            data = self._record(key, self.portal, gfxobj_id, "gfxobj")
            try:
                record = unpack_gfxobj(data)
            except DatError as error:
                raise self.ctx.fail(key, f"{self.portal.path}: {error}") from None
            if record.did != gfxobj_id:
                raise self.ctx.fail(
                    key, f"{self.portal.path}: record {gfxobj_id:#010x} holds gfxobj {record.did:#010x}"
                )
            self._gfxobjs[gfxobj_id] = record
        sphere = record.physics_sphere
        return Setup(
            name=f"{gfxobj_id:#010x}",
            physics_bsp=record.physics_bsp,
            sorting_sphere=sphere.copy() if sphere is not None else Sphere(Vector3(), 0.0),
        )


def setup_id(name: str) -> int | None:
    """The DAT setup id a setup name like ``"0x02000001"`` spells, or None for other names."""
    if not name.lower().startswith("0x"):
        return None
    try:
        return int(name, 16)
    except ValueError:
        return None


def _open(ctx: Ctx, name: str, value: Any, folder: Path) -> DatFile:
    """Open ``[data]`` key ``name`` ("portal" or "cell") and check the file's data set."""
    key = f"data.{name}"
    path = Path(read.string(ctx, key, value)).expanduser()
    if not path.is_absolute():
        path = folder / path
    try:
        dat = DatFile(path)
    except FileNotFoundError:
        raise ctx.fail(key, f"no such file {path}") from None
    except DatError as error:
        raise ctx.fail(key, str(error)) from None
    except OSError as error:
        raise ctx.fail(key, f"cannot read {path}: {error.strerror or error}") from None
    if dat.header.data_set != DATA_SETS[name]:
        dat.close()
        found = f"a {dat.header.data_set_name} DAT (data set {dat.header.data_set})"
        raise ctx.fail(key, f"{path} is {found}, not a {name} DAT")
    return dat


def read_data(ctx: Ctx, raw: Any, folder: str | Path | None = None) -> RetailData:
    """Open the DAT files of a ``[data]`` table; relative paths resolve against ``folder``
    (the scenario file's folder; the current directory when None)."""
    table = read.table(ctx, "data", raw, DATA_KEYS)
    base = Path(folder) if folder is not None else Path()
    portal = _open(ctx, "portal", table["portal"], base) if "portal" in table else None
    try:
        cell = _open(ctx, "cell", table["cell"], base) if "cell" in table else None
    except BaseException:
        if portal is not None:
            portal.close()
        raise
    return RetailData(ctx, portal, cell)
