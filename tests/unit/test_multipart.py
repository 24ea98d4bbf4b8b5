"""Many-part setups: one ``CPhysicsPart`` per part (``CPartArray::InitParts``, acclient.c:325273),
each placed by the body's frame combined with its default placement frame (``CPartArray::CreateSetup``
→ ``SetPlacementFrame(0x65)``, acclient.c:326973; ``UpdateParts``, 326600), scaled by its default
scale (``SetScaleInternal``, 326181), colliding part by part until one answers other than OK
(``CPartArray::FindObjCollisions``, 325463) and shadowing by every part's box.

The hand-built object: two box parts (x, y ±1, z 0..2 locally) on flat ground in landblock 0xA9B4;
part 0 placed 3 m west of the body origin, part 1 3 m east with default scale 2. The mover is one
sphere of r 0.5, 0.5 above its origin, swept airborne.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import acphys
from acphys.dat import DatError, DatFile, unpack_setup
from acphys.dat.gfxobj import needs_setup_parts, setup_parts
from acphys.flags import PhysicsState as PS
from acphys.flags import TransitionState as TS
from acphys.geometry.bsp_builder import build_box_tree
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.setup import Setup, SetupPart
from acphys.transition.transition import Transition
from acphys.world.static_objects import add_static_object
from acphys.world.world import World
from dat_support import (
    BOX_GFXOBJ_ID,
    BOX_SETUP_ID,
    SETUP_ID,
    box_gfxobj_record,
    box_setup_record,
    parts_setup_record,
    setup_record,
    simple_dat,
)

BLOCK = 0xA9B4
CORNER = V(48.0, 48.0, 0.0)
SWEEP_CELL = 0xA9B4000A


def two_boxes(west: float = -3.0, east: float = 3.0) -> Setup:
    tree = build_box_tree(V(-1.0, -1.0, 0.0), V(1.0, 1.0, 2.0))
    parts = [
        SetupPart(physics_bsp=tree, placement_frame=Frame(V(west, 0.0, 0.0))),
        SetupPart(physics_bsp=tree, default_scale=V(2.0, 2.0, 2.0), placement_frame=Frame(V(east, 0.0, 0.0))),
    ]
    return Setup("two boxes", parts=parts)


@pytest.fixture
def ground() -> World:
    world = World()
    world.set_flat_ground(BLOCK, 0.0)
    return world


def place(world: World, setup: Setup, origin: V = CORNER, scale: float = 1.0) -> PhysicsObj:
    where = Position(outdoor_cell_id(BLOCK, origin), Frame(origin))
    return add_static_object(world, "boxes", setup, where, scale)


def sweep(world: World, curr: V, check: V, cell_id: int = SWEEP_CELL) -> Transition:
    """A transition of the mover's sphere (r 0.5, centre 0.5 up) from origin ``curr`` to ``check``,
    both in cell ``cell_id``."""
    t = Transition(world, PhysicsObj(world, "mover"))
    path = t.sphere_path
    path.local_sphere = [Sphere(V(0, 0, 0.5), 0.5)]
    path.curr_pos = Position(cell_id, Frame(curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(cell_id, Frame(check)), None)
    path.walk_interp = 1.0
    return t


def close(a: V, b: V, tol: float = 1e-9) -> bool:
    return all(abs(p - q) <= tol for p, q in zip(a, b, strict=True))


def test_setup_parts_are_checked() -> None:
    with pytest.raises(ValueError, match="parts is empty"):
        Setup("none", parts=[])
    tree = build_box_tree(V(-1.0, -1.0, 0.0), V(1.0, 1.0, 2.0))
    with pytest.raises(ValueError, match="physics_bsp is for one-part setups"):
        Setup("both", physics_bsp=tree, parts=[SetupPart(physics_bsp=tree)])
    assert two_boxes().has_physics_bsp
    assert not Setup("bare", parts=[SetupPart()]).has_physics_bsp


def test_each_part_is_placed_by_its_placement_frame_and_scaled_by_its_default_scale(ground) -> None:
    obj = place(ground, two_boxes())
    assert obj.state & PS.HAS_PHYSICS_BSP
    west, east = obj.part_array.parts
    # Frame::combine(body, placement, scale 1) (acclient.c:326562): unturned body, offsets ±3.
    assert west.pos.frame.origin.exactly_equals(V(45.0, 48.0, 0.0))
    assert east.pos.frame.origin.exactly_equals(V(51.0, 48.0, 0.0))
    # SetScaleInternal: default_scale[i] × scale per axis (acclient.c:326181, default scale branch).
    assert west.gfxobj_scale.exactly_equals(V(1.0, 1.0, 1.0))
    assert east.gfxobj_scale.exactly_equals(V(2.0, 2.0, 2.0))
    # The box stays the gfx object's own, unscaled (CPhysicsPart::GetBoundingBox, acclient.c:314453).
    box = east.get_bounding_box()
    assert box.min.exactly_equals(V(-1.0, -1.0, 0.0)) and box.max.exactly_equals(V(1.0, 1.0, 2.0))


def test_the_body_scale_multiplies_the_default_scale_and_the_placement_offset(ground) -> None:
    obj = place(ground, two_boxes(), scale=1.5)
    west, east = obj.part_array.parts
    assert west.gfxobj_scale.exactly_equals(V(1.5, 1.5, 1.5))
    assert east.gfxobj_scale.exactly_equals(V(3.0, 3.0, 3.0))
    # UpdateParts combines with the part array's scale (acclient.c:326600): offsets 3 × 1.5 = 4.5.
    assert west.pos.frame.origin.exactly_equals(V(43.5, 48.0, 0.0))
    assert east.pos.frame.origin.exactly_equals(V(52.5, 48.0, 0.0))


def test_a_turned_body_turns_its_parts_around_its_origin(ground) -> None:
    setup = two_boxes()
    body = PhysicsObj(ground, "boxes", PartArray(setup))
    body.part_array.set_frame(Frame.from_heading(V(10.0, 10.0, 0.0), 90.0))
    west, east = body.part_array.parts
    # Heading 90 turns local +x to global -y (compass: 0 = +y, 90 = +x, so local +y → +x and
    # local +x → -y): the west part (-3, 0) lands at (10, 13), the east (3, 0) at (10, 7).
    assert close(west.pos.frame.origin, V(10.0, 13.0, 0.0), 1e-6)
    assert close(east.pos.frame.origin, V(10.0, 7.0, 0.0), 1e-6)
    assert east.pos.frame.get_heading() == pytest.approx(90.0)


def test_a_sweep_into_the_first_part_stops_there_and_the_second_is_not_asked(ground) -> None:
    obj = place(ground, two_boxes())
    west, east = obj.part_array.parts
    # The west part spans x 44..46. Centre (43.6, 48, 1.5) is (-1.4, 0, 1.5) in its frame, 0.4 from
    # the x = -1 face < r 0.5: BSPTREE::find_collisions, airborne → ADJUSTED (acclient.c:361295).
    t = sweep(ground, V(43.0, 48.0, 1.0), V(43.6, 48.0, 1.0))
    assert obj.find_obj_collisions(t) == TS.ADJUSTED
    path = t.sphere_path
    assert path.collide and close(path.step_up_normal, V(-1.0, 0.0, 0.0))
    # The loop breaks on the first answer other than OK (acclient.c:325482): the localspace cache
    # is still the west part's, the east part never cached the spheres.
    assert path.localspace_pos.frame.origin.exactly_equals(west.pos.frame.origin)
    assert not path.localspace_pos.frame.origin.exactly_equals(east.pos.frame.origin)
    # The sphere centre is a float32: x 43.6 is stored as f32(43.6), 1.5e-6 short of it, and the
    # part frame's x 45 takes that to local -1.4000015 exactly.
    assert close(path.localspace_sphere[0].center, V(f32(43.6) - 45.0, 0.0, 1.5))


def test_a_sweep_into_the_second_part_is_met_at_its_default_scaled_face(ground) -> None:
    obj = place(ground, two_boxes())
    east = obj.part_array.parts[1]
    # The east part at x 51 scaled 2 spans x 49..53. Centre (48.6, 48, 1.5): the west part answers
    # OK (its root sphere, centre (45, 48, 1) r √3, is 3.6 away); the east part divides by
    # gfxobj_scale.z 2 (CPhysicsPart::find_obj_collisions, acclient.c:314669): localspace centre
    # (-1.2, 0, 0.75), r 0.25, 0.2 from the x = -1 face → ADJUSTED.
    t = sweep(ground, V(48.0, 48.0, 1.0), V(48.6, 48.0, 1.0))
    assert obj.find_obj_collisions(t) == TS.ADJUSTED
    path = t.sphere_path
    assert path.localspace_pos.frame.origin.exactly_equals(east.pos.frame.origin)
    # As above, from the float32 centre x f32(48.6) and the part at 51, halved by the scale.
    assert close(path.localspace_sphere[0].center, V((f32(48.6) - 51.0) / 2.0, 0.0, 0.75))
    assert path.localspace_sphere[0].radius == 0.25
    assert path.collide and close(path.step_up_normal, V(-1.0, 0.0, 0.0))
    # Between the parts (centre 48.1: 1.9 from the west box, local x -1.45 at the east one) every
    # part answers OK, so the array does (acclient.c:325473 starts from 1).
    t = sweep(ground, V(47.5, 48.0, 1.0), V(48.1, 48.0, 1.0))
    assert obj.find_obj_collisions(t) == TS.OK and not t.sphere_path.collide


def test_shadows_cover_both_parts_cells(ground) -> None:
    # Body at (36, 36) in cell (1, 1) = 0x0A. The west part, 6 m west, boxes x 29..31: cell 0x0A.
    # The east part, 18 m east, boxes x 53..55 (unscaled): cell (2, 1) = 1 + 8·2 + 1 = 0x12.
    # find_bbox_cell_list (acclient.c:318275) asks every part's box (CLandCell's parts overload).
    obj = place(ground, two_boxes(west=-6.0, east=18.0), origin=V(36.0, 36.0, 0.0))
    cells = set()
    for shadow in obj.shadow_objects:
        assert shadow.cell is not None and any(s is shadow for s in shadow.cell.shadow_objects)
        cells.add(shadow.cell.id)
    assert cells == {0xA9B4000A, 0xA9B40012}
    # A sweep in cell 0x12 meets the east part (centre 51.6 is local (-1.2, 0, 0.75) to the part at
    # 54 scaled 2, as above) through either shadow: a shadow is the whole body, all its parts
    # (CObjCell::find_obj_collisions, acclient.c:347141).
    for cell_id in (0xA9B40012, 0xA9B4000A):
        t = sweep(ground, V(51.0, 36.0, 1.0), V(51.6, 36.0, 1.0), 0xA9B40012)
        assert ground.get_cell(cell_id).find_obj_collisions(t) == TS.ADJUSTED
        assert close(t.sphere_path.localspace_sphere[0].center, V((f32(51.6) - 54.0) / 2.0, 0.0, 0.75))


# -- the DAT path ------------------------------------------------------------------------------

EAST_GFXOBJ_ID = 0x01000011
PARTS_SETUP_ID = 0x02000020


def dat_records() -> dict[int, bytes]:
    """The ladder-03 wall cut in two: part 0 a 2 x 0.5 x 2.5 box 12 m west of the object origin;
    part 1 a 1 x 1 x 1.25 box at default scale 2 (2 x 2 x 2.5) 12 m east and 0.75 m north, so
    both south faces are at y = origin - 0.25."""
    return {
        BOX_GFXOBJ_ID: box_gfxobj_record((-1.0, -0.25, 0.0), (1.0, 0.25, 2.5)),
        EAST_GFXOBJ_ID: box_gfxobj_record((-0.5, -0.5, 0.0), (0.5, 0.5, 1.25), gfxobj_id=EAST_GFXOBJ_ID),
        PARTS_SETUP_ID: parts_setup_record(
            PARTS_SETUP_ID,
            (BOX_GFXOBJ_ID, EAST_GFXOBJ_ID),
            ((-12.0, 0.0, 0.0), (12.0, 0.75, 0.0)),
            scales=((1.0, 1.0, 1.0), (2.0, 2.0, 2.0)),
        ),
        SETUP_ID: setup_record(steps=(0.0, 0.0)),
    }


def test_setup_parts_reads_every_part(tmp_path: Path) -> None:
    records = dat_records()
    records[BOX_SETUP_ID] = box_setup_record()
    records[0x02000021] = parts_setup_record(0x02000021, (BOX_GFXOBJ_ID,), ((1.0, 0.0, 0.0),), placement_id=7)
    with DatFile(simple_dat(tmp_path, records)) as dat:
        record = unpack_setup(dat.read(PARTS_SETUP_ID))
        assert needs_setup_parts(record)
        west, east = setup_parts(record, dat)
        assert west.placement_frame.origin.exactly_equals(V(-12.0, 0.0, 0.0))
        assert east.placement_frame.origin.exactly_equals(V(12.0, 0.75, 0.0))
        assert east.default_scale.exactly_equals(V(2.0, 2.0, 2.0))
        # gfx_bound_box is the box around the GfxObj's vertices (CGfxObj::init_end, acclient.c:356199).
        assert east.bounding_box is not None and east.bounding_box.max.exactly_equals(V(0.5, 0.5, 1.25))
        assert west.physics_bsp is not None and east.physics_bsp is not None
        # A one-part, unscaled, unmoved setup stays with setup_physics_bsp; the human has no flag 8.
        assert not needs_setup_parts(unpack_setup(dat.read(BOX_SETUP_ID)))
        assert not needs_setup_parts(unpack_setup(dat.read(SETUP_ID)))
        # Neither placement 0x65 nor 0: SetPlacementFrame places nothing (acclient.c:326817).
        with pytest.raises(DatError, match="no placement frame 0x65 or 0"):
            setup_parts(unpack_setup(dat.read(0x02000021)), dat)


SCENARIO = """
[data]
portal = "client_portal.dat"

[scenario]
name = "dat-parts"
duration = 3.0
driver_hz = 60.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[object]]
name = "wall"
setup = "0x02000020"
landblock = "0xA9B4"
origin = [96.0, 100.0, 50.0]

[[body]]
name = "west"
landblock = "0xA9B4"
origin = [84.0, 96.0, 50.0]
state = ["gravity", "report_collisions", "edge_slide"]
on_ground = true

[[body]]
name = "east"
landblock = "0xA9B4"
origin = [108.0, 96.0, 50.0]
state = ["gravity", "report_collisions", "edge_slide"]
on_ground = true

[[body]]
name = "between"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]
state = ["gravity", "report_collisions", "edge_slide"]
on_ground = true

[[event]]
at = 0.0
body = "west"
action = "motion"
motion = "WalkForward"

[[event]]
at = 0.0
body = "east"
action = "motion"
motion = "WalkForward"

[[event]]
at = 0.0
body = "between"
action = "motion"
motion = "WalkForward"
"""


def test_bodies_walking_into_either_dat_part_stop_like_ladder_rung_3(tmp_path: Path) -> None:
    simple_dat(tmp_path, dat_records())
    path = tmp_path / "parts.toml"
    path.write_text(SCENARIO, encoding="utf-8")
    sim = acphys.load_scenario(path)
    sim.run()
    # Both south faces are at y 99.75, as ladder-03's wall (tests/ladder/test_03_wall.py): one
    # 0.104 m sub-step a step; the step reaching the face fails its step-up
    # (BSPTREE::step_sphere_up, acclient.c:361071) and is rolled back (CTransition::validate_transition,
    # acclient.c:312193): 31 steps, 96 + 31 × 0.104. The east part is met at its default scale.
    # Each step adds the float32 walk frame (the sequence's float spills of 1/30 × f32(3.12),
    # CSequence::apply_physics acclient.c:339877-339880) to a float32 y near 97-99 m, where the
    # spacing is 2^-17: the walk frame is 13631.49 of those, so every step rounds down by 0.49 of one and
    # the 31 steps end 0.12 mm short of 96 + 31 × 0.104, as retail's would.
    frame_of_walking = f32(f32(1.0 / 30.0 * f32(3.12)) + 0.0)
    expected = 96.0
    for _ in range(31):
        expected = f32(expected + frame_of_walking)
    for name, x in (("west", 84.0), ("east", 108.0)):
        origin = sim.body(name).position.frame.origin
        assert origin.y == expected, name
        assert origin.x == x
    # Between the parts (x 96) nothing is in the way: 3 s at 3.12 m/s.
    assert sim.body("between").position.frame.origin.y > 99.75 + 5.0
