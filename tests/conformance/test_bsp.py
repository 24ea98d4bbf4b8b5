"""BSP queries against hand-built trees; expected values read off the decompiled BSPNODE/BSPLEAF."""

from __future__ import annotations

import struct

import pytest

from acphys.constants import EPSILON
from acphys.geometry.bsp import (
    CELL_ENTIRELY_INSIDE,
    CELL_OUTSIDE,
    CELL_PARTIALLY_INSIDE,
    CELL_SPHERE_SLACK,
    NODE_TYPE_LEAF,
    BSPLeaf,
    BSPNode,
    BSPTree,
    SolidPolyHit,
    spheres_intersect,
    type_tag,
)
from acphys.geometry.plane import Plane
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import f32

BIG = Sphere(Vector3(), 100.0)


def f32_step(value: float, steps: int) -> float:
    """The float32 ``steps`` representable values away from the float32 ``value``, away from zero
    for positive ``steps`` (toward it for negative)."""
    bits = struct.unpack("<I", struct.pack("<f", value))[0] + steps
    return struct.unpack("<f", struct.pack("<I", bits))[0]


def square_at_x0() -> Polygon:
    """A 2x2 face in the plane x = 0, normal -x."""
    return Polygon([Vector3(0, -1, -1), Vector3(0, -1, 1), Vector3(0, 1, 1), Vector3(0, 1, -1)])


def half_space_tree(solid_polys: list[Polygon] | None = None) -> BSPNode:
    """Split on x = 0 (N = +x): positive side an empty leaf, negative side a solid leaf."""
    return BSPNode(
        Plane(Vector3(1, 0, 0), 0.0),
        pos_node=BSPLeaf(0),
        neg_node=BSPLeaf(1, solid=True, sphere=BIG, polys=solid_polys or [square_at_x0()]),
        sphere=BIG,
    )


def test_type_tags() -> None:
    assert NODE_TYPE_LEAF == 1279607110  # UnPackChild compares with 1279607110 (acclient.c:363371)
    assert type_tag("PORT") == 1347375700  # acclient.c:363358
    assert BSPNode().type == 589505315  # BSPNODE ctor '####' (acclient.c:363069)
    assert BSPLeaf().leaf_index == -1 and not BSPLeaf().solid  # BSPLEAF ctor (acclient.c:364072)
    with pytest.raises(ValueError):
        type_tag("LEAFY")


def test_spheres_intersect_is_strict() -> None:
    a = Sphere(Vector3(), 1.0)
    assert spheres_intersect(a, Sphere(Vector3(1.5, 0, 0), 0.6))
    # dist² < (ra+rb)² strictly: exactly touching misses (acclient.c:356354)
    assert not spheres_intersect(a, Sphere(Vector3(2.0, 0, 0), 1.0))


class TestPointIntersectsSolid:
    def test_sides(self) -> None:
        root = half_space_tree()
        assert root.point_intersects_solid(Vector3(-0.1, 0, 0))  # < 0 -> neg (acclient.c:363033)
        assert not root.point_intersects_solid(Vector3(0.1, 0, 0))

    def test_on_plane_goes_positive(self) -> None:
        # Retail tests `dist < 0.0` for neg, so dist == 0 takes pos_node (acclient.c:363033-363036).
        # ACE BSPNode.point_intersects_solid uses `dist > 0 ? pos : neg`, sending it negative: here
        # the on-plane point is NOT solid; under ACE it would be.
        assert not half_space_tree().point_intersects_solid(Vector3(0.0, 5.0, 5.0))

    def test_leaf_reads_polys_not_solid_flag(self) -> None:
        # BSPLEAF::point_intersects_solid returns num_polys != 0 (acclient.c:364088).
        assert BSPLeaf(solid=False, polys=[square_at_x0()]).point_intersects_solid(Vector3())
        assert not BSPLeaf(solid=True).point_intersects_solid(Vector3())


class TestSphereIntersectsSolid:
    def test_node_sphere_miss(self) -> None:
        root = half_space_tree()
        root.sphere = Sphere(Vector3(-10, 0, 0), 1.0)
        # CSphere::intersects(&this->sphere) fails -> 0 (acclient.c:363583)
        assert not root.sphere_intersects_solid(Sphere(Vector3(-1, 0, 0), 0.5), True)

    def test_centre_inside_solid_leaf(self) -> None:
        # dist -5 <= -(0.5 - EPS): only neg, center_check kept (acclient.c:363593); solid -> 1 (364247)
        assert half_space_tree().sphere_intersects_solid(Sphere(Vector3(-5, 30, 0), 0.5), True)
        # without center_check the leaf falls to its polygons, far away -> 0 (acclient.c:364253)
        assert not half_space_tree().sphere_intersects_solid(Sphere(Vector3(-5, 30, 0), 0.5), False)

    def test_band_is_radius_less_epsilon(self) -> None:
        r = 0.5
        # The band is the double r - EPS = 0.4998000000051 (acclient.c:363589); a float32 centre
        # cannot sit on it: f32(r - EPS) = 0.49979999661 is just inside, the next float32 up
        # (0.49980002642) just outside.
        inside = f32(r - EPSILON)
        outside = f32_step(inside, 1)
        assert inside < r - EPSILON < outside
        # dist >= r - EPS: `v5 >= v6` -> only the empty pos leaf (acclient.c:363591)
        assert not half_space_tree().sphere_intersects_solid(Sphere(Vector3(outside, 0, 0), r), True)
        # just inside straddles: pos with center_check, neg without; the face is hit (acclient.c:363606)
        assert half_space_tree().sphere_intersects_solid(Sphere(Vector3(inside, 0, 0), r), True)
        assert half_space_tree().sphere_intersects_solid(Sphere(Vector3(r - 2 * EPSILON, 0, 0), r), True)

    def test_straddle_passes_center_check_only_to_centre_side(self) -> None:
        # Solid leaf with a far-away face: only center_check can make it hit.
        far = Polygon([Vector3(0, 50, 0), Vector3(0, 50, 1), Vector3(0, 51, 1)])
        # centre at +0.1: dist >= 0 -> neg gets center_check 0 (acclient.c:363608) -> miss
        assert not half_space_tree([far]).sphere_intersects_solid(Sphere(Vector3(0.1, 0, 0), 0.5), True)
        # centre at -0.1: dist < 0 -> neg keeps center_check (acclient.c:363600) -> hit
        assert half_space_tree([far]).sphere_intersects_solid(Sphere(Vector3(-0.1, 0, 0), 0.5), True)
        # dist == 0 counts as positive (`v5 < 0.0` false, acclient.c:363596): neg gets 0 -> miss
        assert not half_space_tree([far]).sphere_intersects_solid(Sphere(Vector3(0.0, 0, 0), 0.5), True)

    def test_leaf_without_polys(self) -> None:
        # num_polys == 0 -> 0 even when solid and center_check (acclient.c:364245)
        assert not BSPLeaf(solid=True).sphere_intersects_solid(Sphere(Vector3(), 1.0), True)

    def test_leaf_sphere_gates_polys(self) -> None:
        leaf = BSPLeaf(solid=False, sphere=Sphere(Vector3(0, 20, 0), 1.0), polys=[square_at_x0()])
        # leaf sphere missed -> 0 though the face itself is touched (acclient.c:364251)
        assert not leaf.sphere_intersects_solid(Sphere(Vector3(0.2, 0, 0), 0.5), False)


class TestSphereIntersectsSolidPoly:
    def test_records_hit_poly(self) -> None:
        face = square_at_x0()
        hit = SolidPolyHit()
        s = Sphere(Vector3(0.2, 0, 0), 0.5)
        assert half_space_tree([face]).sphere_intersects_solid_poly(s, 0.5, hit, True)
        assert hit.hit_poly is face  # *hit_poly = in_polys[v8] (acclient.c:364364)
        assert not hit.center_solid  # centre side (pos) is the empty leaf; neg got center_check 0

    def test_center_solid_without_poly(self) -> None:
        far = Polygon([Vector3(0, 50, 0), Vector3(0, 50, 1), Vector3(0, 51, 1)])
        hit = SolidPolyHit()
        s = Sphere(Vector3(-0.1, 0, 0), 0.5)
        # dist < 0: neg first with center_check -> *center_solid = 1 (acclient.c:364355), no poly,
        # so pos is asked with 0 and its empty leaf returns 0 (acclient.c:363760, 364375).
        assert not half_space_tree([far]).sphere_intersects_solid_poly(s, 0.5, hit, True)
        assert hit.center_solid and hit.hit_poly is None

    def test_leaf_returns_center_solid(self) -> None:
        far = Polygon([Vector3(0, 50, 0), Vector3(0, 50, 1), Vector3(0, 51, 1)])
        hit = SolidPolyHit()
        leaf = BSPLeaf(solid=True, sphere=BIG, polys=[far])
        # no polygon hit -> result = *center_solid (acclient.c:364370)
        assert leaf.sphere_intersects_solid_poly(Sphere(Vector3(), 0.5), 0.5, hit, True)

    def test_radius_argument_sets_band(self) -> None:
        hit = SolidPolyHit()
        s = Sphere(Vector3(0.3, 0, 0), 0.5)
        # v9 = radius - EPS uses the `radius` argument (acclient.c:363730): 0.3 >= 0.2 - EPS -> pos only
        assert not half_space_tree().sphere_intersects_solid_poly(s, 0.2, hit, True)
        assert hit.hit_poly is None

    def test_on_plane_pos_first(self) -> None:
        # Retail: `v8 < 0.0` picks neg first, so dist == 0 goes pos first with center_check and neg
        # gets 0 (acclient.c:363751/363769). ACE uses `dist <= 0` (neg first): its solid leaf
        # would set center_solid; retail leaves it clear.
        far = Polygon([Vector3(0, 50, 0), Vector3(0, 50, 1), Vector3(0, 51, 1)])
        hit = SolidPolyHit()
        assert not half_space_tree([far]).sphere_intersects_solid_poly(Sphere(Vector3(), 0.5), 0.5, hit, True)
        assert not hit.center_solid


def cell_chain() -> BSPTree:
    """A cell BSP chain x >= 0 then x <= 10 (pos links only), ending at a leaf with the zero plane."""
    second = BSPNode(Plane(Vector3(-1, 0, 0), 10.0), pos_node=BSPLeaf(0))
    return BSPTree(BSPNode(Plane(Vector3(1, 0, 0), 0.0), pos_node=second))


class TestCellBsp:
    def test_point_inside(self) -> None:
        t = cell_chain()
        assert t.point_inside_cell_bsp(Vector3(5, 0, 0))
        # within EPSILON behind counts as on the plane (side 2 continues, acclient.c:362959/362969)
        assert t.point_inside_cell_bsp(Vector3(-EPSILON * 0.5, 0, 0))
        # more than EPSILON behind -> 0 (acclient.c:362970)
        assert not t.point_inside_cell_bsp(Vector3(-2 * EPSILON, 0, 0))
        assert not t.point_inside_cell_bsp(Vector3(10.001, 0, 0))

    def test_sphere_inside(self) -> None:
        t = cell_chain()
        # dist >= r + 0.01 at both planes, then the leaf's zero plane gives dist 0 < r', with no
        # pos_node after it -> 1 (acclient.c:363005, 363020): a chain ending at a leaf never says 2.
        assert t.sphere_intersects_cell_bsp(Sphere(Vector3(5, 0, 0), 1.0)) == CELL_PARTIALLY_INSIDE
        # dist <= -(r + 0.0099999998) -> 0 (acclient.c:362995). The slack is the float32 0.01 and
        # r + slack = 1.0099999998 is summed in double; the float32 centre nearest it,
        # -1.0099999905, is inside, the next one out (-1.0100001097) is outside.
        assert f32(0.01) == CELL_SPHERE_SLACK
        near = f32(-1.0099999998)
        assert -near < 1.0 + CELL_SPHERE_SLACK
        assert t.sphere_intersects_cell_bsp(Sphere(Vector3(near, 0, 0), 1.0)) == CELL_PARTIALLY_INSIDE
        beyond = Sphere(Vector3(f32_step(near, 1), 0, 0), 1.0)
        assert t.sphere_intersects_cell_bsp(beyond) == CELL_OUTSIDE
        assert t.sphere_intersects_cell_bsp(Sphere(Vector3(-1.0, 0, 0), 1.0)) == CELL_PARTIALLY_INSIDE

    def test_sphere_entirely_inside_without_leaf(self) -> None:
        t = BSPTree(BSPNode(Plane(Vector3(1, 0, 0), 0.0)))
        # dist >= r' and no pos_node -> 2 (acclient.c:363008)
        assert t.sphere_intersects_cell_bsp(Sphere(Vector3(1.02, 0, 0), 1.0)) == CELL_ENTIRELY_INSIDE
        assert t.sphere_intersects_cell_bsp(Sphere(Vector3(1.0, 0, 0), 1.0)) == CELL_PARTIALLY_INSIDE

    def test_box(self) -> None:
        t = cell_chain()
        assert t.box_intersects_cell_bsp(Vector3(-5, 0, 0), Vector3(1, 1, 1))
        # every corner more than EPSILON behind x = 0 -> 0 (acclient.c:363453-363507)
        assert not t.box_intersects_cell_bsp(Vector3(-5, 0, 0), Vector3(-0.001, 1, 1))
        # max corner within EPSILON of the plane is not behind -> stays inside
        assert t.box_intersects_cell_bsp(Vector3(-5, 0, 0), Vector3(-EPSILON * 0.5, 1, 1))

    def test_get_sphere(self) -> None:
        t = BSPTree(half_space_tree())
        assert t.get_sphere() is t.root_node.sphere  # &root_node->sphere (acclient.c:360664)
