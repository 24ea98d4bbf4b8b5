"""Copying into the records' small arrays, element by element (the kernels run without Numba's
runtime, which a slice assignment between nested arrays needs)."""

from __future__ import annotations

from numba import njit


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
