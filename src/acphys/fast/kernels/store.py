"""Copying into the records' small arrays, element by element (the kernels run without Numba's
runtime, which a slice assignment between nested arrays needs), and whole records at once."""

from __future__ import annotations

from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def copy_record(typingctx, dst, src):
    """``dst = src`` for two records of one type, as one ``memcpy`` of its bytes (an assignment
    between records loads the whole record into registers and the stack first)."""
    if not (isinstance(dst, types.Record) and dst == src):
        return None

    def codegen(context, builder, signature, args):
        size = context.get_constant(types.intp, dst.size)
        cgutils.raw_memcpy(builder, args[0], args[1], size, 1)
        return context.get_dummy_value()

    return types.void(dst, src), codegen


@njit(cache=True, inline="always", _nrt=False)
def put(dst, src):
    """``dst[:] = src`` for a record's array and an array or tuple of the same length."""
    for k in range(len(dst)):
        dst[k] = src[k]


@njit(cache=True, inline="always", _nrt=False)
def fill(dst, value):
    """``dst[:] = value``."""
    for k in range(len(dst)):
        dst[k] = value
