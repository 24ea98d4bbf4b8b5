"""Physics and cell BSP trees: ``BSPTREE``, ``BSPNODE`` and ``BSPLEAF`` with their pure queries.

A physics BSP splits space with planes; its leaves hold the polygons that bound them and a ``solid``
flag. Retail dispatches the per-node queries through a vtable; here ``BSPLeaf`` overrides the
``BSPNode`` methods. The queries that need a polygon routine call ``hits_sphere`` on the polygons
a leaf holds (``acphys.geometry.polygon.Polygon`` provides it).

Retail's cell BSPs (``point_inside_cell_bsp`` and friends) walk only ``pos_node`` links. Retail
never initialises a leaf's splitting plane; here a leaf carries the zero plane, which every walk
reads as "on the plane" (distance 0).

The physics walks sum a plane distance z, y, x (:func:`_plane_dist`), the cell walks
``point_inside_cell_bsp`` and ``sphere_intersects_cell_bsp`` y, z, x (:func:`_cell_plane_dist`);
the order matters once the operands are float32 and the sums double.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple, Protocol

from acphys.constants import EPSILON
from acphys.geometry.bsp_collision import BSPTreeCollisions
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.transition.transition import SpherePath


def type_tag(name: str) -> int:
    """The retail ``type`` integer of a four-letter node tag (``'LEAF'`` -> ``0x4C454146``)."""
    if len(name) != 4 or not name.isascii():
        raise ValueError(f"a BSP node tag is four ASCII letters, got {name!r}")
    return int.from_bytes(name.encode("ascii"), "big")


#: ``BSPNODE::BSPNODE`` default tag ``'####'`` (acclient.c:363069).
NODE_TYPE_DEFAULT = type_tag("####")
#: Leaf and portal tags tested by ``UnPackChild`` (acclient.c:363358, 363371).
NODE_TYPE_LEAF = type_tag("LEAF")
NODE_TYPE_PORTAL = type_tag("PORT")
#: Interior tag with both children. ``BSPNODE::UnPack`` (acclient.c:363220-363249) reads both
#: children for ``BPIN`` and ``BPnN``, only ``pos_node`` for ``BPIn``/``BPnn``, only ``neg_node``
#: for ``BpIN``/``BpnN``.
NODE_TYPE_BOTH_CHILDREN = type_tag("BPnN")

#: Cell-BSP sphere slack, the float32 literal ``0.0099999998`` (float32 0.01;
#: BSPNODE::sphere_intersects_cell_bsp, acclient.c:362993).
CELL_SPHERE_SLACK: float = f32(0.0099999998)

#: ``sphere_intersects_cell_bsp`` results.
CELL_OUTSIDE = 0
CELL_PARTIALLY_INSIDE = 1
CELL_ENTIRELY_INSIDE = 2


class BSPPolygon(Protocol):
    """What a BSP leaf needs from the polygons it holds (``CPolygon``,
    :class:`acphys.geometry.polygon.Polygon`)."""

    plane: Plane

    def hits_sphere(self, sphere: Sphere) -> bool: ...

    def pos_hits_sphere(
        self, sphere: Sphere, movement: Vector3, contact_pt: Vector3
    ) -> tuple[bool, bool]: ...

    def walkable_hits_sphere(self, sphere: Sphere, up: Vector3, walkable_allowance: float) -> bool: ...

    def check_small_walkable(self, sphere: Sphere, up: Vector3) -> bool: ...

    def adjust_sphere_to_plane(
        self, valid_pos: Sphere, movement: Vector3, walk_interp: float
    ) -> float | None: ...

    def adjust_sphere_to_poly(self, check_pos: Sphere, curr_pos: Vector3, movement: Vector3) -> float: ...

    def adjust_to_placement_poly(
        self,
        struck_sphere: Sphere,
        other_sphere: Sphere,
        radius: float,
        center_solid: bool,
        solid_check: bool,
    ) -> None: ...


class SolidPolyHit:
    """The in/out arguments ``int *center_solid`` and ``CPolygon **hit_poly`` of
    ``sphere_intersects_solid_poly``; the caller starts them cleared."""

    __slots__ = ("center_solid", "hit_poly")

    def __init__(self) -> None:
        self.center_solid = False
        self.hit_poly: BSPPolygon | None = None


class PolyHit(NamedTuple):
    """What ``sphere_intersects_poly`` returns: the result, and its out-parameters ``polygon``
    (the last polygon the sphere touched, heading into it or not; the caller's value if none)
    and ``contact_pt`` (the centre's foot on the last plane in reach)."""

    hit: bool
    polygon: BSPPolygon | None
    contact_pt: Vector3


class _PolySearch:
    """The in/out pointers ``polygon`` and ``contact_pt`` shared by one ``sphere_intersects_poly`` walk."""

    __slots__ = ("contact_pt", "polygon")

    def __init__(self, polygon: BSPPolygon | None, contact_pt: Vector3) -> None:
        self.polygon = polygon
        self.contact_pt = contact_pt


def spheres_intersect(a: Sphere, b: Sphere) -> bool:
    """``CSphere::intersects``, kept under this name: see :meth:`Sphere.intersects`.

    Retail: CSphere::intersects @ 0x005344A0 (acclient.c:356340)
    """
    return a.intersects(b)


def _plane_dist(plane: Plane, p: Vector3) -> float:
    """``N·p + d`` summed z, y, x (the physics walks, e.g. acclient.c:363586)."""
    n = plane.N
    return n.z * p.z + n.y * p.y + n.x * p.x + plane.d


def _cell_plane_dist(plane: Plane, p: Vector3) -> float:
    """``N·p + d`` summed y, z, x (the cell walks, acclient.c:362952, 362989)."""
    n = plane.N
    return n.y * p.y + n.z * p.z + n.x * p.x + plane.d


def _is_behind(plane: Plane, p: Vector3) -> bool:
    """``Plane::which_side(p, EPSILON) == 1``: farther than EPSILON on the negative side."""
    return _plane_dist(plane, p) < -EPSILON


class BSPNode:
    """Retail ``BSPNODE`` (acclient.h:32157): sphere, splitting plane, type tag, polygons, children."""

    __slots__ = ("neg_node", "polys", "pos_node", "sphere", "splitting_plane", "type")

    def __init__(
        self,
        splitting_plane: Plane | None = None,
        pos_node: BSPNode | None = None,
        neg_node: BSPNode | None = None,
        sphere: Sphere | None = None,
        polys: list[BSPPolygon] | None = None,
        type: int = NODE_TYPE_DEFAULT,
    ) -> None:
        self.splitting_plane = splitting_plane.copy() if splitting_plane is not None else Plane()
        self.pos_node = pos_node
        self.neg_node = neg_node
        self.sphere = sphere.copy() if sphere is not None else Sphere(Vector3(), 0.0)
        self.polys: list[BSPPolygon] = list(polys) if polys is not None else []
        self.type = type

    @property
    def num_polys(self) -> int:
        return len(self.polys)

    @property
    def type_string(self) -> str:
        """The tag as its four letters (the ``type_string`` arm of the union)."""
        return self.type.to_bytes(4, "big").decode("ascii", errors="replace")

    def _children(self) -> tuple[BSPNode, BSPNode]:
        if self.pos_node is None or self.neg_node is None:
            raise ValueError(f"physics BSP node {self.type_string!r} lacks a child; solid queries need both")
        return self.pos_node, self.neg_node

    def point_intersects_solid(self, point: Vector3) -> bool:
        """Descend by the sign of the plane distance; a point exactly on the plane goes positive.

        Retail: BSPNODE::point_intersects_solid @ 0x0053C310 (acclient.c:363025)
        """
        pos, neg = self._children()
        if _plane_dist(self.splitting_plane, point) < 0.0:
            return neg.point_intersects_solid(point)
        return pos.point_intersects_solid(point)

    def sphere_intersects_solid(self, check_pos: Sphere, center_check: bool) -> bool:
        """Whether ``check_pos`` overlaps the solid below this node.

        Misses when the node's bounding sphere misses. Past ``radius - EPSILON`` on one side only
        that child is asked; otherwise the side holding the centre keeps ``center_check`` (a
        centre at distance exactly 0 counts as positive) and the other side is asked without it.

        Retail: BSPNODE::sphere_intersects_solid @ 0x0053CAF0 (acclient.c:363573)
        """
        if not spheres_intersect(self.sphere, check_pos):
            return False
        pos, neg = self._children()
        dist = _plane_dist(self.splitting_plane, check_pos.center)
        reach = check_pos.radius - EPSILON
        if dist >= reach:
            return pos.sphere_intersects_solid(check_pos, center_check)
        if dist <= -reach:
            return neg.sphere_intersects_solid(check_pos, center_check)
        if dist < 0.0:
            return pos.sphere_intersects_solid(check_pos, False) or neg.sphere_intersects_solid(
                check_pos, center_check
            )
        return pos.sphere_intersects_solid(check_pos, center_check) or neg.sphere_intersects_solid(
            check_pos, False
        )

    def sphere_intersects_solid_poly(
        self, check_pos: Sphere, radius: float, hit: SolidPolyHit, center_check: bool
    ) -> bool:
        """Like ``sphere_intersects_solid`` but records the first polygon hit and whether the
        centre lies in a solid leaf; straddling, the centre's side goes first (distance exactly 0
        counts as positive) and the other side is asked only while no polygon is recorded.

        ``radius`` (not ``check_pos.radius``) sets the straddle band. The result is
        ``hit.center_solid`` once the first side recorded a polygon, else the second side's.

        Retail: BSPNODE::sphere_intersects_solid_poly @ 0x0053CD50 (acclient.c:363713)
        """
        if not spheres_intersect(self.sphere, check_pos):
            return False
        pos, neg = self._children()
        dist = _plane_dist(self.splitting_plane, check_pos.center)
        reach = radius - EPSILON
        if dist >= reach:
            return pos.sphere_intersects_solid_poly(check_pos, radius, hit, center_check)
        if dist <= -reach:
            return neg.sphere_intersects_solid_poly(check_pos, radius, hit, center_check)
        first, second = (neg, pos) if dist < 0.0 else (pos, neg)
        first.sphere_intersects_solid_poly(check_pos, radius, hit, center_check)
        if hit.hit_poly is None:
            return second.sphere_intersects_solid_poly(check_pos, radius, hit, False)
        return hit.center_solid

    def sphere_intersects_poly(
        self,
        check_pos: Sphere,
        movement: Vector3,
        polygon: BSPPolygon | None = None,
        contact_pt: Vector3 | None = None,
    ) -> PolyHit:
        """Whether ``check_pos``, moving by ``movement``, runs into a polygon face first.

        Misses when the node's bounding sphere misses; past ``radius - EPSILON`` on one side only
        that child is asked; straddling, the positive child is asked first and the negative one
        only if that missed. Retail's in/out pointers are the arguments ``polygon`` (the
        caller's starting value) and ``contact_pt`` (written in place when given) and come back
        in the :class:`PolyHit`; a polygon touched but not headed into is recorded without a hit,
        and the walk goes on.

        Retail: BSPNODE::sphere_intersects_poly @ 0x0053CA30 (acclient.c:363521)
        """
        search = _PolySearch(polygon, contact_pt if contact_pt is not None else Vector3())
        hit = self._intersects_poly(check_pos, movement, search)
        return PolyHit(hit, search.polygon, search.contact_pt)

    def _intersects_poly(self, check_pos: Sphere, movement: Vector3, search: _PolySearch) -> bool:
        """The node walk of :meth:`sphere_intersects_poly`."""
        if not spheres_intersect(self.sphere, check_pos):
            return False
        pos, neg = self._children()
        dist = _plane_dist(self.splitting_plane, check_pos.center)
        reach = check_pos.radius - EPSILON
        if dist >= reach:
            return pos._intersects_poly(check_pos, movement, search)
        if dist <= -reach:
            return neg._intersects_poly(check_pos, movement, search)
        return pos._intersects_poly(check_pos, movement, search) or neg._intersects_poly(
            check_pos, movement, search
        )

    def hits_walkable(self, path: SpherePath, valid_pos: Sphere, up: Vector3) -> bool:
        """Whether ``valid_pos`` touches a polygon it could stand on (see the leaf's test).

        Same walk as :meth:`sphere_intersects_poly`: one side past ``radius - EPSILON``, else
        positive then negative.

        Retail: BSPNODE::hits_walkable @ 0x0053CBD0 (acclient.c:363614)
        """
        if not spheres_intersect(self.sphere, valid_pos):
            return False
        pos, neg = self._children()
        dist = _plane_dist(self.splitting_plane, valid_pos.center)
        reach = valid_pos.radius - EPSILON
        if dist >= reach:
            return pos.hits_walkable(path, valid_pos, up)
        if dist <= -reach:
            return neg.hits_walkable(path, valid_pos, up)
        return pos.hits_walkable(path, valid_pos, up) or neg.hits_walkable(path, valid_pos, up)

    def find_walkable(
        self, path: SpherePath, valid_pos: Sphere, movement: Vector3, up: Vector3
    ) -> BSPPolygon | None:
        """Back ``valid_pos`` along ``movement`` onto each walkable polygon it touches.

        Straddling, both children are walked (positive first); ``valid_pos`` and
        ``path.walk_interp`` carry each adjustment into the next test. Returns the last polygon
        that adjusted the sphere, or None: retail's out-parameter ``changed`` is ``polygon is not
        None`` (every retail caller starts ``polygon`` and ``changed`` cleared).

        Retail: BSPNODE::find_walkable @ 0x0053CC80 (acclient.c:363662)
        """
        if not spheres_intersect(self.sphere, valid_pos):
            return None
        pos, neg = self._children()
        dist = _plane_dist(self.splitting_plane, valid_pos.center)
        reach = valid_pos.radius - EPSILON
        if dist >= reach:
            return pos.find_walkable(path, valid_pos, movement, up)
        if dist <= -reach:
            return neg.find_walkable(path, valid_pos, movement, up)
        first = pos.find_walkable(path, valid_pos, movement, up)
        later = neg.find_walkable(path, valid_pos, movement, up)
        return later if later is not None else first

    def point_inside_cell_bsp(self, origin: Vector3) -> bool:
        """Cell BSP: inside unless some node on the ``pos_node`` chain has ``origin`` more than
        EPSILON behind its plane.

        Retail: BSPNODE::point_inside_cell_bsp @ 0x0053C1F0 (acclient.c:362943)
        """
        node: BSPNode | None = self
        while node is not None:
            if _cell_plane_dist(node.splitting_plane, origin) < -EPSILON:
                return False
            node = node.pos_node
        return True

    def sphere_intersects_cell_bsp(self, curr_sphere: Sphere) -> int:
        """Cell BSP: ``CELL_OUTSIDE`` (0), ``CELL_PARTIALLY_INSIDE`` (1) or ``CELL_ENTIRELY_INSIDE`` (2).

        With ``r = radius + 0.0099999998``, walking the ``pos_node`` chain: distance ``<= -r`` is
        outside; ``>= r`` goes on (2 at the chain's end); in between, the answer is 1 if the rest of
        the chain (from the next node) is not outside, and 1 if there is no next node. ``r`` is
        the ``float`` local ``curr_spherea``, but this node's tests read it from the register
        (acclient.c:362989-363013); the nodes further on read the stored float.

        Retail: BSPNODE::sphere_intersects_cell_bsp @ 0x0053C260 (acclient.c:362979)
        """
        center = curr_sphere.center
        slack = curr_sphere.radius + CELL_SPHERE_SLACK
        stored = f32(slack)
        node: BSPNode = self
        while True:
            dist = _cell_plane_dist(node.splitting_plane, center)
            if dist <= -slack:
                return CELL_OUTSIDE
            nxt = node.pos_node
            if dist < slack:
                if nxt is None:
                    return CELL_PARTIALLY_INSIDE
                inside = nxt.sphere_intersects_cell_bsp(curr_sphere) != CELL_OUTSIDE
                return CELL_PARTIALLY_INSIDE if inside else CELL_OUTSIDE
            if nxt is None:
                return CELL_ENTIRELY_INSIDE
            node = nxt
            slack = stored

    def box_intersects_cell_bsp(self, box_min: Vector3, box_max: Vector3) -> bool:
        """Cell BSP: false once some node on the ``pos_node`` chain has all eight corners of the
        box more than EPSILON behind its plane (the min corner is tested first).

        Retail: BSPNODE::box_intersects_cell_bsp @ 0x0053C880 (acclient.c:363424)
        """
        corners = _box_corners(box_min, box_max)
        node: BSPNode | None = self
        while node is not None:
            if all(_is_behind(node.splitting_plane, c) for c in corners):
                return False
            node = node.pos_node
        return True

    def __repr__(self) -> str:
        return f"BSPNode({self.type_string!r}, plane={self.splitting_plane!r}, polys={self.num_polys})"


def _box_corners(lo: Vector3, hi: Vector3) -> tuple[Vector3, ...]:
    return (
        lo,
        Vector3(hi.x, hi.y, hi.z),
        Vector3(lo.x, lo.y, hi.z),
        Vector3(lo.x, hi.y, lo.z),
        Vector3(hi.x, lo.y, lo.z),
        Vector3(hi.x, lo.y, hi.z),
        Vector3(lo.x, hi.y, hi.z),
        Vector3(hi.x, hi.y, lo.z),
    )


class BSPLeaf(BSPNode):
    """Retail ``BSPLEAF`` (acclient.h:57775): a ``BSPNODE`` tagged ``LEAF`` with ``leaf_index``
    and ``solid``. In a physics BSP its polygons bound the leaf's region."""

    __slots__ = ("leaf_index", "solid")

    def __init__(
        self,
        leaf_index: int = -1,
        solid: bool = False,
        sphere: Sphere | None = None,
        polys: list[BSPPolygon] | None = None,
    ) -> None:
        super().__init__(sphere=sphere, polys=polys, type=NODE_TYPE_LEAF)
        self.leaf_index = leaf_index
        self.solid = bool(solid)

    def point_intersects_solid(self, point: Vector3) -> bool:
        """A leaf is solid for a point exactly when it holds polygons; ``solid`` is not read.

        Retail: BSPLEAF::point_intersects_solid @ 0x0053D3F0 (acclient.c:364085)
        """
        return bool(self.polys)

    def sphere_intersects_solid(self, check_pos: Sphere, center_check: bool) -> bool:
        """A polygon-less leaf misses; a solid leaf hits when ``center_check``; otherwise a hit
        needs the leaf sphere to intersect and some polygon to ``hits_sphere``.

        Retail: BSPLEAF::sphere_intersects_solid @ 0x0053D5F0 (acclient.c:364235)
        """
        if not self.polys:
            return False
        if center_check and self.solid:
            return True
        if not spheres_intersect(self.sphere, check_pos):
            return False
        return any(poly.hits_sphere(check_pos) for poly in self.polys)

    def _intersects_poly(self, check_pos: Sphere, movement: Vector3, search: _PolySearch) -> bool:
        """Polygon-less leaves and leaves whose sphere misses give false. Otherwise each polygon
        in turn: one the sphere touches (``polygon_hits_sphere_slow_but_sure``) is recorded in
        ``search.polygon``; the first also headed into (``N·movement < 0``) gives true.

        Retail: BSPLEAF::sphere_intersects_poly @ 0x0053D580 (acclient.c:364199)
        """
        if not self.polys or not spheres_intersect(self.sphere, check_pos):
            return False
        for poly in self.polys:
            hit, struck = poly.pos_hits_sphere(check_pos, movement, search.contact_pt)
            if struck:
                search.polygon = poly
            if hit:
                return True
        return False

    def hits_walkable(self, path: SpherePath, valid_pos: Sphere, up: Vector3) -> bool:
        """True for the first polygon facing ``up`` more than ``path.walkable_allowance`` that
        touches ``valid_pos`` and on which the half-radius sphere stands (``check_small_walkable``).

        Retail: BSPLEAF::hits_walkable @ 0x0053D670 (acclient.c:364274)
        """
        if not self.polys or not spheres_intersect(self.sphere, valid_pos):
            return False
        return any(
            poly.walkable_hits_sphere(valid_pos, up, path.walkable_allowance)
            and poly.check_small_walkable(valid_pos, up)
            for poly in self.polys
        )

    def find_walkable(
        self, path: SpherePath, valid_pos: Sphere, movement: Vector3, up: Vector3
    ) -> BSPPolygon | None:
        """Every polygon walkable under ``path.walkable_allowance`` that touches ``valid_pos``
        backs it along ``movement`` onto its plane (``adjust_sphere_to_plane``, which also lowers
        ``path.walk_interp``); returns the last that did, None if none.

        Retail: BSPLEAF::find_walkable @ 0x0053D6F0 (acclient.c:364310)
        """
        if not self.polys or not spheres_intersect(self.sphere, valid_pos):
            return None
        found: BSPPolygon | None = None
        for poly in self.polys:
            if not poly.walkable_hits_sphere(valid_pos, up, path.walkable_allowance):
                continue
            interp = poly.adjust_sphere_to_plane(valid_pos, movement, path.walk_interp)
            if interp is not None:
                path.walk_interp = interp
                found = poly
        return found

    def sphere_intersects_solid_poly(
        self, check_pos: Sphere, radius: float, hit: SolidPolyHit, center_check: bool
    ) -> bool:
        """Polygon-less leaves return false untouched. Otherwise ``center_check`` on a solid leaf
        sets ``hit.center_solid``; the first polygon that ``hits_sphere`` is recorded and gives
        true; with none, the result is ``hit.center_solid``.

        Retail: BSPLEAF::sphere_intersects_solid_poly @ 0x0053D780 (acclient.c:364344)
        """
        if not self.polys:
            return False
        if center_check and self.solid:
            hit.center_solid = True
        if spheres_intersect(self.sphere, check_pos):
            for poly in self.polys:
                if poly.hits_sphere(check_pos):
                    hit.hit_poly = poly
                    return True
        return hit.center_solid

    def __repr__(self) -> str:
        return f"BSPLeaf({self.leaf_index}, solid={self.solid}, polys={self.num_polys})"


class BSPTree(BSPTreeCollisions):
    """Retail ``BSPTREE`` (acclient.h:31963): just the root node. The collision queries
    come from :class:`acphys.geometry.bsp_collision.BSPTreeCollisions`."""

    __slots__ = ("root_node",)

    def __init__(self, root_node: BSPNode) -> None:
        self.root_node = root_node

    def get_sphere(self) -> Sphere:
        """The root's bounding sphere (the object itself, not a copy).

        Retail: BSPTREE::GetSphere @ 0x005397E0 (acclient.c:360661)
        """
        return self.root_node.sphere

    def polygons(self) -> list[BSPPolygon]:
        """Every polygon the tree's nodes hold, once each (leaves share a solid's faces), in
        depth-first order, positive side first; without recursion. Not retail: for pictures."""
        seen: set[int] = set()
        found: list[BSPPolygon] = []
        stack: list[BSPNode | None] = [self.root_node]
        while stack:
            node = stack.pop()
            if node is None:
                continue
            for poly in node.polys:
                if id(poly) not in seen:
                    seen.add(id(poly))
                    found.append(poly)
            stack += [node.neg_node, node.pos_node]
        return found

    def point_inside_cell_bsp(self, origin: Vector3) -> bool:
        """Retail: BSPTREE::point_inside_cell_bsp @ 0x005398C0 (acclient.c:360730)"""
        return self.root_node.point_inside_cell_bsp(origin)

    def sphere_intersects_cell_bsp(self, sphere: Sphere) -> int:
        """Retail: BSPTREE::sphere_intersects_cell_bsp @ 0x005398D0 (acclient.c:360736)"""
        return self.root_node.sphere_intersects_cell_bsp(sphere)

    def box_intersects_cell_bsp(self, box_min: Vector3, box_max: Vector3) -> bool:
        """Retail: BSPTREE::box_intersects_cell_bsp @ 0x005398B0 (acclient.c:360724)"""
        return self.root_node.box_intersects_cell_bsp(box_min, box_max)
