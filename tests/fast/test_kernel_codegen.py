"""The kernels compile with LLVM's SLP vectoriser on (:mod:`acphys.fast.kernels.codegen`): packed
narrowings with the scalar ones' bits, and Numba's own setting untouched outside the kernels."""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit
from numba.core import config

from acphys.fast.kernels.codegen import vectorising
from acphys.scenario import load_scenario


def _narrow_four(dst, x, y, z, w):
    """Four float32 stores of products, as a vector's store in the kernels."""
    dst[0] = np.float64(np.float32(x * 3.1))
    dst[1] = np.float64(np.float32(y * 3.1))
    dst[2] = np.float64(np.float32(z * 3.1))
    dst[3] = np.float64(np.float32(w * 3.1))


def _conversions(dispatcher) -> list[str]:
    (asm,) = dispatcher.inspect_asm().values()
    return [line.split()[0] for line in asm.splitlines() if "cvt" in line]


def test_within_the_block_the_narrowings_are_packed_and_give_the_scalar_bits() -> None:
    out = np.zeros(4)
    scalar = njit(_narrow_four)
    scalar(out, 1.0, 2.0, 3.0, 4.0)
    with vectorising():
        packed = njit(_narrow_four)
        packed(out, 1.0, 2.0, 3.0, 4.0)
    assert not any("cvtpd2ps" in op for op in _conversions(scalar))  # one lane at a time
    assert any("cvtpd2ps" in op for op in _conversions(packed))  # several lanes at once
    rng = np.random.default_rng(8)
    values = np.concatenate(
        [
            rng.standard_normal(4000) * 10.0 ** rng.integers(-40, 40, 4000),
            [0.0, -0.0, np.inf, -np.inf, np.nan],
        ]
    )
    a, b = np.zeros(4), np.zeros(4)
    for k in range(0, len(values) - 3):
        scalar(a, *values[k : k + 4])
        packed(b, *values[k : k + 4])
        assert a.tobytes() == b.tobytes()


def _setting() -> int:
    """Numba's SLP setting now."""
    return config.SLP_VECTORIZE


def test_numbas_setting_is_restored_after_the_block_and_a_fast_run() -> None:
    before = _setting()
    with pytest.raises(RuntimeError), vectorising():
        assert _setting() == 1
        raise RuntimeError("a compile that fails")
    assert _setting() == before
    sim = load_scenario(engine="fast")  # the embedded default
    sim.step()
    assert _setting() == before
