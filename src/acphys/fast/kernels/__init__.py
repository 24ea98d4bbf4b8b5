"""Numba kernels of the fast engine: ports of the reference engine's tick over records."""

from acphys.fast.kernels import codegen  # noqa: F401 (LLVM's dead-store budget, before any kernel compiles)
from acphys.fast.kernels.stamp import install

install()  # before any kernel is defined: its cache is stamped by every kernel source
