"""``Frame``: an origin, a unit quaternion and its cached rotation matrix.

Conventions, all retail's:

* The quaternion is ``(qw, qx, qy, qz)``.
* ``m`` is ``m_fl2gv``, the local-to-global rotation stored column by column:
  ``m[0:3]`` is the local x axis in global coordinates, ``m[3:6]`` the local
  y axis (the body's forward), ``m[6:9]`` the local z axis.
* The matrix is refreshed only by :meth:`Frame.cache` (which
  :meth:`Frame.set_rotate` calls). Code that writes the quaternion directly
  must cache before anything reads the matrix, exactly as in retail.
* Headings are compass degrees: 0 faces +y (north), 90 faces +x (east).
* Every stored number is a float32 (retail's fields are ``float``): the origin
  is a :class:`Vector3`, ``set_rotate`` narrows its arguments and the
  quaternion it stores, ``cache`` narrows the matrix. The methods narrow
  their locals where the decompilation stores a ``float`` (see
  :mod:`acphys.precision`).
* The decompiler prints double literals with 16 significant digits:
  ``0.0174532925199433`` is π/180 and ``57.29577951308232`` is 180/π.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from acphys.constants import EPSILON
from acphys.math.vector import Vector3, compass_heading, float_array, zero_vector
from acphys.precision import f32, pack3, pack4, pack9, unpack3, unpack4, unpack9

if TYPE_CHECKING:
    import numpy as np

_new = object.__new__
_isnan = math.isnan
#: ``Frame::IsValid``'s tolerance on the quaternion's squared norm.
_NORM_TOLERANCE = EPSILON * 5.0
#: The degrees-radians factors retail multiplies by (``math.radians`` and ``math.degrees`` use the same).
_RAD_PER_DEG = math.pi / 180.0
_DEG_PER_RAD = 180.0 / math.pi
#: ``m`` for the identity quaternion (1, +0, +0, +0), as :meth:`Frame.cache` computes it.
_IDENTITY_M = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
#: The default quaternion components, as objects: ``Frame()`` recognises an untouched
#: default rotation by identity (``is``), so a passed-in -0.0 still goes through cache().
_ONE = 1.0
_ZERO = 0.0


class Frame:
    """Retail ``Frame`` (acclient.h:30647)."""

    __slots__ = ("m", "origin", "qw", "qx", "qy", "qz")

    def __init__(
        self,
        origin: Vector3 | None = None,
        qw: float = _ONE,
        qx: float = _ZERO,
        qy: float = _ZERO,
        qz: float = _ZERO,
    ) -> None:
        self.origin = origin.copy() if origin is not None else zero_vector()
        if qw is _ONE and qx is _ZERO and qy is _ZERO and qz is _ZERO:
            # the default rotation: skip the float() calls and cache()'s arithmetic
            self.qw = 1.0
            self.qx = self.qy = self.qz = 0.0
            self.m = _IDENTITY_M.copy()  # what cache() gives for (1, +0, +0, +0)
        else:
            self.qw, self.qx, self.qy, self.qz = unpack4(pack4(qw, qx, qy, qz))
            self.m = [0.0] * 9
            self.cache()

    @classmethod
    def from_heading(cls, origin: Vector3, heading: float) -> Frame:
        """A frame at ``origin`` facing compass ``heading`` degrees."""
        frame = cls(origin)
        frame.set_heading(heading)
        return frame

    def copy(self) -> Frame:
        """An independent copy, cached matrix included (retail ``Frame::operator=``)."""
        other = _new(Frame)
        other.origin = self.origin.copy()
        other.qw = self.qw
        other.qx = self.qx
        other.qy = self.qy
        other.qz = self.qz
        other.m = self.m.copy()
        return other

    def assign(self, other: Frame) -> None:
        """Copy ``other`` into this frame, cached matrix included (``Frame::operator=``)."""
        self.origin.set(other.origin)
        self.qw, self.qx, self.qy, self.qz = other.qw, other.qx, other.qy, other.qz
        self.m[:] = other.m

    @property
    def rotation(self) -> tuple[float, float, float, float]:
        """The quaternion as ``(w, x, y, z)``."""
        return (self.qw, self.qx, self.qy, self.qz)

    def __repr__(self) -> str:
        return f"Frame({self.origin!r}, q=({self.qw}, {self.qx}, {self.qy}, {self.qz}))"

    # -- NumPy ------------------------------------------------------------------------------

    def to_numpy(self) -> np.ndarray:
        """``[x, y, z, qw, qx, qy, qz]``: the origin, then the quaternion (w first, as traces
        write it), a new float64 array of shape (7,). ``numpy.asarray(frame)`` gives the same."""
        o = self.origin
        return float_array((o.x, o.y, o.z, self.qw, self.qx, self.qy, self.qz))

    def __array__(self, dtype: Any = None, copy: bool | None = None) -> np.ndarray:
        """``numpy.asarray(frame)``: :meth:`to_numpy`, as ``dtype`` when one is given."""
        o = self.origin
        return float_array((o.x, o.y, o.z, self.qw, self.qx, self.qy, self.qz), dtype, copy, "Frame")

    def to_matrix(self) -> np.ndarray:
        """The 4x4 homogeneous transform from this frame to its parent's (for a body's frame: from
        body-local to landblock-local coordinates), built from the cached rotation ``m``: column j
        of the rotation is local axis j in the parent frame, the last column the origin."""
        import numpy as np

        matrix = np.eye(4)
        matrix[:3, :3] = np.array(self.m, dtype=np.float64).reshape(3, 3).T
        matrix[:3, 3] = (self.origin.x, self.origin.y, self.origin.z)
        return matrix

    # -- the cached matrix ----------------------------------------------------------------

    def cache(self) -> None:
        """Recompute ``m`` (``m_fl2gv``) from the quaternion.

        Retail: Frame::cache @ 0x00534DF0 (acclient.c:356983)
        """
        qw, qx, qy, qz = self.qw, self.qx, self.qy, self.qz
        x2, y2, z2 = qx + qx, qy + qy, qz + qz
        wx, wy, wz = qw * x2, qw * y2, qw * z2
        xx, xy, xz = qx * x2, qx * y2, qx * z2
        yy, yz, zz = qy * y2, qy * z2, qz * z2
        self.m[:] = unpack9(
            pack9(
                1.0 - yy - zz,
                xy + wz,
                xz - wy,
                xy - wz,
                1.0 - xx - zz,
                yz + wx,
                xz + wy,
                yz - wx,
                1.0 - xx - yy,
            )
        )

    # -- validity --------------------------------------------------------------------------

    def is_valid(self) -> bool:
        """No NaN anywhere and a quaternion norm within 5 × EPSILON of 1.

        The squared norm is a ``float`` local, summed z first.

        Retail: Frame::IsValid @ 0x00534ED0 (acclient.c:357024)
        """
        o = self.origin
        qw, qx, qy, qz = self.qw, self.qx, self.qy, self.qz
        if _isnan(o.x) or _isnan(o.y) or _isnan(o.z) or _isnan(qw) or _isnan(qx) or _isnan(qy) or _isnan(qz):
            return False
        norm = f32(qz * qz + qy * qy + qx * qx + qw * qw)
        return not (_isnan(norm) or abs(norm - 1.0) > _NORM_TOLERANCE)

    def is_equal(self, other: Frame) -> bool:
        """Origins within EPSILON on every axis (``<=``) and quaternions strictly within EPSILON
        (``Frame::is_quaternion_equal`` @ 0x00424C70, acclient.c:96712).

        Retail: Frame::is_equal @ 0x00424C30 (acclient.c:96699)
        """
        return (
            abs(self.origin.x - other.origin.x) <= EPSILON
            and abs(self.origin.y - other.origin.y) <= EPSILON
            and abs(self.origin.z - other.origin.z) <= EPSILON
            and abs(self.qw - other.qw) < EPSILON
            and abs(self.qx - other.qx) < EPSILON
            and abs(self.qy - other.qy) < EPSILON
            and abs(self.qz - other.qz) < EPSILON
        )

    def is_valid_except_for_heading(self) -> bool:
        """True when the origin is a number but some quaternion component is NaN.

        The name is retail's: the frame is sound "except for its heading".

        Retail: Frame::IsValidExceptForHeading @ 0x00534FE0 (acclient.c:357050)
        """
        origin_ok = not any(math.isnan(v) for v in (self.origin.x, self.origin.y, self.origin.z))
        return origin_ok and any(math.isnan(v) for v in (self.qw, self.qx, self.qy, self.qz))

    # -- rotation --------------------------------------------------------------------------

    def set_rotate(self, qw: float, qx: float, qy: float, qz: float) -> None:
        """Normalise and store a quaternion; if the frame is then invalid, restore the old one.

        The arguments are ``float`` parameters (narrowed at the call), the
        reciprocal norm stays double, the stored quaternion is narrowed. On
        success the matrix is re-cached; on failure neither the quaternion nor
        the matrix changes (note that a NaN origin also makes the frame
        invalid, so a frame with a NaN origin keeps its rotation).

        Retail: Frame::set_rotate @ 0x00535080 (acclient.c:357062)
        """
        old = (self.qw, self.qx, self.qy, self.qz)
        qw, qx, qy, qz = unpack4(pack4(qw, qx, qy, qz))
        norm2 = qw * qw + qx * qx + qy * qy + qz * qz
        inv = 1.0 / math.sqrt(norm2) if norm2 > 0.0 else math.nan
        self.qw, self.qx, self.qy, self.qz = unpack4(pack4(qw * inv, qx * inv, qy * inv, inv * qz))
        if self.is_valid():
            self.cache()
        else:
            self.qw, self.qx, self.qy, self.qz = old

    def grotate(self, w: Vector3) -> None:
        """Rotate by the global axis-angle vector ``w`` (radians); ignored when |w| < EPSILON.

        The rotation ``(cos θ/2, sin θ/2 · ŵ)`` multiplies the quaternion from the left. The
        reciprocal angle, the cosine and the first two axis terms are ``float`` locals; the
        sine and the third term stay double (acclient.c:357433-357440).

        Retail: Frame::grotate @ 0x005357A0 (acclient.c:357421)
        """
        theta2 = w.x * w.x + w.y * w.y + w.z * w.z
        if theta2 < EPSILON * EPSILON:
            return
        theta = math.sqrt(theta2)
        inv = f32(1.0 / theta)
        s = math.sin(theta * 0.5)
        c = f32(math.cos(theta * 0.5))
        f = f32(s * w.x * inv)
        g = f32(inv * s * w.y)
        h = s * inv * w.z
        qw, qx, qy, qz = self.qw, self.qx, self.qy, self.qz
        self.set_rotate(
            c * qw - f * qx - g * qy - h * qz,
            c * qx + g * qz + f * qw - h * qy,
            c * qy - f * qz + h * qx + g * qw,
            f * qy + c * qz - g * qx + h * qw,
        )

    def rotate(self, w: Vector3) -> None:
        """Rotate by the local axis-angle vector ``w``: convert it to global, then grotate.

        Retail: Frame::rotate @ 0x004525B0 (acclient.c:143690)
        """
        self.grotate(self.localtoglobalvec(w))

    def interpolate_rotation(self, start: Frame, end: Frame, t: float) -> None:
        """Slerp from ``start`` to ``end`` by ``t`` along the shorter arc.

        Falls back to a linear blend when the rotations are within EPSILON
        of each other or when a slerp weight leaves [0, 1]. ``t`` is a ``float``
        parameter; the cosine and the weights stay double.

        Retail: Frame::interpolate_rotation @ 0x00535390 (acclient.c:357257)
        """
        t = f32(t)
        cosom = start.qy * end.qy + start.qw * end.qw + start.qx * end.qx + start.qz * end.qz
        to = (end.qw, end.qx, end.qy, end.qz)
        if cosom < 0.0:
            cosom = -cosom
            to = (-end.qw, -end.qx, -end.qy, -end.qz)
        if 1.0 - cosom <= EPSILON:
            scale0, scale1 = 1.0 - t, t
        else:
            omega = math.acos(cosom)
            inv_sin = 1.0 / math.sin(omega)
            scale0 = inv_sin * math.sin(omega * (1.0 - t))
            scale1 = math.sin(t * omega) * inv_sin
            if not (0.0 <= scale0 <= 1.0 and 0.0 <= scale1 <= 1.0):
                scale0, scale1 = 1.0 - t, t
        self.set_rotate(
            scale0 * start.qw + scale1 * to[0],
            start.qx * scale0 + to[1] * scale1,
            start.qy * scale0 + to[2] * scale1,
            to[3] * scale1 + start.qz * scale0,
        )

    def interpolate_origin(self, start: Frame, end: Frame, t: float) -> None:
        """Blend the origins: ``(1 - t) · start + t · end``.

        ``t`` is a ``float`` parameter; every product but ``t · end.x`` is spilled to a
        ``float`` (acclient.c:357242-357255).

        Retail: Frame::interpolate_origin @ 0x005352F0 (acclient.c:357228)
        """
        t = f32(t)
        u = 1.0 - t
        ty, tz = f32(t * end.origin.y), f32(t * end.origin.z)
        ux, uy, uz = unpack3(pack3(u * start.origin.x, u * start.origin.y, u * start.origin.z))
        o = self.origin
        o.x, o.y, o.z = unpack3(pack3(t * end.origin.x + ux, uy + ty, uz + tz))

    # -- composition -----------------------------------------------------------------------

    def combine(self, f1: Frame, f2: Frame) -> None:
        """Set this frame to ``f1 ∘ f2``: f2 expressed in f1's space, taken to global.

        ``origin = f1.origin + f1.m · f2.origin``; ``q = q1 · q2``. Reads f1's
        cached matrix, so f1 must be cached. ``self`` may be ``f1`` or ``f2``.

        Retail: Frame::combine @ 0x005122E0 (acclient.c:319448)
        """
        m = f1.m
        o = f2.origin
        x = m[6] * o.z + m[0] * o.x + m[3] * o.y + f1.origin.x
        y = m[7] * o.z + m[1] * o.x + m[4] * o.y + f1.origin.y
        z = m[8] * o.z + m[2] * o.x + m[5] * o.y + f1.origin.z
        w1, x1, y1, z1 = f1.qw, f1.qx, f1.qy, f1.qz
        w2, x2, y2, z2 = f2.qw, f2.qx, f2.qy, f2.qz
        so = self.origin
        so.x, so.y, so.z = unpack3(pack3(x, y, z))
        self.set_rotate(
            w1 * w2 - x2 * x1 - y2 * y1 - z2 * z1,
            w1 * x2 + z2 * y1 + w2 * x1 - y2 * z1,
            y2 * w1 - z2 * x1 + z1 * x2 + y1 * w2,
            y2 * x1 + z2 * w1 - y1 * x2 + z1 * w2,
        )

    def subtract1(self, f1: Frame, f2: Frame) -> None:
        """Set this frame to X with ``X ∘ f2 = f1`` (undo a local offset f2 from f1).

        ``q = q1 · conj(q2)``, then ``origin = f1.origin - m_X · f2.origin``; the rotated
        offset's x and y are spilled to ``float`` before f1's origin is added, its z is not
        (acclient.c:357345-357357).

        Retail: Frame::subtract1 @ 0x00535520 (acclient.c:357321)
        """
        w1, x1, y1, z1 = f1.qw, f1.qx, f1.qy, f1.qz
        w2, x2, y2, z2 = f2.qw, f2.qx, f2.qy, f2.qz
        ox, oy, oz = -f2.origin.x, -f2.origin.y, -f2.origin.z
        base = f1.origin.copy()
        self.set_rotate(
            y1 * y2 + x2 * x1 + w1 * w2 + z2 * z1,
            x1 * w2 - x2 * w1 - y1 * z2 + z1 * y2,
            y1 * w2 - w1 * y2 + z2 * x1 - x2 * z1,
            z1 * w2 - (w1 * z2 + y2 * x1) + y1 * x2,
        )
        m = self.m
        rx = f32(oz * m[6] + ox * m[0] + oy * m[3])
        ry = f32(oz * m[7] + ox * m[1] + oy * m[4])
        rz = oz * m[8] + ox * m[2] + oy * m[5]
        o = self.origin
        o.x, o.y, o.z = unpack3(pack3(rx + base.x, ry + base.y, rz + base.z))

    def subtract2(self, f1: Frame, f2: Frame) -> None:
        """Set this frame to X with ``f2 ∘ X = f1`` (f1 expressed in f2's space).

        ``origin = f2.globaltolocal(f1.origin)``; ``q = conj(q2) · q1``.

        Retail: Frame::subtract2 @ 0x00535650 (acclient.c:357364)
        """
        local = f2.globaltolocal(f1.origin)
        w1, x1, y1, z1 = f1.qw, f1.qx, f1.qy, f1.qz
        w2, x2, y2, z2 = f2.qw, f2.qx, f2.qy, f2.qz
        self.origin.set(local)
        self.set_rotate(
            w1 * w2 + y2 * y1 + x1 * x2 + z1 * z2,
            x1 * w2 - w1 * x2 - y2 * z1 + y1 * z2,
            z1 * x2 + w2 * y1 - y2 * w1 - x1 * z2,
            z1 * w2 - y1 * x2 + x1 * y2 - w1 * z2,
        )

    # -- points and vectors ----------------------------------------------------------------

    def localtoglobalvec(self, v: Vector3) -> Vector3:
        """Rotate a local vector into global space.

        Retail: Frame::localtoglobalvec @ 0x004524F0 (acclient.c:143658)
        """
        m = self.m
        r = _new(Vector3)
        r.x, r.y, r.z = unpack3(
            pack3(
                m[6] * v.z + m[0] * v.x + m[3] * v.y,
                m[7] * v.z + m[1] * v.x + m[4] * v.y,
                m[8] * v.z + m[2] * v.x + m[5] * v.y,
            )
        )
        return r

    def globaltolocalvec(self, v: Vector3) -> Vector3:
        """Rotate a global vector into local space (the transposed matrix).

        Retail: Frame::globaltolocalvec @ 0x00452550 (acclient.c:143674)
        """
        m = self.m
        return Vector3(
            m[2] * v.z + m[0] * v.x + m[1] * v.y,
            m[5] * v.z + m[3] * v.x + m[4] * v.y,
            m[8] * v.z + m[6] * v.x + m[7] * v.y,
        )

    def localtoglobal(self, p: Vector3) -> Vector3:
        """Take a local point to global space.

        Retail: Frame::localtoglobal @ 0x00452620 (acclient.c:143701)
        """
        # localtoglobalvec(p) + origin in one construction, the same sums in the same order
        m = self.m
        o = self.origin
        v = _new(Vector3)
        v.x, v.y, v.z = unpack3(
            pack3(
                m[6] * p.z + m[0] * p.x + m[3] * p.y + o.x,
                m[7] * p.z + m[1] * p.x + m[4] * p.y + o.y,
                m[8] * p.z + m[2] * p.x + m[5] * p.y + o.z,
            )
        )
        return v

    def globaltolocal(self, p: Vector3) -> Vector3:
        """Take a global point to local space.

        The offset from the origin is spilled to ``float``, except that the local z
        row uses the unspilled z difference (acclient.c:143727-143733).

        Retail: Frame::globaltolocal @ 0x00452680 (acclient.c:143717)
        """
        m = self.m
        o = self.origin
        dx, dy, dz32 = unpack3(pack3(p.x - o.x, p.y - o.y, p.z - o.z))
        dz = p.z - o.z
        return Vector3(
            dz32 * m[2] + dx * m[0] + dy * m[1],
            dz32 * m[5] + dx * m[3] + dy * m[4],
            dz * m[8] + dx * m[6] + dy * m[7],
        )

    # -- headings --------------------------------------------------------------------------

    def get_vector_heading(self) -> Vector3:
        """The local +y axis (the facing) in global coordinates.

        Retail adds the other two columns times 0.0 (``localtoglobalvec`` of (0, 1, 0) inlined),
        which only turns a -0.0 into +0.0; so does this.

        Retail: Frame::get_vector_heading @ 0x00535720 (acclient.c:357393)
        """
        m = self.m
        return Vector3((m[6] + m[0]) * 0.0 + m[3], (m[7] + m[1]) * 0.0 + m[4], (m[8] + m[2]) * 0.0 + m[5])

    def get_heading(self) -> float:
        """The compass heading of the facing, in degrees [0, 360).

        Retail: Frame::get_heading @ 0x00535760 (acclient.c:357409)
        """
        m = self.m
        return compass_heading((m[6] + m[0]) * 0.0 + m[3], (m[7] + m[1]) * 0.0 + m[4])

    def set_vector_heading(self, heading: Vector3) -> None:
        """Face along ``heading``: yaw from its horizontal bearing, pitch from its z.

        Leaves the rotation untouched when ``heading`` is shorter than EPSILON.
        The new rotation replaces the old one entirely (any roll is lost). The yaw and the
        pitch are ``float`` arguments; the pitch goes through degrees and back, as retail's does.

        Retail: Frame::set_vector_heading @ 0x00535DB0 (acclient.c:357667)
        """
        normal = heading.copy()
        if normal.normalize_check_small():
            return
        yaw = -compass_heading(normal.x, normal.y) * _RAD_PER_DEG
        pitch = math.asin(normal.z) * _DEG_PER_RAD * _RAD_PER_DEG
        self.euler_set_rotate(pitch, 0.0, yaw)

    def set_heading(self, degrees: float) -> None:
        """Face compass ``degrees``, keeping the facing's current z as the pitch input.

        ``degrees`` is a ``float`` parameter; the direction is a ``Vector3``.

        Retail: Frame::set_heading @ 0x00535E40 (acclient.c:357691)
        """
        rad = f32(degrees) * _RAD_PER_DEG
        m = self.m
        self.set_vector_heading(Vector3(math.sin(rad), math.cos(rad), (m[8] + m[2]) * 0.0 + m[5]))

    def euler_set_rotate(self, x: float, y: float, z: float) -> None:
        """Set the rotation from static-axis Euler angles applied x, then y, then z (radians).

        Retail always calls this with order 0 (Shoemake's ``EulOrdXYZs``:
        i=0, j=1, k=2, no repetition, even parity, static frame), the only
        order ported here. The angles are ``float`` parameters; the half z angle, the
        cosines, the x sine and the four products are ``float`` locals, the y and z sines
        stay double (acclient.c:357620-357660).

        Retail: Frame::euler_set_rotate @ 0x00535BF0 (acclient.c:357588)
        """
        x, y, z = unpack3(pack3(x, y, z))
        half_z = f32(z * 0.5)
        ci, si = f32(math.cos(x * 0.5)), f32(math.sin(x * 0.5))
        cj, sj = f32(math.cos(y * 0.5)), math.sin(y * 0.5)
        ch, sh = f32(math.cos(half_z)), math.sin(half_z)
        cc, cs, sc, ss = unpack4(pack4(ch * ci, ci * sh, si * ch, sh * si))
        self.set_rotate(
            ss * sj + cc * cj,
            sc * cj - cs * sj,
            cc * sj + ss * cj,
            cs * cj - sc * sj,
        )
