"""Build physics BSPs of the retail shape from convex solids (boxes or closed convex meshes).

Layout, as the retail queries read it (``BSPNODE``/``BSPLEAF`` in ``acphys.geometry.bsp``):

- every interior node of a solid's chain splits on one face plane of the solid, outward normal,
  and has both children (the physics queries call ``pos_node`` and ``neg_node`` unchecked);
- the positive side of a face plane is outside: it gets an empty leaf (no polygons, not solid);
- the negative side goes on to the next face plane; after the last plane sits the solid leaf,
  flagged ``solid`` and holding every face of the solid. Interior nodes hold no polygons: a
  physics BSP node packs only its plane and sphere (``BSPNODE::Pack`` with ``pack_tree_type`` 1,
  acclient.c:363142), while a physics leaf packs ``solid``, its sphere and its polygon ids
  (``BSPLEAF::PackLeaf``, acclient.c:364091);
- every node's sphere bounds all polygon vertices below it; an empty leaf's is radius 0.

A union of solids is built in two ways, both of the shape above:

- solids an axis-aligned plane parts (every solid wholly on one side, touching allowed, both sides
  non-empty) are parted: a node on that plane, each side built on its own. Of the planes that
  part them the most even split is taken, so N separate solids give a tree of depth O(log N),
  built in O(N log N). The plane is the outer face of the side holding the solid listed first,
  and that side is negative: a query straddling it visits the later solids first, as nesting
  does;
- solids no axis-aligned plane parts (overlapping ones, or separate ones arranged like a
  pinwheel) nest: the chain of the first solid, and in place of the empty leaf off each of its
  planes a tree of the remaining solids that reach past that plane (not wholly behind it, nor
  wholly in front of one of the chain's earlier planes), so a point outside the first solid is
  classified by the later ones. Nesting grows with every overlapping solid;
  :data:`MAX_BSP_NODES` and :data:`MAX_BSP_DEPTH` bound it.

Faces are ``acphys.geometry.polygon.Polygon`` objects (vertices counter-clockwise seen from
outside, so the plane faces out); they are shared, not copied, between a solid's leaves.

The tree is data of the shape a DAT holds, so it is float32 throughout: vertices are float32
``Vector3`` values, each face's plane is the one ``CPolygon::make_plane`` derives from them (as
``CPolygon::UnPack`` does, acclient.c:359911), splitting planes are those face planes or axis
planes through a vertex coordinate (exact in float32), and node spheres have float32 centres
and radii, each radius rounded up to the next float32 so that the sphere still holds every
vertex below it.
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

#: Most faces one solid may have: its chain is a level a distinct face plane, and checking it is
#: convex tests every face against every corner. 256 faces draw a 128-sided prism or a fine dome.
MAX_SOLID_FACES = 256
#: Most corners (vertices counted once a face) one solid's faces may have in all: with
#: :data:`MAX_SOLID_FACES` it bounds the convexity check to some 520,000 tests (a tenth of a
#: second); a prism of the most faces (254 sides) has 1,524.
MAX_SOLID_CORNERS = 2_048
#: Most nodes a union's tree may have: separate boxes take 14 a box, so this holds some 3,500 of
#: them (about 20 MB of Python objects, a second or two to build); it stops a union of
#: overlapping solids, whose nesting can multiply with every one, before it eats memory or time.
MAX_BSP_NODES = 50_000
#: Most solids one union may have: separate, their trees (14 nodes a box) stay within
#: :data:`MAX_BSP_NODES`, and their faces (about 5 KB a box) within some 15 MB.
MAX_UNION_SOLIDS = 3_000
#: Most corners the solids of one union may have in all (3,000 boxes have 72,000): it bounds the
#: checks and chains of many large solids to a few seconds.
MAX_UNION_CORNERS = 100_000
#: Deepest a union's tree may be: the queries (``acphys.geometry.bsp``) recurse once a level and
#: this builder at most twice, within Python's default limit of 1,000 frames with the caller's
#: own frames beneath. Retail's trees are a few dozen deep; one solid's chain is at most 256.
MAX_BSP_DEPTH = 300

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
    if len(faces) > MAX_SOLID_FACES:
        raise ValueError(f"a solid has at most {MAX_SOLID_FACES} faces (MAX_SOLID_FACES), got {len(faces)}")
    corners = sum(len(face.vertices) for face in faces)
    if corners > MAX_SOLID_CORNERS:
        raise ValueError(
            f"a solid's faces have at most {MAX_SOLID_CORNERS} corners in all (MAX_SOLID_CORNERS), "
            f"got {corners}"
        )
    for face in faces:
        if len(face.vertices) < 3:
            raise ValueError(f"face {face!r} has fewer than 3 vertices")
    points = list(dict.fromkeys((p.x, p.y, p.z) for face in faces for p in face.vertices))
    for face in faces:
        n, d = face.plane.N, face.plane.d
        nx, ny, nz = n.x, n.y, n.z
        if max(nx * x + ny * y + nz * z for x, y, z in points) + d > EPSILON:
            p = next(p for other in faces for p in other.vertices if n.dot(p) + d > EPSILON)
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


def _f32_at_least(value: float) -> float:
    """The smallest float32 not below ``value`` (``value`` finite and not negative)."""
    narrowed = f32(value)
    if narrowed >= value:
        return narrowed
    return _F32_BITS.unpack(_U32.pack(_U32.unpack(_F32_BITS.pack(narrowed))[0] + 1))[0]


class SolidError(ValueError):
    """A solid of a union that is not a closed convex solid; ``index`` is its place in the list."""

    def __init__(self, index: int, problem: str) -> None:
        super().__init__(problem)
        self.index = index


class _Solid:
    """One solid of a union: its faces, distinct face planes, distinct vertices (coordinate
    triples), bounds per axis and bounding sphere."""

    __slots__ = ("faces", "hi", "lo", "planes", "points", "sphere")

    def __init__(self, faces: Sequence[Polygon]) -> None:
        _check_convex(faces)
        self.faces = list(faces)
        self.planes = _distinct_planes(faces)
        self.points = list(dict.fromkeys((p.x, p.y, p.z) for face in faces for p in face.vertices))
        axes = list(zip(*self.points, strict=True))
        self.lo = tuple(min(values) for values in axes)
        self.hi = tuple(max(values) for values in axes)
        self.sphere = _bounding_sphere([self])

    def span(self, plane: Plane) -> tuple[float, float]:
        """The least and greatest distance of a vertex from ``plane``."""
        n, d = plane.N, plane.d
        dists = [n.z * z + n.y * y + n.x * x + d for x, y, z in self.points]
        return min(dists), max(dists)


def _bounding_sphere(solids: Sequence[_Solid]) -> Sphere:
    """The sphere about the middle of the vertices' bounds, out to the farthest vertex."""
    lo = Vector3(*(min(s.lo[axis] for s in solids) for axis in range(3)))
    hi = Vector3(*(max(s.hi[axis] for s in solids) for axis in range(3)))
    center = (lo + hi) * 0.5
    cx, cy, cz = center.x, center.y, center.z
    reach = max(
        ((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) ** 0.5 for s in solids for x, y, z in s.points
    )
    return Sphere(center, _f32_at_least(reach))


class _Group:
    """Solids to build one subtree of: in listing order, and sorted by their low bound on each
    axis (sorted once for the whole union; subsets keep the order)."""

    __slots__ = ("by_axis", "solids")

    def __init__(self, solids: list[_Solid], by_axis: Sequence[list[_Solid]]) -> None:
        self.solids = solids
        self.by_axis = by_axis

    def subset(self, members: list[_Solid]) -> _Group:
        keep = set(map(id, members))
        return _Group(members, [[s for s in order if id(s) in keep] for order in self.by_axis])


_AXES = (Vector3(1.0, 0.0, 0.0), Vector3(0.0, 1.0, 0.0), Vector3(0.0, 0.0, 1.0))


def _axis_split(group: _Group) -> tuple[Plane, list[_Solid], list[_Solid]] | None:
    """The axis plane parting ``group`` most evenly, with the solids behind it and those in front
    (the first listed solid behind), or None when no axis plane parts it."""
    count = len(group.solids)
    best: tuple[int, int, int, float] | None = None  # larger side, axis, solids below, plane
    for axis, order in enumerate(group.by_axis):
        reach = order[0].hi[axis]
        for below in range(1, count):
            if reach <= order[below].lo[axis] and (best is None or max(below, count - below) < best[0]):
                best = (max(below, count - below), axis, below, reach)
            reach = max(reach, order[below].hi[axis])
    if best is None:
        return None
    _larger, axis, below, reach = best
    order = group.by_axis[axis]
    low = {id(s) for s in order[:below]}
    under = [s for s in group.solids if id(s) in low]
    over = [s for s in group.solids if id(s) not in low]
    if id(group.solids[0]) in low:
        return Plane(_AXES[axis], -reach), under, over
    return Plane(-_AXES[axis], order[below].lo[axis]), over, under


#: What a union past the limits can do about it.
_NESTING = "solids that overlap one another nest: list the largest first, or make them separate or touching"

#: A subtree and the distinct solids of its solid leaves, by ``id``.
_Part = tuple[BSPNode, dict[int, _Solid]]


class _Builder:
    """Builds the nodes of one union, counting them against the limits."""

    __slots__ = ("nodes",)

    def __init__(self) -> None:
        self.nodes = 0

    def _count(self, level: int) -> None:
        self.nodes += 1
        if self.nodes > MAX_BSP_NODES:
            raise ValueError(
                f"the union of solids needs over {MAX_BSP_NODES} BSP nodes (MAX_BSP_NODES); {_NESTING}"
            )
        if level > MAX_BSP_DEPTH:
            raise ValueError(
                f"the union of solids needs over {MAX_BSP_DEPTH} BSP levels (MAX_BSP_DEPTH); {_NESTING}"
            )

    def _empty(self, level: int) -> _Part:
        self._count(level)
        return BSPLeaf(), {}

    def _node(self, level: int, plane: Plane, pos: _Part, neg: _Part) -> _Part:
        """A node on ``plane`` whose sphere bounds the solids below; an empty child leaf gets a
        sphere of radius 0 at its centre."""
        self._count(level)
        solids = pos[1] | neg[1]
        sphere = (
            next(iter(solids.values())).sphere
            if len(solids) == 1
            else _bounding_sphere(list(solids.values()))
        )
        node = BSPNode(plane, pos[0], neg[0], sphere, type=NODE_TYPE_BOTH_CHILDREN)
        for child in (pos[0], neg[0]):
            if isinstance(child, BSPLeaf) and not child.polys:
                child.sphere = Sphere(node.sphere.center, 0.0)
        return node, solids

    def build(self, group: _Group, level: int) -> _Part:
        """The subtree of ``group``, its root ``level`` deep (the tree's root is level 1)."""
        if len(group.solids) > 1:
            split = _axis_split(group)
            if split is not None:
                plane, under, over = split
                pos = self.build(group.subset(over), level + 1)
                return self._node(level, plane, pos, self.build(group.subset(under), level + 1))
        return self._nest(group, level)

    def _nest(self, group: _Group, level: int) -> _Part:
        """The chain of the first solid, off each of its planes the others that reach past it."""
        first, rest = group.solids[0], group.solids[1:]
        planes = first.planes
        spans = [[solid.span(plane) for plane in planes] for solid in rest]
        self._count(level + len(planes))
        part: _Part = BSPLeaf(solid=True, sphere=first.sphere, polys=list(first.faces)), {id(first): first}
        for i in reversed(range(len(planes))):
            past = [
                solid
                for solid, span in zip(rest, spans, strict=True)
                if span[i][1] > 0.0 and all(span[j][0] < 0.0 for j in range(i))
            ]
            outside = self.build(group.subset(past), level + i + 1) if past else self._empty(level + i + 1)
            part = self._node(level + i, planes[i], outside, part)
        return part


def _number_leaves(node: BSPNode, leaves: list[BSPLeaf]) -> None:
    """Number the leaves depth first, positive side first."""
    if isinstance(node, BSPLeaf):
        node.leaf_index = len(leaves)
        leaves.append(node)
        return
    assert node.pos_node is not None and node.neg_node is not None
    _number_leaves(node.pos_node, leaves)
    _number_leaves(node.neg_node, leaves)


def build_union_tree(solids: Sequence[Sequence[Polygon]]) -> BSPTree:
    """A physics BSP of the union of closed convex solids, each given as its faces.

    Raises :class:`SolidError` for a solid that is not convex with outward faces, ``ValueError``
    for no solids or a union past :data:`MAX_UNION_SOLIDS`, :data:`MAX_UNION_CORNERS`,
    :data:`MAX_BSP_NODES` or :data:`MAX_BSP_DEPTH`.
    """
    if not solids:
        raise ValueError("need at least one solid")
    if len(solids) > MAX_UNION_SOLIDS:
        raise ValueError(
            f"a union has at most {MAX_UNION_SOLIDS} solids (MAX_UNION_SOLIDS), got {len(solids)}"
        )
    corners = sum(len(face.vertices) for faces in solids for face in faces)
    if corners > MAX_UNION_CORNERS:
        raise ValueError(
            f"a union's faces have at most {MAX_UNION_CORNERS} corners in all (MAX_UNION_CORNERS), "
            f"got {corners}"
        )
    parts: list[_Solid] = []
    for index, faces in enumerate(solids):
        try:
            parts.append(_Solid(faces))
        except ValueError as error:
            raise SolidError(index, str(error)) from None
    by_axis = [sorted(parts, key=lambda solid, axis=axis: solid.lo[axis]) for axis in range(3)]
    root, _solids = _Builder().build(_Group(parts, by_axis), 1)
    _number_leaves(root, [])
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
