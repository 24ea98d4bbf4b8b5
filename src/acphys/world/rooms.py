"""Build env cells and buildings from boxes: "a house with two rooms and a doorway".

Not a retail routine: retail reads cells from the DAT. This builds cells of the shape the retail
queries read (see :mod:`acphys.world.env_cell`), in a landblock's frame with axis-aligned boxes.

A room is a box ``(cell_id, min, max)``; its cell sits at ``min`` (identity rotation) and its
structure is in that frame:

- cell BSP: the six inward face planes chained on ``pos_node`` (what ``point_inside_cell_bsp``
  and ``sphere_intersects_cell_bsp`` walk);
- physics BSP: the same six planes chained on ``pos_node``; behind each (``neg_node``) a leaf
  with the wall pieces on that face, facing into the room, with the doorways cut out. The
  leaves are not ``solid``: a wall collides where its polygons are, so a sphere may stand in
  a doorway. The room's inside is the last, empty, positive leaf;
- portals: each doorway on a face is a polygon of the structure facing into the room; the
  other room (or outside) lies behind it, so ``portal_side`` is 0.

A doorway is a rectangle ``(lo, hi)`` flat on one axis, lying on a face of one room (a door to
the outside) or on the shared face of two rooms (adjoining rooms share the wall plane).

Everything built here stands for DAT data, so every stored number is a float32: the corners
and box coordinates are :class:`~acphys.math.vector.Vector3` values (narrowed), the face planes
of axis-aligned boxes have unit axis normals and offsets equal to a float32 coordinate, and the
BSP spheres' radii are narrowed.

``build_house`` also makes the building: a shell around the rooms' bounding box (which the rooms
must fill), ``wall_thickness`` outside it on the four sides and the roof, facing out, with the
outside doorways cut through; one ``BldPortal`` per outside doorway. The building's origin is the
centre of the footprint at floor height: retail shows a building only from the outdoor cell
holding its origin (acclient.c:352157-352166).
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise
from typing import NamedTuple

from acphys.geometry.bsp import NODE_TYPE_BOTH_CHILDREN, BSPLeaf, BSPNode, BSPTree
from acphys.geometry.plane import Plane
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import FIRST_ENV_CELL, format_cell_id
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.world.building import BldPortal, BuildingObj
from acphys.world.env_cell import OUTSIDE_CELL_ID, CellPortal, CellStruct, EnvCell

_TOL = 1e-6


class RoomSpec(NamedTuple):
    """A room: an env cell id and its box (landblock-local)."""

    cell_id: int
    box_min: Vector3
    box_max: Vector3


class DoorwaySpec(NamedTuple):
    """An opening: a rectangle flat on one axis (``lo`` and ``hi`` equal there)."""

    lo: Vector3
    hi: Vector3


class _Face(NamedTuple):
    axis: int  # 0 x, 1 y, 2 z
    coord: float
    sign: int  # +1: normal along +axis, -1: along -axis
    u0: float
    u1: float
    v0: float
    v1: float


def _get(v: Vector3, axis: int) -> float:
    return (v.x, v.y, v.z)[axis]


def _uv_axes(axis: int) -> tuple[int, int]:
    """The two in-plane axes in cyclic order, so ``e_u × e_v = e_axis``."""
    return (axis + 1) % 3, (axis + 2) % 3


def _point(axis: int, coord: float, u: float, v: float) -> Vector3:
    a_u, a_v = _uv_axes(axis)
    xyz = [0.0, 0.0, 0.0]
    xyz[axis], xyz[a_u], xyz[a_v] = coord, u, v
    return Vector3(*xyz)


def _rect(
    axis: int, coord: float, sign: int, u0: float, u1: float, v0: float, v1: float, shift: Vector3
) -> Polygon:
    """A rectangle on the plane ``axis = coord`` with its normal along ``sign``, moved by ``-shift``."""
    corners = [_point(axis, coord, u, v) - shift for u, v in ((u0, v0), (u1, v0), (u1, v1), (u0, v1))]
    if sign < 0:
        corners.reverse()
    return Polygon(corners)


def _box_faces(lo: Vector3, hi: Vector3, outward: bool) -> list[_Face]:
    faces = []
    for axis in range(3):
        a_u, a_v = _uv_axes(axis)
        u0, u1, v0, v1 = _get(lo, a_u), _get(hi, a_u), _get(lo, a_v), _get(hi, a_v)
        for coord, out_sign in ((_get(lo, axis), -1), (_get(hi, axis), 1)):
            faces.append(_Face(axis, coord, out_sign if outward else -out_sign, u0, u1, v0, v1))
    return faces


def _doorway_rect(door: DoorwaySpec) -> tuple[int, float, float, float, float, float]:
    flat = [axis for axis in range(3) if abs(_get(door.lo, axis) - _get(door.hi, axis)) <= _TOL]
    if len(flat) != 1:
        raise ValueError(f"doorway {door!r} must be flat on exactly one axis")
    axis = flat[0]
    a_u, a_v = _uv_axes(axis)
    u0, u1 = sorted((_get(door.lo, a_u), _get(door.hi, a_u)))
    v0, v1 = sorted((_get(door.lo, a_v), _get(door.hi, a_v)))
    return axis, _get(door.lo, axis), u0, u1, v0, v1


def _on_face(face: _Face, rect: tuple[int, float, float, float, float, float]) -> bool:
    axis, coord, u0, u1, v0, v1 = rect
    return (
        face.axis == axis
        and abs(face.coord - coord) <= _TOL
        and face.u0 - _TOL <= u0
        and u1 <= face.u1 + _TOL
        and face.v0 - _TOL <= v0
        and v1 <= face.v1 + _TOL
    )


_Hole = tuple[float, float, float, float]


def _wall_pieces(face: _Face, holes: Sequence[_Hole], shift: Vector3) -> list[Polygon]:
    """The face as grid rectangles, leaving out those inside a hole."""
    us = sorted({face.u0, face.u1, *(c for h in holes for c in h[:2])})
    vs = sorted({face.v0, face.v1, *(c for h in holes for c in h[2:])})
    pieces = []
    for ua, ub in pairwise(us):
        for va, vb in pairwise(vs):
            mu, mv = (ua + ub) / 2, (va + vb) / 2
            if any(h[0] < mu < h[1] and h[2] < mv < h[3] for h in holes):
                continue
            pieces.append(_rect(face.axis, face.coord, face.sign, ua, ub, va, vb, shift))
    return pieces


def _face_plane(face: _Face, shift: Vector3) -> Plane:
    normal = _point(face.axis, float(face.sign), 0.0, 0.0)
    return Plane.from_point(normal, _point(face.axis, face.coord, face.u0, face.v0) - shift)


def _bounding_sphere(polys: Sequence[Polygon]) -> Sphere:
    points = [p for poly in polys for p in poly.vertices]
    lo = Vector3(min(p.x for p in points), min(p.y for p in points), min(p.z for p in points))
    hi = Vector3(max(p.x for p in points), max(p.y for p in points), max(p.z for p in points))
    center = (lo + hi) * 0.5
    return Sphere(center, f32(max((p - center).length() for p in points)))


def _plane_chain_tree(walls: Sequence[tuple[Plane, list[Polygon]]], inside_positive: bool) -> BSPTree:
    """A physics BSP of walls on convex-hull planes: each plane splits off a leaf with its walls
    (on the side away from the inside); the inside is the empty leaf at the chain's end."""
    every = [poly for _plane, polys in walls for poly in polys]
    if not every:
        raise ValueError("a physics BSP needs at least one wall polygon")
    center = _bounding_sphere(every).center
    node: BSPNode = BSPLeaf(sphere=Sphere(center, 0.0))
    below: list[Polygon] = []
    for plane, polys in reversed(walls):
        sphere = _bounding_sphere(polys) if polys else Sphere(center, 0.0)
        leaf = BSPLeaf(solid=False, sphere=sphere, polys=list(polys))
        below = below + list(polys)
        pos, neg = (node, leaf) if inside_positive else (leaf, node)
        node = BSPNode(
            plane,
            pos_node=pos,
            neg_node=neg,
            sphere=_bounding_sphere(below) if below else sphere,
            type=NODE_TYPE_BOTH_CHILDREN,
        )
    leaves: list[BSPLeaf] = []
    _number_leaves(node, leaves)
    return BSPTree(node)


def _number_leaves(node: BSPNode, leaves: list[BSPLeaf]) -> None:
    if isinstance(node, BSPLeaf):
        node.leaf_index = len(leaves)
        leaves.append(node)
        return
    assert node.pos_node is not None and node.neg_node is not None
    _number_leaves(node.pos_node, leaves)
    _number_leaves(node.neg_node, leaves)


def _cell_tree(planes: Sequence[Plane], sphere: Sphere) -> BSPTree:
    """A cell BSP: the inward planes chained on ``pos_node`` (no leaf at the end)."""
    node: BSPNode | None = None
    for plane in reversed(planes):
        node = BSPNode(plane, pos_node=node, sphere=sphere)
    assert node is not None
    return BSPTree(node)


def _check_rooms(rooms: Sequence[RoomSpec]) -> None:
    seen: set[int] = set()
    for room in rooms:
        low = room.cell_id & 0xFFFF
        if not FIRST_ENV_CELL <= low < 0xFFFF or not 0 <= room.cell_id <= 0xFFFFFFFF:
            raise ValueError(f"room id {room.cell_id:#x} is not an env cell id (low word 0x0100-0xFFFE)")
        if room.cell_id in seen:
            raise ValueError(f"room {format_cell_id(room.cell_id)} is declared twice")
        seen.add(room.cell_id)
        lo, hi = room.box_min, room.box_max
        if not (lo.x < hi.x and lo.y < hi.y and lo.z < hi.z):
            raise ValueError(f"room {format_cell_id(room.cell_id)}: min {lo!r} must be below max {hi!r}")
    for i, a in enumerate(rooms):
        for b in rooms[i + 1 :]:
            if all(
                _get(a.box_min, k) < _get(b.box_max, k) - _TOL
                and _get(b.box_min, k) < _get(a.box_max, k) - _TOL
                for k in range(3)
            ):
                raise ValueError(f"rooms {format_cell_id(a.cell_id)} and {format_cell_id(b.cell_id)} overlap")


def _match_doorways(
    rooms: Sequence[RoomSpec], doorways: Sequence[DoorwaySpec]
) -> list[list[tuple[int, int]]]:
    """For each doorway, the ``(room index, face index)`` it lies on (one or two rooms)."""
    faces = [_box_faces(r.box_min, r.box_max, outward=False) for r in rooms]
    matches = []
    for door in doorways:
        rect = _doorway_rect(door)
        on = [
            (ri, fi)
            for ri, room_faces in enumerate(faces)
            for fi, f in enumerate(room_faces)
            if _on_face(f, rect)
        ]
        if not on:
            raise ValueError(f"doorway {door!r} is not on a wall of any room")
        if len(on) > 2:
            raise ValueError(f"doorway {door!r} lies on walls of more than two rooms")
        matches.append(on)
    return matches


def build_rooms(rooms: Sequence[RoomSpec], doorways: Sequence[DoorwaySpec] = ()) -> list[EnvCell]:
    """Env cells for ``rooms`` joined by ``doorways`` (see the module docstring), in order.

    Raises ``ValueError`` for a bad id, an empty or overlapping box, or a doorway that is not
    flat, not on a room's wall, or on more than two rooms' walls.
    """
    _check_rooms(rooms)
    matches = _match_doorways(rooms, doorways)
    cells = []
    for ri, room in enumerate(rooms):
        shift = room.box_min
        faces = _box_faces(room.box_min, room.box_max, outward=False)
        holes: list[list[_Hole]] = [[] for _ in faces]
        polygons: list[Polygon] = []
        portal_links: list[tuple[Polygon, int]] = []
        for door, on in zip(doorways, matches, strict=True):
            mine = [fi for r, fi in on if r == ri]
            if not mine:
                continue
            _axis, _coord, u0, u1, v0, v1 = _doorway_rect(door)
            face = faces[mine[0]]
            holes[mine[0]].append((u0, u1, v0, v1))
            poly = _rect(face.axis, face.coord, face.sign, u0, u1, v0, v1, shift)
            others = [rooms[r].cell_id for r, _fi in on if r != ri]
            polygons.append(poly)
            portal_links.append((poly, others[0] if others else OUTSIDE_CELL_ID))
        walls = []
        for face, face_holes in zip(faces, holes, strict=True):
            pieces = _wall_pieces(face, face_holes, shift)
            walls.append((_face_plane(face, shift), pieces))
            polygons.extend(pieces)
        planes = [plane for plane, _pieces in walls]
        physics_bsp = _plane_chain_tree(walls, inside_positive=True)
        cell_bsp = _cell_tree(planes, physics_bsp.get_sphere())
        portal_polys = [poly for poly, _other in portal_links]
        physics_polys = [p for _plane, ps in walls for p in ps]
        structure = CellStruct(cell_bsp, physics_bsp, polygons, portal_polys, physics_polys)
        portals = [CellPortal(poly, other, portal_side=0) for poly, other in portal_links]
        cells.append(EnvCell(room.cell_id, structure, Frame(room.box_min.copy()), portals))
    # Each room lists its portals in doorway order: link each to its twin in the other room.
    slot: dict[tuple[int, int], int] = {}
    counts = [0] * len(rooms)
    for k, on in enumerate(matches):
        for ri, _fi in on:
            slot[k, ri] = counts[ri]
            counts[ri] += 1
    for k, on in enumerate(matches):
        if len(on) == 2:
            (ra, _fa), (rb, _fb) = on
            cells[ra].portals[slot[k, ra]].other_portal_id = slot[k, rb]
            cells[rb].portals[slot[k, rb]].other_portal_id = slot[k, ra]
    return cells


def build_house(
    rooms: Sequence[RoomSpec],
    doorways: Sequence[DoorwaySpec],
    wall_thickness: float = 0.25,
    building_id: int = 0,
) -> tuple[BuildingObj, list[EnvCell]]:
    """The rooms (``build_rooms``) and a building around them: a shell ``wall_thickness`` outside
    the rooms' bounding box (four sides and roof, facing out) with the outside doorways cut
    through, and a ``BldPortal`` per outside doorway (``other_portal_id``: that room's portal
    index). The building is not yet in a cell: ``add_to_cell`` the outdoor cell holding its
    origin.

    Raises ``ValueError`` when the rooms do not fill their bounding box, there is no outside
    doorway, or ``wall_thickness`` is not positive.
    """
    if not wall_thickness > 0.0:
        raise ValueError(f"wall thickness must be positive, got {wall_thickness!r}")
    cells = build_rooms(rooms, doorways)
    lo = Vector3(*(min(_get(r.box_min, k) for r in rooms) for k in range(3)))
    hi = Vector3(*(max(_get(r.box_max, k) for r in rooms) for k in range(3)))
    volume = sum(
        (r.box_max.x - r.box_min.x) * (r.box_max.y - r.box_min.y) * (r.box_max.z - r.box_min.z) for r in rooms
    )
    if abs(volume - (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z)) > _TOL:
        raise ValueError("the rooms of a house must fill their bounding box exactly")
    origin = Vector3((lo.x + hi.x) / 2, (lo.y + hi.y) / 2, lo.z)
    t = wall_thickness
    shell_lo = Vector3(lo.x - t, lo.y - t, lo.z)
    shell_hi = Vector3(hi.x + t, hi.y + t, hi.z + t)
    shell_faces = [
        f for f in _box_faces(shell_lo, shell_hi, outward=True) if not (f.axis == 2 and f.sign < 0)
    ]
    room_faces = _box_faces(lo, hi, outward=True)
    holes: list[list[_Hole]] = [[] for _ in shell_faces]
    portals = []
    for cell in cells:
        for index, portal in enumerate(cell.portals):
            if portal.other_cell_id != OUTSIDE_CELL_ID:
                continue
            corners = [cell.pos.frame.localtoglobal(v) for v in portal.portal.vertices]
            xs, ys, zs = [c.x for c in corners], [c.y for c in corners], [c.z for c in corners]
            door = DoorwaySpec(Vector3(min(xs), min(ys), min(zs)), Vector3(max(xs), max(ys), max(zs)))
            rect = _doorway_rect(door)
            face = next(f for f in room_faces if _on_face(f, rect))
            if face.axis == 2 and face.sign < 0:
                raise ValueError(f"outside doorway {door!r} is in the floor; a house has no floor shell")
            shell_index = next(
                i for i, f in enumerate(shell_faces) if f.axis == face.axis and f.sign == face.sign
            )
            holes[shell_index].append(rect[2:])
            portals.append(BldPortal(cell.id, index, stab_list=[c.id for c in cells]))
    if not portals:
        raise ValueError("a house needs at least one doorway to the outside")
    walls = [
        (_face_plane(f, origin), _wall_pieces(f, h, origin)) for f, h in zip(shell_faces, holes, strict=True)
    ]
    shell = _plane_chain_tree(walls, inside_positive=False)
    return BuildingObj(shell, Frame(origin), portals, building_id=building_id), cells
