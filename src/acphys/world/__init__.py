"""The world a body moves through: cells, the clocks, and the player object."""

from acphys.world.world import ObjCell, World

__all__ = ["ObjCell", "World"]
