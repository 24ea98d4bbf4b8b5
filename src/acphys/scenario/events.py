"""``[[event]]``: what a scenario does to a body at a given time.

Each action reads its own keys; a key another action uses is an error, so a
misplaced key never passes silently. Motion actions go through the same
retail entry points a client's command interpreter uses (``DoMotion``,
``StopMotion``, ``CMotionInterp::jump``, a move-to or turn-to request), and
their result lands in the body's next trace record: ``"motion:RunForward"``,
or ``"motion:RunForward:error:0x43"`` when retail refuses it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from acphys.constants import BLOCK_LENGTH, MAX_VELOCITY
from acphys.math.cell_id import landblock_of, outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.commands import motion_name
from acphys.motion.movement import HoldKey, MovementParameters
from acphys.physics_obj import PhysicsObj
from acphys.scenario import values as read
from acphys.scenario.values import Ctx
from acphys.simulation import Event

#: The keys each action takes besides ``at``, ``body`` and ``action``; the first list is required.
ACTION_KEYS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "set_velocity": (("velocity",), ()),
    "set_omega": (("omega",), ()),
    "set_state": (("state",), ()),
    "motion": (("motion",), ("speed", "hold_run")),
    "stop_motion": (("motion",), ("speed", "hold_run")),
    "jump": ((), ("extent",)),
    "move_to": (("origin",), ("landblock", "distance", "min_distance", "speed", "hold_run", "fail_distance")),
    "turn_to": (("heading",), ("speed",)),
    "move_to_object": (("target",), ("distance", "min_distance", "speed", "hold_run", "fail_distance")),
    "turn_to_object": (("target",), ("speed",)),
    "interpolate_to": (("origin",), ("landblock", "heading", "keep_heading")),
    "stick_to": (("target",), ()),
    "unstick": ((), ()),
    "constrain_to": (("origin", "start", "max"), ("landblock",)),
    "unconstrain": ((), ()),
    "play_script": (("script",), ()),
    "set_parent": (("target",), ("part", "location", "origin", "heading")),
    "unset_parent": ((), ()),
}
EVENT_ACTIONS = tuple(ACTION_KEYS)
#: Actions that need the body to have a motion table (and so a movement manager).
MOTION_ACTIONS = ("motion", "stop_motion", "jump", "move_to", "turn_to", "move_to_object", "turn_to_object")

Apply = Callable[[PhysicsObj], None]


def speed_limited(ctx: Ctx, key: str, value: Any) -> Vector3:
    """A velocity no faster than retail's 50 m/s limit."""
    velocity = read.vector(ctx, key, value)
    if velocity.length() > MAX_VELOCITY:
        raise ctx.fail(key, f"speed {velocity.length():g} m/s exceeds the retail limit of 50 m/s")
    return velocity


def _report(obj: PhysicsObj, label: str, error: int) -> None:
    obj.record_event(label if not error else f"{label}:error:0x{error:02X}")


def _params(ctx: Ctx, key: str, table: dict[str, Any]) -> MovementParameters:
    """The retail default parameters with the event's speed and hold key.

    ``hold_run = true`` holds the run key (``HoldKey_Run``), ``false`` releases it
    (``HoldKey_None``); without ``hold_run`` the parameters keep retail's default
    ``HoldKey_Invalid``, which leaves the run key as it is, as the keyboard path
    (``CommandInterpreter::MovePlayer``) sends it.
    """
    params = MovementParameters()
    if "speed" in table:
        params.speed = read.float32(ctx, f"{key}.speed", table["speed"], 0.0, 100.0, open_low=True)
    if "hold_run" in table:
        held = read.boolean(ctx, f"{key}.hold_run", table["hold_run"])
        params.hold_key_to_apply = HoldKey.RUN if held else HoldKey.NONE
    return params


def _motion_apply(ctx: Ctx, key: str, action: str, table: dict[str, Any]) -> Apply:
    motion = read.motion(ctx, f"{key}.motion", table["motion"])
    params = _params(ctx, key, table)
    label = f"{action}:{motion_name(motion)}"
    if action == "motion":
        return lambda obj: _report(obj, label, obj.do_motion(motion, params.copy()))
    return lambda obj: _report(obj, label, obj.stop_motion(motion, params.copy()))


def _jump_apply(ctx: Ctx, key: str, table: dict[str, Any]) -> Apply:
    extent = read.float32(ctx, f"{key}.extent", table.get("extent", 1.0), 0.0, 1.0)

    def jump(obj: PhysicsObj) -> None:
        error, _stamina = obj.get_minterp().jump(extent)
        _report(obj, "jump", error)

    return jump


def _position(ctx: Ctx, key: str, table: dict[str, Any], body: PhysicsObj) -> Position:
    """``origin`` (landblock-local) in ``landblock`` (default: the body's), facing ``heading``."""
    origin = read.vector(ctx, f"{key}.origin", table["origin"])
    if not (0.0 <= origin.x < BLOCK_LENGTH and 0.0 <= origin.y < BLOCK_LENGTH):
        raise ctx.fail(
            f"{key}.origin", f"x and y must be landblock-local, in [0, 192), got ({origin.x:g}, {origin.y:g})"
        )
    if "landblock" in table:
        landblock = read.landblock(ctx, f"{key}.landblock", table["landblock"])
    else:
        landblock = landblock_of(body.position.objcell_id)
    heading = read.float32(ctx, f"{key}.heading", table.get("heading", 0.0), -360.0, 360.0)
    return Position(outdoor_cell_id(landblock, origin), Frame.from_heading(origin, heading))


def _move_params(ctx: Ctx, key: str, table: dict[str, Any]) -> MovementParameters:
    """The parameters of a move-to: speed and hold key, and the distances it stops and fails at."""
    params = _params(ctx, key, table)
    if "distance" in table:
        params.distance_to_object = read.float32(ctx, f"{key}.distance", table["distance"], 0.0, 1000.0)
    if "min_distance" in table:
        params.min_distance = read.float32(ctx, f"{key}.min_distance", table["min_distance"], 0.0, 1000.0)
    if "fail_distance" in table:
        params.fail_distance = read.float32(ctx, f"{key}.fail_distance", table["fail_distance"], 0.0, 1e6)
    return params


def _move_to_apply(ctx: Ctx, key: str, table: dict[str, Any], body: PhysicsObj) -> Apply:
    target = _position(ctx, key, table, body)
    params = _move_params(ctx, key, table)
    return lambda obj: _report(obj, "move_to", obj.move_to_position(target, params.copy()))


def _other_body(
    ctx: Ctx, key: str, table: dict[str, Any], body: PhysicsObj, bodies: dict[str, PhysicsObj], purpose: str
) -> str:
    """The name of the event's ``target``: another body of the scenario (``purpose`` is for the error)."""
    name = read.string(ctx, f"{key}.target", table["target"])
    ctx.uses(f"body.{name}")
    if name not in bodies:
        raise ctx.missing("body", f"{key}.target", f"no other body named {name!r} {purpose}")
    if bodies[name] is body:
        raise ctx.fail(f"{key}.target", f"no other body named {name!r} {purpose}")
    return name


def _to_object_apply(
    ctx: Ctx, key: str, action: str, table: dict[str, Any], body: PhysicsObj, bodies: dict[str, PhysicsObj]
) -> Apply:
    """``move_to_object`` / ``turn_to_object``: CPhysicsObj::MoveToObject / TurnToObject on a body."""
    name = _other_body(ctx, key, table, body, bodies, "to move or turn to")
    target = bodies[name]
    if action == "move_to_object":
        params = _move_params(ctx, key, table)

        def move(obj: PhysicsObj) -> None:
            obj.move_to_object(target.id, params.copy())
            obj.record_event(f"move_to_object:{name}")

        return move
    params = _params(ctx, key, table)

    def turn(obj: PhysicsObj) -> None:
        obj.turn_to_object(target.id, params.copy())
        obj.record_event(f"turn_to_object:{name}")

    return turn


def _turn_to_apply(ctx: Ctx, key: str, table: dict[str, Any]) -> Apply:
    params = _params(ctx, key, table)
    params.desired_heading = read.float32(ctx, f"{key}.heading", table["heading"], 0.0, 360.0) % 360.0

    def turn(obj: PhysicsObj) -> None:
        obj.turn_to_heading(params.copy())
        obj.record_event("turn_to")

    return turn


def _manager_apply(
    ctx: Ctx,
    key: str,
    action: str,
    table: dict[str, Any],
    body: PhysicsObj,
    bodies: dict[str, PhysicsObj],
    scripts: dict[str, int],
) -> Apply:
    """The position-manager and script actions, each noted in the body's events."""
    if action == "interpolate_to":
        target = _position(ctx, key, table, body)
        keep_heading = read.boolean(ctx, f"{key}.keep_heading", table.get("keep_heading", False))

        def interpolate(obj: PhysicsObj) -> None:
            obj.interpolate_to(target, keep_heading)
            obj.record_event("interpolate_to")

        return interpolate
    if action == "stick_to":
        name = _other_body(ctx, key, table, body, bodies, "to stick to")
        other = bodies[name]

        def stick(obj: PhysicsObj) -> None:
            obj.stick_to_object(other.id)
            obj.record_event(f"stick_to:{name}")

        return stick
    if action == "unstick":

        def unstick(obj: PhysicsObj) -> None:
            obj.unstick_from_object()
            obj.record_event("unstick")

        return unstick
    if action == "constrain_to":
        anchor = _position(ctx, key, table, body)
        start = read.float32(ctx, f"{key}.start", table["start"], 0.0, 1e4)
        limit = read.float32(ctx, f"{key}.max", table["max"], 0.0, 1e4)
        if not limit > start:
            raise ctx.fail(f"{key}.max", f"must be more than start ({start:g}), got {limit:g}")

        def constrain(obj: PhysicsObj) -> None:
            obj.constrain_to(anchor, start, limit)
            obj.record_event("constrain_to")

        return constrain
    if action == "unconstrain":

        def unconstrain(obj: PhysicsObj) -> None:
            # PositionManager::UnConstrain on the body's manager: retail has no CPhysicsObj entry
            # for it, and a body without a position manager has nothing to let go (making one
            # would activate an inactive body).
            if obj.position_manager is not None:
                obj.position_manager.unconstrain()
            obj.record_event("unconstrain")

        return unconstrain
    name = read.string(ctx, f"{key}.script", table["script"])
    ctx.uses(f"script.{name}")
    if name not in scripts:
        known = ", ".join(scripts) or "none: declare [script.NAME]"
        raise ctx.missing("script", f"{key}.script", f"no script named {name!r} (known: {known})")
    script_id = scripts[name]

    def play(obj: PhysicsObj) -> None:
        obj.record_event(
            f"play_script:{name}" if obj.play_script(script_id) else f"play_script:{name}:failed"
        )

    return play


def _parent_apply(
    ctx: Ctx, key: str, action: str, table: dict[str, Any], body: PhysicsObj, bodies: dict[str, PhysicsObj]
) -> Apply:
    """``set_parent``: the body is held by ``target``, at its setup's holding ``location`` or at
    ``origin``/``heading`` on part ``part`` (default -1, the target itself); ``unset_parent``."""
    if action == "unset_parent":

        def unset(obj: PhysicsObj) -> None:
            obj.unset_parent()
            obj.record_event("unset_parent")

        return unset
    name = _other_body(ctx, key, table, body, bodies, "to be held by")
    parent = bodies[name]
    if "location" in table:
        for frame_key in ("part", "origin", "heading"):
            if frame_key in table:
                raise ctx.fail(f"{key}.{frame_key}", "not used with location (the setup's location gives it)")
        where = table["location"]
        if not isinstance(where, int) or isinstance(where, bool) or not 0 <= where <= 0xFFFFFFFF:
            raise ctx.fail(f"{key}.location", f"expected a holding location id (an integer), got {where!r}")
        if where not in parent.part_array.setup.holding_locations:
            known = ", ".join(str(k) for k in sorted(parent.part_array.setup.holding_locations)) or "none"
            raise ctx.fail(
                f"{key}.location", f"{name!r}'s setup has no holding location {where} (it has: {known})"
            )
        attach = lambda obj: obj.set_parent_at_location(parent, where)  # noqa: E731
    else:
        part = table.get("part", -1)
        parts = len(parent.part_array.parts)
        if not isinstance(part, int) or isinstance(part, bool) or not -1 <= part < parts:
            raise ctx.fail(
                f"{key}.part", f"expected -1 (the whole body) or a part below {parts}, got {part!r}"
            )
        origin = read.local_point(ctx, f"{key}.origin", table.get("origin", [0.0, 0.0, 0.0]))
        heading = read.float32(ctx, f"{key}.heading", table.get("heading", 0.0), -360.0, 360.0)
        frame = Frame.from_heading(origin, heading)
        attach = lambda obj: obj.set_parent(parent, part, frame)  # noqa: E731

    def hold(obj: PhysicsObj) -> None:
        try:
            held = attach(obj)
        except ValueError:  # the target is held, at some depth, by this body
            obj.record_event(f"set_parent:{name}:cycle")
            return
        obj.record_event(f"set_parent:{name}" if held else f"set_parent:{name}:failed")
        if held:
            parent.record_event(f"holds:{obj.name}")

    return hold


def read_event(
    ctx: Ctx, key: str, raw: Any, bodies: dict[str, PhysicsObj], duration: float, scripts: dict[str, int]
) -> Event:
    """One ``[[event]]``, checked against the scenario's bodies and duration."""
    table = read.table(
        ctx, key, raw, ("at", "body", "action", *{k for r, o in ACTION_KEYS.values() for k in r + o})
    )
    for required in ("at", "body", "action"):
        if required not in table:
            raise ctx.fail(f"{key}.{required}", "missing (every event needs at, body and action)")
    at = read.number(ctx, f"{key}.at", table["at"])
    if not 0.0 <= at <= duration:
        raise ctx.fail(f"{key}.at", f"{at:g} s is outside the scenario's [0, {duration:g}] s")
    # The event's own keys first: they are checked even when its body failed to load.
    action = read.string(ctx, f"{key}.action", table["action"])
    if action not in ACTION_KEYS:
        raise ctx.fail(
            f"{key}.action", f"unknown action {action!r} (expected one of: {', '.join(EVENT_ACTIONS)})"
        )
    required, optional = ACTION_KEYS[action]
    extra = [k for k in table if k not in ("at", "body", "action", *required, *optional)]
    if extra:
        takes = ", ".join((*required, *optional)) or "nothing else"
        raise ctx.fail(f"{key}.{extra[0]}", f"not used by action {action!r} (it takes {takes})")
    for needed in required:
        if needed not in table:
            raise ctx.fail(f"{key}.{needed}", f"missing (action {action!r} needs {needed})")
    name = read.string(ctx, f"{key}.body", table["body"])
    ctx.uses(f"body.{name}")
    if name not in bodies:
        known = ", ".join(sorted(bodies))
        raise ctx.missing("body", f"{key}.body", f"no body named {name!r} (bodies: {known})")
    body = bodies[name]
    if action in MOTION_ACTIONS and (body.part_array is None or body.part_array.motion_table_manager is None):
        raise ctx.fail(
            f"{key}.action",
            f'body {name!r} has no motion table for {action!r} (give it motion_table = "humanoid")',
        )

    apply: Apply
    if action == "set_velocity":
        velocity = speed_limited(ctx, f"{key}.velocity", table["velocity"])
        apply = lambda obj: obj.set_velocity(velocity)  # noqa: E731
    elif action == "set_omega":
        omega = read.degrees_per_second(ctx, f"{key}.omega", table["omega"])
        apply = lambda obj: obj.set_omega(omega)  # noqa: E731
    elif action == "set_state":
        state = read.state(ctx, f"{key}.state", table["state"])
        apply = lambda obj: obj.set_state(state)  # noqa: E731
    elif action in ("motion", "stop_motion"):
        apply = _motion_apply(ctx, key, action, table)
    elif action == "jump":
        apply = _jump_apply(ctx, key, table)
    elif action == "move_to":
        apply = _move_to_apply(ctx, key, table, body)
    elif action == "turn_to":
        apply = _turn_to_apply(ctx, key, table)
    elif action in ("move_to_object", "turn_to_object"):
        apply = _to_object_apply(ctx, key, action, table, body, bodies)
    elif action in ("set_parent", "unset_parent"):
        apply = _parent_apply(ctx, key, action, table, body, bodies)
    else:
        apply = _manager_apply(ctx, key, action, table, body, bodies, scripts)
    return Event(at=at, body=name, action=action, apply=apply, source=key)
