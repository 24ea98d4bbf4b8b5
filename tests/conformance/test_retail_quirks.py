"""Two retail behaviours that look like bugs and are not to be "fixed" (issue 12, point 6).

Both are what the decompiled client (build 11.4186) does; acphys keeps them. Each expected value
below is worked by hand from the cited lines.

(a) A static object's cells come from its *unscaled* bounding box. ``CPhysicsPart::GetBoundingBox``
    (0x0050D600, acclient.c:314453-314456) returns ``gfx_bound_box`` as it is, and the parts
    overload of ``CLandCell::add_all_outside_cells`` (0x00533360, acclient.c:355311-355316) floors
    that box, moved by the part's frame only (``BBox::LocalToGlobal``, 0x005B2120,
    acclient.c:476912), to cell columns and rows. ``gfxobj_scale`` (``CPartArray::SetScaleInternal``,
    0x00518A00, acclient.c:326221-326225) is read only by the collision:
    ``CPhysicsPart::find_obj_collisions`` (0x0050D8D0, acclient.c:314669-314670). A moving sphere is
    tested only against the objects shadowed into the cells its own sweep reaches (the sphere
    overload of ``add_all_outside_cells``, 0x00533630, and ``CTransition::check_other_cells``,
    0x0050AE50), so a scaled-up object is solid only inside the cells of its unscaled box.

(b) ``OBJECTINFO::validate_walkable`` (0x0050D010, acclient.c:314160) returns OK, not ADJUSTED, for
    a terrain plane too steep to walk on while the body is on walkable ground and not stepping
    down. A body without EDGE_SLIDE that runs at such a face sinks into it for one step; the next
    step, no longer on walkable ground, it is lifted onto the plane by its full depth.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pytest

from acphys.flags import ObjectInfoState as OI
from acphys.flags import TransientState as TS
from acphys.flags import TransitionState as TRS
from acphys.geometry.bbox import BBox
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.scenario import parse_scenario
from acphys.simulation import Simulation
from acphys.transition.collision_info import CollisionInfo
from acphys.transition.object_info import ObjectInfo
from acphys.transition.sphere_path import SpherePath
from acphys.world.land_cell import LandCell
from acphys.world.obj_cell import CellArray

BLOCK = 0xA9B4


def _cell(low: int) -> int:
    return (BLOCK << 16) | low


def _outdoor(cx: int, cy: int) -> int:
    """The outdoor cell in column ``cx``, row ``cy`` of BLOCK: low word 1 + 8·cx + cy."""
    return _cell(1 + 8 * cx + cy)


@dataclass
class Step:
    cell: int
    origin: Vector3
    velocity: Vector3
    cached_velocity: Vector3
    transient: TS
    contact_normal: Vector3 | None
    events: tuple[str, ...]
    quantum: float


def _record(sim: Simulation, name: str) -> list[Step]:
    """Run ``sim`` and return every physics step of body ``name``."""
    steps: list[Step] = []

    def observe(body: PhysicsObj, quantum: float) -> None:
        contact = bool(body.transient_state & TS.CONTACT)
        steps.append(
            Step(
                body.position.objcell_id,
                body.position.frame.origin.copy(),
                body.velocity.copy(),
                body.cached_velocity.copy(),
                body.transient_state,
                body.contact_plane.N.copy() if contact else None,
                tuple(body.step_events),
                quantum,
            )
        )

    sim.body(name).observer = observe
    sim.run()
    return steps


def _vec(v: Vector3) -> tuple[float, float, float]:
    return (v.x, v.y, v.z)


# == (a) a scaled static object shadows by its unscaled box ======================================

# Column 1 is x in [24, 48), column 2 is [48, 72); row 1 is y in [24, 48). The box stands at
# x = 46.3 in cell (1, 1) = 0x0A. The ball (radius 0.5, no gravity, 1 m up so it never touches the
# ground) comes from cell (2, 1) = 0x12 at 3 m/s west: 0.1 m per 1/30-s step.
BOX_ORIGIN_X = 46.3
BALL_RADIUS = 0.5
HOME = _outdoor(1, 1)  # 0x0A: the box's cell
NEIGHBOUR = _outdoor(2, 1)  # 0x12: where the ball comes from


def _box_world(half: float, top: float, scale: float) -> str:
    return f"""
[scenario]
name = "scaled-box"
duration = 1.5
driver_hz = 30.0

[[landblock]]
id = "0xA9B4"
height = 0.0

[setup.box]
boxes = [{{ min = [{-half}, {-half}, 0], max = [{half}, {half}, {top}] }}]

[setup.ball]
spheres = [{{ center = [0, 0, 0.5], radius = {BALL_RADIUS} }}]

[[object]]
name = "box"
setup = "box"
landblock = "0xA9B4"
origin = [{BOX_ORIGIN_X}, 36.0, 0.0]
scale = {scale}

[[body]]
name = "ball"
setup = "ball"
landblock = "0xA9B4"
origin = [51.05, 36.0, 1.0]
state = ["report_collisions"]
velocity = [-3.0, 0.0, 0.0]
elasticity = 0.05
"""


#: The quirk: a 2 × 2 × 2 box scaled by 2, so it collides as x [44.3, 48.3] × y [34, 38] × z [0, 4]
#: but shadows by its unscaled x [45.3, 47.3] × y [35, 37].
SCALED = _box_world(half=1.0, top=2.0, scale=2.0)
#: The control: the same solid volume built at scale 1 (a 4 × 4 × 4 box).
UNSCALED = _box_world(half=2.0, top=4.0, scale=1.0)
#: The scaled box's east face, where collision puts it (44.3 + 4).
SCALED_FACE_X = BOX_ORIGIN_X + 2.0


def _box(sim: Simulation) -> PhysicsObj:
    home = sim.world.get_cell(HOME)
    assert home is not None
    return next(obj for obj in home.objects if obj.name == "box")


def _shadow_cells(obj: PhysicsObj) -> list[int]:
    cells = []
    for shadow in obj.shadow_objects:
        assert shadow.cell is not None and any(s is shadow for s in shadow.cell.shadow_objects)
        cells.append(shadow.cell.id)
    return cells


def test_a_scale_2_box_shadows_only_into_the_cells_of_its_unscaled_box():
    sim = parse_scenario(SCALED, source="<scaled>")
    box = _box(sim)
    (part,) = box.part_array.parts
    # SetScaleStatic (acclient.c:319013-319020) → SetScaleInternal: with no default_scale array the
    # part's gfxobj_scale is the scale itself (acclient.c:326221-326225).
    assert part.gfxobj_scale.exactly_equals(Vector3(2.0, 2.0, 2.0))
    # GetBoundingBox returns gfx_bound_box, unscaled (acclient.c:314455).
    box_local = part.get_bounding_box()
    assert _vec(box_local.min) == (-1.0, -1.0, 0.0) and _vec(box_local.max) == (1.0, 1.0, 2.0)
    # add_all_outside_cells (parts): LocalToGlobal through the part's frame only (acclient.c:355312;
    # BBox::LocalToGlobal, acclient.c:476946-476965, has no scale), then floor(c / 24) per corner
    # (acclient.c:355313-355319): x [45.3, 47.3] and y [35, 37] are all column 1 and row 1.
    anchor = sim.world.get_cell(HOME)
    assert anchor is not None
    world_box = BBox.local_to_global(box_local, part.pos, anchor.pos)
    assert world_box.min.x == pytest.approx(45.3, abs=1e-5) and world_box.max.x == pytest.approx(
        47.3, abs=1e-5
    )
    columns = {math.floor(world_box.min.x / 24.0), math.floor(world_box.max.x / 24.0)}
    rows = {math.floor(world_box.min.y / 24.0), math.floor(world_box.max.y / 24.0)}
    assert columns == {1} and rows == {1}
    # Scaled, the east face would be 46.3 + 2 = 48.3: column 2, the ball's cell.
    assert math.floor((BOX_ORIGIN_X + 2.0 * box_local.max.x) / 24.0) == 2
    # So the object is shadowed into 0x0A alone (add_cell_block, acclient.c:355337), not 0x12.
    assert _shadow_cells(box) == [HOME]
    neighbour = sim.world.get_cell(NEIGHBOUR)
    assert neighbour is not None
    assert all(shadow.physobj is not box for shadow in neighbour.shadow_objects)


def test_the_same_volume_unscaled_shadows_into_both_cells():
    # The control: a box built 4 m wide at scale 1 has the same solid volume, and its box x
    # [44.3, 48.3] floors to columns 1..2 (acclient.c:355313-355331).
    box = _box(parse_scenario(UNSCALED, source="<unscaled>"))
    assert box.part_array.parts[0].gfxobj_scale.exactly_equals(Vector3(1.0, 1.0, 1.0))
    assert _shadow_cells(box) == [HOME, NEIGHBOUR]


def test_the_ball_sweep_reaches_the_box_cell_only_within_a_radius_of_the_boundary():
    sim = parse_scenario(SCALED, source="<scaled>")

    def sweep_cells(x: float) -> list[int]:
        cells = CellArray(sim.world)
        centre = Vector3(x, 36.0, 1.5)
        where = Position(NEIGHBOUR, Frame(Vector3(x, 36.0, 1.0)))
        LandCell.add_all_outside_cells(where, [Sphere(centre, BALL_RADIUS)], cells)
        return cells.cell_ids()

    # The sphere overload of add_all_outside_cells: pt1.x = x - 24·floor(x / 24) (acclient.c:355390)
    # against incell_min = radius (acclient.c:355389); check_add_cell_boundary adds column x - 1
    # when pt1.x < incell_min (acclient.c:355176-355179). At 48.55: 0.55 > 0.5, 0x12 alone, though
    # the sphere (x from 48.05) is already 0.25 m inside the scaled box (face at 48.3).
    assert sweep_cells(48.55) == [NEIGHBOUR]
    # At 48.45: 0.45 < 0.5, and 0x0A (the box's only cell) joins the sweep.
    assert sweep_cells(48.45) == [NEIGHBOUR, HOME]


def test_a_ball_from_the_neighbouring_cell_passes_into_the_outer_part_of_a_scaled_box():
    """The ball meets the scaled face at centre x 48.8 but stays free for three more steps, to
    48.55 (its sphere 0.25 m inside the box's scaled volume), because its sweep is in 0x12 only and
    the box is shadowed into 0x0A only. The step to 48.45 takes 0x0A into the sweep
    (acclient.c:355176-355179); CTransition::check_other_cells (acclient.c:312403-312419) runs that
    cell's collisions, CObjCell::find_obj_collisions (0x0052B750, acclient.c:347154-347161) reaches
    the box's shadow, and the box collides at scale 2 (CPhysicsPart::find_obj_collisions,
    acclient.c:314669-314670); CTransition::validate_transition rolls the step back to 48.55
    (acclient.c:312223-312253). The bounce (CPhysicsObj::handle_all_collisions,
    acclient.c:321876-321886) is v·n = -3 against n = +x, impulse 3·(1 + 0.05) = 3.15: v.x = 0.15,
    inside the deadband (0.15² − 0.25² < EPSILON, CPhysicsObj::UpdatePhysicsInternal,
    acclient.c:317750-317755), so the ball comes to rest embedded in the box."""
    steps = _record(parse_scenario(SCALED, source="<scaled>"), "ball")
    # Steps 1..25 move freely from 51.05 by 0.1 m each: 51.05 - 0.1·n (float32 sums, to 1e-4).
    for n, step in enumerate(steps[:25], start=1):
        assert step.origin.x == pytest.approx(51.05 - 0.1 * n, abs=1e-4)
        assert step.cell == NEIGHBOUR
        assert step.events == ()
        assert _vec(step.velocity) == (-3.0, 0.0, 0.0)
    # From centre 48.75 on (step 23) the sphere overlaps the scaled volume x [44.3, 48.3] without a
    # collision; at step 25 it is 0.25 m in.
    inside = [s for s in steps[:25] if s.origin.x - BALL_RADIUS < SCALED_FACE_X]
    assert [round(s.origin.x, 2) for s in inside] == [48.75, 48.65, 48.55]
    free = steps[24]
    assert SCALED_FACE_X - (free.origin.x - BALL_RADIUS) == pytest.approx(0.25, abs=1e-4)
    # Step 26: the candidate 48.45 reaches 0x0A; the box collides (it reports as the environment),
    # the step is rolled back (cached_velocity 0), and the ball bounces to +0.15 m/s.
    hit = steps[25]
    assert hit.events == ("collision:environment",)
    assert hit.origin.exactly_equals(free.origin)
    assert hit.cached_velocity.exactly_equals(Vector3())
    assert hit.velocity.x == f32(-3.0 + 3.0 * (1.0 + f32(0.05)))
    assert hit.velocity.x == pytest.approx(0.15, abs=1e-6)
    assert hit.transient & TS.SLIDING
    # Step 27 on: 0.15 m/s is in the deadband; the ball rests where it stopped, still 0.25 m inside
    # the scaled box and still in 0x12.
    for step in steps[26:]:
        assert step.velocity.exactly_equals(Vector3())
        assert step.origin.exactly_equals(free.origin)
        assert step.cell == NEIGHBOUR


def test_against_the_same_volume_unscaled_the_ball_stops_outside_it():
    """The control: the 4-m box at scale 1 is shadowed into 0x12 too, so the ball collides at the
    first step whose sphere would cross the face: the candidate 48.75 (sphere from 48.25 < 48.3) is
    rolled back to 48.85, and the ball rests 0.05 m short of the face."""
    steps = _record(parse_scenario(UNSCALED, source="<unscaled>"), "ball")
    first = next(i for i, s in enumerate(steps) if s.events)
    assert first == 22  # step 23
    assert steps[first].events == ("collision:environment",)
    rest = steps[first].origin
    assert rest.x == pytest.approx(48.85, abs=1e-4)
    assert rest.x - BALL_RADIUS > SCALED_FACE_X
    assert steps[-1].origin.exactly_equals(rest) and steps[-1].velocity.exactly_equals(Vector3())


# == (b) the one-step sink into a too-steep terrain face =========================================

# Height bytes: x = 0..4 (the first 45 of the x·9 + y entries) byte 50, x = 5..8 byte 80, through the
# table height(i) = 2·i: vertices at x = 0..96 m stand at 100 m, those at x = 120..192 m at 160 m.
# Cells of column 4 (x 96..120) hold the face: both triangles lie in z = 100 + 2.5·(x - 96) whatever
# the split, normal (-2.5, 0, 1)/√7.25, z 0.371 < floor_z 0.664. The ball starts in cell (3, 4) =
# 0x1D; the face's cell in its row is (4, 4) = 0x25.
HEIGHTS = [50] * 45 + [80] * 36
HEIGHT_TABLE = [i * 2.0 for i in range(256)]
FLAT = _outdoor(3, 4)  # 0x1D
FACE = _outdoor(4, 4)  # 0x25
SLOPE = 60.0 / 24.0
FACE_N = (-SLOPE / math.sqrt(1.0 + SLOPE * SLOPE), 0.0, 1.0 / math.sqrt(1.0 + SLOPE * SLOPE))


def _face_height(x: float) -> float:
    return 100.0 + SLOPE * (x - 96.0)


def _steep_world(edge_slide: bool) -> str:
    state = (
        '["gravity", "report_collisions", "edge_slide"]' if edge_slide else '["gravity", "report_collisions"]'
    )
    return f"""
[scenario]
name = "steep-face"
duration = 1.0
driver_hz = 30.0

[[landblock]]
id = "0xA9B4"
heights = {HEIGHTS}
height_table = {HEIGHT_TABLE}

[setup.ball]
spheres = [{{ center = [0, 0, 0.5], radius = 0.5 }}]

[[body]]
name = "ball"
setup = "ball"
landblock = "0xA9B4"
origin = [89.93, 100.0, 100.0]
state = {state}
velocity = [10.0, 0.0, 0.0]
friction = 0.0
elasticity = 0.05
on_ground = true
"""


def test_validate_walkable_returns_ok_for_a_steep_plane_while_on_walkable_ground():
    sim = parse_scenario(_steep_world(edge_slide=False), source="<steep>")
    cell = sim.world.get_cell(FACE)
    assert isinstance(cell, LandCell)
    poly = cell.find_terrain_poly(Vector3(96.26338, 100.0, 100.0))
    assert poly is not None
    plane = poly.plane
    assert _vec(plane.N) == pytest.approx(FACE_N, abs=1e-6)
    assert plane.N.z < ObjectInfo().get_walkable_z()
    # Sphere 0 of the sink step below: centre (96.26338, 100, 100.5), its low point 0.263 m past
    # the foot of the face. acclient.c:314224-314228: dist = N·(c - r·z) + d = -0.9285·0.26338
    # = -0.2445, below -EPSILON.
    sphere = Sphere(Vector3(96.26338, 100.0, 100.5), 0.5)
    c, n = sphere.center, plane.N
    dist = c.y * n.y + (c.z - sphere.radius) * n.z + c.x * n.x + plane.d
    assert dist == pytest.approx(FACE_N[0] * (96.26338 - 96.0), abs=1e-4)
    assert dist == pytest.approx(-0.24455, abs=1e-4)

    def validate(state: OI, step_down: bool = False) -> tuple[TRS, SpherePath, CollisionInfo]:
        path, info = SpherePath(), CollisionInfo()
        if step_down:  # what transitional_insert's step_down(step_down_height = 0) sets up
            path.step_down, path.step_down_amt, path.walk_interp = True, 0.0, 1.0
        ts = ObjectInfo(state=state).validate_walkable(sphere, plane, False, 0.0, path, info, FACE)
        return ts, path, info

    # On walkable ground, not stepping down, too steep: acclient.c:314255 is false, so no contact
    # plane, no lift, and ts keeps the OK it started with (acclient.c:314186, 314280). ACE
    # (ObjectInfo.ValidateWalkable) returns Adjusted here.
    ts, path, info = validate(OI.CONTACT | OI.ON_WALKABLE)
    assert ts == TRS.OK
    assert not info.contact_plane_valid and not info.collision_normal_valid
    assert path.check_pos.frame.origin.exactly_equals(Vector3())
    # The step-down that follows (step_down_height 0): the contact plane is taken, but the interp
    # (1 - (-1 / (0·1))·depth)·1 is -inf < -0.1: COLLIDED (acclient.c:314257-314263).
    ts, path, info = validate(OI.CONTACT | OI.ON_WALKABLE, step_down=True)
    assert ts == TRS.COLLIDED and info.contact_plane_valid
    # Off walkable ground (the next step): the plane is taken and the sphere lifted by the vertical
    # depth patha = dist / N.z (acclient.c:314253-314270): 2.5 · 0.26338 = 0.6585 here; ADJUSTED,
    # and without CONTACT the plane's normal becomes the collision normal (acclient.c:314272-314276).
    ts, path, info = validate(OI.DEFAULT)
    assert ts == TRS.ADJUSTED and info.contact_plane_valid
    assert path.check_pos.frame.origin.z == pytest.approx(SLOPE * 0.26338, abs=1e-4)
    assert info.collision_normal_valid and _vec(info.collision_normal) == pytest.approx(FACE_N, abs=1e-6)


def test_a_ball_without_edge_slide_sinks_into_a_steep_face_for_one_step_then_is_lifted_onto_it():
    """A ball on flat ground at 100 m (radius 0.5, friction 0, elasticity 0.05) runs east at
    10 m/s, 1/3 m per 1/30-s step, from x = 89.93 at a face rising 2.5 m per metre from x = 96.

    CLandCell::find_env_collisions tests the triangle under the sphere's low point
    (acclient.c:355023-355028), so the face counts from the first step whose centre is past x = 96:
    step 19, candidate 89.93 + 19/3 = 96.263. There validate_walkable returns OK without a contact
    plane (acclient.c:314255, 314280; the body is ON_WALKABLE and the plane too steep); the
    step-down with step_down_height 0 fails (acclient.c:314261-314263, CTransition::step_down
    acclient.c:312662-312679) and, without EDGE_SLIDE, CTransition::edge_slide restores the
    candidate and accepts it without contact (acclient.c:312775-312788). So the ball commits with
    its low point 2.5 · 0.263 = 0.658 m below the face (0.2445 m along its normal) and leaves the
    ground.

    Step 20 is off walkable ground: gravity pulls the candidate down 9.8·(1/30)²/2 = 0.0054 m, and
    validate_walkable lifts it by the vertical depth (acclient.c:314253-314270), 2.5 · 0.5967 +
    0.0054 = 1.497 m, onto the face at 100 + 2.5 · 0.5967 = 101.4917. The cached velocity is the
    step's offset over the quantum (CPhysicsObj::UpdateObjectInternal, acclient.c:322816-322828):
    z = 1.4917 · 30 = 44.75 m/s. The face's normal is the collision normal (acclient.c:314272-314276)
    and the bounce (acclient.c:321876-321886) gives v = (0.830, 0, 3.341).

    Divergence: ACE's ObjectInfo.ValidateWalkable returns Adjusted in this branch whether or not it
    took the plane, which makes transitional_insert go round without moving the candidate and ends
    in a rolled-back step: in ACE the ball stops at the foot of the face, as retail's does only with
    EDGE_SLIDE (the next test).
    """
    steps = _record(parse_scenario(_steep_world(edge_slide=False), source="<steep>"), "ball")
    quantum = steps[0].quantum
    assert quantum == f32(1.0 / 30.0)
    # Steps 1..18 roll on the flat ground of 0x1D: the last is at 89.93 + 18/3 = 95.93.
    for n, step in enumerate(steps[:18], start=1):
        assert step.cell == FLAT
        assert step.origin.x == pytest.approx(89.93 + n / 3.0, abs=1e-4)
        assert step.origin.z == 100.0
        assert step.transient & TS.CONTACT and step.transient & TS.ON_WALKABLE
        assert _vec(step.velocity) == (10.0, 0.0, 0.0)

    # Step 19: the sink.
    sink = steps[18]
    assert sink.cell == FACE
    assert sink.origin.x == pytest.approx(89.93 + 19.0 / 3.0, abs=1e-4)
    assert sink.origin.z == 100.0  # not lifted: the sphere's bottom is still at 100 m
    depth = _face_height(sink.origin.x) - sink.origin.z
    assert depth == pytest.approx(0.6585, abs=1e-3)
    assert depth * FACE_N[2] == pytest.approx(0.2445, abs=1e-3)  # along the normal
    assert not sink.transient & (TS.CONTACT | TS.ON_WALKABLE)
    assert sink.events == ("leave_ground",)
    assert _vec(sink.velocity) == (10.0, 0.0, 0.0)
    assert sink.cached_velocity.z == 0.0

    # Step 20: the lift.
    lift = steps[19]
    assert lift.cell == FACE
    assert lift.origin.x == pytest.approx(89.93 + 20.0 / 3.0, abs=1e-4)
    assert lift.origin.z == pytest.approx(_face_height(lift.origin.x), abs=1e-4)  # on the face
    assert lift.origin.z == pytest.approx(101.4917, abs=1e-3)
    fall = 0.5 * 9.8 * quantum * quantum
    assert lift.origin.z - (sink.origin.z - fall) == pytest.approx(1.497, abs=1e-3)  # the lift itself
    # The cached velocity: the 1.4917-m rise over one quantum.
    assert lift.cached_velocity.z == pytest.approx(44.75, rel=1e-3)
    assert lift.cached_velocity.z == pytest.approx((lift.origin.z - sink.origin.z) / quantum, rel=1e-6)
    assert lift.transient & TS.CONTACT and not lift.transient & TS.ON_WALKABLE
    assert lift.contact_normal is not None
    assert _vec(lift.contact_normal) == pytest.approx(FACE_N, abs=1e-6)
    assert lift.events == ("collision:environment",)
    # The bounce off the face: v = (10, 0, -9.8/30) before; v·n = -9.4061; impulse 1.05 · 9.4061.
    v = (10.0, 0.0, -9.8 * quantum)
    approach = v[0] * FACE_N[0] + v[2] * FACE_N[2]
    impulse = -approach * 1.05
    expected = (v[0] + impulse * FACE_N[0], 0.0, v[2] + impulse * FACE_N[2])
    assert expected == pytest.approx((0.830, 0.0, 3.341), abs=1e-3)
    assert _vec(lift.velocity) == pytest.approx(expected, abs=1e-4)


def test_with_edge_slide_the_ball_stops_at_the_foot_of_the_face():
    """With EDGE_SLIDE, the failed step-down of step 19 leaves the steep plane as the contact plane
    (acclient.c:314257-314258), so CTransition::edge_slide takes its cliff-slide branch
    (acclient.c:312707-312717, CTransition::cliff_slide acclient.c:312004). That returns ADJUSTED on
    each of transitional_insert's three rounds (acclient.c:312988-313004), so the step ends
    ADJUSTED and CTransition::validate_transition rolls it back to the current position, killing
    the velocity because the flat ground is the last known contact plane (acclient.c:312223-312227).
    The ball stays on walkable ground at x = 95.93, the foot of the face."""
    steps = _record(parse_scenario(_steep_world(edge_slide=True), source="<steep-edge>"), "ball")
    foot = steps[17].origin
    assert foot.x == pytest.approx(89.93 + 18.0 / 3.0, abs=1e-4)
    stop = steps[18]
    assert stop.origin.exactly_equals(foot)
    assert stop.velocity.exactly_equals(Vector3()) and stop.cached_velocity.exactly_equals(Vector3())
    assert stop.transient & TS.CONTACT and stop.transient & TS.ON_WALKABLE and stop.transient & TS.SLIDING
    assert stop.contact_normal is not None and _vec(stop.contact_normal) == (0.0, 0.0, 1.0)
    for step in steps[18:]:
        assert step.cell == FLAT and step.origin.exactly_equals(foot)
        assert "leave_ground" not in step.events
