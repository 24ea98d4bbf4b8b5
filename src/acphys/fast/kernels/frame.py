"""Vectors, frames, positions and cell ids for the compiled engine: the reference's math under Numba.

Every function is a port of one reference function (named in its docstring) and gives the same
bits: it narrows to float32 exactly where the reference does (:func:`f32`, the kernels' spelling
of :func:`acphys.precision.f32` and of ``unpack3(pack3(...))``) and evaluates every double
expression with the reference's operands in the reference's order (see :mod:`acphys.precision`).
Never compile these with ``fastmath``.

Data, all plain tuples of float64 (no objects):

* a vector is ``(x, y, z)``; a quaternion ``(w, x, y, z)``; the cached matrix ``m`` (``m_fl2gv``)
  a 9-tuple in the reference's index order (``m[0:3]`` the local x axis, ``m[3:6]`` local y,
  ``m[6:9]`` local z). A frame is the three of them, ``origin, q, m``.
* Functions return new tuples. A port of a ``Frame`` method that writes its frame takes that
  frame first as ``origin, q, m`` (the "self" frame) and returns what the method leaves in it:
  ``(q, m)`` for the rotation-only methods, ``(origin, q, m)`` for the others. ``m`` comes back
  with ``q`` because ``Frame.set_rotate`` keeps the old quaternion *and the old matrix* when the
  new rotation is invalid (and re-caches only on success): the caller stores both, with no
  ``frame_cache`` of its own.
* Cell ids and lcoords are integers (taken as int64).
* Every float argument must be a float64 (Python floats, or read out of an array with
  ``np.float64``): Numba multiplies two float32 values in float32, where retail and the reference
  compute in double. Each function then stays in float64 throughout (:func:`f32` returns float64).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from acphys.constants import BLOCK_LENGTH, CELL_LENGTH, EPSILON, MAX_LCOORD
from acphys.math.cell_id import FIRST_ENV_CELL, LAST_LAND_CELL

#: ``Frame::IsValid``'s tolerance on the quaternion's squared norm (``acphys.math.frame``).
_NORM_TOLERANCE = EPSILON * 5.0
#: The degrees-radians factors of ``acphys.math.frame``.
_RAD_PER_DEG = math.pi / 180.0
_DEG_PER_RAD = 180.0 / math.pi
#: The identity rotation's cached matrix (row-major ``m``), as a new ``Frame`` holds it.
IDENTITY_M = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
_EPSILON2 = EPSILON * EPSILON


# -- float32 stores -------------------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def f32(x):
    """``x`` stored into a C ``float`` and read back (round to nearest even; overflow gives inf).

    Port of :func:`acphys.precision.f32`.
    """
    return np.float64(np.float32(x))


@njit(cache=True, inline="always", _nrt=False)
def f32x3(x, y, z):
    """Three values narrowed to float32 (a ``Vector3`` store).

    Port of :func:`acphys.precision.f32x3`.
    """
    return (f32(x), f32(y), f32(z))


# -- Vector3 --------------------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def v_add(a, b):
    """``a + b``, narrowed.

    Port of :meth:`acphys.math.vector.Vector3.__add__`.
    """
    return f32x3(a[0] + b[0], a[1] + b[1], a[2] + b[2])


@njit(cache=True, _nrt=False)
def v_sub(a, b):
    """``a - b``, narrowed.

    Port of :meth:`acphys.math.vector.Vector3.__sub__`.
    """
    return f32x3(a[0] - b[0], a[1] - b[1], a[2] - b[2])


@njit(cache=True, _nrt=False)
def v_scale(v, s):
    """``v * s``, narrowed.

    Port of :meth:`acphys.math.vector.Vector3.__mul__`.
    """
    return f32x3(v[0] * s, v[1] * s, v[2] * s)


@njit(cache=True, _nrt=False)
def v_div(v, s):
    """``v / s`` by the reciprocal: x scaled by the double reciprocal, y and z by its float32.

    Port of :meth:`acphys.math.vector.Vector3.__truediv__` (a zero ``s`` raises ZeroDivisionError, as there).
    Retail: Vector3::operator/ @ 0x00455DE0 (acclient.c:146865)
    """
    inv = 1.0 / f32(s)
    inv32 = f32(inv)
    return f32x3(inv * v[0], inv32 * v[1], inv32 * v[2])


@njit(cache=True, _nrt=False)
def v_neg(v):
    """``-v`` (exact).

    Port of :meth:`acphys.math.vector.Vector3.__neg__`.
    """
    return (-v[0], -v[1], -v[2])


@njit(cache=True, _nrt=False)
def v_dot(a, b):
    """The dot product, in double.

    Port of :meth:`acphys.math.vector.Vector3.dot`.
    """
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, _nrt=False)
def v_cross(a, b):
    """The cross product, narrowed.

    Port of :meth:`acphys.math.vector.Vector3.cross`.
    """
    return f32x3(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(cache=True, _nrt=False)
def v_length_squared(v):
    """The squared length, in double.

    Port of :meth:`acphys.math.vector.Vector3.length_squared`.
    """
    return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]


@njit(cache=True, _nrt=False)
def v_length(v):
    """The length, in double.

    Port of :meth:`acphys.math.vector.Vector3.length`.
    """
    return math.sqrt(v_length_squared(v))


@njit(cache=True, _nrt=False)
def v_is_zero(v):
    """Every axis strictly within EPSILON of zero.

    Port of :meth:`acphys.math.vector.Vector3.is_zero`.
    Retail: AC1Legacy::Vector3::is_zero @ 0x0050E7B0 (acclient.c:315576)
    """
    return abs(v[0]) < EPSILON and abs(v[1]) < EPSILON and abs(v[2]) < EPSILON


@njit(cache=True, _nrt=False)
def v_normalized(v):
    """``v`` scaled to unit length, with no small-length check (zero raises ZeroDivisionError, as there).

    Port of :meth:`acphys.math.vector.Vector3.normalized`.
    Retail: AC1Legacy::Vector3::normalize @ 0x00452400 (acclient.c:143600)
    """
    inv = 1.0 / math.sqrt(v_length_squared(v))
    return f32x3(inv * v[0], inv * v[1], inv * v[2])


@njit(cache=True, _nrt=False)
def v_normalize_check_small(v):
    """``(True, v)`` for a vector shorter than EPSILON (left as is), else ``(False, v normalised)``.

    Port of :meth:`acphys.math.vector.Vector3.normalize_check_small` (the vector it stores is returned).
    Retail: AC1Legacy::Vector3::normalize_check_small @ 0x00452460 (acclient.c:143621)
    """
    length = math.sqrt(v_length_squared(v))
    if length < EPSILON:
        return True, v
    inv = 1.0 / length
    return False, f32x3(inv * v[0], inv * v[1], inv * v[2])


@njit(cache=True, _nrt=False)
def compass_heading(x, y):
    """``fmod(450 - degrees(atan2(y, x)), 360)``: the compass bearing of (x, y).

    Port of :func:`acphys.math.vector.compass_heading` (``np.fmod``: Numba lacks ``math.fmod``;
    fmod is exact, so any correct one gives the same bits).
    """
    return np.fmod(450.0 - math.degrees(math.atan2(y, x)), 360.0)


@njit(cache=True, _nrt=False)
def v_get_heading(v):
    """The compass heading of the horizontal part of ``v``, in degrees (0 with no horizontal length).

    Port of :meth:`acphys.math.vector.Vector3.get_heading`.
    Retail: AC1Legacy::Vector3::get_heading @ 0x004575D0 (acclient.c:148166)
    """
    small, flat = v_normalize_check_small(f32x3(v[0], v[1], 0.0))
    if small:
        return 0.0
    return compass_heading(flat[0], flat[1])


# -- Frame: matrix and validity -------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def frame_cache(q):
    """The cached matrix ``m_fl2gv`` of the quaternion ``q``, narrowed.

    Port of :meth:`acphys.math.frame.Frame.cache`.
    Retail: Frame::cache @ 0x00534DF0 (acclient.c:356983)
    """
    qw, qx, qy, qz = q
    x2, y2, z2 = qx + qx, qy + qy, qz + qz
    wx, wy, wz = qw * x2, qw * y2, qw * z2
    xx, xy, xz = qx * x2, qx * y2, qx * z2
    yy, yz, zz = qy * y2, qy * z2, qz * z2
    return (
        f32(1.0 - yy - zz),
        f32(xy + wz),
        f32(xz - wy),
        f32(xy - wz),
        f32(1.0 - xx - zz),
        f32(yz + wx),
        f32(xz + wy),
        f32(yz - wx),
        f32(1.0 - xx - yy),
    )


@njit(cache=True, _nrt=False)
def frame_is_valid(origin, q):
    """No NaN anywhere and a quaternion norm within 5 × EPSILON of 1 (a ``float`` local, z first).

    Port of :meth:`acphys.math.frame.Frame.is_valid`.
    Retail: Frame::IsValid @ 0x00534ED0 (acclient.c:357024)
    """
    qw, qx, qy, qz = q
    if (
        math.isnan(origin[0])
        or math.isnan(origin[1])
        or math.isnan(origin[2])
        or math.isnan(qw)
        or math.isnan(qx)
        or math.isnan(qy)
        or math.isnan(qz)
    ):
        return False
    norm = f32(qz * qz + qy * qy + qx * qx + qw * qw)
    return not (math.isnan(norm) or abs(norm - 1.0) > _NORM_TOLERANCE)


@njit(cache=True, _nrt=False)
def frame_is_valid_except_for_heading(origin, q):
    """True when the origin is a number but some quaternion component is NaN.

    Port of :meth:`acphys.math.frame.Frame.is_valid_except_for_heading`.
    Retail: Frame::IsValidExceptForHeading @ 0x00534FE0 (acclient.c:357050)
    """
    origin_ok = not (math.isnan(origin[0]) or math.isnan(origin[1]) or math.isnan(origin[2]))
    return origin_ok and (math.isnan(q[0]) or math.isnan(q[1]) or math.isnan(q[2]) or math.isnan(q[3]))


@njit(cache=True, _nrt=False)
def frame_is_equal(o1, q1, o2, q2):
    """Origins within EPSILON on every axis (``<=``) and quaternions strictly within EPSILON.

    Port of :meth:`acphys.math.frame.Frame.is_equal`.
    Retail: Frame::is_equal @ 0x00424C30 (acclient.c:96699)
    """
    return (
        abs(o1[0] - o2[0]) <= EPSILON
        and abs(o1[1] - o2[1]) <= EPSILON
        and abs(o1[2] - o2[2]) <= EPSILON
        and abs(q1[0] - q2[0]) < EPSILON
        and abs(q1[1] - q2[1]) < EPSILON
        and abs(q1[2] - q2[2]) < EPSILON
        and abs(q1[3] - q2[3]) < EPSILON
    )


# -- Frame: rotation ------------------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def frame_set_rotate(origin, q, m, new_q):
    """Normalise and store ``new_q``; returns ``(q, m)`` to store: the new ones, or the old if invalid.

    ``new_q`` holds the four ``float`` arguments before their narrowing; validity is checked on the
    frame at ``origin`` with the new quaternion, and only a valid one re-caches the matrix.

    Port of :meth:`acphys.math.frame.Frame.set_rotate`.
    Retail: Frame::set_rotate @ 0x00535080 (acclient.c:357062)
    """
    qw, qx, qy, qz = f32(new_q[0]), f32(new_q[1]), f32(new_q[2]), f32(new_q[3])
    norm2 = qw * qw + qx * qx + qy * qy + qz * qz
    inv = 1.0 / math.sqrt(norm2) if norm2 > 0.0 else math.nan
    stored = (f32(qw * inv), f32(qx * inv), f32(qy * inv), f32(inv * qz))
    if frame_is_valid(origin, stored):
        return stored, frame_cache(stored)
    return q, m


@njit(cache=True, inline="always", _nrt=False)
def frame_grotate(origin, q, m, w):
    """Rotate by the global axis-angle vector ``w`` (radians); ``(q, m)`` unchanged when |w| < EPSILON.

    Port of :meth:`acphys.math.frame.Frame.grotate`.
    Retail: Frame::grotate @ 0x005357A0 (acclient.c:357421)
    """
    theta2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
    if theta2 < _EPSILON2:
        return q, m
    inv, s, c = _grotate_terms(theta2)
    return _grotate_by(origin, q, m, w, inv, s, c)


@njit(cache=True, inline="always", _nrt=False)
def grotate_remembered(memo, origin, q, m, w):
    """:func:`frame_grotate` with the terms of its angle kept in ``memo`` (a record's 4-array:
    the squared angle they are of, then :func:`_grotate_terms`) and reused while the squared angle
    repeats, as it does turn after turn of a steady motion: the square root, the division, the sine
    and the cosine are functions of it alone, so the rotation is the same to the bit. Not retail:
    a memo (a NaN angle never matches, an all-zero memo is no angle ``grotate`` takes)."""
    theta2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
    if theta2 < _EPSILON2:
        return q, m
    if theta2 != memo[0]:
        memo[0] = theta2
        memo[1], memo[2], memo[3] = _grotate_terms(theta2)
    return _grotate_by(origin, q, m, w, memo[1], memo[2], memo[3])


@njit(cache=True, inline="always", _nrt=False)
def _grotate_terms(theta2):
    """``Frame::grotate``'s terms of the angle whose square is ``theta2``: 1/angle (a ``float``),
    the sine of its half and the cosine of its half (a ``float``)."""
    theta = math.sqrt(theta2)
    return f32(1.0 / theta), math.sin(theta * 0.5), f32(math.cos(theta * 0.5))


@njit(cache=True, inline="always", _nrt=False)
def _grotate_by(origin, q, m, w, inv, s, c):
    """``Frame::grotate`` past its angle's terms: the rotation about ``w`` composed before ``q``."""
    f = f32(s * w[0] * inv)
    g = f32(inv * s * w[1])
    h = s * inv * w[2]
    qw, qx, qy, qz = q
    return frame_set_rotate(
        origin,
        q,
        m,
        (
            c * qw - f * qx - g * qy - h * qz,
            c * qx + g * qz + f * qw - h * qy,
            c * qy - f * qz + h * qx + g * qw,
            f * qy + c * qz - g * qx + h * qw,
        ),
    )


@njit(cache=True, inline="always", _nrt=False)
def frame_rotate(memo, origin, q, m, w):
    """Rotate by the local axis-angle vector ``w``: ``localtoglobalvec``, then ``grotate`` (its
    angle's terms kept in ``memo``: :func:`grotate_remembered`).

    Port of :meth:`acphys.math.frame.Frame.rotate`.
    Retail: Frame::rotate @ 0x004525B0 (acclient.c:143690)
    """
    return grotate_remembered(memo, origin, q, m, frame_localtoglobalvec(m, w))


@njit(cache=True, inline="always", _nrt=False)
def frame_interpolate_rotation(origin, q, m, start_q, end_q, t):
    """Slerp from ``start_q`` to ``end_q`` by ``t`` along the shorter arc, set on the frame ``origin, q, m``.

    At ``t == 1`` (a sweep's last step) the weights are taken as 0 and 1 without ``acos`` and
    ``sin``: retail's are ``+0`` (``sin(omega * 0)`` times a positive ``1 / sin(omega)``) and
    ``sin(omega) * (1 / sin(omega))``, within a double's ulp of 1 (or 1 exactly, from the linear
    blend it falls back to when that product passes 1 or the two are within EPSILON). Both
    quaternions hold float32 values (``set_rotate`` stored them), and ``set_rotate`` reads the
    blend through float32: an end component scaled by ``1 - 2**-53`` rounds back to itself there,
    a zero keeps its sign, and the zero start term adds nothing but its sign to a zero. So every
    branch stores what weights 0 and 1 store.

    Port of :meth:`acphys.math.frame.Frame.interpolate_rotation`.
    Retail: Frame::interpolate_rotation @ 0x00535390 (acclient.c:357257)
    """
    t = f32(t)
    sw, sx, sy, sz = start_q
    ew, ex, ey, ez = end_q
    cosom = sy * ey + sw * ew + sx * ex + sz * ez
    if cosom < 0.0:
        cosom = -cosom
        ew, ex, ey, ez = -ew, -ex, -ey, -ez
    if t == 1.0 or 1.0 - cosom <= EPSILON:
        scale0, scale1 = 1.0 - t, t
    else:
        omega = math.acos(cosom)  # in (0, pi/2]: sin(omega) > 0
        inv_sin = 1.0 / math.sin(omega)
        scale0 = inv_sin * math.sin(omega * (1.0 - t))
        scale1 = math.sin(t * omega) * inv_sin
        if not (0.0 <= scale0 <= 1.0 and 0.0 <= scale1 <= 1.0):
            scale0, scale1 = 1.0 - t, t
    return frame_set_rotate(
        origin,
        q,
        m,
        (
            scale0 * sw + scale1 * ew,
            sx * scale0 + ex * scale1,
            sy * scale0 + ey * scale1,
            ez * scale1 + sz * scale0,
        ),
    )


@njit(cache=True, _nrt=False)
def frame_interpolate_origin(start_origin, end_origin, t):
    """The blended origin ``(1 - t) · start + t · end`` (every product but ``t · end.x`` spilled).

    Port of :meth:`acphys.math.frame.Frame.interpolate_origin`.
    Retail: Frame::interpolate_origin @ 0x005352F0 (acclient.c:357228)
    """
    t = f32(t)
    u = 1.0 - t
    ty, tz = f32(t * end_origin[1]), f32(t * end_origin[2])
    ux, uy, uz = f32x3(u * start_origin[0], u * start_origin[1], u * start_origin[2])
    return f32x3(t * end_origin[0] + ux, uy + ty, uz + tz)


# -- Frame: composition ---------------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def frame_combine(origin, q, m, o1, q1, m1, o2, q2):
    """The frame ``origin, q, m`` set to ``f1 ∘ f2``; returns ``(origin, q, m)``.

    ``origin`` is overwritten unread; ``q, m`` are what stays if the product is invalid (pass f1's
    own for the in-place ``f1.combine(f1, f2)``).

    Port of :meth:`acphys.math.frame.Frame.combine`.
    Retail: Frame::combine @ 0x005122E0 (acclient.c:319448)
    """
    new_origin = f32x3(
        m1[6] * o2[2] + m1[0] * o2[0] + m1[3] * o2[1] + o1[0],
        m1[7] * o2[2] + m1[1] * o2[0] + m1[4] * o2[1] + o1[1],
        m1[8] * o2[2] + m1[2] * o2[0] + m1[5] * o2[1] + o1[2],
    )
    w1, x1, y1, z1 = q1
    w2, x2, y2, z2 = q2
    q, m = frame_set_rotate(
        new_origin,
        q,
        m,
        (
            w1 * w2 - x2 * x1 - y2 * y1 - z2 * z1,
            w1 * x2 + z2 * y1 + w2 * x1 - y2 * z1,
            y2 * w1 - z2 * x1 + z1 * x2 + y1 * w2,
            y2 * x1 + z2 * w1 - y1 * x2 + z1 * w2,
        ),
    )
    return new_origin, q, m


@njit(cache=True, _nrt=False)
def frame_subtract1(origin, q, m, o1, q1, o2, q2):
    """The frame ``origin, q, m`` set to X with ``X ∘ f2 = f1``; returns ``(origin, q, m)``.

    The rotation's validity is checked at the frame's own ``origin`` (it is overwritten after);
    pass f1's frame as ``origin, q, m`` for the in-place ``f1.subtract1(f1, f2)``.

    Port of :meth:`acphys.math.frame.Frame.subtract1`.
    Retail: Frame::subtract1 @ 0x00535520 (acclient.c:357321)
    """
    w1, x1, y1, z1 = q1
    w2, x2, y2, z2 = q2
    ox, oy, oz = -o2[0], -o2[1], -o2[2]
    q, m = frame_set_rotate(
        origin,
        q,
        m,
        (
            y1 * y2 + x2 * x1 + w1 * w2 + z2 * z1,
            x1 * w2 - x2 * w1 - y1 * z2 + z1 * y2,
            y1 * w2 - w1 * y2 + z2 * x1 - x2 * z1,
            z1 * w2 - (w1 * z2 + y2 * x1) + y1 * x2,
        ),
    )
    rx = f32(oz * m[6] + ox * m[0] + oy * m[3])
    ry = f32(oz * m[7] + ox * m[1] + oy * m[4])
    rz = oz * m[8] + ox * m[2] + oy * m[5]
    return f32x3(rx + o1[0], ry + o1[1], rz + o1[2]), q, m


@njit(cache=True, _nrt=False)
def frame_subtract2(origin, q, m, o1, q1, o2, q2, m2):
    """The frame ``origin, q, m`` set to X with ``f2 ∘ X = f1``; returns ``(origin, q, m)``.

    ``origin`` is overwritten unread (by f1's origin local to f2) before the rotation's check.

    Port of :meth:`acphys.math.frame.Frame.subtract2`.
    Retail: Frame::subtract2 @ 0x00535650 (acclient.c:357364)
    """
    local = frame_globaltolocal(o2, m2, o1)
    w1, x1, y1, z1 = q1
    w2, x2, y2, z2 = q2
    q, m = frame_set_rotate(
        local,
        q,
        m,
        (
            w1 * w2 + y2 * y1 + x1 * x2 + z1 * z2,
            x1 * w2 - w1 * x2 - y2 * z1 + y1 * z2,
            z1 * x2 + w2 * y1 - y2 * w1 - x1 * z2,
            z1 * w2 - y1 * x2 + x1 * y2 - w1 * z2,
        ),
    )
    return local, q, m


@njit(cache=True, _nrt=False)
def combine_anim_frame(origin, q, m, pos_origin, pos_q):
    """The frame ``origin, q, m`` composed with a position frame (``frame ∘ pos``): ``(origin, q, m)``.

    Port of :func:`acphys.motion.sequence.combine_anim_frame` (its own operand order).
    Retail: Frame::combine @ 0x00525180 (acclient.c:340419)
    """
    new_origin = f32x3(
        m[6] * pos_origin[2] + m[0] * pos_origin[0] + m[3] * pos_origin[1] + origin[0],
        m[7] * pos_origin[2] + m[1] * pos_origin[0] + m[4] * pos_origin[1] + origin[1],
        m[8] * pos_origin[2] + m[2] * pos_origin[0] + m[5] * pos_origin[1] + origin[2],
    )
    w1, x1, y1, z1 = q
    w2, x2, y2, z2 = pos_q
    q, m = frame_set_rotate(
        new_origin,
        q,
        m,
        (
            w1 * w2 - x1 * x2 - y2 * y1 - z2 * z1,
            x1 * w2 + w1 * x2 + z2 * y1 - y2 * z1,
            y2 * w1 - x1 * z2 + z1 * x2 + y1 * w2,
            x1 * y2 + z2 * w1 - y1 * x2 + z1 * w2,
        ),
    )
    return new_origin, q, m


@njit(cache=True, _nrt=False)
def combine_scaled(origin, q, m, o1, q1, m1, o2, q2, scale):
    """The frame ``origin, q, m`` set to ``f1 ∘ f2`` with f2's offset scaled; returns ``(origin, q, m)``.

    ``origin`` is overwritten unread; ``q, m`` stay if the product is invalid.

    Port of :func:`acphys.part_array.combine_scaled`.
    Retail: Frame::combine @ 0x00518FD0 (acclient.c:326562)
    """
    sx, sy, sz = o2[0] * scale, o2[1] * scale, o2[2] * scale
    new_origin = f32x3(
        sx * m1[0] + sz * m1[6] + sy * m1[3] + o1[0],
        sx * m1[1] + sz * m1[7] + sy * m1[4] + o1[1],
        sx * m1[2] + sz * m1[8] + sy * m1[5] + o1[2],
    )
    w1, x1, y1, z1 = q1
    w2, x2, y2, z2 = q2
    q, m = frame_set_rotate(
        new_origin,
        q,
        m,
        (
            w2 * w1 - x2 * x1 - y2 * y1 - z2 * z1,
            x2 * w1 + w2 * x1 + z2 * y1 - y2 * z1,
            w1 * y2 - x1 * z2 + x2 * z1 + w2 * y1,
            w1 * z2 + x1 * y2 - x2 * y1 + w2 * z1,
        ),
    )
    return new_origin, q, m


# -- Frame: points and vectors --------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def frame_localtoglobalvec(m, v):
    """A local vector rotated into global space (each row sums its z term first).

    Port of :meth:`acphys.math.frame.Frame.localtoglobalvec`.
    Retail: Frame::localtoglobalvec @ 0x004524F0 (acclient.c:143658)
    """
    return f32x3(
        m[6] * v[2] + m[0] * v[0] + m[3] * v[1],
        m[7] * v[2] + m[1] * v[0] + m[4] * v[1],
        m[8] * v[2] + m[2] * v[0] + m[5] * v[1],
    )


@njit(cache=True, _nrt=False)
def frame_globaltolocalvec(m, v):
    """A global vector rotated into local space (the transposed matrix).

    Port of :meth:`acphys.math.frame.Frame.globaltolocalvec`.
    Retail: Frame::globaltolocalvec @ 0x00452550 (acclient.c:143674)
    """
    return f32x3(
        m[2] * v[2] + m[0] * v[0] + m[1] * v[1],
        m[5] * v[2] + m[3] * v[0] + m[4] * v[1],
        m[8] * v[2] + m[6] * v[0] + m[7] * v[1],
    )


@njit(cache=True, _nrt=False)
def frame_localtoglobal(origin, m, p):
    """A local point taken to global space.

    Port of :meth:`acphys.math.frame.Frame.localtoglobal`.
    Retail: Frame::localtoglobal @ 0x00452620 (acclient.c:143701)
    """
    return f32x3(
        m[6] * p[2] + m[0] * p[0] + m[3] * p[1] + origin[0],
        m[7] * p[2] + m[1] * p[0] + m[4] * p[1] + origin[1],
        m[8] * p[2] + m[2] * p[0] + m[5] * p[1] + origin[2],
    )


@njit(cache=True, _nrt=False)
def frame_globaltolocal(origin, m, p):
    """A global point taken to local space (the offset spilled, but the z row uses the unspilled z).

    Port of :meth:`acphys.math.frame.Frame.globaltolocal`.
    Retail: Frame::globaltolocal @ 0x00452680 (acclient.c:143717)
    """
    dx, dy, dz32 = f32x3(p[0] - origin[0], p[1] - origin[1], p[2] - origin[2])
    dz = p[2] - origin[2]
    return f32x3(
        dz32 * m[2] + dx * m[0] + dy * m[1],
        dz32 * m[5] + dx * m[3] + dy * m[4],
        dz * m[8] + dx * m[6] + dy * m[7],
    )


# -- Frame: headings ------------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def frame_get_vector_heading(m):
    """The local +y axis (the facing) in global coordinates, a -0.0 turned to +0.0 as retail's.

    Port of :meth:`acphys.math.frame.Frame.get_vector_heading`.
    Retail: Frame::get_vector_heading @ 0x00535720 (acclient.c:357393)
    """
    return f32x3((m[6] + m[0]) * 0.0 + m[3], (m[7] + m[1]) * 0.0 + m[4], (m[8] + m[2]) * 0.0 + m[5])


@njit(cache=True, _nrt=False)
def frame_get_heading(m):
    """The compass heading of the facing, in degrees [0, 360).

    Port of :meth:`acphys.math.frame.Frame.get_heading`.
    Retail: Frame::get_heading @ 0x00535760 (acclient.c:357409)
    """
    return compass_heading((m[6] + m[0]) * 0.0 + m[3], (m[7] + m[1]) * 0.0 + m[4])


@njit(cache=True, _nrt=False)
def frame_euler_set_rotate(origin, q, m, x, y, z):
    """The rotation set from static-axis Euler angles x, then y, then z (radians); returns ``(q, m)``.

    Port of :meth:`acphys.math.frame.Frame.euler_set_rotate`.
    Retail: Frame::euler_set_rotate @ 0x00535BF0 (acclient.c:357588)
    """
    x, y, z = f32x3(x, y, z)
    half_z = f32(z * 0.5)
    ci, si = f32(math.cos(x * 0.5)), f32(math.sin(x * 0.5))
    cj, sj = f32(math.cos(y * 0.5)), math.sin(y * 0.5)
    ch, sh = f32(math.cos(half_z)), math.sin(half_z)
    cc, cs, sc, ss = f32(ch * ci), f32(ci * sh), f32(si * ch), f32(sh * si)
    return frame_set_rotate(
        origin,
        q,
        m,
        (
            ss * sj + cc * cj,
            sc * cj - cs * sj,
            cc * sj + ss * cj,
            cs * cj - sc * sj,
        ),
    )


@njit(cache=True, _nrt=False)
def frame_set_vector_heading(origin, q, m, heading):
    """Face along ``heading`` (yaw from its bearing, pitch from its z); ``(q, m)`` kept if it is tiny.

    Port of :meth:`acphys.math.frame.Frame.set_vector_heading`.
    Retail: Frame::set_vector_heading @ 0x00535DB0 (acclient.c:357667)
    """
    small, normal = v_normalize_check_small(heading)
    if small:
        return q, m
    yaw = -compass_heading(normal[0], normal[1]) * _RAD_PER_DEG
    pitch = math.asin(normal[2]) * _DEG_PER_RAD * _RAD_PER_DEG
    return frame_euler_set_rotate(origin, q, m, pitch, 0.0, yaw)


@njit(cache=True, _nrt=False)
def frame_set_heading(origin, q, m, degrees):
    """Face compass ``degrees``, keeping the facing's z as the pitch input; returns ``(q, m)``.

    Port of :meth:`acphys.math.frame.Frame.set_heading`.
    Retail: Frame::set_heading @ 0x00535E40 (acclient.c:357691)
    """
    rad = f32(degrees) * _RAD_PER_DEG
    heading = f32x3(math.sin(rad), math.cos(rad), (m[8] + m[2]) * 0.0 + m[5])
    return frame_set_vector_heading(origin, q, m, heading)


# -- cell ids -------------------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def valid_cell_index(cell_id):
    """The low word names a land cell (1..0x40), an env cell (0x100..0xFFFD) or the block (0xFFFF).

    Port of :func:`acphys.math.cell_id._valid_cell_index`.
    """
    low = np.int64(cell_id) & 0xFFFF
    return 1 <= low <= LAST_LAND_CELL or FIRST_ENV_CELL <= low <= 0xFFFD or low == 0xFFFF


@njit(cache=True, _nrt=False)
def gid_to_lcoord(cell_id):
    """``(True, x, y)``: the lcoord of an outdoor cell id, or ``(False, 0, 0)`` for no valid land cell.

    Port of :func:`acphys.math.cell_id.gid_to_lcoord`.
    Retail: LandDefs::gid_to_lcoord @ 0x00497A90 (acclient.c:209520)
    """
    c = np.int64(cell_id)
    low = c & 0xFFFF
    if not 1 <= low <= LAST_LAND_CELL:
        return False, 0, 0
    block_x = (c >> 21) & 0x7F8
    if block_x >= MAX_LCOORD or ((c >> 13) & 0x7F8) >= MAX_LCOORD:
        return False, 0, 0
    index = low - 1
    x = block_x + (index >> 3)
    y = 8 * ((c >> 16) & 0xFF) + (index & 7)
    if 0 <= x < MAX_LCOORD and 0 <= y < MAX_LCOORD:
        return True, x, y
    return False, 0, 0


@njit(cache=True, _nrt=False)
def lcoord_to_gid(x, y):
    """The outdoor cell id of lcoord (x, y), or 0 outside the world.

    Port of :func:`acphys.math.cell_id.lcoord_to_gid`.
    Retail: LandDefs::lcoord_to_gid @ 0x004A19A0 (acclient.c:218181)
    """
    x = np.int64(x)
    y = np.int64(y)
    if x < 0 or y < 0 or x >= MAX_LCOORD or y >= MAX_LCOORD:
        return np.int64(0)
    return (((y >> 3) | 32 * (x & ~7)) << 16) | ((y & 7) + 8 * (x & 7) + 1)


@njit(cache=True, _nrt=False)
def _floor_checked(x):
    """``math.floor(x)`` as a float, raising as Python's does for NaN and the infinities."""
    if math.isnan(x):
        raise ValueError("cannot convert float NaN to integer")
    if math.isinf(x):
        raise OverflowError("cannot convert float infinity to integer")
    return np.floor(x)


@njit(cache=True, inline="always", _nrt=False)
def adjust_to_outside_lcoord(cell_id, loc):
    """``(ok, lx, ly, loc)``: the lcoord of the land cell under the block-local ``loc``; ``loc`` rewritten.

    ``loc`` comes back as the reference leaves it: untouched for a bad cell index; |x|, |y| <
    EPSILON snapped to +0 when off the world (``ok`` False, lcoord 0, 0); on success x and y made
    local to the new cell's landblock (float32 stores), z untouched. A NaN or infinite x or y
    raises ValueError or OverflowError, as the reference's ``math.floor`` does.

    Port of :func:`acphys.math.cell_id.adjust_to_outside_lcoord`.
    Retail: LandDefs::adjust_to_outside @ 0x005A9BC0 (acclient.c:467433)
    """
    c = np.int64(cell_id)
    if not valid_cell_index(c):
        return False, np.int64(0), np.int64(0), loc
    x, y, z = loc
    if abs(x) < EPSILON:
        x = 0.0
    if abs(y) < EPSILON:
        y = 0.0
    snapped = (x, y, z)
    # float floors: equal to the reference's integer sums wherever they can be in range
    lx = np.float64((c >> 21) & 0x7F8) + _floor_checked(x / CELL_LENGTH)
    ly = np.float64(8 * ((c >> 16) & 0xFF)) + _floor_checked(y / CELL_LENGTH)
    if not (0.0 <= lx < MAX_LCOORD and 0.0 <= ly < MAX_LCOORD):
        return False, np.int64(0), np.int64(0), snapped
    new_x = f32(x - np.floor(x / BLOCK_LENGTH) * BLOCK_LENGTH)
    new_y = f32(y - np.floor(y / BLOCK_LENGTH) * BLOCK_LENGTH)
    return True, np.int64(lx), np.int64(ly), (new_x, new_y, z)


@njit(cache=True, _nrt=False)
def adjust_to_outside(cell_id, loc):
    """``(cell_id, loc)``: the outdoor cell holding block-local ``loc`` (0 off the world); ``loc`` rewritten.

    Port of :func:`acphys.math.cell_id.adjust_to_outside`.
    Retail: LandDefs::adjust_to_outside @ 0x005A9BC0 (acclient.c:467433)
    """
    ok, lx, ly, loc = adjust_to_outside_lcoord(cell_id, loc)
    if not ok:
        return np.int64(0), loc
    return lcoord_to_gid(lx, ly), loc


@njit(cache=True, inline="always", _nrt=False)
def get_block_offset(cell_from, cell_to):
    """The offset from ``cell_from``'s landblock origin to ``cell_to``'s: Δblock × 192 m, z = 0.

    The reference raises for a ``cell_to`` of 0 in another block; this raises nothing (the
    kernels never pass 0 as ``cell_to``) and measures to block (0, 0).

    Port of :func:`acphys.math.cell_id.get_block_offset`.
    Retail: LandDefs::get_block_offset @ 0x0043E630 (acclient.c:123109)
    """
    cf = np.int64(cell_from)
    ct = np.int64(cell_to)
    if (cf >> 16) == (ct >> 16):
        return (0.0, 0.0, 0.0)
    fx = np.int64(0)
    fy = np.int64(0)
    if cf != 0:
        fx = (cf >> 21) & 0x7F8
        fy = 8 * ((cf >> 16) & 0xFF)
    tx = (ct >> 21) & 0x7F8
    ty = 8 * ((ct >> 16) & 0xFF)
    return f32x3((tx - fx) * CELL_LENGTH, (ty - fy) * CELL_LENGTH, 0.0)


# -- Position -------------------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def position_get_offset(cell_a, origin_a, cell_b, origin_b):
    """The vector from position a's origin to position b's, across landblocks.

    Port of :meth:`acphys.math.position.Position.get_offset`.
    Retail: Position::get_offset @ 0x00509F60 (acclient.c:311690)
    """
    block = get_block_offset(cell_a, cell_b)
    y, z = f32(block[1] + origin_b[1]), f32(block[2] + origin_b[2])
    return f32x3(block[0] + origin_b[0] - origin_a[0], y - origin_a[1], z - origin_a[2])


@njit(cache=True, _nrt=False)
def position_localtoglobal_offset(cell_a, origin_a, cell_b, origin_b, m_b, v):
    """The vector from position a's origin to the point ``v`` local to position b's frame.

    Port of :meth:`acphys.math.position.Position.localtoglobal_offset`.
    Retail: Position::get_offset @ 0x0050D920 (acclient.c:314676)
    """
    block = get_block_offset(cell_a, cell_b)
    gx = m_b[3] * v[1] + m_b[0] * v[0] + m_b[6] * v[2] + origin_b[0]
    gy = m_b[4] * v[1] + m_b[1] * v[0] + m_b[7] * v[2] + origin_b[1]
    gz = f32(m_b[5] * v[1] + m_b[2] * v[0] + m_b[8] * v[2] + origin_b[2])
    x, z = f32(block[0] + gx), f32(block[2] + gz)
    return f32x3(x - origin_a[0], block[1] + gy - origin_a[1], z - origin_a[2])


@njit(cache=True, _nrt=False)
def position_localtoglobal(cell_a, cell_b, origin_b, m_b, v):
    """The point ``v`` local to position b's frame, in position a's landblock.

    Port of :meth:`acphys.math.position.Position.localtoglobal`.
    Retail: Position::localtoglobal @ 0x00456180 (acclient.c:147140)
    """
    gx, gy, gz = f32x3(
        m_b[3] * v[1] + m_b[0] * v[0] + m_b[6] * v[2] + origin_b[0],
        m_b[4] * v[1] + m_b[1] * v[0] + m_b[7] * v[2] + origin_b[1],
        m_b[5] * v[1] + m_b[2] * v[0] + m_b[8] * v[2] + origin_b[2],
    )
    block = get_block_offset(cell_a, cell_b)
    return f32x3(block[0] + gx, block[1] + gy, block[2] + gz)


@njit(cache=True, _nrt=False)
def position_localtoglobalvec(m, v):
    """``v`` rotated by the position's frame, each row summing its y term first.

    Port of :meth:`acphys.math.position.Position.localtoglobalvec`.
    Retail: Position::localtoglobalvec @ 0x00456220 (acclient.c:147164)
    """
    return f32x3(
        m[3] * v[1] + m[0] * v[0] + m[6] * v[2],
        m[4] * v[1] + m[1] * v[0] + m[7] * v[2],
        m[5] * v[1] + m[2] * v[0] + m[8] * v[2],
    )


@njit(cache=True, _nrt=False)
def position_globaltolocalvec(m, v):
    """A global vector rotated into the position's frame, each row summing its y term first.

    Port of :meth:`acphys.math.position.Position.globaltolocalvec`.
    Retail: Position::globaltolocalvec @ 0x0050C420 (acclient.c:313494)
    """
    return f32x3(
        m[1] * v[1] + m[0] * v[0] + m[2] * v[2],
        m[4] * v[1] + m[3] * v[0] + m[5] * v[2],
        m[7] * v[1] + m[6] * v[0] + m[8] * v[2],
    )


@njit(cache=True, _nrt=False)
def position_localtolocal(cell_a, origin_a, m_a, cell_b, origin_b, m_b, v):
    """The point ``v`` local to position b's frame, expressed in position a's frame (across blocks).

    Port of :meth:`acphys.math.position.Position.localtolocal`.
    Retail: Position::localtolocal @ 0x004527F0 (acclient.c:143794)
    """
    return frame_globaltolocal(origin_a, m_a, position_localtoglobal(cell_a, cell_b, origin_b, m_b, v))
