"""Retail ``CObjCell``, the base of every cell, with ``CELLARRAY`` and ``CShadowObj``.

A cell holds the bodies whose origin is in it (``objects``) and a shadow entry for every body
that overlaps it (``shadow_objects``); collisions are found through the shadows, so a body is
hit from every cell it reaches into. ``find_cell_list`` gathers the cells a set of spheres
touches: the outdoor cells under them (``LandCell.add_all_outside_cells``), then whatever each
cell adds through its virtual ``find_transit_cells`` (buildings, portals), then the cell that
holds the first sphere's centre.

Retail reaches cells through globals (``CLandCell::Get``, ``CEnvCell::GetVisible``); acphys
gives the ``CellArray`` a :class:`CellSource` (a ``World``), and every lookup a cell makes while
filling the array goes through ``cell_array.source.get_cell(cell_id)``.

Subclasses (``LandCell``, ``EnvCell``) override the retail virtuals with these signatures:
``find_transit_cells(p, spheres, cell_array, path)``, ``point_in_cell(point)``,
``find_env_collisions(transition)``, ``find_collisions(transition)``.

Each cell also keeps a voyeur table for global detection cylinders (``add_voyeur``,
``remove_voyeur``): bodies entering, leaving, hiding in or unhiding in a watched cell are reported to
every voyeur's ``receive_detection_update``. Retail's table is a hash; acphys visits voyeurs in
insertion order.

Not ported: lights, clip planes, visibility and the attack checks; they do not touch the physics
tick.

Divergences from ACE's ``ObjCell.cs`` (the decompilation wins):

- ACE only looks for the current cell when the caller's cell reference is already non-null
  (``if (currCell != null)``); retail tests the out-pointer itself, so the cell is found
  whenever the caller asks for it (acclient.c:347028).
- ACE returns as soon as the current cell is indoors, skipping the ``do_not_load_cells`` pruning;
  retail breaks out of the loop, sets ``hits_interior_cell`` and still prunes
  (acclient.c:347059-347063).
- ACE prunes whenever the start cell is indoors; retail prunes only inside the
  ``visible cell && num_sphere`` block (acclient.c:347009).
- ACE keeps the objects and shadows in order (``List.Remove``); retail moves the last entry into
  the freed slot (acclient.c:347789, 346851).
- ACE's ``find_obj_collisions`` walks the shadows last-to-first and skips ethereal hits during
  placement (marked custom); retail walks first-to-last and stops at the first result that is
  not OK (acclient.c:347151-347162).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from operator import attrgetter
from typing import TYPE_CHECKING, Any, NamedTuple, Protocol

from acphys.constants import BLOCK_LENGTH
from acphys.flags import ObjectInfoState, TransitionState, member_namespace
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import FIRST_ENV_CELL, format_cell_id, get_block_offset
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.transition.transition import InsertType
from acphys.world.terrain import ENTIRELY_WATER_DEPTH, SOLID_VERTEX_WATER_DEPTH, WaterType

if TYPE_CHECKING:
    from acphys.geometry.cylsphere import CylSphere
    from acphys.managers.detection import DetectionCylsphere
    from acphys.physics_obj import PhysicsObj
    from acphys.physics_part import PhysicsPart
    from acphys.transition.collision_info import CollisionInfo
    from acphys.transition.object_info import ObjectInfo
    from acphys.transition.transition import SpherePath

OI = member_namespace(ObjectInfoState)
TS = member_namespace(TransitionState)
WT = member_namespace(WaterType)
IT = member_namespace(InsertType)

#: ``DetectionType`` values the voyeur calls send (acclient.h:6075).
ENTERED_DETECTION = 1
LEFT_DETECTION = 2

#: ``find_cell_list`` for cylspheres fills a static array of 10 spheres (acclient.c:347351-347357).
MAX_CYLSPHERE_CELL_LIST = 10

#: A cell files its shadows by place once it holds this many, so that a sweep through a crowded
#: cell asks only the bodies within its reach (:meth:`ObjCell.find_obj_collisions`): below it,
#: asking every body costs less than keeping the files.
SHADOW_INDEX_MIN = 16
#: ... and forgets the files when it falls below this many (half, so that a cell at the edge
#: does not file and forget at every step).
SHADOW_INDEX_DROP = 8
#: The side of the squares (m) a filed cell sorts its shadows into, by the centre of each body's
#: box: about a human's width, so a sweep looks into a few squares holding a few bodies each. A
#: body wider than two squares is not filed but asked by every sweep.
SHADOW_TILE = 2.0
#: How much farther apart than touching (m) a body's box and a sweep's must be for the sweep to
#: pass the body by: far beyond the float32 rounding of positions a few landblocks across
#: (about 3e-5 m at 400 m), far below any shape.
SHADOW_REACH_MARGIN = 0.01

#: A box in landblock-global metres: x0, y0, z0, x1, y1, z1.
Box = tuple[float, float, float, float, float, float]

_INDEX = attrgetter("index")


class CellSource(Protocol):
    """Where cells are looked up by id (retail ``CLandCell::Get`` / ``CEnvCell::GetVisible``)."""

    def get_cell(self, cell_id: int) -> ObjCell | None: ...


class CellTransition(Protocol):
    """What the cell routines read from a ``CTransition``."""

    object_info: ObjectInfo
    sphere_path: SpherePath
    collision_info: CollisionInfo


class ShadowBody(Protocol):
    """The body side of a shadow (``PhysicsObj``): its collisions with a sweep and with a body,
    and the box its collision shapes fill (``CellMembership.collision_box``)."""

    parent: object | None

    def find_obj_collisions(self, transition: Any) -> TransitionState: ...

    def check_collision(self, obj: Any) -> bool: ...

    def collision_box(self) -> Box | None: ...


class BlockWater(Protocol):
    """What a cell reads from its landblock (``myLandBlock_``) for water."""

    water_type: WaterType

    def calc_water_depth(self, cell_id: int, point: Vector3) -> float: ...


class ShadowObj:
    """Retail ``CShadowObj`` (acclient.h): a body's entry in one cell it overlaps.

    acphys adds where the entry stands in its cell's list (``index``) and, in a cell that files
    its shadows, the body's box (``box``, None: asked by every sweep) and its square (``tile``).
    """

    __slots__ = ("box", "cell", "cell_id", "index", "physobj", "tile")

    def __init__(self, physobj: ShadowBody, cell_id: int = 0) -> None:
        self.physobj = physobj
        self.cell_id = cell_id
        self.cell: ObjCell | None = None
        self.index = -1
        self.box: Box | None = None
        self.tile: tuple[int, int] | None = None

    def __repr__(self) -> str:
        return f"ShadowObj({self.physobj!r}, {format_cell_id(self.cell_id)})"


class GlobalVoyeurInfo:
    """Retail ``GlobalVoyeurInfo`` (acclient.h:52784): a voyeur of a cell, its cylinder's
    detection type and how many times it has added itself."""

    __slots__ = ("object_iid", "ref_count", "type")

    def __init__(self, object_iid: int, type: int, ref_count: int) -> None:
        self.object_iid = object_iid
        self.type = type
        self.ref_count = ref_count

    def __repr__(self) -> str:
        return f"GlobalVoyeurInfo(0x{self.object_iid:08X}, type={self.type}, ref_count={self.ref_count})"


def _tell_voyeur(obj: PhysicsObj, voyeur_id: int, status: int) -> None:
    """Report ``obj`` to the voyeur ``voyeur_id`` (when it exists), unless the object is the voyeur,
    has id 0 or is parented (the inline test of acclient.c:347477, 347537, 347596, 347738)."""
    from acphys.managers.detection import DetectionInfo, DetectionType

    if obj.id == voyeur_id or not obj.id or obj.parent is not None:
        return
    voyeur = obj.world.get_object(voyeur_id)
    if voyeur is not None:
        voyeur.receive_detection_update(DetectionInfo(obj.id, DetectionType(status)))


class CellInfo(NamedTuple):
    """Retail ``CELLINFO``: a cell id and the cell (None when it is not loaded)."""

    cell_id: int
    cell: ObjCell | None


class CellArray:
    """Retail ``CELLARRAY``: the cells a sweep touches, each id once.

    Retail: CELLARRAY::CELLARRAY @ 0x0050A920 (acclient.c:312113)
    """

    __slots__ = ("added_outside", "cells", "do_not_load_cells", "source")

    def __init__(self, source: CellSource) -> None:
        self.source = source
        self.added_outside = False
        self.do_not_load_cells = False
        self.cells: list[CellInfo] = []

    def __repr__(self) -> str:
        ids = ", ".join(format_cell_id(info.cell_id) for info in self.cells)
        return f"CellArray([{ids}])"

    @property
    def num_cells(self) -> int:
        return len(self.cells)

    def cell_ids(self) -> list[int]:
        """The ids in array order."""
        return [info.cell_id for info in self.cells]

    def add_cell(self, cell_id: int, cell: ObjCell | None) -> None:
        """Append ``(cell_id, cell)`` unless ``cell_id`` is already there.

        Retail: CELLARRAY::add_cell @ 0x006B4FF0 (acclient.c:718895)
        """
        for info in self.cells:
            if info.cell_id == cell_id:
                return
        self.cells.append(CellInfo(cell_id, cell))

    def remove_cell(self, index: int) -> None:
        """Drop entry ``index`` by moving the last entry into its slot.

        Retail: CELLARRAY::remove_cell @ 0x006B4E80 (acclient.c:718761)
        """
        if not self.cells:
            return
        if not 0 <= index < len(self.cells):
            raise ValueError(f"remove_cell: index {index} outside the {len(self.cells)} cells")
        last = self.cells.pop()
        if index < len(self.cells):
            self.cells[index] = last

    def clear(self) -> None:
        """``num_cells = 0; added_outside = 0`` as ``find_cell_list`` starts (acclient.c:346987-346988)."""
        self.cells = []
        self.added_outside = False


class ObjCell:
    """Retail ``CObjCell`` (acclient.h:30915): id, position, objects and shadow objects.

    ``pos`` is the cell's position (landblock-local frame); ``landblock`` is ``myLandBlock_``;
    ``stab_list`` the ids of the cells visible from this one (env cells fill it).

    Retail: CObjCell::CObjCell @ 0x0052AF70 (acclient.c:346602)
    """

    __slots__ = (
        "_reach",
        "_unfiled",
        "id",
        "landblock",
        "objects",
        "pos",
        "restriction_obj",
        "seen_outside",
        "shadow_objects",
        "shadow_tiles",
        "stab_list",
        "voyeur_table",
        "water_type",
    )

    def __init__(self, cell_id: int) -> None:
        if isinstance(cell_id, bool) or not isinstance(cell_id, int) or not 0 <= cell_id <= 0xFFFFFFFF:
            raise ValueError(f"cell id must be a 32-bit integer, got {cell_id!r}")
        self.id = cell_id
        self.water_type = WT.NOT_WATER
        self.pos = Position(cell_id)
        self.objects: list[PhysicsObj] = []
        self.shadow_objects: list[ShadowObj] = []
        #: Not retail: with ``SHADOW_INDEX_MIN`` shadows or more, the filed ones by square
        #: (``SHADOW_TILE``) of their box's centre, the others (no box, or too wide) in
        #: ``_unfiled``, and ``_reach`` the widest half-width filed; None below that.
        self.shadow_tiles: dict[tuple[int, int], set[ShadowObj]] | None = None
        self._unfiled: set[ShadowObj] = set()
        self._reach = 0.0
        #: Id of the object that guards entry (housing barriers); 0 for none.
        self.restriction_obj = 0
        self.stab_list: list[int] = []
        self.seen_outside = False
        self.landblock: BlockWater | None = None
        #: ``voyeur_table``: the global detection cylinders watching this cell, by voyeur id; made by
        #: the first ``add_voyeur``.
        self.voyeur_table: dict[int, GlobalVoyeurInfo] | None = None

    def __repr__(self) -> str:
        return f"{type(self).__name__}({format_cell_id(self.id)})"

    @property
    def num_objects(self) -> int:
        return len(self.objects)

    @property
    def num_shadow_objects(self) -> int:
        return len(self.shadow_objects)

    # --- object and shadow lists ----------------------------------------------------------

    def add_object(self, obj: PhysicsObj) -> None:
        """Append ``obj`` to the object list and report it ``Entered`` to the voyeurs (a hidden
        object is not reported).

        Retail: CObjCell::add_object @ 0x0052BF60 (acclient.c:347702)
        """
        self.objects.append(obj)
        self.unhide_object(obj)

    def remove_object(self, obj: PhysicsObj) -> None:
        """Remove ``obj`` (by identity) by moving the last object into its slot, then report it
        ``Left`` to the voyeurs; absent is a no-op.

        Retail: CObjCell::remove_object @ 0x0052C040 (acclient.c:347764)
        """
        if _swap_remove(self.objects, obj):
            self.update_all_voyeur(obj, LEFT_DETECTION)

    # --- voyeurs (global detection) -------------------------------------------------------

    def add_voyeur(self, voyeur_id: int, detcyl: DetectionCylsphere | None) -> bool:
        """Let ``voyeur_id``'s global cylinder watch this cell. A known voyeur only counts one more
        reference; a new one hears ``Entered`` for every object already here (hidden ones too).
        False (nothing done) for voyeur id 0 or no cylinder.

        Retail: CObjCell::add_voyeur @ 0x0052BB60 (acclient.c:347422)
        """
        if not voyeur_id or detcyl is None:
            return False
        if self.voyeur_table is None:
            self.voyeur_table = {}
        known = self.voyeur_table.pop(voyeur_id, None)
        if known is not None:
            known.ref_count += 1
            self.voyeur_table[voyeur_id] = known
            return True
        self.voyeur_table[voyeur_id] = GlobalVoyeurInfo(voyeur_id, detcyl.detection_type, 1)
        for obj in list(self.objects):
            _tell_voyeur(obj, voyeur_id, ENTERED_DETECTION)
        return True

    def remove_voyeur(self, voyeur_id: int, detcyl: DetectionCylsphere | None) -> bool:
        """Drop one reference of ``voyeur_id``; at none left it goes and hears ``Left`` for every
        object here. False when it is not a voyeur of this cell (``detcyl`` is unused).

        Retail: CObjCell::remove_voyeur @ 0x0052BC90 (acclient.c:347501)
        """
        if self.voyeur_table is None:
            return False
        known = self.voyeur_table.pop(voyeur_id, None)
        if known is None:
            return False
        known.ref_count -= 1
        if known.ref_count > 0:
            self.voyeur_table[voyeur_id] = known
            return True
        for obj in list(self.objects):
            _tell_voyeur(obj, voyeur_id, LEFT_DETECTION)
        return True

    def update_all_voyeur(self, obj: PhysicsObj, detection_type: int) -> None:
        """Report ``obj`` with ``detection_type`` to every voyeur; a hidden object (``HIDDEN``) is
        never reported ``Entered``, and objects with id 0 or a parent not at all.

        Retail: CObjCell::update_all_voyeur @ 0x0052BD80 (acclient.c:347568)
        """
        from acphys.flags import PhysicsState

        if not obj.id or obj.parent is not None:
            return
        if obj._state & PhysicsState.HIDDEN and detection_type == ENTERED_DETECTION:
            return
        if self.voyeur_table is None:
            return
        for voyeur_id in list(self.voyeur_table):
            _tell_voyeur(obj, voyeur_id, detection_type)

    def hide_object(self, obj: PhysicsObj) -> None:
        """``obj`` was hidden: the voyeurs hear ``Left``.

        Retail: CObjCell::hide_object @ 0x0052BE30 (acclient.c:347616)
        """
        self.update_all_voyeur(obj, LEFT_DETECTION)

    def unhide_object(self, obj: PhysicsObj) -> None:
        """``obj`` was unhidden (or entered): the voyeurs hear ``Entered`` unless it is hidden.

        Retail: CObjCell::unhide_object @ 0x0052BE40 (acclient.c:347622)
        """
        self.update_all_voyeur(obj, ENTERED_DETECTION)

    def get_object(self, obj_iid: int) -> PhysicsObj | None:
        """The first object with id ``obj_iid``, or None.

        Retail: CObjCell::get_object @ 0x0052B8F0 (acclient.c:347258)
        """
        for obj in self.objects:
            if obj is not None and obj.id == obj_iid:
                return obj
        return None

    def add_shadow_object(self, shadow: ShadowObj, num_shadow_cells: int = 0) -> None:
        """Append ``shadow`` and point it at this cell (``num_shadow_cells`` is unused by retail).
        A cell that files its shadows files it; the ``SHADOW_INDEX_MIN``-th starts the files.

        Retail: CObjCell::add_shadow_object @ 0x0052B280 (acclient.c:346804)
        """
        shadow.index = len(self.shadow_objects)
        self.shadow_objects.append(shadow)
        shadow.cell = self
        if self.shadow_tiles is not None:
            self._file(shadow, shadow.physobj.collision_box())
        elif len(self.shadow_objects) >= SHADOW_INDEX_MIN:
            self._start_files()

    def remove_shadow_object(self, shadow: ShadowObj) -> None:
        """Remove ``shadow`` (by identity), clearing its cell; the last shadow takes its slot.
        Below ``SHADOW_INDEX_DROP`` shadows the files are dropped.

        Retail: CObjCell::remove_shadow_object @ 0x0052B2D0 (acclient.c:346823)
        """
        shadows = self.shadow_objects
        index = shadow.index
        if not (0 <= index < len(shadows) and shadows[index] is shadow):
            return
        last = shadows.pop()
        if last is not shadow:
            shadows[index] = last
            last.index = index
        shadow.cell = None
        shadow.index = -1
        if self.shadow_tiles is not None:
            self._unfile(shadow)
            if len(shadows) < SHADOW_INDEX_DROP:
                self._stop_files()

    # --- the shadow files (not retail: the sweep asks only the bodies within its reach) ------

    def refile_shadow(self, shadow: ShadowObj, box: Box | None) -> None:
        """The body of ``shadow`` moved, turned or was scaled and its collision shapes now fill
        ``box``: file it again (nothing to do in a cell that does not file its shadows)."""
        if self.shadow_tiles is None:
            return
        self._unfile(shadow)
        self._file(shadow, box)

    def replace_shadow_objects(self, shadows: list[ShadowObj], moved: set[int]) -> None:
        """Make ``shadows`` the list (each pointed at this cell and its slot), keeping the files: a
        shadow that stays keeps its square unless its body is in ``moved`` (by ``id``), a new one
        is filed, a gone one unfiled, so the cost follows what changed, not the list's length.

        Not retail: how the fast engine hands a cell's list back (:mod:`acphys.fast.engine`).
        """
        old = self.shadow_objects
        for index, shadow in enumerate(shadows):
            shadow.cell = self
            shadow.index = index
        self.shadow_objects = shadows
        if self.shadow_tiles is None or len(shadows) < SHADOW_INDEX_DROP:
            self.shadow_tiles = None
            if len(shadows) >= SHADOW_INDEX_MIN:
                self._start_files()
            return
        staying = set(shadows)
        for shadow in old:
            if shadow not in staying:
                self._unfile(shadow)
        known = set(old)
        for shadow in shadows:
            if shadow not in known:
                self._file(shadow, shadow.physobj.collision_box())
            elif id(shadow.physobj) in moved:
                self.refile_shadow(shadow, shadow.physobj.collision_box())

    def _start_files(self) -> None:
        self.shadow_tiles = {}
        self._unfiled = set()
        self._reach = 0.0
        for shadow in self.shadow_objects:
            self._file(shadow, shadow.physobj.collision_box())

    def _stop_files(self) -> None:
        self.shadow_tiles = None
        self._unfiled = set()
        for shadow in self.shadow_objects:
            shadow.box = shadow.tile = None

    def _file(self, shadow: ShadowObj, box: Box | None) -> None:
        """File ``shadow`` by the centre of ``box``; no box, or one wider than two squares, goes to
        ``_unfiled`` (asked by every sweep)."""
        assert self.shadow_tiles is not None
        shadow.box = box
        shadow.tile = None
        if box is not None:
            x0, y0, _, x1, y1, _ = box
            half = 0.5 * max(x1 - x0, y1 - y0)
            if half <= SHADOW_TILE:
                cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
                shadow.tile = (math.floor(cx / SHADOW_TILE), math.floor(cy / SHADOW_TILE))
                self._reach = max(self._reach, half)
                self.shadow_tiles.setdefault(shadow.tile, set()).add(shadow)
                return
        self._unfiled.add(shadow)

    def _unfile(self, shadow: ShadowObj) -> None:
        assert self.shadow_tiles is not None
        if shadow.tile is None:
            self._unfiled.discard(shadow)
            return
        square = self.shadow_tiles[shadow.tile]
        square.discard(shadow)
        if not square:
            del self.shadow_tiles[shadow.tile]

    def _shadows_in_reach(self, path: SpherePath, after: int) -> list[ShadowObj]:
        """The shadows listed after position ``after`` that a sweep at ``check_pos`` could touch,
        in list order: the unfiled ones and the filed ones whose box comes within
        ``SHADOW_REACH_MARGIN`` of the box around ``global_sphere`` (all of them when a sphere is
        not finite). Any other body is farther from every moving sphere than their radii and the
        margin, where its ``find_obj_collisions`` could only answer OK and change nothing.
        """
        tiles = self.shadow_tiles
        assert tiles is not None
        sweep = _sphere_box(path)
        if sweep is None:
            return self.shadow_objects[after + 1 :]
        margin = SHADOW_REACH_MARGIN
        x0, y0, z0 = sweep[0] - margin, sweep[1] - margin, sweep[2] - margin
        x1, y1, z1 = sweep[3] + margin, sweep[4] + margin, sweep[5] + margin
        reach = self._reach
        tx0, tx1 = math.floor((x0 - reach) / SHADOW_TILE), math.floor((x1 + reach) / SHADOW_TILE)
        ty0, ty1 = math.floor((y0 - reach) / SHADOW_TILE), math.floor((y1 + reach) / SHADOW_TILE)
        squares: Any = tiles.values()
        if (tx1 - tx0 + 1) * (ty1 - ty0 + 1) < len(tiles):
            squares = [
                square
                for tx in range(tx0, tx1 + 1)
                for ty in range(ty0, ty1 + 1)
                if (square := tiles.get((tx, ty))) is not None
            ]
        found = [
            shadow
            for square in squares
            for shadow in square
            if shadow.index > after
            and (box := shadow.box) is not None
            and box[0] <= x1
            and box[3] >= x0
            and box[1] <= y1
            and box[4] >= y0
            and box[2] <= z1
            and box[5] >= z0
        ]
        found.extend(shadow for shadow in self._unfiled if shadow.index > after)
        found.sort(key=_INDEX)
        return found

    # --- collisions -----------------------------------------------------------------------

    def find_obj_collisions(self, transition: CellTransition) -> TransitionState:
        """Ask each shadowed body, in list order, to collide with the transition's spheres.

        Initial placement collides with nothing. Parented bodies and the moving body itself
        are skipped; the first result other than OK is returned.

        Retail: CObjCell::find_obj_collisions @ 0x0052B750 (acclient.c:347141)
        """
        path = transition.sphere_path
        if path.insert_type == IT.INITIAL_PLACEMENT:
            return TS.OK
        result = TS.OK
        mover = transition.object_info.object
        if self.shadow_tiles is None:
            for shadow in list(self.shadow_objects):
                body = shadow.physobj
                if body.parent is not None or body is mover:
                    continue
                result = body.find_obj_collisions(transition)
                if result != TS.OK:
                    break
            return result
        # A filed cell asks, in the same order, only the bodies the spheres could touch; a body
        # that answers OK may have moved them (a step up), and the rest are then found again.
        pending = self._shadows_in_reach(path, -1)
        next_index = 0
        while next_index < len(pending):
            shadow = pending[next_index]
            next_index += 1
            body = shadow.physobj
            if body.parent is not None or body is mover:
                continue
            sweep = _sweep_key(path)
            result = body.find_obj_collisions(transition)
            if result != TS.OK:
                break
            if _sweep_key(path) != sweep:
                pending = self._shadows_in_reach(path, shadow.index)
                next_index = 0
        return result

    def check_collisions(self, obj: ShadowBody) -> bool:
        """Whether a body shadowed here (not ``obj``, not parented) overlaps ``obj``.

        Retail: CObjCell::check_collisions @ 0x0052B7B0 (acclient.c:347173)
        """
        return any(
            other.parent is None and other is not obj and other.check_collision(obj)
            for other in (shadow.physobj for shadow in self.shadow_objects)
        )

    def check_entry_restrictions(self, transition: CellTransition) -> TransitionState:
        """COLLIDED without a moving object; OK unless a player's weenie meets a restriction
        object, which needs the housing-barrier weenie calls (not ported: ValueError).

        Retail: CObjCell::check_entry_restrictions @ 0x0052B6D0 (acclient.c:347102)
        """
        obj = transition.object_info.object
        if obj is None:
            return TS.COLLIDED
        if (
            getattr(obj, "weenie_obj", None) is not None
            and transition.object_info.state & OI.IS_PLAYER
            and self.restriction_obj
        ):
            raise ValueError(
                f"cell {format_cell_id(self.id)} has restriction object {self.restriction_obj:#x}: "
                "entry restrictions (housing barriers) are not supported"
            )
        return TS.OK

    def find_env_collisions(self, transition: CellTransition) -> TransitionState:
        """Collide with the cell's own geometry (pure virtual in ``CObjCell``)."""
        raise NotImplementedError(f"{type(self).__name__} has no find_env_collisions")

    def find_collisions(self, transition: CellTransition) -> TransitionState:
        """Collide with everything in the cell (pure virtual in ``CObjCell``)."""
        raise NotImplementedError(f"{type(self).__name__} has no find_collisions")

    def point_in_cell(self, point: Vector3) -> bool:
        """Whether the landblock-local ``point`` is inside the cell (pure virtual in ``CObjCell``)."""
        raise NotImplementedError(f"{type(self).__name__} has no point_in_cell")

    def find_transit_cells(
        self, p: Position, spheres: Sequence[Sphere], cell_array: CellArray, path: SpherePath | None
    ) -> None:
        """Add the cells the spheres reach from this one; retail's base aborts.

        Retail: CObjCell::find_transit_cells @ 0x0052B070 (acclient.c:346660)
        """
        raise NotImplementedError(f"{type(self).__name__} has no find_transit_cells")

    def find_transit_cells_for_parts(self, parts: Sequence[PhysicsPart], cell_array: CellArray) -> None:
        """Add the cells the parts' bounding boxes reach from this one; retail's base aborts.

        Retail: CObjCell::find_transit_cells @ 0x0052B080 (acclient.c:346666)
        """
        raise NotImplementedError(f"{type(self).__name__} has no find_transit_cells for parts")

    # --- water ----------------------------------------------------------------------------

    def get_block_water_type(self) -> WaterType:
        """The water type of the cell's landblock, NOT_WATER without one.

        Retail: CObjCell::get_block_water_type @ 0x0052AD90 (acclient.c:346438)
        """
        return self.landblock.water_type if self.landblock is not None else WT.NOT_WATER

    def get_water_depth(self, point: Vector3) -> float:
        """0 for a dry cell, 0.9 for an all-water one; a partly wet one asks its landblock at
        the block-local ``point`` (0.1 without a landblock).

        Retail: CObjCell::get_water_depth @ 0x0052B8A0 (acclient.c:347232)
        """
        if self.water_type == WT.ENTIRELY_WATER:
            return ENTIRELY_WATER_DEPTH
        if self.water_type != WT.PARTIALLY_WATER:
            return 0.0
        if self.landblock is None:
            return SOLID_VERTEX_WATER_DEPTH
        return self.landblock.calc_water_depth(self.id, point)

    # --- cell lists -----------------------------------------------------------------------

    @staticmethod
    def find_cell_list(
        p: Position,
        spheres: Sequence[Sphere],
        cell_array: CellArray,
        path: SpherePath | None = None,
        want_curr_cell: bool = False,
    ) -> ObjCell | None:
        """Fill ``cell_array`` with the cells the global ``spheres`` (in ``p``'s landblock
        frame) touch; with ``want_curr_cell``, return the cell holding sphere 0's centre.

        From an indoor ``p`` the array starts with that cell (and ``path.hits_interior_cell``
        is set); from outdoors with every land cell the spheres overlap. Each cell in the
        array (including those added meanwhile) then adds its transit cells. The current
        cell is the last one whose ``point_in_cell`` holds sphere 0's centre, or the first
        indoor one (which sets ``hits_interior_cell``). With ``do_not_load_cells`` and an
        indoor ``p``, cells not in the start cell's ``stab_list`` are dropped.

        Retail: CObjCell::find_cell_list @ 0x0052B4E0 (acclient.c:346960)
        """
        from acphys.world.land_cell import LandCell

        cell_array.clear()
        cell_id = p.objcell_id
        visible = cell_array.source.get_cell(cell_id) if cell_id else None
        if (cell_id & 0xFFFF) >= FIRST_ENV_CELL:
            if path is not None:
                path.hits_interior_cell = True
            cell_array.add_cell(cell_id, visible)
        else:
            LandCell.add_all_outside_cells(p, spheres, cell_array)
        if visible is None or not spheres:
            return None
        i = 0
        while i < cell_array.num_cells:
            cell = cell_array.cells[i].cell
            if cell is not None:
                cell.find_transit_cells(p, spheres, cell_array, path)
            i += 1
        curr_cell: ObjCell | None = None
        if want_curr_cell:
            for info in cell_array.cells:
                cell = info.cell
                if cell is None:
                    continue
                local_point = spheres[0].center - get_block_offset(cell_id, cell.id)
                if cell.point_in_cell(local_point):
                    curr_cell = cell
                    if (cell.id & 0xFFFF) >= FIRST_ENV_CELL:
                        if path is not None:
                            path.hits_interior_cell = True
                        break
        if cell_array.do_not_load_cells and (cell_id & 0xFFFF) >= FIRST_ENV_CELL:
            i = 0
            while i < cell_array.num_cells:
                kept = cell_array.cells[i].cell_id
                if kept == visible.id or kept in visible.stab_list:
                    i += 1
                else:
                    cell_array.remove_cell(i)
        return curr_cell

    @staticmethod
    def find_cell_list_for_path(
        cell_array: CellArray, path: SpherePath, want_check_cell: bool = True
    ) -> ObjCell | None:
        """``find_cell_list`` for the path's candidate: ``check_pos`` and its global spheres.

        Retail: CObjCell::find_cell_list @ 0x0052B960 (acclient.c:347315)
        """
        return ObjCell.find_cell_list(path.check_pos, path.global_sphere, cell_array, path, want_check_cell)

    @staticmethod
    def find_cell_list_for_sphere(
        p: Position, sphere: Sphere, cell_array: CellArray, path: SpherePath | None = None
    ) -> None:
        """``find_cell_list`` for one sphere given in ``p``'s local frame, placed by
        ``Position::localtoglobal`` (acclient.c:347329; its rows sum the y term first, unlike
        ``Frame.localtoglobal``).

        Retail: CObjCell::find_cell_list @ 0x0052B990 (acclient.c:347321)
        """
        global_sphere = Sphere.owning(p.localtoglobal(p, sphere.center), sphere.radius)
        ObjCell.find_cell_list(p, [global_sphere], cell_array, path)

    @staticmethod
    def find_cell_list_for_cylspheres(
        p: Position, cylspheres: Sequence[CylSphere], cell_array: CellArray, path: SpherePath | None = None
    ) -> None:
        """``find_cell_list`` for at most the first 10 cylspheres, each as a sphere of its
        radius centred on its low point, placed by ``Position::localtoglobal`` (acclient.c:347366).

        Retail: CObjCell::find_cell_list @ 0x0052B9F0 (acclient.c:347336)
        """
        spheres = [
            Sphere.owning(p.localtoglobal(p, cyl.low_pt), cyl.radius)
            for cyl in cylspheres[:MAX_CYLSPHERE_CELL_LIST]
        ]
        ObjCell.find_cell_list(p, spheres, cell_array, path)


def _sphere_box(path: SpherePath) -> Box | None:
    """The box around the sweep's spheres (``global_sphere``, in ``check_pos``'s landblock), in
    landblock-global metres; None without spheres or when one is not finite.

    Every centre is given the largest radius: the sphere tests measure the second sphere with
    the first one's radius (``radsum`` in ``CSphere::intersects_sphere`` and
    ``step_sphere_down``, acclient.c:359211, 358647), which may be the larger.
    """
    spheres = path.global_sphere
    if not spheres:
        return None
    radius = 0.0
    for sphere in spheres:
        if not math.isfinite(sphere.radius):
            return None
        if sphere.radius > radius:
            radius = sphere.radius
    xs = [sphere.center.x for sphere in spheres]
    ys = [sphere.center.y for sphere in spheres]
    zs = [sphere.center.z for sphere in spheres]
    if not math.isfinite(sum(xs) + sum(ys) + sum(zs)):
        return None
    cell_id = path.check_pos.objcell_id
    bx, by = ((cell_id >> 24) & 0xFF) * BLOCK_LENGTH, ((cell_id >> 16) & 0xFF) * BLOCK_LENGTH
    return (
        min(xs) - radius + bx,
        min(ys) - radius + by,
        min(zs) - radius,
        max(xs) + radius + bx,
        max(ys) + radius + by,
        max(zs) + radius,
    )


def _sweep_key(path: SpherePath) -> tuple[int, list[tuple[float, float, float, float]]]:
    """What a body's answer may change of the sweep: its cell and its spheres."""
    return path.check_pos.objcell_id, [
        (sphere.center.x, sphere.center.y, sphere.center.z, sphere.radius) for sphere in path.global_sphere
    ]


def _swap_remove(items: list, item: object) -> bool:
    """Remove ``item`` (by identity) by moving the last entry into its slot; False if absent."""
    for index, candidate in enumerate(items):
        if candidate is item:
            last = items.pop()
            if index < len(items):
                items[index] = last
            return True
    return False
