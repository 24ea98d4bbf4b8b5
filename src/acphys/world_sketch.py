"""What a picture shows of a simulation's world: terrain, water, static objects, buildings, rooms
and doorways, as plain arrays (no matplotlib here).

:func:`sketch_world` reads a built :class:`~acphys.simulation.Simulation` (a scenario loaded, or a
run at hand) and returns a :class:`WorldSketch` in landblock-global metres (landblock ``0xXXYY``'s
south-west corner at ``(XX · 192, YY · 192)``, the frame :mod:`acphys.plot` collects paths in):

- each landblock's terrain: its 9×9 vertex heights, the two triangles of each 24-m cell as retail
  cuts them (so contours drawn on them are the ground the bodies walk on) and each cell's water;
- each static object's solid faces (its parts' physics BSP polygons, placed and scaled), spheres
  and cylspheres;
- each building's shell faces, each indoor (env) cell's polygons (its room) and its portals
  (doorways).

:mod:`acphys.plot` draws them from above and from the south; a viewer may draw them otherwise.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from acphys.constants import BLOCK_LENGTH, CELLS_PER_BLOCK
from acphys.flags import PhysicsState
from acphys.math.cell_id import cell_of, format_cell_id, landblock_of
from acphys.world.env_cell import EnvCell
from acphys.world.land_cell import SortCell
from acphys.world.terrain import SIDE_VERTEX_COUNT

if TYPE_CHECKING:
    from acphys.geometry.bsp import BSPPolygon, BSPTree
    from acphys.math.frame import Frame
    from acphys.physics_obj import PhysicsObj
    from acphys.simulation import Simulation
    from acphys.world.world import World

#: The most faces a sketch keeps over all its shapes: some 60 MB of vertices at most, and more
#: than a picture can tell apart. Past it, shapes keep their anchor (drawn as a cross) alone and
#: :attr:`WorldSketch.faces_left_out` counts what was left out.
MAX_SKETCH_FACES = 200_000

#: The kinds of :class:`ShapeSketch`, in the order a picture draws them (later on top).
SHAPE_KINDS = ("building", "room", "object", "doorway")


@dataclass(frozen=True)
class TerrainSketch:
    """One landblock's ground: vertex ``i = 9·ix + iy`` at ``(x[i], y[i], z[i])`` (global metres),
    ``triangles`` the 128 terrain triangles (rows of 3 vertex indices, retail's cuts) and ``water``
    each cell's :class:`~acphys.world.terrain.WaterType` value (index ``8·cx + cy``)."""

    block: int
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    triangles: np.ndarray
    water: tuple[int, ...]

    @property
    def corner(self) -> tuple[float, float]:
        """The landblock's south-west corner, in global metres."""
        return (self.block >> 8) * BLOCK_LENGTH, (self.block & 0xFF) * BLOCK_LENGTH


@dataclass
class ShapeSketch:
    """One thing of the world: ``kind`` (one of :data:`SHAPE_KINDS`), a ``name`` to label it with,
    its ``anchor`` (origin, global metres), ``faces`` (3-D polygons, each an ``(n, 3)`` array),
    ``spheres`` ``(x, y, z, r)`` and ``cylinders`` ``(x, y, z_low, r, height)``."""

    kind: str
    name: str
    anchor: tuple[float, float, float]
    faces: list[np.ndarray] = field(default_factory=list)
    spheres: list[tuple[float, float, float, float]] = field(default_factory=list)
    cylinders: list[tuple[float, float, float, float, float]] = field(default_factory=list)

    @property
    def empty(self) -> bool:
        """Whether the shape has nothing but its anchor."""
        return not (self.faces or self.spheres or self.cylinders)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """``(low, high)``: the corners of the box around the shape (its anchor when empty)."""
        points = list(self.faces)
        for x, y, z, r in self.spheres:
            points.append(np.array([[x - r, y - r, z - r], [x + r, y + r, z + r]]))
        for x, y, z, r, h in self.cylinders:
            points.append(np.array([[x - r, y - r, z], [x + r, y + r, z + h]]))
        if not points:
            points.append(np.asarray([self.anchor], dtype=np.float64))
        every = np.concatenate(points)
        return every.min(axis=0), every.max(axis=0)


@dataclass
class WorldSketch:
    """A simulation's world as a picture draws it (see the module docstring)."""

    name: str = ""
    terrain: list[TerrainSketch] = field(default_factory=list)
    shapes: list[ShapeSketch] = field(default_factory=list)
    #: Faces left out past :data:`MAX_SKETCH_FACES`.
    faces_left_out: int = 0

    @property
    def landblocks(self) -> set[int]:
        """The landblocks (``0xXXYY``) with terrain."""
        return {terrain.block for terrain in self.terrain}

    def of_kind(self, kind: str) -> list[ShapeSketch]:
        return [shape for shape in self.shapes if shape.kind == kind]


def sketch_world(sim: Simulation) -> WorldSketch:
    """The sketch of ``sim``'s world: its landblocks' terrain, and the static objects, buildings,
    rooms and doorways in them (the simulation's bodies are not part of it)."""
    world = sim.world
    bodies = {id(body) for body in sim.bodies}
    blocks = set(world.landscape.landblocks())
    blocks.update(landblock_of(body.position.objcell_id) for body in sim.bodies if body.position.objcell_id)
    sketch = WorldSketch(name=sim.name)
    budget = _Budget()
    for block in sorted(blocks):
        landblock = world.landscape.get_landblock(block << 16)
        if landblock is not None:
            sketch.terrain.append(_terrain(block, landblock.terrain))
    seen: set[int] = set()
    for block in sorted(blocks):
        for cell in _cells(world, block):
            if isinstance(cell, SortCell) and cell.building is not None and id(cell.building) not in seen:
                seen.add(id(cell.building))
                sketch.shapes.append(_building(cell.building, cell.id, budget))
            if isinstance(cell, EnvCell):
                sketch.shapes.extend(_room(cell, budget))
            for obj in cell.objects:
                if id(obj) in seen or id(obj) in bodies or not obj.state & PhysicsState.STATIC:
                    continue
                seen.add(id(obj))
                sketch.shapes.append(_object(obj, budget))
    sketch.shapes = _unique_doorways(sketch.shapes)
    sketch.faces_left_out = budget.left_out
    return sketch


class _Budget:
    """Counts faces against :data:`MAX_SKETCH_FACES`."""

    def __init__(self) -> None:
        self.kept = 0
        self.left_out = 0

    def take(self, faces: list[np.ndarray]) -> list[np.ndarray]:
        room = max(0, MAX_SKETCH_FACES - self.kept)
        kept = faces[:room]
        self.kept += len(kept)
        self.left_out += len(faces) - len(kept)
        return kept


def _cells(world: World, block: int) -> Iterator[Any]:
    """The land cells of ``block`` (those of its terrain, else the world's empty ones), then its
    env cells."""
    landblock = world.landscape.get_landblock(block << 16)
    if landblock is not None:
        yield from landblock.lcell
    else:
        for index in range(CELLS_PER_BLOCK * CELLS_PER_BLOCK):
            cell = world.get_cell(cell_of(block, index + 1))
            if cell is not None:
                yield cell
    yield from world.landscape.env_cells(block)


def _corner(cell_id: int) -> np.ndarray:
    block = landblock_of(cell_id)
    return np.array([(block >> 8) * BLOCK_LENGTH, (block & 0xFF) * BLOCK_LENGTH, 0.0])


def _terrain(block: int, terrain: Any) -> TerrainSketch:
    corner = np.array([(block >> 8) * BLOCK_LENGTH, (block & 0xFF) * BLOCK_LENGTH])
    vertices = np.array([(v.x, v.y, v.z) for v in terrain.vertices], dtype=np.float64)
    triangles = []
    side = SIDE_VERTEX_COUNT
    for cx in range(CELLS_PER_BLOCK):
        for cy in range(CELLS_PER_BLOCK):
            sw, nw = cx * side + cy, cx * side + cy + 1
            se, ne = sw + side, nw + side
            if terrain.sw_to_ne_cut[cx * CELLS_PER_BLOCK + cy]:  # as ConstructPolygons cuts the cell
                triangles += [(sw, se, ne), (sw, ne, nw)]
            else:
                triangles += [(sw, se, nw), (ne, nw, se)]
    return TerrainSketch(
        block=block,
        x=vertices[:, 0] + corner[0],
        y=vertices[:, 1] + corner[1],
        z=vertices[:, 2],
        triangles=np.array(triangles, dtype=np.int32),
        water=tuple(int(kind) for kind in terrain.cell_water_types),
    )


def _placed(polygons: Iterable[Any], frame: Frame, corner: np.ndarray, scale: Any = 1.0) -> list[np.ndarray]:
    """``polygons`` (local to ``frame``, before ``scale``) in global metres."""
    matrix = frame.to_matrix()
    rotation, origin = matrix[:3, :3], matrix[:3, 3] + corner
    scaling = np.asarray(scale, dtype=np.float64)
    faces = []
    for poly in polygons:
        local = np.array([(v.x, v.y, v.z) for v in getattr(poly, "vertices", ())], dtype=np.float64)
        if len(local) >= 3:
            faces.append((local * scaling) @ rotation.T + origin)
    return faces


def _point(frame: Frame, corner: np.ndarray, x: float, y: float, z: float) -> np.ndarray:
    matrix = frame.to_matrix()
    return matrix[:3, :3] @ np.array([x, y, z]) + matrix[:3, 3] + corner


def _anchor(frame: Frame, corner: np.ndarray) -> tuple[float, float, float]:
    origin = frame.origin
    return (float(origin.x + corner[0]), float(origin.y + corner[1]), float(origin.z))


def _object(obj: PhysicsObj, budget: _Budget) -> ShapeSketch:
    corner = _corner(obj.position.objcell_id)
    frame = obj.position.frame
    shape = ShapeSketch("object", obj.name, _anchor(frame, corner))
    parts = obj.part_array
    if parts is None:
        return shape
    faces: list[np.ndarray] = []
    for part in parts.parts:
        if part.physics_bsp is not None:
            scale = part.gfxobj_scale
            faces += _placed(_polygons(part.physics_bsp), part.pos.frame, corner, (scale.x, scale.y, scale.z))
    shape.faces = budget.take(faces)
    scale = parts.scale
    for sphere in parts.setup.spheres:
        c = sphere.center
        x, y, z = _point(frame, corner, c.x * scale, c.y * scale, c.z * scale)
        shape.spheres.append((float(x), float(y), float(z), float(sphere.radius * scale)))
    for cyl in parts.setup.cylspheres:
        low = cyl.low_pt
        x, y, z = _point(frame, corner, low.x * scale, low.y * scale, low.z * scale)
        shape.cylinders.append(
            (float(x), float(y), float(z), float(cyl.radius * scale), float(cyl.height * scale))
        )
    return shape


def _building(building: Any, cell_id: int, budget: _Budget) -> ShapeSketch:
    corner = _corner(cell_id)
    frame = building.pos.frame
    shape = ShapeSketch("building", f"building in {format_cell_id(cell_id)}", _anchor(frame, corner))
    shape.faces = budget.take(_placed(_polygons(building.physics_bsp), frame, corner, building.scale))
    return shape


def _room(cell: EnvCell, budget: _Budget) -> list[ShapeSketch]:
    """The room of an env cell (its polygons but the portals) and its doorways (each portal)."""
    corner = _corner(cell.id)
    frame = cell.pos.frame
    structure = cell.structure
    portals = {id(poly) for poly in structure.portals}
    walls = [poly for poly in structure.polygons if id(poly) not in portals]
    anchor = _anchor(frame, corner)
    room = ShapeSketch(
        "room", f"room {cell.id & 0xFFFF:#06x}", anchor, budget.take(_placed(walls, frame, corner))
    )
    doors = [
        ShapeSketch("doorway", f"doorway of {format_cell_id(cell.id)}", _middle(face), budget.take([face]))
        for face in _placed(structure.portals, frame, corner)
    ]
    if room.faces:  # the room's anchor: the middle of its floor, where its label goes
        low, high = room.bounds()
        room.anchor = (float(low[0] + high[0]) / 2, float(low[1] + high[1]) / 2, float(low[2]))
    return [room, *doors]


def _middle(face: np.ndarray) -> tuple[float, float, float]:
    x, y, z = face.mean(axis=0)
    return float(x), float(y), float(z)


def _unique_doorways(shapes: list[ShapeSketch]) -> list[ShapeSketch]:
    """Each doorway once: the portal between two rooms is in both rooms' polygons."""
    seen: set[bytes] = set()
    kept = []
    for shape in shapes:
        if shape.kind == "doorway" and shape.faces:
            key = (np.round(np.sort(shape.faces[0], axis=0), 3) + 0.0).tobytes()  # -0.0 as 0.0
            if key in seen:
                continue
            seen.add(key)
        kept.append(shape)
    return kept


def _polygons(tree: BSPTree | None) -> list[BSPPolygon]:
    """A physics BSP's polygons (none without one)."""
    return tree.polygons() if tree is not None else []
