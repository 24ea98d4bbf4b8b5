"""Whole and partial copies between records (:mod:`acphys.fast.kernels.store`)."""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit
from numba.core.errors import TypingError

from acphys.fast.kernels.store import copy_head, copy_record, copy_span
from acphys.fast.layout import BODY, CARRIED, PLANE_BYTES, TRANSITION


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


@njit(_nrt=False)
def _copy_contact_plane(dst, src):
    copy_span(dst[0], "contact_n", src[0], "contact_n", PLANE_BYTES)


def test_a_span_is_copied_from_field_to_field_and_nothing_else() -> None:
    """The body's contact plane into the transition's: the 32 bytes from ``contact_n`` on in the
    one to the 32 from ``contact_n`` on in the other (normal and distance), not a byte around."""
    src, dst = _filled(BODY, 5), _filled(TRANSITION, 6)
    before = dst.tobytes()
    _copy_contact_plane(dst, src)
    at, to = BODY.fields["contact_n"][1], TRANSITION.fields["contact_n"][1]
    assert dst.tobytes()[to : to + PLANE_BYTES] == src.tobytes()[at : at + PLANE_BYTES]
    end = to + PLANE_BYTES
    assert dst.tobytes()[:to] == before[:to] and dst.tobytes()[end:] == before[end:]
    for name in ("contact_n", "contact_d"):  # the normal and the distance, bit for bit
        assert dst[name].tobytes() == src[name].tobytes()


@pytest.mark.parametrize(
    ("record", "plane"),
    [(BODY, "contact"), (TRANSITION, "contact"), (TRANSITION, "last_known_contact")],
)
def test_a_planes_normal_and_distance_lie_side_by_side(record: np.dtype, plane: str) -> None:
    normal, distance = record.fields[f"{plane}_n"], record.fields[f"{plane}_d"]
    assert distance[1] == normal[1] + normal[0].itemsize and normal[0].itemsize + 8 == PLANE_BYTES


#: The body record's last field: a span of two bytes from it runs past the record.
_LAST = BODY.names[-1]


def test_a_span_past_the_record_does_not_compile() -> None:
    assert BODY.fields[_LAST][1] + 1 == BODY.itemsize

    @njit(_nrt=False)
    def last_byte(dst, src):
        copy_span(dst[0], _LAST, src[0], "contact_n", 1)

    @njit(_nrt=False)
    def past(dst, src):
        copy_span(dst[0], _LAST, src[0], "contact_n", 2)

    dst, src = _filled(BODY, 7), _filled(BODY, 8)
    last_byte(dst, src)  # the field's name is read as a constant: one byte fits
    assert dst.tobytes()[-1] == src.tobytes()[BODY.fields["contact_n"][1]]
    with pytest.raises(TypingError):
        past(dst, src)
