"""Collision geometry: planes, polygons, spheres, cylinders and the physics BSP."""

from acphys.geometry.bsp import BSPLeaf, BSPNode, BSPTree
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.plane import Plane, Ray, Sidedness
from acphys.geometry.polygon import Polygon, SidesType
from acphys.geometry.sphere import Sphere

__all__ = [
    "BSPLeaf",
    "BSPNode",
    "BSPTree",
    "CylSphere",
    "Plane",
    "Polygon",
    "Ray",
    "Sidedness",
    "SidesType",
    "Sphere",
]
