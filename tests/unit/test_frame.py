"""Unit tests for ``Vector3`` and ``Frame`` against the retail decompilation (build 11.4186).

Every expected value is worked out by hand from the decompiled retail function
cited beside the test. Where a test compares against quaternion algebra, that
algebra is written here with plain ``math`` (:func:`qmul`, :func:`axis_angle`,
:func:`qrot`) and does not call the code under test.

Quaternions are ``(w, x, y, z)``, Hamilton product, as retail stores them
(``Frame``: qw, qx, qy, qz, m_fl2gv[9], m_fOrigin; acclient.h:30647).
"""

from __future__ import annotations

import math

import pytest

from acphys.constants import EPSILON
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32

C45 = math.cos(math.pi / 4)  # cos 45° = sin 45° = √½
S45 = math.sin(math.pi / 4)
Q_IDENTITY = (1.0, 0.0, 0.0, 0.0)
Q_Z90 = (f32(C45), 0.0, 0.0, f32(S45))  # +90° about z, as a Frame stores it (float32)
Q_X90 = (f32(C45), f32(S45), 0.0, 0.0)  # +90° about x (float32)
Q_CYCLE = (0.5, 0.5, 0.5, 0.5)  # +120° about (1,1,1)/√3: x→y→z→x

#: Frames store float32 (acphys.precision), so the algebra below holds to a few float32 ulps, not to
#: double precision: TOL absolute (unit quaternions, small vectors), REL relative (origins far out).
TOL = 1e-6
REL = 1e-6
#: A heading set and read back in float32: set_vector_heading hands euler_set_rotate the yaw as a
#: float radian angle, good near 2π to half an ulp, 2.4e-7 rad (1.4e-5°).
HEADING_TOL = 3e-5


# -- independent quaternion algebra (plain math, not the code under test) ----------------------


def qmul(a, b):
    """Hamilton product a·b."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )


def qconj(q):
    return (q[0], -q[1], -q[2], -q[3])


def axis_angle(w):
    """The unit quaternion of the rotation vector ``w`` (radians about ŵ)."""
    theta = math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)
    s = math.sin(theta / 2) / theta
    return (math.cos(theta / 2), s * w[0], s * w[1], s * w[2])


def qrot(q, v):
    """Rotate the vector v by q: the vector part of q·(0, v)·q*."""
    r = qmul(qmul(q, (0.0, v[0], v[1], v[2])), qconj(q))
    return (r[1], r[2], r[3])


def vec(v):
    return tuple(v)


def assert_quat(frame: Frame, expected, tol: float = TOL) -> None:
    assert frame.rotation == pytest.approx(tuple(expected), abs=tol)


def round_trip_tol(*frames: Frame) -> float:
    """16 float32 ulps of the largest origin component a round trip passes through."""
    return 16 * 2.0**-23 * max(max(abs(c) for c in f.origin) for f in frames)


def assert_vec(v, expected, tol: float = TOL) -> None:
    assert tuple(v) == pytest.approx(tuple(expected), abs=tol, rel=REL)


def make(origin, q) -> Frame:
    return Frame(Vector3(*origin), *q)


# Non-trivial frames (unit quaternions from the independent helper) for round trips.
FRAMES = [
    make((12.5, -3.25, 40.0), axis_angle((0.3, -1.1, 0.7))),
    make((-7.0, 2.5, 1.75), axis_angle((2.0, 0.4, -0.9))),
    make((100.0, 150.0, -2.0), axis_angle((-0.1, 0.2, 3.0))),
    make((1.0, 2.0, 3.0), Q_CYCLE),
    make((0.0, 0.0, 0.0), Q_Z90),
]
FRAME_PAIRS = [(a, b) for a in range(len(FRAMES)) for b in range(len(FRAMES)) if a != b]


# -- Vector3 ----------------------------------------------------------------------------------


class TestVector3:
    def test_eq_is_the_retail_epsilon_test(self):
        # AC1Legacy::Vector3::operator== @ 0x00509F10 (acclient.c:311682):
        #   fabs(x - v.x) <= 0.00019999999 && (same for y) && (same for z).
        # 0 - EPSILON is exact, so |Δ| == EPSILON: equal (<=, not <).
        assert Vector3(0, 0, 0) == Vector3(EPSILON, 0, 0)
        assert Vector3(0, 0, 0) == Vector3(0, -EPSILON, 0)
        assert Vector3(0, 0, 0) == Vector3(0, 0, EPSILON)
        assert Vector3(1.0, 2.0, 3.0) == Vector3(1.0 + 1e-4, 2.0 - 1e-4, 3.0 + 1e-4)
        # Any one axis beyond EPSILON breaks equality.
        assert (Vector3(0, 0, 0) == Vector3(3e-4, 0, 0)) is False
        assert (Vector3(0, 0, 0) == Vector3(0, 3e-4, 0)) is False
        assert (Vector3(0, 0, 0) == Vector3(0, 0, -3e-4)) is False
        assert Vector3(0, 0, 0) != Vector3(0, 0, -3e-4)
        # The epsilon-equal vectors are not bitwise equal.
        assert not Vector3(0, 0, 0).exactly_equals(Vector3(EPSILON, 0, 0))

    def test_is_zero_is_strict(self):
        # AC1Legacy::Vector3::is_zero @ 0x0050E7B0 (acclient.c:315576):
        #   fabs(x) < 0.00019999999 && fabs(y) < ... && fabs(z) < ...   (strict <)
        assert Vector3(0.999 * EPSILON, -0.999 * EPSILON, 0.0).is_zero()
        assert not Vector3(EPSILON, 0.0, 0.0).is_zero()
        assert not Vector3(0.0, -EPSILON, 0.0).is_zero()
        assert not Vector3(0.0, 0.0, EPSILON).is_zero()

    def test_normalize_check_small_leaves_a_short_vector(self):
        # AC1Legacy::Vector3::normalize_check_small @ 0x00452460 (acclient.c:143621):
        #   len = sqrt(x²+y²+z²); if (len >= 0.00019999999) scale by 1/len, return 0;
        #   else return 1 and leave the vector alone. |(1e-4, 1e-4, 0)| = 1.414e-4 < EPSILON.
        v = Vector3(1e-4, 1e-4, 0.0)
        assert v.normalize_check_small() is True
        assert v.exactly_equals(Vector3(1e-4, 1e-4, 0.0))

    def test_normalize_check_small_normalises(self):
        # Same function: |(3, 0, 4)| = 5 → (0.6, 0, 0.8), returns 0 (False).
        v = Vector3(3.0, 0.0, 4.0)
        assert v.normalize_check_small() is False
        assert_vec(v, (0.6, 0.0, 0.8))
        # len == EPSILON exactly is not "small" (retail tests len >= EPSILON).
        w = Vector3(EPSILON, 0.0, 0.0)
        assert w.normalize_check_small() is False
        assert_vec(w, (1.0, 0.0, 0.0))


# -- Frame::cache ----------------------------------------------------------------------------


class TestCache:
    def test_identity(self):
        # Frame::cache @ 0x00534DF0 (acclient.c:356983) with q = (1,0,0,0): every product
        # term is 0, so m = [1,0,0, 0,1,0, 0,0,1].
        f = Frame()
        assert f.m == [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]

    def test_z90_column_major_layout(self):
        # Frame::cache @ 0x00534DF0 (acclient.c:356983), q = (c, 0, 0, s), c = s = √½:
        #   b2 = c2 = 0, v3 = 2s; v6 = qw·v3 = 2cs = 1; v12 = qz·v3 = 2s² = 1; all else 0.
        #   m[0] = 1 - cc2 - v12 = 0   m[1] = v8 + v6 = 1    m[2] = bd2 - v5 = 0
        #   m[3] = v8 - v6 = -1        m[4] = 1 - v7 - v12 = 0   m[5] = v11 + v4 = 0
        #   m[6] = 0  m[7] = 0  m[8] = 1 - v7 - cc2 = 1
        # Column-major: local x → +y (m[0:3]), local y/forward → -x (m[3:6]), local z → +z.
        f = make((0, 0, 0), Q_Z90)
        assert f.m[0:3] == pytest.approx([0.0, 1.0, 0.0], abs=TOL)
        assert f.m[3:6] == pytest.approx([-1.0, 0.0, 0.0], abs=TOL)
        assert f.m[6:9] == pytest.approx([0.0, 0.0, 1.0], abs=TOL)

    def test_x90(self):
        # Frame::cache (acclient.c:356983), q = (c, s, 0, 0): b2 = 2s, v4 = qw·b2 = 1,
        # v7 = qx·b2 = 1, rest 0. m[0..2] = (1, 0, 0); m[3] = 0, m[4] = 1 - v7 - 0 = 0,
        # m[5] = v11 + v4 = 1; m[6] = 0, m[7] = v11 - v4 = -1, m[8] = 1 - v7 - 0 = 0.
        # Pitching +90° about x lifts the forward (local y) to +z.
        f = make((0, 0, 0), Q_X90)
        assert f.m == pytest.approx([1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0], abs=TOL)

    def test_cyclic_quaternion_exact(self):
        # Frame::cache (acclient.c:356983), q = (½, ½, ½, ½): every doubled component is 1,
        # every product is ½. m[0] = 1-½-½ = 0, m[1] = ½+½ = 1, m[2] = ½-½ = 0;
        # m[3] = 0, m[4] = 0, m[5] = 1; m[6] = 1, m[7] = 0, m[8] = 0 (exact in binary).
        f = make((0, 0, 0), Q_CYCLE)
        assert f.m == [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0]

    @pytest.mark.parametrize("frame", FRAMES)
    def test_columns_are_the_rotated_axes(self, frame):
        # Frame::cache (acclient.c:356983) is the matrix of v ↦ q·v·q*; its columns are the
        # images of the local axes (independent algebra: qrot).
        q = frame.rotation
        assert frame.m[0:3] == pytest.approx(qrot(q, (1, 0, 0)), abs=TOL)
        assert frame.m[3:6] == pytest.approx(qrot(q, (0, 1, 0)), abs=TOL)
        assert frame.m[6:9] == pytest.approx(qrot(q, (0, 0, 1)), abs=TOL)


# -- Frame::set_rotate -----------------------------------------------------------------------


class TestSetRotate:
    def test_normalises_and_caches(self):
        # Frame::set_rotate @ 0x00535080 (acclient.c:357062): v6 = 1/sqrt(w²+x²+y²+z²),
        # q = q_in·v6, then IsValid → cache. (0, 0, 0, 3): v6 = ⅓ → q = (0, 0, 0, 1) (180° z);
        # cache: v12 = qz·2qz = 2 → m[0] = 1-0-2 = -1, m[4] = 1-0-2 = -1, m[8] = 1.
        f = Frame()
        f.set_rotate(0.0, 0.0, 0.0, 3.0)
        assert f.rotation == (0.0, 0.0, 0.0, 1.0)
        assert f.m == [-1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0]

    def test_normalises_a_generic_quaternion(self):
        # Same line: (1, 1, 1, 1) · 1/sqrt(4) = (½, ½, ½, ½), exactly.
        f = Frame()
        f.set_rotate(1.0, 1.0, 1.0, 1.0)
        assert f.rotation == Q_CYCLE
        assert f.m == [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0]
        # (2, 0, 0, 0) → identity.
        f.set_rotate(2.0, 0.0, 0.0, 0.0)
        assert f.rotation == Q_IDENTITY

    @pytest.mark.parametrize(
        "bad",
        [
            (0.0, 0.0, 0.0, 0.0),  # 1/sqrt(0) = inf, 0·inf = NaN → IsValid fails
            (math.nan, 0.0, 0.0, 1.0),  # NaN propagates
            (math.inf, 0.0, 0.0, 0.0),  # 1/sqrt(inf) = 0, inf·0 = NaN
        ],
    )
    def test_invalid_result_restores_old_quaternion_and_skips_cache(self, bad):
        # Frame::set_rotate (acclient.c:357062): if !IsValid → qw..qz = oldqw..oldqz, and
        # Frame::cache is not called, so the matrix keeps whatever it held.
        f = make((1, 2, 3), Q_Z90)
        sentinel = [9.0, 8.0, 7.0, 6.0, 5.0, 4.0, 3.0, 2.0, 1.0]
        f.m[:] = sentinel
        f.set_rotate(*bad)
        assert f.rotation == Q_Z90
        assert f.m == sentinel

    def test_nan_origin_blocks_any_rotation(self):
        # Frame::IsValid (acclient.c:357024) also tests the origin for NaN, so
        # Frame::set_rotate (acclient.c:357062) restores the old quaternion even for a good one.
        f = Frame(Vector3(math.nan, 0.0, 0.0))
        f.set_rotate(*Q_Z90)
        assert f.rotation == Q_IDENTITY
        assert f.m == [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]


# -- Frame::IsValid / IsValidExceptForHeading -----------------------------------------------


class TestValidity:
    def test_unit_quaternion_is_valid(self):
        # Frame::IsValid @ 0x00534ED0 (acclient.c:357024): no NaN, |norm - 1| <= 5·EPSILON.
        assert Frame().is_valid()
        assert make((1, 2, 3), Q_CYCLE).is_valid()

    @pytest.mark.parametrize("where", ["ox", "oy", "oz", "qw", "qx", "qy", "qz"])
    def test_nan_anywhere_is_invalid(self, where):
        # Frame::IsValid (acclient.c:357024): __isnan on each origin and quaternion component.
        f = Frame()
        if where.startswith("o"):
            setattr(f.origin, where[1], math.nan)
        else:
            setattr(f, where, math.nan)
        assert not f.is_valid()

    def test_infinite_origin_is_still_valid(self):
        # Frame::IsValid (acclient.c:357024) tests only __isnan on the origin, never finiteness.
        f = Frame(Vector3(math.inf, 0.0, -math.inf))
        assert f.is_valid()

    def test_norm_tolerance_is_five_epsilon(self):
        # Frame::IsValid (acclient.c:357024): invalid when 0.00019999999 * 5.0 < fabs(norm - 1.0),
        # the float32 F_EPSILON times 5 in double: 0.00099999997. qw = sqrt(1 ± δ) gives
        # norm = 1 ± δ (up to float32 rounding, far from the bound).
        assert 5 * EPSILON == 5 * f32(0.0002) == 0.0009999999747378752
        assert Frame(qw=math.sqrt(1.0 + 0.00099)).is_valid()
        assert Frame(qw=math.sqrt(1.0 - 0.00099)).is_valid()
        assert not Frame(qw=math.sqrt(1.0 + 0.00101)).is_valid()
        assert not Frame(qw=math.sqrt(1.0 - 0.00101)).is_valid()
        assert not Frame(qw=math.inf).is_valid()  # norm = inf, fabs(inf - 1) > 5ε

    def test_is_valid_except_for_heading(self):
        # Frame::IsValidExceptForHeading @ 0x00534FE0 (acclient.c:357050):
        #   !isnan(ox) && !isnan(oy) && !isnan(oz) && (isnan(qw) || isnan(qx) || isnan(qy) || isnan(qz))
        assert not Frame().is_valid_except_for_heading()  # no NaN quaternion component
        for comp in ("qw", "qx", "qy", "qz"):
            f = Frame(Vector3(1.0, 2.0, 3.0))
            setattr(f, comp, math.nan)
            assert f.is_valid_except_for_heading(), comp
        # NaN origin (any axis) → False even with a NaN quaternion.
        for axis in ("x", "y", "z"):
            f = Frame()
            f.qx = math.nan
            setattr(f.origin, axis, math.nan)
            assert not f.is_valid_except_for_heading(), axis
        # Retail tests __isnan only: an infinite origin still counts as "sound".
        f = Frame(Vector3(math.inf, 0.0, 0.0))
        f.qz = math.nan
        assert f.is_valid_except_for_heading()
        # A bad norm without NaN is not "except for heading".
        assert not Frame(qw=2.0).is_valid_except_for_heading()


# -- combine / subtract1 / subtract2 ---------------------------------------------------------


class TestCombineSubtract:
    def test_combine_hand_example(self):
        # Frame::combine @ 0x005122E0 (acclient.c:319448):
        #   origin = f1.m · f2.origin + f1.origin; q = q1·q2 (Hamilton).
        # f1 = (10, 20, 30), 90° z: m columns x→(0,1,0), y→(-1,0,0), z→(0,0,1).
        # f2 = (1, 2, 3), 90° x.
        #   m·(1,2,3) = 1·(0,1,0) + 2·(-1,0,0) + 3·(0,0,1) = (-2, 1, 3) → origin (8, 21, 33).
        #   new_qw = c·c - 0 = ½; new_qx = c·s = ½; new_qy = qz1·qx2 = s·s = ½; new_qz = s·c = ½.
        f1 = make((10, 20, 30), Q_Z90)
        f2 = make((1, 2, 3), Q_X90)
        out = Frame()
        out.combine(f1, f2)
        assert_vec(out.origin, (8.0, 21.0, 33.0))
        assert_quat(out, Q_CYCLE)

    @pytest.mark.parametrize(("a", "b"), FRAME_PAIRS)
    def test_combine_matches_quaternion_algebra(self, a, b):
        # Frame::combine (acclient.c:319448), checked against q1·q2 and q1·p·q1* written here.
        f1, f2 = FRAMES[a], FRAMES[b]
        out = Frame()
        out.combine(f1, f2)
        rotated = qrot(f1.rotation, vec(f2.origin))
        assert_vec(out.origin, (f1.origin.x + rotated[0], f1.origin.y + rotated[1], f1.origin.z + rotated[2]))
        assert_quat(out, qmul(f1.rotation, f2.rotation))

    def test_combine_in_place_on_f1(self):
        # Frame::combine (acclient.c:319448) reads all of f1's origin before writing this->origin
        # and computes the quaternion from f1 before set_rotate, so this == f1 is safe.
        f1 = make((10, 20, 30), Q_Z90)
        f1.combine(f1, make((1, 2, 3), Q_X90))
        assert_vec(f1.origin, (8.0, 21.0, 33.0))
        assert_quat(f1, Q_CYCLE)

    def test_subtract2_hand_example(self):
        # Frame::subtract2 @ 0x00535650 (acclient.c:357364): origin = f2.globaltolocal(f1.origin),
        # q = conj(q2)·q1. Undo the combine example: f1 = (8, 21, 33), q ½½½½; f2 = (10,20,30), 90° z.
        #   f1.origin - f2.origin = (-2, 1, 3); Mᵀ rows are the columns: (0,1,0)·v = 1,
        #   (-1,0,0)·v = 2, (0,0,1)·v = 3 → (1, 2, 3).
        #   new_qw = ½c + ½s = c; new_qx = ½c + ½s = c; new_qy = ½s - ½c = 0; new_qz = ½c - ½s = 0
        #   → (c, c, 0, 0) = 90° about x.
        out = Frame()
        out.subtract2(make((8, 21, 33), Q_CYCLE), make((10, 20, 30), Q_Z90))
        assert_vec(out.origin, (1.0, 2.0, 3.0))
        assert_quat(out, Q_X90)

    def test_subtract1_hand_example(self):
        # Frame::subtract1 @ 0x00535520 (acclient.c:357321): q = q1·conj(q2) (new_qw = q1·q2 dot),
        # then origin = -m_X·f2.origin + f1.origin. With f1 = (8, 21, 33), ½½½½ and f2 = (1, 2, 3),
        # 90° x: q1·conj(q2): w = ½c + ½s = c, x = ½c - ½s = 0, y = ½c - ½s = 0, z = ½s + ½c = c
        # → 90° about z; m_X·(1,2,3) = (-2, 1, 3) → origin (8+2, 21-1, 33-3) = (10, 20, 30).
        out = Frame()
        out.subtract1(make((8, 21, 33), Q_CYCLE), make((1, 2, 3), Q_X90))
        assert_vec(out.origin, (10.0, 20.0, 30.0))
        assert_quat(out, Q_Z90)

    @pytest.mark.parametrize(("a", "b"), FRAME_PAIRS)
    def test_subtract1_undoes_combine(self, a, b):
        # Frame::subtract1 (acclient.c:357321) ∘ Frame::combine (acclient.c:319448):
        # (a∘b)∘b⁻¹ = a, i.e. subtract1(combine(a, b), b) == a.
        fa, fb = FRAMES[a], FRAMES[b]
        ab = Frame()
        ab.combine(fa, fb)
        out = Frame()
        out.subtract1(ab, fb)
        assert_vec(out.origin, vec(fa.origin), tol=round_trip_tol(fa, fb, ab))
        assert_quat(out, fa.rotation)
        assert out.m == pytest.approx(fa.m, abs=TOL)

    @pytest.mark.parametrize(("a", "b"), FRAME_PAIRS)
    def test_subtract2_undoes_combine(self, a, b):
        # Frame::subtract2 (acclient.c:357364) ∘ Frame::combine (acclient.c:319448):
        # a⁻¹∘(a∘b) = b, i.e. subtract2(combine(a, b), a) == b.
        fa, fb = FRAMES[a], FRAMES[b]
        ab = Frame()
        ab.combine(fa, fb)
        out = Frame()
        out.subtract2(ab, fa)
        assert_vec(out.origin, vec(fb.origin), tol=round_trip_tol(fa, fb, ab))
        assert_quat(out, fb.rotation)


# -- grotate / rotate ------------------------------------------------------------------------


class TestGrotateRotate:
    def test_grotate_hand_example(self):
        # Frame::grotate @ 0x005357A0 (acclient.c:357421), w = (0, 0, π/2) on identity:
        # θ = π/2, f = g = 0, v10 = sin(π/4); new_qz = v10·qw = s, new_qw = cos(π/4)·qw = c
        # → (c, 0, 0, s); the forward m[3:6] becomes (-1, 0, 0).
        f = Frame()
        f.grotate(Vector3(0.0, 0.0, math.pi / 2))
        assert_quat(f, Q_Z90)
        assert f.m[3:6] == pytest.approx([-1.0, 0.0, 0.0], abs=TOL)

    @pytest.mark.parametrize("frame", FRAMES)
    @pytest.mark.parametrize("w", [(0.0, 0.0, 1.0), (0.5, -0.25, 0.1), (-2.0, 1.5, 0.3), (0.0, 3.0, 0.0)])
    def test_grotate_left_multiplies(self, frame, w):
        # Frame::grotate (acclient.c:357421): (c, f, g, h) = (cos θ/2, sin θ/2·ŵ); new_qw =
        # c·qw - f·qx - g·qy - h·qz etc. is the Hamilton product (c,f,g,h)·q: a global-axis turn.
        f = frame.copy()
        f.grotate(Vector3(*w))
        assert_quat(f, qmul(axis_angle(w), frame.rotation))

    def test_grotate_ignores_tiny_w(self):
        # Frame::grotate (acclient.c:357421): runs only if |w|² >= 0.00019999999 * 0.00019999999.
        # |w| = 0.999·EPSILON (one axis) and |(1.4e-4, 1.4e-4, 0)| = 1.98e-4: both nothing.
        for w in (Vector3(0.999 * EPSILON, 0.0, 0.0), Vector3(1.4e-4, 1.4e-4, 0.0)):
            f = make((1, 2, 3), Q_Z90)
            before_m = f.m.copy()
            f.grotate(w)
            assert f.rotation == Q_Z90
            assert f.m == before_m

    def test_grotate_acts_at_and_above_epsilon(self):
        # Same line: |w| = EPSILON exactly gives |w|² == EPSILON², not < → rotates; so does 1.001·ε.
        # Identity rotated by θ about x: (cos θ/2, sin θ/2, 0, 0).
        # Worked in float32 from acclient.c:357433-357446: thetainv, the cosine and f are float
        # locals; the sine stays double; set_rotate then normalises (c, f, 0, 0) and stores floats.
        for theta in (EPSILON, f32(1.001 * EPSILON)):
            f = Frame()
            f.grotate(Vector3(theta, 0.0, 0.0))
            angle = math.sqrt(theta * theta)
            inv = f32(1.0 / angle)
            c = f32(math.cos(angle * 0.5))
            fx = f32(math.sin(angle * 0.5) * theta * inv)
            norm = 1.0 / math.sqrt(c * c + fx * fx)
            assert f.rotation == (f32(c * norm), f32(fx * norm), 0.0, 0.0)
            assert f.qx > 0.0

    @pytest.mark.parametrize("frame", FRAMES)
    @pytest.mark.parametrize("w", [(1.0, 0.0, 0.0), (0.5, -0.25, 0.1), (0.0, -2.5, 1.0)])
    def test_rotate_is_grotate_of_the_global_vector(self, frame, w):
        # Frame::rotate @ 0x004525B0 (acclient.c:143690): v2 = m·w (local → global), then grotate(v2).
        # Algebra: aa(q·w·q*)·q = q·aa(w)·q*·q = q·aa(w): a right multiplication (local axis).
        f = frame.copy()
        f.rotate(Vector3(*w))
        assert_quat(f, qmul(frame.rotation, axis_angle(w)))
        g = frame.copy()
        g.grotate(Vector3(*qrot(frame.rotation, w)))
        assert_quat(f, g.rotation)

    def test_local_x_pitch_differs_from_global_x(self):
        # A frame facing east: Frame::set_heading(90) (acclient.c:357691) → q = (c, 0, 0, -s),
        # local x = m[0:3] = (0, -1, 0) (south), forward = (1, 0, 0).
        # Frame::rotate (acclient.c:143690) by (π/2, 0, 0) turns about local x = global -y:
        #   forward (1,0,0) → k×v = (0,-1,0)×(1,0,0) = (0, 0, 1): the nose pitches up.
        # Frame::grotate (acclient.c:357421) by (π/2, 0, 0) turns about global x, the forward
        #   axis itself: forward stays (1, 0, 0) and the local z (0,0,1) rolls to (0, -1, 0).
        east = Frame()
        east.set_heading(90.0)
        assert_quat(east, (C45, 0.0, 0.0, -S45))
        local = east.copy()
        local.rotate(Vector3(math.pi / 2, 0.0, 0.0))
        assert_vec(local.get_vector_heading(), (0.0, 0.0, 1.0))
        globl = east.copy()
        globl.grotate(Vector3(math.pi / 2, 0.0, 0.0))
        assert_vec(globl.get_vector_heading(), (1.0, 0.0, 0.0))
        assert globl.m[6:9] == pytest.approx([0.0, -1.0, 0.0], abs=TOL)


# -- localtoglobal / globaltolocal -----------------------------------------------------------


class TestLocalGlobal:
    def test_values(self):
        # Frame::localtoglobal @ 0x00452620 (acclient.c:143701): m·in + origin.
        # Frame at (10, 20, 30) turned 90° about z: m·(1, 2, 3) = (-2, 1, 3) → (8, 21, 33).
        f = make((10, 20, 30), Q_Z90)
        assert_vec(f.localtoglobal(Vector3(1, 2, 3)), (8.0, 21.0, 33.0))
        # Frame::globaltolocal @ 0x00452680 (acclient.c:143717): Mᵀ·(in - origin):
        # (8,21,33) - (10,20,30) = (-2,1,3); rows (0,1,0)→1, (-1,0,0)→2, (0,0,1)→3.
        assert_vec(f.globaltolocal(Vector3(8, 21, 33)), (1.0, 2.0, 3.0))
        # Frame::localtoglobalvec @ 0x004524F0 (acclient.c:143658): no origin; local x → +y.
        assert_vec(f.localtoglobalvec(Vector3(1, 0, 0)), (0.0, 1.0, 0.0))
        # Frame::globaltolocalvec @ 0x00452550 (acclient.c:143674): Mᵀ; global +y → local x.
        assert_vec(f.globaltolocalvec(Vector3(0, 1, 0)), (1.0, 0.0, 0.0))
        assert_vec(f.globaltolocalvec(Vector3(1, 0, 0)), (0.0, -1.0, 0.0))

    @pytest.mark.parametrize("frame", FRAMES)
    def test_inverse_and_agrees_with_quaternion(self, frame):
        # Frame::localtoglobal (acclient.c:143701) is q·p·q* + origin; Frame::globaltolocal
        # (acclient.c:143717) is its inverse since m is orthonormal.
        p = (3.5, -1.25, 7.0)
        g = frame.localtoglobal(Vector3(*p))
        r = qrot(frame.rotation, p)
        tol = round_trip_tol(frame)
        assert_vec(g, (r[0] + frame.origin.x, r[1] + frame.origin.y, r[2] + frame.origin.z), tol=tol)
        assert_vec(frame.globaltolocal(g), p, tol=tol)
        assert_vec(frame.localtoglobal(frame.globaltolocal(Vector3(*p))), p, tol=tol)


# -- interpolation ---------------------------------------------------------------------------


class TestInterpolate:
    def test_endpoints(self):
        # Frame::interpolate_rotation @ 0x00535390 (acclient.c:357257): cosom = c > 0, ω = π/4;
        # t = 0: v11 = sin(ω)/sin(ω) = 1, v12 = 0 → from; t = 1: v11 = 0, v12 = 1 → to.
        a, b = Frame(), make((0, 0, 0), Q_Z90)
        out = Frame()
        out.interpolate_rotation(a, b, 0.0)
        assert_quat(out, Q_IDENTITY)
        out.interpolate_rotation(a, b, 1.0)
        assert_quat(out, Q_Z90)

    def test_midpoint_is_45_degrees(self):
        # Same line, t = ½: v11 = v12 = sin(π/8)/sin(π/4); q ∝ (1 + c, 0, 0, s), which after
        # set_rotate's normalisation is (cos π/8, 0, 0, sin π/8): 45° about z.
        out = Frame()
        out.interpolate_rotation(Frame(), make((0, 0, 0), Q_Z90), 0.5)
        assert_quat(out, (math.cos(math.pi / 8), 0.0, 0.0, math.sin(math.pi / 8)))
        assert out.get_heading() == pytest.approx(315.0, abs=1e-12)  # forward turned 45° west of north

    def test_shortest_arc_flips_the_sign(self):
        # Same line: cosom = q1·q2 < 0 → cosom = -cosom, to1 = -q2. With to = -(90° z) =
        # (-c, 0, 0, -s) (the same rotation), cosom = -c → flipped to +c and to1 = (c, 0, 0, s),
        # so the midpoint is again (cos π/8, 0, 0, sin π/8). Without the flip it would be
        # ∝ (1 - c, 0, 0, -s): the 135° long way round.
        out = Frame()
        out.interpolate_rotation(Frame(), make((0, 0, 0), (-C45, 0.0, 0.0, -S45)), 0.5)
        assert_quat(out, (math.cos(math.pi / 8), 0.0, 0.0, math.sin(math.pi / 8)))

    def test_linear_fallback_when_nearly_equal(self):
        # Same line: if 1 - cosom <= 0.00019999999 → v11 = 1 - t, v12 = t (plain lerp).
        # End = h = 0.01 rad about z: cosom = cos(h/2), 1 - cosom = 1.25e-5 <= ε.
        # t = ¼: q ∝ (¾ + ¼cos(h/2), 0, 0, ¼sin(h/2)), normalised by set_rotate.
        # In float32: the end quaternion is stored as floats, the weights stay double, the blended
        # quaternion passes to set_rotate as float arguments and is stored normalised as floats.
        h = 0.01
        end = make((0, 0, 0), (math.cos(h / 2), 0.0, 0.0, math.sin(h / 2)))
        out = Frame()
        out.interpolate_rotation(Frame(), end, 0.25)
        w, z = f32(0.75 * 1.0 + end.qw * 0.25), f32(end.qz * 0.25)
        n = 1.0 / math.sqrt(w * w + z * z)
        assert out.rotation == (f32(w * n), 0.0, 0.0, f32(n * z))
        # And that is measurably not the slerp value (cos h/8, 0, 0, sin h/8).
        assert abs(out.qz - math.sin(h / 8)) > 1e-10

    def test_linear_fallback_when_a_weight_leaves_unit_interval(self):
        # Same line: t = 1.5 on the 90° pair: v11 = sin(ω·(-½))/sin ω < 0 → v11 = 1 - t = -½,
        # v12 = t = 1.5. q ∝ (-½ + 1.5c, 0, 0, 1.5s), normalised.
        out = Frame()
        out.interpolate_rotation(Frame(), make((0, 0, 0), Q_Z90), 1.5)
        w, z = -0.5 + 1.5 * C45, 1.5 * S45
        n = math.hypot(w, z)
        assert_quat(out, (w / n, 0.0, 0.0, z / n))

    def test_interpolate_origin(self):
        # Frame::interpolate_origin @ 0x005352F0 (acclient.c:357228): t·to + (1 - t)·from.
        # t = ¼, from (0, 8, -4), to (4, 0, 4): (1, 6, -2).
        out = Frame()
        out.interpolate_origin(make((0, 8, -4), Q_IDENTITY), make((4, 0, 4), Q_IDENTITY), 0.25)
        assert_vec(out.origin, (1.0, 6.0, -2.0))


# -- headings --------------------------------------------------------------------------------


def facing_for_compass(d: float):
    """The unit horizontal direction of compass bearing d (0 = +y, 90 = +x), as set_heading builds it."""
    r = math.radians(d)
    return (math.sin(r), math.cos(r), 0.0)


class TestHeading:
    """The heading convention: compass degrees, 0 faces +y (north), 90 faces +x (east).

    Hex-Rays prints ``fmod(450 - atan2(x, y) * 57.29577951308232, 360)`` in
    Frame::get_heading @ 0x00535760 (acclient.c:357409), Frame::set_vector_heading
    @ 0x00535DB0 (acclient.c:357667) and AC1Legacy::Vector3::get_heading @ 0x004575D0
    (acclient.c:148166). Read with C's ``atan2(y, x)`` parameter order that would be the
    plain mathematical angle (identity → 90, facing +x → 0). acphys reads the operands
    as ``atan2(y, x)`` (the compass bearing) because retail's own consumers need it:

    * Frame::set_heading @ 0x00535E40 (acclient.c:357691) builds the direction
      ``(sin d, cos d, m[5])`` (the compass direction d) and hands it to
      set_vector_heading; set_heading(d) must then face d.
    * CPhysicsObj::UpdateObjectInternal @ 0x005156B0 (acclient.c:322718), ALIGNPATH_PS:
      ``set_vector_heading(&new_pos.frame, &diff)`` must face the body along its path;
      SLEDDING_PS: ``set_heading(get_heading(velocity))`` must face along the velocity.

    Under the literal reading set_vector_heading(v) would yaw by -angle(v), turning +y to
    the mirror image of v about the x = y diagonal, so neither consumer would face its
    direction. The tests below pin the consumer-consistent reading.
    """

    def test_identity_faces_north_with_heading_zero(self):
        # Frame::get_vector_heading @ 0x00535720 (acclient.c:357393) = (m[3], m[4], m[5]) = (0, 1, 0).
        # Frame::get_heading (acclient.c:357409): fmod(450 - atan2(1, 0)·(180/π), 360) = fmod(360, 360) = 0.
        f = Frame()
        assert_vec(f.get_vector_heading(), (0.0, 1.0, 0.0))
        assert f.get_heading() == 0.0
        # The literal Hex-Rays operand order would give 90 for the identity: not what acphys does.
        assert math.fmod(450.0 - math.degrees(math.atan2(f.m[3], f.m[4])), 360.0) == 90.0

    def test_set_heading_90_faces_east(self):
        # Frame::set_heading (acclient.c:357691): direction = (sin 90°, cos 90°, m[5] = 0) ≈ (1, 0, 0).
        # Frame::set_vector_heading (acclient.c:357667): bearing = fmod(450 - atan2(0, 1)°, 360) = 90,
        # z = -90° in radians = -π/2, x = asin(0) = 0; euler_set_rotate(0, 0, -π/2, 0)
        # (acclient.c:357588, order XYZs): q = (cos(-π/4), 0, 0, sin(-π/4)) = (c, 0, 0, -s).
        # Frame::cache: m[3] = v8 - v6 = 0 - 2c(-s) = 1, m[4] = 1 - 2s² = 0 → forward (1, 0, 0).
        f = Frame()
        f.set_heading(90.0)
        assert_quat(f, (C45, 0.0, 0.0, -S45))
        assert_vec(f.get_vector_heading(), (1.0, 0.0, 0.0))
        assert f.get_heading() == pytest.approx(90.0, abs=HEADING_TOL)

    @pytest.mark.parametrize("degrees", [0.0, 30.0, 90.0, 180.0, 270.0, 359.5])
    def test_set_heading_round_trips(self, degrees):
        # Frame::set_heading (acclient.c:357691) then Frame::get_heading (acclient.c:357409):
        # the facing is (sin d, cos d, 0), whose compass bearing is d.
        f = Frame()
        f.set_heading(degrees)
        assert_vec(f.get_vector_heading(), facing_for_compass(degrees))
        got = f.get_heading()
        assert 0.0 <= got < 360.0
        wrapped = (got - degrees + 180.0) % 360.0 - 180.0
        assert wrapped == pytest.approx(0.0, abs=HEADING_TOL)

    @pytest.mark.parametrize(
        "v",
        [
            (1.0, 0.0, 0.0),
            (0.0, -1.0, 0.0),
            (-1.0, 0.0, 0.0),
            (1.0, 1.0, 0.0),
            (3.0, -4.0, 0.0),
            (-2.0, 5.0, 0.0),
        ],
    )
    def test_set_vector_heading_faces_the_vector(self, v):
        # Frame::set_vector_heading (acclient.c:357667): a horizontal v gives pitch asin(0) = 0 and
        # yaw -bearing(v); the forward (local +y) ends parallel to v (the ALIGNPATH requirement).
        f = make((5, 6, 7), axis_angle((0.4, -0.3, 1.2)))  # any prior rotation is replaced
        f.set_vector_heading(Vector3(*v))
        n = math.hypot(v[0], v[1])
        assert_vec(f.get_vector_heading(), (v[0] / n, v[1] / n, 0.0))
        # And the body's up stays +z (no roll, no pitch): m[6:9] = (0, 0, 1).
        assert f.m[6:9] == pytest.approx([0.0, 0.0, 1.0], abs=TOL)

    def test_set_vector_heading_ignores_a_tiny_vector(self):
        # Frame::set_vector_heading (acclient.c:357667): if normalize_check_small(normalized)
        # (|v| < 0.00019999999) nothing happens.
        for v in (Vector3(1e-4, 0.0, 0.0), Vector3(0.0, 0.0, 0.0), Vector3(1e-4, -1e-4, 1e-4)):
            f = make((0, 0, 0), Q_CYCLE)
            before_m = f.m.copy()
            f.set_vector_heading(v)
            assert f.rotation == Q_CYCLE
            assert f.m == before_m

    def test_set_vector_heading_pitches_by_asin_z(self):
        # Frame::set_vector_heading (acclient.c:357667): x = asin(normalized.z).
        # v = (0, 1, 1) → n = (0, c, s): bearing 0 (yaw 0), pitch asin(s) = π/4;
        # euler_set_rotate(π/4, 0, 0) → q = (cos π/8, sin π/8, 0, 0); forward = (0, c, s).
        f = Frame()
        f.set_vector_heading(Vector3(0.0, 1.0, 1.0))
        assert_quat(f, (math.cos(math.pi / 8), math.sin(math.pi / 8), 0.0, 0.0))
        assert_vec(f.get_vector_heading(), (0.0, C45, S45))
        # v = (3, 0, 4) → n = (0.6, 0, 0.8): bearing 90, pitch asin(0.8). Pitch first about
        # global x (XYZs), then yaw -90° about z: forward = (0.6, 0, 0.8), still heading 90.
        f.set_vector_heading(Vector3(3.0, 0.0, 4.0))
        assert_vec(f.get_vector_heading(), (0.6, 0.0, 0.8))
        assert f.get_heading() == pytest.approx(90.0, abs=HEADING_TOL)

    def test_set_heading_reuses_the_facing_z_unnormalised(self):
        # Frame::set_heading (acclient.c:357691): direction = (sin d, cos d, m[5]), not rescaled,
        # so a pitched facing (0.6, 0, 0.8) turned to d = 0 becomes (0, 1, 0.8)/√1.64.
        f = Frame()
        f.set_vector_heading(Vector3(3.0, 0.0, 4.0))
        f.set_heading(0.0)
        r = math.sqrt(1.64)
        assert_vec(f.get_vector_heading(), (0.0, 1.0 / r, 0.8 / r))
        assert f.get_heading() == pytest.approx(0.0, abs=1e-12)

    def test_from_heading(self):
        # Frame::set_heading (acclient.c:357691) on a fresh frame at an origin: d = 180 faces -y.
        f = Frame.from_heading(Vector3(1, 2, 3), 180.0)
        assert_vec(f.origin, (1.0, 2.0, 3.0))
        assert_vec(f.get_vector_heading(), (0.0, -1.0, 0.0))

    @pytest.mark.parametrize(
        ("v", "expected"),
        [
            ((1.0, 0.0, 0.0), 90.0),
            ((0.0, 3.0, 0.0), 0.0),
            ((0.0, -2.0, 7.0), 180.0),
            ((-1.0, 0.0, 0.0), 270.0),
            ((1.0, 1.0, -9.0), 45.0),
        ],
    )
    def test_vector_get_heading(self, v, expected):
        # AC1Legacy::Vector3::get_heading @ 0x004575D0 (acclient.c:148166): normal = (x, y, 0),
        # normalize_check_small, then fmod(450 - atan2°, 360). (1,0,0): 450 - 0 = 90;
        # (0,1,0): 450 - 90 = 360 → 0; (0,-1,0): 450 + 90 = 540 → 180; (-1,0,0): 450 - 180 = 270;
        # (1,1,0)/√2: 450 - 45 = 405 → 45. z never matters.
        assert Vector3(*v).get_heading() == pytest.approx(expected, abs=1e-12)

    def test_vector_get_heading_of_a_vertical_vector_is_zero(self):
        # AC1Legacy::Vector3::get_heading (acclient.c:148166): (0, 0, 5) → normal (0, 0, 0),
        # normalize_check_small returns 1 → result = 0.0. Also horizontally tiny: (1e-4, 0, 5).
        assert Vector3(0.0, 0.0, 5.0).get_heading() == 0.0
        assert Vector3(1e-4, 0.0, 5.0).get_heading() == 0.0

    def test_velocity_heading_feeds_set_heading(self):
        # UpdateObjectInternal (acclient.c:322718), SLEDDING_PS branch:
        # set_heading(new_pos.frame, Vector3::get_heading(velocity)) must face along velocity.
        velocity = Vector3(-3.0, -4.0, 2.0)
        f = Frame()
        f.set_heading(velocity.get_heading())
        assert_vec(f.get_vector_heading(), (-0.6, -0.8, 0.0))


class TestPositionLocalToLocal:
    """Position::localtolocal @ 0x004527F0 (acclient.c:143794): other-local, global, block shift, local."""

    def test_a_point_in_the_next_landblock_east(self):
        from acphys.math.position import Position

        here = Position(0xA9B40001, Frame.from_heading(Vector3(180.0, 10.0, 0.0), 90.0))
        there = Position(0xAAB40001, Frame(Vector3(4.0, 10.0, 2.0)))
        # there's (1, 0, 0) is (5, 10, 2) in 0xAAB4, i.e. (197, 10, 2) seen from 0xA9B4: 17 m east of
        # here's origin. Facing east (compass 90), east is the body's local +y.
        local = here.localtolocal(there, Vector3(1.0, 0.0, 0.0))
        # The float32 matrix of "facing east" is east only to about 1e-7, over 17 m.
        assert local.x == pytest.approx(0.0, abs=4e-6)
        assert local.y == pytest.approx(17.0, abs=4e-6)
        assert local.z == pytest.approx(2.0, abs=4e-6)
