"""The kernel's world in one record: where each of its arrays lies, and its shape.

Numba hands an array to a compiled function as all of its fields (data, shape, strides, item
size, ...), and a function that is not inlined takes them on the stack: a call passing the
world's arrays on copied about a hundred words, and on 2,000 walkers about half of the
kernel's time went to such copies (``perf``, samples on the copying instructions). So the
kernels take one record instead, ``w`` (:data:`CONTEXT`, passed as a pointer), and view an array
where they use it (``bodies_of(w)``, ...; a view is two loads, inlined). Not retail: plumbing.

The engine makes the record before each kernel call (:func:`make_context`) from arrays it keeps
alive and does not reallocate while the kernel runs.
"""

from __future__ import annotations

import numpy as np
from numba import from_dtype, njit, types
from numba.core import cgutils
from numba.extending import intrinsic
from numba.np.arrayobj import make_array, populate_array

from acphys.fast.layout import BODY, CELL, INTERPOLATION

#: The arrays of the record, in order: ``(name, dtype, dimensions)``.
ARRAYS = (
    ("bodies", BODY, 1),  # the records, in table order
    ("cells", CELL, 1),  # the land cells (acphys.fast.world_arrays)
    ("landblock_index", np.int32, 1),  # landblock id -> its index in the cells // 64 (-1: not read)
    ("shadow_pool", np.int32, 1),  # the cells' shadow lists, end to end
    ("other_spans", np.int32, 2),  # the static objects' rows of other_shapes (acphys.fast.statics)
    ("other_shapes", np.float64, 2),  # their balls and columns
    ("heads", np.int32, 1),  # the broad phase's buckets (acphys.fast.kernels.grid)
    ("grid", np.float64, 1),  # the broad phase's numbers (grid.MAX_REACH)
    ("anims", np.int32, 2),  # the animations (acphys.fast.kernels.sequence)
    ("pos_frames", np.float64, 2),
    ("hooks", np.uint8, 1),
    ("clock", np.float64, 1),  # cur_time, physics_time, player index, activity cull
    ("log", np.float64, 2),  # the trace log (tick.LOG_WIDTH columns)
    ("moves", np.int32, 2),  # the cell-move log
    ("counters", np.int64, 1),  # tick.STEPS, ...
    ("journal", np.int64, 2),  # the undo journal of a body's update
    ("owed", np.int32, 2),  # the deferred log (tick.DEFERRED_*)
    ("handback", np.float64, 1),  # where a handed-back update was sweeping (tick.HB_*)
    ("glides", INTERPOLATION, 1),  # the covered bodies' interpolation queues (BODY.glide)
    ("building_shapes", np.float64, 2),  # the buildings' shell balls (acphys.fast.buildings)
    ("door_spans", np.int32, 2),  # each building door's rows of door_planes
    ("door_planes", np.float64, 2),  # the planes of the doors' cells
)


def _fields() -> list[tuple[str, type]]:
    fields: list[tuple[str, type]] = []
    for name, _, ndim in ARRAYS:
        fields += [(name, np.int64), (f"{name}_rows", np.int64)]
        if ndim == 2:
            fields.append((f"{name}_cols", np.int64))
    return fields


#: The record: per array its address (``name``) and its extents (``name_rows``, ``name_cols``). A
#: change of the records' layouts (:data:`~acphys.fast.layout.BODY`, ``CELL``) compiles every kernel
#: again (:mod:`acphys.fast.kernels.stamp`).
CONTEXT = np.dtype(_fields())


def make_context(**arrays: np.ndarray) -> np.ndarray:
    """A one-element :data:`CONTEXT` array over ``arrays`` (every name of :data:`ARRAYS`, each
    C-contiguous and of its dtype; a wrong one is a ``ValueError``). The caller keeps the arrays
    alive, unmoved, while a kernel uses the record."""
    context = np.zeros(1, dtype=CONTEXT)
    for name, dtype, ndim in ARRAYS:
        array = arrays[name]
        if array.dtype != np.dtype(dtype) or array.ndim != ndim or not array.flags.c_contiguous:
            wanted = f"a C-contiguous {np.dtype(dtype)} array of {ndim} dimensions"
            raise ValueError(f"kernel array {name}: {array.dtype} {array.shape}, not {wanted}")
        context[name] = array.ctypes.data
        context[f"{name}_rows"] = array.shape[0]
        if ndim == 2:
            context[f"{name}_cols"] = array.shape[1]
    return context


def _viewer(array_type: types.Array):
    """An intrinsic ``view(address, shape)``: an ``array_type`` over the memory at ``address``
    (``shape`` an int, or a pair for two dimensions), C order, owning nothing."""

    @intrinsic
    def view(typingctx, address, shape):
        def codegen(context, builder, signature, args):
            address_value, shape_value = args
            array = make_array(array_type)(context, builder)
            size = context.get_abi_sizeof(context.get_data_type(array_type.dtype))
            itemsize = context.get_constant(types.intp, size)
            if isinstance(signature.args[1], types.BaseTuple):
                extents = cgutils.unpack_tuple(builder, shape_value)
            else:
                extents = [shape_value]
            strides, stride = [], itemsize
            for extent in reversed(extents):
                strides.insert(0, stride)
                stride = builder.mul(stride, extent)
            data = builder.inttoptr(address_value, array.data.type)
            populate_array(array, data=data, shape=extents, strides=strides, itemsize=itemsize, meminfo=None)
            return array._getvalue()

        return array_type(address, shape), codegen

    return view


# Packed records (odd item sizes) are unaligned, as Numba types them in a NumPy array.
_bodies = _viewer(types.Array(from_dtype(BODY), 1, "C", aligned=False))
_cells = _viewer(types.Array(from_dtype(CELL), 1, "C", aligned=False))
_glides = _viewer(types.Array(from_dtype(INTERPOLATION), 1, "C", aligned=False))
_int32_1d = _viewer(types.Array(types.int32, 1, "C"))
_int32_2d = _viewer(types.Array(types.int32, 2, "C"))
_int64_1d = _viewer(types.Array(types.int64, 1, "C"))
_int64_2d = _viewer(types.Array(types.int64, 2, "C"))
_float64_1d = _viewer(types.Array(types.float64, 1, "C"))
_float64_2d = _viewer(types.Array(types.float64, 2, "C"))
_uint8_1d = _viewer(types.Array(types.uint8, 1, "C"))


@njit(cache=True, inline="always", _nrt=False)
def bodies_of(w):
    return _bodies(w.bodies, w.bodies_rows)


@njit(cache=True, inline="always", _nrt=False)
def cells_of(w):
    return _cells(w.cells, w.cells_rows)


@njit(cache=True, inline="always", _nrt=False)
def landblock_index_of(w):
    return _int32_1d(w.landblock_index, w.landblock_index_rows)


@njit(cache=True, inline="always", _nrt=False)
def shadow_pool_of(w):
    return _int32_1d(w.shadow_pool, w.shadow_pool_rows)


@njit(cache=True, inline="always", _nrt=False)
def other_spans_of(w):
    return _int32_2d(w.other_spans, (w.other_spans_rows, w.other_spans_cols))


@njit(cache=True, inline="always", _nrt=False)
def other_shapes_of(w):
    return _float64_2d(w.other_shapes, (w.other_shapes_rows, w.other_shapes_cols))


@njit(cache=True, inline="always", _nrt=False)
def heads_of(w):
    return _int32_1d(w.heads, w.heads_rows)


@njit(cache=True, inline="always", _nrt=False)
def grid_of(w):
    return _float64_1d(w.grid, w.grid_rows)


@njit(cache=True, inline="always", _nrt=False)
def anims_of(w):
    return _int32_2d(w.anims, (w.anims_rows, w.anims_cols))


@njit(cache=True, inline="always", _nrt=False)
def pos_frames_of(w):
    return _float64_2d(w.pos_frames, (w.pos_frames_rows, w.pos_frames_cols))


@njit(cache=True, inline="always", _nrt=False)
def hooks_of(w):
    return _uint8_1d(w.hooks, w.hooks_rows)


@njit(cache=True, inline="always", _nrt=False)
def clock_of(w):
    return _float64_1d(w.clock, w.clock_rows)


@njit(cache=True, inline="always", _nrt=False)
def log_of(w):
    return _float64_2d(w.log, (w.log_rows, w.log_cols))


@njit(cache=True, inline="always", _nrt=False)
def moves_of(w):
    return _int32_2d(w.moves, (w.moves_rows, w.moves_cols))


@njit(cache=True, inline="always", _nrt=False)
def counters_of(w):
    return _int64_1d(w.counters, w.counters_rows)


@njit(cache=True, inline="always", _nrt=False)
def journal_of(w):
    return _int64_2d(w.journal, (w.journal_rows, w.journal_cols))


@njit(cache=True, inline="always", _nrt=False)
def owed_of(w):
    return _int32_2d(w.owed, (w.owed_rows, w.owed_cols))


@njit(cache=True, inline="always", _nrt=False)
def handback_of(w):
    return _float64_1d(w.handback, w.handback_rows)


@njit(cache=True, inline="always", _nrt=False)
def glides_of(w):
    return _glides(w.glides, w.glides_rows)


@njit(cache=True, inline="always", _nrt=False)
def building_shapes_of(w):
    return _float64_2d(w.building_shapes, (w.building_shapes_rows, w.building_shapes_cols))


@njit(cache=True, inline="always", _nrt=False)
def door_spans_of(w):
    return _int32_2d(w.door_spans, (w.door_spans_rows, w.door_spans_cols))


@njit(cache=True, inline="always", _nrt=False)
def door_planes_of(w):
    return _float64_2d(w.door_planes, (w.door_planes_rows, w.door_planes_cols))
