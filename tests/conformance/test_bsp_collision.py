"""BSP collision queries (BSPNODE/BSPLEAF walks, BSPTREE::find_collisions and its responses) against
trees from bsp_builder; expected values worked by hand from the decompiled CBSPTree.c, CBSPNode.c,
CBSPLeaf.c and CPolygon.c.

Unless a test says otherwise: the floor is the box (-5,-5,0)-(5,5,1), top face z = 1 (N +z, d -1);
the moving body has one sphere of radius 0.5 centred 0.5 above its origin; the tree's owner sits at
the landblock origin unrotated at scale 1, so tree space is global space.
"""

from __future__ import annotations

import math
import struct

import pytest

from acphys.constants import FLOOR_Z, LANDING_Z
from acphys.flags import ObjectInfoState as OIS
from acphys.flags import TransitionState as TS
from acphys.geometry.bsp import BSPLeaf, BSPTree
from acphys.geometry.bsp_builder import build_box_tree, build_boxes_tree
from acphys.geometry.bsp_collision import plane_localtoglobal
from acphys.geometry.plane import Plane
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo
from acphys.transition.transition import InsertType, SpherePath

CELL = 0xA9B40001
EAST_CELL = 0xAAB40001  # one landblock east (+192 m in x)
R = 0.5
UP = Vector3(0, 0, 1)


class Sweep:
    """The CTransition parts the BSP routines read; ``step_up`` (CTransition, not ported) is scripted.

    Like retail's ``CTransition::step_up`` (acclient.c:312806) the stand-in stores the normal as
    ``step_up_normal`` before reporting the scripted outcome.
    """

    def __init__(self, path: SpherePath, state: OIS = OIS.DEFAULT, step_up_ok: bool = False) -> None:
        self.sphere_path = path
        self.collision_info = CollisionInfo()
        self.object_info = ObjectInfo(state=state, step_up_height=0.4)
        self.step_up_ok = step_up_ok
        self.step_up_normals: list[Vector3] = []

    def step_up(self, collision_normal: Vector3) -> bool:
        self.step_up_normals.append(collision_normal.copy())
        self.sphere_path.step_up_normal = collision_normal.copy()
        return self.step_up_ok


def floor() -> BSPTree:
    return build_box_tree(Vector3(-5, -5, 0), Vector3(5, 5, 1))


def make_path(
    curr: Vector3, check: Vector3, second: bool = False, owner: Position | None = None, scale: float = 1.0
) -> SpherePath:
    """Origins ``curr`` and ``check`` (sphere centres 0.5 higher; sphere 1, if any, 1 m above sphere 0)."""
    path = SpherePath()
    path.local_sphere = [Sphere(Vector3(0, 0, R), R)]
    if second:
        path.local_sphere.append(Sphere(Vector3(0, 0, R + 1.0), R))
    path.curr_pos = Position(CELL, Frame(origin=curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(CELL, Frame(origin=check)), None)
    path.walk_interp = 1.0
    path.walkable_allowance = FLOOR_Z
    path.cache_localspace_sphere(owner if owner is not None else Position(CELL, Frame()), scale)
    return path


def f32_neighbour(value: float, steps: int) -> float:
    """The float32 ``steps`` representable values above (below, if negative) the positive ``value``."""
    bits = struct.unpack("<I", struct.pack("<f", value))[0] + steps
    return struct.unpack("<f", struct.pack("<I", bits))[0]


def close(a: Vector3, b: Vector3, tol: float = 1e-9) -> bool:
    return all(abs(p - q) <= tol for p, q in zip(a, b, strict=True))


def top_face(tree: BSPTree) -> Polygon:
    leaf = tree.root_node
    while not isinstance(leaf, BSPLeaf):
        assert leaf.neg_node is not None
        leaf = leaf.neg_node
    face = leaf.polys[4]
    assert isinstance(face, Polygon)
    return face


def touch(curr: Vector3, movement: Vector3) -> float:
    """``adjust_sphere_to_poly`` of the face z = 1 (N +z) for a sphere of radius 0.5."""
    face = Polygon([Vector3(-1, -1, 1), Vector3(1, -1, 1), Vector3(1, 1, 1), Vector3(-1, 1, 1)])
    return face.adjust_sphere_to_poly(Sphere(Vector3(), R), curr, movement)


class TestAdjustSphereToPoly:
    """CPolygon::adjust_sphere_to_poly with the reconstructed sign test (see its docstring)."""

    def test_start_within_radius_is_one(self) -> None:
        # radius <= |dist| fails (0.5 > 0.3) -> 1.0 (acclient.c:359528).
        assert touch(Vector3(0, 0, 1.3), UP * -1) == 1.0

    def test_parallel_is_zero(self) -> None:
        # |N·movement| < EPSILON -> 0.0 (acclient.c:359514, 359523).
        assert touch(Vector3(0, 0, 2), Vector3(1, 0, 0)) == 0.0

    def test_from_above_touches_at_plus_radius(self) -> None:
        # dist 1.0, N·m -1: (0.5 - 1.0)/-1 = 0.5 (acclient.c:359520).
        assert touch(Vector3(0, 0, 2), Vector3(0, 0, -1)) == 0.5

    def test_from_below_touches_at_minus_radius(self) -> None:
        # dist -1.0 <= 0 -> -radius (the lost compare at 359517): (-0.5 + 1)/1 = 0.5. ACE's
        # |movement|² <= r² reading would keep +0.5 here: (0.5 + 1)/1 = 1.5.
        assert touch(Vector3(0, 0, 0), Vector3(0, 0, 1)) == 0.5
        # From above with a short step: ACE's reading would give (-0.5 - 1)/-0.2 = 7.5 (through the face).
        short = Vector3(0, 0, -0.2)
        assert touch(Vector3(0, 0, 2), short) == pytest.approx(2.5)


class TestNodeQueries:
    def test_sphere_intersects_poly_records_touched_face_without_hit(self) -> None:
        tree = floor()
        top = top_face(tree)
        ball = Sphere(Vector3(0, 0, 1.45), R)
        # Touching the top (0.45 <= 0.4998) but moving along it: N·m = 0 is not < 0, so no hit,
        # yet pos_hits_sphere stores the struck polygon (acclient.c:360499-360504, 364213).
        found = tree.root_node.sphere_intersects_poly(ball, Vector3(0.1, 0, 0))
        assert not found.hit and found.polygon is top
        assert close(found.contact_pt, Vector3(0, 0, 1))  # the centre's foot on the top plane
        found = tree.root_node.sphere_intersects_poly(ball, Vector3(0, 0, -0.1))
        assert found.hit and found.polygon is top
        # Out of reach (0.5 > 0.4998): the caller's polygon comes back untouched.
        found = tree.root_node.sphere_intersects_poly(Sphere(Vector3(0, 0, 1.5), R), UP * -1, top)
        assert not found.hit and found.polygon is top

    def test_hits_walkable_needs_slope_and_half_radius_footing(self) -> None:
        tree = floor()
        path = make_path(Vector3(), Vector3())
        # Over the middle: top face walkable (1 > FLOOR_Z) and touched (acclient.c:364290-364291).
        assert tree.root_node.hits_walkable(path, Sphere(Vector3(0, 0, 1.45), R), UP)
        # Centre 0.05 above the top, 0.2 / 0.3 past the edge x = 5: the touch test's radsq is
        # 0.4998² - 0.05² = 0.2473, so both touch; check_small_walkable's is 0.5²/4 = 0.0625,
        # which 0.2² meets and 0.3² does not (acclient.c:364291, 360311).
        assert tree.root_node.hits_walkable(path, Sphere(Vector3(5.2, 0, 1.05), R), UP)
        assert not tree.root_node.hits_walkable(path, Sphere(Vector3(5.3, 0, 1.05), R), UP)
        # A steep face alone is never walkable: raise the allowance above 1 (acclient.c:360529).
        path.walkable_allowance = 1.0
        assert not tree.root_node.hits_walkable(path, Sphere(Vector3(0, 0, 1.45), R), UP)

    def test_find_walkable_backs_up_and_lowers_walk_interp(self) -> None:
        tree = floor()
        path = make_path(Vector3(), Vector3())
        ball = Sphere(Vector3(0, 0, 1.3), R)
        # dist 0.3, N·m = -0.5: t = (0.3 - 0.5)/-0.5 = 0.4, interp 0.6 (acclient.c:359553-359585).
        poly = tree.root_node.find_walkable(path, ball, Vector3(0, 0, -0.5), UP)
        assert poly is top_face(tree)
        assert ball.center.z == pytest.approx(1.5) and path.walk_interp == pytest.approx(0.6)


class TestPlacementAndEthereal:
    def test_placement_inside_solid_is_refused(self) -> None:
        path = make_path(Vector3(0, 0, 0.2), Vector3(0, 0, 0.2))
        path.insert_type = InsertType.PLACEMENT
        # Centre inside the solid leaf with the centre check on (acclient.c:361346-361352).
        assert floor().find_collisions(Sweep(path), 1.0) == TS.COLLIDED

    def test_placement_clear_is_ok_and_bldg_check_drops_centre_check(self) -> None:
        path = make_path(Vector3(0, 0, 1.2), Vector3(0, 0, 1.2))
        path.insert_type = InsertType.PLACEMENT
        assert floor().find_collisions(Sweep(path), 1.0) == TS.OK
        # Deep inside, no face in reach: only the centre check finds it. bldg_check with
        # hits_interior_cell turns it off (acclient.c:361347-361348) -> OK.
        tall = build_box_tree(Vector3(-5, -5, -5), Vector3(5, 5, 5))
        path = make_path(Vector3(), Vector3())
        path.obstruction_ethereal = True
        assert tall.find_collisions(Sweep(path), 1.0) == TS.COLLIDED
        path.bldg_check = True
        path.hits_interior_cell = True
        assert tall.find_collisions(Sweep(path), 1.0) == TS.OK

    def test_placement_insert_pushes_out_along_face(self) -> None:
        path = make_path(Vector3(0, 0, 0.8), Vector3(0, 0, 0.8))
        # Centre 0.3 above the top: pushed to +radius (acclient.c:360849, 360147-360160), the
        # second try is clear (0.5 > 0.4998) -> ADJUSTED by (0, 0, 0.2) (acclient.c:360894-360912).
        assert floor().placement_insert(Sweep(path)) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(0, 0, 1.0))
        assert close(path.global_sphere[0].center, Vector3(0, 0, 1.5))

    def test_placement_insert_clear_is_ok(self) -> None:
        path = make_path(Vector3(0, 0, 2), Vector3(0, 0, 2))
        assert floor().placement_insert(Sweep(path)) == TS.OK  # first try clear, i == 0 (acclient.c:360894)

    def test_placement_insert_offset_is_not_scaled(self) -> None:
        # Owner at scale 2: origin z 1.6 -> centre 2.1 -> tree space 1.05, 0.05 above the top with
        # radius 0.25: pushed to 1.25 (+0.2 in tree space). Retail adds that 0.2 to check_pos
        # unscaled (no scale at acclient.c:360896-360911), not the 0.4 a scaled offset would give.
        path = make_path(Vector3(0, 0, 1.6), Vector3(0, 0, 1.6), scale=2.0)
        assert floor().placement_insert(Sweep(path)) == TS.ADJUSTED
        # float32 tolerance: the tree-space centre, the pushed centre and the origin are each
        # stored as float32 on the way (a few ulps of 1.8); 0.2 and 0.4 are 0.2 apart.
        assert close(path.check_pos.frame.origin, Vector3(0, 0, 1.8), tol=1e-6)

    def test_placement_insert_deep_inside_adjusts_by_nothing(self) -> None:
        # Centre (0,0,0.5) in the floor slab, no face within 0.4998: the first try finds only the
        # solid centre (no polygon) and doubles rad (acclient.c:360881). With rad 1 both splits
        # straddle, the solid side records no polygon and the empty side answers 0
        # (BSPNODE::sphere_intersects_solid_poly, acclient.c:363765-363776): "clear" on try 2,
        # so retail reports ADJUSTED with a zero offset.
        path = make_path(Vector3(0, 0, 0), Vector3(0, 0, 0))
        assert floor().placement_insert(Sweep(path)) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(0, 0, 0))


class TestCheckWalkableAndFloorZ:
    def test_resting_on_floor_is_walkable(self) -> None:
        path = make_path(Vector3(0, 0, 0.95), Vector3(0, 0, 0.95))
        path.check_walkable = True
        # hits_walkable -> (1 != 0) + 1 = COLLIDED (acclient.c:361064).
        assert floor().find_collisions(Sweep(path), 1.0) == TS.COLLIDED
        path = make_path(Vector3(0, 0, 1.1), Vector3(0, 0, 1.1))
        path.check_walkable = True
        assert floor().find_collisions(Sweep(path), 1.0) == TS.OK  # out of reach: (0 != 0) + 1

    @pytest.mark.parametrize(
        ("nz", "walkable"),
        [(FLOOR_Z, False), (f32_neighbour(FLOOR_Z, 1), True), (f32_neighbour(FLOOR_Z, -1), False)],
    )
    def test_slope_at_floor_z(self, nz: float, walkable: bool) -> None:
        # A ramp face through the origin with N = (sqrt(1 - nz²), 0, nz); walkable_hits_sphere
        # needs N·up > walkable_allowance strictly (acclient.c:360529), allowance = FLOOR_Z. The
        # plane's N.z is a float32, so the neighbours tried are the float32 ones.
        nx = math.sqrt(1.0 - nz * nz)
        ramp = Polygon([Vector3(x, y, -nx * x / nz) for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
        ramp.plane = Plane(Vector3(nx, 0, nz), 0.0)
        tree = BSPTree(BSPLeaf(0, solid=True, sphere=Sphere(Vector3(), 3.0), polys=[ramp]))
        path = make_path(Vector3(), Vector3())
        path.check_walkable = True
        path.localspace_sphere = [Sphere(Vector3(nx, 0, nz) * 0.3, R)]
        expected = TS.COLLIDED if walkable else TS.OK
        assert tree.find_collisions(Sweep(path), 1.0) == expected


class TestStepDown:
    def lowered(self, z: float, amt: float = 0.5) -> SpherePath:
        path = make_path(Vector3(0, 0, z), Vector3(0, 0, z))
        path.step_down = True
        path.step_down_amt = amt
        return path

    def test_within_step_down_lands_on_floor(self) -> None:
        # Already lowered by the caller to centre 1.3 (dist 0.3). movement = -(0.5·1)·z (acclient.c:361211):
        # t = 0.4, interp 0.6; check_pos rises 0.2 (acclient.c:361258-361270).
        path = self.lowered(0.8)
        sweep = Sweep(path)
        tree = floor()
        assert tree.find_collisions(sweep, 1.0) == TS.ADJUSTED
        assert path.walkable is top_face(tree)
        assert close(path.check_pos.frame.origin, Vector3(0, 0, 1.0))
        assert path.walk_interp == pytest.approx(0.6)
        info = sweep.collision_info
        assert info.contact_plane_valid and not info.contact_plane_is_water  # acclient.c:361274-361283
        assert close(info.contact_plane.N, UP) and info.contact_plane.d == pytest.approx(-1.0)
        assert info.contact_plane_cell_id == CELL
        assert close(path.walkable_check_pos.center, Vector3(0, 0, 1.5))  # set_walkable (acclient.c:361285)
        assert close(path.walkable_up, UP) and path.walkable_scale == 1.0

    def test_beyond_step_down_is_ok(self) -> None:
        # Lowered sphere still 0.6 above the top (> 0.4998): nothing walkable touched
        # -> OK (acclient.c:361290).
        path = self.lowered(1.1)
        assert floor().find_collisions(Sweep(path), 1.0) == TS.OK
        assert close(path.check_pos.frame.origin, Vector3(0, 0, 1.1)) and path.walk_interp == 1.0

    def test_too_deep_is_refused_by_interp_floor(self) -> None:
        # Centre 0.3 below the top: gap -0.8, t 1.6, interp -0.6 < -0.5 -> no adjust (acclient.c:359575).
        path = self.lowered(0.2)
        assert floor().find_collisions(Sweep(path), 1.0) == TS.OK
        assert path.walk_interp == 1.0


class TestCollide:
    def test_falling_onto_floor_flags_collide_then_lands(self) -> None:
        # Airborne, centre 1.8 -> 1.3: the top is hit (N·m -0.5 < 0): set_collide with the global
        # normal, walkable_allowance = z_for_landing, ADJUSTED (acclient.c:361457-361461).
        path = make_path(Vector3(0, 0, 1.3), Vector3(0, 0, 0.8))
        sweep = Sweep(path)
        tree = floor()
        assert tree.find_collisions(sweep, 1.0) == TS.ADJUSTED
        assert path.collide and close(path.step_up_normal, UP)
        assert path.walkable_allowance == LANDING_Z and path.walk_interp == 1.0
        assert close(path.backup_check_pos.frame.origin, Vector3(0, 0, 0.8))
        # The collide pass backs the sphere onto the top (t 0.4 of -0.5) and sets the contact plane
        # and walkable (acclient.c:361370-361404).
        assert tree.find_collisions(sweep, 1.0) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(0, 0, 1.0))
        assert path.walk_interp == pytest.approx(0.6)
        info = sweep.collision_info
        assert info.contact_plane_valid and close(info.contact_plane.N, UP)
        assert info.contact_plane.d == pytest.approx(-1.0) and info.contact_plane_cell_id == CELL
        assert path.walkable is top_face(tree)

    def test_collide_without_walkable_is_ok(self) -> None:
        # Into a wall face (-x, not walkable): find_walkable changes nothing -> OK (acclient.c:361498).
        wall = build_box_tree(Vector3(1, -5, 0), Vector3(2, 5, 3))
        path = make_path(Vector3(0.2, 0, 1), Vector3(0.8, 0, 1))
        path.collide = True
        assert wall.find_collisions(Sweep(path), 1.0) == TS.OK
        assert close(path.check_pos.frame.origin, Vector3(0.8, 0, 1))

    def test_airborne_sphere_one_hit_sets_collision_normal(self) -> None:
        # A ledge (-z face at 2.5) only sphere 1 (centre 2.5 -> 2.6, moving by sphere 0's step) reaches:
        # set_collision_normal, COLLIDED (acclient.c:361466-361474).
        ledge = build_box_tree(Vector3(-5, -5, 2.5), Vector3(5, 5, 3))
        path = make_path(Vector3(0, 0, 1.0), Vector3(0, 0, 1.1), second=True)
        sweep = Sweep(path)
        assert ledge.find_collisions(sweep, 1.0) == TS.COLLIDED
        assert sweep.collision_info.collision_normal_valid
        assert close(sweep.collision_info.collision_normal, Vector3(0, 0, -1))
        assert not path.collide


class TestContact:
    wall = staticmethod(
        lambda: build_boxes_tree(
            [(Vector3(-5, -5, 0), Vector3(5, 5, 1)), (Vector3(1, -5, 1), Vector3(2, 5, 4))]
        )
    )

    def test_walking_into_wall_steps_up_then_slides(self) -> None:
        # Sphere 0 heads into the -x face (dist 0.4, N·m -0.4): step_sphere_up with the global normal
        # (acclient.c:361418, 361086); step_up fails -> step_up_slide (acclient.c:361089) drops the
        # contact plane and slides along step_up_normal on the last known plane: direction
        # (-1,0,0)x(0,0,1) = (0,1,0), step (0.4,0.3,0) keeps (0,0.3,0): moved by (-0.4,0,0), SLID.
        path = make_path(Vector3(0.2, 0, 1.0), Vector3(0.6, 0.3, 1.0))
        sweep = Sweep(path, OIS.CONTACT)
        sweep.collision_info.set_contact_plane(Plane.horizontal(1.0), False)
        sweep.collision_info.last_known_contact_plane = Plane.horizontal(1.0)
        assert self.wall().find_collisions(sweep, 1.0) == TS.SLID
        assert close(sweep.step_up_normals[0], Vector3(-1, 0, 0))
        assert not sweep.collision_info.contact_plane_valid
        # In float32 (CSphere::slide_sphere, acclient.c:358944-358951): the step's x is
        # f32(0 + (0.6f - 0.2f)) = f32(0.40000002086) = 0.40000003576 (a tie, to even), the slide
        # keeps none of it, and the origin x is f32(0.6f - 0.40000003576) = 0.19999998808.
        step_x = f32(0.0 + (f32(0.6) - f32(0.2)))
        assert step_x == 0.40000003576278687
        assert path.check_pos.frame.origin.exactly_equals(Vector3(f32(f32(0.6) - step_x), 0.3, 1.0))
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0))

    def test_step_up_success_is_ok(self) -> None:
        path = make_path(Vector3(0.2, 0, 1.0), Vector3(0.6, 0, 1.0))
        sweep = Sweep(path, OIS.CONTACT, step_up_ok=True)
        assert self.wall().find_collisions(sweep, 1.0) == TS.OK  # acclient.c:361087
        assert len(sweep.step_up_normals) == 1

    def test_step_up_normal_is_rotated_to_global(self) -> None:
        owner = Position(CELL, Frame())
        owner.frame.set_heading(90.0)
        path = make_path(Vector3(), Vector3(), owner=owner)
        sweep = Sweep(path, step_up_ok=True)
        assert BSPTree.step_sphere_up(sweep, Vector3(-1, 0, 0)) == TS.OK
        # localspace_pos rotates local -x (acclient.c:361075-361083): heading 90 maps local +y to +x.
        assert close(sweep.step_up_normals[0], owner.frame.localtoglobalvec(Vector3(-1, 0, 0)))
        assert close(sweep.step_up_normals[0], Vector3(0, 1, 0), 1e-6)

    def test_sphere_one_into_ledge_slides_sphere_zero(self) -> None:
        # Sphere 1 (centre z 2.5) runs into the -x face of a ledge above sphere 0's reach: slide_sphere
        # with global_sphere[0] from global_curr_center[0] (acclient.c:361427, 361048). Step (0.3,0.2,0),
        # direction (-1,0,0)x(0,0,1) = (0,1,0): keep (0,0.2,0), move by (-0.3,0,0) -> SLID.
        ledge = build_boxes_tree(
            [(Vector3(-5, -5, 0), Vector3(5, 5, 1)), (Vector3(1, -5, 2.2), Vector3(2, 5, 4))]
        )
        path = make_path(Vector3(0.4, 0, 1.0), Vector3(0.7, 0.2, 1.0), second=True)
        sweep = Sweep(path, OIS.CONTACT)
        sweep.collision_info.set_contact_plane(Plane.horizontal(1.0), False)
        assert ledge.find_collisions(sweep, 1.0) == TS.SLID
        assert close(path.check_pos.frame.origin, Vector3(0.4, 0.2, 1.0))
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0))
        assert sweep.step_up_normals == []

    def test_negative_polygon_hits(self) -> None:
        tree = floor()
        # Both spheres touch nothing headed into; sphere 0 touches the top while sliding along it:
        # set_neg_poly_hit(1, N) -> reversed normal stored, OK (acclient.c:361440-361441).
        path = make_path(Vector3(0, 0, 0.95), Vector3(0.1, 0, 0.95), second=True)
        assert tree.find_collisions(Sweep(path, OIS.CONTACT), 1.0) == TS.OK
        assert path.neg_poly_hit and path.neg_step_up
        assert close(path.neg_collision_normal, Vector3(0, 0, -1))
        # A sphere-1 touch wins and gives step-up flag 0 (acclient.c:361434): a ceiling face
        # (-z at z 2.9) that sphere 1 (centre 2.45) touches while moving sideways.
        ceiling = build_boxes_tree(
            [(Vector3(-5, -5, 0), Vector3(5, 5, 1)), (Vector3(-5, -5, 2.9), Vector3(5, 5, 4))]
        )
        path = make_path(Vector3(0, 0, 0.95), Vector3(0.1, 0, 0.95), second=True)
        assert ceiling.find_collisions(Sweep(path, OIS.CONTACT), 1.0) == TS.OK
        assert path.neg_poly_hit and not path.neg_step_up
        assert close(path.neg_collision_normal, Vector3(0, 0, 1))
        # One sphere: the back-face record is inside the num_sphere > 1 test (acclient.c:361421).
        path = make_path(Vector3(0, 0, 0.95), Vector3(0.1, 0, 0.95))
        assert tree.find_collisions(Sweep(path, OIS.CONTACT), 1.0) == TS.OK
        assert not path.neg_poly_hit


class TestPathClipped:
    wall = staticmethod(lambda: build_box_tree(Vector3(1, -5, 0), Vector3(2, 5, 3)))

    def test_without_perfect_clip_collides_with_face_normal(self) -> None:
        path = make_path(Vector3(0.2, 0, 1), Vector3(0.8, 0, 1))
        sweep = Sweep(path, OIS.PATH_CLIPPED)
        assert self.wall().find_collisions(sweep, 1.0) == TS.COLLIDED  # acclient.c:361136-361148
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0))

    def test_perfect_clip_backs_up_to_touch(self) -> None:
        # adjust_sphere_to_poly: dist 0.8 at curr, N·m -0.6 -> t 0.5, centre x 0.5 clear (0.5 > 0.4998):
        # lower bound 0.5 (acclient.c:360974); bisection toward 1 keeps hitting; ends at t 0.5
        # (acclient.c:361017): check_pos moves -0.3 in x, ADJUSTED (acclient.c:361161-361173).
        # ACE reads the loop test the other way round and fails here (COLLIDED).
        path = make_path(Vector3(0.2, 0, 1), Vector3(0.8, 0, 1))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert self.wall().find_collisions(sweep, 1.0) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(0.5, 0, 1), 1e-6)
        assert close(sweep.collision_info.collision_normal, Vector3(-1, 0, 0))

    def test_perfect_clip_bisects_when_already_touching(self) -> None:
        # Curr centre x 0.55 is 0.45 from the face's plane (< radius): adjust_sphere_to_poly gives 1.0
        # (acclient.c:359528), the first loop stops (reconstructed test at acclient.c:360954) and
        # bisection runs on [0, 1]: mids 0.5, 0.25, ..., 0.015625 all still hit (dist <= 0.4998),
        # the bracket drops under 0.02 (acclient.c:361006) and the sphere goes back to lower = 0
        # (acclient.c:361017): check_pos moves -0.1 in x, ADJUSTED. Without the stop the first
        # loop would retry t = 1.0 fifteen times and fail (COLLIDED).
        path = make_path(Vector3(0.55, 0, 1), Vector3(0.65, 0, 1))
        sweep = Sweep(path, OIS.PATH_CLIPPED | OIS.PERFECT_CLIP)
        assert self.wall().find_collisions(sweep, 1.0) == TS.ADJUSTED
        assert close(path.check_pos.frame.origin, Vector3(0.55, 0, 1), 1e-6)

    def test_sphere_one_is_not_tested(self) -> None:
        # Retail's path-clipped arm asks only sphere 0 (acclient.c:361447-361492). ACE also tests
        # sphere 1 for path-clipped bodies and would return COLLIDED here.
        ledge = build_box_tree(Vector3(-5, -5, 2.5), Vector3(5, 5, 3))
        path = make_path(Vector3(0, 0, 1.0), Vector3(0, 0, 1.1), second=True)
        sweep = Sweep(path, OIS.PATH_CLIPPED)
        assert ledge.find_collisions(sweep, 1.0) == TS.OK
        assert not sweep.collision_info.collision_normal_valid


class TestSpherePathHelpers:
    def test_cache_localspace_sphere(self) -> None:
        owner = Position(EAST_CELL, Frame(origin=Vector3(2, 0, 1)))
        owner.frame.set_heading(90.0)
        path = make_path(Vector3(1, 0, 0), Vector3(1, 0, 0.5), owner=owner, scale=2.0)
        # Check centre (1,0,1) in CELL is (1-192-2, 0, 0) from the owner, rotated into its frame
        # and halved (acclient.c:313872-313895).
        expect = owner.frame.globaltolocalvec(Vector3(1 - 192 - 2, 0, 0)) * 0.5
        assert close(path.localspace_sphere[0].center, expect, 1e-9)
        assert path.localspace_sphere[0].radius == 0.25
        curr = owner.frame.globaltolocalvec(Vector3(1 - 192 - 2, 0, -0.5)) * 0.5
        assert close(path.localspace_curr_center[0], curr, 1e-9)
        assert close(path.localspace_z, UP, 1e-9)  # yaw only: global up stays up (acclient.c:313913-313919)
        assert close(path.localspace_low_point, expect - UP * 0.25, 1e-9)
        assert path.localspace_pos.objcell_id == EAST_CELL

    def test_adjust_check_pos(self) -> None:
        path = make_path(Vector3(), Vector3(10, 0, 0))
        path.adjust_check_pos(EAST_CELL)
        # Outdoor: offset from EAST's block to CELL's = (-192, 0, 0) (acclient.c:313968-313975).
        assert path.check_pos.objcell_id == EAST_CELL
        assert close(path.check_pos.frame.origin, Vector3(-182, 0, 0))
        assert close(path.global_sphere[0].center, Vector3(-182, 0, 0.5))
        path.adjust_check_pos(0xAAB40105)  # an indoor cell: id only
        assert close(path.check_pos.frame.origin, Vector3(-182, 0, 0))
        assert path.check_pos.objcell_id == 0xAAB40105

    def test_check_walkables_halves_radius_each_call(self) -> None:
        path = make_path(Vector3(), Vector3())
        assert path.check_walkables()  # no walkable -> 1 (acclient.c:313467)
        face = top_face(floor())
        path.set_walkable(Sphere(Vector3(5.2, 0, 1.5), R), face, UP, Position(CELL, Frame()), 1.0)
        # radius 0.25: 0.2 past the edge is within reach (acclient.c:313481).
        assert path.check_walkables() and path.walkable_check_pos.radius == 0.25
        # radius 0.125 next time: 0.2 past is not.
        assert not path.check_walkables() and path.walkable_check_pos.radius == 0.125

    def test_precipice_slide(self) -> None:
        face = top_face(floor())
        path = make_path(Vector3(4.9, 0, 1), Vector3(5.2, 0.1, 1))
        path.set_walkable(Sphere(Vector3(5.2, 0.1, 1.5), R), face, UP, Position(CELL, Frame()), 1.0)
        info = CollisionInfo()
        info.set_contact_plane(Plane.horizontal(1.0), False)
        # Crossed edge x = 5 has inward normal (-1,0,0); the step (0.3,0.1,0) runs against it, so no
        # flip (acclient.c:314026); slide along (-1,0,0)x(0,0,1) = (0,1,0): keep (0,0.1,0) -> SLID.
        assert path.precipice_slide(info) == TS.SLID
        assert path.walkable is None and not path.step_up
        assert close(path.check_pos.frame.origin, Vector3(4.9, 0.1, 1))
        assert close(info.collision_normal, Vector3(-1, 0, 0))

    def test_precipice_slide_without_crossed_edge_collides(self) -> None:
        face = top_face(floor())
        path = make_path(Vector3(), Vector3(0.1, 0, 1))
        path.set_walkable(Sphere(Vector3(0.1, 0, 1.5), R), face, UP, Position(CELL, Frame()), 1.0)
        assert path.precipice_slide(CollisionInfo()) == TS.COLLIDED  # acclient.c:314037
        assert path.walkable is None
        with pytest.raises(ValueError):
            path.precipice_slide(CollisionInfo())


def test_plane_localtoglobal_across_blocks() -> None:
    owner = Position(EAST_CELL, Frame(origin=Vector3(2, 0, 1)))
    to = Position(CELL, Frame())
    # Local top plane z = 1 -> point (0,0,1) -> global (194, 0, 2) in CELL's block (acclient.c:467689-467703).
    plane = plane_localtoglobal(to, owner, Plane(UP, -1.0))
    assert close(plane.N, UP) and plane.d == pytest.approx(-2.0)
