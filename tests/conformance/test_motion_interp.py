"""CMotionInterp, RawMotionState / InterpretedMotionState and the weenie formulas, against the decompilation.

Expected values are worked by hand from the cited acclient.c lines
(CMotionInterp.c, CMInterpPrim.c, ACCWeenieObj.c, MovementSystem.c). The
state tests run the real chain: a body with a part array whose motion-table
manager holds a small hand-built NonCombat table.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState, TransientState
from acphys.math.vector import Vector3
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.commands import (
    CROUCH,
    DEAD,
    FALLEN,
    FALLING,
    HAND_COMBAT,
    NON_COMBAT,
    READY,
    RUN_FORWARD,
    SIDE_STEP_LEFT,
    SIDE_STEP_RIGHT,
    SITTING,
    SLEEPING,
    TURN_LEFT,
    TURN_RIGHT,
    WALK_BACKWARDS,
    WALK_FORWARD,
    motion_id,
)
from acphys.motion.interp import (
    SIDESTEP_FACTOR,
    InterpretedMotionState,
    MotionInterp,
    RawMotionState,
    motion_allows_jump,
)
from acphys.motion.motion_table import MotionData, MotionTable, cycle_key
from acphys.motion.movement import HoldKey, MovementError, MovementFlags, MovementParameters
from acphys.motion.weenie import Weenie, get_jump_height, get_run_rate, jump_stamina_cost, load_mod
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.world.world import World
from support import place

MF = MovementFlags
TS = TransientState
ACTION = motion_id("Twitch1")  # an action (0x10000000 class)


def anim_table() -> MotionTable:
    """NonCombat: Ready / walk / run / falling cycles, turn and sidestep modifiers; HandCombat: Ready."""
    anim = Animation([AnimFrame() for _ in range(10)], name="loop")

    def data(velocity: Vector3 | None = None, omega: Vector3 | None = None) -> MotionData:
        return MotionData([AnimData(anim)], velocity, omega)

    cycles = {
        cycle_key(NON_COMBAT, READY): data(),
        cycle_key(NON_COMBAT, WALK_FORWARD): data(Vector3(0.0, 3.12, 0.0)),
        cycle_key(NON_COMBAT, RUN_FORWARD): data(Vector3(0.0, 4.0, 0.0)),
        cycle_key(NON_COMBAT, FALLING): data(),
        cycle_key(HAND_COMBAT, READY): data(),
    }
    modifiers = {
        cycle_key(NON_COMBAT, TURN_RIGHT): data(omega=Vector3(0.0, 0.0, 1.5)),
        cycle_key(NON_COMBAT, SIDE_STEP_RIGHT): data(Vector3(1.25, 0.0, 0.0)),
    }
    links = {
        cycle_key(NON_COMBAT, READY): {ACTION: data()},
        cycle_key(NON_COMBAT, WALK_FORWARD): {ACTION: data()},
    }
    return MotionTable(NON_COMBAT, {NON_COMBAT: READY, HAND_COMBAT: READY}, cycles, modifiers, links)


def body_with_table(world: World, *, on_ground: bool = True, weenie: Weenie | None = None) -> PhysicsObj:
    body = place(world, on_ground=on_ground)
    body.weenie_obj = weenie
    body.set_motion_table(anim_table())
    return body


def interp(world: World, **kwargs: object) -> MotionInterp:
    return body_with_table(world, **kwargs).get_minterp()


def table_state(body: PhysicsObj):  # the motion table manager's MotionState
    return body.part_array.motion_table_manager.state


F32_WALK = f32(3.1199999)


# -- get_state_velocity ------------------------------------------------------------------------


class TestStateVelocity:
    def test_walk_is_3_12_times_speed(self, world: World) -> None:
        m = interp(world)
        m.interpreted_state.forward_command = WALK_FORWARD
        m.interpreted_state.forward_speed = 0.5
        # v.y = 3.1199999 * forward_speed (acclient.c:343561)
        assert m.get_state_velocity().y == pytest.approx(F32_WALK * 0.5, abs=0.0)
        assert m.get_state_velocity().x == 0.0

    def test_run_is_4_times_speed(self, world: World) -> None:
        m = interp(world)
        m.interpreted_state.forward_command = RUN_FORWARD
        m.interpreted_state.forward_speed = 0.75
        # v.y = 4.0 * forward_speed (acclient.c:343565)
        assert m.get_state_velocity().y == 3.0

    def test_sidestep_is_1_25_times_speed_only_for_sidestep_right(self, world: World) -> None:
        m = interp(world)
        m.interpreted_state.sidestep_command = SIDE_STEP_RIGHT
        m.interpreted_state.sidestep_speed = -0.5
        # v.x = 1.25 * sidestep_speed for 0x6500000F only (acclient.c:343552-343553)
        assert m.get_state_velocity().x == -0.625
        m.interpreted_state.sidestep_command = SIDE_STEP_LEFT
        assert m.get_state_velocity().x == 0.0  # (acclient.c:343555)

    def test_magnitude_capped_at_run_rate_times_4(self, world: World) -> None:
        m = interp(world)
        s = m.interpreted_state
        s.forward_command, s.forward_speed = RUN_FORWARD, 3.0
        s.sidestep_command, s.sidestep_speed = SIDE_STEP_RIGHT, 3.0
        v = m.get_state_velocity()
        # |(3.75, 12)| > 1.0 * 4 -> scaled to length 4 along the same direction (acclient.c:343586-343592)
        assert v.length() == pytest.approx(4.0)
        assert v.x / v.y == pytest.approx(3.75 / 12.0)

    def test_no_weenie_caps_at_4_even_with_my_run_rate_set(self, world: World) -> None:
        m = interp(world)
        m.my_run_rate = 2.0
        m.interpreted_state.forward_command, m.interpreted_state.forward_speed = RUN_FORWARD, 2.0
        # No weenie: rate 1.0 (acclient.c:343582-343584), so 8 m/s is capped to 4.
        # ACE's get_state_velocity starts from MyRunRate without a weenie (8 m/s): decompile wins.
        assert m.get_state_velocity().y == pytest.approx(4.0)

    def test_weenie_that_cannot_say_uses_my_run_rate(self, world: World) -> None:
        m = interp(world, weenie=Weenie(the_player=False))
        m.my_run_rate = 2.0
        m.interpreted_state.forward_command, m.interpreted_state.forward_speed = RUN_FORWARD, 2.5
        # InqRunRate fails -> my_run_rate (acclient.c:343577-343580): cap 8, so 10 -> 8.
        assert m.get_state_velocity().y == pytest.approx(8.0)


# -- adjust_motion / apply_run_to_command --------------------------------------------------------


class TestAdjustMotion:
    def test_turn_left_becomes_turn_right_negated(self, world: World) -> None:
        # (acclient.c:343764-343767)
        assert interp(world).adjust_motion(TURN_LEFT, 0.8, HoldKey.NONE) == (TURN_RIGHT, f32(-0.8))

    def test_walk_backwards_is_walk_forward_times_minus_0_65(self, world: World) -> None:
        motion, speed = interp(world).adjust_motion(WALK_BACKWARDS, 1.0, HoldKey.NONE)
        # v7 = -0.64999998 (acclient.c:343776-343777)
        assert motion == WALK_FORWARD
        assert speed == f32(-0.64999998)

    def test_sidestep_left_becomes_right_negated_and_scaled(self, world: World) -> None:
        motion, speed = interp(world).adjust_motion(SIDE_STEP_LEFT, 1.0, HoldKey.NONE)
        # negate, then x 3.1199999 / 1.25 * 0.5 (acclient.c:343789-343793, 343786)
        assert motion == SIDE_STEP_RIGHT
        assert speed == -f32(F32_WALK / 1.25 * 0.5)

    def test_sidestep_factor_is_the_float32_retail_value(self, world: World) -> None:
        _, speed = interp(world).adjust_motion(SIDE_STEP_RIGHT, 1.0, HoldKey.NONE)
        # 3.1199999f / 1.25 * 0.5 stored to a float (acclient.c:343786): 1.2479999 (0x3F9FBE76),
        # not f32(1.248) = 1.2480000 (0x3F9FBE77).
        assert pytest.approx(1.248, abs=1e-7) == SIDESTEP_FACTOR
        assert speed == 1.247999906539917
        assert speed != f32(1.248)

    def test_run_forward_is_returned_untouched(self, world: World) -> None:
        # RunForward returns before the hold key is looked at (acclient.c:343772-343773)
        assert interp(world).adjust_motion(RUN_FORWARD, 0.3, HoldKey.RUN) == (RUN_FORWARD, 0.3)

    def test_non_creature_weenie_is_left_alone(self, world: World) -> None:
        m = interp(world, weenie=Weenie(creature=False))
        # weenie && !IsCreature -> return (acclient.c:343759-343760)
        assert m.adjust_motion(TURN_LEFT, 1.0, HoldKey.RUN) == (TURN_LEFT, 1.0)

    def test_invalid_key_follows_current_holdkey(self, world: World) -> None:
        m = interp(world)
        m.raw_state.current_holdkey = HoldKey.RUN
        # key Invalid -> raw_state.current_holdkey; == 2 -> apply_run_to_command (acclient.c:343798-343802)
        assert m.adjust_motion(WALK_FORWARD, 1.0) == (RUN_FORWARD, 1.0)
        assert m.adjust_motion(WALK_FORWARD, 1.0, HoldKey.NONE) == (WALK_FORWARD, 1.0)


class TestApplyRunToCommand:
    def test_walk_becomes_run_at_the_run_rate(self, world: World) -> None:
        m = interp(world, weenie=Weenie(run_skill=200))
        # rate = (1 * (200/400 * 11) + 4) / 4 = 2.375 (acclient.c:713801); walk -> run x rate
        # (acclient.c:343463-343466)
        assert m.apply_run_to_command(WALK_FORWARD, 1.0) == (RUN_FORWARD, 2.375)

    def test_backwards_walk_stays_a_walk_but_is_scaled(self, world: World) -> None:
        m = interp(world, weenie=Weenie(run_skill=200))
        # speed <= 0 keeps WalkForward; speed still x rate (acclient.c:343464-343466)
        assert m.apply_run_to_command(WALK_FORWARD, -0.5) == (WALK_FORWARD, -1.1875)

    def test_turn_is_1_5_times(self, world: World) -> None:
        # (acclient.c:343468-343469)
        assert interp(world).apply_run_to_command(TURN_RIGHT, -1.0) == (TURN_RIGHT, -1.5)

    def test_sidestep_clamped_to_plus_minus_3(self, world: World) -> None:
        m = interp(world, weenie=Weenie(run_skill=600))
        # rate = (600/800 * 11 + 4) / 4 = 3.0625; 1.248 * 3.0625 = 3.82 > 3 -> 3 (acclient.c:343471-343479)
        assert m.apply_run_to_command(SIDE_STEP_RIGHT, SIDESTEP_FACTOR) == (SIDE_STEP_RIGHT, 3.0)
        assert m.apply_run_to_command(SIDE_STEP_RIGHT, -SIDESTEP_FACTOR) == (SIDE_STEP_RIGHT, -3.0)
        assert m.apply_run_to_command(SIDE_STEP_RIGHT, 0.5) == (SIDE_STEP_RIGHT, 1.53125)

    def test_no_weenie_rate_is_1(self, world: World) -> None:
        m = interp(world)
        m.my_run_rate = 2.0
        # no weenie -> 1.0 (acclient.c:343457-343459)
        assert m.apply_run_to_command(WALK_FORWARD, 1.0) == (RUN_FORWARD, 1.0)


class TestMaxSpeed:
    def test_max_speed_is_run_rate_times_4(self, world: World) -> None:
        # (acclient.c:343497-343506)
        assert interp(world).get_max_speed() == 4.0
        assert interp(world, weenie=Weenie(run_skill=200)).get_max_speed() == 9.5
        m = interp(world, weenie=Weenie(the_player=False))
        m.my_run_rate = 1.5
        assert m.get_max_speed() == 6.0

    def test_adjusted_max_speed_uses_the_running_speed(self, world: World) -> None:
        m = interp(world, weenie=Weenie(run_skill=200))
        assert m.get_adjusted_max_speed() == 9.5  # rate x 4 (acclient.c:343535)
        m.interpreted_state.forward_command, m.interpreted_state.forward_speed = RUN_FORWARD, 1.5
        m.current_speed_factor = 0.5
        # running: forward_speed / current_speed_factor (acclient.c:343533-343534) -> 3 x 4
        assert m.get_adjusted_max_speed() == 12.0


# -- contact, jumping ------------------------------------------------------------------------------


class TestContactAllowsMove:
    def test_grounded_creature_may_move(self, world: World) -> None:
        assert interp(world).contact_allows_move(WALK_FORWARD) is True  # (acclient.c:343911-343915)

    def test_airborne_gravity_creature_may_only_turn_fall_or_die(self, world: World) -> None:
        m = interp(world, on_ground=False)
        # (acclient.c:343893-343901, 343918)
        assert m.contact_allows_move(WALK_FORWARD) is False
        for motion in (TURN_RIGHT, TURN_LEFT, FALLING, DEAD):
            assert m.contact_allows_move(motion) is True

    def test_contact_without_walkable_is_not_enough(self, world: World) -> None:
        m = interp(world, on_ground=False)
        m.physics_obj.transient_state |= TS.CONTACT
        assert m.contact_allows_move(WALK_FORWARD) is False  # v7 & 1 && v7 & 2 (acclient.c:343912-343915)

    def test_no_gravity_or_non_creature_always_moves(self, world: World) -> None:
        m = interp(world, on_ground=False)
        m.physics_obj.state &= ~PhysicsState.GRAVITY
        assert m.contact_allows_move(WALK_FORWARD) is True  # (acclient.c:343909-343910)
        m2 = interp(world, on_ground=False, weenie=Weenie(creature=False))
        assert m2.contact_allows_move(WALK_FORWARD) is True  # (acclient.c:343903-343904)


class TestChargeJump:
    def test_standing_longjump_only_dead_still_on_walkable(self, world: World) -> None:
        m = interp(world)
        # Ready, no sidestep, no turn, CONTACT and ON_WALKABLE (acclient.c:343866-343871)
        assert m.charge_jump() == 0
        assert m.standing_longjump is True

    @pytest.mark.parametrize("field", ["sidestep", "turn", "walk", "air"])
    def test_any_motion_or_airborne_charges_a_plain_jump(self, world: World, field: str) -> None:
        m = interp(world, on_ground=(field != "air"))
        s = m.interpreted_state
        if field == "sidestep":
            s.sidestep_command = SIDE_STEP_RIGHT
        elif field == "turn":
            s.turn_command = TURN_RIGHT
        elif field == "walk":
            s.forward_command = WALK_FORWARD
        assert m.charge_jump() == 0  # (acclient.c:343864-343872)
        assert m.standing_longjump is False

    @pytest.mark.parametrize("forward", [FALLEN, CROUCH, SITTING, SLEEPING])
    def test_cannot_charge_from_fallen_or_resting(self, world: World, forward: int) -> None:
        m = interp(world)
        m.interpreted_state.forward_command = forward
        # 0x40000008 or 0x41000012..0x41000014 -> 72 (acclient.c:343858-343861).
        # ACE's charge_jump tests Falling and Crouch..<Sleeping (Fallen and Sleeping pass): decompile wins.
        assert m.charge_jump() == MovementError.CANT_JUMP_FROM_THIS_POSITION
        assert m.standing_longjump is False

    def test_falling_may_charge(self, world: World) -> None:
        m = interp(world)
        m.interpreted_state.forward_command = FALLING
        assert m.charge_jump() == 0  # Falling is not in the refused set (acclient.c:343858)

    def test_weenie_that_cannot_jump_is_loaded_down(self, world: World) -> None:
        # CanJump false -> 73 (acclient.c:343855, 343874-343877); the player's CanJump is load < 2.0
        # (acclient.c:442883)
        assert interp(world, weenie=Weenie(load=2.0)).charge_jump() == MovementError.CANT_JUMP_LOADED_DOWN
        assert interp(world, weenie=Weenie(the_player=False)).charge_jump() == 73
        assert interp(world, weenie=Weenie(load=1.99)).charge_jump() == 0


class TestJumpVelocity:
    def test_default_v_z_is_10_without_weenie(self, world: World) -> None:
        m = interp(world)
        m.jump_extent = 0.3
        assert m.get_jump_v_z() == 10.0  # (acclient.c:343356-343357)

    def test_uncharged_is_zero(self, world: World) -> None:
        m = interp(world)
        m.jump_extent = 0.0001
        assert m.get_jump_v_z() == 0.0  # extent < 0.00019999999 (acclient.c:343351-343352)

    def test_weenie_velocity_from_jump_skill_clamped_extent(self, world: World) -> None:
        m = interp(world, weenie=Weenie(jump_skill=200))
        m.jump_extent = 1.5
        # extent -> 1.0 (acclient.c:343353-343354); h = (200/1500 * 22.200001 + 0.050000001) * 1
        # (acclient.c:713823); v_z = sqrt(h * 19.6) (acclient.c:443843)
        h = 200.0 / 1500.0 * f32(22.200001) + f32(0.050000001)
        assert m.get_jump_v_z() == f32(math.sqrt(h * 19.6))

    def test_weenie_that_cannot_say_gives_zero(self, world: World) -> None:
        m = interp(world, weenie=Weenie(the_player=False))
        m.jump_extent = 0.5
        assert m.get_jump_v_z() == 0.0  # InqJumpVelocity fails (acclient.c:343358-343362)


class TestLeaveGroundVelocity:
    def test_local_state_velocity_plus_jump_z(self, world: World) -> None:
        m = interp(world)
        m.physics_obj.set_heading(90.0)
        m.interpreted_state.forward_command, m.interpreted_state.forward_speed = RUN_FORWARD, 1.0
        m.jump_extent = 1.0
        v = m.get_leave_ground_velocity()
        # local (0, 4, 10), not rotated by the heading (acclient.c:343821-343824)
        assert (v.x, v.y, v.z) == (0.0, 4.0, 10.0)

    def test_fallback_is_the_body_velocity_in_local_space(self, world: World) -> None:
        m = interp(world)
        body = m.physics_obj
        body.set_heading(90.0)  # facing +x
        body.velocity = Vector3(3.0, 0.0, -1.0)
        v = m.get_leave_ground_velocity()
        # all three < EPSILON -> m_fl2gv-transposed x velocity (acclient.c:343825-343840): global +x is
        # local +y when facing +x
        assert v.x == pytest.approx(0.0, abs=1e-6)
        assert v.y == pytest.approx(3.0)
        assert v.z == pytest.approx(-1.0)


class TestJump:
    def test_jump_launches_with_state_velocity_and_v_z(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        assert m.charge_jump() == 0
        error, cost = m.jump(0.5)
        # jump_is_allowed ok -> jump_extent, set_on_walkable(0) (acclient.c:344244-344247) -> LeaveGround:
        # set_local_velocity (0, 0, 10), standing_longjump = 0, jump_extent = 0 (acclient.c:344478-344482)
        assert (error, cost) == (0, 0)
        assert not body.transient_state & TS.ON_WALKABLE
        assert (body.velocity.x, body.velocity.y, body.velocity.z) == (0.0, 0.0, 10.0)
        assert m.standing_longjump is False
        assert m.jump_extent == 0.0

    def test_jump_in_the_air_is_refused_without_weenie(self, world: World) -> None:
        m = interp(world, on_ground=False)
        m.standing_longjump = True
        # gravity creature not on ground -> 36 (acclient.c:343936-343940, 343969); refusal clears the
        # long jump (acclient.c:344239-344241). ACE's jump_is_allowed passes any body without a weenie.
        assert m.jump(1.0) == (MovementError.CANT_JUMP_WHILE_IN_THE_AIR, 0)
        assert m.standing_longjump is False

    def test_pending_head_jump_error_wins(self, world: World) -> None:
        m = interp(world)
        m.pending_motions.clear()
        m.add_to_queue(0, CROUCH, MovementError.CANT_JUMP_FROM_THIS_POSITION)
        # the oldest pending motion's jump_error_code is returned (acclient.c:343948-343949), even when it
        # is the only one (ACE requires more than one pending motion).
        assert m.jump_is_allowed(1.0) == (MovementError.CANT_JUMP_FROM_THIS_POSITION, 0)

    def test_player_gets_the_stamina_cost(self, world: World) -> None:
        m = interp(world, weenie=Weenie(load=0.5))
        m.pending_motions.clear()
        # JumpStaminaCost: ceil((0.5 + 0.5) * 0.5 * 8 + 2) = 6 (acclient.c:713837)
        assert m.jump_is_allowed(0.5) == (0, 6)

    def test_falling_allows_a_jump_fallen_does_not(self) -> None:
        # 0x40000015 < 0x40000016 and != 0x40000008 -> 0 (acclient.c:343302-343307).
        # ACE's motion_allows_jump refuses Falling: decompile wins.
        assert motion_allows_jump(FALLING) == 0
        assert motion_allows_jump(FALLEN) == 72
        assert motion_allows_jump(motion_id("Pickup")) == 72  # 0x40000016..18 (acclient.c:343302, 343314)
        assert motion_allows_jump(motion_id("MagicPowerUp01")) == 72  # (acclient.c:343309-343314)
        assert motion_allows_jump(WALK_FORWARD) == 0


class TestGround:
    def test_hit_ground_replays_the_walk(self, world: World) -> None:
        body = body_with_table(world, on_ground=False)
        m = body.get_minterp()
        params = MovementParameters()
        m.do_interpreted_motion(WALK_FORWARD, params)
        assert table_state(body).substate == FALLING  # airborne: recorded, Falling plays
        body.set_on_walkable(True)
        body.transient_state |= TS.CONTACT
        m.hit_ground()
        # HitGround: RemoveLinkAnimations, apply_current_movement (acclient.c:344448-344449)
        assert table_state(body).substate == WALK_FORWARD

    def test_leave_ground_plays_falling(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.do_interpreted_motion(WALK_FORWARD, MovementParameters())
        body.transient_state &= ~TS.CONTACT
        body.set_on_walkable(False)
        # LeaveGround -> apply_current_movement; contact forbids walking -> Falling (acclient.c:344190-344193)
        assert table_state(body).substate == FALLING
        # launched with the walk velocity, body-local (acclient.c:344478-344479)
        assert body.velocity.y == pytest.approx(F32_WALK)
        assert m.interpreted_state.forward_command == WALK_FORWARD

    def test_non_creature_weenie_ignores_ground_changes(self, world: World) -> None:
        body = body_with_table(world, weenie=Weenie(creature=False))
        m = body.get_minterp()
        m.interpreted_state.forward_command = WALK_FORWARD  # what a replay would play
        body.velocity = Vector3(0.0, 0.0, -2.0)
        body.set_on_walkable(False)
        # weenie && !IsCreature: LeaveGround and HitGround do nothing
        # (acclient.c:344469-344470, 344439-344440)
        assert table_state(body).substate == READY
        assert body.velocity.z == -2.0
        body.set_on_walkable(True)
        assert table_state(body).substate == READY


# -- commands and their effect on the states ----------------------------------------------------


class TestDoMotion:
    def test_walk_backwards(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        assert m.do_motion(WALK_BACKWARDS, MovementParameters()) == 0
        # raw keeps the command (acclient.c:344660-344661, 332891-332906); SET_HOLD_KEY in the default
        # params -> forward_holdkey 0 (acclient.c:332897-332899)
        assert (m.raw_state.forward_command, m.raw_state.forward_speed) == (WALK_BACKWARDS, 1.0)
        assert m.raw_state.forward_holdkey == HoldKey.INVALID
        # interpreted holds the canonical form (acclient.c:344638, 344656, 332771-332774)
        assert m.interpreted_state.forward_command == WALK_FORWARD
        assert m.interpreted_state.forward_speed == f32(-0.64999998)
        assert table_state(body).substate == WALK_FORWARD
        assert m.pending_motions[-1].motion == WALK_FORWARD

    def test_turn_left_and_sidestep_left(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.do_motion(TURN_LEFT, MovementParameters())
        m.do_motion(SIDE_STEP_LEFT, MovementParameters())
        assert (m.raw_state.turn_command, m.raw_state.sidestep_command) == (TURN_LEFT, SIDE_STEP_LEFT)
        s = m.interpreted_state
        assert (s.turn_command, s.turn_speed) == (TURN_RIGHT, -1.0)
        assert (s.sidestep_command, s.sidestep_speed) == (SIDE_STEP_RIGHT, -1.247999906539917)

    def test_combat_refusals_use_the_raw_motion(self, world: World) -> None:
        m = interp(world)
        m.interpreted_state.current_style = HAND_COMBAT
        # (acclient.c:344639-344648)
        assert m.do_motion(CROUCH, MovementParameters()) == MovementError.CANT_CROUCH_IN_COMBAT
        assert m.do_motion(SITTING, MovementParameters()) == MovementError.CANT_SIT_IN_COMBAT
        assert m.do_motion(SLEEPING, MovementParameters()) == MovementError.CANT_LIE_DOWN_IN_COMBAT
        assert m.do_motion(motion_id("Wave"), MovementParameters()) == MovementError.CANT_CHAT_EMOTE_IN_COMBAT

    def test_seventh_action_is_refused(self, world: World) -> None:
        m = interp(world)
        for _ in range(6):
            m.interpreted_state.add_action(ACTION, 1.0, 0, False)
        # GetNumActions >= 6 -> 69 (acclient.c:344650-344652)
        assert m.do_motion(ACTION, MovementParameters()) == MovementError.TOO_MANY_ACTIONS

    def test_set_hold_key_run_turns_walk_into_run(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        params = MovementParameters(hold_key_to_apply=HoldKey.RUN)
        m.do_motion(WALK_FORWARD, params)
        # SetHoldKey(RUN) (acclient.c:344636-344637, 344517-344520); ACE's SetHoldKey ignores RUN.
        assert m.raw_state.current_holdkey == HoldKey.RUN
        assert (m.interpreted_state.forward_command, m.interpreted_state.forward_speed) == (RUN_FORWARD, 1.0)
        assert table_state(body).substate == RUN_FORWARD


class TestHoldRun:
    def test_hold_run_replays_raw_walk_as_run(self, world: World) -> None:
        body = body_with_table(world, weenie=Weenie(run_skill=200))
        m = body.get_minterp()
        body.do_motion(WALK_FORWARD, MovementParameters())  # autonomous move
        assert m.interpreted_state.forward_command == WALK_FORWARD
        m.set_hold_run(True)
        # holdkey 2, apply_current_movement -> player + autonomous -> apply_raw_movement -> adjust_motion
        # with the current hold key -> RunForward x 2.375 (acclient.c:344494-344497, 344310-344311)
        assert m.raw_state.current_holdkey == HoldKey.RUN
        assert (m.interpreted_state.forward_command, m.interpreted_state.forward_speed) == (
            RUN_FORWARD,
            2.375,
        )
        assert table_state(body).substate == RUN_FORWARD
        assert m.my_run_rate == 2.375  # apply_interpreted_movement learns it (acclient.c:344162-344163)
        m.set_hold_run(False)
        assert (m.interpreted_state.forward_command, m.interpreted_state.forward_speed) == (WALK_FORWARD, 1.0)

    def test_non_player_creature_replays_interpreted(self, world: World) -> None:
        body = body_with_table(world, weenie=Weenie(the_player=False))
        m = body.get_minterp()
        body.do_motion(WALK_FORWARD, MovementParameters())
        m.set_hold_run(True)
        # weenie && !IsThePlayer -> apply_interpreted_movement: interpreted unchanged
        # (acclient.c:344310-344313).
        # ACE tests IsCreature here and would rebuild from raw (RunForward).
        assert m.interpreted_state.forward_command == WALK_FORWARD

    def test_no_change_no_replay(self, world: World) -> None:
        m = interp(world)
        m.interpreted_state.forward_command = WALK_FORWARD  # would be undone by a replay from raw
        m.set_hold_run(False)  # already NONE (acclient.c:344494)
        assert m.interpreted_state.forward_command == WALK_FORWARD

    def test_an_invalid_hold_key_keeps_the_run_key_and_a_walk_stop_stops_the_run(self, world: World) -> None:
        # The keyboard path (CommandInterpreter::MovePlayer, acclient.c:717799) sends DoMotion and
        # StopMotion with the default parameters and hold_key_to_apply HoldKey_Invalid.
        body = body_with_table(world)
        m = body.get_minterp()
        m.set_hold_run(True)
        assert body.do_motion(WALK_FORWARD, MovementParameters()) == 0
        # SetHoldKey(Invalid) changes nothing (acclient.c:344501-344522, called at 344637); adjust_motion
        # with an invalid key takes the current one, RUN (acclient.c:343796-343802): WalkForward runs.
        assert m.raw_state.current_holdkey == HoldKey.RUN
        assert m.interpreted_state.forward_command == RUN_FORWARD
        assert table_state(body).substate == RUN_FORWARD
        # StopMotion adjusts the stop the same way (acclient.c:344128): it stops RunForward.
        assert body.stop_motion(WALK_FORWARD, MovementParameters()) == 0
        assert table_state(body).substate == READY
        assert m.raw_state.forward_command == READY
        assert m.raw_state.current_holdkey == HoldKey.RUN

    def test_a_walk_stop_released_from_the_run_key_misses_the_run(self, world: World) -> None:
        body = body_with_table(world)
        body.do_motion(WALK_FORWARD, MovementParameters(hold_key_to_apply=HoldKey.RUN))
        # HoldKey_None: the stop stays a WalkForward stop, which the table cannot find while the
        # substate is RunForward (StopSequenceMotion, acclient.c:337911): 0x43.
        stop = MovementParameters(hold_key_to_apply=HoldKey.NONE)
        assert body.stop_motion(WALK_FORWARD, stop) == MovementError.NO_MTABLE_DATA
        assert table_state(body).substate == RUN_FORWARD


class TestPlayerOrCreature:
    """apply_current_movement (acclient.c:344300-344314): the player (or a body without a weenie)
    moving autonomously replays its raw state; any other creature its interpreted state."""

    @pytest.mark.parametrize(
        ("weenie", "replayed"), [(Weenie(the_player=False), RUN_FORWARD), (Weenie(), READY)]
    )
    def test_landing_replays_interpreted_for_a_creature_and_raw_for_the_player(
        self, world: World, weenie: Weenie, replayed: int
    ) -> None:
        body = body_with_table(world, on_ground=False, weenie=weenie)
        m = body.get_minterp()
        body.last_move_was_autonomous = True
        # An interpreted state the raw one does not hold (as move_to_interpreted_state leaves it).
        m.interpreted_state.forward_command, m.interpreted_state.forward_speed = RUN_FORWARD, 1.0
        body.transient_state |= TS.CONTACT
        body.set_on_walkable(True)
        m.hit_ground()
        # HitGround: a creature (IsCreature) with gravity replays (acclient.c:344440-344449); the
        # player's raw state says Ready, the creature's interpreted state RunForward.
        assert table_state(body).substate == replayed


class TestStops:
    def test_stop_motion_clears_raw_and_interpreted(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.do_motion(WALK_BACKWARDS, MovementParameters())
        assert m.stop_motion(WALK_BACKWARDS, MovementParameters()) == 0
        # StopInterpretedMotion(WalkForward) -> RemoveMotion; raw RemoveMotion(WalkBackwards)
        # (acclient.c:344128-344134, 332547-332552, 332508-332513)
        assert (m.interpreted_state.forward_command, m.interpreted_state.forward_speed) == (READY, 1.0)
        assert m.raw_state.forward_command == READY
        assert table_state(body).substate == READY
        assert m.pending_motions[-1].motion == READY  # (acclient.c:344059)

    def test_stop_interpreted_airborne_only_edits_state(self, world: World) -> None:
        body = body_with_table(world, on_ground=False)
        m = body.get_minterp()
        m.interpreted_state.sidestep_command = SIDE_STEP_RIGHT
        queued = len(m.pending_motions)
        assert m.stop_interpreted_motion(SIDE_STEP_RIGHT, MovementParameters()) == 0
        # !contact_allows_move -> RemoveMotion only, nothing queued (acclient.c:344046-344052)
        assert m.interpreted_state.sidestep_command == 0
        assert len(m.pending_motions) == queued

    def test_stop_completely(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.do_motion(WALK_FORWARD, MovementParameters(speed=0.5))
        m.do_motion(TURN_RIGHT, MovementParameters())
        m.do_motion(SIDE_STEP_RIGHT, MovementParameters())
        m.pending_motions.clear()
        assert m.stop_completely() == 0
        # both states back to Ready/1.0, no sidestep, no turn (acclient.c:343615-343622)
        for s in (m.raw_state, m.interpreted_state):
            assert (s.forward_command, s.forward_speed, s.sidestep_command, s.turn_command) == (
                READY,
                1.0,
                0,
                0,
            )
        assert m.raw_state.sidestep_speed == 1.0  # the speeds of cleared channels are kept
        assert table_state(body).substate == READY
        assert table_state(body).modifiers == []
        # Ready queued with motion_allows_jump(old forward) (acclient.c:343612, 343624)
        assert [(n.motion, n.jump_error_code) for n in m.pending_motions] == [(READY, 0)]


class TestDoInterpretedMotion:
    def test_airborne_action_fails_non_action_is_recorded(self, world: World) -> None:
        body = body_with_table(world, on_ground=False)
        m = body.get_minterp()
        # (acclient.c:344020-344022, 344013-344017)
        assert (
            m.do_interpreted_motion(ACTION, MovementParameters()) == MovementError.CANT_JUMP_WHILE_IN_THE_AIR
        )
        assert m.do_interpreted_motion(RUN_FORWARD, MovementParameters(speed=1.5)) == 0
        assert (m.interpreted_state.forward_command, m.interpreted_state.forward_speed) == (RUN_FORWARD, 1.5)
        assert table_state(body).substate == FALLING

    def test_standing_longjump_holds_forward_motions(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.charge_jump()
        queued = len(m.pending_motions)
        assert m.do_interpreted_motion(WALK_FORWARD, MovementParameters()) == 0
        # recorded, not played, not queued (acclient.c:343989, 344013-344017)
        assert m.interpreted_state.forward_command == WALK_FORWARD
        assert table_state(body).substate == READY
        assert len(m.pending_motions) == queued

    def test_queue_carries_jump_error(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.do_interpreted_motion(WALK_FORWARD, MovementParameters(flags=MF.DISABLE_JUMP_DURING_LINK))
        assert m.pending_motions[-1].jump_error_code == 72  # (acclient.c:343996-343998)
        params = MovementParameters(flags=MF.MODIFY_INTERPRETED_STATE)
        m.do_interpreted_motion(WALK_FORWARD, params)
        assert m.pending_motions[-1].jump_error_code == 0  # (acclient.c:344002-344004)

    def test_without_modify_flag_state_is_untouched(self, world: World) -> None:
        body = body_with_table(world)
        m = body.get_minterp()
        m.do_interpreted_motion(WALK_FORWARD, MovementParameters(flags=MF(0)))
        # played (table) but not recorded (acclient.c:344007-344009)
        assert table_state(body).substate == WALK_FORWARD
        assert m.interpreted_state.forward_command == READY


class TestActionsAndMotionDone:
    def test_motion_done_pops_actions_from_both_states(self, world: World) -> None:
        m = interp(world)
        m.pending_motions.clear()
        m.add_to_queue(0, ACTION, 0)
        m.add_to_queue(0, WALK_FORWARD, 0)
        m.raw_state.add_action(ACTION, 1.0, 1, False)
        m.interpreted_state.add_action(ACTION, 1.0, 1, False)
        m.motion_done(False)
        # head & 0x10000000 -> RemoveAction on both, then the node is dropped (acclient.c:343657-343672)
        assert m.raw_state.actions == [] and m.interpreted_state.actions == []
        assert [n.motion for n in m.pending_motions] == [WALK_FORWARD]
        m.interpreted_state.add_action(ACTION, 1.0, 2, False)
        m.motion_done(True)  # a non-action head leaves the actions alone
        assert m.interpreted_state.get_num_actions() == 1
        assert m.motions_pending() is False

    def test_enter_default_state_keeps_older_pending_motions(self, world: World) -> None:
        # A body without a motion table: nothing completes or plays, so the queue shows only the interpreter.
        m = MotionInterp(place(world, on_ground=True))
        m.add_to_queue(7, WALK_FORWARD, 0)
        m.enter_default_state()
        # the Ready node is appended to the existing list (acclient.c:344577-344594); ACE clears the list
        assert [(n.context_id, n.motion) for n in m.pending_motions] == [(7, WALK_FORWARD), (0, READY)]
        assert m.initted is True  # (acclient.c:344595)


class TestMotionStates:
    def test_defaults(self) -> None:
        raw, interp_state = RawMotionState(), InterpretedMotionState()
        # (acclient.c:332567-332577, 332645-332651)
        assert (raw.current_holdkey, raw.current_style, raw.forward_command) == (
            HoldKey.NONE,
            NON_COMBAT,
            READY,
        )
        assert (interp_state.current_style, interp_state.forward_command) == (NON_COMBAT, READY)
        assert interp_state.sidestep_speed == 1.0 and raw.turn_speed == 1.0

    def test_raw_ignores_run_forward_and_same_style(self) -> None:
        raw = RawMotionState()
        raw.forward_command = WALK_FORWARD
        raw.apply_motion(RUN_FORWARD, MovementParameters(speed=2.0))
        assert raw.forward_command == WALK_FORWARD  # (acclient.c:332893)
        raw.apply_motion(NON_COMBAT, MovementParameters())
        assert raw.forward_command == WALK_FORWARD  # same style: no reset (acclient.c:332914)
        raw.apply_motion(HAND_COMBAT, MovementParameters())
        assert (raw.current_style, raw.forward_command) == (HAND_COMBAT, READY)  # (acclient.c:332916-332917)

    def test_raw_holdkey_from_params_without_set_hold_key(self) -> None:
        raw = RawMotionState()
        raw.apply_motion(TURN_LEFT, MovementParameters(flags=MF(0), hold_key_to_apply=HoldKey.RUN, speed=0.5))
        assert (raw.turn_command, raw.turn_holdkey, raw.turn_speed) == (TURN_LEFT, HoldKey.RUN, 0.5)

    def test_interpreted_style_resets_forward_even_if_same(self) -> None:
        s = InterpretedMotionState()
        s.forward_command = WALK_FORWARD
        s.apply_motion(NON_COMBAT, MovementParameters())
        # no style comparison in InterpretedMotionState::ApplyMotion (acclient.c:332783-332784)
        assert s.forward_command == READY

    def test_remove_motion_needs_matching_forward(self) -> None:
        s = InterpretedMotionState()
        s.forward_command, s.forward_speed = WALK_FORWARD, 2.0
        s.remove_motion(RUN_FORWARD)
        assert s.forward_command == WALK_FORWARD  # (acclient.c:332549)
        s.remove_motion(WALK_FORWARD)
        assert (s.forward_command, s.forward_speed) == (READY, 1.0)
        s.current_style = HAND_COMBAT
        s.remove_motion(HAND_COMBAT)
        assert s.current_style == NON_COMBAT  # (acclient.c:332555-332557)

    def test_actions_keep_stamp_and_autonomous(self) -> None:
        s = InterpretedMotionState()
        s.apply_motion(ACTION, MovementParameters(flags=MF.AUTONOMOUS, speed=1.25, action_stamp=9))
        node = s.actions[0]
        # AddAction(motion, speed, action_stamp, bit 12) (acclient.c:332779)
        assert (node.action, node.speed, node.stamp, node.autonomous) == (ACTION, 1.25, 9, True)
        assert s.remove_action() == ACTION and s.remove_action() == 0


# -- the weenie formulas -----------------------------------------------------------------------------


class TestWeenie:
    def test_run_rate_curve_and_the_800_quirk(self) -> None:
        # (1 * (s / (s + 200) * 11) + 4) / 1 / 4 (acclient.c:713801);
        # exactly 800 -> 18/4 (acclient.c:713798-713799)
        assert get_run_rate(0.0, 0) == 1.0
        assert get_run_rate(0.0, 300) == pytest.approx((300 / 500 * 11 + 4) / 4)
        assert get_run_rate(0.0, 800) == 4.5
        assert get_run_rate(0.0, 801) == pytest.approx((801 / 1001 * 11 + 4) / 4)  # ACE: >= 800 -> 4.5

    def test_load_mod(self) -> None:
        # (acclient.c:296781-296790)
        assert (load_mod(0.99), load_mod(1.25), load_mod(2.0)) == (1.0, 0.75, 0.0)
        assert get_run_rate(1.5, 300) == pytest.approx((0.5 * 300 / 500 * 11 + 4) / 4)

    def test_out_of_stamina_runs_at_skill_0(self) -> None:
        # stamina 0 -> runskill 0 (acclient.c:443759-443760) -> rate 1.0
        assert Weenie(run_skill=300, stamina=0).inq_run_rate() == 1.0
        assert Weenie(run_skill=300, the_player=False).inq_run_rate() is None

    def test_jump_height_floor_and_power_clamp(self) -> None:
        # max(..., 0.34999999) and power in [0, 1] (acclient.c:713812-713825)
        assert get_jump_height(0.0, 100, 0.0) == f32(0.34999999)
        assert get_jump_height(0.0, 100, 2.0) == get_jump_height(0.0, 100, 1.0)

    def test_stamina_cost(self) -> None:
        # pk: (power + 1) * 100 truncated; else ceil((load + 0.5) * power * 8 + 2) (acclient.c:713834-713837)
        assert jump_stamina_cost(0.555, 0.0, True) == 155
        assert jump_stamina_cost(1.0, 0.0, False) == 6
        assert jump_stamina_cost(0.1, 0.0, False) == 3

    def test_bad_input(self) -> None:
        with pytest.raises(ValueError, match="run_skill"):
            Weenie(run_skill=-1)
        with pytest.raises(ValueError, match="load"):
            Weenie(load=float("nan"))


class TestMoveToInterpretedState:
    def server_state(self, *actions: tuple[int, bool]) -> InterpretedMotionState:
        state = InterpretedMotionState()
        state.forward_command, state.forward_speed = WALK_FORWARD, 0.5
        for stamp, autonomous in actions:
            state.add_action(ACTION, 1.0, stamp, autonomous)
        return state

    def test_adopts_movement_and_plays_newer_actions(self, world: World) -> None:
        body = body_with_table(world, weenie=Weenie())
        m = body.get_minterp()
        m.server_action_stamp = 0x7FFE
        assert m.move_to_interpreted_state(self.server_state((0x0001, False))) is True
        # copy_movement_from, then replay (acclient.c:344393-344394); 1 vs 0x7FFE differ by more than
        # 0x3FFF, so the wrapped compare says 1 is newer (acclient.c:344398-344407)
        assert (m.interpreted_state.forward_command, m.interpreted_state.forward_speed) == (WALK_FORWARD, 0.5)
        assert table_state(body).substate == WALK_FORWARD
        assert m.server_action_stamp == 0x0001
        assert [a.action for a in m.interpreted_state.actions] == [ACTION]

    def test_stamps_compare_in_15_bits(self, world: World) -> None:
        m = interp(world, weenie=Weenie())
        m.server_action_stamp = 0x8005
        m.move_to_interpreted_state(self.server_state((0x0003, False)))
        # 0x8005 & 0x7FFF = 5 > 3: not newer, skipped (acclient.c:344398-344407).
        # ACE masks the server stamp with 0x7FFFF and would play it.
        assert m.server_action_stamp == 0x8005
        assert m.interpreted_state.actions == []

    def test_the_players_own_autonomous_actions_are_skipped(self, world: World) -> None:
        m = interp(world, weenie=Weenie())
        m.move_to_interpreted_state(self.server_state((0x0002, True)))
        # weenie is the player and the action is autonomous -> skipped (acclient.c:344410)
        assert m.server_action_stamp == 0
        other = interp(world, weenie=Weenie(the_player=False))
        other.move_to_interpreted_state(self.server_state((0x0002, True)))
        # anyone else plays it (ACE: IsCreature || autonomous, the opposite test)
        assert other.server_action_stamp == 0x0002
        assert other.interpreted_state.actions[0].autonomous is True
