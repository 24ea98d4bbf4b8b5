"""The physics BSP builder at scale: separate and touching solids are parted by axis planes (a
tree growing linearly, depth logarithmic), overlapping ones nest only where they reach; the trees
stay retail-shaped and answer queries as direct geometry does; the limits are one-line errors.

Build times are in the benchmarks' and the issue's figures, not here: the node counts and depths
asserted imply them (10 separate boxes: 139 nodes, 11 levels).
"""

from __future__ import annotations

import math
import random
import resource
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from acphys.geometry.bsp import NODE_TYPE_BOTH_CHILDREN, BSPLeaf, BSPNode, SolidPolyHit
from acphys.geometry.bsp_builder import (
    MAX_BSP_DEPTH,
    MAX_BSP_NODES,
    MAX_SOLID_FACES,
    MAX_UNION_CORNERS,
    MAX_UNION_SOLIDS,
    SolidError,
    box_faces,
    build_boxes_tree,
    build_union_tree,
)
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from acphys.precision import is_f32
from acphys.scenario import ScenarioError, load_scenario

Box = tuple[Vector3, Vector3]
V = Vector3


def posts(count: int) -> list[Box]:
    """0.2-m posts 2 m tall, 2 m apart along x."""
    return [(V(2.0 * i, 0.0, 0.0), V(2.0 * i + 0.2, 0.2, 2.0)) for i in range(count)]


def touching_stairs(steps: int) -> list[Box]:
    """The yard's stairs: 0.3-m steps 0.5 m deep, each box on the one below."""
    return [(V(-1.0, 0.5 * i, 0.3 * i), V(1.0, 0.5 * steps, 0.3 * (i + 1))) for i in range(steps)]


def overlapping_stairs(steps: int) -> list[Box]:
    """ladder-06's stairs: every step a box from the ground up, each overlapping the others."""
    return [(V(-1.0, 0.0, 0.0), V(1.0, 3.0 + 0.5 * i, 0.3 * (steps - i))) for i in range(steps)]


def pinwheel() -> list[Box]:
    """Four separate boxes round a square that no axis plane parts (so they nest)."""
    return [
        (V(0.0, 0.0, 0.0), V(1.9, 0.9, 1.0)),
        (V(2.0, 0.0, 0.0), V(2.9, 1.9, 1.0)),
        (V(1.0, 2.0, 0.0), V(2.9, 2.9, 1.0)),
        (V(0.0, 1.0, 0.0), V(0.9, 2.9, 1.0)),
    ]


def scattered(rng: random.Random, count: int) -> list[Box]:
    """Separate boxes of random sizes, one in each 2-m cell of a grid, listed in random order."""
    boxes = []
    for i in range(count):
        cell = V(2.0 * (i % 4), 2.0 * (i // 4 % 4), 2.0 * (i // 16))
        lo = [rng.randrange(0, 48) / 64 for _ in range(3)]
        hi = [a + rng.randrange(8, 72) / 64 for a in lo]
        boxes.append((cell + V(*lo), cell + V(*hi)))
    rng.shuffle(boxes)
    return boxes


def nodes_of(node: BSPNode) -> Iterator[tuple[BSPNode, int]]:
    """Every node below ``node`` with its depth (``node`` is 1), depth first, positive first."""
    stack = [(node, 1)]
    while stack:
        current, depth = stack.pop()
        yield current, depth
        if not isinstance(current, BSPLeaf):
            assert current.pos_node is not None and current.neg_node is not None
            stack += [(current.neg_node, depth + 1), (current.pos_node, depth + 1)]


def size(boxes: list[Box]) -> tuple[int, int]:
    """Node count and depth of the tree of ``boxes``."""
    found = list(nodes_of(build_boxes_tree(boxes).root_node))
    return len(found), max(depth for _node, depth in found)


# -- growth ---------------------------------------------------------------------------------


@pytest.mark.parametrize("count", [1, 2, 4, 6, 8, 10, 20, 50])
def test_separate_posts_grow_linearly(count: int) -> None:
    # Each box is its 13-node chain; count - 1 axis planes part them, most evenly each time.
    nodes, depth = size(posts(count))
    assert nodes == 14 * count - 1
    assert depth <= 7 + math.ceil(math.log2(count))


def test_separate_boxes_in_any_order_and_grid() -> None:
    boxes = scattered(random.Random(7), 64)
    nodes, depth = size(boxes)
    assert nodes == 14 * 64 - 1
    assert depth <= 7 + 6


@pytest.mark.parametrize("steps", [4, 10, 40])
def test_touching_stairs_are_parted(steps: int) -> None:
    # A step's top face is the next step's bottom: touching solids are parted like separate ones.
    assert size(touching_stairs(steps))[0] == 14 * steps - 1


@pytest.mark.parametrize("steps", [4, 10, 40])
def test_overlapping_stairs_nest_only_where_they_reach(steps: int) -> None:
    # Every later step reaches past one face of each earlier one (+y): one graft a step.
    nodes, depth = size(overlapping_stairs(steps))
    assert nodes <= 13 * steps
    assert depth <= 3 * steps + 7


def test_contained_solids_add_nothing() -> None:
    # Listed largest first, boxes inside earlier ones reach past none of their faces.
    nested = [(V(-k, -k, -k), V(k, k, k)) for k in (8.0, 6.0, 4.0, 2.0)]
    assert size(nested)[0] == 13


# -- shape ----------------------------------------------------------------------------------


def test_trees_are_retail_shaped() -> None:
    tetra = [V(5, 5, 0), V(6, 5, 0), V(5, 6, 0), V(5, 5, 1)]
    a, b, c, d = tetra
    solids = [box_faces(lo, hi) for lo, hi in posts(5) + overlapping_stairs(3) + pinwheel()]
    solids.append([Polygon([a, c, b]), Polygon([a, b, d]), Polygon([a, d, c]), Polygon([b, c, d])])
    tree = build_union_tree(solids)
    leaves = []
    for node, _depth in nodes_of(tree.root_node):
        sphere = node.sphere
        assert is_f32(sphere.radius) and all(is_f32(v) for v in sphere.center)
        if isinstance(node, BSPLeaf):
            leaves.append(node)
            if not node.solid:
                assert node.polys == [] and sphere.radius == 0.0
                continue
            assert any(node.polys == faces for faces in solids)  # the solid's own faces, shared
        else:
            assert node.type == NODE_TYPE_BOTH_CHILDREN and node.polys == []
            plane = node.splitting_plane
            assert is_f32(plane.d) and all(is_f32(v) for v in plane.N)
        for below, _ in nodes_of(node):
            for poly in below.polys:
                for v in poly.vertices:
                    c = sphere.center
                    assert ((v.x - c.x) ** 2 + (v.y - c.y) ** 2 + (v.z - c.z) ** 2) ** 0.5 <= sphere.radius
    assert [leaf.leaf_index for leaf in leaves] == list(range(len(leaves)))
    assert all(any(leaf.polys == faces for leaf in leaves) for faces in solids)


# -- queries against direct geometry -------------------------------------------------------


def box_distance(p: Vector3, lo: Vector3, hi: Vector3) -> float:
    """From ``p`` to the box, 0 inside."""
    d = [max(a - x, 0.0, x - b) for x, a, b in zip(p, lo, hi, strict=True)]
    return math.sqrt(sum(t * t for t in d))


def face_distances(p: Vector3, lo: Vector3, hi: Vector3) -> list[tuple[float, Vector3]]:
    """From ``p`` to each face of the box, with the face's outward normal."""
    out = []
    for axis in range(3):
        for side, at in ((-1.0, tuple(lo)[axis]), (1.0, tuple(hi)[axis])):
            near = [min(max(x, a), b) for x, a, b in zip(p, lo, hi, strict=True)]
            near[axis] = at
            normal = [0.0, 0.0, 0.0]
            normal[axis] = side
            out.append((math.dist(p, near), V(*normal)))
    return out


def random_spheres(rng: random.Random, boxes: list[Box], count: int) -> Iterator[tuple[Sphere, Vector3]]:
    """Spheres about the boxes (half of them centred near a face, edge or corner) and movements."""
    corners = [(tuple(lo), tuple(hi)) for lo, hi in boxes]
    low = [min(axis) - 1.0 for axis in zip(*(lo for lo, _hi in corners), strict=True)]
    high = [max(axis) + 1.0 for axis in zip(*(hi for _lo, hi in corners), strict=True)]
    for _ in range(count):
        radius = rng.choice([0.2, 0.48, rng.uniform(0.05, 1.5)])
        if rng.random() < 0.5:
            center = V(*(rng.uniform(a, b) for a, b in zip(low, high, strict=True)))
        else:
            lo, hi = rng.choice(corners)
            near = (
                rng.choice([a, b, rng.uniform(a, b)]) + rng.uniform(-radius, radius)
                for a, b in zip(lo, hi, strict=True)
            )
            center = V(*near)
        movement = V(*(rng.uniform(-0.5, 0.5) for _ in range(3)))
        yield Sphere(center, radius), movement


#: Spheres this close to touching a face are skipped: the queries' EPSILON slack decides them.
BAND = 1e-3


@pytest.mark.parametrize(
    "name", ["posts", "scattered", "pinwheel", "touching stairs", "overlapping stairs", "random overlaps"]
)
def test_solid_queries_match_geometry(name: str) -> None:
    rng = random.Random(name)
    boxes = {
        "posts": posts(10),
        "scattered": scattered(rng, 40),
        "pinwheel": pinwheel(),
        "touching stairs": touching_stairs(6),
        "overlapping stairs": overlapping_stairs(6),
        "random overlaps": [
            (V(x, y, 0.0), V(x + w, y + d, h))
            for x, y, w, d, h in ([rng.randrange(0, 320) / 64 for _ in range(5)] for _ in range(12))
            if w > 0 and d > 0 and h > 0
        ],
    }[name]
    root = build_boxes_tree(boxes).root_node
    checked = 0
    for sphere, _movement in random_spheres(rng, boxes, 600):
        c, r = sphere.center, sphere.radius
        distances = [box_distance(c, lo, hi) for lo, hi in boxes]
        if any(abs(d - r) < BAND or 0.0 < d < BAND for d in distances):
            continue
        inside = any(
            d == 0.0 and min(f for f, _n in face_distances(c, *box)) > BAND
            for d, box in zip(distances, boxes, strict=True)
        )
        if not inside and min(distances) == 0.0:
            continue  # within BAND of a face from inside
        checked += 1
        assert root.point_intersects_solid(c) == inside, (c, name)
        assert root.sphere_intersects_solid(sphere, True) == (min(distances) < r), (c, r, name)
    assert checked > 300


@pytest.mark.parametrize("name", ["posts", "scattered", "pinwheel"])
def test_polygon_queries_match_geometry(name: str) -> None:
    # Separate boxes: every face is on the union's surface, so a query finds a face exactly when
    # the sphere reaches it, and one of those it reaches.
    rng = random.Random(name)
    boxes = {"posts": posts(10), "scattered": scattered(rng, 24), "pinwheel": pinwheel()}[name]
    solids = [box_faces(lo, hi) for lo, hi in boxes]
    owner = {id(face): i for i, faces in enumerate(solids) for face in faces}
    root = build_union_tree(solids).root_node
    checked = 0
    for sphere, movement in random_spheres(rng, boxes, 600):
        c, r = sphere.center, sphere.radius
        faces = [face_distances(c, lo, hi) for lo, hi in boxes]
        if any(abs(d - r) < BAND for box in faces for d, _n in box):
            continue
        inside = [box_distance(c, lo, hi) == 0.0 for lo, hi in boxes]
        touched = {i for i, box in enumerate(faces) if min(d for d, _n in box) < r}
        headed = {i for i, box in enumerate(faces) if any(d < r and n.dot(movement) < 0.0 for d, n in box)}
        checked += 1
        assert root.sphere_intersects_solid(sphere, False) == bool(touched), (c, r, name)

        hit = SolidPolyHit()
        root.sphere_intersects_solid_poly(sphere, r, hit, True)
        assert hit.center_solid == any(inside), (c, r, name)
        assert (hit.hit_poly is not None) == bool(touched)
        if hit.hit_poly is not None:
            assert owner[id(hit.hit_poly)] in touched

        found = root.sphere_intersects_poly(sphere, movement)
        assert found.hit == bool(headed), (c, r, movement, name)
        assert (found.polygon is not None) == bool(touched)
        if found.hit:
            assert owner[id(found.polygon)] in headed and found.polygon.plane.N.dot(movement) < 0.0
    assert checked > 300


# -- limits ---------------------------------------------------------------------------------


def test_bad_solid_is_named_by_its_place() -> None:
    inward = [Polygon(list(reversed(f.vertices))) for f in box_faces(V(0, 0, 0), V(1, 1, 1))]
    with pytest.raises(SolidError) as error:
        build_union_tree([box_faces(V(2, 0, 0), V(3, 1, 1)), inward])
    assert error.value.index == 1


def test_too_deep_a_nesting_is_refused() -> None:
    # Each box overlaps the others and reaches past the top of every earlier one: 5 levels a box.
    with pytest.raises(ValueError, match=f"over {MAX_BSP_DEPTH} BSP levels .MAX_BSP_DEPTH."):
        build_boxes_tree([(V(-1, -1, 0), V(1, 1, 1 + i)) for i in range(61)])


def scenario(tmp_path: Path, setup: str) -> Path:
    path = tmp_path / "solids.toml"
    body = '[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 50.0]\n'
    path.write_text(f"[setup.thing]\n{setup}\n\n{body}", encoding="utf-8")
    return path


def box_list(boxes: list[Box]) -> str:
    rows = (f"{{ min = [{lo.x}, {lo.y}, {lo.z}], max = [{hi.x}, {hi.y}, {hi.z}] }}" for lo, hi in boxes)
    return "boxes = [\n" + ",\n".join(rows) + "\n]"


def test_separate_boxes_scenario_builds(tmp_path: Path) -> None:
    sim = load_scenario(scenario(tmp_path, box_list(posts(10))))
    assert sim.bodies


def test_too_many_solids_is_one_error(tmp_path: Path) -> None:
    path = scenario(tmp_path, box_list(posts(MAX_UNION_SOLIDS + 1)))
    with pytest.raises(ScenarioError, match=f"setup.thing: a setup has at most {MAX_UNION_SOLIDS} boxes"):
        load_scenario(path)


def prism(sides: int, x: float) -> list[list[list[float]]]:
    """The faces of a 1-m prism of ``sides`` sides about ``(x, 0)``, as scenario points."""
    ring = [(x + math.cos(2 * math.pi * k / sides), math.sin(2 * math.pi * k / sides)) for k in range(sides)]
    faces = [[[px, py, 1.0] for px, py in ring], [[px, py, 0.0] for px, py in reversed(ring)]]
    for (x0, y0), (x1, y1) in zip(ring, ring[1:] + ring[:1], strict=True):
        faces.append([[x0, y0, 0.0], [x1, y1, 0.0], [x1, y1, 1.0], [x0, y0, 1.0]])
    return faces


def test_too_many_faces_names_the_solid(tmp_path: Path) -> None:
    assert load_scenario(scenario(tmp_path, f"solids = [{prism(8, 0.0)}, {prism(MAX_SOLID_FACES - 2, 3.0)}]"))
    # MAX_SOLID_FACES - 1 sides and two ends: one face too many.
    path = scenario(tmp_path, f"solids = [{prism(8, 0.0)}, {prism(MAX_SOLID_FACES - 1, 3.0)}]")
    with pytest.raises(
        ScenarioError, match=rf"setup\.thing\.solids\[1\]: a solid has at most {MAX_SOLID_FACES}"
    ):
        load_scenario(path)


def test_too_many_corners_in_all_is_refused() -> None:
    sides = MAX_SOLID_FACES - 2
    faces = [Polygon([V(*point) for point in face]) for face in prism(sides, 0.0)]
    build_union_tree([faces])
    copies = MAX_UNION_CORNERS // (6 * sides) + 1
    with pytest.raises(ValueError, match=f"at most {MAX_UNION_CORNERS} corners in all .MAX_UNION_CORNERS."):
        build_union_tree([faces] * copies)


def _limit_memory() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))


def test_overlapping_blowup_is_one_error_line(tmp_path: Path) -> None:
    # Six boxes each inside the next, smallest first: every one reaches past every face of every
    # earlier one, so the nesting multiplies by six a box until MAX_BSP_NODES stops it.
    path = scenario(tmp_path, box_list([(V(-k, -k, -k), V(k, k, k)) for k in range(1, 7)]))
    done = subprocess.run(
        [sys.executable, "-m", "acphys.cli", "check", str(path)],
        capture_output=True,
        text=True,
        timeout=60,
        preexec_fn=_limit_memory,
        check=False,
    )
    assert done.returncode == 2, done.stderr
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and "Traceback" not in done.stderr
    assert lines[0].startswith(f"acphys: error: {path}: setup.thing: ")
    assert f"over {MAX_BSP_NODES} BSP nodes (MAX_BSP_NODES)" in lines[0]
