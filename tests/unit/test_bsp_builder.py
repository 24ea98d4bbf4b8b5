"""The physics BSP builder: shape of the tree and agreement with direct geometry."""

from __future__ import annotations

import itertools

import pytest

from acphys.geometry.bsp import BSPLeaf, BSPNode
from acphys.geometry.bsp_builder import box_faces, build_box_tree, build_boxes_tree, build_convex_tree
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3

LO, HI = Vector3(0, 0, 0), Vector3(1, 1, 1)


def walk(node: BSPNode) -> list[BSPNode]:
    out = [node]
    if not isinstance(node, BSPLeaf):
        assert node.pos_node is not None and node.neg_node is not None
        out += walk(node.pos_node) + walk(node.neg_node)
    return out


def box_distance(p: Vector3, lo: Vector3, hi: Vector3) -> float:
    dx = max(lo.x - p.x, 0.0, p.x - hi.x)
    dy = max(lo.y - p.y, 0.0, p.y - hi.y)
    dz = max(lo.z - p.z, 0.0, p.z - hi.z)
    return (dx * dx + dy * dy + dz * dz) ** 0.5


def test_shape() -> None:
    nodes = walk(build_box_tree(LO, HI).root_node)
    leaves = [n for n in nodes if isinstance(n, BSPLeaf)]
    assert len(nodes) - len(leaves) == 6
    solid = [leaf for leaf in leaves if leaf.solid]
    assert len(solid) == 1 and solid[0].num_polys == 6
    assert all(leaf.num_polys == 0 for leaf in leaves if not leaf.solid)
    assert all(n.num_polys == 0 for n in nodes if not isinstance(n, BSPLeaf))
    assert sorted(leaf.leaf_index for leaf in leaves) == list(range(7))


def test_spheres_contain_polygons() -> None:
    tree = build_boxes_tree([(LO, HI), (Vector3(0.5, 0.5, 0.5), Vector3(2, 3, 1.5))])
    for node in walk(tree.root_node):
        below = [n for n in walk(node) if isinstance(n, BSPLeaf)]
        for leaf in below:
            for poly in leaf.polys:
                for v in poly.vertices:
                    assert (v - node.sphere.center).length() <= node.sphere.radius + 1e-12


def test_points_inside_outside_and_on_faces() -> None:
    root = build_box_tree(LO, HI).root_node
    assert root.point_intersects_solid(Vector3(0.5, 0.5, 0.5))
    assert not root.point_intersects_solid(Vector3(1.5, 0.5, 0.5))
    assert not root.point_intersects_solid(Vector3(-0.5, 0.5, 0.5))
    # On a face the distance is 0, which retail sends to pos_node = outside (acclient.c:363033).
    for p in (Vector3(1, 0.5, 0.5), Vector3(0, 0.5, 0.5), Vector3(0.5, 0.5, 1), Vector3(0.5, 0, 0.5)):
        assert not root.point_intersects_solid(p)


def test_union_points() -> None:
    root = build_boxes_tree([(LO, HI), (Vector3(2, 0, 0), Vector3(3, 1, 1))]).root_node
    assert root.point_intersects_solid(Vector3(0.5, 0.5, 0.5))
    assert root.point_intersects_solid(Vector3(2.5, 0.5, 0.5))
    assert not root.point_intersects_solid(Vector3(1.5, 0.5, 0.5))


GRID = [-0.6, -0.25, 0.0, 0.5, 1.0, 1.3, 1.7]


@pytest.mark.parametrize("radius", [0.3, 0.5])
def test_sphere_query_matches_geometry(radius: float) -> None:
    root = build_box_tree(LO, HI).root_node
    for x, y, z in itertools.product(GRID, repeat=3):
        c = Vector3(x, y, z)
        d = box_distance(c, LO, HI)
        got = root.sphere_intersects_solid(Sphere(c, radius), True)
        # Boundary band: node and polygon tests use radius - EPSILON, skip the ambiguous shell.
        if abs(d - radius) < 1e-3:
            continue
        assert got == (d < radius), (c, d)


def test_convex_mesh_tetrahedron() -> None:
    a, b, c, d = Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)
    faces = [Polygon([a, c, b]), Polygon([a, b, d]), Polygon([a, d, c]), Polygon([b, c, d])]
    root = build_convex_tree(faces).root_node
    assert root.point_intersects_solid(Vector3(0.1, 0.1, 0.1))
    assert not root.point_intersects_solid(Vector3(0.5, 0.5, 0.5))
    assert root.sphere_intersects_solid(Sphere(Vector3(0.4, 0.4, 0.4), 0.3), False)
    assert not root.sphere_intersects_solid(Sphere(Vector3(0.8, 0.8, 0.8), 0.3), True)


def test_bad_input() -> None:
    with pytest.raises(ValueError):
        box_faces(HI, LO)
    inward = [Polygon(list(reversed(f.vertices))) for f in box_faces(LO, HI)]
    with pytest.raises(ValueError):
        build_convex_tree(inward)
    with pytest.raises(ValueError):
        build_boxes_tree([])
