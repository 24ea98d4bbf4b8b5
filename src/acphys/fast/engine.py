"""The fast engine's clock: ``CPhysics::UseTime`` over records, with the reference path behind it.

:class:`FastPhysics` replaces :class:`acphys.simulation.Physics` in a simulation made with
``engine="fast"``. Each ``use_time`` walks the bodies in object-table order, as the reference
does, but hands runs of them to the compiled kernel (:func:`acphys.fast.kernels.tick.run_bodies`),
which steps every body it covers and stops at the first it does not. That body's update runs on
the reference path (``PhysicsObj.update_object``), in its place in the order, with its world
brought up to date first and its record read back after; then the kernel goes on from the next
body. The share of body-steps that ran on the reference path is counted (:attr:`counts`).

Hand-off, both ways, is exact: records hold the float32 and double values the objects hold. What
the kernel changed and the objects do not know yet (positions, cells, shadow lists) is written
back lazily, before anything reads the objects: a reference step, an event, the end of a run
(:meth:`FastPhysics.flush`). Between two public ``Simulation.step`` calls the user may change
bodies directly, so after a flush the records are read again before the next kernel run.
"""

from __future__ import annotations

import gc
import operator
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from acphys.arrays import BodyArrays, body_arrays
from acphys.constants import MAX_QUANTUM, MIN_QUANTUM
from acphys.fast.animations import AnimationTable
from acphys.fast.coverage import uncovered_reason
from acphys.fast.kernels import grid
from acphys.fast.kernels import tick as kernels
from acphys.fast.kernels.cells import BAIL_REASONS, R_GLIDE
from acphys.fast.kernels.codegen import vectorising
from acphys.fast.kernels.context import ARRAYS, make_context
from acphys.fast.layout import BODY, INTERPOLATION, MAX_GLIDE_NODES, TRANSITION
from acphys.fast.pool import transition_from_pool, transition_to_pool
from acphys.fast.reach import Box, cells_under, global_xy, sweep_box, update_boxes, within_reach
from acphys.fast.sync import (
    interpolation_of,
    load_body,
    load_glide,
    load_motion_queues,
    rows_of,
    store_bodies,
    store_glide,
    store_motion_queues,
    vector_column,
)
from acphys.fast.world_arrays import BLOCK_CELLS, WorldArrays, build_world_arrays, shadow_entries
from acphys.flags import TransientState, flag_names
from acphys.math.cell_id import format_cell_id, landblock_of
from acphys.motion.anim_hooks import ANIM_DONE_HOOK
from acphys.physics_obj import PhysicsObj
from acphys.simulation import Physics
from acphys.trace import heading_of, motion_record
from acphys.world.land_cell import LandCell
from acphys.world.obj_cell import ShadowObj
from acphys.world.terrain import WaterType
from acphys.world.world import World

#: Kernel log rows held before the engine writes them out (a row is one traced body-step).
LOG_ROWS = 4096
#: A record's fields that say where the kernel cast its body's shadows (and their slots), and
#: whether its object is behind (:meth:`FastPhysics._read_again` with ``keep_shadows``).
_KERNEL_SHADOWS = ("stale", "shadows_moved", "num_shadow", "shadow_cell", "shadow_cell_id", "shadow_slot")
#: Event actions that change their own body's state alone, neither moving it nor reading or
#: changing another body or a cell (a motion, a jump, a move to a position, a velocity, an
#: interpolation node, a constraint): the engine writes back and reads again that body only.
OWN_STATE_ACTIONS = frozenset(
    {
        "set_velocity",
        "set_omega",
        "motion",
        "stop_motion",
        "jump",
        "move_to",
        "turn_to",
        "interpolate_to",
        "constrain_to",
        "unconstrain",
    }
)


@dataclass
class Counts:
    """Body-steps taken by each path (``update_object_internal`` calls), and why updates went to
    the reference path: ``reasons`` counts body updates by reason (a reason of
    :data:`~acphys.fast.kernels.cells.BAIL_REASONS`, or the first thing
    :func:`~acphys.fast.coverage.uncovered_reason` found)."""

    kernel: int = 0
    reference: int = 0
    #: Of the kernel's body-steps, those whose sweep met another body (held by it, slid off it, or
    #: stepped down onto it).
    touching: int = 0
    #: AnimDone hooks of kernel steps run on the reference path after the kernel returned (those
    #: the record's motion queues could not retire: :mod:`acphys.fast.kernels.motion_queues`).
    owed_hooks: int = 0
    reasons: dict[str, int] = field(default_factory=dict)

    @property
    def reference_share(self) -> float:
        total = self.kernel + self.reference
        return self.reference / total if total else 0.0


#: The names of the kernel's world record's arrays, in the order :meth:`FastPhysics._context` holds them.
_CONTEXT_ARRAYS = tuple(name for name, _, _ in ARRAYS)


@contextmanager
def _cycle_collector_paused() -> Iterator[None]:
    """Python's cycle collector held off: a write-back makes tens of thousands of small objects,
    none of them in a cycle, and every collection they would set off walks the whole world."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


class FastPhysics(Physics):
    """``CPhysics`` over the kernel's records; see the module docstring."""

    def __init__(self, world: World) -> None:
        super().__init__(world)
        self.counts = Counts()
        self._bodies: list[PhysicsObj] = []
        self._records = np.zeros(0, dtype=BODY)
        self._arrays: WorldArrays | None = None
        self._transition = np.zeros(1, dtype=TRANSITION)
        #: Room for a body's record and the transition as they were, to undo an update handed back.
        self._saved_body = np.zeros(1, dtype=BODY)
        self._saved_transition = np.zeros(1, dtype=TRANSITION)
        self._saved_glide = np.zeros(1, dtype=INTERPOLATION)
        #: The interpolation table (``BODY.glide``): a row for each covered body with a position
        #: manager, kept for it (``_glide_rows``: body index -> row) until the arrays are made again.
        self._glides = np.zeros(0, dtype=INTERPOLATION)
        self._glide_rows: dict[int, int] = {}
        self._clock = np.zeros(4, dtype=np.float64)
        # Room for at least one body's update in each log, or the kernel could never go on.
        rows = max(LOG_ROWS, kernels.MAX_STEPS_PER_UPDATE * kernels.DEFERRED_PER_STEP)
        self._log = np.zeros((rows, kernels.LOG_WIDTH), dtype=np.float64)
        self._moves = np.zeros((rows, 3), dtype=np.int32)
        self._counters = np.zeros(kernels.NUM_COUNTERS, dtype=np.int64)
        self._journal = np.zeros((kernels.JOURNAL_ROWS, 3), dtype=np.int64)
        #: What the kernel's steps left for the engine (kernels.DEFERRED_*): AnimDone hooks owed,
        #: collision reports to name.
        self._owed = np.zeros((rows, kernels.DEFERRED_WIDTH), dtype=np.int32)
        self._index: dict[int, int] = {}
        #: Why each body is not covered ("" when it is): the first uncovered_reason.
        self._uncovered: list[str] = []
        self._animations = AnimationTable()
        self._grid_heads, bits = grid.heads_for(0)
        self._grid = np.zeros(grid.GRID_SLOTS, dtype=np.float64)
        self._grid[grid.SPAN_BITS] = bits
        #: True once the objects may have changed behind the records (a flush, a new body).
        self._reload = True
        self._writer: Any = None
        #: The kernel's world record and the arrays it was made over (:meth:`_context`).
        self._made_context: tuple[tuple[np.ndarray, ...], np.ndarray] | None = None
        self._kernels_loaded = False  # run_bodies has been called (and so compiled) once
        #: Where the last update handed back was sweeping (kernels.HB_*).
        self._handback = np.zeros(kernels.HANDBACK_SLOTS, dtype=np.float64)
        #: Cells a partial write-back left as they were while writing back bodies shadowed in them:
        #: kernel cell -> the ``id`` of those bodies, whose shadows there are new objects (each
        #: such cell is dirty, and is written with them counted as moved).
        self._pending: dict[int, set[int]] = {}

    # -- bodies and arrays -------------------------------------------------------------------

    def add(self, obj: PhysicsObj) -> None:
        self.flush()
        super().add(obj)
        self._arrays = None

    def _build(self) -> None:
        """Number the bodies in table order and make the world's arrays and every record."""
        self._bodies = self._walk_order()
        self._index = {id(body): i for i, body in enumerate(self._bodies)}
        self._records = np.zeros(len(self._bodies), dtype=BODY)
        self._uncovered = [""] * len(self._bodies)
        self._glides = np.zeros(0, dtype=INTERPOLATION)
        self._glide_rows.clear()
        self._arrays = build_world_arrays(self.world, self._bodies)
        self._grid_heads, bits = grid.heads_for(len(self._bodies))
        self._grid[grid.SPAN_BITS] = bits
        self._transition["memo_valid"] = False  # its cell list holds the old arrays' indices
        self._pending.clear()  # (a whole write-back came first)
        self._reload = True

    def _load(self, i: int) -> None:
        """Read body ``i`` into its record, its cells' shadow slots included."""
        assert self._arrays is not None
        body = self._bodies[i]
        arrays = self._arrays
        present = self.world.has_object(body)
        if present:  # the landblocks of its cells first, so that its cell has an index
            cells = (body.cell, *(shadow.cell for shadow in body.shadow_objects))
            self._read_landblocks([c.id for c in cells if isinstance(c, LandCell)])
        cell = arrays.cell_index(body.position.objcell_id) if body.cell is not None else -1
        observer = self._writer.write_step if self._writer is not None else None
        reason = uncovered_reason(body, arrays.land_cell, observer) if present else "gone"
        record = self._records[i]
        load_body(record, body, cell, reason is None)
        if body.part_array is not None and not self._animations.load(record, body.part_array.sequence):
            reason = reason or "a sequence the kernel cannot play"
            record["covered"] = False
        self._uncovered[i] = reason or ""
        if record["covered"] and body.position_manager is not None:
            row = self._glide_row(i)
            load_glide(self._glides[row], body)
            record["glide"] = row
        shadows = body.shadow_objects[: record["shadow_cell"].size]
        record["num_shadow"] = len(shadows)
        for s, shadow in enumerate(shadows):
            record["shadow_cell_id"][s] = shadow.cell_id
            record["shadow_cell"][s] = arrays.cell_index(shadow.cell_id) if shadow.cell is not None else -1
            record["shadow_slot"][s] = shadow.index

    def _glide_row(self, i: int) -> int:
        """Body ``i``'s row of the interpolation table, made if need be (the table grows by
        doubling: a new array, which the kernel's world record then names)."""
        row = self._glide_rows.get(i)
        if row is None:
            row = self._glide_rows[i] = len(self._glide_rows)
            if row >= len(self._glides):
                grown = np.zeros(max(4, 2 * len(self._glides)), dtype=INTERPOLATION)
                grown[: len(self._glides)] = self._glides
                self._glides = grown
        return row

    def _read_landblocks(self, cell_ids: list[int]) -> bool:
        """Give the kernel the landblocks of the land cells ``cell_ids`` that it does not know:
        ones without terrain, which the world makes up past its edge, or ones loaded since the
        arrays were made. Their cells are the world's own, so both paths list the same shadows
        in them. False when it knew them all or the world makes none of them."""
        assert self._arrays is not None
        arrays = self._arrays
        blocks = []
        for key in sorted({landblock_of(cell_id) for cell_id in cell_ids if arrays.cell_index(cell_id) < 0}):
            block = self.world.landscape.get_landblock(key << 16)
            if block is not None:
                blocks.append((block.lcell, int(block.water_type)))
                continue
            void = [self.world.get_cell((key << 16) | low) for low in range(1, BLOCK_CELLS + 1)]
            if all(isinstance(cell, LandCell) for cell in void):
                blocks.append((void, int(WaterType.NOT_WATER)))
                arrays.void_blocks.add(key)
        arrays.add_landblocks(blocks, self._index)
        return bool(blocks)

    def _void_loaded(self) -> bool:
        """Whether a landblock the arrays hold as terrain-less cells has since been added to the
        world (the arrays are then made again)."""
        assert self._arrays is not None
        void = self._arrays.void_blocks
        if not void:
            return False
        landscape = self.world.landscape
        return any(landscape.get_landblock(key << 16) is not None for key in void)

    def _reload_all(self) -> None:
        for i in range(len(self._bodies)):
            self._load(i)
        self.world_arrays.place_others()
        transition_from_pool(self._transition, self.world_arrays, self.world)
        self._grid[grid.MAX_REACH] = float(grid.reaches_now(self._records).max(initial=0.0))
        grid.grid_place_all(self._records, self._grid_heads, int(self._grid[grid.SPAN_BITS]))
        self._clock[1] = self.world.physics_time
        self._reload = False

    # -- the tick -----------------------------------------------------------------------------

    def use_time(self) -> bool:
        """``CPhysics::UseTime``: every body's ``update_object``, the covered ones in the kernel.

        Retail: CPhysics::UseTime @ 0x00509950 (acclient.c:311334)
        """
        elapsed = self.world.cur_time - self.last_update
        if elapsed < 0.0:
            self.last_update = self.world.cur_time
            return False
        if elapsed < MIN_QUANTUM:
            return False
        if self._arrays is not None and self._void_loaded():
            self.flush()
            self._arrays = None
        if self._arrays is None:
            self._build()
        if self._reload:
            self._reload_all()
        self._run_kernel()
        self.last_update = self.world.cur_time
        return True

    def _run_kernel(self) -> None:
        assert self._arrays is not None
        arrays = self.world_arrays
        player = self.world.player
        self._clock[0] = self.world.cur_time
        self._clock[2] = self._index.get(id(player), -1) if player is not None else -1
        self._clock[3] = 1.0 if self.world.activity_cull else 0.0
        tracing = self._writer is not None
        start = 0
        while start < len(self._bodies):
            arguments = (self._context(), self._transition, start, tracing)
            arguments += (self._saved_body, self._saved_transition, self._saved_glide)
            if self._kernels_loaded:
                status, stop = kernels.run_bodies(*arguments)
            else:
                with vectorising():  # the first call compiles the kernels (or loads them)
                    status, stop = kernels.run_bodies(*arguments)
                self._kernels_loaded = True
            counters = self._counters.tolist()
            self.counts.kernel += counters[kernels.STEPS]
            self.counts.touching += counters[kernels.TOUCHING]
            self._counters[kernels.STEPS] = self._counters[kernels.TOUCHING] = 0
            deferred = self._owed[: counters[kernels.OWED]].tolist() if counters[kernels.OWED] else []
            self._counters[kernels.OWED] = 0
            if deferred or tracing:
                self._write_log(deferred)
                self._run_owed_hooks(deferred)
            start = stop
            if status == kernels.GROW:
                arrays.grow(int(self._counters[kernels.GROW_CELL]))
            elif status == kernels.LOG_FULL:  # the trace log and the hooks are done above; the moves:
                self._replay_moves()
            elif status == kernels.UNREAD and self._read_landblocks([self._unread_cell()]):
                pass  # the step runs again, in the kernel
            elif status in (kernels.FALLBACK, kernels.UNREAD):
                self._count_reason(start)
                self._reference_update(start)
                start += 1
        self.world.physics_time = float(self._clock[1])

    def _unread_cell(self) -> int:
        """The land cell whose landblock the kernel asked for (``UNREAD``)."""
        return int(self._counters[kernels.UNREAD_CELL])

    def _context(self) -> np.ndarray:
        """The kernel's world record over the arrays as they are now: made again when one of them
        is a new array (a grown cell list's pool, new bodies' records, new animations); the
        arrays are never resized in place, so the same objects lie where they lay."""
        arrays = self.world_arrays
        animations = self._animations
        held = (
            self._records,
            arrays.cells,
            arrays.landblock_index,
            arrays.shadow_pool,
            arrays.other_spans,
            arrays.other_shapes,
            self._grid_heads,
            self._grid,
            animations.anims,
            animations.pos_frames,
            animations.hooks,
            self._clock,
            self._log,
            self._moves,
            self._counters,
            self._journal,
            self._owed,
            self._handback,
            self._glides,
            arrays.building_shapes,
            arrays.door_spans,
            arrays.door_planes,
        )
        made = self._made_context
        if made is None or not all(map(operator.is_, held, made[0])):
            made = self._made_context = (held, make_context(**dict(zip(_CONTEXT_ARRAYS, held, strict=True))))
        return made[1]

    def _run_owed_hooks(self, deferred: list[list[int]]) -> None:
        """Run the AnimDone hooks the kernel's steps owed in ``deferred`` (the rows of its deferred
        log: those its record's motion queues could not retire) (``process_hooks``, the end of
        ``update_position_internal``), in the order the steps queued them, and the motion table's
        tick after (``CPartArray::HandleMovement``, the step's last act) when they left a motion with
        no animation to wait for. Both reach only the body's motion-table manager and motion
        interpreter (``MotionTableManager::AnimationDone`` → ``CMotionInterp::MotionDone``), which
        no step reads, so they run when the kernel returns: on the queues as the record has them
        (what the kernel retired before is written back first), read into the record again
        after."""
        for kind, i, count, _, _ in deferred:
            if kind != kernels.DEFERRED_ANIM_DONE:
                continue
            body = self._bodies[i]
            record = self._records[i]
            store_motion_queues(record, body)
            self.counts.owed_hooks += count
            body.anim_hooks.extend([ANIM_DONE_HOOK] * count)
            body.process_hooks()
            parts = body.part_array
            table = parts.motion_table_manager if parts is not None else None
            if table is not None and table.pending_animations and not table.pending_animations[0].num_anims:
                parts.handle_movement()
            load_motion_queues(record, body)

    def _count_reason(self, i: int) -> None:
        record = self._records[i]
        if record["covered"]:
            reason = BAIL_REASONS[int(self._counters[kernels.REASON])]
        else:
            reason = self._uncovered[i]
        self.counts.reasons[reason] = self.counts.reasons.get(reason, 0) + 1

    def _reference_update(self, i: int) -> None:
        """Body ``i``'s ``update_object`` on the reference path, what it reads up to date."""
        body = self._bodies[i]
        # its collision partners: the kernel's record holds a covered body's table, its object
        # an uncovered one's (a record keeps only MAX_RECORDS)
        partners = self._record_partners(i) if self._records[i]["covered"] else self._partners(body)
        self._write_back_for(i, partners)
        self.world.physics_time = float(self._clock[1])
        if self.world.has_object(body):
            steps = _StepCounter(body)
            try:
                body.update_object()
            finally:
                steps.detach()
            self.counts.reference += steps.count
            transition_from_pool(self._transition, self.world_arrays, self.world)
        self._clock[1] = self.world.physics_time
        self._reload_after(i, partners | self._partners(body))

    def _write_back_for(self, i: int, partners: set[int]) -> None:
        """Write back what body ``i``'s reference update can read: when its reach is known
        (:meth:`_reach_of_update`), the cells there with the stale bodies shadowed or standing in
        them, its collision partners and the player (the others wait for a later write-back);
        else the whole world. Such an update reads nothing else: it has no manager but the motion
        interpreter (which acts on the body), its sweep meets only what is shadowed in the cells
        it reaches, and it reports collisions to the bodies in its collision table
        (``partners``)."""
        if self._gave_up_a_glide(i) and self._records[i]["stale"]:  # its reach is measured on its object
            with _cycle_collector_paused():
                self._write_back(np.array([i], dtype=np.intp), cells=[])
        boxes = self._reach_of_update(i)
        cells = cells_under(self.world_arrays, boxes) if boxes is not None else None
        if boxes is None or cells is None:
            self.flush()
            return
        self._write_back_around(cells, boxes, {i, *partners})

    def _write_back_around(self, cells: list[int], boxes: list[Box], bodies: set[int]) -> None:
        """Write back ``bodies`` (those that are stale), the player, and the kernel ``cells`` with
        the stale bodies shadowed or standing in them: whole those within reach of ``boxes``,
        only their places (:meth:`_store_places`) those out of it, which the update finds out of
        its reach from where they stand (``out_of_reach``, the shadow files) and reads no more
        of. Those stay stale, to be written whole later."""
        arrays, records = self.world_arrays, self._records
        wanted = set(bodies)
        player = self.world.player
        if player is not None and id(player) in self._index:
            wanted.add(self._index[id(player)])
        reached = np.zeros(len(arrays.cells) + 1, dtype=bool)  # the last slot: no cell (-1)
        reached[cells] = True
        listed = [arrays.shadow_list(k) for k in cells]
        around = set(np.concatenate(listed).tolist() if listed else ())
        around.update(np.flatnonzero(reached[records["cell"]]).tolist())
        candidates = np.array(sorted(j for j in around | wanted if j >= 0), dtype=np.intp)
        stale = candidates[records["stale"][candidates].astype(bool)]
        near = within_reach(records[stale], boxes) | np.isin(stale, sorted(wanted))
        with _cycle_collector_paused():
            self._write_back(stale[near], cells, places=stale[~near])

    def _reach_of_update(self, i: int) -> list[Box] | None:
        """Where body ``i``'s reference update can read (:mod:`acphys.fast.reach`), or None when
        that is not known: a covered body handed back during its sweep of one quantum reaches
        around its path, an uncovered one that reads only through its sweep around where it
        stands, as does a covered one whose interpolation gave a node up (the reference glides
        it, or blips it to a node); any other update may read anything."""
        record, handback = self._records[i], self._handback
        if record["covered"] and not self._gave_up_a_glide(i):
            if handback[kernels.HB_SWEPT] != 1.0 or self._clock[0] - record["update_time"] > MAX_QUANTUM:
                return None  # (of several quanta, only the last one's path is kept)
            ends = [
                global_xy(int(handback[at]), handback[at + 1], handback[at + 2])
                for at in (kernels.HB_BEGIN, kernels.HB_END)
            ]
            box = sweep_box(ends[0], ends[1], float(record["reach"]))
            return [box] if box is not None else None
        body = self._bodies[i]
        observer = self._writer.write_step if self._writer is not None else None
        return update_boxes(body, float(record["reach"]), self.world.cur_time - body.update_time, observer)

    def _gave_up_a_glide(self, i: int) -> bool:
        """Whether body ``i``, covered, was handed back by its interpolation (``R_GLIDE``)."""
        return bool(self._records[i]["covered"]) and int(self._counters[kernels.REASON]) == R_GLIDE

    def _record_partners(self, i: int) -> set[int]:
        """The engine's bodies in body ``i``'s collision records as the kernel holds them."""
        record = self._records[i]
        partners = set()
        for object_id in record["record_obj"][: record["num_records"]].tolist():
            other = self.world.get_object(object_id)
            if other is not None and id(other) in self._index:
                partners.add(self._index[id(other)])
        return partners

    def _partners(self, body: PhysicsObj) -> set[int]:
        """The engine's bodies in ``body``'s collision table: a step of ``body`` may report to them."""
        if body.collision_table is None:
            return set()
        partners = (self.world.get_object(object_id) for object_id in body.collision_table.ids())
        return {self._index[id(o)] for o in partners if o is not None and id(o) in self._index}

    def _reload_after(self, i: int, partners: set[int]) -> None:
        """Read back body ``i``, its collision ``partners`` (before and after its step: a step
        reports collisions and their ends to both bodies; their shadows stay as the kernel cast
        them), and the shadow lists of the cells its shadows left or entered (with the slots of
        the bodies listed there)."""
        assert self._arrays is not None
        arrays = self._arrays
        record = self._records[i]
        body = self._bodies[i]
        touched = {int(k) for k in record["shadow_cell"][: record["num_shadow"]] if k >= 0}
        touched |= {arrays.cell_index(s.cell_id) for s in body.shadow_objects if s.cell is not None}
        touched.discard(-1)
        behind = [k for k in touched if k in self._pending or arrays.cells[k]["dirty"]]
        stale = [j for j in sorted(partners) if self._records[j]["stale"]]
        if behind or stale:
            raise RuntimeError(
                f"fast engine: the reference step of {body.name or hex(body.id)} reached past what was "
                f"written back for it (cells {behind}, bodies {stale}): a bug in acphys, please report it"
            )
        before = {k: arrays.shadow_list(k).tolist() for k in touched}
        known = len(arrays.others)
        for k in touched:
            arrays.set_shadow_list(k, shadow_entries(arrays, k, arrays.land_cells[k], self._index))
        if len(arrays.others) != known:
            arrays.place_others()
        if body.detection_manager is not None:  # its detection may have watched or left cells
            arrays.refresh_uncovered()
            self._transition["memo_valid"] = False
        self._read_again(i)  # its shadows are its step's, in cells written before it
        for j in sorted(partners - {i}):  # the step reported to them, and cast none of their shadows
            self._read_again(j, keep_shadows=True)
        for k in touched:  # the bodies whose slots the step's removals and additions moved
            was = before[k]
            for slot, j in enumerate(arrays.shadow_list(k).tolist()):
                if j >= 0 and j != i and (slot >= len(was) or was[slot] != j):
                    other = self._records[j]
                    cells = other["shadow_cell"][: other["num_shadow"]].tolist()
                    if k in cells:
                        other["shadow_slot"][cells.index(k)] = slot

    def _read_again(self, j: int, keep_shadows: bool = False) -> None:
        """Read body ``j``'s object into its record again, and file it in the grid there. With
        ``keep_shadows`` the record keeps where the kernel cast the body's shadows (with their
        slots) and whether its object is behind: the object's own shadows may be new ones that
        cells left for a later write-back do not list yet."""
        kept = rows_of(self._records, [j]) if keep_shadows else None
        self._load(j)
        if kept is not None:
            for name in _KERNEL_SHADOWS:
                self._records[name][j] = kept[name][0]
        reach = float(grid.reaches_now(self._records[j : j + 1])[0])
        self._grid[grid.MAX_REACH] = max(self._grid[grid.MAX_REACH], reach)
        grid.grid_place(self._records, self._grid_heads, int(self._grid[grid.SPAN_BITS]), j)

    # -- writing back ---------------------------------------------------------------------------

    def flush(self) -> None:
        """Write everything the kernel changed back into the objects (cells, shadows, bodies)."""
        if self._arrays is None or not len(self._records):
            return
        stale = np.flatnonzero(self._records["stale"])
        moves = int(self._counters[kernels.MOVES])
        if not len(stale) and not moves and not self._arrays.cells["dirty"].any():
            return
        with _cycle_collector_paused():
            self._write_back(stale)

    def _write_back(
        self, stale: np.ndarray, cells: list[int] | None = None, places: np.ndarray | None = None
    ) -> None:
        """Write the ``stale`` bodies' rows back into their objects, the ``places`` bodies' places
        only (they stay stale), and the dirty cells among ``cells`` (None: every dirty cell) into
        theirs; a written body's new shadows in a cell left dirty are noted in :attr:`_pending`
        for that cell's write."""
        arrays = self._arrays
        assert arrays is not None
        places = np.zeros(0, dtype=np.intp) if places is None else places
        transition_to_pool(self._transition, arrays, self.world)
        self._replay_moves()
        bodies = [self._bodies[i] for i in stale.tolist()]
        placed = [self._bodies[i] for i in places.tolist()]
        rows = rows_of(self._records, np.concatenate((stale, places)))
        self._store_rows(rows[: len(stale)], bodies)
        self._store_places(rows[len(stale) :], placed)
        bodies += placed
        columns = (rows[name].tolist() for name in ("shadows_moved", "num_shadow", "shadow_cell_id"))
        for body, shadows_moved, count, ids in zip(bodies, *columns, strict=True):
            if shadows_moved:  # the kernel cast them again: new shadow objects
                body.shadow_objects = [ShadowObj(body, shadow_cell_id) for shadow_cell_id in ids[:count]]
        self._records["stale"][stale] = False
        self._records["shadows_moved"][stale] = False
        self._records["shadows_moved"][places] = False
        moved = {id(body) for body in bodies}
        dirty = arrays.cells["dirty"]
        written = np.flatnonzero(dirty).tolist() if cells is None else [k for k in cells if dirty[k]]
        for k in written:
            pending = self._pending.pop(k, None)  # (a union with the written bodies copies them all)
            self._write_cell(k, moved | pending if pending else moved)
        dirty[written] = False
        if cells is None:
            self._pending.clear()
            return
        done = set(written)
        columns = (rows[name].tolist() for name in ("shadows_moved", "num_shadow", "shadow_cell"))
        for body, shadows_moved, count, shadow_cells in zip(bodies, *columns, strict=True):
            if shadows_moved:  # its new shadow objects, in cells written later
                for k in shadow_cells[:count]:
                    if k >= 0 and k not in done:
                        self._pending.setdefault(k, set()).add(id(body))
                        dirty[k] = True

    def _store_rows(self, rows: np.ndarray, bodies: list[PhysicsObj]) -> None:
        """Write record ``rows`` into ``bodies``: their state, sequences, cells and parts' frames
        (not their shadows)."""
        store_bodies(rows, bodies)
        for body, row in zip(bodies, rows["glide"].tolist(), strict=True):
            if row >= 0:
                store_glide(self._glides[row], body)
        parts = [body.part_array for body in bodies]
        self._animations.store(rows, [p.sequence if p is not None else None for p in parts])
        for body, body_parts, cell_id in zip(bodies, parts, rows["cell_id"].tolist(), strict=True):
            body.position.objcell_id = cell_id
            if body_parts is not None:
                body_parts.update_parts(body.position.frame)
                for part in body_parts.parts:
                    part.pos.objcell_id = cell_id

    def _store_places(self, rows: np.ndarray, bodies: list[PhysicsObj]) -> None:
        """Write where record ``rows`` put ``bodies`` (cell, frame, state bits): with their shadow
        objects, what a sweep out of their reach reads of them."""
        columns = (rows[name].tolist() for name in ("cell_id", "state", "q", "m"))
        origins = vector_column(rows["origin"])
        for body, origin, cell_id, state, q, m in zip(bodies, origins, *columns, strict=True):
            body._state = state
            body.position.objcell_id = cell_id
            frame = body.position.frame
            frame.origin = origin
            frame.qw, frame.qx, frame.qy, frame.qz = q
            frame.m[:] = m

    def _replay_moves(self) -> None:
        """Move the bodies that changed cells into their cells' object lists, in the order they
        moved (the lists' order is retail's: ``add_object`` appends, ``remove_object`` swaps the
        last object in)."""
        assert self._arrays is not None
        land_cells = self._arrays.land_cells
        moves = int(self._counters[kernels.MOVES])
        for body_index, old, new in self._moves[:moves].tolist():
            body = self._bodies[body_index]
            if old >= 0:
                land_cells[old].remove_object(body)
            if new >= 0:
                cell = land_cells[new]
                cell.add_object(body)
                body.cell = cell
        self._counters[kernels.MOVES] = 0

    def sync_objects(self) -> None:
        """Write the kernel's changes back, and read the objects again before the next run (the
        user may change them in between)."""
        self.flush()
        self._reload = True

    def body_arrays(self, bodies: list[PhysicsObj]) -> BodyArrays:
        """The state of ``bodies`` read from the kernel's records, which hold every body of the
        table as it is whether or not its object was written back (a body the kernel has not
        read, from its object)."""
        index = self._index
        rows = np.fromiter((index.get(id(body), -1) for body in bodies), dtype=np.intp, count=len(bodies))
        if self._arrays is None or self._reload or (rows < 0).any():
            return body_arrays(bodies)
        records = self._records

        def column(name: str) -> np.ndarray:
            return records[name][rows]  # a copy

        return BodyArrays.of_columns(
            names=tuple(body.name for body in bodies),
            cell_ids=column("cell_id"),
            origins=column("origin"),
            orientations=column("q"),
            velocities=column("velocity"),
            cached_velocities=column("cached_velocity"),
            omegas=column("omega"),
            transient_states=column("transient"),
        )

    def apply_events(self, events: list[Any], body_named: Any) -> None:
        """Apply events to up-to-date objects: one of ``OWN_STATE_ACTIONS`` (read from a scenario
        or named to ``add_event``) to its body written back alone (but for its shadows, which no
        such event reads or moves: they stay the kernel's, to be written with their cells) and
        read again after (an interpolation node to a body the kernel glides: its queue alone, when
        that is all the node changed); any other (a function among them) to the whole world
        written back, every body read again before the next run."""
        for event in events:
            body = body_named(event.body)
            i = self._index.get(id(body))
            own = event.action in OWN_STATE_ACTIONS and event.source != "add_event"
            if i is None or not own or self._arrays is None or self._reload:
                self.flush()
                event.apply(body)
                self._reload = True
                continue
            if self._records[i]["stale"]:  # all but its shadows, which stay the kernel's
                self._replay_moves()
                self._store_rows(rows_of(self._records, [i]), [body])
            frame = body.position.frame
            placed = (frame.rotation, tuple(frame.origin))
            event.apply(body)
            if event.action != "interpolate_to" or not self._only_glided(i, body, placed):
                self._read_again(i, keep_shadows=True)

    def _only_glided(self, i: int, body: PhysicsObj, placed: tuple[Any, ...]) -> bool:
        """After an interpolation node to body ``i``: when the kernel glides the body and the node
        left its frame as it was (``placed``: a node within 0.05 m turns the body to face as the
        node does) and its queue within the kernel's bound, read its queue again, and the events
        it holds, and say True; else False (the body is to be read again whole)."""
        row = int(self._records[i]["glide"])
        manager = interpolation_of(body)
        frame = body.position.frame
        if row < 0 or manager is None or len(manager.position_queue) > MAX_GLIDE_NODES:
            return False
        if (frame.rotation, tuple(frame.origin)) != placed:
            return False
        load_glide(self._glides[row], body)
        self._records[i]["step_events"] = bool(body.step_events)
        return True

    def _write_cell(self, k: int, moved: set[int]) -> None:
        """Make the reference cell ``k``'s shadow list the kernel's (``moved``: the ``id`` of each
        body written back, whose place in the cell's files may have changed)."""
        assert self._arrays is not None
        arrays = self._arrays
        cell = arrays.land_cells[k]
        current = cell.shadow_objects
        shadows: list[ShadowObj] = []
        for slot, entry in enumerate(arrays.shadow_list(k).tolist()):
            if entry < 0:
                shadows.append(arrays.other_shadows[(-1 - entry, k)])
                continue
            body = self._bodies[entry]
            if slot < len(current) and current[slot].physobj is body and id(body) not in moved:
                shadows.append(current[slot])  # the same shadow in the same slot
            else:
                shadows.append(next(s for s in body.shadow_objects if s.cell_id == cell.id))
        cell.replace_shadow_objects(shadows, moved)

    # -- traces ------------------------------------------------------------------------------

    def set_trace_writer(self, writer: Any) -> None:
        """Write the kernel's steps to ``writer`` (a :class:`acphys.trace.TraceWriter`), or stop."""
        self._writer = writer
        self._reload = True

    def _write_log(self, deferred: list[list[int]]) -> None:
        """Write the kernel's trace rows, handing each collision report of ``deferred`` (the rows
        of its deferred log) to its receiver in step order: one of another body's step is
        appended to the receiver's ``step_events`` before the receiver's next row (as the
        reference appends it at once); the mover's own goes into its step's row."""
        rows = int(self._counters[kernels.LOGGED]) if self._writer is not None else 0
        reports = [r for r in deferred if r[0] != kernels.DEFERRED_ANIM_DONE]
        next_report = 0
        for n, row in enumerate(self._log[:rows]):
            own = []
            while next_report < len(reports) and reports[next_report][1] <= n:
                kind, _, receiver, other, is_own = reports[next_report]
                if is_own:
                    own.append(self._report_name(kind, other))
                else:
                    self._bodies[receiver].step_events.append(self._report_name(kind, other))
                next_report += 1
            self._writer.write_record(self._record_of(row, own))
        for kind, _, receiver, other, is_own in reports[next_report:]:
            if not is_own:  # the mover's own report lived for its step only (no trace: no row)
                self._bodies[receiver].step_events.append(self._report_name(kind, other))
        self._counters[kernels.LOGGED] = 0

    def _report_name(self, kind: int, j: int) -> str:
        """``collision:NAME`` (or ``collision_end:NAME`` for a report of the end) of a report of
        body ``j`` (its id in hex without a name)."""
        other = self._bodies[j]
        prefix = "collision_end:" if kind == kernels.DEFERRED_COLLISION_END else "collision:"
        return prefix + (other.name if other.name else f"0x{other.id:08X}")

    def _record_of(self, row: np.ndarray, reports: list[str]) -> dict[str, Any]:
        """A trace record from a kernel log row; ``reports``: the collision reports the step made
        to its own body (after a landing or leaving, before touching the environment)."""
        values = row.tolist()
        body = self._bodies[int(values[0])]
        transient = TransientState(int(values[20]))
        bits = int(values[24])
        events = []
        if bits & kernels.EVENT_PENDING:
            events = list(body.step_events)
            body.step_events.clear()
        if bits & kernels.EVENT_HIT_GROUND:
            events.append("hit_ground")
        if bits & kernels.EVENT_LEAVE_GROUND:
            events.append("leave_ground")
        events.extend(reports)
        if bits & kernels.EVENT_COLLISION_ENVIRONMENT:
            events.append("collision:environment")
        playing = int(values[25])
        animation = self._animations.animations[playing].name if playing >= 0 else None
        return {
            "t": values[1],
            "body": body.name,
            "id": f"0x{body.id:08X}",
            "quantum": values[2],
            "cell": format_cell_id(int(values[3])),
            "origin": values[4:7],
            "orientation": values[7:11],
            "heading": heading_of(values[7:11]),
            "velocity": values[11:14],
            "cached_velocity": values[14:17],
            "omega": values[17:20],
            "transient": flag_names(transient, TransientState),
            "contact_normal": values[21:24] if transient & TransientState.CONTACT else None,
            # the interpreter's state is the body's: no kernel step changes it
            "motion": motion_record(body, animation, values[26] if playing >= 0 else None),
            "events": events,
        }

    def array_bytes(self) -> int:
        """The bytes the kernel's arrays take: records, interpolation queues, cells, shadow lists,
        static shapes, grid, animations."""
        arrays = self._arrays
        held = [self._records, self._grid_heads, self._transition, self._log, self._moves, self._journal]
        held += [self._owed, self._glides]
        if arrays is not None:
            held += [arrays.cells, arrays.shadow_pool, arrays.landblock_index]
            held += [arrays.other_spans, arrays.other_shapes]
            held += [arrays.building_shapes, arrays.door_spans, arrays.door_planes]
        held += [self._animations.anims, self._animations.pos_frames, self._animations.hooks]
        return sum(array.nbytes for array in held)

    @property
    def world_arrays(self) -> WorldArrays:
        assert self._arrays is not None
        return self._arrays


class _StepCounter:
    """Counts a body's reference steps by wrapping its observer for one update."""

    def __init__(self, body: PhysicsObj) -> None:
        self.body = body
        self.count = 0
        self.inner = body.observer
        body.observer = self._observe

    def _observe(self, body: PhysicsObj, quantum: float) -> None:
        self.count += 1
        if self.inner is not None:
            self.inner(body, quantum)

    def detach(self) -> None:
        self.body.observer = self.inner


__all__ = ["Counts", "FastPhysics"]
