"""Whole and partial copies between records (:mod:`acphys.fast.kernels.store`)."""

from __future__ import annotations

import numpy as np
from numba import njit

from acphys.fast.kernels.store import copy_head, copy_record
from acphys.fast.layout import BODY, CARRIED, TRANSITION


@njit(_nrt=False)
def _copy_whole(dst, src):
    copy_record(dst[0], src[0])


@njit(_nrt=False)
def _copy_carried(dst, src):
    copy_head(dst[0], src[0], CARRIED)


def _filled(dtype: np.dtype, seed: int) -> np.ndarray:
    """A record of ``dtype`` whose every byte is random."""
    record = np.zeros(1, dtype=dtype)
    record.view(np.uint8)[:] = np.random.default_rng(seed).integers(0, 256, dtype.itemsize, dtype=np.uint8)
    return record


def test_a_record_is_copied_whole() -> None:
    src, dst = _filled(BODY, 1), _filled(BODY, 2)
    _copy_whole(dst, src)
    assert dst.tobytes() == src.tobytes()


def test_the_head_is_copied_and_the_rest_left() -> None:
    """Every one of the first CARRIED bytes (not a multiple of the 32-byte moves: the 8- and
    1-byte tail too), and not one after."""
    assert CARRIED % 32 and CARRIED % 8
    src, dst = _filled(TRANSITION, 3), _filled(TRANSITION, 4)
    before = dst.tobytes()
    _copy_carried(dst, src)
    assert dst.tobytes()[:CARRIED] == src.tobytes()[:CARRIED]
    assert dst.tobytes()[CARRIED:] == before[CARRIED:]
