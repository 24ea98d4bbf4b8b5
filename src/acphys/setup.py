"""``CSetup``: a body's archetype: its collision shapes, size, step heights and motion table."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3

if TYPE_CHECKING:
    from acphys.geometry.bsp import BSPTree
    from acphys.motion.motion_table import MotionTable


@dataclass
class Setup:
    """Retail ``CSetup`` (acclient.h:31119): the parts of it the physics reads.

    Shapes are in the body's local frame, before scaling; ``CPartArray``
    scales ``height``, ``radius`` and the step heights by the body's scale.
    ``physics_bsp`` is the solid geometry of a one-part object (retail keeps
    it on the part's ``CGfxObj``; ``has_physics_bsp`` says whether there is one).
    ``motion_table`` stands for ``default_mtable_id``.
    """

    name: str
    spheres: list[Sphere] = field(default_factory=list)
    cylspheres: list[CylSphere] = field(default_factory=list)
    height: float = 0.0
    radius: float = 0.0
    step_up_height: float = 0.0
    step_down_height: float = 0.0
    physics_bsp: BSPTree | None = None
    motion_table: MotionTable | None = None

    @property
    def has_physics_bsp(self) -> bool:
        """Retail ``CSetup::has_physics_bsp``."""
        return self.physics_bsp is not None


def human_setup() -> Setup:
    """The retail human (setup 0x02000001): two spheres of radius 0.48 at z 0.475 and 1.35.

    Its height, radius and step heights are DAT data acphys does not ship;
    scenarios set them where they matter.
    """
    return Setup(
        name="human",
        spheres=[Sphere(Vector3(0.0, 0.0, 0.475), 0.48), Sphere(Vector3(0.0, 0.0, 1.35), 0.48)],
    )


#: Built-in setups by scenario name.
BUILTIN_SETUPS = {"human": human_setup}
