"""``CSetup``: a body's archetype: its collision shapes, size, step heights and motion table."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32, pack4, unpack4

if TYPE_CHECKING:
    from acphys.geometry.bbox import BBox
    from acphys.geometry.bsp import BSPTree
    from acphys.motion.motion_table import MotionTable


@dataclass
class LocationType:
    """Retail ``LocationType``: a holding location or connection point, a part (0xFFFFFFFF: the
    whole object) and a frame relative to it."""

    part_id: int
    frame: Frame


@dataclass
class SetupPart:
    """One part of a many-part setup: what retail reads from ``CSetup::parts[i]`` (its
    ``CGfxObj``'s physics BSP and ``gfx_bound_box``), ``default_scale[i]`` and frame ``i`` of the
    default placement (``placement_frames`` id 0x65, else 0, as ``CPartArray::SetPlacementFrame``
    picks it). The placement frame is in the body's frame, the box in the part's; both unscaled.
    """

    physics_bsp: BSPTree | None = None
    #: ``gfx_bound_box``; None: the box around the physics BSP's polygon vertices (zero box without one).
    bounding_box: BBox | None = None
    default_scale: Vector3 = field(default_factory=lambda: Vector3(1.0, 1.0, 1.0))
    placement_frame: Frame = field(default_factory=Frame)


@dataclass
class Setup:
    """Retail ``CSetup`` (acclient.h:31119): the parts of it the physics reads.

    Shapes are in the body's local frame, before scaling; ``CPartArray``
    scales ``height``, ``radius`` and the step heights by the body's scale.
    Those four are ``float`` fields, stored as float32 when the setup is made.
    ``physics_bsp`` is the solid geometry of a one-part object (retail keeps
    it on the part's ``CGfxObj``; ``has_physics_bsp`` says whether there is one).
    ``motion_table`` stands for ``default_mtable_id``.

    ``parts``, when given, describes every part (retail ``num_parts`` parts); then
    ``physics_bsp`` must stay None and the setup has a physics BSP when any part has one.
    Without it the setup has one part at the origin, unscaled, made from ``physics_bsp``.
    """

    name: str
    spheres: list[Sphere] = field(default_factory=list)
    cylspheres: list[CylSphere] = field(default_factory=list)
    height: float = 0.0
    radius: float = 0.0
    step_up_height: float = 0.0
    step_down_height: float = 0.0
    physics_bsp: BSPTree | None = None
    #: ``allow_free_heading``: the sweep may turn the body to its end heading at once (FREE_ROTATE).
    allow_free_heading: bool = False
    #: ``sorting_sphere``: what a body without cylspheres shadows into cells with (local, unscaled).
    sorting_sphere: Sphere = field(default_factory=lambda: Sphere(Vector3(), 0.0))
    motion_table: MotionTable | None = None
    parts: list[SetupPart] | None = None
    #: ``holding_locations``: where a held object goes, by location id (``CSetup::GetHoldingLocation``).
    holding_locations: dict[int, LocationType] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.height, self.radius, self.step_up_height, self.step_down_height = unpack4(
            pack4(self.height, self.radius, self.step_up_height, self.step_down_height)
        )
        if self.parts is None:
            return
        if not self.parts:
            raise ValueError(f"setup {self.name!r}: parts is empty (leave it None for a one-part setup)")
        if self.physics_bsp is not None:
            raise ValueError(f"setup {self.name!r}: physics_bsp is for one-part setups; give it to a part")

    @property
    def has_physics_bsp(self) -> bool:
        """Retail ``CSetup::has_physics_bsp``."""
        if self.parts is not None:
            return any(part.physics_bsp is not None for part in self.parts)
        return self.physics_bsp is not None


def human_setup() -> Setup:
    """The retail human (setup 0x02000001, shared by 0x0200004E): two spheres of radius 0.48 at
    z 0.475 and 1.35, step-up height 0.6 and step-down height 1.5.

    acphys ships no DAT; these values are public dumps of the record: holtburger's census of the
    end-of-retail client_portal.dat (merklejerk/holtburger, docs/plans/
    holtburger-3d-host-physics-recovery-plan.md, and its PLAYER_STEP_UP_HEIGHT /
    PLAYER_STEP_DOWN_HEIGHT in crates/holtburger-world/src/spatial/physics.rs), which give the
    spheres, the step heights and the height 1.835, as do OpenAC's player-body tests (a fork of
    acdream). The setup's own radius field and sorting sphere stay stand-ins: radius 0.48 (the
    spheres'; one dump gives 0.679) and the smallest sphere around the two. A ``[data]`` portal
    gives the record itself.
    """
    spheres = [Sphere(Vector3(0.0, 0.0, 0.475), 0.48), Sphere(Vector3(0.0, 0.0, 1.35), 0.48)]
    return Setup(
        name="human",
        spheres=spheres,
        height=1.835,
        radius=0.48,
        step_up_height=0.6,
        step_down_height=1.5,
        sorting_sphere=bounding_sphere(spheres),
    )


def bounding_sphere(spheres: list[Sphere]) -> Sphere:
    """The sphere around the first and last of ``spheres`` (exact for two; a zero sphere for none)."""
    if not spheres:
        return Sphere(Vector3(), 0.0)
    first, last = spheres[0], spheres[-1]
    gap = (last.center - first.center).length()
    if gap + last.radius <= first.radius:
        return first.copy()
    if gap + first.radius <= last.radius:
        return last.copy()
    radius = (gap + first.radius + last.radius) / 2.0
    direction = (last.center - first.center) / gap
    center = first.center + direction * (radius - first.radius)
    enclosing = Sphere(center, radius)
    for sphere in spheres[1:-1]:
        enclosing.radius = f32(max(enclosing.radius, (sphere.center - center).length() + sphere.radius))
    return enclosing


#: Built-in setups by scenario name.
BUILTIN_SETUPS = {"human": human_setup}
