"""CPolygon routines: expected values hand-derived from the decompilation (acclient.c lines cited)."""

from __future__ import annotations

import math
import struct

import pytest

from acphys.constants import EPSILON, FLOOR_Z
from acphys.geometry.plane import Ray, Sidedness
from acphys.geometry.polygon import Polygon, SidesType
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import f32

UP = Vector3(0.0, 0.0, 1.0)

#: The float32 just above 0.5 + EPSILON: the smallest float32 radius whose ``radius - EPSILON``
#: reaches 0.5 (f32(0.5 + EPSILON) = 0.50019997 falls short: 0.50019997 - EPSILON = 0.49999997).
R_REACHES_HALF = 0.5002000331878662


def f32_neighbour(value: float, up: bool) -> float:
    """The float32 next to the float32 ``value``, above or below (both positive)."""
    step = struct.unpack("<I", struct.pack("<f", value))[0] + (1 if up else -1)
    return struct.unpack("<f", struct.pack("<I", step))[0]


def square(z: float = 0.0, sides: SidesType = SidesType.SINGLE) -> Polygon:
    """Unit square in the plane z, counter-clockwise seen from above (normal +z)."""
    pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    return Polygon([Vector3(x, y, z) for x, y in pts], sides)


def down_square() -> Polygon:
    """The unit square at z=0 wound clockwise from above (normal -z)."""
    pts = [(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0)]
    return Polygon([Vector3(x, y, 0.0) for x, y in pts])


# --- make_plane -------------------------------------------------------------------------


def test_make_plane_square() -> None:
    poly = square(2.0)
    # acclient.c:359692 normal = fan cross sum (0,0,2) normalised; 359713 d = -(mean N·v) = -2
    assert poly.plane.N.exactly_equals(Vector3(0.0, 0.0, 1.0))
    assert poly.plane.d == -2.0
    assert poly.num_points == 4


def test_make_plane_clockwise_faces_down_and_d_is_vertex_mean() -> None:
    poly = Polygon([Vector3(0, 0, 1), Vector3(0, 1, 3), Vector3(1, 1, 3), Vector3(1, 0, 1)])
    # fan: (0,1,2)x(1,1,2) + (1,1,2)x(1,0,0) = (0,2,-1) + (0,2,-1) -> (0, 2, -1)/sqrt5
    s5 = math.sqrt(5.0)
    assert poly.plane.N.x == 0.0
    assert poly.plane.N.y == pytest.approx(2.0 / s5)
    assert poly.plane.N.z == pytest.approx(-1.0 / s5)
    # acclient.c:359713 d = -mean(2y - z)/sqrt5 = -mean(-1, -1, -1, -1)/sqrt5
    assert poly.plane.d == pytest.approx(1.0 / s5)


def test_bad_polygons_rejected() -> None:
    with pytest.raises(ValueError, match="at least 3"):
        Polygon([Vector3(), Vector3(1, 0, 0)])
    with pytest.raises(ValueError, match="collinear"):
        Polygon([Vector3(), Vector3(1, 0, 0), Vector3(2, 0, 0)])
    with pytest.raises(ValueError, match="sides_type"):
        Polygon([Vector3(), Vector3(1, 0, 0), Vector3(0, 1, 0)], 3)


# --- point tests ------------------------------------------------------------------------


def test_point_in_poly2D_sides() -> None:
    poly = square()
    # acclient.c:359437 every edge value for (0.5, 0.5) is -0.5: POSITIVE rejects > 0 (359448)
    assert poly.point_in_poly2D(Vector3(0.5, 0.5, 9.0), Sidedness.POSITIVE) is True
    # NEGATIVE rejects < 0 (359443)
    assert poly.point_in_poly2D(Vector3(0.5, 0.5, 9.0), Sidedness.NEGATIVE) is False
    # (1.5, 0.5): the x=1 edge gives +0.5
    assert poly.point_in_poly2D(Vector3(1.5, 0.5, 0.0), Sidedness.POSITIVE) is False
    # on the x=0 edge that edge's value is exactly 0, not > 0: still inside
    assert poly.point_in_poly2D(Vector3(0.0, 0.5, 0.0), Sidedness.POSITIVE) is True
    # wound clockwise from above, every value for (0.5, 0.5) is +0.5: only NEGATIVE accepts
    assert down_square().point_in_poly2D(Vector3(0.5, 0.5, 0.0), Sidedness.NEGATIVE) is True
    assert down_square().point_in_poly2D(Vector3(0.5, 0.5, 0.0), Sidedness.POSITIVE) is False


def test_point_in_polygon() -> None:
    poly = square()
    assert poly.point_in_polygon(Vector3(0.5, 0.5, 0.0)) is True
    assert poly.point_in_polygon(Vector3(1.0, 1.0, 0.0)) is True  # on a vertex: dp 0 not < 0 (360215)
    assert poly.point_in_polygon(Vector3(1.0001, 0.5, 0.0)) is False  # no epsilon: acclient.c:360215


# --- sphere tests -----------------------------------------------------------------------


@pytest.mark.parametrize("method", ["polygon_hits_sphere", "polygon_hits_sphere_slow_but_sure"])
def test_sphere_exactly_touching_face_misses(method: str) -> None:
    poly = square()
    contact = Vector3(7.0, 7.0, 7.0)
    # acclient.c:359953/360053 rad = 0.5 - EPSILON < |dist| 0.5: no hit, contact untouched
    assert getattr(poly, method)(Sphere(Vector3(0.5, 0.5, 0.5), 0.5), contact) is False
    assert contact.exactly_equals(Vector3(7.0, 7.0, 7.0))
    # The radius is a float32 (CSphere::radius): 0.5 + EPSILON is stored as 0.50019997, whose
    # rad = 0.50019997 - EPSILON = 0.49999997 < 0.5 still misses; the next float32 up reaches.
    assert f32(0.5 + EPSILON) < R_REACHES_HALF and f32(0.5 + EPSILON) - EPSILON < 0.5
    assert getattr(poly, method)(Sphere(Vector3(0.5, 0.5, 0.5), 0.5 + EPSILON), contact) is False
    # rad 0.50000003 >= 0.5, foot (0.5, 0.5, 0) inside every edge
    assert getattr(poly, method)(Sphere(Vector3(0.5, 0.5, 0.5), R_REACHES_HALF), contact) is True
    assert contact.exactly_equals(Vector3(0.5, 0.5, 0.0))


@pytest.mark.parametrize("method", ["polygon_hits_sphere", "polygon_hits_sphere_slow_but_sure"])
def test_sphere_behind_face_hits(method: str) -> None:
    contact = Vector3()
    # fabs(dist): a sphere behind a single-sided face is still hit (acclient.c:359954)
    assert getattr(square(), method)(Sphere(Vector3(0.5, 0.5, -0.3), 0.5), contact) is True
    assert contact.z == 0.0


@pytest.mark.parametrize("method", ["polygon_hits_sphere", "polygon_hits_sphere_slow_but_sure"])
def test_sphere_beside_edge(method: str) -> None:
    poly = square()
    contact = Vector3()
    # foot (1.3, 0.5): x=1 edge dp = -0.3, 0.09 <= 0.4998**2 (359991), along 0.5 in [0, 1] (359994)
    assert getattr(poly, method)(Sphere(Vector3(1.3, 0.5, 0.0), 0.5), contact) is True
    # grazing at 1.5: dp**2 = 0.25 > (0.5 - EPSILON)**2 -> the lost compare returns 0 (359991)
    assert getattr(poly, method)(Sphere(Vector3(1.5, 0.5, 0.0), 0.5), contact) is False
    # the smallest float32 radius with rad >= 0.5 (see R_REACHES_HALF): rad**2 >= 0.25 = dp**2, in reach
    assert getattr(poly, method)(Sphere(Vector3(1.5, 0.5, 0.0), R_REACHES_HALF), contact) is True


@pytest.mark.parametrize("method", ["polygon_hits_sphere", "polygon_hits_sphere_slow_but_sure"])
def test_sphere_near_corner(method: str) -> None:
    poly = square()
    contact = Vector3()
    # foot (1.3, 1.3): no edge projection in range; vertex (1,1) at distance**2 0.18 <= radsq (359998)
    assert getattr(poly, method)(Sphere(Vector3(1.3, 1.3, 0.0), 0.5), contact) is True
    # foot (1.4, 1.4): vertex distance**2 0.32 > 0.2498: result cleared at 359996 / loop ends 360124
    assert getattr(poly, method)(Sphere(Vector3(1.4, 1.4, 0.0), 0.5), contact) is False


def test_hits_sphere_and_pos_hits_sphere() -> None:
    poly = square()
    sphere = Sphere(Vector3(0.5, 0.5, 0.3), 0.5)
    assert poly.hits_sphere(sphere) is True
    contact = Vector3()
    # moving into the face (N·movement < 0): hit and struck (acclient.c:360500-360506)
    assert poly.pos_hits_sphere(sphere, Vector3(0, 0, -1), contact) == (True, True)
    # moving away (N·movement >= 0, 360503): no hit, but retail still stored struck_poly
    assert poly.pos_hits_sphere(sphere, Vector3(1, 0, 0), contact) == (False, True)
    assert poly.pos_hits_sphere(Sphere(Vector3(0.5, 0.5, 2.0), 0.5), Vector3(0, 0, -1), contact) == (
        False,
        False,
    )


def _slope(nz: float) -> Polygon:
    """A square through the origin whose normal is (sqrt(1 - nz**2), 0, nz), normal z set exactly
    (``nz`` a float32, as a plane holds it)."""
    nx = math.sqrt(1.0 - nz * nz)
    slope = -nx / nz  # z = slope * x keeps nx*x + nz*z = 0
    pts = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
    poly = Polygon([Vector3(x, y, slope * x) for x, y in pts])
    poly.plane.N.z = nz
    return poly


def test_walkable_hits_sphere_floor_z_boundary() -> None:
    sphere = Sphere(Vector3(0.0, 0.0, 0.3), 0.5)
    # acclient.c:360528 N·up > walkable_allowance, strict; the float32 normals on either side
    above, below = f32_neighbour(FLOOR_Z, up=True), f32_neighbour(FLOOR_Z, up=False)
    assert _slope(FLOOR_Z).walkable_hits_sphere(sphere, UP, FLOOR_Z) is False
    assert _slope(above).walkable_hits_sphere(sphere, UP, FLOOR_Z) is True
    assert _slope(below).walkable_hits_sphere(sphere, UP, FLOOR_Z) is False
    # steep enough but out of reach
    far = Sphere(Vector3(0.0, 0.0, 3.0), 0.5)
    assert _slope(above).walkable_hits_sphere(far, UP, FLOOR_Z) is False


# --- walkable checks --------------------------------------------------------------------


def test_check_walkable_and_small() -> None:
    poly = square()
    high = Sphere(Vector3(1.3, 0.5, 5.0), 0.5)  # foot (1.3, 0.5, 0); height above plane ignored
    # radsq = 0.25 (no EPSILON): x=1 edge dp**2 = 0.09 in reach, along 0.5 in range (360296-360300)
    assert poly.check_walkable(high, UP) is True
    # small: radsq = 0.25 * 0.25 (360359): 0.09 > 0.0625 -> return 0 (360296)
    assert poly.check_small_walkable(high, UP) is False
    assert poly.check_small_walkable(Sphere(Vector3(1.2, 0.5, 5.0), 0.5), UP) is True  # 0.04 <= 0.0625


def test_check_walkable_parallel_up_rejected() -> None:
    wall = Polygon([Vector3(0, 0, 0), Vector3(0, 0, 1), Vector3(0, 1, 1), Vector3(0, 1, 0)])
    assert wall.check_walkable(Sphere(Vector3(0.0, 0.5, 0.5), 0.5), UP) is False  # acclient.c:360260


def test_check_walkable_down_facing_face_divergence_from_ace() -> None:
    # Retail tests fabs(N·up) < EPSILON (acclient.c:360260); ACE's check_walkable tests N·up < EPSILON
    # without fabs and so rejects a downward-facing polygon. Retail: t = -3 / -1, foot (0.5, 0.5, 0).
    assert down_square().check_walkable(Sphere(Vector3(0.5, 0.5, 3.0), 0.5), UP) is True


def test_find_crossed_edge() -> None:
    poly = square()
    normal = poly.find_crossed_edge(Sphere(Vector3(1.3, 0.5, 2.0), 0.5), UP)
    # first edge the foot is outside: (1,0)->(1,1); N x edge = (-1, 0, 0) normalised (360479)
    assert normal is not None
    assert normal.exactly_equals(Vector3(-1.0, 0.0, 0.0))
    assert poly.find_crossed_edge(Sphere(Vector3(0.5, 0.5, 2.0), 0.5), UP) is None
    assert poly.find_crossed_edge(Sphere(Vector3(0.5, 0.5, 2.0), 0.5), Vector3(1, 0, 0)) is None  # 360429


# --- adjustments ------------------------------------------------------------------------


def test_adjust_sphere_to_plane_backs_off() -> None:
    poly = square()
    sphere = Sphere(Vector3(0.5, 0.5, 0.2), 0.5)
    # N·movement = -1 < -EPSILON: gap = dist - r = -0.3 (acclient.c:359564), t = 0.3 (359572),
    # interp = (1 - 0.3) * 1.0 (359573); centre -= t * movement (359583-359585)
    interp = poly.adjust_sphere_to_plane(sphere, Vector3(0.0, 0.0, -1.0), 1.0)
    assert interp == pytest.approx(0.7)
    assert sphere.center.z == pytest.approx(0.5)


def test_adjust_sphere_to_plane_refusals() -> None:
    poly = square()
    sphere = Sphere(Vector3(0.5, 0.5, 0.2), 0.5)
    # |N·movement| <= EPSILON (acclient.c:359557-359560), EPSILON itself included
    assert poly.adjust_sphere_to_plane(sphere, Vector3(1.0, 0.0, EPSILON), 1.0) is None
    assert poly.adjust_sphere_to_plane(sphere, Vector3(1.0, 0.0, -EPSILON), 1.0) is None
    # moving up: gap = -0.5 - 0.2, t = -1.4, interp 2.4 >= 1.0 (359575)
    assert poly.adjust_sphere_to_plane(sphere, Vector3(0.0, 0.0, 0.5), 1.0) is None
    # moving down fast from deep below: gap = -1 - 0.5, t = 1.5 / -1 ... interp < -0.5 refused
    deep = Sphere(Vector3(0.5, 0.5, -1.0), 0.5)
    # gap = -1.0 - 0.5 = -1.5, t = 1.5, interp = -0.5 * 1.0 = -0.5: not < -0.5, accepted
    assert poly.adjust_sphere_to_plane(deep, Vector3(0.0, 0.0, -1.0), 1.0) == pytest.approx(-0.5)
    deeper = Sphere(Vector3(0.5, 0.5, -1.1), 0.5)
    assert poly.adjust_sphere_to_plane(deeper, Vector3(0.0, 0.0, -1.0), 1.0) is None  # interp -0.6
    # untouched: the centres are the float32 values they were built with
    assert deeper.center.z == f32(-1.1) and sphere.center.z == f32(0.2)


def test_adjust_to_placement_poly() -> None:
    poly = square()
    struck, other = Sphere(Vector3(0.5, 0.5, 0.1), 0.5), Sphere(Vector3(9.0, 9.0, 1.0), 0.2)
    poly.adjust_to_placement_poly(struck, other, 0.5, False, False)
    # acclient.c:360162 shift = radius - dist = 0.4, applied to both (360164-360170)
    assert struck.center.z == pytest.approx(0.5)
    assert other.center.z == pytest.approx(1.4)


def test_adjust_to_placement_poly_double_negation_divergence_from_ace() -> None:
    poly = square()
    struck, other = Sphere(Vector3(0.5, 0.5, -0.1), 0.5), Sphere(Vector3(), 0.2)
    # acclient.c:360155 center_solid negates, 360157 dist <= 0 negates again: target +0.5,
    # shift 0.6. ACE negates once for (center_solid || dist <= 0) and would give z = -0.5.
    poly.adjust_to_placement_poly(struck, other, 0.5, True, True)
    assert struck.center.z == pytest.approx(0.5)
    assert other.center.z == pytest.approx(0.6)
    only_behind = Sphere(Vector3(0.5, 0.5, -0.1), 0.5)
    poly.adjust_to_placement_poly(only_behind, other, 0.5, False, True)
    assert only_behind.center.z == pytest.approx(-0.5)  # one negation: target -0.5, shift -0.4


# --- rays -------------------------------------------------------------------------------


def test_polygon_hits_ray() -> None:
    down = Vector3(0.0, 0.0, -1.0)
    up = Vector3(0.0, 0.0, 1.0)
    # acclient.c:360559 N·dir <= 0 then time 2 (359603) and point (0.5, 0.5, 0) inside
    assert square().polygon_hits_ray(Ray(Vector3(0.5, 0.5, 2.0), down)) == (True, 2.0)
    assert square().polygon_hits_ray(Ray(Vector3(1.5, 0.5, 2.0), down)) == (False, 2.0)
    # single-sided, from behind: rejected before the plane test (360558-360559)
    assert square().polygon_hits_ray(Ray(Vector3(0.5, 0.5, -2.0), up)) == (False, None)
    # any other sides_type is tested from behind: time (-2) * (-1 / 1) = 2
    assert square(sides=SidesType.DOUBLE).polygon_hits_ray(Ray(Vector3(0.5, 0.5, -2.0), up)) == (True, 2.0)
    # pointing away from a double-sided face: time -2, no hit (359605)
    assert square(sides=SidesType.BOTH).polygon_hits_ray(Ray(Vector3(0.5, 0.5, 2.0), up)) == (False, -2.0)
