"""Float32 at rest, float64 in flight: the stores of ``Vector3``, ``Frame`` and ``Position``.

Each test works a retail function by hand: double arithmetic between stores, ``f32`` at each
store into a ``float`` (field, local, 4-byte spill, float parameter), citing the decompiled
lines. Inputs are chosen so that narrowing at a different place gives a different answer, and
each test checks that too, so it cannot pass by accident.
"""

from __future__ import annotations

import math

from acphys.constants import EPSILON
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32, is_f32


def test_vector_components_are_stored_as_float32() -> None:
    # AC1Legacy::Vector3 is three floats (acclient.h): constructing one is a store.
    v = Vector3(0.1, 1.0 / 3.0, 96.10400000001)
    assert (v.x, v.y, v.z) == (f32(0.1), f32(1.0 / 3.0), f32(96.10400000001))
    assert v.x != 0.1


def test_vector_difference_is_one_store_per_component() -> None:
    # AC1Legacy::Vector3::operator- @ 0x004524C0 (acclient.c:143642): result->x = this->x - b->x,
    # computed in a register and stored once.
    a, b = Vector3(252.63719, 0.0, 0.0), Vector3(0.1, 0.0, 0.0)
    d = a - b
    assert d.x == f32(a.x - b.x)
    assert a.x - b.x != d.x  # the double difference is not a float32


def test_dot_and_length_stay_double() -> None:
    # AC1Legacy::Vector3::magnitude (acclient.c:143594) returns sqrt(...) in st0: no store.
    v = Vector3(0.1, 0.2, 0.3)
    assert v.length_squared() == v.x * v.x + v.y * v.y + v.z * v.z
    assert not is_f32(v.length_squared())


def test_normalize_check_small_stores_the_scaled_components() -> None:
    # AC1Legacy::Vector3::normalize_check_small @ 0x00452460 (acclient.c:143621):
    # len = sqrt(x² + y² + z²) in st4; this->x = 1.0 / len * this->x (a float store).
    v = Vector3(1.0, 2.0, 2.5)
    length = math.sqrt(1.0 + 4.0 + 6.25)
    assert v.normalize_check_small() is False
    assert (v.x, v.y, v.z) == (f32(1.0 / length * 1.0), f32(1.0 / length * 2.0), f32(1.0 / length * 2.5))


def test_cache_stores_the_matrix_as_float32() -> None:
    # Frame::cache @ 0x00534DF0 (acclient.c:356983): the products are 8-byte spills (ST08_8 ...),
    # only m_fl2gv[i] are float stores. m[0] = 1 - cc2 - v12 with cc2 = qy·2qy, v12 = qz·2qz.
    f = Frame(qw=0.8, qx=0.1, qy=0.3, qz=0.5)
    qy, qz = f32(0.3), f32(0.5)
    assert f.m[0] == f32(1.0 - qy * (qy + qy) - qz * (qz + qz))
    assert all(is_f32(c) for c in f.m)


def test_set_rotate_narrows_its_float_parameters_before_normalising() -> None:
    # Frame::set_rotate @ 0x00535080 (acclient.c:357062): the four arguments are float parameters;
    # v6 = 1.0 / sqrt(w² + x² + y² + z²) stays in st7; this->qw = new_qw * v6 (float store).
    f = Frame()
    w, x, y, z = 0.9, 0.1 + 1e-12, 0.2, 0.3
    f.set_rotate(w, x, y, z)
    w32, x32, y32, z32 = f32(w), f32(x), f32(y), f32(z)
    inv = 1.0 / math.sqrt(w32 * w32 + x32 * x32 + y32 * y32 + z32 * z32)
    assert f.rotation == (f32(w32 * inv), f32(x32 * inv), f32(y32 * inv), f32(inv * z32))


def test_is_valid_sums_a_float_norm_z_first() -> None:
    # Frame::IsValid @ 0x00534ED0 (acclient.c:357024): float norm = qz² + qy² + qx² + qw²
    # ([sp+14h]); invalid when 0.00019999999 * 5.0 < fabs(norm - 1.0). These float32 components
    # have a double norm 1 - 1.0000049e-3 (outside the bound) that the float store rounds to
    # 1 - 0.9999871e-3 (inside): retail calls the frame valid.
    f = Frame()
    f.qw, f.qx = 0.11636403948068619, 0.9927030801773071
    double_norm = f.qx * f.qx + f.qw * f.qw
    assert abs(double_norm - 1.0) > 5.0 * EPSILON
    assert abs(f32(double_norm) - 1.0) <= 5.0 * EPSILON
    assert f.is_valid()
    # ...and the other way: a double norm inside the bound that the store rounds outside.
    f.qw, f.qx = 0.7510169744491577, 0.6610397100448608
    assert abs(f.qx * f.qx + f.qw * f.qw - 1.0) <= 5.0 * EPSILON
    assert not f.is_valid()


def test_grotate_keeps_the_sine_and_the_z_term_double() -> None:
    # Frame::grotate @ 0x005357A0 (acclient.c:357421): thetainv (ST18_4), the cosine (the
    # reused wa slot), f (ST10_4) and g (ST14_4) are floats; sin(θ/2) (rt0) and the z term v10 (st7)
    # stay double. g multiplies thetainv · sin · w.y in that order.
    w = Vector3(0.3, -0.7, 1.1)
    f = Frame()
    f.grotate(w)
    theta = math.sqrt(w.x * w.x + w.y * w.y + w.z * w.z)
    inv = f32(1.0 / theta)
    s = math.sin(theta * 0.5)
    c = f32(math.cos(theta * 0.5))
    fx, gy = f32(s * w.x * inv), f32(inv * s * w.y)
    hz = s * inv * w.z
    # identity quaternion: new_q = (c, f, g, h), then set_rotate narrows and normalises
    qw, qx, qy, qz = f32(c), f32(fx), f32(gy), f32(hz)
    norm = 1.0 / math.sqrt(qw * qw + qx * qx + qy * qy + qz * qz)
    assert f.rotation == (f32(qw * norm), f32(qx * norm), f32(qy * norm), f32(norm * qz))


def test_combine_stores_the_origin_once() -> None:
    # Frame::combine @ 0x005122E0 (acclient.c:319448): each origin component is one register
    # sum m6·z + m0·x + m3·y + origin, spilled once (ST18_4, ST1C_4, ST20_4): the rotated offset
    # is not stored on its own before the origin is added.
    f1 = Frame.from_heading(Vector3(100.3, 50.7, 12.1), 33.0)
    f2 = Frame(Vector3(1.470103144645691, 0.5448281764984131, -0.9271421432495117))
    out = Frame()
    out.combine(f1, f2)
    m, o = f1.m, f2.origin
    rotated_x = m[6] * o.z + m[0] * o.x + m[3] * o.y
    assert out.origin.x == f32(rotated_x + f1.origin.x)
    assert out.origin.x != f32(f32(rotated_x) + f1.origin.x)


def test_globaltolocal_spills_the_offset_but_its_z_row_reads_the_register() -> None:
    # Frame::globaltolocal @ 0x00452680 (acclient.c:143717): v3 = in.x - origin.x and
    # v4 = in.y - origin.y are float spills; v6 = in.z - origin.z stays in st7 and is also spilled
    # to v7. The local z row uses v6, the x and y rows use v7.
    frame = Frame(Vector3(10.0, 20.0, 30.3), qw=0.9, qx=0.2, qy=-0.3, qz=0.1)
    frame.set_rotate(0.9, 0.2, -0.3, 0.1)
    p = Vector3(11.7, 18.2, 99.1)
    local = frame.globaltolocal(p)
    m, o = frame.m, frame.origin
    dx, dy, dz = f32(p.x - o.x), f32(p.y - o.y), p.z - o.z
    assert local.z == f32(dz * m[8] + dx * m[6] + dy * m[7])
    assert local.x == f32(f32(dz) * m[2] + dx * m[0] + dy * m[1])
    assert dz != f32(dz)


def test_interpolate_origin_spills_every_product_but_one() -> None:
    # Frame::interpolate_origin @ 0x005352F0 (acclient.c:357228): t·to.y, t·to.z and the three
    # (1 - t)·from products are float spills; x = t·to.x + v8 adds in the register.
    start, end = Frame(Vector3(1.1, 2.2, 3.3)), Frame(Vector3(101.7, -52.9, 7.77))
    out = Frame()
    out.interpolate_origin(start, end, 0.3)
    t = f32(0.3)
    u = 1.0 - t
    assert out.origin.x == f32(t * end.origin.x + f32(u * start.origin.x))
    assert out.origin.y == f32(f32(u * start.origin.y) + f32(t * end.origin.y))
    assert out.origin.z == f32(f32(u * start.origin.z) + f32(t * end.origin.z))


def test_get_offset_spills_y_and_z_but_not_x() -> None:
    # Position::get_offset @ 0x00509F60 (acclient.c:311690): v4 = block.x + p.x stays in st7,
    # v10 = block.y + p.y and v11 = block.z + p.z are float locals; then each minus this origin.
    here = Position(0xA9B40001, Frame(Vector3(115.48934173583984, 115.48934173583984, 0.0)))
    there = Position(0xAAB50001, Frame(Vector3(60.63718795776367, 60.63718795776367, 0.0)))
    offset = here.get_offset(there)
    assert offset.x == f32(192.0 + there.origin.x - here.origin.x) == 137.14784240722656
    assert offset.y == f32(f32(192.0 + there.origin.y) - here.origin.y) == 137.14785766601562


def test_heading_uses_float_angles() -> None:
    # Frame::set_heading @ 0x00535E40 (acclient.c:357691): degrees is a float parameter; the
    # direction is a Vector3 (floats); set_vector_heading (acclient.c:357667) hands
    # euler_set_rotate float angles, so the yaw is f32(-heading in radians).
    a, b = Frame(), Frame()
    a.set_heading(123.456)
    b.set_heading(f32(123.456))
    assert a.rotation == b.rotation
    assert all(is_f32(q) for q in a.rotation)


def test_division_multiplies_by_the_stored_reciprocal() -> None:
    # Vector3::operator/ @ 0x00455DE0 (acclient.c:146865): v4 = 1.0 / rhs in st7, stored into the
    # float parameter's slot (_rhsa); x is scaled by v4, y and z by the stored float.
    v = Vector3(0.1, 0.1, 0.1)  # a walk frame's 0.1 m over a 30 Hz quantum
    q = f32(1.0 / 30.0)
    inv = 1.0 / q
    got = v / q
    assert (got.x, got.y, got.z) == (f32(inv * v.x), f32(f32(inv) * v.y), f32(f32(inv) * v.z))
    assert got.x != got.y  # the same component, scaled by the two reciprocals
