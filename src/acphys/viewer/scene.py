"""The world a replay shows, gathered from a built :class:`~acphys.world.world.World` into flat
arrays: terrain per landblock, the polygons of static objects' physics BSPs, their cylspheres and
spheres, building shells and rooms (env cells).

Everything is in the *scene frame*: scenario-local metres, landblock ``0xXXYY`` starting at
``(XX - X0)·192, (YY - Y0)·192`` where ``(X0, Y0)`` is the smallest landblock index of the world
(and of the trace), so a one-landblock scenario spans 0-192 m; z is the world's height. The
geometry is what the world holds, not derived again: terrain heights are the vertices
``ConstructVertices`` made (through the height table), cut directions those of
``ConstructPolygons``, water the vertices whose terrain type is a water type; objects are their
parts' physics BSP polygons placed by the parts' frames and scales, as the collision code reads them.
"""

from __future__ import annotations

from array import array
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from acphys.constants import BLOCK_LENGTH
from acphys.flags import PhysicsState
from acphys.geometry.bsp import BSPPolygon, BSPTree
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.world.env_cell import EnvCell
from acphys.world.terrain import TERRAIN_SURF_CHAR, SurfChar, terrain_type

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj
    from acphys.world.world import World

#: The most triangles the scene keeps (static objects, shells and rooms together): about 40 bytes
#: each in the page; a landblock of retail buildings and scenery has some tens of thousands.
MAX_SCENE_TRIANGLES = 200_000
#: The most cylinders and spheres of static objects the scene keeps.
MAX_SCENE_PRIMITIVES = 100_000


def block_index(cell_or_block: int) -> tuple[int, int]:
    """``(XX, YY)`` of a cell id ``0xXXYY....`` (or of a landblock ``0xXXYY`` when below 0x10000)."""
    block = cell_or_block >> 16 if cell_or_block > 0xFFFF else cell_or_block
    return (block >> 8) & 0xFF, block & 0xFF


def block_offset(cell_id: int, base: tuple[int, int]) -> tuple[float, float]:
    """Where the landblock of ``cell_id`` starts in the scene frame (metres)."""
    bx, by = block_index(cell_id)
    return (bx - base[0]) * BLOCK_LENGTH, (by - base[1]) * BLOCK_LENGTH


@dataclass
class SceneObject:
    """One thing in the scene, for the page's list: what it is and where (scene frame)."""

    name: str
    kind: str  # "object", "building" or "room"
    at: tuple[float, float, float]


@dataclass
class TerrainBlock:
    """One landblock's terrain: its 9×9 vertex heights (vertex ``(x, y)`` at ``9x + y``), which
    vertices are water, and each cell's cut (``8cx + cy``; True: SW-NE)."""

    landblock: int
    x: float
    y: float
    heights: list[float]
    water: list[int]
    cut: list[int]


@dataclass
class Scene:
    """The static world, in the scene frame. Triangles are 9 floats each, with the index of
    their owner in ``objects``; cylinders ``x, y, z (low point), radius, height``; spheres
    ``x, y, z, radius``."""

    base: tuple[int, int]
    terrain: list[TerrainBlock] = field(default_factory=list)
    objects: list[SceneObject] = field(default_factory=list)
    solids: array[float] = field(default_factory=lambda: array("f"))
    solid_owner: array[int] = field(default_factory=lambda: array("I"))
    shells: array[float] = field(default_factory=lambda: array("f"))
    shell_owner: array[int] = field(default_factory=lambda: array("I"))
    rooms: array[float] = field(default_factory=lambda: array("f"))
    room_owner: array[int] = field(default_factory=lambda: array("I"))
    cylinders: array[float] = field(default_factory=lambda: array("f"))
    cylinder_owner: array[int] = field(default_factory=lambda: array("I"))
    spheres: array[float] = field(default_factory=lambda: array("f"))
    sphere_owner: array[int] = field(default_factory=lambda: array("I"))
    #: What was left out (one line each), for the page and the command line.
    notes: list[str] = field(default_factory=list)

    @property
    def triangles(self) -> int:
        return (len(self.solids) + len(self.shells) + len(self.rooms)) // 9


def world_landblocks(world: World) -> list[int]:
    """The world's landblocks (``0xXXYY``), sorted."""
    return sorted(world.landscape.landblocks())


def gather_scene(world: World, base: tuple[int, int]) -> Scene:
    """The terrain, static objects, buildings and rooms of ``world`` in the scene frame of ``base``."""
    scene = Scene(base)
    for landblock in world_landblocks(world):
        block = world.landscape.get_landblock(landblock << 16)
        if block is None:  # pragma: no cover - landblocks() lists only present blocks
            continue
        terrain = block.terrain
        x, y = block_offset(landblock << 16 | 0xFFFF, base)
        scene.terrain.append(
            TerrainBlock(
                landblock=landblock,
                x=x,
                y=y,
                heights=[v.z for v in terrain.vertices],
                water=[
                    int(TERRAIN_SURF_CHAR[terrain_type(word)] == SurfChar.WATER) for word in terrain.terrain
                ],
                cut=[int(cut) for cut in terrain.sw_to_ne_cut],
            )
        )
    for obj in static_objects(world):
        _add_object(scene, obj)
    for landblock in world_landblocks(world):
        block = world.landscape.get_landblock(landblock << 16)
        if block is None:  # pragma: no cover
            continue
        for cell in block.lcell:
            building = getattr(cell, "building", None)
            if building is None:
                continue
            dx, dy = block_offset(cell.id, base)
            frame = building.pos.frame
            o = frame.origin
            owner = _own(scene, f"building in {cell.id:#010x}", "building", (dx + o.x, dy + o.y, o.z))
            scale = building.scale
            _add_polygons(
                scene, "shells", owner, _polygons(building.physics_bsp), frame, (scale,) * 3, dx, dy
            )
        for cell in world.landscape.env_cells(landblock):
            if not isinstance(cell, EnvCell):
                continue
            dx, dy = block_offset(cell.id, base)
            frame = cell.pos.frame
            o = frame.origin
            owner = _own(scene, f"room {cell.id:#010x}", "room", (dx + o.x, dy + o.y, o.z))
            portals = {id(p) for p in cell.structure.portals}
            polygons = [p for p in cell.structure.polygons if id(p) not in portals]
            _add_polygons(scene, "rooms", owner, polygons, frame, (1.0, 1.0, 1.0), dx, dy)
    return scene


def static_objects(world: World) -> Iterator[PhysicsObj]:
    """The world's static objects (``STATIC`` state), in id order."""
    for obj in sorted(world._objects.values(), key=lambda o: o.id):
        if obj.state & PhysicsState.STATIC and obj.part_array is not None:
            yield obj


def _own(scene: Scene, name: str, kind: str, at: tuple[float, float, float]) -> int:
    scene.objects.append(SceneObject(name, kind, at))
    return len(scene.objects) - 1


def _add_object(scene: Scene, obj: PhysicsObj) -> None:
    """An object's shapes: each part's physics BSP at the part's frame and scale, the setup's
    cylspheres and spheres at the object's frame and scale."""
    parts = obj.part_array
    assert parts is not None
    setup = parts.setup
    dx, dy = block_offset(obj.position.objcell_id, scene.base)
    frame = obj.position.frame
    o = frame.origin
    owner = _own(scene, obj.name, "object", (dx + o.x, dy + o.y, o.z))
    for part in parts.parts:
        if part.physics_bsp is None:
            continue
        pdx, pdy = block_offset(part.pos.objcell_id or obj.position.objcell_id, scene.base)
        s = part.gfxobj_scale
        _add_polygons(
            scene, "solids", owner, _polygons(part.physics_bsp), part.pos.frame, (s.x, s.y, s.z), pdx, pdy
        )
    scale = parts.scale
    for cyl in setup.cylspheres:
        low = frame.localtoglobal(cyl.low_pt * scale)
        if _primitive_room(scene):
            scene.cylinders.extend((dx + low.x, dy + low.y, low.z, cyl.radius * scale, cyl.height * scale))
            scene.cylinder_owner.append(owner)
    for sphere in setup.spheres:
        centre = frame.localtoglobal(sphere.center * scale)
        if _primitive_room(scene):
            scene.spheres.extend((dx + centre.x, dy + centre.y, centre.z, sphere.radius * scale))
            scene.sphere_owner.append(owner)


def _primitive_room(scene: Scene) -> bool:
    if len(scene.cylinder_owner) + len(scene.sphere_owner) < MAX_SCENE_PRIMITIVES:
        return True
    note = f"more than {MAX_SCENE_PRIMITIVES:,} cylinders and spheres: the rest are not drawn"
    if note not in scene.notes:
        scene.notes.append(note)
    return False


def _add_polygons(
    scene: Scene,
    layer: str,
    owner: int,
    polygons: Iterable,
    frame: Frame,
    scale: tuple[float, float, float],
    dx: float,
    dy: float,
) -> None:
    """Each convex polygon as a fan of triangles, placed by ``frame`` after ``scale`` and moved
    into the scene frame by ``(dx, dy)``."""
    out: array[float] = getattr(scene, layer)
    owners: array[int] = getattr(scene, layer.rstrip("s") + "_owner")
    sx, sy, sz = scale
    for poly in polygons:
        points = []
        for v in poly.vertices:
            p = frame.localtoglobal(Vector3(v.x * sx, v.y * sy, v.z * sz))
            points.append((dx + p.x, dy + p.y, p.z))
        for k in range(1, len(points) - 1):
            if scene.triangles >= MAX_SCENE_TRIANGLES:
                note = (
                    f"more than {MAX_SCENE_TRIANGLES:,} triangles of objects and buildings: "
                    "the rest are not drawn"
                )
                if note not in scene.notes:
                    scene.notes.append(note)
                return
            out.extend((*points[0], *points[k], *points[k + 1]))
            owners.append(owner)


def _polygons(tree: BSPTree | None) -> list[BSPPolygon]:
    """A physics BSP's polygons (none without one)."""
    return tree.polygons() if tree is not None else []
