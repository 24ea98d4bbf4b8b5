"""Reading the user's retail DAT files: the container (:mod:`acphys.dat.container`) and the
records acphys needs: setups, the region and landblocks (:mod:`acphys.dat.records`), GfxObj
physics trees (:mod:`acphys.dat.gfxobj`), animations and motion tables (:mod:`acphys.dat.motion`),
landblock info (:mod:`acphys.dat.landblock_info`) and indoor cells (:mod:`acphys.dat.env_cell`)."""

from __future__ import annotations

from acphys.dat.container import DatEntry, DatError, DatFile, DatHeader, DatNode
from acphys.dat.env_cell import unpack_env_cell, unpack_environment
from acphys.dat.gfxobj import GfxObjRecord, needs_setup_parts, setup_parts, setup_physics_bsp, unpack_gfxobj
from acphys.dat.motion import unpack_animation, unpack_motion_table
from acphys.dat.records import (
    REGION_ID,
    LandBlockRecord,
    RegionRecord,
    SetupRecord,
    landblock_terrain,
    unpack_landblock,
    unpack_region,
    unpack_setup,
)

__all__ = [
    "REGION_ID",
    "DatEntry",
    "DatError",
    "DatFile",
    "DatHeader",
    "DatNode",
    "GfxObjRecord",
    "LandBlockRecord",
    "RegionRecord",
    "SetupRecord",
    "landblock_terrain",
    "needs_setup_parts",
    "setup_parts",
    "setup_physics_bsp",
    "unpack_animation",
    "unpack_env_cell",
    "unpack_environment",
    "unpack_gfxobj",
    "unpack_landblock",
    "unpack_motion_table",
    "unpack_region",
    "unpack_setup",
]
