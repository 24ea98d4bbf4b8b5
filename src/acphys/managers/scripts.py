"""Physics scripts: timed lists of animation hooks, and the per-body ``ScriptManager`` that fires them.

A physics script (DAT type 0x2B, ``PhysicsScript``) is a list of
``PhysicsScriptData`` entries, each an animation hook (``acphys.motion.anim_hooks``)
with the time, in seconds from the script's start, at which it fires. A body's
``ScriptManager`` queues scripts back to back: a script added while another is
queued starts when the last one's ``length`` (its last hook's start time) has
passed, so a long effect played twice runs twice in sequence, and a script
whose hooks outlast its predecessor's length still fires every hook, in order.

acphys has no DAT: scripts and script tables are plain Python objects, and
:func:`register_script` stands in for ``DBObj::Get`` (the portal database).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.motion.anim_hooks import AnimHook
    from acphys.physics_obj import PhysicsObj


class PhysicsScriptData:
    """Retail ``PhysicsScriptData`` (acclient.h:31992): ``hook`` fires ``start_time`` s into the script."""

    __slots__ = ("hook", "start_time")

    def __init__(self, start_time: float, hook: AnimHook) -> None:
        if not start_time >= 0.0:
            raise ValueError(f"PhysicsScriptData: start_time must be a number >= 0, got {start_time!r}")
        self.start_time = float(start_time)
        self.hook = hook

    def __repr__(self) -> str:
        return f"PhysicsScriptData({self.start_time!r}, {self.hook!r})"


class PhysicsScript:
    """Retail ``PhysicsScript`` (acclient.h:31801): ``script_data`` sorted by start time, and ``length``.

    As ``UnPack`` leaves it: the entries sorted by ``start_time``
    (``PhysicsScriptData::Sort``; retail's qsort leaves equal times in no
    defined order, acphys keeps them in the given order) and ``length`` the
    last entry's start time. Retail dereferences the first entry when a script
    is queued, so a script needs at least one hook.

    Retail: PhysicsScript::UnPack @ 0x005218B0 (acclient.c:336451)
    """

    __slots__ = ("length", "script_data")

    def __init__(self, script_data: list[PhysicsScriptData]) -> None:
        if not script_data:
            raise ValueError("PhysicsScript: a script needs at least one hook (retail reads the first entry)")
        self.script_data = sorted(script_data, key=lambda entry: entry.start_time)
        self.length = self.script_data[-1].start_time

    @classmethod
    def of(cls, *entries: tuple[float, AnimHook]) -> PhysicsScript:
        """A script from ``(start_time, hook)`` pairs."""
        return cls([PhysicsScriptData(start, hook) for start, hook in entries])

    def __repr__(self) -> str:
        return f"PhysicsScript(length={self.length!r}, hooks={len(self.script_data)})"


class ScriptAndModData:
    """Retail ``ScriptAndModData`` (acclient.h:31999): ``script_id`` is played for intensities up to
    ``mod`` (a ``float`` field)."""

    __slots__ = ("mod", "script_id")

    def __init__(self, mod: float, script_id: int) -> None:
        self.mod = f32(mod)
        self.script_id = script_id


class PhysicsScriptTableData:
    """Retail ``PhysicsScriptTableData``: one script type's variants, by rising intensity ``mod``."""

    __slots__ = ("script_array",)

    def __init__(self, script_array: list[ScriptAndModData]) -> None:
        self.script_array = list(script_array)

    def get_script(self, mod: float) -> int:
        """The first variant whose ``mod`` is at least ``mod`` (0 when every one is below it).

        ``mod`` is a ``float`` parameter.

        Retail: PhysicsScriptTableData::GetScript @ 0x00521A20 (acclient.c:336551)
        """
        mod = f32(mod)
        for entry in self.script_array:
            if not mod > entry.mod:
                return entry.script_id
        return 0


class PhysicsScriptTable:
    """Retail ``PhysicsScriptTable`` (DAT type 0x34): script variants by ``PScriptType``."""

    __slots__ = ("script_table",)

    def __init__(self, script_table: dict[int, PhysicsScriptTableData]) -> None:
        self.script_table = dict(script_table)

    def get_script(self, script_type: int, mod: float) -> int:
        """The script id for ``script_type`` at intensity ``mod`` (a ``float`` parameter); 0 for a
        type the table lacks.

        Retail: PhysicsScriptTable::GetScript @ 0x00521E40 (acclient.c:336930)
        """
        data = self.script_table.get(script_type)
        return data.get_script(mod) if data is not None else 0


#: The scripts ``ScriptManager.add_script`` can find by id (retail: the portal DAT, type 0x2B).
_SCRIPTS: dict[int, PhysicsScript] = {}


def register_script(script_id: int, script: PhysicsScript) -> None:
    """Make ``script`` known under ``script_id`` (a non-zero DID)."""
    if not isinstance(script_id, int) or not 0 < script_id <= 0xFFFFFFFF:
        raise ValueError(f"register_script: script_id must be a non-zero 32-bit id, got {script_id!r}")
    _SCRIPTS[script_id] = script


def unregister_script(script_id: int) -> None:
    """Forget the script registered under ``script_id`` (if any)."""
    _SCRIPTS.pop(script_id, None)


def get_script(script_id: int) -> PhysicsScript | None:
    """The script registered under ``script_id`` (retail ``DBObj::Get``), or None."""
    return _SCRIPTS.get(script_id)


class ScriptData:
    """Retail ``ScriptData``: one queued script, its absolute ``start_time`` and the next in the queue."""

    __slots__ = ("next_data", "script", "start_time")

    def __init__(self, start_time: float, script: PhysicsScript) -> None:
        self.start_time = start_time
        self.script = script
        self.next_data: ScriptData | None = None


#: ``next_hook_time`` when no hook is pending (retail writes the double -1.0).
NO_HOOK_TIME = -1.0


class ScriptManager:
    """Retail ``ScriptManager`` (acclient.h:30815): the body's queue of playing scripts.

    ``curr_data`` is the playing script, ``last_data`` the last queued one,
    ``hook_index`` the index of the last hook fired in ``curr_data`` (-1 before
    the first) and ``next_hook_time`` the ``Timer::cur_time`` at which the next
    hook is due. Times are the world clock (``world.cur_time``), not the
    physics timer.

    Retail: ScriptManager::ScriptManager @ 0x0051B2F0 (acclient.c:329058)
    """

    __slots__ = ("curr_data", "hook_index", "last_data", "next_hook_time", "physobj")

    def __init__(self, physobj: PhysicsObj) -> None:
        self.physobj = physobj
        self.curr_data: ScriptData | None = None
        self.last_data: ScriptData | None = None
        self.hook_index = -1
        self.next_hook_time = 0.0

    def add_script_internal(self, script: PhysicsScript) -> bool:
        """Queue ``script``: it starts when the last queued one's length has run, or now.

        With an empty queue the script becomes current and its first hook is
        due at ``start_time + first start time``.

        Retail: ScriptManager::AddScriptInternal @ 0x0051B310 (acclient.c:329068)
        """
        last = self.last_data
        start_time = last.start_time + last.script.length if last is not None else self.physobj.world.cur_time
        data = ScriptData(start_time, script)
        if last is not None:
            last.next_data = data
            self.last_data = data
        else:
            self.curr_data = data
            self.last_data = data
            self.hook_index = -1
            self.next_hook_time = start_time + script.script_data[0].start_time
        return True

    def add_script(self, script_id: int) -> bool:
        """Queue the script registered under ``script_id``; False when there is none.

        Retail: ScriptManager::AddScript @ 0x0051B3A0 (acclient.c:329123)
        """
        script = get_script(script_id)
        if script is None:
            return False
        return self.add_script_internal(script)

    def next_hook(self) -> AnimHook | None:
        """Advance to the current script's next hook and return it (None past the last one).

        Sets ``next_hook_time`` to the hook after it: the next one in this
        script, else the first of the next queued script, else -1.0 (due at
        once, so the finished script is dropped on the same pass).

        Retail: ScriptManager::NextHook @ 0x0051B3F0 (acclient.c:329141)
        """
        curr = self.curr_data
        assert curr is not None
        self.hook_index += 1
        entries = curr.script.script_data
        index = self.hook_index
        if index >= len(entries):
            return None
        if index + 1 < len(entries):
            self.next_hook_time = curr.start_time + entries[index + 1].start_time
        elif curr.next_data is not None:
            following = curr.next_data
            self.next_hook_time = following.start_time + following.script.script_data[0].start_time
        else:
            self.next_hook_time = NO_HOOK_TIME
        return entries[index].hook

    def update_scripts(self) -> None:
        """Fire every hook that is due by ``world.cur_time``, dropping scripts as they run out.

        Retail: ScriptManager::UpdateScripts @ 0x0051B480 (acclient.c:329188)
        """
        while self.curr_data is not None and not self.physobj.world.cur_time < self.next_hook_time:
            hook = self.next_hook()
            if hook is not None:
                hook.execute(self.physobj)
                continue
            following = self.curr_data.next_data
            self.curr_data = following
            self.hook_index = -1
            if following is not None:
                self.next_hook_time = following.start_time + following.script.script_data[0].start_time
            else:
                self.next_hook_time = NO_HOOK_TIME
                self.last_data = None
