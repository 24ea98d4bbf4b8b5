"""Collision geometry: planes, spheres, and (with later issues) polygons, cylinders and BSPs."""

from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere

__all__ = ["Plane", "Sphere"]
