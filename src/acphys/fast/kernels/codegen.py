"""How the kernels are compiled: with LLVM's SLP vectoriser on, which Numba leaves off by default.

The SLP (superword-level parallelism) vectoriser packs the same scalar operation on neighbouring
values into one vector instruction: the three float32 narrowings of a vector's store into one
``vcvtpd2ps``, a frame's copy from record to record into wide moves. Each lane is the scalar IEEE
operation it replaces and nothing is reassociated (the kernels have no fast-math), so no result
changes; the differential tests hold the traces to the reference's bits as before. A walker's step
on hills runs about 9% fewer instructions (5,374 to 4,901, ``benchmarks/kernel_instructions.py``)
and about 7% faster.

Numba turned the vectoriser off by default after miscompilations in an older LLVM (numba#8705);
it is turned on here only while a kernel compiles (:func:`vectorising`), never for the rest of
the process's Numba code. Not retail: plumbing.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from numba.core import config


@contextmanager
def vectorising() -> Iterator[None]:
    """Compile with the SLP vectoriser on within the block (a kernel compiles, or loads from
    Numba's cache, at its first call); Numba's own setting is restored after."""
    saved = config.SLP_VECTORIZE
    config.SLP_VECTORIZE = 1
    try:
        yield
    finally:
        config.SLP_VECTORIZE = saved
