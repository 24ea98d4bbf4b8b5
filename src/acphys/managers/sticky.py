"""``StickyManager``: keep a body at arm's length from the object it is stuck to.

A sticky move (a pet following its owner, a monster on its prey) ends with
the body stuck to its target. Each step the sticky manager replaces the
offset's origin with a flat move towards the target that stops 0.3 m short of
its cylinder, and turns the body to face it. The target manager reports where
the target is; the stick lapses one second (``Timer::cur_time``) after it was
made, or when the target goes away.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.managers.target import TargetStatus
from acphys.math.position import Position
from acphys.motion.move_to import position_heading
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    from acphys.managers.target import TargetInfo
    from acphys.math.frame import Frame
    from acphys.physics_obj import PhysicsObj

#: The gap kept between the two cylinders, the float32 0.3 (acclient.c:388559).
STICKY_RADIUS: float = f32(0.30000001)
#: The stick lasts this long after ``StickTo`` (acclient.c:388684).
STICKY_TIME: float = 1.0
#: Closing speed as a multiple of the body's max speed (acclient.c:388572) ...
STICKY_SPEED_FACTOR: float = 5.0
#: ... or this when that is below EPSILON (acclient.c:388579).
STICKY_FALLBACK_SPEED: float = 15.0
#: ``set_target(0, id, 0.5, 0.5)``: the radius and quantum asked of the target manager (388687).
STICKY_TARGET_RADIUS: float = 0.5
STICKY_TARGET_QUANTUM: float = 0.5


def cylinder_distance_no_z(r1: float, p1: Position, r2: float, p2: Position) -> float:
    """The full 3-D centre distance less both radii (despite its name, z is included).

    The radii are ``float`` parameters.

    Retail: Position::cylinder_distance_no_z @ 0x005A98B0 (acclient.c:467268)
    """
    return p1.get_offset(p2).length() - (f32(r1) + f32(r2))


class StickyManager:
    """Retail ``StickyManager``: the object a body is stuck to, and where it was last seen.

    Retail: StickyManager::Create @ 0x00555800 (acclient.c:388727)
    """

    __slots__ = (
        "initialized",
        "physics_obj",
        "sticky_timeout_time",
        "target_id",
        "target_position",
        "target_radius",
    )

    def __init__(self, physics_obj: PhysicsObj) -> None:
        self.physics_obj = physics_obj
        self.target_id = 0
        self.target_radius = 0.0
        self.target_position = Position()
        #: Set by the first OK report about the target; until then the body is not pulled.
        self.initialized = False
        self.sticky_timeout_time = 0.0

    def stick_to(self, target_id: int, target_radius: float, target_height: float) -> None:
        """Drop any current stick, then stick to ``target_id`` for one second.

        The body asks its target manager to track the target (radius 0.5,
        quantum 0.5); the pull starts with the manager's first OK report.
        ``target_height`` is accepted and unused, as in retail; ``target_radius``
        is a ``float`` parameter and field.

        Retail: StickyManager::StickTo @ 0x00555710 (acclient.c:388664)
        """
        self.handle_exit_world()
        self.target_radius = f32(target_radius)
        self.target_id = target_id
        self.initialized = False
        self.sticky_timeout_time = self.physics_obj.world.cur_time + STICKY_TIME
        self.physics_obj.set_target(0, target_id, STICKY_TARGET_RADIUS, STICKY_TARGET_QUANTUM)

    def handle_exit_world(self) -> None:
        """Let go: forget the target, clear the body's target and cancel its move-to.

        Retail's ``UseTime``, ``StickTo`` and ``HandleUpdateTarget`` inline this same sequence.

        Retail: StickyManager::HandleExitWorld @ 0x00555400 (acclient.c:388501)
        """
        if self.target_id:
            self.target_id = 0
            self.initialized = False
            self.physics_obj.clear_target()
            self.physics_obj.cancel_moveto()

    def handle_update_target(self, target_info: TargetInfo) -> None:
        """A target-manager report: OK records the target's position; any other status lets go.

        Reports about other objects are ignored.

        Retail: StickyManager::HandleUpdateTarget @ 0x00555780 (acclient.c:388690)
        """
        if target_info.object_id != self.target_id:
            return
        if target_info.status == TargetStatus.OK:
            self.initialized = True
            self.target_position = target_info.target_position.copy()
        else:
            self.handle_exit_world()

    def use_time(self) -> None:
        """Let go once ``Timer::cur_time`` passes the timeout.

        Retail: StickyManager::UseTime @ 0x00555610 (acclient.c:388604)
        """
        if self.target_id and self.physics_obj.world.cur_time > self.sticky_timeout_time:
            self.handle_exit_world()

    def adjust_offset(self, offset: Frame, quantum: float) -> None:
        """Replace the offset with a flat step towards the target and a turn to face it.

        The target is the live object when the world knows it, else the last
        reported position. The step runs along the body-local horizontal
        direction to the target, ``max_speed × 5`` (15 when that is below
        EPSILON) times ``quantum`` long, or exactly the gap to the 0.3 m
        standoff (negative: backing off) when that is within reach. The
        rotation becomes the heading still to turn, in [0, 360).

        The direction is rotated into the body's frame by ``Position::globaltolocalvec``;
        the body's radius (a ``float`` argument), the gap ``mag``, the sought heading and
        the turn are ``float`` stores; the step length stays double, and the "no turn"
        test reads the turn before it is narrowed (acclient.c:388548-388600).

        Retail: StickyManager::adjust_offset @ 0x00555430 (acclient.c:388518)
        """
        if not self.target_id or not self.initialized:
            return
        obj = self.physics_obj
        here = obj.position
        target = obj.world.get_object(self.target_id)
        there = target.position if target is not None else self.target_position
        direction = here.globaltolocalvec(here.get_offset(there))
        direction.z = 0.0
        gap = f32(cylinder_distance_no_z(obj.get_radius(), here, self.target_radius, there) - STICKY_RADIUS)
        if direction.normalize_check_small():
            direction.x = direction.y = direction.z = 0.0
        speed = obj.get_minterp().get_max_speed() * STICKY_SPEED_FACTOR
        if speed < EPSILON:
            speed = STICKY_FALLBACK_SPEED
        step = speed * quantum
        if step >= abs(gap):
            step = gap
        o = offset.origin
        o.x, o.y, o.z = unpack3(pack3(step * direction.x, step * direction.y, step * direction.z))
        sought = f32(position_heading(here, there))
        turn = sought - here.frame.get_heading()
        heading = 0.0 if abs(turn) < EPSILON else f32(turn)
        if heading < -EPSILON:
            heading += 360.0
        offset.set_heading(heading)
