"""Retail DAT animations (``CAnimation``, 0x03xxxxxx) and motion tables (``CMotionTable``,
0x09xxxxxx), read into :class:`acphys.motion.animation.Animation` and
:class:`acphys.motion.motion_table.MotionTable`.

Like the other records, each starts with its DID (``DBObj::Serialize``), then the class's
``UnPack`` body; little-endian, IEEE single floats. A motion table names its animations by id;
the caller's ``load_animation`` resolves them (retail asks the DBO cache).
"""

from __future__ import annotations

from collections.abc import Callable

from acphys.dat.container import DatError
from acphys.dat.records import Reader
from acphys.math.vector import Vector3
from acphys.motion import anim_hooks as hooks
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.motion_table import MotionData, MotionTable

#: ``CAnimation`` bitfield bit 0: position (root-motion) frames follow the counts.
ANIM_HAS_POS_FRAMES = 0x1
#: ``MotionData`` flag byte: bit 0 a velocity vector follows the animations, bit 1 an omega.
MOTION_HAS_VELOCITY = 0x1
MOTION_HAS_OMEGA = 0x2
#: The fastest animation framerate read, frames a second either way (a negative rate plays
#: backwards). Retail's animations play at tens of frames a second; a sequence steps through
#: every frame it passes, hooks and all, so a damaged rate (1e7) would stall the simulation.
MAX_FRAMERATE = 1000.0
#: ``AnimPartChange`` part ids are GfxObj ids (``Unpack_AsDataIDOfKnownType(0x1000000, ...)``).
GFXOBJ_ID_TYPE = 0x01000000


def _packed_data_id(reader: Reader, known_type: int) -> int:
    """A data id stored as a u16 (``known_type + value``) or, with the u16's top bit set, as
    two u16s (``known_type + ((first & 0x3FFF) << 16 | second)``).

    The retail reader (``Unpack_AsDataIDOfKnownType``) is not in the decompiled modules; this
    rule is ACE's ``ReadAsDataIDOfKnownType``.
    """
    first = int(reader.unpack("H")[0])
    if first & 0x8000:
        second = int(reader.unpack("H")[0])
        return known_type + (((first & 0x3FFF) << 16) | second)
    return known_type + first


def _u32s(reader: Reader, count: int) -> list[int]:
    return [reader.u32() for _ in range(count)]


def _f32s(reader: Reader, count: int) -> list[float]:
    return [reader.f32() for _ in range(count)]


def _tween(reader: Reader, with_part: bool) -> list[int | float]:
    """{part,} start, end, time of the look hooks."""
    head: list[int | float] = [reader.u32()] if with_part else []
    return head + _f32s(reader, 3)


def _hook_body(reader: Reader, kind: int, direction: int) -> hooks.AnimHook | None:
    """The hook of type ``kind``, its body read (None for a type retail builds no hook for)."""
    d = {"direction": direction}
    T = hooks.AnimHookType
    if kind in (T.NOOP, T.DEFAULT_SCRIPT):
        return hooks.NOOPHook(**d) if kind == T.NOOP else hooks.DefaultScriptHook(**d)
    if kind == T.SOUND:
        return hooks.SoundHook(reader.u32(), **d)
    if kind == T.SOUND_TABLE:
        return hooks.SoundTableHook(reader.u32(), **d)
    if kind == T.SOUND_TWEAKED:
        # Retail stores prob before prio (SoundTweakedHook::UnPack); ACE reads prio first.
        gid = reader.u32()
        prob, prio, vol = _f32s(reader, 3)
        return hooks.SoundTweakedHook(gid, prio=prio, prob=prob, vol=vol, **d)
    if kind == T.ATTACK:
        part_index = int(reader.unpack("i")[0])
        lx, ly, rx, ry, radius, height = _f32s(reader, 6)
        return hooks.AttackHook(part_index, (lx, ly), (rx, ry), radius, height, **d)
    if kind == T.REPLACE_OBJECT:
        part_index = int(reader.unpack("B")[0])
        return hooks.ReplaceObjectHook(part_index, _packed_data_id(reader, GFXOBJ_ID_TYPE), **d)
    if kind == T.ETHEREAL:
        return hooks.EtherealHook(bool(reader.u32()), **d)
    if kind == T.NODRAW:
        return hooks.NoDrawHook(bool(reader.u32()), **d)
    if kind == T.SET_LIGHT:
        return hooks.SetLightHook(bool(reader.u32()), **d)
    if kind == T.DEFAULT_SCRIPT_PART:
        return hooks.DefaultScriptPartHook(reader.u32(), **d)
    tweens: dict[int, type[hooks.AnimHook]] = {
        T.TRANSPARENT: hooks.TransparentHook,
        T.LUMINOUS: hooks.LuminousHook,
        T.DIFFUSE: hooks.DiffuseHook,
        T.TRANSPARENT_PART: hooks.TransparentPartHook,
        T.LUMINOUS_PART: hooks.LuminousPartHook,
        T.DIFFUSE_PART: hooks.DiffusePartHook,
    }
    if kind in tweens:
        with_part = kind in (T.TRANSPARENT_PART, T.LUMINOUS_PART, T.DIFFUSE_PART)
        return tweens[kind](*_tween(reader, with_part), **d)
    if kind == T.SCALE:
        end, time = _f32s(reader, 2)
        return hooks.ScaleHook(end, time, **d)
    if kind in (T.CREATE_PARTICLE, T.CREATE_BLOCKING_PARTICLE):
        emitter_info_id, part_index = _u32s(reader, 2)
        offset = reader.frame()
        cls = hooks.CreateParticleHook if kind == T.CREATE_PARTICLE else hooks.CreateBlockingParticleHook
        return cls(emitter_info_id, part_index, offset, reader.u32(), **d)
    if kind in (T.DESTROY_PARTICLE, T.STOP_PARTICLE):
        cls2 = hooks.DestroyParticleHook if kind == T.DESTROY_PARTICLE else hooks.StopParticleHook
        return cls2(reader.u32(), **d)
    if kind == T.CALL_PES:
        pes = reader.u32()
        return hooks.CallPESHook(pes, reader.f32(), **d)
    if kind == T.SET_OMEGA:
        return hooks.SetOmegaHook(reader.vector(), **d)
    if kind == T.TEXTURE_VELOCITY:
        u, v = _f32s(reader, 2)
        return hooks.TextureVelocityHook(u, v, **d)
    if kind == T.TEXTURE_VELOCITY_PART:
        part_index = int(reader.unpack("i")[0])
        u, v = _f32s(reader, 2)
        return hooks.TextureVelocityPartHook(part_index, u, v, **d)
    if kind == T.ANIM_DONE:
        return None
    raise DatError(f"{reader.what}: unknown animation hook type {kind} at byte {reader.pos - 8}")


def unpack_hook(reader: Reader) -> hooks.AnimHook | None:
    """One hook: type, direction, the type's fields, then alignment to a dword.

    Retail's switch has no case for AnimDone (4): it reads the type and direction and yields
    no hook, which ``add_to_list`` then leaves off the frame; so does this (None). Any other
    type outside the switch is a DatError (retail would go on reading its fields as the next
    hook).

    Retail: CAnimHook::UnPackHook @ 0x005271D0 (acclient.c:342736)
    """
    kind = reader.u32()
    direction = int(reader.unpack("i")[0])
    try:
        hook = _hook_body(reader, kind, direction)
    except ValueError as error:
        raise DatError(f"{reader.what}: hook type {kind}: {error}") from None
    reader.align()
    return hook


def _anim_frame(reader: Reader, num_parts: int) -> AnimFrame:
    """Retail: AnimFrame::UnPack @ 0x0051F8E0 (acclient.c:333869)"""
    frames = [reader.frame() for _ in range(num_parts)]
    found = [unpack_hook(reader) for _ in range(reader.count(8, "hook"))]
    return AnimFrame(frames, [hook for hook in found if hook is not None])


def unpack_animation(data: bytes) -> Animation:
    """Parse a ``CAnimation``: DID, bitfield, part count, frame count; with bitfield bit 0 one
    position frame per frame; then per frame its part frames and hooks.

    Retail: CAnimation::UnPack @ 0x0051FB50 (acclient.c:334085)
    """
    reader = Reader(data, "animation")
    did = reader.u32()
    reader.what = f"animation {did:#010x}"
    bitfield = reader.u32()
    num_parts = reader.count(28, "part")
    num_frames = reader.count(4, "frame")
    pos_frames = [reader.frame() for _ in range(num_frames)] if bitfield & ANIM_HAS_POS_FRAMES else None
    part_frames = [_anim_frame(reader, num_parts) for _ in range(num_frames)]
    try:
        return Animation(part_frames, pos_frames, name=f"{did:#010x}")
    except ValueError as error:
        raise DatError(f"{reader.what}: {error}") from None


def _anim_data(reader: Reader, load_animation: Callable[[int], Animation]) -> AnimData:
    """Retail: AnimData::UnPack @ 0x00525E50 (acclient.c:341178)"""
    anim_id = reader.u32()
    low_frame, high_frame = (int(v) for v in reader.unpack("2i"))
    framerate = reader.f32()
    if abs(framerate) > MAX_FRAMERATE:
        raise DatError(
            f"{reader.what}: animation {anim_id:#010x} plays at {framerate:.6g} frames a second, over "
            f"{MAX_FRAMERATE:g} (MAX_FRAMERATE)"
        )
    animation = load_animation(anim_id)
    try:
        return AnimData(animation, low_frame, high_frame, framerate)
    except ValueError as error:
        raise DatError(f"{reader.what}: animation {anim_id:#010x}: {error}") from None


def _motion_data(reader: Reader, load_animation: Callable[[int], Animation]) -> tuple[int, MotionData]:
    """One keyed ``MotionData``: key, animation count (byte), bitfield (byte), flag byte,
    padding to a dword, the animations, then velocity (flag bit 0) and omega (flag bit 1);
    an absent vector is zero.

    Retail: MotionData::UnPack @ 0x00526570 (acclient.c:341813)
    """
    key = reader.u32()
    num_anims, bitfield, flags = (int(v) for v in reader.unpack("3B"))
    reader.align()
    anims = [_anim_data(reader, load_animation) for _ in range(num_anims)]
    velocity = reader.vector() if flags & MOTION_HAS_VELOCITY else Vector3()
    omega = reader.vector() if flags & MOTION_HAS_OMEGA else Vector3()
    return key, MotionData(anims, velocity, omega, bitfield)


def _motion_hash(
    reader: Reader, load_animation: Callable[[int], Animation], name: str
) -> dict[int, MotionData]:
    """A count, then that many keyed MotionData; a repeated key keeps the last one (retail
    pushes each onto the front of its hash bucket, so lookups find the newest)."""
    return dict(_motion_data(reader, load_animation) for _ in range(reader.count(8, name)))


def unpack_motion_table(data: bytes, load_animation: Callable[[int], Animation]) -> MotionTable:
    """Parse a ``CMotionTable``: DID, default style; style defaults (count, {style, substate});
    cycles; modifiers (each a count of keyed MotionData); links (count, {key, count, keyed
    MotionData}). ``load_animation(anim_id)`` supplies each AnimData's animation.

    The decompiled body's member names are shifted by its base classes; the order above is
    acclient.h's ``CMotionTable`` member order, which ACE's reader also follows.

    Retail: CMotionTable::UnPack @ 0x005238C0 (acclient.c:338603)
    """
    reader = Reader(data, "motion table")
    did = reader.u32()
    reader.what = f"motion table {did:#010x}"
    default_style = reader.u32()
    style_defaults: dict[int, int] = {}
    for _ in range(reader.count(8, "style default")):
        style = reader.u32()
        style_defaults[style] = reader.u32()
    cycles = _motion_hash(reader, load_animation, "cycle")
    modifiers = _motion_hash(reader, load_animation, "modifier")
    links: dict[int, dict[int, MotionData]] = {}
    for _ in range(reader.count(8, "link")):
        key = reader.u32()
        links[key] = _motion_hash(reader, load_animation, f"link {key:#010x}")
    try:
        return MotionTable(default_style, style_defaults, cycles, modifiers, links)
    except ValueError as error:
        raise DatError(f"{reader.what}: {error}") from None
