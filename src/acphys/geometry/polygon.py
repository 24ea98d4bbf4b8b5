"""``Polygon``: retail ``CPolygon``, a convex planar polygon used for collision.

Edge tests walk the edges ``vertices[i-1] -> vertices[i]`` (starting with the closing edge
``vertices[-1] -> vertices[0]``); a point is inside an edge when ``(p - start)·(N × edge) >= 0``.

Several edge loops contain a second FPU compare that Hex-Rays printed only as condition bits
(``if (c0 | c2) return 0``). acphys reads it, with ACE, as "the point is farther than the radius
from the edge line": ``dp² > |N × edge|²·radsq`` (an unordered, NaN, compare also returns 0).
"""

from __future__ import annotations

from collections.abc import Iterator
from enum import IntEnum

from acphys.constants import EPSILON
from acphys.geometry.plane import Plane, Ray, Sidedness
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3


class SidesType(IntEnum):
    """Retail ``SidesType`` (acclient.h:7372), the ``CPolygon::sides_type`` field."""

    SINGLE = 0
    DOUBLE = 1
    BOTH = 2


def _edge_too_far(dp: float, cross: Vector3, radsq: float) -> bool:
    """The reconstructed lost compare (see the module docstring): True means "return 0"."""
    return not (cross.length_squared() * radsq >= dp * dp)


class Polygon:
    """A convex polygon in its owner's local frame, with the plane ``make_plane`` derives."""

    __slots__ = ("plane", "sides_type", "vertices")

    def __init__(self, vertices: list[Vector3], sides_type: SidesType | int = SidesType.SINGLE) -> None:
        if len(vertices) < 3:
            raise ValueError(f"Polygon needs at least 3 vertices, got {len(vertices)}")
        try:
            self.sides_type = SidesType(sides_type)
        except ValueError:
            raise ValueError(f"sides_type must be 0, 1 or 2 (SidesType), got {sides_type!r}") from None
        self.vertices = [v.copy() for v in vertices]
        self.plane = Plane()
        self.make_plane()

    @property
    def num_points(self) -> int:
        return len(self.vertices)

    def __repr__(self) -> str:
        return f"Polygon({self.vertices!r}, sides_type={self.sides_type!r}, plane={self.plane!r})"

    def _edges(self) -> Iterator[tuple[Vector3, Vector3, Vector3]]:
        """Yield ``(start, edge, N × edge)`` for each edge, the closing edge first."""
        n = self.plane.N
        last = self.vertices[-1]
        for vertex in self.vertices:
            edge = vertex - last
            yield last, edge, n.cross(edge)
            last = vertex

    def make_plane(self) -> None:
        """Set ``plane``: normal = normalised fan sum of ``(v[i]-v[0]) × (v[i+1]-v[0])``, and
        ``d`` = minus the mean of ``N·v`` over all vertices.

        Raises ``ValueError`` for collinear vertices (retail divides by a zero length).

        Retail: CPolygon::make_plane @ 0x005383D0 (acclient.c:359627)
        """
        first = self.vertices[0]
        total = Vector3()
        for i in range(1, self.num_points - 1):
            total = total + (self.vertices[i] - first).cross(self.vertices[i + 1] - first)
        length_sq = total.length_squared()
        if length_sq == 0.0:
            raise ValueError(f"Polygon vertices are collinear, no plane: {self.vertices!r}")
        normal = total * (1.0 / length_sq**0.5)
        dist_sum = 0.0
        for v in self.vertices:
            dist_sum += normal.z * v.z + normal.y * v.y + normal.x * v.x
        self.plane.N = normal
        self.plane.d = -(dist_sum / self.num_points)

    def point_in_poly2D(self, point: Vector3, side: Sidedness | int) -> bool:
        """Whether ``point`` is inside the polygon projected on the xy plane.

        Walks the edges from the last vertex back to the first; for ``side`` POSITIVE (0) a
        positive 2D cross value is outside, for any other side a negative one is.

        Retail: CPolygon::point_in_poly2D @ 0x00538060 (acclient.c:359419)
        """
        px, py = point.x, point.y
        following = self.vertices[0]
        for vertex in reversed(self.vertices):
            ey = following.y - vertex.y
            ex = vertex.x - following.x
            value = -(ey * vertex.x) - ex * vertex.y + ex * py + ey * px
            if side:
                if value < 0.0:
                    return False
            elif value > 0.0:
                return False
            following = vertex
        return True

    def point_in_polygon(self, point: Vector3) -> bool:
        """Whether ``point`` (assumed in the plane) is inside every edge; edges count as inside.

        Retail: CPolygon::point_in_polygon @ 0x00538D90 (acclient.c:360176)
        """
        return not any((point - start).dot(cross) < 0.0 for start, _edge, cross in self._edges())

    def _touch_setup(self, sphere: Sphere, contact_pt: Vector3) -> float | None:
        """Shared start of the sphere tests: None if the sphere (radius less EPSILON) misses the
        plane, else ``radsq`` (rad² - dist²) with ``contact_pt`` set to the centre's foot on the plane."""
        dist = self.plane.dot_point(sphere.center)
        rad = sphere.radius - EPSILON
        if not rad >= abs(dist):
            return None
        n = self.plane.N
        contact_pt.set(
            Vector3(sphere.center.x - dist * n.x, sphere.center.y - dist * n.y, sphere.center.z - dist * n.z)
        )
        return rad * rad - dist * dist

    def polygon_hits_sphere(self, sphere: Sphere, contact_pt: Vector3) -> bool:
        """Fast sphere test: plane distance within ``radius - EPSILON``, then one pass over the edges.

        ``contact_pt`` is set to the centre projected on the plane whenever the plane is in reach.
        An edge the foot point is outside of decides at once when the edge line is out of reach
        (miss) or the foot projects onto the edge segment (hit); otherwise the answer so far
        becomes "miss" and the loop goes on. A vertex within reach is a hit.

        Retail: CPolygon::polygon_hits_sphere @ 0x005387C0 (acclient.c:359915)
        """
        radsq = self._touch_setup(sphere, contact_pt)
        if radsq is None:
            return False
        return self._edge_walk(contact_pt, radsq)

    def polygon_hits_sphere_slow_but_sure(self, sphere: Sphere, contact_pt: Vector3) -> bool:
        """Exact sphere test: a hit if the foot point is inside every edge; otherwise a second
        pass over all edges finds an edge segment or vertex within reach.

        Unlike ``polygon_hits_sphere``, an edge the foot is outside of whose segment it does not
        project onto does not make the answer "miss": only the end of the pass does.

        Retail: CPolygon::polygon_hits_sphere_slow_but_sure @ 0x00538A10 (acclient.c:360006)
        """
        radsq = self._touch_setup(sphere, contact_pt)
        if radsq is None:
            return False
        if not any((contact_pt - start).dot(cross) < 0.0 for start, _edge, cross in self._edges()):
            return True
        for start, edge, cross in self._edges():
            disp = contact_pt - start
            dp = disp.dot(cross)
            if dp < 0.0:
                if _edge_too_far(dp, cross, radsq):
                    return False
                along = disp.dot(edge)
                if along >= 0.0 and along <= edge.length_squared():
                    return True
            if disp.length_squared() <= radsq:
                return True
        return False

    def pos_hits_sphere(self, sphere: Sphere, movement: Vector3, contact_pt: Vector3) -> tuple[bool, bool]:
        """``(hit, struck)``: ``struck`` is whether the sphere touches (retail then stores this polygon
        as ``struck_poly``); ``hit`` additionally needs ``movement`` to head into the face (N·movement < 0).

        Retail: CPolygon::pos_hits_sphere @ 0x005394F0 (acclient.c:360493)
        """
        touched = self.polygon_hits_sphere_slow_but_sure(sphere, contact_pt)
        n = self.plane.N
        if n.z * movement.z + n.y * movement.y + n.x * movement.x >= 0.0:
            return False, touched
        return touched, touched

    def hits_sphere(self, sphere: Sphere) -> bool:
        """``polygon_hits_sphere_slow_but_sure`` with the contact point discarded.

        Retail: CPolygon::hits_sphere @ 0x00539540 (acclient.c:360510)
        """
        return self.polygon_hits_sphere_slow_but_sure(sphere, Vector3())

    def walkable_hits_sphere(self, sphere: Sphere, up: Vector3, walkable_allowance: float) -> bool:
        """Whether a face steep enough to stand on (``N·up > walkable_allowance``) touches the sphere.

        ``walkable_allowance`` is ``SPHEREPATH::walkable_allowance``, the only path field read.
        Retail's cross-check call of ``polygon_hits_sphere`` (a debugging aid) changes nothing and
        is not repeated.

        Retail: CPolygon::walkable_hits_sphere @ 0x00539560 (acclient.c:360518)
        """
        n = self.plane.N
        if not n.z * up.z + n.y * up.y + up.x * n.x > walkable_allowance:
            return False
        return self.polygon_hits_sphere_slow_but_sure(sphere, Vector3())

    def adjust_sphere_to_plane(
        self, valid_pos: Sphere, movement: Vector3, walk_interp: float
    ) -> float | None:
        """Back ``valid_pos`` along ``movement`` until it just touches the plane.

        ``walk_interp`` is ``SPHEREPATH::walk_interp``; the new value is returned (retail stores it
        in the path) and ``valid_pos.center`` moves back by ``t·movement``. Returns None, changing
        nothing, when ``|N·movement| <= EPSILON`` or the new interp is not below the old one or is
        below -0.5.

        Retail: CPolygon::adjust_sphere_to_plane @ 0x00538210 (acclient.c:359533)
        """
        n = self.plane.N
        dist = self.plane.dot_point(valid_pos.center)
        along = n.z * movement.z + n.y * movement.y + n.x * movement.x
        if along <= EPSILON:
            if along >= -EPSILON:
                return None
            gap = dist - valid_pos.radius
        else:
            gap = -valid_pos.radius - dist
        t = gap / along
        interp = (1.0 - t) * walk_interp
        if interp >= walk_interp or interp < -0.5:
            return None
        c = valid_pos.center
        c.set(Vector3(c.x - t * movement.x, c.y - t * movement.y, c.z - t * movement.z))
        return interp

    def adjust_sphere_to_poly(self, check_pos: Sphere, curr_pos: Vector3, movement: Vector3) -> float:
        """The fraction of ``movement`` from ``curr_pos`` at which a sphere of ``check_pos.radius``
        first touches this plane.

        1.0 when the sphere at ``curr_pos`` already reaches the plane (``radius > |dist|``);
        0.0 when ``|N·movement| < EPSILON``; otherwise ``(±radius - dist) / N·movement``.

        Hex-Rays lost the compare that picks the sign (acclient.c:359517 keeps only
        ``if (c0 | c3) v7 = -v7``): c0|c3 is a "<=" and the only values in reach are the
        start distance, ``N·movement`` and the radius. Read as ``dist <= 0`` -> ``-radius``: a
        sphere starting at ``dist >= radius`` touches at ``dist = +radius``, one starting at
        ``dist <= -radius`` at ``-radius``. ACE reads ``|movement|² <= radius²``, which for the
        sub-radius steps a transition takes gives ``(-radius - dist)/N·movement``, a time past
        the end of the step on the far side of the plane; ``BSPTREE::adjust_to_plane`` would then
        place the sphere through the wall. ``N·movement <= 0`` fails the same way for every face
        a sphere is heading into (the only faces that report a hit).

        Retail: CPolygon::adjust_sphere_to_poly @ 0x00538170 (acclient.c:359497)
        """
        n = self.plane.N
        dist = n.z * curr_pos.z + n.y * curr_pos.y + curr_pos.x * n.x + self.plane.d
        if not check_pos.radius <= abs(dist):
            return 1.0
        along = n.z * movement.z + n.y * movement.y + movement.x * n.x
        if not abs(along) >= EPSILON:
            return 0.0
        reach = -check_pos.radius if dist <= 0.0 else check_pos.radius
        return (reach - dist) / along

    def adjust_to_placement_poly(
        self,
        struck_sphere: Sphere,
        other_sphere: Sphere,
        radius: float,
        center_solid: bool,
        solid_check: bool,
    ) -> None:
        """Push both spheres along N so ``struck_sphere`` ends ``radius`` from the plane.

        With ``solid_check`` the target side is ``+radius``, negated once for ``center_solid``
        and once more when the centre is on or behind the plane (so both together give +radius).

        Retail: CPolygon::adjust_to_placement_poly @ 0x00538CE0 (acclient.c:360136)
        """
        dist = self.plane.dot_point(struck_sphere.center)
        if solid_check:
            target = radius
            if center_solid:
                target = target * -1.0
            if dist <= 0.0:
                target = -target
            shift = target - dist
        else:
            shift = radius - dist
        delta = self.plane.N * shift
        struck_sphere.center.set(struck_sphere.center + delta)
        other_sphere.center.set(other_sphere.center + delta)

    def _walkable_foot(self, sphere: Sphere, up: Vector3) -> Vector3 | None:
        """The sphere centre slid along ``up`` onto the plane; None if ``|N·up| < EPSILON``."""
        n = self.plane.N
        along = n.y * up.y + n.z * up.z + up.x * n.x
        if not abs(along) >= EPSILON:
            return None
        t = self.plane.dot_point(sphere.center) / along
        return Vector3(sphere.center.x - t * up.x, sphere.center.y - t * up.y, sphere.center.z - t * up.z)

    def _edge_walk(self, foot: Vector3, radsq: float) -> bool:
        """The edge walk of ``polygon_hits_sphere`` and the walkable checks, from ``foot`` with ``radsq``."""
        result = True
        for start, edge, cross in self._edges():
            disp = foot - start
            dp = disp.dot(cross)
            if not dp >= 0.0:
                if _edge_too_far(dp, cross, radsq):
                    return False
                along = disp.dot(edge)
                if along >= 0.0 and along <= edge.length_squared():
                    return True
                result = False
            if disp.length_squared() <= radsq:
                return True
        return result

    def check_walkable(self, sphere: Sphere, up: Vector3) -> bool:
        """Whether the sphere, dropped along ``up`` onto the plane, stands on the polygon
        (the ``polygon_hits_sphere`` edge walk with ``radsq = radius²``).

        False when the plane is within EPSILON of parallel to ``up`` (``|N·up| < EPSILON``);
        a face whose normal points away from ``up`` is still tested.

        Retail: CPolygon::check_walkable @ 0x00538E60 (acclient.c:360226)
        """
        foot = self._walkable_foot(sphere, up)
        if foot is None:
            return False
        return self._edge_walk(foot, sphere.radius * sphere.radius)

    def check_small_walkable(self, sphere: Sphere, up: Vector3) -> bool:
        """``check_walkable`` with a half radius (``radsq = radius²·0.25``).

        Retail: CPolygon::check_small_walkable @ 0x005390B0 (acclient.c:360311)
        """
        foot = self._walkable_foot(sphere, up)
        if foot is None:
            return False
        return self._edge_walk(foot, sphere.radius * sphere.radius * 0.25)

    def find_crossed_edge(self, sphere: Sphere, up: Vector3) -> Vector3 | None:
        """The unit inward normal (``N × edge``, normalised) of the first edge the sphere centre,
        dropped along ``up`` onto the plane, is outside of; None if inside all or ``|N·up| < EPSILON``.

        Retail: CPolygon::find_crossed_edge @ 0x00539300 (acclient.c:360396)
        """
        foot = self._walkable_foot(sphere, up)
        if foot is None:
            return None
        for start, _edge, cross in self._edges():
            if not (foot - start).dot(cross) >= 0.0:
                return cross * (1.0 / cross.length())
        return None

    def polygon_hits_ray(self, ray: Ray) -> tuple[bool, float | None]:
        """``(hit, time)``: whether ``ray`` meets the polygon, and the time from
        ``Plane.compute_time_of_intersection``. A SINGLE-sided polygon ignores rays with
        ``N·dir > 0`` (from behind), returning ``(False, None)``.

        Retail: CPolygon::polygon_hits_ray @ 0x005395E0 (acclient.c:360545)
        """
        n = self.plane.N
        if self.sides_type == SidesType.SINGLE and ray.dir.z * n.z + ray.dir.y * n.y + ray.dir.x * n.x > 0.0:
            return False, None
        hit, time = self.plane.compute_time_of_intersection(ray)
        if not hit:
            return False, time
        point = Vector3(time * ray.dir.x + ray.pt.x, time * ray.dir.y + ray.pt.y, time * ray.dir.z + ray.pt.z)
        return self.point_in_polygon(point), time
