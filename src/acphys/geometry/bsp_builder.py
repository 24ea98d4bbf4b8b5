"""Build physics BSPs of the retail shape from convex solids (boxes or closed convex meshes).

Layout, as the retail queries read it (``BSPNODE``/``BSPLEAF`` in ``acphys.geometry.bsp``):

- every interior node splits on one face plane of the solid, outward normal, and has both
  children (the physics queries call ``pos_node`` and ``neg_node`` unchecked);
- the positive side of a face plane is outside: it gets an empty leaf (no polygons, not solid);
- the negative side goes on to the next face plane; after the last plane sits the solid leaf,
  flagged ``solid`` and holding every face of the solid. Interior nodes hold no polygons: a
  physics BSP node packs only its plane and sphere (``BSPNODE::Pack`` with ``pack_tree_type`` 1,
  acclient.c:363142), while a physics leaf packs ``solid``, its sphere and its polygon ids
  (``BSPLEAF::PackLeaf``, acclient.c:364091);
- every node's sphere bounds all polygon vertices below it; an empty leaf's is radius 0.

A union of solids nests them: each empty leaf of the tree so far is replaced by a fresh tree of
the next solid, so a point outside the earlier solids is classified by the later ones. The tree
grows as the product of the face counts; it is meant for a few solids.

Faces are ``acphys.geometry.polygon.Polygon`` objects (vertices counter-clockwise seen from
outside, so the plane faces out); they are shared, not copied, between a solid's leaves.

The tree is data of the shape a DAT holds, so it is float32 throughout: vertices are float32
``Vector3`` values, each face's plane is the one ``CPolygon::make_plane`` derives from them (as
``CPolygon::UnPack`` does, acclient.c:359911), splitting planes are those face planes, and node
spheres have float32 centres and radii, each radius rounded up to the next float32 so that the
sphere still holds every vertex below it.
"""

from __future__ import annotations

import struct
from collections.abc import Sequence

from acphys.constants import EPSILON
from acphys.geometry.bsp import NODE_TYPE_BOTH_CHILDREN, BSPLeaf, BSPNode, BSPTree
from acphys.geometry.plane import Plane
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import f32

_F32_BITS = struct.Struct("<f")
_U32 = struct.Struct("<I")


def box_faces(box_min: Vector3, box_max: Vector3) -> list[Polygon]:
    """The six faces of an axis-aligned box, normals outward."""
    lo, hi = box_min, box_max
    if not (lo.x < hi.x and lo.y < hi.y and lo.z < hi.z):
        raise ValueError(f"box min {lo!r} must be below max {hi!r} on every axis")

    def v(x: float, y: float, z: float) -> Vector3:
        return Vector3(x, y, z)

    return [
        Polygon([v(hi.x, lo.y, lo.z), v(hi.x, hi.y, lo.z), v(hi.x, hi.y, hi.z), v(hi.x, lo.y, hi.z)]),  # +x
        Polygon([v(lo.x, lo.y, lo.z), v(lo.x, lo.y, hi.z), v(lo.x, hi.y, hi.z), v(lo.x, hi.y, lo.z)]),  # -x
        Polygon([v(lo.x, hi.y, lo.z), v(lo.x, hi.y, hi.z), v(hi.x, hi.y, hi.z), v(hi.x, hi.y, lo.z)]),  # +y
        Polygon([v(lo.x, lo.y, lo.z), v(hi.x, lo.y, lo.z), v(hi.x, lo.y, hi.z), v(lo.x, lo.y, hi.z)]),  # -y
        Polygon([v(lo.x, lo.y, hi.z), v(hi.x, lo.y, hi.z), v(hi.x, hi.y, hi.z), v(lo.x, hi.y, hi.z)]),  # +z
        Polygon([v(lo.x, lo.y, lo.z), v(lo.x, hi.y, lo.z), v(hi.x, hi.y, lo.z), v(hi.x, lo.y, lo.z)]),  # -z
    ]


def _check_convex(faces: Sequence[Polygon]) -> None:
    if len(faces) < 4:
        raise ValueError(f"a closed convex solid needs at least 4 faces, got {len(faces)}")
    for face in faces:
        if len(face.vertices) < 3:
            raise ValueError(f"face {face!r} has fewer than 3 vertices")
    for face in faces:
        n, d = face.plane.N, face.plane.d
        for other in faces:
            for p in other.vertices:
                if n.dot(p) + d > EPSILON:
                    raise ValueError(
                        f"faces are not a convex solid with outward normals: vertex {p!r} lies "
                        f"{n.dot(p) + d:.6g} in front of the plane of {face!r}"
                    )


def _distinct_planes(faces: Sequence[Polygon]) -> list[Plane]:
    planes: list[Plane] = []
    for face in faces:
        plane = face.plane
        if not any((plane.N - q.N).length() < 1e-9 and abs(plane.d - q.d) < 1e-9 for q in planes):
            planes.append(plane)
    return planes


def _convex_chain(faces: Sequence[Polygon], planes: Sequence[Plane]) -> BSPNode:
    node: BSPNode = BSPLeaf(solid=True, polys=list(faces))
    for plane in reversed(planes):
        node = BSPNode(plane, pos_node=BSPLeaf(), neg_node=node, type=NODE_TYPE_BOTH_CHILDREN)
    return node


def _graft(node: BSPNode, faces: Sequence[Polygon], planes: Sequence[Plane]) -> BSPNode:
    """``node`` with every empty leaf replaced by a fresh chain of the solid ``faces``."""
    if isinstance(node, BSPLeaf):
        return node if node.polys else _convex_chain(faces, planes)
    assert node.pos_node is not None and node.neg_node is not None
    node.pos_node = _graft(node.pos_node, faces, planes)
    node.neg_node = _graft(node.neg_node, faces, planes)
    return node


def _f32_at_least(value: float) -> float:
    """The smallest float32 not below ``value`` (``value`` finite and not negative)."""
    narrowed = f32(value)
    if narrowed >= value:
        return narrowed
    return _F32_BITS.unpack(_U32.pack(_U32.unpack(_F32_BITS.pack(narrowed))[0] + 1))[0]


def _bounding_sphere(points: Sequence[Vector3]) -> Sphere:
    lo = Vector3(min(p.x for p in points), min(p.y for p in points), min(p.z for p in points))
    hi = Vector3(max(p.x for p in points), max(p.y for p in points), max(p.z for p in points))
    center = (lo + hi) * 0.5
    reach = max(
        ((p.x - center.x) ** 2 + (p.y - center.y) ** 2 + (p.z - center.z) ** 2) ** 0.5 for p in points
    )
    return Sphere(center, _f32_at_least(reach))


def _finish(node: BSPNode, leaves: list[BSPLeaf]) -> list[Vector3]:
    """Number the leaves depth first (positive side first) and set every sphere; returns the
    vertices below ``node``."""
    if isinstance(node, BSPLeaf):
        node.leaf_index = len(leaves)
        leaves.append(node)
        points = [p for face in node.polys for p in face.vertices]
    else:
        assert node.pos_node is not None and node.neg_node is not None
        points = _finish(node.pos_node, leaves) + _finish(node.neg_node, leaves)
    if points:
        node.sphere = _bounding_sphere(points)
    return points


def _place_empty_spheres(node: BSPNode, center: Vector3) -> None:
    if isinstance(node, BSPLeaf):
        if not node.polys:
            node.sphere = Sphere(center, 0.0)
        return
    assert node.pos_node is not None and node.neg_node is not None
    _place_empty_spheres(node.pos_node, node.sphere.center)
    _place_empty_spheres(node.neg_node, node.sphere.center)


def build_union_tree(solids: Sequence[Sequence[Polygon]]) -> BSPTree:
    """A physics BSP of the union of closed convex solids, each given as its faces.

    Raises ``ValueError`` for no solids or a solid that is not convex with outward faces.
    """
    if not solids:
        raise ValueError("need at least one solid")
    root: BSPNode | None = None
    for faces in solids:
        _check_convex(faces)
        planes = _distinct_planes(faces)
        root = _convex_chain(faces, planes) if root is None else _graft(root, faces, planes)
    assert root is not None
    _finish(root, [])
    _place_empty_spheres(root, root.sphere.center)
    return BSPTree(root)


def build_convex_tree(faces: Sequence[Polygon]) -> BSPTree:
    """A physics BSP of one closed convex solid given as its faces."""
    return build_union_tree([faces])


def build_box_tree(box_min: Vector3, box_max: Vector3) -> BSPTree:
    """A physics BSP of one axis-aligned box."""
    return build_convex_tree(box_faces(box_min, box_max))


def build_boxes_tree(boxes: Sequence[tuple[Vector3, Vector3]]) -> BSPTree:
    """A physics BSP of the union of axis-aligned boxes ``(min, max)``."""
    return build_union_tree([box_faces(lo, hi) for lo, hi in boxes])
