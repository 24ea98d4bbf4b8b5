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
the process's Numba code.

LLVM's dead-store elimination also gets a larger budget (:data:`DEAD_STORE_BUDGET`). Numba
zero-fills every stack slot of a function at its entry, the slots of the tuples its calls return
among them, and fills each again at the call; in a function as large as a step's quantum
(``tick._run_quantum``, the sequence and the candidate inlined) the default budget ran out before
it proved those entry stores dead: about 90 stores a step, 2% of the kernels' instructions
(4,797 to 4,692 a walker's step), about 4% of the time in paired runs. A store proved dead is
one no read can see, so no result changes. LLVM's options are the process's: they only let
its optimiser look further, for any Numba code compiled in the process. Not retail: plumbing.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import llvmlite.binding as llvm
from numba.core import config

#: LLVM's ``cl::opt`` limits of the MemorySSA-based dead-store elimination, raised from their
#: defaults (150, 90, 5,000, 50 and 5).
DEAD_STORE_BUDGET = (
    "-dse-memoryssa-scanlimit=5000",
    "-dse-memoryssa-walklimit=5000",
    "-dse-memoryssa-defs-per-block-limit=100000",
    "-dse-memoryssa-path-check-limit=5000",
    "-dse-memoryssa-partial-store-limit=100",
)
for _option in DEAD_STORE_BUDGET:
    llvm.set_option("acphys", _option)


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
