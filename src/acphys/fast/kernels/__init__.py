"""Numba kernels of the fast engine: ports of the reference engine's tick over records."""
