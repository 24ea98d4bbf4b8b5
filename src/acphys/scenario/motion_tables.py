"""``[motion_table.NAME]``: motion tables written in scenario files, and the built-in ones.

A table names its default style and lists its cycles, links and modifiers.
Each entry is one animation (``frames`` at ``framerate``, optionally played
from ``low_frame`` to ``high_frame``) with the entry's baked root motion:
``velocity`` in m/s and ``omega`` in degrees per second, both in the body's
local space and per unit of speed. Optional ``pos_frame`` (a translation
applied at every frame boundary, body-local metres) and ``hooks`` fill in
the animation's position frames and frame hooks. Motions and styles are
retail command names (``"RunForward"``) or ids. Velocities, turn rates and
framerates are stored as float32, as the DAT records hold them.

The built-in tables are files of the same format in ``acphys/data/motion_tables``.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Callable
from importlib import resources
from typing import Any

from acphys.math.frame import Frame
from acphys.motion import anim_hooks
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.commands import READY, SUBSTATE_MASK
from acphys.motion.motion_table import (
    CLEARS_MODIFIERS,
    DEFAULT_SUBSTATE_ONLY,
    MotionData,
    MotionTable,
    cycle_key,
)
from acphys.scenario import values as read
from acphys.scenario.values import Ctx, ScenarioError

ANIMATION_KEYS = ("framerate", "frames", "low_frame", "high_frame", "velocity", "omega", "pos_frame", "hooks")
CYCLE_KEYS = ("style", "motion", "flags", *ANIMATION_KEYS)
LINK_KEYS = ("style", "from", "to", *ANIMATION_KEYS)
MODIFIER_KEYS = ("style", "motion", *ANIMATION_KEYS)
TABLE_KEYS = ("default_style", "style_defaults", "cycle", "link", "modifier")

#: ``MotionData`` bitfield names for ``flags``.
DATA_FLAGS = {"clears_modifiers": CLEARS_MODIFIERS, "default_substate_only": DEFAULT_SUBSTATE_ONLY}

_DIRECTIONS = {
    "both": anim_hooks.AnimHookDir.BOTH,
    "forward": anim_hooks.AnimHookDir.FORWARD,
    "backward": anim_hooks.AnimHookDir.BACKWARD,
}


#: The most frames one animation may have, and all the animations of a scenario's motion tables
#: together: a frame costs some 500 bytes built (its part and position frames), so 200,000 are
#: about 100 MB. Retail's humanoid table has 232 frames in all, 30 in its longest animation.
MAX_ANIMATION_FRAMES = 100_000
MAX_SCENARIO_FRAMES = 200_000
#: The sections of a motion table that hold animations.
ANIMATION_SECTIONS = ("cycle", "link", "modifier")


def _count(ctx: Ctx, key: str, value: Any, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ctx.fail(key, f"expected a whole number in [{low}, {high}], got {read.kind(value)}")
    return value


_HOOK_ARGS: dict[str, tuple[Callable[..., anim_hooks.AnimHook], tuple[str, ...]]] = {
    "AnimDone": (anim_hooks.AnimDoneHook, ()),
    "SetOmega": (anim_hooks.SetOmegaHook, ("axis",)),
    "Ethereal": (anim_hooks.EtherealHook, ("ethereal",)),
    "Scale": (anim_hooks.ScaleHook, ("end", "time")),
    "NoDraw": (anim_hooks.NoDrawHook, ("no_draw",)),
    "Sound": (anim_hooks.SoundHook, ()),
    "Attack": (anim_hooks.AttackHook, ()),
    "CreateParticle": (anim_hooks.CreateParticleHook, ()),
    "DefaultScript": (anim_hooks.DefaultScriptHook, ()),
    "CallPES": (anim_hooks.CallPESHook, ()),
}


HOOK_KEYS = ("kind", "direction", "axis", "ethereal", "end", "time", "no_draw")


def read_hook(ctx: Ctx, key: str, entry: dict[str, Any], where: str) -> anim_hooks.AnimHook:
    """One hook from ``entry`` (its ``kind``, its arguments and ``direction``); ``where`` is the
    key that places it (``frame`` in an animation, ``at`` in a script), already read by the caller.
    """
    if "kind" not in entry:
        raise ctx.fail(f"{key}.kind", f"missing (a hook needs {where} and kind)")
    kind = read.string(ctx, f"{key}.kind", entry["kind"])
    if kind not in _HOOK_ARGS:
        raise ctx.fail(f"{key}.kind", f"unknown hook {kind!r} (known: {', '.join(_HOOK_ARGS)})")
    factory, arg_names = _HOOK_ARGS[kind]
    extra = [name for name in entry if name not in (where, "kind", "direction", *arg_names)]
    if extra:
        raise ctx.fail(f"{key}.{extra[0]}", f"not used by a {kind} hook")
    args: list[Any] = []
    for name in arg_names:
        if name not in entry:
            raise ctx.fail(f"{key}.{name}", f"missing (a {kind} hook needs {', '.join(arg_names)})")
        if name == "axis":
            args.append(read.degrees_per_second(ctx, f"{key}.axis", entry["axis"]))
        elif name in ("ethereal", "no_draw"):
            args.append(read.boolean(ctx, f"{key}.{name}", entry[name]))
        else:
            args.append(read.float32(ctx, f"{key}.{name}", entry[name], 0.0, 1e6))
    direction = read.string(ctx, f"{key}.direction", entry.get("direction", "both"))
    if direction not in _DIRECTIONS:
        raise ctx.fail(f"{key}.direction", f"expected one of {', '.join(_DIRECTIONS)}, got {direction!r}")
    return factory(*args, direction=_DIRECTIONS[direction])


def _hook(ctx: Ctx, key: str, raw: Any, num_frames: int) -> tuple[int, anim_hooks.AnimHook]:
    entry = read.table(ctx, key, raw, ("frame", *HOOK_KEYS))
    if "frame" not in entry:
        raise ctx.fail(f"{key}.frame", "missing (a hook needs frame and kind)")
    frame = _count(ctx, f"{key}.frame", entry["frame"], 0, num_frames - 1)
    return frame, read_hook(ctx, key, entry, "frame")


def _motion_data(ctx: Ctx, key: str, entry: dict[str, Any], bitfield: int) -> MotionData:
    """One animation and its root motion, as the ``MotionData`` of a cycle, link or modifier."""
    for required in ("framerate", "frames"):
        if required not in entry:
            raise ctx.fail(f"{key}.{required}", "missing (an animation needs framerate and frames)")
    framerate = read.float32(ctx, f"{key}.framerate", entry["framerate"], -1000.0, 1000.0)
    num_frames = _count(ctx, f"{key}.frames", entry["frames"], 1, MAX_ANIMATION_FRAMES)
    low_frame = _count(ctx, f"{key}.low_frame", entry.get("low_frame", 0), 0, num_frames - 1)
    high_frame = _count(ctx, f"{key}.high_frame", entry.get("high_frame", -1), -1, num_frames - 1)

    frames = [AnimFrame() for _ in range(num_frames)]
    for index, raw in enumerate(read.list_of_tables(ctx, f"{key}.hooks", entry.get("hooks", []))):
        frame, hook = _hook(ctx, f"{key}.hooks[{index}]", raw, num_frames)
        frames[frame].hooks.append(hook)
    pos_frames = None
    if "pos_frame" in entry:
        step = read.vector(ctx, f"{key}.pos_frame", entry["pos_frame"])
        pos_frames = [Frame(origin=step) for _ in range(num_frames)]
    animation = Animation(frames, pos_frames, name=key)

    velocity = read.vector(ctx, f"{key}.velocity", entry.get("velocity", [0.0, 0.0, 0.0]))
    omega = read.degrees_per_second(ctx, f"{key}.omega", entry.get("omega", [0.0, 0.0, 0.0]))
    return MotionData([AnimData(animation, low_frame, high_frame, framerate)], velocity, omega, bitfield)


def _flags(ctx: Ctx, key: str, value: Any) -> int:
    if not isinstance(value, list) or not all(isinstance(name, str) for name in value):
        raise ctx.fail(key, f"expected a list of flag names, got {read.kind(value)}")
    bitfield = 0
    for name in value:
        if name not in DATA_FLAGS:
            raise ctx.fail(key, f"unknown flag {name!r} (known: {', '.join(DATA_FLAGS)})")
        bitfield |= DATA_FLAGS[name]
    return bitfield


def read_motion_table(ctx: Ctx, key: str, raw: Any) -> MotionTable:
    """Build one ``MotionTable`` from its ``[motion_table.NAME]`` table."""
    table = read.table(ctx, key, raw, TABLE_KEYS)
    if "default_style" not in table:
        raise ctx.fail(f"{key}.default_style", 'missing (for example default_style = "NonCombat")')
    default_style = read.style(ctx, f"{key}.default_style", table["default_style"])

    style_defaults = {default_style: READY}
    raw_defaults = table.get("style_defaults", {})
    if not isinstance(raw_defaults, dict):
        raise ctx.fail(
            f"{key}.style_defaults", f"expected a table of style = substate, got {read.kind(raw_defaults)}"
        )
    for style_name, substate in raw_defaults.items():
        style = read.style(ctx, f"{key}.style_defaults.{style_name}", style_name)
        style_defaults[style] = read.motion(ctx, f"{key}.style_defaults.{style_name}", substate)

    cycles: dict[int, MotionData] = {}
    for index, item in enumerate(read.list_of_tables(ctx, f"{key}.cycle", table.get("cycle", []))):
        where = f"{key}.cycle[{index}]"
        entry = read.table(ctx, where, item, CYCLE_KEYS)
        if "motion" not in entry:
            raise ctx.fail(f"{where}.motion", "missing (which motion this cycle plays)")
        style = read.style(ctx, f"{where}.style", entry["style"]) if "style" in entry else default_style
        motion = read.motion(ctx, f"{where}.motion", entry["motion"])
        if not motion & SUBSTATE_MASK:
            raise ctx.fail(f"{where}.motion", f"0x{motion:08X} is not a substate, so it cannot cycle")
        bitfield = _flags(ctx, f"{where}.flags", entry.get("flags", []))
        cycle = cycle_key(style, motion)
        if cycle in cycles:
            raise ctx.fail(f"{where}.motion", "this style already has a cycle for that motion")
        cycles[cycle] = _motion_data(ctx, where, entry, bitfield)
    for style, substate in style_defaults.items():
        if cycle_key(style, substate) not in cycles:
            raise ctx.fail(
                f"{key}.cycle", f"the default substate 0x{substate:08X} of style 0x{style:08X} has no cycle"
            )

    links: dict[int, dict[int, MotionData]] = {}
    for index, item in enumerate(read.list_of_tables(ctx, f"{key}.link", table.get("link", []))):
        where = f"{key}.link[{index}]"
        entry = read.table(ctx, where, item, LINK_KEYS)
        for required in ("from", "to"):
            if required not in entry:
                raise ctx.fail(f"{where}.{required}", "missing (a link goes from one motion to another)")
        style = read.style(ctx, f"{where}.style", entry["style"]) if "style" in entry else default_style
        source = read.motion(ctx, f"{where}.from", entry["from"])
        target = read.motion(ctx, f"{where}.to", entry["to"])
        inner = links.setdefault(cycle_key(style, source), {})
        if target in inner:
            raise ctx.fail(f"{where}.to", "a link between these motions already exists")
        inner[target] = _motion_data(ctx, where, entry, 0)

    modifiers: dict[int, MotionData] = {}
    for index, item in enumerate(read.list_of_tables(ctx, f"{key}.modifier", table.get("modifier", []))):
        where = f"{key}.modifier[{index}]"
        entry = read.table(ctx, where, item, MODIFIER_KEYS)
        if "motion" not in entry:
            raise ctx.fail(f"{where}.motion", "missing (which motion this modifier plays)")
        motion = read.motion(ctx, f"{where}.motion", entry["motion"])
        # A modifier without a style is the style-independent one, keyed by the bare command index.
        style = read.style(ctx, f"{where}.style", entry["style"]) if "style" in entry else 0
        modifier = cycle_key(style, motion)
        if modifier in modifiers:
            raise ctx.fail(f"{where}.motion", "this style already has a modifier for that motion")
        modifiers[modifier] = _motion_data(ctx, where, entry, 0)

    return MotionTable(default_style, style_defaults, cycles, modifiers, links)


def read_motion_tables(ctx: Ctx, raw: Any) -> dict[str, MotionTable]:
    """Every ``[motion_table.NAME]`` of a scenario."""
    if not isinstance(raw, dict):
        raise ctx.fail("motion_table", f"expected tables [motion_table.NAME], got {read.kind(raw)}")
    frames = _frames_declared(raw)
    if frames > MAX_SCENARIO_FRAMES:
        raise ctx.fail(
            "motion_table",
            f"the animations declare {frames:,} frames in all: more than the {MAX_SCENARIO_FRAMES:,} "
            "allowed (MAX_SCENARIO_FRAMES)",
        )
    tables: dict[str, MotionTable] = {}
    for name, value in raw.items():
        with ctx.part(f"motion_table.{name}"):
            tables[name] = read_motion_table(ctx, f"motion_table.{name}", value)
    return tables


def builtin_motion_tables() -> list[str]:
    """The names of the motion tables shipped with acphys."""
    folder = resources.files("acphys.data.motion_tables")
    return sorted(entry.name[:-5] for entry in folder.iterdir() if entry.name.endswith(".toml"))


def _builtin_text(name: str) -> str:
    if name not in builtin_motion_tables():
        raise KeyError(f"no built-in motion table {name!r} (known: {', '.join(builtin_motion_tables())})")
    return resources.files("acphys.data.motion_tables").joinpath(f"{name}.toml").read_text("utf-8")


def builtin_motion_table_text(name: str) -> str:
    """The built-in motion table ``name`` as a scenario's ``[motion_table.NAME]`` section (its file
    holds one ``[motion_table]``), to copy into a scenario and change."""
    text = _builtin_text(name)
    text = re.sub(r"^\[motion_table\]", f"[motion_table.{name}]", text, flags=re.MULTILINE)
    return re.sub(r"^\[\[motion_table\.", f"[[motion_table.{name}.", text, flags=re.MULTILINE)


def builtin_motion_table(name: str) -> MotionTable:
    """A fresh copy of the built-in motion table ``name`` (``"humanoid"``)."""
    text = _builtin_text(name)
    source = f"<built-in motion table {name}>"
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ScenarioError(f"{source}: not valid TOML: {error}") from None
    # Keyed as a scenario's [motion_table.NAME] would be: its animations are named the same
    # ("motion_table.humanoid.cycle[0]") whether a scenario writes the table out or not.
    return read_motion_table(Ctx(source), f"motion_table.{name}", document.get("motion_table"))


def _frames_declared(tables: dict[str, Any]) -> int:
    """The frames all the animations of ``[motion_table.*]`` declare, counted before any is built
    (a ``frames`` that is not a whole number counts nothing: its reader reports it)."""
    total = 0
    for table in tables.values():
        for section in ANIMATION_SECTIONS:
            entries = table.get(section) if isinstance(table, dict) else None
            for entry in entries if isinstance(entries, list) else ():
                frames = entry.get("frames") if isinstance(entry, dict) else None
                if isinstance(frames, int) and not isinstance(frames, bool) and frames > 0:
                    total += frames
    return total
