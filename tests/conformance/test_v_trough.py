"""A ball dropped into a V between two steep faces jitters across the V and never counts past
one stationary-fall frame. This is retail's behaviour, not a port bug.

The V is two wedges (faces of slope 2, normal z 1/sqrt(5) = 0.447, below FLOOR_Z) meeting at a
line 0 m up. The ball (r 0.1) lands on one face in CONTACT but not ON_WALKABLE, so gravity keeps
pulling it and CTransition::adjust_offset (acclient.c:311863) runs each step along its contact
plane towards the V's bottom. Sphere 0 then runs into the opposite face: BSPTREE::find_collisions
calls BSPTREE::step_sphere_up (acclient.c:361071), and CTransition::step_up off walkable ground
steps down only 0.04 m but accepts any plane with normal z >= LANDING_Z (acclient.c:312807-312808):
the opposite face. The ball hops from face to face, a centimetre either side of the middle.

The stationary counter (CTransition::validate_transition, acclient.c:312272-312316) only climbs
over consecutive frames in which no step moves. When a step is rolled back (COLLIDED) the count
goes 0 -> 1 and, with a last known contact plane, the velocity is killed (acclient.c:312227);
CPhysicsObj::handle_all_collisions then sets STATIONARY_FALL. At zero velocity the next frame's
candidate does not move (CPhysicsObj::UpdatePhysicsInternal, acclient.c:317700), so no sweep
runs (CPhysicsObj::UpdateObjectInternal, acclient.c:322781) and the bit stays. The frame after,
CPhysicsObj::transition seeds the count at 1 from that bit (acclient.c:320113-320115), but the
step slides along the contact plane and moves, which zeroes it (acclient.c:312279), and the
bits are cleared. STATIONARY_STOP (2) and STATIONARY_STUCK (3) are never reached.
"""

from __future__ import annotations

from acphys.flags import TransientState as TS
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.scenario import parse_scenario

TROUGH = """
[scenario]
name = "trough"
duration = 4.0
driver_hz = 60.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[setup.trough]  # two prisms, 2 m wide, 4 m high at their outer sides, meeting at x = 0
solids = [
    [
        [[-2, -2, 0], [0, -2, 0], [-2, -2, 4]],
        [[-2, 2, 0], [-2, 2, 4], [0, 2, 0]],
        [[-2, -2, 0], [-2, 2, 0], [0, 2, 0], [0, -2, 0]],
        [[-2, -2, 0], [-2, -2, 4], [-2, 2, 4], [-2, 2, 0]],
        [[0, -2, 0], [0, 2, 0], [-2, 2, 4], [-2, -2, 4]],
    ],
    [
        [[2, -2, 4], [0, -2, 0], [2, -2, 0]],
        [[0, 2, 0], [2, 2, 4], [2, 2, 0]],
        [[0, -2, 0], [0, 2, 0], [2, 2, 0], [2, -2, 0]],
        [[2, 2, 0], [2, 2, 4], [2, -2, 4], [2, -2, 0]],
        [[2, -2, 4], [2, 2, 4], [0, 2, 0], [0, -2, 0]],
    ],
]

[setup.ball]
spheres = [{ center = [0.0, 0.0, 0.1], radius = 0.1 }]

[[object]]
name = "trough"
setup = "trough"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]

[[body]]
name = "ball"
setup = "ball"
landblock = "0xA9B4"
origin = [96.3, 96.0, 52.0]
state = ["gravity", "report_collisions"]
"""

# |normal x| and normal z of the faces (2, 0, 1) / sqrt(5), as the float32 plane normals hold them.
FACE_X = f32(2.0 / 5.0**0.5)
FACE_Z = f32(1.0 / 5.0**0.5)
#: Two float32 ulps near 0.9: the normals are float32 and reach the contact plane through float
#: stores, so they match the faces' to the last bit or two, not to 1e-9.
NORMAL_TOL = 1.2e-7
STATIONARY = TS.STATIONARY_FALL | TS.STATIONARY_STOP | TS.STATIONARY_STUCK


def test_a_ball_in_a_steep_v_hops_between_the_faces_and_never_counts_past_one():
    sim = parse_scenario(TROUGH, source="<trough>")
    ball = sim.body("ball")
    steps: list[tuple[Vector3, Vector3, Vector3, TS, Vector3]] = []

    def observe(body, quantum):
        steps.append(
            (
                body.position.frame.origin.copy(),
                body.velocity.copy(),
                body.cached_velocity.copy(),
                body.transient_state,
                body.contact_plane.N.copy(),
            )
        )

    ball.observer = observe
    sim.run()
    landed = next(i for i, step in enumerate(steps) if step[3] & TS.CONTACT)
    settled = steps[landed + 10 :]
    assert len(settled) > 80
    # Never STATIONARY_STOP or STATIONARY_STUCK (validate_transition, acclient.c:312283-312293).
    assert not any(step[3] & (TS.STATIONARY_STOP | TS.STATIONARY_STUCK) for step in steps)
    # In contact throughout, on one steep face or the other, never on walkable ground; the ball
    # stays within 2 cm of the V's middle line.
    faces = set()
    for origin, _, _, state, normal in settled:
        assert state & TS.CONTACT and not state & TS.ON_WALKABLE
        assert abs(abs(normal.x) - FACE_X) < NORMAL_TOL and abs(normal.z - FACE_Z) < NORMAL_TOL
        faces.add(normal.x > 0.0)
        assert abs(origin.x - 96.0) < 0.02
    assert faces == {True, False}
    # Each stationary frame: velocity killed, then a frame without a sweep (origin kept,
    # cached_velocity zeroed, the bits kept), then a moving frame that clears the bits.
    cycles = 0
    for i in range(landed, len(steps) - 2):
        (origin, velocity, _, state, _), following, after = steps[i], steps[i + 1], steps[i + 2]
        if not state & STATIONARY or steps[i - 1][3] & STATIONARY:
            continue
        cycles += 1
        assert state & STATIONARY == TS.STATIONARY_FALL
        assert velocity.exactly_equals(Vector3())
        assert following[0].exactly_equals(origin)
        assert following[2].exactly_equals(Vector3())
        assert following[3] & STATIONARY == TS.STATIONARY_FALL
        assert following[1].x == 0.0 and following[1].y == 0.0 and following[1].z < 0.0
        assert not after[0].exactly_equals(origin)
        assert not after[3] & STATIONARY
    assert cycles >= 10
