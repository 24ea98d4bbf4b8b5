"""``Polygon``: retail ``CPolygon``, a convex planar polygon used for collision.

Edge tests walk the edges ``vertices[i-1] -> vertices[i]`` (starting with the closing edge
``vertices[-1] -> vertices[0]``); a point is inside an edge when ``(p - start)·(N × edge) >= 0``.

Several edge loops contain a second FPU compare that Hex-Rays printed only as condition bits
(``if (c0 | c2) return 0``). acphys reads it, with ACE, as "the point is farther than the radius
from the edge line": ``dp² > |N × edge|²·radsq`` (an unordered, NaN, compare also returns 0).

Float32 at rest (:mod:`acphys.precision`): the edge loops keep the x and y of each edge and of
each point's displacement from the edge start in ``float`` locals, and their z both as a
``float`` local and as an x87 register, using each where retail does; the contact point, the
walkable foot point and ``radsq`` are ``float`` stores. The plane comes from :meth:`make_plane`,
which is how ``CPolygon::UnPack`` builds it from the vertices of a DAT (acclient.c:359909).
"""

from __future__ import annotations

import math
from enum import IntEnum

from acphys.constants import EPSILON
from acphys.geometry.plane import Plane, Ray, Sidedness
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, unpack3

_new = object.__new__


class SidesType(IntEnum):
    """Retail ``SidesType`` (acclient.h:7372), the ``CPolygon::sides_type`` field."""

    SINGLE = 0
    DOUBLE = 1
    BOTH = 2


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

    def make_plane(self) -> None:
        """Set ``plane``: normal = normalised fan sum of ``(v[i]-v[0]) × (v[i+1]-v[0])``, and
        ``d`` = minus the mean of ``N·v`` over all vertices.

        Stores (acclient.c:359673-359716): the x and y of ``v[i]-v[0]`` and the x and y of each
        cross product are ``float`` spills, the cross products' x and y are summed in registers
        but their z in the ``float`` local ``normal_8``; the reciprocal length is spilled to
        ``float`` for the y and z of the normal but not for its x; the normal and ``d`` are
        ``float`` stores. Raises ``ValueError`` for collinear vertices (retail divides by a
        zero length).

        Retail: CPolygon::make_plane @ 0x005383D0 (acclient.c:359627)
        """
        verts = self.vertices
        first = verts[0]
        x0, y0, z0 = first.x, first.y, first.z
        sum_x = sum_y = 0.0
        sum_z = 0.0
        for i in range(1, len(verts) - 1):
            a, b = verts[i], verts[i + 1]
            bx, by, bz = b.x - x0, b.y - y0, b.z - z0
            ax, ay, _ = unpack3(pack3(a.x - x0, a.y - y0, 0.0))
            az = a.z - z0
            cx, cy, _ = unpack3(pack3(ay * bz - az * by, az * bx - bz * ax, 0.0))
            sum_x += cx
            sum_y += cy
            sum_z = f32(by * ax - ay * bx + sum_z)
        length_sq = sum_z * sum_z + sum_y * sum_y + sum_x * sum_x
        if length_sq == 0.0:
            raise ValueError(f"Polygon vertices are collinear, no plane: {verts!r}")
        inv = 1.0 / math.sqrt(length_sq)
        inv32 = f32(inv)
        normal = Vector3(inv * sum_x, inv32 * sum_y, inv32 * sum_z)
        nx, ny, nz = normal.x, normal.y, normal.z
        dist_sum = 0.0
        for v in verts:
            dist_sum = dist_sum + nz * v.z + ny * v.y + nx * v.x
        self.plane.N = normal
        self.plane.d = f32(-(dist_sum / len(verts)))

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

    def _inside_all_edges(self, px: float, py: float, pz: float) -> bool:
        """The point is inside (or on) every edge: the loop of ``point_in_polygon`` and the first
        loop of ``polygon_hits_sphere_slow_but_sure``. The x and y of ``N × edge`` are ``float``
        spills, its z and the displacements are not (acclient.c:360205-360216, 360080-360090)."""
        n = self.plane.N
        nx, ny, nz = n.x, n.y, n.z
        last = self.vertices[-1]
        for v in self.vertices:
            lx, ly, lz = last.x, last.y, last.z
            ex, ey, ez = v.x - lx, v.y - ly, v.z - lz
            cx, cy, _ = unpack3(pack3(ez * ny - ey * nz, ex * nz - ez * nx, 0.0))
            if (pz - lz) * (ey * nx - ex * ny) + (py - ly) * cy + (px - lx) * cx < 0.0:
                return False
            last = v
        return True

    def point_in_polygon(self, point: Vector3) -> bool:
        """Whether ``point`` (assumed in the plane) is inside every edge; edges count as inside.

        Retail: CPolygon::point_in_polygon @ 0x00538D90 (acclient.c:360176)
        """
        return self._inside_all_edges(point.x, point.y, point.z)

    def _touch_setup(self, sphere: Sphere, contact_pt: Vector3) -> float | None:
        """Shared start of the sphere tests: None if the sphere (radius less EPSILON) misses the
        plane, else ``radsq`` (rad² - dist², a ``float`` local) with ``contact_pt`` set to the
        centre's foot on the plane; its z subtracts the ``float`` spill of ``dist·N.z``
        (acclient.c:359949-359968, 360049-360065)."""
        plane = self.plane
        n = plane.N
        c = sphere.center
        dist = n.y * c.y + n.z * c.z + c.x * n.x + plane.d
        rad = sphere.radius - EPSILON
        if not rad >= abs(dist):
            return None
        contact_pt.x, contact_pt.y, contact_pt.z = unpack3(
            pack3(c.x - dist * n.x, c.y - dist * n.y, c.z - f32(dist * n.z))
        )
        return f32(rad * rad - dist * dist)

    def _edge_walk(self, fx: float, fy: float, fz: float, radsq: float, sure: bool) -> bool:
        """The edge walk of ``polygon_hits_sphere`` and the walkable checks, from the foot point
        ``(fx, fy, fz)`` with ``radsq``; with ``sure``, the second loop of
        ``polygon_hits_sphere_slow_but_sure``, where an edge the foot is outside of whose segment
        it does not project onto leaves the answer alone and the end of the pass is a miss.

        The edge and the displacement are ``float`` locals; the side test reads their z from the
        register (acclient.c:359979-359998)."""
        n = self.plane.N
        nx, ny, nz = n.x, n.y, n.z
        result = True
        last = self.vertices[-1]
        for v in self.vertices:
            lx, ly, lz = last.x, last.y, last.z
            ez_reg = v.z - lz
            dz_reg = fz - lz
            ex, ey, ez = unpack3(pack3(v.x - lx, v.y - ly, ez_reg))
            dx, dy, dz = unpack3(pack3(fx - lx, fy - ly, dz_reg))
            cz = ey * nx - ex * ny
            cy = ex * nz - ez * nx
            cx = ez_reg * ny - ey * nz
            dp = dz_reg * cz + dy * cy + dx * cx
            if dp < 0.0 if sure else not dp >= 0.0:
                if not (cx * cx + cy * cy + cz * cz) * radsq >= dp * dp:
                    return False
                along = dz * ez + dy * ey + dx * ex
                if along >= 0.0 and along <= ez * ez + ey * ey + ex * ex:
                    return True
                result = False
            if dz * dz + dy * dy + dx * dx <= radsq:
                return True
            last = v
        return False if sure else result

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
        return self._edge_walk(contact_pt.x, contact_pt.y, contact_pt.z, radsq, False)

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
        fx, fy, fz = contact_pt.x, contact_pt.y, contact_pt.z
        if self._inside_all_edges(fx, fy, fz):
            return True
        return self._edge_walk(fx, fy, fz, radsq, True)

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
        return self.polygon_hits_sphere_slow_but_sure(sphere, _new(Vector3))

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
        return self.polygon_hits_sphere_slow_but_sure(sphere, _new(Vector3))

    def adjust_sphere_to_plane(
        self, valid_pos: Sphere, movement: Vector3, walk_interp: float
    ) -> float | None:
        """Back ``valid_pos`` along ``movement`` until it just touches the plane.

        ``walk_interp`` is ``SPHEREPATH::walk_interp``; the new value is returned (retail stores it
        in the path) and ``valid_pos.center`` moves back by ``t·movement``. Returns None, changing
        nothing, when ``|N·movement| <= EPSILON`` or the new interp is not below the old one or is
        below -0.5.

        The new interp is the ``float`` local ``valid_posa``: the "not below the old one" test reads
        the register, the -0.5 bound the stored float (acclient.c:359574-359575), so on float32
        lengths a rise of exactly 1.5 step-down heights (0.6f / 0.4f = 1.5000000373) is refused.
        The centre's y and z subtract ``float`` spills of ``t·movement`` (acclient.c:359581-359585).

        Retail: CPolygon::adjust_sphere_to_plane @ 0x00538210 (acclient.c:359533)
        """
        plane = self.plane
        n = plane.N
        c = valid_pos.center
        dist = n.y * c.y + n.z * c.z + c.x * n.x + plane.d
        along = n.z * movement.z + n.y * movement.y + n.x * movement.x
        if along <= EPSILON:
            if along >= -EPSILON:
                return None
            gap = dist - valid_pos.radius
        else:
            gap = -valid_pos.radius - dist
        t = gap / along
        interp = (1.0 - t) * walk_interp
        stored = f32(interp)
        if interp >= walk_interp or stored < -0.5:
            return None
        c.x, c.y, c.z = unpack3(
            pack3(c.x - t * movement.x, c.y - f32(t * movement.y), c.z - f32(t * movement.z))
        )
        return stored

    def adjust_sphere_to_poly(self, check_pos: Sphere, curr_pos: Vector3, movement: Vector3) -> float:
        """The fraction of ``movement`` from ``curr_pos`` at which a sphere of ``check_pos.radius``
        first touches this plane.

        1.0 when the sphere at ``curr_pos`` already reaches the plane (``radius > |dist|``);
        0.0 when ``|N·movement| < EPSILON``; otherwise ``(±radius - dist) / N·movement``. The
        start distance is the ``float`` local ``curr_posa`` (acclient.c:359507).

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
        dist = f32(n.z * curr_pos.z + n.y * curr_pos.y + curr_pos.x * n.x + self.plane.d)
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
        The y and z of the push are ``float`` spills, its x is not (acclient.c:360165-360167).

        Retail: CPolygon::adjust_to_placement_poly @ 0x00538CE0 (acclient.c:360136)
        """
        n = self.plane.N
        s = struck_sphere.center
        dist = n.y * s.y + n.z * s.z + s.x * n.x + self.plane.d
        if solid_check:
            target = radius
            if center_solid:
                target = target * -1.0
            if dist <= 0.0:
                target = -target
            shift = target - dist
        else:
            shift = radius - dist
        px = shift * n.x
        py, pz = f32(shift * n.y), f32(shift * n.z)
        s.x, s.y, s.z = unpack3(pack3(px + s.x, py + s.y, pz + s.z))
        o = other_sphere.center
        o.x, o.y, o.z = unpack3(pack3(px + o.x, py + o.y, pz + o.z))

    def _walkable_foot(self, sphere: Sphere, up: Vector3) -> tuple[float, float, float] | None:
        """The sphere centre slid along ``up`` onto the plane (three ``float`` locals, the y and z
        of ``t·up`` spilled first); None if ``|N·up| < EPSILON`` (acclient.c:360259-360273,
        360428-360442)."""
        plane = self.plane
        n = plane.N
        along = n.y * up.y + n.z * up.z + up.x * n.x
        if not abs(along) >= EPSILON:
            return None
        c = sphere.center
        t = (n.z * c.z + n.y * c.y + c.x * n.x + plane.d) / along
        return unpack3(pack3(c.x - t * up.x, c.y - f32(t * up.y), c.z - f32(t * up.z)))

    def check_walkable(self, sphere: Sphere, up: Vector3) -> bool:
        """Whether the sphere, dropped along ``up`` onto the plane, stands on the polygon
        (the ``polygon_hits_sphere`` edge walk with ``radsq = radius²``, a ``float`` local).

        False when the plane is within EPSILON of parallel to ``up`` (``|N·up| < EPSILON``);
        a face whose normal points away from ``up`` is still tested.

        Retail: CPolygon::check_walkable @ 0x00538E60 (acclient.c:360226)
        """
        foot = self._walkable_foot(sphere, up)
        if foot is None:
            return False
        r = sphere.radius
        return self._edge_walk(foot[0], foot[1], foot[2], f32(r * r), False)

    def check_small_walkable(self, sphere: Sphere, up: Vector3) -> bool:
        """``check_walkable`` with a half radius (``radsq = radius²·0.25``).

        Retail: CPolygon::check_small_walkable @ 0x005390B0 (acclient.c:360311)
        """
        foot = self._walkable_foot(sphere, up)
        if foot is None:
            return False
        r = sphere.radius
        return self._edge_walk(foot[0], foot[1], foot[2], f32(r * r * 0.25), False)

    def find_crossed_edge(self, sphere: Sphere, up: Vector3) -> Vector3 | None:
        """The unit inward normal (``N × edge``, normalised) of the first edge the sphere centre,
        dropped along ``up`` onto the plane, is outside of; None if inside all or ``|N·up| < EPSILON``.

        The normal is built from the ``float`` edge and stored before it is scaled by the
        reciprocal of its length (acclient.c:360470-360482).

        Retail: CPolygon::find_crossed_edge @ 0x00539300 (acclient.c:360396)
        """
        foot = self._walkable_foot(sphere, up)
        if foot is None:
            return None
        fx, fy, fz = foot
        n = self.plane.N
        nx, ny, nz = n.x, n.y, n.z
        last = self.vertices[-1]
        for v in self.vertices:
            lx, ly, lz = last.x, last.y, last.z
            ez_reg = v.z - lz
            ex, ey, ez = unpack3(pack3(v.x - lx, v.y - ly, ez_reg))
            dp = (
                (fz - lz) * (ey * nx - ex * ny)
                + (fy - ly) * (ex * nz - ez * nx)
                + (fx - lx) * (ez_reg * ny - ey * nz)
            )
            if not dp >= 0.0:
                normal = Vector3(ez * ny - ey * nz, ex * nz - ez * nx, ey * nx - ex * ny)
                inv = 1.0 / math.sqrt(normal.length_squared())
                normal.x, normal.y, normal.z = unpack3(pack3(inv * normal.x, inv * normal.y, inv * normal.z))
                return normal
            last = v
        return None

    def polygon_hits_ray(self, ray: Ray) -> tuple[bool, float | None]:
        """``(hit, time)``: whether ``ray`` meets the polygon, and the time from
        ``Plane.compute_time_of_intersection``. A SINGLE-sided polygon ignores rays with
        ``N·dir > 0`` (from behind), returning ``(False, None)``.

        The point in the plane is the ``Vector3`` local ``inplane_point``: its x and y are
        ``time·dir`` stored, then moved by ``pt`` and stored again (acclient.c:360565-360573).

        Retail: CPolygon::polygon_hits_ray @ 0x005395E0 (acclient.c:360545)
        """
        n = self.plane.N
        d = ray.dir
        if self.sides_type == SidesType.SINGLE and not d.z * n.z + d.y * n.y + d.x * n.x <= 0.0:
            return False, None
        hit, time = self.plane.compute_time_of_intersection(ray)
        if not hit:
            return False, time
        assert time is not None
        p = ray.pt
        tx, ty, _ = unpack3(pack3(time * d.x, time * d.y, 0.0))
        px, py, pz = unpack3(pack3(tx + p.x, ty + p.y, time * d.z + p.z))
        return self._inside_all_edges(px, py, pz), time
