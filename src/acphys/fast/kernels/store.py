"""Copying into the records' small arrays, element by element (the kernels run without Numba's
runtime, which a slice assignment between nested arrays needs), and whole records at once."""

from __future__ import annotations

from llvmlite import ir
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


@intrinsic(prefer_literal=True)
def copy_head(typingctx, dst, src, size):
    """The first ``size`` bytes (a constant) of record ``src`` into ``dst``, of the same type, as
    straight-line moves (:func:`_copy_inline`)."""
    if not (isinstance(dst, types.Record) and dst == src and isinstance(size, types.IntegerLiteral)):
        return None
    if not 0 < size.literal_value <= dst.size:
        return None

    def codegen(context, builder, signature, args):
        _copy_inline(context, builder, args[0], args[1], size.literal_value)
        return context.get_dummy_value()

    return types.void(dst, src, size), codegen


@intrinsic(prefer_literal=True)
def copy_span(typingctx, dst, dst_field, src, src_field, size):
    """``size`` bytes (a constant) of record ``src`` from its field ``src_field`` on into record
    ``dst`` from its field ``dst_field`` on, as straight-line moves (:func:`_copy_inline`): fields
    side by side in both records copied at once, so that a wide read of them later takes the
    whole store (a wide read of several narrow stores waits for them to retire)."""
    records = isinstance(dst, types.Record) and isinstance(src, types.Record)
    names = isinstance(dst_field, types.StringLiteral) and isinstance(src_field, types.StringLiteral)
    if not (records and names and isinstance(size, types.IntegerLiteral)):
        return None
    to, start = dst.offset(dst_field.literal_value), src.offset(src_field.literal_value)
    count = size.literal_value
    if not (count > 0 and to + count <= dst.size and start + count <= src.size):
        return None

    def codegen(context, builder, signature, args):
        _copy_inline(context, builder, args[0], args[2], count, to, start)
        return context.get_dummy_value()

    return types.void(dst, dst_field, src, src_field, size), codegen


#: The widest move :func:`_copy_inline` makes (for :func:`copy_head` and :func:`copy_span`), in bytes.
CHUNK = 32


def _copy_inline(context, builder, dst, src, size, dst_at=0, src_at=0):
    """``size`` bytes from ``src`` (from byte ``src_at``) to ``dst`` (from byte ``dst_at``) as
    straight-line moves of :data:`CHUNK` bytes, then 8, then 1 (no call into the C library, whose
    start costs a small copy as much again)."""
    byte = ir.IntType(8).as_pointer()
    to = builder.gep(builder.bitcast(dst, byte), [context.get_constant(types.intp, dst_at)])
    start = builder.gep(builder.bitcast(src, byte), [context.get_constant(types.intp, src_at)])
    offset = 0
    for width, kind in (
        (CHUNK, ir.VectorType(ir.IntType(64), CHUNK // 8)),
        (8, ir.IntType(64)),
        (1, ir.IntType(8)),
    ):
        while size - offset >= width:
            at = context.get_constant(types.intp, offset)
            value = builder.load(builder.bitcast(builder.gep(start, [at]), kind.as_pointer()), align=1)
            builder.store(value, builder.bitcast(builder.gep(to, [at]), kind.as_pointer()), align=1)
            offset += width


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
