"""The retail ``CAnimHook`` kinds: events an animation frame fires on its body.

A sequence queues a frame's hooks on the body as it crosses the frame
(``CSequence::execute_hooks``, filtered by ``direction``); the body fires them
in ``process_hooks``. The hooks retail routes to a body function call it:
AnimDone, SetOmega, Ethereal, Scale, NoDraw, the look tweens (Transparent,
Luminous, Diffuse and their per-part kinds), the particle emitters
(Create, CreateBlocking, Destroy, Stop), DefaultScript and CallPES. The ones
about sound, lights, textures, attacks, part swaps and a child's default
script only record an event (``hook:<Kind>``) on the body, since acphys has
no renderer, sound, weenie or child objects.

Data and ``Execute`` are ported here; reading hooks from a retail DAT is
:func:`acphys.dat.motion.unpack_hook` (``CAnimHook::UnPackHook``). The hooks'
scalar data (scales, times, tween ends, pauses, sound and texture rates, attack
cone sizes) are ``float`` fields in retail (acclient.h) and are kept as float32.
"""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING, ClassVar

from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, pack4, unpack3, unpack4

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj


class AnimHookType(enum.IntEnum):
    """The hook kind ids of the DAT (acclient.h:7278, ``GetType``)."""

    UNKNOWN = -1
    NOOP = 0x0
    SOUND = 0x1
    SOUND_TABLE = 0x2
    ATTACK = 0x3
    ANIM_DONE = 0x4
    REPLACE_OBJECT = 0x5
    ETHEREAL = 0x6
    TRANSPARENT_PART = 0x7
    LUMINOUS = 0x8
    LUMINOUS_PART = 0x9
    DIFFUSE = 0xA
    DIFFUSE_PART = 0xB
    SCALE = 0xC
    CREATE_PARTICLE = 0xD
    DESTROY_PARTICLE = 0xE
    STOP_PARTICLE = 0xF
    NODRAW = 0x10
    DEFAULT_SCRIPT = 0x11
    DEFAULT_SCRIPT_PART = 0x12
    CALL_PES = 0x13
    TRANSPARENT = 0x14
    SOUND_TWEAKED = 0x15
    SET_OMEGA = 0x16
    TEXTURE_VELOCITY = 0x17
    TEXTURE_VELOCITY_PART = 0x18
    SET_LIGHT = 0x19
    CREATE_BLOCKING_PARTICLE = 0x1A


class AnimHookDir(enum.IntEnum):
    """``CAnimHook::AnimHookDir`` (acclient.h): which playback direction fires a hook."""

    UNKNOWN = -2
    BACKWARD = -1
    BOTH = 0
    FORWARD = 1


_DIRECTIONS = frozenset(int(d) for d in AnimHookDir)


class AnimHook:
    """Retail ``CAnimHook`` (acclient.h:30973): the base of every hook kind.

    ``direction`` is retail's ``direction_``: BACKWARD (-1) fires only in
    reverse playback, BOTH (0) always, FORWARD (1) only forwards; UNKNOWN (-2),
    the constructor's value, is never matched by ``execute_hooks``. Hooks read
    from the DAT always carry their own direction; hand-built hooks default
    to BOTH. The base ``execute`` records ``hook:<Kind>`` on the body.
    """

    __slots__ = ("direction",)

    hook_type: ClassVar[AnimHookType] = AnimHookType.UNKNOWN

    def __init__(self, *, direction: int = AnimHookDir.BOTH) -> None:
        if direction not in _DIRECTIONS:
            raise ValueError(f"{type(self).__name__}: direction must be -2, -1, 0 or 1, got {direction!r}")
        self.direction = int(direction)

    def execute(self, obj: PhysicsObj) -> None:
        obj.record_event(f"hook:{type(self).__name__}")

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in _fields(type(self)))
        return f"{type(self).__name__}({fields})"


def _fields(cls: type) -> list[str]:
    names: list[str] = []
    for klass in reversed(cls.__mro__):
        names.extend(getattr(klass, "__slots__", ()))
    return names


# -- the hooks that act on the physics ------------------------------------------------------


class NOOPHook(AnimHook):
    """Retail ``NOOPHook``: does nothing (the decompilation has no Execute of its own for it)."""

    __slots__ = ()
    hook_type = AnimHookType.NOOP

    def execute(self, obj: PhysicsObj) -> None:
        """Nothing."""


class AnimDoneHook(AnimHook):
    """Retail ``AnimDoneHook``: a link animation finished; the motion-table manager is told."""

    __slots__ = ()
    hook_type = AnimHookType.ANIM_DONE

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: AnimDoneHook::Execute @ 0x00526C20 (acclient.c:342335)"""
        obj.hook_anim_done()


#: Retail's static ``anim_done_hook`` (acclient_data.h:6271), queued by ``update_internal``
#: when a non-cyclic animation ends. Its direction is UNKNOWN (-2): it never goes
#: through the direction filter.
ANIM_DONE_HOOK = AnimDoneHook(direction=AnimHookDir.UNKNOWN)


class SetOmegaHook(AnimHook):
    """Retail ``SetOmegaHook``: sets the body's angular velocity (``axis``, rad/s)."""

    __slots__ = ("axis",)
    hook_type = AnimHookType.SET_OMEGA

    def __init__(self, axis: Vector3, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.axis = axis.copy()

    def execute(self, obj: PhysicsObj) -> None:
        """``CPhysicsObj::set_omega(axis, send_event = 1)``.

        Retail: SetOmegaHook::Execute @ 0x00526F30 (acclient.c:342547)
        """
        obj.set_omega(self.axis)


class EtherealHook(AnimHook):
    """Retail ``EtherealHook``: makes the body ethereal (or tries to make it solid)."""

    __slots__ = ("ethereal",)
    hook_type = AnimHookType.ETHEREAL

    def __init__(self, ethereal: bool, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.ethereal = bool(ethereal)

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: EtherealHook::Execute @ 0x00526BC0 (acclient.c:342311)"""
        obj.set_ethereal(self.ethereal, False)


class ScaleHook(AnimHook):
    """Retail ``ScaleHook``: scale the body to ``end`` over ``time`` seconds."""

    __slots__ = ("end", "time")
    hook_type = AnimHookType.SCALE

    def __init__(self, end: float, time: float, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.end, self.time, _ = unpack3(pack3(end, time, 0.0))

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: ScaleHook::Execute @ 0x00526E40 (acclient.c:342473)"""
        obj.set_scale(self.end, self.time)


class NoDrawHook(AnimHook):
    """Retail ``NoDrawHook``: hide or show the body's parts."""

    __slots__ = ("no_draw",)
    hook_type = AnimHookType.NODRAW

    def __init__(self, no_draw: bool, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.no_draw = bool(no_draw)

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: NoDrawHook::Execute @ 0x00526BE0 (acclient.c:342317)"""
        obj.set_nodraw(self.no_draw, False)


# -- sound, attacks and part swaps (recorded), looks, particles and scripts (routed to the body) --


class SoundHook(AnimHook):
    """Plays sound ``gid``.

    Retail: SoundHook::Execute @ 0x00526A20 (acclient.c:342187)
    """

    __slots__ = ("gid",)
    hook_type = AnimHookType.SOUND

    def __init__(self, gid: int = 0, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.gid = gid


class SoundTableHook(AnimHook):
    """Plays the body's sound-table entry ``sound_type``.

    Retail: SoundTableHook::Execute @ 0x00526AB0 (acclient.c:342218)
    """

    __slots__ = ("sound_type",)
    hook_type = AnimHookType.SOUND_TABLE

    def __init__(self, sound_type: int = 0, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.sound_type = sound_type


class SoundTweakedHook(AnimHook):
    """Plays sound ``gid`` with priority, probability and volume (defaults are the constructor's).

    Retail: SoundTweakedHook::Execute @ 0x00526A80 (acclient.c:342206)
    """

    __slots__ = ("gid", "prio", "prob", "vol")
    hook_type = AnimHookType.SOUND_TWEAKED

    def __init__(
        self,
        gid: int = 0,
        prio: float = 0.89999998,
        prob: float = 1.0,
        vol: float = 1.0,
        *,
        direction: int = AnimHookDir.BOTH,
    ) -> None:
        super().__init__(direction=direction)
        self.gid = gid
        self.prio, self.prob, self.vol = unpack3(pack3(prio, prob, vol))


class AttackHook(AnimHook):
    """Runs an attack with ``AttackCone`` ``(part_index, left (x, y), right (x, y), radius, height)``.

    Retail: AttackHook::Execute @ 0x00526B70 (acclient.c:342281)
    """

    __slots__ = ("height", "left", "part_index", "radius", "right")
    hook_type = AnimHookType.ATTACK

    def __init__(
        self,
        part_index: int = 0,
        left: tuple[float, float] = (0.0, 0.0),
        right: tuple[float, float] = (0.0, 0.0),
        radius: float = 0.0,
        height: float = 0.0,
        *,
        direction: int = AnimHookDir.BOTH,
    ) -> None:
        super().__init__(direction=direction)
        self.part_index = part_index
        lx, ly, rx, ry = unpack4(pack4(left[0], left[1], right[0], right[1]))
        self.left, self.right = (lx, ly), (rx, ry)
        self.radius, self.height, _ = unpack3(pack3(radius, height, 0.0))


class ReplaceObjectHook(AnimHook):
    """Swaps part ``part_index`` for object ``part_id`` (retail ``AnimPartChange``).

    The decompilation names no Execute for this kind; acphys records the event.
    """

    __slots__ = ("part_id", "part_index")
    hook_type = AnimHookType.REPLACE_OBJECT

    def __init__(self, part_index: int = 0, part_id: int = 0, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.part_index, self.part_id = part_index, part_id


class _Tween(AnimHook):
    """A look that tweens from ``start`` to ``end`` over ``time`` seconds (no retail counterpart)."""

    __slots__ = ("end", "start", "time")

    def __init__(
        self, start: float = 0.0, end: float = 0.0, time: float = 0.0, *, direction: int = AnimHookDir.BOTH
    ) -> None:
        super().__init__(direction=direction)
        self.start, self.end, self.time = unpack3(pack3(start, end, time))


class _PartTween(_Tween):
    """A per-part tween: ``part`` plus the tween (no retail counterpart)."""

    __slots__ = ("part",)

    def __init__(
        self,
        part: int = 0,
        start: float = 0.0,
        end: float = 0.0,
        time: float = 0.0,
        *,
        direction: int = AnimHookDir.BOTH,
    ) -> None:
        super().__init__(start, end, time, direction=direction)
        self.part = part


class TransparentHook(_Tween):
    """Tween the body's translucency from ``start`` to ``end`` over ``time`` seconds."""

    __slots__ = ()
    hook_type = AnimHookType.TRANSPARENT

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: TransparentHook::Execute @ 0x00526C30 (acclient.c:342341)"""
        obj.set_translucency2(self.start, self.end, self.time)


class TransparentPartHook(_PartTween):
    """Tween part ``part``'s translucency."""

    __slots__ = ()
    hook_type = AnimHookType.TRANSPARENT_PART

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: TransparentPartHook::Execute @ 0x00526CC0 (acclient.c:342388)"""
        obj.set_part_translucency(self.part, self.start, self.end, self.time)


class LuminousHook(_Tween):
    """Tween the part array's luminosity."""

    __slots__ = ()
    hook_type = AnimHookType.LUMINOUS

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: LuminousHook::Execute @ 0x00526D60 (acclient.c:342421)"""
        obj.set_luminosity(self.start, self.end, self.time)


class LuminousPartHook(_PartTween):
    """Tween part ``part``'s luminosity."""

    __slots__ = ()
    hook_type = AnimHookType.LUMINOUS_PART

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: LuminousPartHook::Execute @ 0x00526D30 (acclient.c:342415)"""
        obj.set_part_luminosity(self.part, self.start, self.end, self.time)


class DiffuseHook(_Tween):
    """Tween the part array's diffusion."""

    __slots__ = ()
    hook_type = AnimHookType.DIFFUSE

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: DiffuseHook::Execute @ 0x00526E00 (acclient.c:342461)"""
        obj.set_diffusion(self.start, self.end, self.time)


class DiffusePartHook(_PartTween):
    """Tween part ``part``'s diffusion."""

    __slots__ = ()
    hook_type = AnimHookType.DIFFUSE_PART

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: DiffusePartHook::Execute @ 0x00526D80 (acclient.c:342427)"""
        obj.set_part_diffusion(self.part, self.start, self.end, self.time)


class CreateParticleHook(AnimHook):
    """Creates particle emitter ``emitter_info_id`` on ``part_index`` at ``offset``, tagged ``emitter_id``."""

    __slots__ = ("emitter_id", "emitter_info_id", "offset", "part_index")
    hook_type = AnimHookType.CREATE_PARTICLE

    def __init__(
        self,
        emitter_info_id: int = 0,
        part_index: int = 0,
        offset: Frame | None = None,
        emitter_id: int = 0,
        *,
        direction: int = AnimHookDir.BOTH,
    ) -> None:
        super().__init__(direction=direction)
        self.emitter_info_id, self.part_index, self.emitter_id = emitter_info_id, part_index, emitter_id
        self.offset = offset.copy() if offset is not None else Frame()

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: CreateParticleHook::Execute @ 0x00526EC0 (acclient.c:342512)"""
        obj.create_particle_emitter(self.emitter_info_id, self.part_index, self.offset, self.emitter_id)


class CreateBlockingParticleHook(CreateParticleHook):
    """As CreateParticleHook, unless an emitter tagged ``emitter_id`` is already playing."""

    __slots__ = ()
    hook_type = AnimHookType.CREATE_BLOCKING_PARTICLE

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: CreateBlockingParticleHook::Execute @ 0x00526EF0 (acclient.c:342524)"""
        obj.create_blocking_particle_emitter(
            self.emitter_info_id, self.part_index, self.offset, self.emitter_id
        )


class DestroyParticleHook(AnimHook):
    """Removes the emitter tagged ``emitter_id`` and its particles at once."""

    __slots__ = ("emitter_id",)
    hook_type = AnimHookType.DESTROY_PARTICLE

    def __init__(self, emitter_id: int = 0, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.emitter_id = emitter_id

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: DestroyParticleHook::Execute @ 0x00526F10 (acclient.c:342535)"""
        obj.destroy_particle_emitter(self.emitter_id)


class StopParticleHook(DestroyParticleHook):
    """Stops the emitter tagged ``emitter_id`` emitting; its particles live out their lifespans."""

    __slots__ = ()
    hook_type = AnimHookType.STOP_PARTICLE

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: StopParticleHook::Execute @ 0x00526F20 (acclient.c:342541)"""
        obj.stop_particle_emitter(self.emitter_id)


class DefaultScriptHook(AnimHook):
    """Plays the body's default script."""

    __slots__ = ()
    hook_type = AnimHookType.DEFAULT_SCRIPT

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: DefaultScriptHook::Execute @ 0x00526C10 (acclient.c:342329)"""
        obj.play_default_script()


class DefaultScriptPartHook(AnimHook):
    """Plays the default script of the child held at ``part_index``; acphys bodies have no
    children, so the event is recorded.

    Retail: DefaultScriptPartHook::Execute @ 0x00526C00 (acclient.c:342323)
    """

    __slots__ = ("part_index",)
    hook_type = AnimHookType.DEFAULT_SCRIPT_PART

    def __init__(self, part_index: int = 0, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.part_index = part_index


class CallPESHook(AnimHook):
    """Runs physics script ``pes`` after a random pause of up to ``pause`` seconds."""

    __slots__ = ("pause", "pes")
    hook_type = AnimHookType.CALL_PES

    def __init__(self, pes: int = 0, pause: float = 0.0, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.pes, self.pause = pes, f32(pause)

    def execute(self, obj: PhysicsObj) -> None:
        """Retail: CallPESHook::Execute @ 0x00526E20 (acclient.c:342467)"""
        obj.call_pes(self.pes, self.pause)


class TextureVelocityHook(AnimHook):
    """Retail: TextureVelocityHook::Execute @ 0x00526FB0 (acclient.c:342583)"""

    __slots__ = ("u_speed", "v_speed")
    hook_type = AnimHookType.TEXTURE_VELOCITY

    def __init__(
        self, u_speed: float = 0.0, v_speed: float = 0.0, *, direction: int = AnimHookDir.BOTH
    ) -> None:
        super().__init__(direction=direction)
        self.u_speed, self.v_speed, _ = unpack3(pack3(u_speed, v_speed, 0.0))


class TextureVelocityPartHook(TextureVelocityHook):
    """Retail: TextureVelocityPartHook::Execute @ 0x00526F50 (acclient.c:342553)"""

    __slots__ = ("part_index",)
    hook_type = AnimHookType.TEXTURE_VELOCITY_PART

    def __init__(
        self,
        part_index: int = -1,
        u_speed: float = 0.0,
        v_speed: float = 0.0,
        *,
        direction: int = AnimHookDir.BOTH,
    ) -> None:
        super().__init__(u_speed, v_speed, direction=direction)
        self.part_index = part_index


class SetLightHook(AnimHook):
    """Retail: SetLightHook::Execute @ 0x00526FD0 (acclient.c:342589)"""

    __slots__ = ("lights_on",)
    hook_type = AnimHookType.SET_LIGHT

    def __init__(self, lights_on: bool = False, *, direction: int = AnimHookDir.BOTH) -> None:
        super().__init__(direction=direction)
        self.lights_on = bool(lights_on)
