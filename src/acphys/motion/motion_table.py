"""``CMotionTable``: how a body's motion table turns a command into a chain of animations.

A motion table is four lookups (acclient.h ``CMotionTable``):

- ``style_defaults``: style id -> the substate a body rests in under that style
  (NonCombat -> Ready);
- ``cycles``: ``cycle_key(style, substate)`` -> the looping ``MotionData`` of a substate;
- ``modifiers``: ``cycle_key(style, modifier)`` (or the bare low 24 bits of the
  modifier, a style-independent fallback) -> the ``MotionData`` layered over a cycle;
- ``links``: ``cycle_key(style, from_substate)`` -> {to_motion: transition ``MotionData``}.
  The key ``cycle_key(style, 0)`` (``style << 16``) holds links from any substate.

Keys are 32-bit: ``(style << 16)`` keeps only the style's low 16 bits. The inner
link keys are full motion ids.

``GetObjectSequence`` decides what a command does: a style change, a new cycle
(with the link into it), an action played over the cycle, or a modifier whose
velocity and omega are added to the cycle's. It rewrites the ``MotionState`` and
feeds the ``Sequence`` (clear_physics, remove_cyclic_anims, then ``add_motion``
for each piece), and reports how many animations were queued before the new
cycle starts: the motion-table manager counts AnimDone hooks against that number.

Numbers of animations are retail ``unsigned int`` results: a sum that goes
below zero wraps to 32 bits as in retail (only a cycle with no animations can do
that).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.math.vector import Vector3
from acphys.motion.animation import AnimData
from acphys.motion.commands import ACTION_MASK, MODIFIER_MASK, STYLE_MASK, SUBSTATE_MASK
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.motion.sequence import Sequence

#: ``MotionData::bitfield`` bit 0: entering this cycle clears the modifiers, and no modifier
#: may be layered over it (``GetObjectSequence`` acclient.c:337724, 337783, 337876).
CLEARS_MODIFIERS = 0x1
#: ``MotionData::bitfield`` bit 1: this cycle may be entered only from the style's default
#: substate; from anything else the command falls through to the modifier branch
#: (``CMotionTable::is_allowed`` acclient.c:337568).
DEFAULT_SUBSTATE_ONLY = 0x2

_U32 = 0xFFFFFFFF
_INDEX = 0x00FFFFFF


def cycle_key(style: int, motion: int) -> int:
    """The 32-bit key ``(style << 16) | (motion & 0xFFFFFF)`` of the cycles, modifiers and outer links."""
    return ((style << 16) | (motion & _INDEX)) & _U32


def _check_u32(value: int, what: str) -> None:
    if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value <= _U32:
        raise ValueError(f"{what} must be an unsigned 32-bit int, got {value!r}")


class MotionData:
    """Retail ``MotionData`` (acclient.h:57162): the animations of one cycle, link or modifier.

    ``velocity`` and ``omega`` are the authored body velocity and turn rate
    (local space, per unit of speed); ``bitfield`` holds ``CLEARS_MODIFIERS``
    and ``DEFAULT_SUBSTATE_ONLY``. (The DAT record's separate flag byte that
    says whether velocity and omega are present is consumed by
    ``MotionData::UnPack``, acclient.c:341813, and is not kept.)
    """

    __slots__ = ("anims", "bitfield", "omega", "velocity")

    def __init__(
        self,
        anims: list[AnimData],
        velocity: Vector3 | None = None,
        omega: Vector3 | None = None,
        bitfield: int = 0,
    ) -> None:
        if not isinstance(bitfield, int) or not 0 <= bitfield <= 0xFF:
            raise ValueError(f"MotionData bitfield must be a byte, got {bitfield!r}")
        if len(anims) > 0xFF:
            raise ValueError(f"MotionData holds at most 255 animations (a byte count), got {len(anims)}")
        for index, anim in enumerate(anims):
            if not isinstance(anim, AnimData):
                raise ValueError(f"MotionData animation {index} must be an AnimData, got {anim!r}")
        self.anims = list(anims)
        self.velocity = Vector3() if velocity is None else velocity.copy()
        self.omega = Vector3() if omega is None else omega.copy()
        self.bitfield = bitfield

    @property
    def num_anims(self) -> int:
        return len(self.anims)

    def __repr__(self) -> str:
        return (
            f"MotionData(num_anims={self.num_anims}, velocity={self.velocity!r}, "
            f"omega={self.omega!r}, bitfield=0x{self.bitfield:X})"
        )


class MotionList:
    """Retail ``MotionList`` (acclient.h:31664): one modifier or action with its (float) speed."""

    __slots__ = ("motion", "speed_mod")

    def __init__(self, motion: int, speed_mod: float = 1.0) -> None:
        self.motion = motion
        self.speed_mod = f32(speed_mod)

    def __repr__(self) -> str:
        return f"MotionList(0x{self.motion:08X}, {self.speed_mod!r})"


class MotionState:
    """Retail ``MotionState`` (acclient.h:31081): style, substate, its speed, modifiers and actions.

    Retail keeps two singly linked lists; here ``modifiers`` is a list whose
    first element is the retail ``modifier_head`` (new modifiers go in front)
    and ``actions`` is a FIFO whose first element is ``action_head``.
    ``substate_mod`` is a ``float`` field: the motion table stores its float32
    ``speed_mod`` parameter there.
    """

    __slots__ = ("actions", "modifiers", "style", "substate", "substate_mod")

    def __init__(self) -> None:
        """Retail: MotionState::MotionState @ 0x00525FD0 (acclient.c:341302)"""
        self.style = 0
        self.substate = 0
        self.substate_mod = 1.0
        self.modifiers: list[MotionList] = []
        self.actions: list[MotionList] = []

    def copy(self) -> MotionState:
        """A deep copy (both lists duplicated node by node).

        Retail: MotionState::copy @ 0x005261D0 (acclient.c:341489)
        """
        other = MotionState()
        other.style = self.style
        other.substate = self.substate
        other.substate_mod = self.substate_mod
        other.modifiers = [MotionList(node.motion, node.speed_mod) for node in self.modifiers]
        other.actions = [MotionList(node.motion, node.speed_mod) for node in self.actions]
        return other

    def add_modifier_no_check(self, modifier: int, speed_mod: float) -> None:
        """Push ``modifier`` at the head of the modifier list.

        Retail: MotionState::add_modifier_no_check @ 0x00525FF0 (acclient.c:341313)
        """
        self.modifiers.insert(0, MotionList(modifier, speed_mod))

    def add_modifier(self, modifier: int, speed_mod: float) -> bool:
        """Push ``modifier`` unless it is already a modifier or is the current substate.

        Retail: MotionState::add_modifier @ 0x00526340 (acclient.c:341618)
        """
        if any(node.motion == modifier for node in self.modifiers):
            return False
        if self.substate == modifier:
            return False
        self.add_modifier_no_check(modifier, speed_mod)
        return True

    def remove_modifier(self, node: MotionList) -> None:
        """Unlink ``node`` (by identity) from the modifier list.

        Retail: MotionState::remove_modifier @ 0x00526040 (acclient.c:341337)
        """
        for index, candidate in enumerate(self.modifiers):
            if candidate is node:
                del self.modifiers[index]
                return
        raise ValueError(f"{node!r} is not in this state's modifier list")

    def clear_modifiers(self) -> None:
        """Retail: MotionState::clear_modifiers @ 0x00526070 (acclient.c:341352)"""
        self.modifiers.clear()

    def add_action(self, action: int, speed_mod: float) -> None:
        """Append ``action`` at the tail of the action queue.

        Retail: MotionState::add_action @ 0x005260A0 (acclient.c:341370)
        """
        self.actions.append(MotionList(action, speed_mod))

    def remove_action_head(self) -> int:
        """Pop the oldest action and return its motion (0 when there is none).

        Retail: MotionState::remove_action_head @ 0x00526120 (acclient.c:341419)
        """
        if not self.actions:
            return 0
        return self.actions.pop(0).motion

    def clear_actions(self) -> None:
        """Retail: MotionState::clear_actions @ 0x005260F0 (acclient.c:341400)"""
        self.actions.clear()

    def __repr__(self) -> str:
        return (
            f"MotionState(style=0x{self.style:08X}, substate=0x{self.substate:08X}, "
            f"substate_mod={self.substate_mod!r}, modifiers={self.modifiers!r}, actions={self.actions!r})"
        )


# -- the static helpers of CMTable.obj -------------------------------------------------------


def same_sign(a: float, b: float) -> bool:
    """Whether ``b`` falls on ``a``'s side of zero; zero counts as positive (so 0 and 1 agree).

    Retail: same_sign @ 0x00522260 (acclient.c:337250)
    """
    if not a >= 0.0:  # negative (or NaN: the x87 compare sets C0|C2 for both)
        return b < 0.0
    return b >= 0.0


def add_motion(sequence: Sequence, data: MotionData | None, speed_mod: float) -> None:
    """Install ``data``'s velocity and omega times ``speed_mod`` and append its animations.

    The sequence's velocity and omega are *replaced* (``set_velocity`` /
    ``set_omega``), so of several ``add_motion`` calls the last one wins. Each
    animation is appended as ``speed_mod * anim``: a copy whose framerate is
    multiplied by ``speed_mod`` (retail ``operator*(float, AnimData)``).

    Retail: add_motion @ 0x005224B0 (acclient.c:337430)
    """
    if data is None:
        return
    sequence.set_velocity(data.velocity * speed_mod)
    sequence.set_omega(data.omega * speed_mod)
    for anim in data.anims:
        sequence.append_animation(speed_mod * anim)


def combine_motion(sequence: Sequence, data: MotionData | None, speed_mod: float) -> None:
    """Add ``data``'s velocity and omega times ``speed_mod`` to the sequence's.

    Retail: combine_motion @ 0x00522580 (acclient.c:337476)
    """
    if data is None:
        return
    sequence.combine_physics(data.velocity * speed_mod, data.omega * speed_mod)


def subtract_motion(sequence: Sequence, data: MotionData | None, speed_mod: float) -> None:
    """Take ``data``'s velocity and omega times ``speed_mod`` off the sequence's.

    Retail: subtract_motion @ 0x00522600 (acclient.c:337505)
    """
    if data is None:
        return
    sequence.subtract_physics(data.velocity * speed_mod, data.omega * speed_mod)


def change_cycle_speed(
    sequence: Sequence, data: MotionData | None, old_speed: float, new_speed: float
) -> None:
    """Rescale the cyclic animations' framerate from ``old_speed`` to ``new_speed``.

    From a (near) zero old speed nothing can be rescaled: the framerate is
    zeroed when the new speed is (near) zero too, and otherwise left alone, so
    a cycle slowed to 0 stays frozen when sped up again. ``data`` is unused,
    as in retail.

    The ratio is spilled to a ``float`` (``multiplier``, acclient.c:337280).

    Retail: change_cycle_speed @ 0x00522290 (acclient.c:337268)
    """
    if math.fabs(old_speed) <= EPSILON:
        if math.fabs(new_speed) < EPSILON:
            sequence.multiply_cyclic_animation_framerate(0.0)
    else:
        sequence.multiply_cyclic_animation_framerate(f32(new_speed / old_speed))


def _count(*parts: MotionData | None) -> int:
    return sum(part.num_anims for part in parts if part is not None)


class MotionTable:
    """Retail ``CMotionTable`` (acclient.h:31654). See the module docstring for the four lookups.

    Tables are built from Python data, from scenario files, or from a retail
    DAT by :func:`acphys.dat.motion.unpack_motion_table` (``CMotionTable::UnPack``).
    """

    __slots__ = ("cycles", "default_style", "links", "modifiers", "style_defaults")

    def __init__(
        self,
        default_style: int,
        style_defaults: dict[int, int],
        cycles: dict[int, MotionData],
        modifiers: dict[int, MotionData] | None = None,
        links: dict[int, dict[int, MotionData]] | None = None,
    ) -> None:
        _check_u32(default_style, "default_style")
        for style, substate in style_defaults.items():
            _check_u32(style, "a style_defaults key")
            _check_u32(substate, f"the default substate of style 0x{style:08X}")
        for name, table in (("cycles", cycles), ("modifiers", modifiers or {})):
            for key, data in table.items():
                _check_u32(key, f"a {name} key")
                if not isinstance(data, MotionData):
                    raise ValueError(f"{name}[0x{key:08X}] must be a MotionData, got {data!r}")
        for key, inner in (links or {}).items():
            _check_u32(key, "a links key")
            for motion, data in inner.items():
                _check_u32(motion, f"a links[0x{key:08X}] key")
                if not isinstance(data, MotionData):
                    raise ValueError(f"links[0x{key:08X}][0x{motion:08X}] must be a MotionData, got {data!r}")
        self.default_style = default_style
        self.style_defaults = dict(style_defaults)
        self.cycles = dict(cycles)
        self.modifiers = dict(modifiers or {})
        self.links = {key: dict(inner) for key, inner in (links or {}).items()}

    # -- lookups ------------------------------------------------------------------------------

    def is_allowed(self, motion: int, data: MotionData | None, state: MotionState) -> bool:
        """Whether the cycle ``data`` of ``motion`` may be entered from ``state``.

        A ``DEFAULT_SUBSTATE_ONLY`` cycle (turns, sidesteps) is entered only
        from the style's default substate or when it already is the substate.

        Retail: CMotionTable::is_allowed @ 0x005226C0 (acclient.c:337559)
        """
        if data is None:
            return False
        if data.bitfield & DEFAULT_SUBSTATE_ONLY and motion != state.substate:
            return self.style_defaults.get(state.style) == state.substate
        return True

    def get_link(
        self, style: int, substate: int, substate_speed: float, motion: int, speed: float
    ) -> MotionData | None:
        """The transition from ``substate`` to ``motion`` under ``style``.

        Forward (both speeds >= 0): ``links[(style, substate)][motion]``, else
        the style-wide ``links[style << 16][motion]``. When either speed is
        negative the lookup is reversed, ``links[(style, motion)][substate]``
        (the forward link played backwards), else
        ``links[(style, substate)][default substate of style]``.

        Retail: CMotionTable::get_link @ 0x00522710 (acclient.c:337584)
        """
        if speed < 0.0 or substate_speed < 0.0:
            inner = self.links.get(cycle_key(style, motion))
            if inner is not None:
                found = inner.get(substate)
                if found is not None:
                    return found
            default = self.style_defaults.get(style)
            if default is not None:
                inner = self.links.get(cycle_key(style, substate))
                if inner is not None:
                    return inner.get(default)
            return None
        inner = self.links.get(cycle_key(style, substate))
        if inner is not None:
            found = inner.get(motion)
            if found is not None:
                return found
        inner = self.links.get(cycle_key(style, 0))
        if inner is not None:
            return inner.get(motion)
        return None

    def _modifier_data(self, style: int, motion: int) -> MotionData | None:
        data = self.modifiers.get(cycle_key(style, motion))
        if data is None:
            data = self.modifiers.get(motion & _INDEX)
        return data

    # -- commands -----------------------------------------------------------------------------

    def get_object_sequence(
        self,
        motion: int,
        curr_state: MotionState,
        sequence: Sequence,
        speed_mod: float,
        stop_modifiers: bool = False,
    ) -> tuple[bool, int]:
        """Carry out ``motion`` at ``speed_mod``: returns (success, num_anims).

        num_anims is the number of animations queued ahead of the new cycle
        (link animations; for an action, the action's links), i.e. how many
        AnimDone hooks the manager waits for before the motion is done.

        Branches, tried in order:
        - the style's default substate asked for while the substate is a
          modifier-capable one (a turn or sidestep), outside a stop: nothing
          to do, success;
        - a style (0x80000000): link out of the substate to the old default,
          link to the new style (or via the table's default style), the new
          style's default cycle; the state takes the new style and its default;
        - a substate (0x40000000): same substate and same speed sign with
          animations running -> only rescale (``change_cycle_speed``) and swap
          the physics; otherwise link (directly, or via the default substate
          when there is none or the sign flips) and the cycle; a replaced
          modifier-capable substate stays on as a modifier;
        - an action (0x10000000): queue it on the state's actions and play
          its link (or default -> action -> back) before the current cycle;
        - a modifier (0x20000000): add it to the state and its physics to the
          sequence (a modifier already present is stopped and re-added).
        Every branch that rebuilds the sequence ends with ``re_modify``.

        ``speed_mod`` is a ``float`` parameter, narrowed here: it becomes the state's
        ``substate_mod`` and every framerate ``add_motion`` multiplies.

        Retail: CMotionTable::GetObjectSequence @ 0x00522860 (acclient.c:337640)
        """
        speed_mod = f32(speed_mod)
        style = curr_state.style
        if not style:
            return False, 0
        substate = curr_state.substate
        if not substate:
            return False, 0
        default_substate = self.style_defaults.get(style, 0)
        if motion == default_substate and not stop_modifiers and substate & MODIFIER_MASK:
            return True, 0

        if motion & STYLE_MASK:
            if style == motion:
                return True, 0
            pre_link = None
            if substate != default_substate:
                pre_link = self.get_link(
                    style, substate, curr_state.substate_mod, default_substate, speed_mod
                )
            new_default = self.style_defaults.get(motion)
            if new_default is not None:
                cycle = self.cycles.get(cycle_key(motion, new_default))
                if cycle is not None:
                    if cycle.bitfield & CLEARS_MODIFIERS:
                        curr_state.clear_modifiers()
                    link = self.get_link(style, default_substate, curr_state.substate_mod, motion, speed_mod)
                    via_default = None
                    # Retail also tests motion != style here (acclient.c:337727): always true by now.
                    if link is None:
                        link = self.get_link(style, default_substate, 1.0, self.default_style, 1.0)
                        # A failed lookup leaves retail's variable holding the current substate.
                        home = self.style_defaults.get(self.default_style, substate)
                        via_default = self.get_link(self.default_style, home, 1.0, motion, 1.0)
                    sequence.clear_physics()
                    sequence.remove_cyclic_anims()
                    add_motion(sequence, pre_link, speed_mod)
                    add_motion(sequence, link, speed_mod)
                    add_motion(sequence, via_default, speed_mod)
                    add_motion(sequence, cycle, speed_mod)
                    curr_state.substate = new_default
                    curr_state.style = motion
                    curr_state.substate_mod = speed_mod
                    self.re_modify(sequence, curr_state)
                    return True, (_count(pre_link, link, via_default, cycle) - 1) & _U32

        if motion & SUBSTATE_MASK:
            cycle = self.cycles.get(cycle_key(style, motion))
            if cycle is None:
                cycle = self.cycles.get(cycle_key(self.default_style, motion))
            if cycle is not None and self.is_allowed(motion, cycle, curr_state):
                if (
                    motion == substate
                    and same_sign(speed_mod, curr_state.substate_mod)
                    and sequence.has_anims()
                ):
                    change_cycle_speed(sequence, cycle, curr_state.substate_mod, speed_mod)
                    subtract_motion(sequence, cycle, curr_state.substate_mod)
                    combine_motion(sequence, cycle, speed_mod)
                    curr_state.substate_mod = speed_mod
                    return True, 0
                if cycle.bitfield & CLEARS_MODIFIERS:
                    curr_state.clear_modifiers()
                link = self.get_link(style, substate, curr_state.substate_mod, motion, speed_mod)
                via_default = None
                if link is None or not same_sign(speed_mod, curr_state.substate_mod):
                    # A style with no default leaves retail's variable holding the stop flag (0 or 1).
                    default = self.style_defaults.get(style, int(stop_modifiers))
                    link = self.get_link(style, substate, curr_state.substate_mod, default, 1.0)
                    via_default = self.get_link(style, default, 1.0, motion, speed_mod)
                sequence.clear_physics()
                sequence.remove_cyclic_anims()
                if via_default is not None:
                    add_motion(sequence, link, curr_state.substate_mod)
                    add_motion(sequence, via_default, speed_mod)
                elif curr_state.substate_mod >= 0.0 or speed_mod <= 0.0:
                    add_motion(sequence, link, speed_mod)
                else:
                    add_motion(sequence, link, -speed_mod)
                add_motion(sequence, cycle, speed_mod)
                if (
                    substate != motion
                    and substate & MODIFIER_MASK
                    and self.style_defaults.get(style, int(stop_modifiers)) != motion
                ):
                    curr_state.add_modifier_no_check(substate, curr_state.substate_mod)
                curr_state.substate_mod = speed_mod
                curr_state.substate = motion
                self.re_modify(sequence, curr_state)
                return True, (_count(link, via_default, cycle) - 1) & _U32

        if motion & ACTION_MASK:
            cycle = self.cycles.get(cycle_key(style, substate))
            if cycle is not None:
                link = self.get_link(style, substate, curr_state.substate_mod, motion, speed_mod)
                if link is not None:
                    curr_state.add_action(motion, speed_mod)
                    sequence.clear_physics()
                    sequence.remove_cyclic_anims()
                    add_motion(sequence, link, speed_mod)
                    add_motion(sequence, cycle, curr_state.substate_mod)
                    self.re_modify(sequence, curr_state)
                    return True, link.num_anims
                to_default = self.get_link(style, substate, curr_state.substate_mod, default_substate, 1.0)
                if to_default is not None:
                    action = self.get_link(style, default_substate, 1.0, motion, speed_mod)
                    # Retail looks the cycle up a second time here (acclient.c:337867): same key, same data.
                    if action is not None:
                        back = self.get_link(style, default_substate, 1.0, substate, curr_state.substate_mod)
                        curr_state.add_action(motion, speed_mod)
                        sequence.clear_physics()
                        sequence.remove_cyclic_anims()
                        add_motion(sequence, to_default, 1.0)
                        add_motion(sequence, action, speed_mod)
                        add_motion(sequence, back, 1.0)
                        add_motion(sequence, cycle, curr_state.substate_mod)
                        self.re_modify(sequence, curr_state)
                        return True, _count(to_default, action, back)

        if motion & MODIFIER_MASK:
            cycle = self.cycles.get(cycle_key(style, substate))
            if cycle is not None and not cycle.bitfield & CLEARS_MODIFIERS:
                data = self._modifier_data(style, motion)
                if data is not None:
                    added = curr_state.add_modifier(motion, speed_mod)
                    if not added:
                        # Retail hands StopSequenceMotion a scratch counter: num_anims stays 0.
                        self.stop_sequence_motion(motion, 1.0, curr_state, sequence)
                        added = curr_state.add_modifier(motion, speed_mod)
                    if added:
                        combine_motion(sequence, data, speed_mod)
                        return True, 0
        return False, 0

    def do_object_motion(
        self, motion: int, curr_state: MotionState, sequence: Sequence, speed_mod: float
    ) -> tuple[bool, int]:
        """``get_object_sequence`` outside a stop: returns (success, num_anims).

        Retail: CMotionTable::DoObjectMotion @ 0x00523E90 (acclient.c:339022)
        """
        return self.get_object_sequence(motion, curr_state, sequence, speed_mod, False)

    def stop_sequence_motion(
        self, motion: int, speed: float, curr_state: MotionState, sequence: Sequence
    ) -> tuple[bool, int]:
        """Stop ``motion``: returns (success, num_anims).

        The current substate goes back to the style's default (through
        ``get_object_sequence`` with ``stop_modifiers``); a modifier has its
        physics subtracted at the speed it was added with (``speed`` is unused,
        as in retail) and leaves the list. Anything else fails.

        Retail: CMotionTable::StopSequenceMotion @ 0x00522FC0 (acclient.c:337911)
        """
        if motion & SUBSTATE_MASK and motion == curr_state.substate:
            # A style with no default leaves retail's variable holding a pointer: no motion bits.
            default = self.style_defaults.get(curr_state.style, 0)
            _, num_anims = self.get_object_sequence(default, curr_state, sequence, 1.0, True)
            return True, num_anims
        if motion & MODIFIER_MASK:
            for node in curr_state.modifiers:
                if node.motion == motion:
                    data = self._modifier_data(curr_state.style, motion)
                    if data is None:
                        return False, 0
                    subtract_motion(sequence, data, node.speed_mod)
                    curr_state.remove_modifier(node)
                    return True, 0
        return False, 0

    def stop_object_motion(
        self, motion: int, speed: float, curr_state: MotionState, sequence: Sequence
    ) -> tuple[bool, int]:
        """Stop ``motion`` on the body: returns (success, num_anims).

        The decompilation has only the prototype of ``CMotionTable::StopObjectMotion``
        (same signature as StopSequenceMotion; called by
        ``MotionTableManager::PerformMovement`` at acclient.c:330235) and no body;
        like ACE, acphys takes it to be ``StopSequenceMotion``.

        Retail: CMotionTable::StopSequenceMotion @ 0x00522FC0 (acclient.c:337911)
        """
        return self.stop_sequence_motion(motion, speed, curr_state, sequence)

    def stop_object_completely(self, curr_state: MotionState, sequence: Sequence) -> tuple[bool, int]:
        """Stop every modifier (head first), then the substate: returns (any success, num_anims).

        num_anims is that of the last stop, the substate's.

        Retail: CMotionTable::StopObjectCompletely @ 0x00523ED0 (acclient.c:339028)
        """
        success = False
        while curr_state.modifiers:
            head = curr_state.modifiers[0]
            stopped, _ = self.stop_sequence_motion(head.motion, head.speed_mod, curr_state, sequence)
            if not stopped:
                # A failed stop leaves the head in place: retail would spin on it forever.
                raise ValueError(
                    f"modifier 0x{head.motion:08X} has no modifier data in this table: "
                    "retail StopObjectCompletely would loop forever on it"
                )
            success = True
        stopped, num_anims = self.stop_sequence_motion(
            curr_state.substate, curr_state.substate_mod, curr_state, sequence
        )
        return stopped or success, num_anims

    def set_default_state(self, state: MotionState, sequence: Sequence) -> tuple[bool, int]:
        """Put ``state`` and ``sequence`` in the default style's default cycle at speed 1.

        Clears modifiers and actions, then the sequence's physics and all its
        animations, and adds the cycle: returns (success, cycle animations - 1).

        Retail: CMotionTable::SetDefaultState @ 0x005230A0 (acclient.c:337969)
        """
        default_substate = self.style_defaults.get(self.default_style)
        if default_substate is None:
            return False, 0
        state.clear_modifiers()
        state.clear_actions()
        cycle = self.cycles.get(cycle_key(self.default_style, default_substate))
        if cycle is None:
            return False, 0
        state.style = self.default_style
        state.substate = default_substate
        state.substate_mod = 1.0
        sequence.clear_physics()
        sequence.clear_animations()
        add_motion(sequence, cycle, state.substate_mod)
        return True, (cycle.num_anims - 1) & _U32

    def re_modify(self, sequence: Sequence, state: MotionState) -> None:
        """Re-apply the modifiers after the sequence was rebuilt.

        Retail walks a copy of the state only to count: each turn it takes the
        *current* head modifier off ``state`` and re-issues it through
        ``get_object_sequence`` (which pushes it back at the head). So with n
        modifiers the head one is re-applied n times and the others are not
        re-applied (they stay in the list); a modifier the current cycle
        refuses is dropped.

        Retail: CMotionTable::re_modify @ 0x005222E0 (acclient.c:337285)
        """
        for _ in range(len(state.modifiers)):
            head = state.modifiers[0]
            state.remove_modifier(head)
            self.get_object_sequence(head.motion, state, sequence, head.speed_mod, False)
