"""The kernels' world record (:mod:`acphys.fast.kernels.context`): views over the engine's arrays
and refusals of arrays it cannot view."""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit

from acphys.fast.kernels.context import ARRAYS, bodies_of, journal_of, make_context


def _arrays() -> dict[str, np.ndarray]:
    shapes = {"anims": (2, 3), "pos_frames": (4, 7), "log": (5, 27), "moves": (5, 3), "journal": (6, 3)}
    shapes.update(owed=(5, 5), other_spans=(2, 2), other_shapes=(4, 5))
    shapes.update(building_shapes=(1, 5), door_spans=(2, 2), door_planes=(6, 4))
    return {name: np.zeros(shapes.get(name, (3,)), dtype=dtype) for name, dtype, _ in ARRAYS}


@njit(_nrt=False)  # not cached: a cache of it would outlive a change of the records' layout
def _touch(context, i):
    w = context[0]
    b = bodies_of(w)[i]
    b.origin[1] += 2.5  # written through to the engine's array
    journal_of(w)[1, 2] = 7
    return len(bodies_of(w)), b.origin[0]


def test_views_read_and_write_the_engines_arrays() -> None:
    arrays = _arrays()
    arrays["bodies"]["origin"][:, 0] = [10.0, 11.0, 12.0]
    context = make_context(**arrays)
    assert _touch(context, 1) == (3, 11.0)
    assert arrays["bodies"]["origin"][:, 1].tolist() == [0.0, 2.5, 0.0]
    assert arrays["journal"][1].tolist() == [0, 0, 7]
    assert context["journal_rows"][0] == 6 and context["journal_cols"][0] == 3


def test_an_array_the_kernels_cannot_view_is_refused() -> None:
    arrays = _arrays()
    arrays["counters"] = np.zeros(8, dtype=np.int32)
    with pytest.raises(ValueError, match=r"kernel array counters: int32 .* not a C-contiguous int64 array"):
        make_context(**arrays)
    arrays = _arrays()
    arrays["log"] = np.zeros((27, 5)).T  # the right shape, Fortran order
    with pytest.raises(ValueError, match="kernel array log"):
        make_context(**arrays)
