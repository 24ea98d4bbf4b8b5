"""``CPhysicsPart``: one part of a body, placed in the world, with its gfx object's bounding box.

Retail keeps a part's geometry on its ``CGfxObj``; acphys has no gfx objects, so a part reads
its setup's :class:`~acphys.setup.SetupPart` (many-part setups: that part's physics BSP, its
``gfx_bound_box`` or else the box around the BSP's polygon vertices, no drawing sphere since acphys
reads no drawing data, and ``gfxobj_scale`` starting at its ``default_scale`` as
``CPartArray::InitParts`` sets it, acclient.c:325328), or else the setup itself (a one-part
setup, its part at the setup origin):

- the bounding box (``CGfxObj::gfx_bound_box``) is the box around the vertices of the setup's
  ``physics_bsp`` polygons (retail: around the gfx object's whole vertex array); a setup without
  one gets the box around its spheres (centre ± radius) and cylspheres (``low_pt`` ± radius
  across, ``low_pt.z`` to ``low_pt.z + height`` up); a setup with neither, the zero box;
- ``physics_bsp`` is the setup's physics BSP; ``physics_sphere`` is its root sphere, as retail
  sets it (``CGfxObj::Serialize``, acclient.c:356682); ``drawing_sphere``,
  which retail takes from the drawing BSP, is here the setup's sorting sphere (None when it has
  no radius).

The box is in the part's local frame and is *not* scaled: ``GetBoundingBox`` returns the gfx
object's box as is and ``BBox::LocalToGlobal`` / ``LocalToLocal`` move it by the part's frame
only, so a scaled object shadows into cells by its unscaled box.

Collisions (``find_obj_collisions``) take the moving spheres into the part's frame at its
``gfxobj_scale.z`` and test them against the physics BSP once one overlaps ``physics_sphere``.

Divergence from ACE's ``GfxObj.FindObjCollisions`` (the decompilation wins): ACE goes on to the
BSP when ``|d|² - (r1 + r2)² < EPSILON``; the decompiled compare is lost (acclient.c:356539-356544)
but has the shape of ``CSphere::intersects`` (same deltas, same ``c0 | c2`` test), read here as
``|d|² < (r1 + r2)²``: a sphere touching ``physics_sphere`` does not reach the BSP.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import TransitionState
from acphys.geometry.bbox import BBox
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.transition.transition import InsertType

if TYPE_CHECKING:
    from acphys.geometry.bsp import BSPNode, BSPTree
    from acphys.geometry.sphere import Sphere, SphereTransition
    from acphys.setup import Setup, SetupPart


def _bsp_vertices(node: BSPNode | None, out: list[Vector3]) -> None:
    if node is None:
        return
    for poly in node.polys:
        out.extend(getattr(poly, "vertices", ()))
    _bsp_vertices(node.pos_node, out)
    _bsp_vertices(node.neg_node, out)


def bsp_bound_box(bsp: BSPTree | None) -> BBox:
    """The box around the vertices of ``bsp``'s polygons (the zero box without a tree)."""
    points: list[Vector3] = []
    if bsp is not None:
        _bsp_vertices(bsp.root_node, points)
    return BBox.around(points)


def gfx_bound_box(setup: Setup) -> BBox:
    """The one-part setup's local bounding box from ``setup`` (see the module docstring)."""
    if setup.physics_bsp is not None:
        return bsp_bound_box(setup.physics_bsp)
    points: list[Vector3] = []
    for sphere in setup.spheres:
        r = Vector3(sphere.radius, sphere.radius, sphere.radius)
        points += [sphere.center - r, sphere.center + r]
    for cyl in setup.cylspheres:
        low = cyl.low_pt
        points += [
            Vector3(low.x - cyl.radius, low.y - cyl.radius, low.z),
            Vector3(low.x + cyl.radius, low.y + cyl.radius, low.z + cyl.height),
        ]
    return BBox.around(points)


class PhysicsPart:
    """Retail ``CPhysicsPart`` (acclient.h): a part's position, scale and gfx-object data.

    ``pos`` is the part's position: the body's cell id (``CPartArray::SetCellID``) and the body's
    frame combined with the part's animation or placement frame (``CPartArray::UpdateParts``).
    ``gfxobj_scale`` is the body's scale times the part's default scale
    (``CPartArray::SetScaleInternal``); the collision code reads it, the cell code does not.
    ``part`` is the setup's part description (None: the setup is the one part).

    Retail: CPhysicsPart::makePhysicsPart @ 0x0050E760 (acclient.c:315550)
    """

    __slots__ = ("bounding_box", "drawing_sphere", "gfxobj_scale", "physics_bsp", "physics_sphere", "pos")

    def __init__(self, setup: Setup, part: SetupPart | None = None) -> None:
        self.pos = Position()
        if part is not None:
            self.gfxobj_scale = part.default_scale.copy()
            box = part.bounding_box
            self.bounding_box = BBox(box.min, box.max) if box is not None else bsp_bound_box(part.physics_bsp)
            self.physics_bsp: BSPTree | None = part.physics_bsp
            self.physics_sphere: Sphere | None = (
                part.physics_bsp.get_sphere() if part.physics_bsp is not None else None
            )
            self.drawing_sphere: Sphere | None = None
            return
        self.gfxobj_scale = Vector3(1.0, 1.0, 1.0)
        self.bounding_box = gfx_bound_box(setup)
        self.physics_bsp = setup.physics_bsp
        self.physics_sphere = setup.physics_bsp.get_sphere() if setup.physics_bsp is not None else None
        sorting = setup.sorting_sphere
        self.drawing_sphere = sorting if sorting.radius > 0.0 else None

    def __repr__(self) -> str:
        return f"PhysicsPart({self.pos!r}, box={self.bounding_box!r})"

    def get_bounding_box(self) -> BBox:
        """The gfx object's box, local to the part and unscaled (not a copy).

        Retail: CPhysicsPart::GetBoundingBox @ 0x0050D600 (acclient.c:314453)
        """
        return self.bounding_box

    def always_2d(self) -> bool:
        """Whether the part is drawn as a sprite; retail asks its degrade info (first degrade's
        mode other than 1). acphys parts have no degrade info, so never.

        Retail: CPhysicsPart::Always2D @ 0x0050D8A0 (acclient.c:314641)
        """
        return False

    def get_sphere(self) -> Sphere | None:
        """The physics sphere, else the drawing sphere (what the env-cell portal tests read,
        acclient.c:348194-348195 and 348454-348457)."""
        return self.physics_sphere if self.physics_sphere is not None else self.drawing_sphere

    def find_obj_collisions(self, transition: SphereTransition) -> TransitionState:
        """Collide the moving spheres with the part's physics BSP: OK without one; otherwise the
        spheres are cached in the part's frame (``pos``) at ``gfxobj_scale.z`` and
        :func:`gfx_find_obj_collisions` runs at that scale.

        Retail: CPhysicsPart::find_obj_collisions @ 0x0050D8D0 (acclient.c:314655)
        """
        if self.physics_bsp is None:
            return TransitionState.OK
        scale = self.gfxobj_scale.z
        transition.sphere_path.cache_localspace_sphere(self.pos, scale)
        return gfx_find_obj_collisions(self, transition, scale)


def gfx_find_obj_collisions(part: PhysicsPart, transition: SphereTransition, scale: float) -> TransitionState:
    """The gfx object's half of a part collision (``part`` holds the gfx data): OK unless one of
    the ``localspace_sphere`` overlaps ``physics_sphere`` (strictly, see the module docstring); then
    an initial placement asks the BSP's ``placement_insert``, anything else its
    ``find_collisions`` at ``scale``.

    Retail: CGfxObj::find_obj_collisions @ 0x00534700 (acclient.c:356514)
    """
    bsp, bound = part.physics_bsp, part.physics_sphere
    if bsp is None or bound is None:
        raise ValueError(f"{part!r} has no physics BSP to collide with")
    path = transition.sphere_path
    if not any(bound.intersects(sphere) for sphere in path.localspace_sphere):
        return TransitionState.OK
    if path.insert_type == InsertType.INITIAL_PLACEMENT:
        return bsp.placement_insert(transition)
    return bsp.find_collisions(transition, scale)
