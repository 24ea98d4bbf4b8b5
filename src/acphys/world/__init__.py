"""The world a body moves through: landblocks, cells, the clocks, and the player object."""

from acphys.world.landblock import LandBlock, Landscape
from acphys.world.obj_cell import ObjCell
from acphys.world.world import World

__all__ = ["LandBlock", "Landscape", "ObjCell", "World"]
