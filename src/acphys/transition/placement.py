"""Placement: putting a body's spheres into the world at a position (``find_valid_position`` with
a placement insert type).

The flow, as ``CPhysicsObj::CheckPositionInternal`` drives it: the path starts and ends at the
requested position (``insert_type`` PLACEMENT); :func:`find_placement_position` first inserts the
spheres there as an INITIAL_PLACEMENT (cells collide their geometry, never objects), then as a
PLACEMENT with the objects (:func:`find_placement_pos`, which, when sliding is allowed, tries
rings of positions around the request, up to 4 m away), and finally steps the result down onto
the ground the way a landing does.

The sweep routines used here (``insert_into_cell``, ``check_other_cells``,
``transitional_insert``, ``adjust_offset``, ``step_down``) are the ``Transition``'s.

Divergences from ACE's ``Transition.cs`` (the decompilation wins):

- ACE's ``ValidatePlacementTransition`` resets the collision info only when ``TargetID == 0``
  ("added target id"); retail resets it whenever sliding is allowed (acclient.c:312374).
- ACE spaces the rings with ``Math.PI``; retail multiplies by the literal 3.1415999
  (acclient.c:313096).

One compare of :func:`find_placement_pos` is lost in the decompilation (acclient.c:313148,
``if (c0 | c3)`` after loading ``global_offset``): it is read as "the adjusted offset is at least
EPSILON long", the same reading ACE makes (``GlobalOffset.Length() >= EPSILON``); a shorter one
skips that candidate.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import EPSILON, LANDING_Z
from acphys.flags import TransitionState, member_namespace
from acphys.math.frame import Frame
from acphys.precision import f32
from acphys.transition.transition import InsertType

if TYPE_CHECKING:
    from acphys.transition.transition import Transition

TS = member_namespace(TransitionState)
IT = member_namespace(InsertType)

#: ``find_placement_pos``: rings reach out to this distance (m), 2 m for a sphere under 0.125 m.
PLACEMENT_ADJUST_DISTANCE = 4.0
#: ``find_placement_pos``: smaller spheres are treated as this radius when spacing the rings.
PLACEMENT_MIN_RADIUS = f32(0.48)
#: ``find_placement_pos``: below this radius the sphere is a "fake" one (half the reach).
PLACEMENT_FAKE_RADIUS = 0.125
#: The pi literal ``find_placement_pos`` spaces the candidates around a ring with (acclient.c:313096):
#: a ``float`` constant (the decompiler's eight digits), ``f32(3.1416)``.
PLACEMENT_PI = f32(3.1415999)


def placement_insert(transition: Transition) -> TransitionState:
    """Insert the spheres at ``check_pos`` into ``check_cell`` (three attempts), then into the
    other cells they reach; COLLIDED without a cell.

    Retail: CTransition::placement_insert @ 0x0050B1D0 (acclient.c:312578)
    """
    cell = transition.sphere_path.check_cell
    if cell is None:
        return TS.COLLIDED
    result = transition.insert_into_cell(cell, 3)
    if result == TS.OK:
        result = transition.check_other_cells(transition.sphere_path.check_cell)
    return result


def validate_placement(transition: Transition, ts: TransitionState, adjust: bool) -> TransitionState:
    """Accept an OK insert (``check_pos``/``check_cell`` become ``curr_pos``/``curr_cell``); with
    ``adjust``, re-insert once after ADJUSTED or SLID and validate that without adjusting. No
    ``check_cell`` is COLLIDED.

    Retail: CTransition::validate_placement @ 0x0050B210 (acclient.c:312600)
    """
    path = transition.sphere_path
    if path.check_cell is None:
        return TS.COLLIDED
    if ts == TS.OK:
        _accept_check_pos(transition)
    elif ts in (TS.ADJUSTED, TS.SLID) and adjust:
        return validate_placement(transition, placement_insert(transition), False)
    return ts


def validate_placement_transition(transition: Transition, ts: TransitionState) -> TransitionState:
    """Accept an OK insert as :func:`validate_placement` does; after COLLIDED, ADJUSTED or SLID
    with sliding allowed, reset the collision info for the next try. No ``check_cell`` is
    COLLIDED. (Retail's ``redo`` out-argument is always 0.)

    Retail: CTransition::validate_placement_transition @ 0x0050ADC0 (acclient.c:312354)
    """
    path = transition.sphere_path
    if path.check_cell is None:
        return TS.COLLIDED
    if ts == TS.OK:
        _accept_check_pos(transition)
    elif ts in (TS.COLLIDED, TS.ADJUSTED, TS.SLID) and path.placement_allows_sliding:
        transition.collision_info.init()
    return ts


def _accept_check_pos(transition: Transition) -> None:
    """``curr_pos``/``curr_cell`` take the candidate; the current centres are recached (the OK
    branch of both validations, acclient.c:312366-312370 and 312614-312618)."""
    path = transition.sphere_path
    path.curr_pos = path.check_pos.copy()
    path.curr_cell = path.check_cell
    path.cache_global_curr_center()


def _reset_check_pos(transition: Transition) -> None:
    """Start a candidate over at ``curr_pos`` (acclient.c:313059-313063, 313128-313133)."""
    path = transition.sphere_path
    path.set_check_pos(path.curr_pos, path.curr_cell)


def _clear_contact(transition: Transition) -> None:
    info = transition.collision_info
    info.sliding_normal_valid = False
    info.contact_plane_valid = False
    info.contact_plane_is_water = False


def find_placement_pos(transition: Transition) -> bool:
    """Place the spheres at ``curr_pos`` with a transitional insert (three attempts); failing
    that and with sliding allowed, try rings of candidates around it until one inserts OK.

    The rings: with sphere 0's radius r (raised to 0.48 when under it, unless under 0.125,
    which halves both the reach and the count), there are ceil(4 / r) rings (fewer than two
    gives up), evenly spaced out to 4 m (2 m). Ring i has 2 * ceil(sum of the per-ring angle
    step (spacing / r * 3.1415999) so far) candidates at even compass headings from 0. Each
    candidate offset goes through ``adjust_offset``; one shorter than EPSILON is skipped.

    ``float`` locals (acclient.c:313072-313134): the radius, the reach, the spacing, the angle
    step, the running distance and angle sum (the ring's count is the ceiling of the sum before
    it is stored), the heading step and each heading.

    Retail: CTransition::find_placement_pos @ 0x0050BA50 (acclient.c:313014)
    """
    path = transition.sphere_path
    _reset_check_pos(transition)
    _clear_contact(transition)
    ts = transition.transitional_insert(3)
    if validate_placement_transition(transition, ts) == TS.OK:
        return True
    if not path.placement_allows_sliding:
        return False
    radius = path.local_sphere[0].radius
    fake = radius < PLACEMENT_FAKE_RADIUS
    adjust_rad = PLACEMENT_ADJUST_DISTANCE * 0.5 if fake else PLACEMENT_ADJUST_DISTANCE
    if not fake and radius < PLACEMENT_MIN_RADIUS:
        radius = PLACEMENT_MIN_RADIUS
    steps = PLACEMENT_ADJUST_DISTANCE / radius
    if fake:
        steps *= 0.5
    if steps <= 1.0:
        return False
    num_steps = math.ceil(steps)
    dist_per_step = f32(adjust_rad / num_steps)
    d_num_radial = f32(dist_per_step / radius * PLACEMENT_PI)
    distance = 0.0
    total_rad = 0.0
    for _ in range(num_steps):
        distance = f32(distance + dist_per_step)
        rad_sum = d_num_radial + total_rad
        total_rad = f32(rad_sum)
        num_rad = 2 * math.ceil(rad_sum)
        angle_offset = f32(360.0 / num_rad)
        offset_frame = Frame()
        for ja in range(num_rad):
            _reset_check_pos(transition)
            offset_frame.set_heading(f32(ja * angle_offset))
            offset = offset_frame.get_vector_heading() * distance
            path.global_offset = transition.adjust_offset(offset)
            if path.global_offset.length_squared() < EPSILON * EPSILON:
                continue
            path.add_offset_to_check_pos(path.global_offset)
            _clear_contact(transition)
            ts = transition.transitional_insert(3)
            if validate_placement_transition(transition, ts) == TS.OK:
                return True
    return False


def find_placement_position(transition: Transition) -> bool:
    """Place the spheres at ``curr_pos``: True with ``curr_pos``/``curr_cell`` set when a valid
    position is found.

    An INITIAL_PLACEMENT insert (cell geometry only; ADJUSTED or SLID re-inserts once) must
    succeed; then :func:`find_placement_pos` as a PLACEMENT. A body that steps down then drops
    onto what is below with the landing allowance (``walkable_allowance`` = ``step_down``'s z =
    LANDING_Z) as a transition insert: its step-down height, or half of sphere 0's radius when
    a single sphere's diameter is below it; a height above the diameter is halved and tried
    twice. A failed drop restores the candidate and drops the contact plane. The walkable
    record is cleared and the result validated once more.

    Retail: CTransition::find_placement_position @ 0x0050C170 (acclient.c:313340)
    """
    path = transition.sphere_path
    _reset_check_pos(transition)
    path.insert_type = IT.INITIAL_PLACEMENT
    if validate_placement(transition, placement_insert(transition), True) != TS.OK:
        return False
    path.insert_type = IT.PLACEMENT
    if not find_placement_pos(transition):
        return False
    info = transition.object_info
    if info.step_down:
        step_down_ht = info.step_down_height
        path.walkable_allowance = LANDING_Z
        path.save_check_pos()
        path.backup = path.insert_type
        path.insert_type = IT.TRANSITION
        sphere = path.global_sphere[0]
        if path.num_sphere < 2 and sphere.radius + sphere.radius < step_down_ht:
            step_down_ht = f32(sphere.radius * 0.5)
        if sphere.radius + sphere.radius >= step_down_ht:
            stepped = transition.step_down(step_down_ht, LANDING_Z)
        else:
            half = f32(step_down_ht * 0.5)
            stepped = transition.step_down(half, LANDING_Z) or transition.step_down(half, LANDING_Z)
        if not stepped:
            path.restore_check_pos()
            transition.collision_info.contact_plane_valid = False
            transition.collision_info.contact_plane_is_water = False
        path.insert_type = path.backup
        path.walkable = None
    return validate_placement(transition, TS.OK, True) == TS.OK
