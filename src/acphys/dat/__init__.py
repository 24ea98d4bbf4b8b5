"""Reading the user's retail DAT files: the container (:mod:`acphys.dat.container`) and the
records acphys needs (:mod:`acphys.dat.records`)."""

from __future__ import annotations

from acphys.dat.container import DatEntry, DatError, DatFile, DatHeader, DatNode
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
    "LandBlockRecord",
    "RegionRecord",
    "SetupRecord",
    "landblock_terrain",
    "unpack_landblock",
    "unpack_region",
    "unpack_setup",
]
