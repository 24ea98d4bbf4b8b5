"""Differential tests: :mod:`acphys.fast.kernels.frame` against the reference math, bit for bit.

Every case builds the reference objects (``Vector3``, ``Frame``, ``Position``: float32 at rest),
reads the kernel's inputs from them, and asserts that every output is the identical float
(NaN matches NaN; +0.0 and -0.0 differ) or the identical integer.

The float32 stores hide most of the double arithmetic: products of float32 operands are exact in
double, and a sum computed in another order differs in its last double bit now and then (0.8 % of
quaternion products) but almost never after the store (none in 200,000). So
:func:`test_unnarrowed_double_arithmetic` runs this file again with every float32 store turned
into the identity on both sides (the kernels as plain Python): there any difference in the
operands or their order shows.
"""

from __future__ import annotations

import math
import os
import random
import struct
import subprocess
import sys

import numpy as np
import pytest

from acphys.constants import BLOCK_LENGTH, CELL_LENGTH, EPSILON
from acphys.fast.kernels import frame as K
from acphys.math import cell_id as C
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3, compass_heading
from acphys.motion.sequence import combine_anim_frame
from acphys.part_array import combine_scaled
from acphys.precision import f32

#: Random cases per function.
N = 3000
NAN = math.nan
INF = math.inf
HEADINGS = (0.0, 90.0, 180.0, 270.0, 360.0, -90.0, 450.0, 45.0, 135.0, 225.0, 315.0)
#: The float32 stores are taken out (``test_unnarrowed_double_arithmetic`` runs this file so):
#: a shortcut the kernels take because a store rounds its difference away is not checked then.
UNNARROWED = f32(0.1) == 0.1


def same(a, b) -> bool:
    """Identical results: floats bit-equal up to NaN payloads, ints and bools equal, tuples element-wise."""
    if isinstance(a, np.generic):
        a = a.item()
    if isinstance(b, np.generic):
        b = b.item()
    if isinstance(a, tuple) or isinstance(b, tuple):
        return (
            isinstance(a, tuple)
            and isinstance(b, tuple)
            and len(a) == len(b)
            and all(same(x, y) for x, y in zip(a, b, strict=True))
        )
    if isinstance(a, bool) or isinstance(b, bool):
        return isinstance(a, bool) and isinstance(b, bool) and a == b
    if isinstance(a, int) and isinstance(b, int):
        return a == b
    a, b = float(a), float(b)
    if a != a or b != b:
        return a != a and b != b
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


def check(got, want, *context) -> None:
    assert same(got, want), (got, want, *context)


def vt(v: Vector3) -> tuple[float, float, float]:
    return (v.x, v.y, v.z)


def ft(f: Frame) -> tuple:
    """A frame as the kernels take it: origin, q, m."""
    return vt(f.origin), f.rotation, tuple(f.m)


# -- random inputs, as the reference holds them ------------------------------------------------------


def scalar(rng: random.Random) -> float:
    r = rng.random()
    if r < 0.04:
        return 0.0
    if r < 0.07:
        return -0.0
    if r < 0.17:
        return rng.uniform(-3.0, 3.0) * EPSILON
    if r < 0.27:
        return float(rng.randint(-5, 5))
    if r < 0.55:
        return rng.uniform(-1.0, 1.0)
    if r < 0.9:
        return rng.uniform(-250.0, 250.0)
    return rng.uniform(-1e4, 1e4)


def direction(rng: random.Random) -> tuple[float, float, float]:
    while True:
        x, y, z = rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)
        n = math.sqrt(x * x + y * y + z * z)
        if n > 1e-3:
            return x / n, y / n, z / n


def vector(rng: random.Random) -> Vector3:
    r = rng.random()
    if r < 0.05:
        return Vector3()
    if r < 0.15:  # length about EPSILON, either side
        length = EPSILON * rng.choice((1.0, rng.uniform(0.5, 1.5), 1.0000001, 0.9999999))
        x, y, z = direction(rng)
        return Vector3(x * length, y * length, z * length)
    if r < 0.2:  # on an axis
        v = [0.0, 0.0, 0.0]
        v[rng.randrange(3)] = rng.choice((1.0, -1.0, rng.uniform(-5.0, 5.0)))
        return Vector3(*v)
    return Vector3(scalar(rng), scalar(rng), scalar(rng))


def unit_quaternion(rng: random.Random) -> tuple[float, float, float, float]:
    while True:
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(c * c for c in q))
        if n > 1e-3:
            return tuple(c / n for c in q)


def frame(rng: random.Random, *, nan_origin: float = 0.0) -> Frame:
    """A frame as the reference holds one: float32 origin, a set_rotate'd quaternion, its matrix."""
    f = Frame(vector(rng))
    r = rng.random()
    if r < 0.08:
        pass  # identity
    elif r < 0.2:
        f.set_heading(rng.choice(HEADINGS))
    elif r < 0.25:  # a quarter turn about an axis, negative w sometimes
        axis = rng.randrange(3)
        q = [math.cos(math.pi / 4), 0.0, 0.0, 0.0]
        q[axis + 1] = math.sin(math.pi / 4)
        if rng.random() < 0.5:
            q = [-c for c in q]
        f.set_rotate(*q)
    else:
        f.set_rotate(*unit_quaternion(rng))
    if rng.random() < nan_origin:
        f.origin.z = NAN
    return f


def raw_quaternion(rng: random.Random) -> tuple[float, float, float, float]:
    """Arguments for set_rotate: unit, near-unit, scaled, zero, NaN, huge."""
    r = rng.random()
    q = unit_quaternion(rng)
    if r < 0.5:
        return q
    if r < 0.7:
        s = 1.0 + rng.uniform(-6.0, 6.0) * EPSILON
        return tuple(c * s for c in q)
    if r < 0.85:
        s = rng.choice((1e-30, 1e-3, 7.0, 1e20, 1e39))
        return tuple(c * s for c in q)
    if r < 0.9:
        return (0.0, 0.0, 0.0, 0.0)
    if r < 0.95:
        return (NAN, q[1], q[2], q[3])
    return (INF, q[1], q[2], q[3])


# -- f32 and Vector3 ---------------------------------------------------------------------------------


def test_f32_matches_the_struct_round_trip():
    rng = random.Random(1)
    values = [0.0, -0.0, INF, -INF, 3.4028235677973366e38, 3.402823567797337e38, 1e300, 7e-46, 1.5e-45]
    values += [struct.unpack("<d", struct.pack("<Q", rng.getrandbits(64)))[0] for _ in range(20000)]
    values += [rng.uniform(-1e6, 1e6) for _ in range(5000)]
    for value in values:
        check(K.f32(value), f32(value), value)


def test_vector_operators():
    rng = random.Random(2)
    for _ in range(N):
        a, b = vector(rng), vector(rng)
        s = scalar(rng)
        ta, tb = vt(a), vt(b)
        check(K.v_add(ta, tb), vt(a + b))
        check(K.v_sub(ta, tb), vt(a - b))
        check(K.v_scale(ta, s), vt(a * s), s)
        check(K.v_neg(ta), vt(-a))
        check(K.v_dot(ta, tb), a.dot(b))
        check(K.v_cross(ta, tb), vt(a.cross(b)))
        check(K.v_length_squared(ta), a.length_squared())
        check(K.v_length(ta), a.length())
        check(K.v_is_zero(ta), a.is_zero())


def test_vector_division_by_the_float_reciprocal():
    rng = random.Random(3)
    divisors = [0.0, -0.0, 1e-50, 3.0, 7.0, -0.1, 1e-40, 1e38, 3e38]
    for i in range(N):
        v = vector(rng)
        s = divisors[i % len(divisors)] if i < 50 else scalar(rng)
        try:
            want = vt(v / s)
        except ZeroDivisionError:
            with pytest.raises(ZeroDivisionError):
                K.v_div(vt(v), s)
            continue
        check(K.v_div(vt(v), s), want, s)


def test_normalize_and_heading():
    rng = random.Random(4)
    for _ in range(N):
        v = vector(rng)
        stored = v.copy()
        small = stored.normalize_check_small()
        check(K.v_normalize_check_small(vt(v)), (small, vt(stored)), vt(v))
        if v.length_squared() == 0.0:
            with pytest.raises(ZeroDivisionError):
                v.normalized()
            with pytest.raises(ZeroDivisionError):
                K.v_normalized(vt(v))
        else:
            check(K.v_normalized(vt(v)), vt(v.normalized()))
        check(K.v_get_heading(vt(v)), v.get_heading(), vt(v))


def test_compass_heading_on_and_off_the_axes():
    rng = random.Random(5)
    points = [(x, y) for x in (0.0, -0.0, 1.0, -1.0, NAN) for y in (0.0, -0.0, 1.0, -1.0, NAN)]
    points += [(math.sin(math.radians(d)), math.cos(math.radians(d))) for d in HEADINGS]
    points += [(scalar(rng), scalar(rng)) for _ in range(N)]
    for x, y in points:
        check(K.compass_heading(x, y), compass_heading(x, y), x, y)


# -- Frame -------------------------------------------------------------------------------------------


def test_cache_and_validity():
    rng = random.Random(6)
    for _ in range(N):
        f = frame(rng, nan_origin=0.05)
        g = Frame(f.origin, *raw_quaternion(rng)) if rng.random() < 0.5 else f
        check(K.frame_cache(g.rotation), tuple(g.m), g.rotation)
        check(K.frame_is_valid(vt(g.origin), g.rotation), g.is_valid(), g)
        check(K.frame_is_valid_except_for_heading(vt(g.origin), g.rotation), g.is_valid_except_for_heading())


def test_is_equal_around_epsilon():
    rng = random.Random(7)
    steps = (0.0, EPSILON, -EPSILON, 0.5 * EPSILON, 1.5 * EPSILON, 0.9999 * EPSILON)
    for _ in range(N):
        f = frame(rng)
        g = f.copy()
        g.origin.x = f32(g.origin.x + rng.choice(steps))
        g.origin.z = f32(g.origin.z + rng.choice(steps))
        g.qw = f32(g.qw + rng.choice(steps))
        g.qy = f32(g.qy + rng.choice(steps))
        if rng.random() < 0.2:
            g = frame(rng)
        check(K.frame_is_equal(vt(f.origin), f.rotation, vt(g.origin), g.rotation), f.is_equal(g))


def test_set_rotate_keeps_the_old_rotation_when_invalid():
    rng = random.Random(8)
    invalid = 0
    for _ in range(N):
        f = frame(rng, nan_origin=0.05)
        q = raw_quaternion(rng)
        o, q0, m0 = ft(f)
        f.set_rotate(*q)
        got = K.frame_set_rotate(o, q0, m0, q)
        check(got, (f.rotation, tuple(f.m)), q)
        invalid += got[0] == q0
    assert invalid > N // 10  # the failure path was taken often


def test_grotate_and_rotate():
    rng = random.Random(9)
    for _ in range(N):
        f = frame(rng, nan_origin=0.02)
        w = vector(rng)
        if rng.random() < 0.2:  # |w|² right at EPSILON²
            x, y, z = direction(rng)
            w = Vector3(x * EPSILON, y * EPSILON, z * EPSILON)
        o, q, m = ft(f)
        g = f.copy()
        g.grotate(w)
        check(K.frame_grotate(o, q, m, vt(w)), (g.rotation, tuple(g.m)), vt(w))
        r = f.copy()
        r.rotate(w)
        check(K.frame_rotate(np.zeros(4), o, q, m, vt(w)), (r.rotation, tuple(r.m)), vt(w))


def test_grotate_remembered_is_grotate_with_the_angles_terms_reused():
    """``Frame::grotate`` (acclient.c:357421) takes the square root of the squared angle, its
    inverse, the sine and the cosine of its half: functions of the squared angle alone. The memo
    keeps them and reuses them while the squared angle repeats: for the same vector, for the same
    components in another order (another axis, the same sum), from another frame; the result is
    the reference's ``grotate`` every time, and the memo holds the last angle it met."""
    rng = random.Random(19)
    memo = np.zeros(4)
    w = vector(rng)
    reused = 0
    for n in range(N):
        roll = rng.random()
        if roll < 0.3:
            w = vector(rng)
        elif roll < 0.45:
            w = Vector3(w.z, w.x, w.y)  # the same squared angle about another axis
        elif roll < 0.5:
            x, y, z = direction(rng)
            w = Vector3(x * EPSILON, y * EPSILON, z * EPSILON)
        f = frame(rng, nan_origin=0.02)
        o, q, m = ft(f)
        g = f.copy()
        g.grotate(w)
        theta2 = w.x * w.x + w.y * w.y + w.z * w.z
        reused += theta2 == memo[0] and n > 0
        check(K.grotate_remembered(memo, o, q, m, vt(w)), (g.rotation, tuple(g.m)), vt(w))
        if theta2 >= EPSILON * EPSILON:
            assert memo[0] == theta2
    assert reused > N // 2


def test_interpolate_rotation_and_origin():
    rng = random.Random(10)
    ts = (0.0, 1.0, 0.5, -0.25, 1.25, 1e-9)
    for i in range(N):
        start, end, into = frame(rng), frame(rng), frame(rng, nan_origin=0.02)
        r = rng.random()
        if r < 0.15:  # the same rotation, negated: a negative dot product at the shortest arc
            end.set_rotate(*(-c for c in start.rotation))
        elif r < 0.3:  # within EPSILON
            end.set_rotate(start.qw, start.qx + 0.5 * EPSILON, start.qy, start.qz)
        elif r < 0.4:
            end.set_rotate(*(-c for c in end.rotation))
        t = ts[i % len(ts)] if rng.random() < 0.3 else rng.uniform(-0.2, 1.2)
        o, q, m = ft(into)
        got = K.frame_interpolate_rotation(o, q, m, start.rotation, end.rotation, t)
        into.interpolate_rotation(start, end, t)
        if not (UNNARROWED and t == 1.0):  # the next test's shortcut
            check(got, (into.rotation, tuple(into.m)), t)
        got = K.frame_interpolate_origin(vt(start.origin), vt(end.origin), t)
        into.interpolate_origin(start, end, t)
        check(got, vt(into.origin), t)


@pytest.mark.skipif(UNNARROWED, reason="set_rotate's float32 stores make the shortcut exact")
def test_interpolate_rotation_to_the_end_needs_no_sines():
    """At t = 1 the kernel's slerp takes weights 0 and 1 without acos or sin; retail's
    (acclient.c:357257-357290) are +0 and sin(omega) * (1 / sin(omega)), within an ulp of 1, or
    0 and 1 from the linear blend. Every rotation set is the reference's to the bit: slerps across
    the whole range of angles, turns about z alone (exact zeros, negated to -0 on the shorter
    arc), the same rotation, its negation, and rotations within EPSILON of each other."""
    rng = random.Random(12)
    slerped = signed_zeros = 0
    for i in range(N):
        start, end, into = frame(rng), frame(rng), frame(rng)
        kind = i % 5
        if kind == 1:  # turns about z: x and y are exact zeros, of either sign
            start.set_heading(rng.uniform(0.0, 360.0))
            end.set_heading(rng.uniform(0.0, 360.0))
            if rng.random() < 0.5:
                end.set_rotate(*(-c for c in end.rotation))
        elif kind == 2:
            end.set_rotate(*start.rotation)
        elif kind == 3:
            end.set_rotate(*(-c for c in start.rotation))
        elif kind == 4:
            end.set_rotate(start.qw, start.qx + rng.uniform(-1.0, 1.0) * EPSILON, start.qy, start.qz)
        cosom = sum(a * b for a, b in zip(start.rotation, end.rotation, strict=True))
        slerped += 1.0 - abs(cosom) > EPSILON
        signed_zeros += any(c == 0.0 and math.copysign(1.0, c) < 0.0 for c in end.rotation)
        o, q, m = ft(into)
        got = K.frame_interpolate_rotation(o, q, m, start.rotation, end.rotation, 1.0)
        into.interpolate_rotation(start, end, 1.0)
        check(got, (into.rotation, tuple(into.m)), start.rotation, end.rotation)
    assert slerped > 0.3 * N
    assert signed_zeros > N // 20


def test_combine_subtract_and_the_overloads():
    rng = random.Random(11)
    for _ in range(N):
        f1, f2, dst = frame(rng, nan_origin=0.02), frame(rng, nan_origin=0.02), frame(rng)
        if rng.random() < 0.05:
            f2 = Frame(f2.origin, *raw_quaternion(rng))  # possibly an invalid product
        o1, q1, m1 = ft(f1)
        o2, q2, m2 = ft(f2)
        od, qd, md = ft(dst)
        scale = f32(rng.choice((1.0, 0.5, 2.0, rng.uniform(0.05, 5.0))))

        ref = f1.copy()
        ref.combine(ref, f2)  # in place
        check(K.frame_combine(o1, q1, m1, o1, q1, m1, o2, q2), ft(ref))
        ref = dst.copy()
        ref.combine(f1, f2)
        check(K.frame_combine(od, qd, md, o1, q1, m1, o2, q2), ft(ref))

        ref = f1.copy()
        ref.subtract1(ref, f2)
        check(K.frame_subtract1(o1, q1, m1, o1, q1, o2, q2), ft(ref))
        ref = dst.copy()
        ref.subtract1(f1, f2)
        check(K.frame_subtract1(od, qd, md, o1, q1, o2, q2), ft(ref))

        ref = dst.copy()
        ref.subtract2(f1, f2)
        check(K.frame_subtract2(od, qd, md, o1, q1, o2, q2, m2), ft(ref))

        ref = f1.copy()
        combine_anim_frame(ref, f2)
        check(K.combine_anim_frame(o1, q1, m1, o2, q2), ft(ref))

        ref = dst.copy()
        combine_scaled(ref, f1, f2, scale)
        check(K.combine_scaled(od, qd, md, o1, q1, m1, o2, q2, scale), ft(ref), scale)


def test_points_and_vectors():
    rng = random.Random(12)
    for _ in range(N):
        f = frame(rng)
        p = vector(rng)
        o, _, m = ft(f)
        check(K.frame_localtoglobal(o, m, vt(p)), vt(f.localtoglobal(p)))
        check(K.frame_localtoglobalvec(m, vt(p)), vt(f.localtoglobalvec(p)))
        check(K.frame_globaltolocalvec(m, vt(p)), vt(f.globaltolocalvec(p)))
        check(K.frame_globaltolocal(o, m, vt(p)), vt(f.globaltolocal(p)))


def test_headings():
    rng = random.Random(13)
    for i in range(N):
        f = frame(rng, nan_origin=0.02)
        o, q, m = ft(f)
        check(K.frame_get_vector_heading(m), vt(f.get_vector_heading()))
        check(K.frame_get_heading(m), f.get_heading())

        heading = vector(rng)
        if rng.random() < 0.1:
            heading = Vector3(0.0, 0.0, rng.choice((1.0, -1.0, 1e-3)))
        g = f.copy()
        g.set_vector_heading(heading)
        check(K.frame_set_vector_heading(o, q, m, vt(heading)), (g.rotation, tuple(g.m)), vt(heading))

        degrees = HEADINGS[i % len(HEADINGS)] if rng.random() < 0.4 else rng.uniform(-720.0, 720.0)
        g = f.copy()
        g.set_heading(degrees)
        check(K.frame_set_heading(o, q, m, degrees), (g.rotation, tuple(g.m)), degrees)

        x, y, z = (rng.choice((0.0, math.pi / 2, -math.pi, rng.uniform(-7.0, 7.0))) for _ in range(3))
        g = f.copy()
        g.euler_set_rotate(x, y, z)
        check(K.frame_euler_set_rotate(o, q, m, x, y, z), (g.rotation, tuple(g.m)), (x, y, z))


# -- cell ids and positions --------------------------------------------------------------------------

LOW_WORDS = (0, 1, 2, 8, 9, 0x3F, 0x40, 0x41, 0xFF, 0x100, 0x101, 0xFFFD, 0xFFFE, 0xFFFF)


def cell_id(rng: random.Random, *, near: int | None = None) -> int:
    r = rng.random()
    if r < 0.1:
        return rng.getrandbits(32)
    if near is not None and r < 0.7:
        bx = min(0xFF, max(0, (near >> 24) + rng.randint(-2, 2)))
        by = min(0xFF, max(0, ((near >> 16) & 0xFF) + rng.randint(-2, 2)))
    else:
        bx = rng.choice((0, 1, 0x7F, 0xA9, 0xFE, 0xFF, rng.randrange(256)))
        by = rng.choice((0, 1, 0x7F, 0xB4, 0xFE, 0xFF, rng.randrange(256)))
    low = rng.choice(LOW_WORDS) if rng.random() < 0.4 else rng.randint(1, 0x40)
    return (bx << 24) | (by << 16) | low


def test_gid_lcoord_conversions():
    rng = random.Random(14)
    for _ in range(N):
        c = cell_id(rng)
        want = C.gid_to_lcoord(c)
        check(K.gid_to_lcoord(c), (True, *want) if want is not None else (False, 0, 0), hex(c))
        x, y = rng.randint(-10, 2050), rng.randint(-10, 2050)
        check(K.lcoord_to_gid(x, y), C.lcoord_to_gid(x, y), x, y)
        check(K.valid_cell_index(c), C._valid_cell_index(c))


def test_adjust_to_outside_rehomes_points_beyond_the_block():
    rng = random.Random(15)
    specials = (0.0, -0.0, EPSILON, -EPSILON, 0.5 * EPSILON, -0.99 * EPSILON, 192.0, -192.0, 24.0, 191.99998)
    for _ in range(N):
        c = cell_id(rng)

        def coordinate():
            r = rng.random()
            if r < 0.2:
                return rng.choice(specials)
            if r < 0.3:
                return rng.randint(-20, 28) * CELL_LENGTH + rng.choice((0.0, -1e-5, 1e-5))
            if r < 0.4:
                return rng.uniform(-1e5, 1e5)
            return rng.uniform(-2.5 * BLOCK_LENGTH, 3.5 * BLOCK_LENGTH)

        loc = Vector3(coordinate(), coordinate(), scalar(rng))
        before = vt(loc)
        ref = loc.copy()
        want = C.adjust_to_outside_lcoord(c, ref)
        expected = (True, *want, vt(ref)) if want is not None else (False, 0, 0, vt(ref))
        check(K.adjust_to_outside_lcoord(c, before), expected, hex(c), before)
        ref = loc.copy()
        check(K.adjust_to_outside(c, before), (C.adjust_to_outside(c, ref), vt(ref)), hex(c), before)


@pytest.mark.parametrize(("loc", "error"), [((NAN, 5.0, 0.0), ValueError), ((5.0, INF, 0.0), OverflowError)])
def test_adjust_to_outside_raises_as_the_reference_does(loc, error):
    with pytest.raises(error):
        C.adjust_to_outside_lcoord(0xA9B40021, Vector3(*loc))
    with pytest.raises(error):
        K.adjust_to_outside_lcoord(0xA9B40021, loc)


def test_block_offsets_and_positions():
    rng = random.Random(16)
    for _ in range(N):
        a = cell_id(rng)
        b = cell_id(rng, near=a) or 0x00010001
        if rng.random() < 0.05:
            a = 0
        check(K.get_block_offset(a, b), vt(C.get_block_offset(a, b)), hex(a), hex(b))
        pa, pb = Position(a, frame(rng)), Position(b, frame(rng))
        v = vector(rng)
        oa, _, ma = ft(pa.frame)
        ob, _, mb = ft(pb.frame)
        check(K.position_get_offset(a, oa, b, ob), vt(pa.get_offset(pb)))
        check(K.position_localtoglobal_offset(a, oa, b, ob, mb, vt(v)), vt(pa.localtoglobal_offset(pb, v)))
        check(K.position_localtoglobal(a, b, ob, mb, vt(v)), vt(pa.localtoglobal(pb, v)))
        check(K.position_localtoglobalvec(ma, vt(v)), vt(pa.localtoglobalvec(v)))
        check(K.position_globaltolocalvec(ma, vt(v)), vt(pa.globaltolocalvec(v)))
        check(K.position_localtolocal(a, oa, ma, b, ob, mb, vt(v)), vt(pa.localtolocal(pb, v)))


def test_block_offset_to_cell_zero():
    """The reference refuses a destination of 0 in another block; the kernel measures to block (0, 0)."""
    with pytest.raises(ValueError):
        C.get_block_offset(0xA9B40021, 0)
    check(K.get_block_offset(0xA9B40021, 0), (-0xA9 * 8 * CELL_LENGTH, -0xB4 * 8 * CELL_LENGTH, 0.0))
    check(K.get_block_offset(0x00000021, 0), (0.0, 0.0, 0.0))


# -- the double arithmetic, with the float32 stores taken out ---------------------------------------

#: Loads ``acphys.precision`` alone, makes every narrowing the identity, and only then lets the
#: package import (each module binds ``f32``, ``pack3``... at its import); then the kernels run as
#: plain Python (``NUMBA_DISABLE_JIT``) with their ``f32`` the identity too.
_UNNARROWED = """
import importlib.util, os, sys
spec = importlib.util.find_spec("acphys")
path = os.path.join(spec.submodule_search_locations[0], "precision.py")
spec = importlib.util.spec_from_file_location("acphys.precision", path)
precision = importlib.util.module_from_spec(spec)
spec.loader.exec_module(precision)
precision.f32 = lambda v: v
precision.f32x3 = lambda x, y, z: (x, y, z)
for k in (1, 3, 4, 9):
    setattr(precision, f"pack{k}", lambda *v: v)
    setattr(precision, f"unpack{k}", lambda v: v)
sys.modules["acphys.precision"] = precision
import acphys.fast.kernels.frame as kernels
kernels.f32 = lambda v: v
assert kernels.frame_cache.__module__ == kernels.__name__ and not hasattr(kernels.frame_cache, "py_func")
import pytest
sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "-k", "not unnarrowed", sys.argv[1]]))
"""


def test_unnarrowed_double_arithmetic():
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    result = subprocess.run(
        [sys.executable, "-c", _UNNARROWED, __file__], capture_output=True, text=True, env=env, timeout=300
    )
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-4000:]
    assert " passed" in result.stdout and " failed" not in result.stdout
