"""``CSetup``: a body's archetype, here its collision spheres and step heights."""

from __future__ import annotations

from dataclasses import dataclass, field

from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3


@dataclass
class Setup:
    """Retail ``CSetup`` (acclient.h:31119): the parts of it the physics reads.

    ``spheres`` are in the body's local frame (before ``m_scale``).
    """

    name: str
    spheres: list[Sphere] = field(default_factory=list)
    step_up_height: float = 0.0
    step_down_height: float = 0.0


def human_setup() -> Setup:
    """The retail human (setup 0x02000001): two spheres of radius 0.48 at z 0.475 and 1.35.

    Its step heights are filled in with the collision sweep, which is their only reader.
    """
    return Setup(
        name="human",
        spheres=[Sphere(Vector3(0.0, 0.0, 0.475), 0.48), Sphere(Vector3(0.0, 0.0, 1.35), 0.48)],
    )


#: Built-in setups by scenario name.
BUILTIN_SETUPS = {"human": human_setup}
