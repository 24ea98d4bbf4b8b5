"""CMotionTable: commands to animation chains, checked against the decompiled GetObjectSequence.

Every expectation is derived by hand from CMTable.c / CMotionPrim.c; the
``acclient.c`` line of the deciding statement sits beside each assertion.
The table is small and hand-built: style NonCombat (0x8000003D) resting in
Ready, cycles Ready / WalkForward / RunForward / TurnRight / Crouch, a few
links, two modifiers (TurnRight, Jump) and one action link (Cheer).
"""

from __future__ import annotations

import pytest

from acphys.math.vector import Vector3
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.commands import (
    CROUCH,
    HAND_COMBAT,
    JUMP,
    MOTION_IDS,
    NON_COMBAT,
    READY,
    RUN_FORWARD,
    TURN_RIGHT,
    WALK_FORWARD,
)
from acphys.motion.motion_table import (
    CLEARS_MODIFIERS,
    DEFAULT_SUBSTATE_ONLY,
    MotionData,
    MotionState,
    MotionTable,
    change_cycle_speed,
    cycle_key,
    same_sign,
)
from acphys.motion.sequence import Sequence
from acphys.precision import f32

CHEER = MOTION_IDS["Cheer"]  # 0x1300004C: an action

WALK_V = Vector3(0.0, 3.12, 0.0)
RUN_V = Vector3(0.0, 4.0, 0.0)
TURN_W = Vector3(0.0, 0.0, -1.5)
JUMP_V = Vector3(0.0, 0.0, 2.0)


def _md(*names: str, velocity: Vector3 | None = None, omega: Vector3 | None = None, bitfield: int = 0):
    anims = [AnimData(Animation([AnimFrame(), AnimFrame()], name=name)) for name in names]
    return MotionData(anims, velocity, omega, bitfield)


def build_table() -> MotionTable:
    """The test table. Keys are written out as 32-bit numbers: (0x8000003D << 16) keeps 0x003D."""
    return MotionTable(
        default_style=NON_COMBAT,
        style_defaults={NON_COMBAT: READY, HAND_COMBAT: READY},
        cycles={
            0x003D0003: _md("ready"),
            0x003D0005: _md("walk", velocity=WALK_V),
            0x003D0007: _md("run", velocity=RUN_V),
            0x003D000D: _md("turn", omega=TURN_W, bitfield=DEFAULT_SUBSTATE_ONLY),
            0x003D0012: _md("crouch", bitfield=CLEARS_MODIFIERS),
            0x003C0003: _md("combat_ready"),
        },
        modifiers={
            0x003D000D: _md(omega=TURN_W),  # TurnRight under NonCombat
            0x0000003B: _md(velocity=JUMP_V),  # Jump, style-independent
        },
        links={
            0x003D0003: {  # from Ready
                WALK_FORWARD: _md("ready_walk_a", "ready_walk_b", velocity=Vector3(0.0, 1.0, 0.0)),
                RUN_FORWARD: _md("ready_run"),
                CROUCH: _md("ready_crouch"),
                CHEER: _md("cheer"),
                HAND_COMBAT: _md("to_combat"),
            },
            0x003D0005: {READY: _md("walk_ready")},  # from WalkForward
            0x003D0000: {READY: _md("any_ready")},  # style-wide: from any substate
        },
    )


def names(seq: Sequence) -> list[str]:
    return [node.animation.name for node in seq.anim_list]


def rates(seq: Sequence) -> list[float]:
    return [node.framerate for node in seq.anim_list]


def at_rest(table: MotionTable) -> tuple[MotionState, Sequence]:
    state, seq = MotionState(), Sequence()
    assert table.set_default_state(state, seq) == (True, 0)
    return state, seq


def walking(table: MotionTable, speed: float = 1.0) -> tuple[MotionState, Sequence]:
    state, seq = at_rest(table)
    assert table.do_object_motion(WALK_FORWARD, state, seq, speed)[0]
    return state, seq


# -- keys, state, helpers --------------------------------------------------------------------


def test_cycle_key_keeps_32_bits() -> None:
    # (style << 16) | (motion & 0xFFFFFF) in a 32-bit register (acclient.c:337765)
    assert cycle_key(NON_COMBAT, WALK_FORWARD) == 0x003D0005
    assert cycle_key(NON_COMBAT, 0) == 0x003D0000


def test_motion_data_rejects_a_bitfield_wider_than_a_byte() -> None:
    with pytest.raises(ValueError, match="bitfield"):
        MotionData([], bitfield=0x100)


def test_motion_data_rejects_what_is_not_anim_data() -> None:
    with pytest.raises(ValueError, match="animation 0 must be an AnimData"):
        MotionData([Animation([AnimFrame()])])


def test_table_rejects_a_key_wider_than_32_bits() -> None:
    with pytest.raises(ValueError, match="cycles key"):
        MotionTable(NON_COMBAT, {NON_COMBAT: READY}, {NON_COMBAT << 16: _md("x")})


def test_motion_state_lists() -> None:
    state = MotionState()
    assert (state.style, state.substate, state.substate_mod) == (0, 0, 1.0)  # acclient.c:341305-341307
    state.substate = WALK_FORWARD
    assert state.add_modifier(JUMP, 1.0)
    assert state.add_modifier(TURN_RIGHT, 0.5)
    # new modifiers go to the head (acclient.c:341333-341334)
    assert [node.motion for node in state.modifiers] == [TURN_RIGHT, JUMP]
    assert not state.add_modifier(JUMP, 2.0)  # already there (acclient.c:341626-341632)
    assert not state.add_modifier(WALK_FORWARD, 1.0)  # it is the substate (acclient.c:341635-341636)
    state.add_action(CHEER, 1.0)
    state.add_action(0x1000004A, 1.0)
    assert state.remove_action_head() == CHEER  # FIFO (acclient.c:341392-341397, 341433)
    assert state.remove_action_head() == 0x1000004A
    assert state.remove_action_head() == 0  # acclient.c:341428


def test_motion_state_copy_is_deep() -> None:
    state = MotionState()
    state.add_modifier_no_check(JUMP, 0.5)
    copy = state.copy()
    copy.modifiers[0].speed_mod = 2.0
    # MotionState::copy allocates new nodes (acclient.c:341512-341528)
    assert state.modifiers[0].speed_mod == 0.5


def test_same_sign_counts_zero_as_positive() -> None:
    # a >= 0 -> b >= 0; a < 0 -> b < 0 (acclient.c:337256-337265)
    assert same_sign(0.0, 1.0)
    assert same_sign(1.0, 0.0)
    assert not same_sign(-0.65, 1.0)
    assert same_sign(-0.65, -1.0)
    assert not same_sign(1.0, -0.0001)


def test_change_cycle_speed_cannot_restart_a_zero_speed_cycle() -> None:
    _, seq = walking(build_table())
    # |old| <= EPSILON and |new| >= EPSILON: nothing (acclient.c:337273-337276)
    change_cycle_speed(seq, None, 0.0, 1.0)
    assert rates(seq)[-1] == 30.0
    change_cycle_speed(seq, None, 0.0001, 0.0001)  # both near zero: rate x 0 (acclient.c:337276)
    assert rates(seq)[-1] == 0.0


# -- default state ---------------------------------------------------------------------------


def test_set_default_state() -> None:
    table = build_table()
    state, seq = MotionState(), Sequence()
    state.add_modifier_no_check(JUMP, 1.0)
    state.add_action(CHEER, 1.0)
    seq.set_velocity(Vector3(5.0, 5.0, 5.0))
    ok, num_anims = table.set_default_state(state, seq)
    assert ok
    assert num_anims == 0  # cycle anims - 1 (acclient.c:338009)
    # acclient.c:338006-338008
    assert (state.style, state.substate, state.substate_mod) == (NON_COMBAT, READY, 1.0)
    assert state.modifiers == [] and state.actions == []  # acclient.c:337989-337990
    assert names(seq) == ["ready"]  # clear_animations then add_motion (acclient.c:338011-338012)
    assert seq.velocity.exactly_equals(Vector3())  # clear_physics (acclient.c:338010)


def test_set_default_state_fails_without_a_default_cycle() -> None:
    table = MotionTable(NON_COMBAT, {NON_COMBAT: READY}, {})
    state, seq = MotionState(), Sequence()
    # no cycle: return 0 (acclient.c:337995-337996, 338018)
    assert table.set_default_state(state, seq) == (False, 0)
    assert state.style == 0


def test_set_default_state_count_wraps_for_an_empty_cycle() -> None:
    table = MotionTable(NON_COMBAT, {NON_COMBAT: READY}, {0x003D0003: MotionData([])})
    # *num_anims = (unsigned byte)0 - 1 into an unsigned int (acclient.c:338009)
    assert table.set_default_state(MotionState(), Sequence()) == (True, 0xFFFFFFFF)


def test_no_style_or_no_substate_fails() -> None:
    table = build_table()
    state = MotionState()
    # acclient.c:337683-337684
    assert table.do_object_motion(WALK_FORWARD, state, Sequence(), 1.0) == (False, 0)


# -- substates -------------------------------------------------------------------------------


def test_walk_forward_from_ready_appends_link_then_cycle() -> None:
    table = build_table()
    state, seq = at_rest(table)
    ok, num_anims = table.do_object_motion(WALK_FORWARD, state, seq, 1.5)
    assert ok
    # remove_cyclic_anims drops Ready; link then cycle (acclient.c:337810, 337808)
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk"]
    # each AnimData is appended as speed * anim: framerate 30 x 1.5 (acclient.c:337465)
    assert rates(seq) == [45.0, 45.0, 45.0]
    # the cycle's add_motion comes last and set_velocity replaces the link's (acclient.c:337451)
    assert seq.velocity.exactly_equals(Vector3(0.0, 3.12 * 1.5, 0.0))
    assert num_anims == 2  # link 2 + cycle 1 - 1 (acclient.c:337835)
    assert (state.substate, state.substate_mod) == (WALK_FORWARD, 1.5)  # acclient.c:337824-337825


def test_negative_speed_goes_via_the_default_with_the_reversed_link() -> None:
    table = build_table()
    state, seq = at_rest(table)
    ok, num_anims = table.do_object_motion(WALK_FORWARD, state, seq, -0.65)
    assert ok
    # Sign flip, so via the default (acclient.c:337786-337793): Ready->Ready is the style-wide link
    # (acclient.c:337633), played at the old speed 1.0; get_link(Ready, 1.0, Walk, -0.65) has a
    # negative speed and reverses the lookup to links[Walk][Ready] (acclient.c:337597-337606).
    assert names(seq) == ["any_ready", "walk_ready", "walk"]
    # speed_mod is a float parameter, and each framerate the float store of 30 * f32(-0.65)
    # (operator*, acclient.c:341061-341064).
    speed = f32(-0.65)
    assert rates(seq) == [30.0, f32(30.0 * speed), f32(30.0 * speed)]  # acclient.c:337799-337800, 337810
    assert seq.velocity.exactly_equals(WALK_V * speed)
    assert num_anims == 2  # 1 + 1 + 1 - 1 (acclient.c:337835)
    assert state.substate_mod == speed  # the float field takes the float parameter (acclient.c:337824)


def test_get_link_forward_reversed_and_fallbacks() -> None:
    table = build_table()
    ready_walk = table.links[0x003D0003][WALK_FORWARD]
    walk_ready = table.links[0x003D0005][READY]
    any_ready = table.links[0x003D0000][READY]
    assert table.get_link(NON_COMBAT, READY, 1.0, WALK_FORWARD, 1.0) is ready_walk  # acclient.c:337613-337618
    # either speed negative: links[(style, motion)][substate] (acclient.c:337597-337606)
    assert table.get_link(NON_COMBAT, READY, 1.0, WALK_FORWARD, -1.0) is walk_ready
    assert table.get_link(NON_COMBAT, READY, -1.0, WALK_FORWARD, 1.0) is walk_ready
    # reversed miss: links[(style, substate)][style default] (acclient.c:337626-337631)
    assert table.get_link(NON_COMBAT, WALK_FORWARD, -1.0, RUN_FORWARD, 1.0) is walk_ready
    # forward miss: the style-wide links[style << 16] (acclient.c:337633-337635)
    assert table.get_link(NON_COMBAT, RUN_FORWARD, 1.0, READY, 1.0) is any_ready
    assert table.get_link(NON_COMBAT, RUN_FORWARD, 1.0, CROUCH, 1.0) is None


def test_speed_change_rescales_the_cycle_and_swaps_its_physics() -> None:
    table = build_table()
    state, seq = walking(table)
    assert table.do_object_motion(JUMP, state, seq, 1.0) == (True, 0)  # modifier layered on
    before = list(seq.anim_list)
    ok, num_anims = table.do_object_motion(WALK_FORWARD, state, seq, 2.0)
    assert (ok, num_anims) == (True, 0)
    # same substate, same sign, has anims: nothing is rebuilt (acclient.c:337773)
    assert seq.anim_list == before
    # only the cyclic animation is rescaled by 2.0 / 1.0 (acclient.c:337775, 337281)
    assert rates(seq) == [30.0, 30.0, 60.0]
    # physics: minus walk x 1, plus walk x 2, the Jump modifier kept (acclient.c:337776-337777)
    assert seq.velocity.exactly_equals(Vector3(0.0, 3.12 * 2.0, 2.0))
    assert state.substate_mod == 2.0


def test_speed_zero_then_back_leaves_the_cycle_frozen() -> None:
    # ACE compares Math.Sign, for which 0 and 1 differ, and so relinks: retail's same_sign keeps
    # 0 -> 1 on the rescale path, where change_cycle_speed cannot undo a zero rate.
    table = build_table()
    state, seq = walking(table)
    assert table.do_object_motion(WALK_FORWARD, state, seq, 0.0) == (True, 0)
    assert rates(seq)[-1] == 0.0  # acclient.c:337276
    # same_sign(1, 0) (acclient.c:337773)
    assert table.do_object_motion(WALK_FORWARD, state, seq, 1.0) == (True, 0)
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk"]  # not rebuilt
    assert rates(seq)[-1] == 0.0  # old speed 0: no rescale (acclient.c:337273-337276)
    assert seq.velocity.exactly_equals(WALK_V)  # the physics did come back (acclient.c:337777)


def test_stop_object_motion_returns_to_the_style_default() -> None:
    table = build_table()
    state, seq = walking(table)
    ok, num_anims = table.stop_object_motion(WALK_FORWARD, 1.0, state, seq)
    assert ok  # acclient.c:337934
    # GetObjectSequence(Ready, speed 1, stop_modifiers): link Walk->Ready then Ready (acclient.c:337933)
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk_ready", "ready"]
    assert num_anims == 1  # 1 + 1 - 1
    assert (state.substate, state.substate_mod) == (READY, 1.0)
    assert seq.velocity.exactly_equals(Vector3())


def test_stop_of_something_not_playing_fails() -> None:
    table = build_table()
    state, seq = walking(table)
    assert table.stop_object_motion(RUN_FORWARD, 1.0, state, seq) == (False, 0)  # acclient.c:337963
    assert table.stop_object_motion(JUMP, 1.0, state, seq) == (False, 0)  # modifier not in the list


def test_turn_in_place_then_ready_is_a_no_op_until_stopped() -> None:
    table = build_table()
    state, seq = at_rest(table)
    # TurnRight from Ready: allowed (the substate is the default, acclient.c:337771); no Ready->Turn
    # link, so via the default: Ready->Ready is the style-wide link (acclient.c:337792, 337633)
    assert table.do_object_motion(TURN_RIGHT, state, seq, 1.0) == (True, 1)
    assert names(seq) == ["any_ready", "turn"]
    assert state.substate == TURN_RIGHT
    assert seq.omega.exactly_equals(TURN_W)
    # Ready asked while the substate carries the modifier bit and no stop is under way: return 1
    # without touching anything (acclient.c:337696-337697)
    assert table.do_object_motion(READY, state, seq, 1.0) == (True, 0)
    assert state.substate == TURN_RIGHT
    assert seq.omega.exactly_equals(TURN_W)
    # Stopping the turn passes stop_modifiers = 1, which skips that test (acclient.c:337933)
    assert table.stop_object_motion(TURN_RIGHT, 1.0, state, seq) == (True, 1)
    assert state.substate == READY
    assert names(seq)[-2:] == ["any_ready", "ready"]  # style-wide link (acclient.c:337633)
    # the replaced turn is not kept as a modifier: the new substate is the default (acclient.c:337818-337821)
    assert state.modifiers == []


def test_is_allowed() -> None:
    table = build_table()
    turn = table.cycles[0x003D000D]
    walk = table.cycles[0x003D0005]
    state = MotionState()
    state.style, state.substate = NON_COMBAT, WALK_FORWARD
    # bit 2, not from the default (acclient.c:337568-337574)
    assert not table.is_allowed(TURN_RIGHT, turn, state)
    assert table.is_allowed(WALK_FORWARD, walk, state)  # no bit 2 (acclient.c:337578)
    assert not table.is_allowed(WALK_FORWARD, None, state)  # acclient.c:337565
    state.substate = READY
    assert table.is_allowed(TURN_RIGHT, turn, state)  # from the style default
    state.substate = TURN_RIGHT
    assert table.is_allowed(TURN_RIGHT, turn, state)  # it already is the substate


def test_turn_while_walking_becomes_a_modifier() -> None:
    table = build_table()
    state, seq = walking(table)
    # not allowed as a cycle -> falls to the modifier branch (acclient.c:337870-337886)
    assert table.do_object_motion(TURN_RIGHT, state, seq, 1.0) == (True, 0)
    assert state.substate == WALK_FORWARD
    assert [(n.motion, n.speed_mod) for n in state.modifiers] == [(TURN_RIGHT, 1.0)]
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk"]
    assert seq.velocity.exactly_equals(WALK_V)
    assert seq.omega.exactly_equals(TURN_W)  # combine_motion (acclient.c:337885)


def test_replaced_turn_substate_stays_on_as_a_modifier() -> None:
    table = build_table()
    state, seq = at_rest(table)
    table.do_object_motion(TURN_RIGHT, state, seq, 1.0)
    ok, num_anims = table.do_object_motion(WALK_FORWARD, state, seq, 1.0)
    assert ok
    # no link Turn->Walk: Turn->Ready (style-wide) then Ready->Walk (acclient.c:337792-337793)
    assert names(seq)[1:] == ["any_ready", "ready_walk_a", "ready_walk_b", "walk"]
    assert num_anims == 3  # 1 + 2 + 1 - 1
    # the old substate has the modifier bit and Walk is not the default: kept (acclient.c:337814-337821),
    # then re_modify re-applies it through the modifier branch (acclient.c:337826)
    assert [n.motion for n in state.modifiers] == [TURN_RIGHT]
    assert seq.velocity.exactly_equals(WALK_V)
    assert seq.omega.exactly_equals(TURN_W)


def test_re_modify_reapplies_the_head_modifier_once_per_modifier() -> None:
    # re_modify takes state->modifier_head afresh on every turn, and GetObjectSequence pushes the
    # re-added modifier back at the head: the head is applied n times, the others never
    # (acclient.c:337305-337310). ACE's loop is the same.
    table = build_table()
    state, seq = walking(table)
    table.do_object_motion(JUMP, state, seq, 1.0)
    table.do_object_motion(TURN_RIGHT, state, seq, 1.0)
    assert [n.motion for n in state.modifiers] == [TURN_RIGHT, JUMP]
    assert table.do_object_motion(RUN_FORWARD, state, seq, 1.0)[0]
    assert [n.motion for n in state.modifiers] == [TURN_RIGHT, JUMP]
    assert seq.omega.exactly_equals(TURN_W * 2.0)
    assert seq.velocity.exactly_equals(RUN_V)  # Jump's 2.0 up is not re-added


def test_cycle_that_clears_modifiers_refuses_them() -> None:
    table = build_table()
    state, seq = at_rest(table)
    table.do_object_motion(JUMP, state, seq, 1.0)
    assert table.do_object_motion(CROUCH, state, seq, 1.0)[0]
    assert state.modifiers == []  # bitfield & 1 (acclient.c:337783-337784)
    assert table.do_object_motion(JUMP, state, seq, 1.0) == (False, 0)  # acclient.c:337876
    assert seq.velocity.exactly_equals(Vector3())


# -- modifiers -------------------------------------------------------------------------------


def test_modifier_uses_the_style_independent_fallback_key() -> None:
    table = build_table()
    state, seq = at_rest(table)
    # modifiers[style|0x3B] misses, modifiers[0x3B] hits (acclient.c:337878-337879)
    assert table.do_object_motion(JUMP, state, seq, 0.5) == (True, 0)
    assert seq.velocity.exactly_equals(JUMP_V * 0.5)
    assert names(seq) == ["ready"]


def test_modifier_again_is_stopped_and_re_added_at_the_new_speed() -> None:
    table = build_table()
    state, seq = at_rest(table)
    table.do_object_motion(JUMP, state, seq, 1.0)
    # add_modifier fails, StopSequenceMotion subtracts at the old speed, add again (acclient.c:337881-337885)
    assert table.do_object_motion(JUMP, state, seq, 0.5) == (True, 0)
    assert seq.velocity.exactly_equals(JUMP_V * 0.5)
    assert [(n.motion, n.speed_mod) for n in state.modifiers] == [(JUMP, 0.5)]


def test_stopping_a_modifier_subtracts_at_its_own_speed() -> None:
    table = build_table()
    state, seq = walking(table)
    table.do_object_motion(JUMP, state, seq, 0.5)
    # the speed argument is unused: the node's speed_mod is subtracted (acclient.c:337956)
    assert table.stop_object_motion(JUMP, 3.0, state, seq) == (True, 0)
    assert seq.velocity.exactly_equals(WALK_V)
    assert state.modifiers == []


def test_stop_object_completely() -> None:
    table = build_table()
    state, seq = walking(table)
    table.do_object_motion(JUMP, state, seq, 1.0)
    table.do_object_motion(TURN_RIGHT, state, seq, 1.0)
    ok, num_anims = table.stop_object_completely(state, seq)
    assert ok
    assert num_anims == 1  # the substate stop's: Walk->Ready link + Ready - 1 (acclient.c:339044)
    assert state.modifiers == [] and state.substate == READY
    assert seq.velocity.exactly_equals(Vector3()) and seq.omega.exactly_equals(Vector3())


def test_stop_object_completely_refuses_a_modifier_it_cannot_stop() -> None:
    table = build_table()
    state, seq = walking(table)
    state.add_modifier_no_check(0x2000003A, 1.0)  # StopTurning: no modifier data in this table
    # retail's while (modifier_head) would never end (acclient.c:339039-339043)
    with pytest.raises(ValueError, match="0x2000003A"):
        table.stop_object_completely(state, seq)


# -- actions ---------------------------------------------------------------------------------


def test_action_with_a_direct_link() -> None:
    table = build_table()
    state, seq = at_rest(table)
    ok, num_anims = table.do_object_motion(CHEER, state, seq, 1.0)
    assert ok
    assert [n.motion for n in state.actions] == [CHEER]  # acclient.c:337851
    assert names(seq) == ["cheer", "ready"]  # link, then the cycle again (acclient.c:337854-337855)
    assert num_anims == 1  # the link's count only (acclient.c:337857)
    assert state.substate == READY


def test_action_via_the_default_substate() -> None:
    # ACE counts the third link with the first link's count (motionData.Anims.Count) and would give 3.
    table = build_table()
    state, seq = walking(table)
    ok, num_anims = table.do_object_motion(CHEER, state, seq, 1.0)
    assert ok
    # Walk->Ready, Ready->Cheer, Ready->Walk, Walk (acclient.c:337898-337901)
    assert names(seq)[2:] == ["walk_ready", "cheer", "ready_walk_a", "ready_walk_b", "walk"]
    assert num_anims == 4  # 1 + 1 + 2 (acclient.c:337903-337907)
    assert seq.velocity.exactly_equals(WALK_V)  # the cycle at substate_mod comes last
    assert state.substate == WALK_FORWARD


# -- styles ----------------------------------------------------------------------------------


def test_style_change() -> None:
    table = build_table()
    state, seq = walking(table)
    ok, num_anims = table.do_object_motion(HAND_COMBAT, state, seq, 1.0)
    assert ok
    # pre_link Walk->Ready, link Ready->HandCombat, the new style's default cycle (acclient.c:337738-337741)
    assert names(seq)[2:] == ["walk_ready", "to_combat", "combat_ready"]
    assert num_anims == 2  # 1 + 1 + 0 + 1 - 1 (acclient.c:337758)
    assert (state.style, state.substate) == (HAND_COMBAT, READY)  # acclient.c:337742-337743
    # already there (acclient.c:337702)
    assert table.do_object_motion(HAND_COMBAT, state, seq, 1.0) == (True, 0)


def test_style_change_enters_the_new_styles_default() -> None:
    # ACE looks the cycle up with the *current* style's default and stores that as the substate;
    # retail uses style_defaults[new style] for both (acclient.c:337716-337720, 337742).
    table = build_table()
    table.style_defaults[HAND_COMBAT] = WALK_FORWARD
    table.cycles[0x003C0005] = _md("combat_walk")
    state, seq = at_rest(table)
    assert table.do_object_motion(HAND_COMBAT, state, seq, 1.0)[0]
    assert (state.style, state.substate) == (HAND_COMBAT, WALK_FORWARD)
    assert names(seq)[-1] == "combat_walk"
