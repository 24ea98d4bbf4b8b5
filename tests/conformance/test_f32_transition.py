"""Float32 at rest in the transition machinery (CTransition, SPHEREPATH, COLLISIONINFO, OBJECTINFO).

Each expected value is worked from the decompiled lines cited beside it: a ``float`` field,
local or spill is narrowed with ``f32`` where retail stores it, and everything between two stores
is double arithmetic in retail's order. Each case also checks that the float64-at-rest answer
differs, so the test pins the narrowing and not only the formula.
"""

from __future__ import annotations

import math
from typing import ClassVar

import pytest

from acphys.constants import SMALL_STEP_DOWN_HEIGHT
from acphys.flags import ObjectInfoState as OI
from acphys.flags import PhysicsState as PS
from acphys.flags import TransitionState as TS
from acphys.geometry.bsp_builder import build_box_tree
from acphys.geometry.plane import Plane
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32, is_f32
from acphys.setup import Setup, human_setup
from acphys.transition import placement
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo
from acphys.transition.sphere_path import SpherePath
from acphys.transition.transition import Transition
from acphys.world.obj_cell import CellInfo
from acphys.world.static_objects import add_static_object
from acphys.world.world import World
from support import LANDBLOCK

GROUND = 50.0
#: The dart: one sphere of radius 0.2 at its origin.
DART_RADIUS = 0.2


def dart(world: World, origin: V) -> PhysicsObj:
    """A gravity-free dart entered into ``world`` at ``origin``."""
    body = PhysicsObj(world, "dart", PartArray(Setup("dart", spheres=[Sphere(V(), DART_RADIUS)])))
    body.state = PS(0)
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, origin), Frame(origin)))
    return body


def dart_path(start: V, offset: V) -> Transition:
    """A transition for a dart at ``start`` moving by ``offset`` (positions are float32)."""
    t = Transition(World())
    t.init_sphere([Sphere(V(), DART_RADIUS)], 1.0)
    begin = Position(outdoor_cell_id(LANDBLOCK, start), Frame(start))
    end = begin.copy()
    end.frame.origin = end.frame.origin + offset
    t.init_path(None, begin, end)
    return t


# --- calc_num_steps: the dart ------------------------------------------------------------------


class TestDartSteps:
    def test_a_one_metre_quantum_is_five_sub_steps(self) -> None:
        t = dart_path(V(96.1, 96.0, 52.0), V(1.0, 0.0, 0.0))
        # SPHEREPATH::init_sphere stores the radius as a float (acclient.c:313681): f32(0.2).
        radius = t.sphere_path.local_sphere[0].radius
        assert radius == f32(0.2) and radius > 0.2
        offset, per_step, steps = t.calc_num_steps()
        # Position::get_offset (acclient.c:311704-311714): the end is stored at f32(96.1) + 1,
        # exact in float32, so the offset is exactly 1 m.
        assert offset.exactly_equals(V(1.0, 0.0, 0.0))
        # calc_num_steps (acclient.c:311794-311795, 311822-311835): dist / (1.0 * radius) in the
        # FPU with the float radius, 4.99999992549..., whose ceiling is 5; each step is the
        # offset times 1/5, stored as float.
        ratio = math.sqrt(1.0) / (1.0 * f32(0.2))
        assert ratio < 5.0 and math.ceil(ratio) == 5
        assert steps == 5
        assert per_step.exactly_equals(V(f32(1.0 / 5.0 * 1.0), 0.0, 0.0))
        # Float64 at rest took six: with a 0.2 radius, an offset a rounding over 1 m (as double
        # positions give) puts the ratio just past 5. The float radius leaves room for it.
        stale = math.nextafter(1.0, 2.0)
        assert math.ceil(stale / (1.0 * DART_RADIUS)) == 6
        assert math.ceil(stale / (1.0 * f32(DART_RADIUS))) == 5

    def test_the_float_radius_alone_decides_a_two_radius_step(self) -> None:
        # f32(0.4) is 2 * f32(0.2) exactly: with the float radius the ratio is 2.0, two steps
        # (acclient.c:311822-311835); with a double 0.2 it would be 2.00000003, three. (The
        # start, 1/16 m into the block, keeps start + f32(0.4) exact in float32.)
        t = dart_path(V(0.0625, 96.0, 52.0), V(f32(0.4), 0.0, 0.0))
        offset, per_step, steps = t.calc_num_steps()
        assert offset.x == f32(0.4) == 2.0 * f32(0.2)
        assert math.ceil(offset.x / DART_RADIUS) == 3
        assert steps == 2
        assert per_step.x == f32(1.0 / 2.0 * offset.x)

    def test_a_one_metre_sweep_takes_five_steps_of_the_float_step(self, monkeypatch) -> None:
        world = World()
        world.set_flat_ground(LANDBLOCK, GROUND)
        body = dart(world, V(96.1, 96.0, 52.0))
        validated: list[TS] = []
        original = Transition.validate_transition

        def counting(self: Transition, ts: TS) -> TS:
            validated.append(ts)
            return original(self, ts)

        monkeypatch.setattr(Transition, "validate_transition", counting)
        target = body.position.copy()
        target.frame.origin = target.frame.origin + V(1.0, 0.0, 0.0)
        t = body.transition(body.position, target)
        assert t is not None
        # find_transitional_position (acclient.c:313241-313320): five steps, each adding the
        # float step f32(0.2) to the float check_pos origin (acclient.c:313300-313306).
        assert validated == [TS.OK] * 5
        x = f32(96.1)
        for _ in range(5):
            x = f32(x + f32(0.2))
        assert t.sphere_path.curr_pos.frame.origin.x == x


# --- adjust_offset --------------------------------------------------------------------------------


class TestAdjustOffset:
    def test_a_step_into_the_contact_plane_loses_its_float_component(self) -> None:
        t = Transition(World())
        info = t.collision_info
        n = V(0.0, 0.3, 1.0).normalized()
        info.contact_plane_valid = True
        info.contact_plane = Plane(n, 0.0)
        x, y, z = f32(0.3), f32(0.1), f32(-0.2)
        result = t.adjust_offset(V(x, y, z))
        # acclient.c:311909-311911: the component into the plane is a float local (offseta);
        # acclient.c:311943-311949: x and y lose it times N in the FPU, z loses a float spill.
        into = f32(z * n.z + y * n.y + x * n.x)
        assert into <= 0.0
        expected = V(x - into * n.x, y - into * n.y, z - f32(into * n.z))
        assert result.exactly_equals(expected)
        into64 = z * n.z + y * n.y + x * n.x
        assert not result.exactly_equals(V(x - into64 * n.x, y - into64 * n.y, z - into64 * n.z))

    def test_a_step_into_the_sliding_normal_loses_it_with_float_spills(self) -> None:
        t = Transition(World())
        t.init_sliding_normal(V(-0.8, 0.6, 0.0))
        s = t.collision_info.sliding_normal
        x, y, z = f32(0.3), f32(-0.3), f32(0.05)
        result = t.adjust_offset(V(x, y, z))
        # acclient.c:311984-311995: the dot runs x, z, y; the y and z products are float spills
        # (v22, v23), the x product is not.
        along = x * s.x + z * s.z + y * s.y
        assert along < 0.0
        expected = V(x - along * s.x, y - f32(along * s.y), z - f32(along * s.z))
        assert result.exactly_equals(expected)
        assert not result.exactly_equals(V(x - along * s.x, y - along * s.y, z - along * s.z))


# --- OBJECTINFO::validate_walkable ---------------------------------------------------------------


def test_a_step_down_into_a_slope_stores_a_float_depth_and_walk_interp() -> None:
    obj = ObjectInfo(state=OI.CONTACT | OI.ON_WALKABLE)
    path = SpherePath()
    path.step_down = True
    path.step_down_amt = f32(0.4)
    path.walk_interp = 1.0
    info = CollisionInfo()
    n = V(0.0, 0.3, 1.0).normalized()
    plane = Plane(n, 0.0)
    sphere = Sphere(V(0.0, 0.0, 0.45), f32(0.48))
    ts = obj.validate_walkable(sphere, plane, False, 0.0, path, info, 0xA9B40001)
    assert ts == TS.ADJUSTED
    # acclient.c:314224-314228: the distance of the sphere's bottom (in the FPU); 314253: the
    # depth is a float local (patha); 314261-314264: the new interp, stored as float.
    c, r = sphere.center, sphere.radius
    dist = c.y * n.y + (c.z - r) * n.z + c.x * n.x + plane.d + 0.0
    depth = f32(dist / n.z)
    interp = (1.0 - -1.0 / (f32(0.4) * 1.0) * depth) * 1.0
    assert path.walk_interp == f32(interp)
    assert path.walk_interp != (1.0 - -1.0 / (f32(0.4) * 1.0) * (dist / n.z)) * 1.0
    # acclient.c:314266-314269: the sphere rises by the float depth.
    assert path.check_pos.frame.origin.z == f32(0.0 - depth)


# --- SPHEREPATH ----------------------------------------------------------------------------------


def test_init_sphere_narrows_the_scale_and_the_scaled_radius() -> None:
    path = SpherePath()
    path.init_sphere([Sphere(V(0.0, 0.0, f32(0.3)), f32(0.2))], 1.1)
    # acclient.c:313646: scale is a float parameter; 313673-313681: every product is a float.
    scale = f32(1.1)
    sphere = path.local_sphere[0]
    assert sphere.radius == f32(scale * f32(0.2))
    assert sphere.radius != f32(1.1 * 0.2)
    assert sphere.center.exactly_equals(V(0.0, 0.0, f32(scale * f32(0.3))))
    # acclient.c:313688-313693: the low point is the float centre minus the float radius.
    assert path.local_low_point.z == f32(sphere.center.z - sphere.radius)


def test_the_localspace_low_point_keeps_its_x_product_in_the_fpu() -> None:
    path = SpherePath()
    path.init_sphere([Sphere(V(0.0, 0.0, 0.475), 0.48)], 1.0)
    pos = Position(0xA9B40001, Frame(V(96.0, 96.0, 50.0)))
    path.init_path(None, pos, pos)
    path.set_check_pos(pos, None)
    tilted = Frame(V(95.5, 96.25, 49.75))
    tilted.set_rotate(1.0, 0.2, 0.1, 0.0)
    path.cache_localspace_sphere(Position(0xA9B40001, tilted), 1.0)
    low = path.localspace_sphere[0]
    c, r, z = low.center, low.radius, path.localspace_z
    # acclient.c:313949-313958: the y and z products are float spills (v25, v26), the x one
    # is subtracted straight from the FPU.
    expected = V(c.x - r * z.x, c.y - f32(r * z.y), c.z - f32(r * z.z))
    assert path.localspace_low_point.exactly_equals(expected)
    assert not path.localspace_low_point.exactly_equals(V(c.x - f32(r * z.x), expected.y, expected.z))


# --- constants and fabricated planes ---------------------------------------------------------------


def test_float_literals_of_the_transition_are_float32() -> None:
    # step_up / transitional_insert's 0.039999999 (acclient.c:312807, 312966) and
    # find_placement_pos's 3.1415999 (acclient.c:313096) and 0.47999999 (313077) are float
    # constants: the decompiler's eight digits of f32(0.04), f32(3.1416) and f32(0.48).
    assert SMALL_STEP_DOWN_HEIGHT == f32(0.04) != 0.04
    assert placement.PLACEMENT_PI == f32(3.1416) != 3.1415999
    assert f32(0.48) == placement.PLACEMENT_MIN_RADIUS


def test_the_fabricated_floor_has_a_float_distance() -> None:
    world = World()
    body = PhysicsObj(world, "faller", PartArray(human_setup()))
    body.state = PS.GRAVITY
    point = V(96.0, 96.0, 60.3)
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, point), Frame(point)))
    t = Transition(world, body)
    t.init_object(body, OI.DEFAULT)
    t.init_sphere(body.part_array.get_sphere(), 1.0)
    t.init_path(body.cell, body.position, body.position)
    t.sphere_path.set_check_pos(t.sphere_path.curr_pos, t.sphere_path.curr_cell)
    t.collision_info.frames_stationary_fall = 2
    t.validate_transition(TS.OK)
    sphere = t.sphere_path.global_sphere[0]
    # acclient.c:312294-312299: d = radius - ((y + x) * 0 + z), stored into the plane's float d.
    height = (sphere.center.y + sphere.center.x) * 0.0 + sphere.center.z
    assert t.collision_info.contact_plane.d == f32(sphere.radius - height)
    assert f32(sphere.radius - height) != 0.48 - (60.3 + 0.475)


# --- check_other_cells walks the live cell array -------------------------------------------------


class _Cell:
    """A stand-in cell: records each ``find_collisions`` and may rebuild the cell array the way
    a nested insert does (step_up -> step_down -> transitional_insert -> check_other_cells ->
    ``find_cell_list``, which refills the same transition's array)."""

    def __init__(self, cell_id: int, visits: list[str], name: str) -> None:
        self.id = cell_id
        self.name = name
        self.visits = visits
        self.rebuild: list[_Cell] | None = None

    def find_collisions(self, transition: Transition) -> TS:
        self.visits.append(self.name)
        if self.rebuild is not None:
            cells = transition.cell_array
            cells.clear()
            for cell in self.rebuild:
                cells.add_cell(cell.id, cell)  # type: ignore[arg-type]
        return TS.OK


class _FixedCellList(Transition):
    """A transition whose ``find_cell_list`` keeps a prepared array and names ``home`` as the
    cell holding sphere 0."""

    home: _Cell | None = None
    prepared: ClassVar[list[_Cell]] = []

    def _find_cell_list(self, want_cell: bool):  # type: ignore[override]
        self.cell_array.cells = [CellInfo(cell.id, cell) for cell in self.prepared]  # type: ignore[arg-type]
        return self.home if want_cell else None


def test_check_other_cells_goes_on_in_the_rebuilt_array() -> None:
    visits: list[str] = []
    a, b, c = (_Cell(0xA9B40001 + i, visits, name) for i, name in enumerate("abc"))
    d, e, f = (_Cell(0xA9B40011 + i, visits, name) for i, name in enumerate("def"))
    b.rebuild = [a, d, e, f]
    t = _FixedCellList(World())
    t.home = a
    t.prepared = [a, b, c]
    t.sphere_path.check_pos = Position(0xA9B40001, Frame(V(96.0, 96.0, 50.0)))
    ts = t.check_other_cells(a)
    # acclient.c:312404-312424: the loop reads cells.data[i] and num_cells from the transition
    # on every pass. b (index 1) rebuilds the array to [a, d, e, f]; the walk goes on at index 2
    # of the rebuilt array: e, then f. c (index 2 of the old array) and d (index 1 of the new
    # one) are never asked; a walk over a copy of the old array would have asked c.
    assert visits == ["b", "e", "f"]
    assert ts == TS.OK and t.sphere_path.check_cell is a


def test_check_other_cells_stops_when_the_rebuilt_array_is_shorter() -> None:
    visits: list[str] = []
    a, b, c = (_Cell(0xA9B40001 + i, visits, name) for i, name in enumerate("abc"))
    b.rebuild = [a]
    t = _FixedCellList(World())
    t.home = a
    t.prepared = [a, b, c]
    t.sphere_path.check_pos = Position(0xA9B40001, Frame(V(96.0, 96.0, 50.0)))
    assert t.check_other_cells(a) == TS.OK
    # acclient.c:312415-312417: index 2 is past the rebuilt num_cells (1): the walk ends.
    assert visits == ["b"]


# --- stored fields after real sweeps ---------------------------------------------------------------


def _floats_of(t: Transition) -> dict[str, float]:
    """Every float the transition's records store, by name."""
    path, info, obj = t.sphere_path, t.collision_info, t.object_info
    values: dict[str, float] = {
        "object_info.scale": obj.scale,
        "object_info.step_up_height": obj.step_up_height,
        "object_info.step_down_height": obj.step_down_height,
        "walkable_allowance": path.walkable_allowance,
        "walk_interp": path.walk_interp,
        "step_down_amt": path.step_down_amt,
        "walkable_scale": path.walkable_scale,
        "walkable_check_pos.radius": path.walkable_check_pos.radius,
        "contact_plane.d": info.contact_plane.d,
        "last_known_contact_plane.d": info.last_known_contact_plane.d,
    }
    vectors: dict[str, V] = {
        "local_low_point": path.local_low_point,
        "global_low_point": path.global_low_point,
        "localspace_low_point": path.localspace_low_point,
        "localspace_z": path.localspace_z,
        "global_offset": path.global_offset,
        "step_up_normal": path.step_up_normal,
        "walkable_up": path.walkable_up,
        "neg_collision_normal": path.neg_collision_normal,
        "walkable_check_pos.center": path.walkable_check_pos.center,
        "curr_pos": path.curr_pos.frame.origin,
        "check_pos": path.check_pos.frame.origin,
        "backup_check_pos": path.backup_check_pos.frame.origin,
        "contact_plane.N": info.contact_plane.N,
        "last_known_contact_plane.N": info.last_known_contact_plane.N,
        "sliding_normal": info.sliding_normal,
        "collision_normal": info.collision_normal,
        "adjust_offset": info.adjust_offset,
    }
    for group in ("local_sphere", "global_sphere", "localspace_sphere"):
        for i, sphere in enumerate(getattr(path, group)):
            values[f"{group}[{i}].radius"] = sphere.radius
            vectors[f"{group}[{i}].center"] = sphere.center
    for group in ("global_curr_center", "localspace_curr_center"):
        for i, center in enumerate(getattr(path, group)):
            vectors[f"{group}[{i}]"] = center
    for name, v in vectors.items():
        for axis in "xyz":
            values[f"{name}.{axis}"] = getattr(v, axis)
    return values


def _walker(world: World, origin: V, state: PS = PS.GRAVITY) -> PhysicsObj:
    setup = human_setup()
    setup.step_up_height = setup.step_down_height = 0.4
    body = PhysicsObj(world, "walker", PartArray(setup))
    body.state = state
    body.set_scale_static(1.1)
    assert body.enter_world(Position(outdoor_cell_id(LANDBLOCK, origin), Frame.from_heading(origin, 33.0)))
    return body


def _box(world: World, lo: V, hi: V) -> None:
    setup = Setup("box", physics_bsp=build_box_tree(V(), hi - lo))
    add_static_object(world, "box", setup, Position(outdoor_cell_id(LANDBLOCK, lo), Frame(lo)))


@pytest.mark.parametrize(
    ("box_hi", "start", "offset", "state"),
    [
        # onto a 0.3-m step (step_up, step_down, BSP walkables, localspace spheres)
        ((99.0, 0.3), V(96.1, 96.3, GROUND), V(2.3, 0.7, 0.0), PS.GRAVITY),
        # into a 3-m wall at an angle (slides, collision and sliding normals)
        ((99.0, 3.0), V(96.1, 96.3, GROUND), V(4.3, 1.1, 0.0), PS.GRAVITY),
        # towards the far edge of a 2-m block with EDGE_SLIDE (edge_slide and its slides)
        ((99.0, 2.0), V(97.9, 96.3, GROUND + 2.1), V(3.1, 0.3, 0.0), PS.GRAVITY | PS.EDGE_SLIDE),
    ],
)
def test_the_records_hold_float32_after_real_sweeps(
    box_hi: tuple[float, float], start: V, offset: V, state: PS
) -> None:
    world = World()
    world.set_flat_ground(LANDBLOCK, GROUND)
    _box(world, V(97.0, 90.0, GROUND), V(box_hi[0], 102.0, GROUND + box_hi[1]))
    body = _walker(world, start, state)
    target = body.position.copy()
    target.frame.origin = target.frame.origin + offset
    t = body.transition(body.position, target)
    assert t is not None
    bad = {name: value for name, value in _floats_of(t).items() if not is_f32(value)}
    assert not bad
