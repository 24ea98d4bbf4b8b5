"""Particles: emitter descriptions, emitters with their closed-form particles, and the body's manager.

A ``ParticleEmitterInfo`` (DAT type 0x2A) describes an effect: how particles
are born (``emitter_type``: ``birthrate`` seconds between births, or metres the
emitter must move), how they move (``particle_type``, a closed-form path in the
particle's age), how long they live, and their scale and translucency ramps.
A ``ParticleEmitter`` plays one info on a body, and the body's
``ParticleManager`` holds its emitters by id and updates them every tick.

Every particle position is written from scratch each update from its age
(``Particle.update``), so a trace of particle positions is a function of time,
the emitter's parent frame and the random draws taken at birth.

acphys has no DAT and no renderer:

- emitter infos are plain objects, found by id through
  :func:`register_emitter_info` (retail ``DBObj::Get``);
- retail's particle ``CPhysicsObj`` (``makeParticleObject``: a child of the
  body holding one ``CPhysicsPart`` per particle) is folded into the emitter:
  ``parts`` hold each live particle's frame, scale and translucency, the
  emitter's position is its parent's frame combined with ``parent_offset``, and
  ``no_draw`` is the particle object's no-draw flag;
- the viewer distance ``CYpt`` the renderer keeps on that object
  (``CPhysicsObj::UpdateViewerDistance``) is measured from ``world.player``,
  acphys's stand-in for ``Render::viewer_pos``; without a player the viewer is
  taken to stand at the emitter (distance 0).
"""

from __future__ import annotations

import enum
import math
import random
import struct
from typing import TYPE_CHECKING

from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.precision import f32, pack3, pack4, unpack3, unpack4

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

_new = object.__new__
#: Two values narrowed to float32 at once (a particle's scale and translucency).
_F2 = struct.Struct("2f")
_pack2, _unpack2 = _F2.pack, _F2.unpack

#: ``CPhysicsPart::GetMaxDegradeDistance`` for a gfx object without degrade info (acclient.c:314377).
DEFAULT_DEGRADE_DISTANCE = 100.0

#: ``ParticleManager::next_emitter_id``'s first value, -65536 as an unsigned id (acclient.c:329310).
FIRST_EMITTER_ID = 0xFFFF0000

#: ``LongNIHash<ParticleEmitter>`` bucket count made by the ParticleManager constructor (acclient.c:329311).
EMITTER_TABLE_SIZE = 2

#: ``RollDice``'s bounds for the EXPLODE angles: the float32 π its ``float`` parameters hold
#: (acclient.c:330779-330780).
_PI32 = f32(3.1415927)


class EmitterType(enum.IntEnum):
    """Retail ``EmitterType`` (acclient.h:7225): what ``birthrate`` measures."""

    UNKNOWN = 0
    BIRTHRATE_PER_SEC = 1
    BIRTHRATE_PER_METER = 2


class ParticleType(enum.IntEnum):
    """Retail ``ParticleType`` (acclient.h:7234): the closed-form path of a particle.

    LV / GV: the velocity ``a`` is local to the emitter's frame at birth, or
    global; GA / LA: likewise the acceleration ``b``; GR / LR: the rotation
    rate ``c``.
    """

    UNKNOWN = 0
    STILL = 1
    LOCAL_VELOCITY = 2
    PARABOLIC_LVGA = 3
    PARABOLIC_LVGAGR = 4
    SWARM = 5
    EXPLODE = 6
    IMPLODE = 7
    PARABOLIC_LVLA = 8
    PARABOLIC_LVLALR = 9
    PARABOLIC_GVGA = 10
    PARABOLIC_GVGAGR = 11
    GLOBAL_VELOCITY = 12


def _roll(dice: random.Random, lower: float, upper: float) -> float:
    """``Random::RollDice(lower, upper)``: uniform in [lower, upper], from the world's ``dice``.

    The bounds are ``float`` parameters: callers pass float32 values. The draw is a double.
    """
    return dice.uniform(lower, upper)


class ParticleEmitterInfo:
    """Retail ``ParticleEmitterInfo`` (acclient.h:52409); defaults are the retail constructor's.

    Fields, with retail names:

    - ``emitter_type`` (EmitterType), ``birthrate``: seconds between births
      (per second) or metres of emitter travel between births (per metre);
    - ``particle_type`` (ParticleType); ``is_parent_local``: particles follow
      the parent's current frame instead of their frame at birth;
    - ``gfxobj_id`` / ``hw_gfxobj_id``: the particle's graphics; an emitter
      with ``hw_gfxobj_id`` 0 cannot start (``SetInfo`` fails);
    - ``max_particles`` alive at once, ``initial_particles`` born at start,
      ``total_particles`` (0: no limit) and ``total_seconds`` (0: no limit)
      after which the emitter stops; with neither limit the particles are
      persistent (their lifetime accumulates);
    - ``lifespan`` ± ``lifespan_rand`` seconds;
    - ``offset_dir``, ``min_offset``, ``max_offset``: the birth offset, random
      in the plane normal to ``offset_dir`` at a random distance in
      [min_offset, max_offset];
    - ``a``, ``b``, ``c`` with magnitudes random in [min_a, max_a] etc.: the
      path vectors of ``particle_type``;
    - ``start_scale``, ``final_scale`` ± ``scale_rand`` (clamped to [0.1, 10]),
      ``start_trans``, ``final_trans`` ± ``trans_rand`` (clamped to [0, 1]);
    - ``sorting_sphere``: set by ``init_end`` (radius only).

    ``degrade_distance`` has no field in retail's info: it is
    ``CPhysicsPart::GetMaxDegradeDistance`` of the particle gfx object (100 m
    without degrade info), which acphys, having no gfx objects, keeps here.

    The ``float`` fields (the offsets, the magnitude bounds, the scale and
    translucency values, the sorting sphere) are narrowed as the DAT holds them;
    ``birthrate``, ``total_seconds``, ``lifespan`` and ``lifespan_rand`` are
    doubles (acclient.h:52409-52441).

    Retail: ParticleEmitterInfo::ParticleEmitterInfo @ 0x00517250 (acclient.c:324406)
    """

    __slots__ = (
        "a",
        "b",
        "birthrate",
        "c",
        "degrade_distance",
        "emitter_type",
        "final_scale",
        "final_trans",
        "gfxobj_id",
        "hw_gfxobj_id",
        "initial_particles",
        "is_parent_local",
        "lifespan",
        "lifespan_rand",
        "max_a",
        "max_b",
        "max_c",
        "max_offset",
        "max_particles",
        "min_a",
        "min_b",
        "min_c",
        "min_offset",
        "offset_dir",
        "particle_type",
        "scale_rand",
        "sorting_sphere_radius",
        "start_scale",
        "start_trans",
        "total_particles",
        "total_seconds",
        "trans_rand",
    )

    def __init__(
        self,
        *,
        emitter_type: EmitterType = EmitterType.UNKNOWN,
        particle_type: ParticleType = ParticleType.UNKNOWN,
        is_parent_local: bool = False,
        gfxobj_id: int = 0,
        hw_gfxobj_id: int = 0,
        birthrate: float = 0.0,
        max_particles: int = 0,
        initial_particles: int = 0,
        total_particles: int = 0,
        total_seconds: float = 0.0,
        lifespan: float = 0.0,
        lifespan_rand: float = 0.0,
        offset_dir: Vector3 | None = None,
        min_offset: float = 0.0,
        max_offset: float = 0.0,
        a: Vector3 | None = None,
        min_a: float = 1.0,
        max_a: float = 1.0,
        b: Vector3 | None = None,
        min_b: float = 1.0,
        max_b: float = 1.0,
        c: Vector3 | None = None,
        min_c: float = 1.0,
        max_c: float = 1.0,
        start_scale: float = 1.0,
        final_scale: float = 1.0,
        scale_rand: float = 0.0,
        start_trans: float = 0.0,
        final_trans: float = 0.0,
        trans_rand: float = 0.0,
        degrade_distance: float = DEFAULT_DEGRADE_DISTANCE,
    ) -> None:
        self.emitter_type = EmitterType(emitter_type)
        self.particle_type = ParticleType(particle_type)
        self.is_parent_local = bool(is_parent_local)
        self.gfxobj_id = gfxobj_id
        self.hw_gfxobj_id = hw_gfxobj_id
        self.birthrate = float(birthrate)
        for name, count in (
            ("max_particles", max_particles),
            ("initial_particles", initial_particles),
            ("total_particles", total_particles),
        ):
            if not isinstance(count, int) or count < 0:
                raise ValueError(f"ParticleEmitterInfo: {name} must be an int >= 0, got {count!r}")
        self.max_particles = max_particles
        self.initial_particles = initial_particles
        self.total_particles = total_particles
        self.total_seconds = float(total_seconds)
        self.lifespan = float(lifespan)
        self.lifespan_rand = float(lifespan_rand)
        self.offset_dir = offset_dir.copy() if offset_dir is not None else Vector3()
        self.min_offset, self.max_offset = f32(min_offset), f32(max_offset)
        self.a = a.copy() if a is not None else Vector3()
        self.b = b.copy() if b is not None else Vector3()
        self.c = c.copy() if c is not None else Vector3()
        self.min_a, self.max_a, self.min_b, self.max_b = unpack4(pack4(min_a, max_a, min_b, max_b))
        self.min_c, self.max_c = f32(min_c), f32(max_c)
        self.start_scale, self.final_scale, self.start_trans, self.final_trans = unpack4(
            pack4(start_scale, final_scale, start_trans, final_trans)
        )
        self.scale_rand, self.trans_rand = f32(scale_rand), f32(trans_rand)
        self.degrade_distance = f32(degrade_distance)
        self.sorting_sphere_radius = 0.0
        self.init_end()

    def init_end(self) -> None:
        """The sorting sphere's radius: the larger of ``max_offset`` and ``max_a × lifespan``
        (a ``float`` local, acclient.c:324489).

        Retail: ParticleEmitterInfo::InitEnd @ 0x005173B0 (acclient.c:324481)
        """
        self.sorting_sphere_radius = max(self.max_offset, f32(self.max_a * self.lifespan))

    def is_persistent(self) -> bool:
        """Neither ``total_particles`` nor ``total_seconds`` limits the emitter (EmitParticle's flag)."""
        return not self.total_particles and self.total_seconds == 0.0

    # The five GetRandom* scalars return doubles; EmitParticle narrows four of them into the
    # ``float`` arguments of Particle::Init.

    def get_random_start_scale(self, dice: random.Random) -> float:
        """Retail: ParticleEmitterInfo::GetRandomStartScale @ 0x005170D0 (acclient.c:324323)"""
        return min(max(_roll(dice, -1.0, 1.0) * self.scale_rand + self.start_scale, 0.1), 10.0)

    def get_random_final_scale(self, dice: random.Random) -> float:
        """Retail: ParticleEmitterInfo::GetRandomFinalScale @ 0x00517120 (acclient.c:324341)"""
        return min(max(_roll(dice, -1.0, 1.0) * self.scale_rand + self.final_scale, 0.1), 10.0)

    def get_random_start_trans(self, dice: random.Random) -> float:
        """Retail: ParticleEmitterInfo::GetRandomStartTrans @ 0x00517170 (acclient.c:324359)"""
        return min(max(_roll(dice, -1.0, 1.0) * self.trans_rand + self.start_trans, 0.0), 1.0)

    def get_random_final_trans(self, dice: random.Random) -> float:
        """Retail: ParticleEmitterInfo::GetRandomFinalTrans @ 0x005171C0 (acclient.c:324377)"""
        return min(max(_roll(dice, -1.0, 1.0) * self.trans_rand + self.final_trans, 0.0), 1.0)

    def get_random_lifespan(self, dice: random.Random) -> float:
        """Retail: ParticleEmitterInfo::GetRandomLifespan @ 0x00517210 (acclient.c:324395)"""
        return max(_roll(dice, -1.0, 1.0) * self.lifespan_rand + self.lifespan, 0.0)

    def get_random_offset(self, dice: random.Random) -> Vector3:
        """A random direction normal to ``offset_dir`` times a distance in [min_offset, max_offset].

        Three rolls (z, y, x in draw order) make a vector; its component along
        ``offset_dir`` is removed; when the rest is shorter than EPSILON the
        offset is zero (and the distance is not rolled).

        The rolls are ``float`` stores; the projection sums its y term first and stays
        double, its y and z products are spilled to ``float`` (acclient.c:324551-324569).

        Retail: ParticleEmitterInfo::GetRandomOffset @ 0x005174A0 (acclient.c:324527)
        """
        d = self.offset_dir
        rz = _roll(dice, -1.0, 1.0)
        ry = _roll(dice, -1.0, 1.0)
        rx = _roll(dice, -1.0, 1.0)
        rx, ry, rz = unpack3(pack3(rx, ry, rz))
        along = ry * d.y + rz * d.z + rx * d.x
        offset = Vector3(rx - along * d.x, ry - f32(along * d.y), rz - f32(along * d.z))
        if offset.normalize_check_small():
            return Vector3()
        return offset * (_roll(dice, 0.0, 1.0) * (self.max_offset - self.min_offset) + self.min_offset)

    def get_random_a(self, dice: random.Random) -> Vector3:
        """``a`` times a magnitude in [min_a, max_a] (a ``float`` spill, acclient.c:324608).

        Retail: ParticleEmitterInfo::GetRandomA @ 0x00517610 (acclient.c:324595)
        """
        return self.a * f32((self.max_a - self.min_a) * _roll(dice, 0.0, 1.0) + self.min_a)

    def get_random_b(self, dice: random.Random) -> Vector3:
        """``b`` times a magnitude in [min_b, max_b] (a ``float`` spill, acclient.c:324630).

        Retail: ParticleEmitterInfo::GetRandomB @ 0x00517670 (acclient.c:324617)
        """
        return self.b * f32((self.max_b - self.min_b) * _roll(dice, 0.0, 1.0) + self.min_b)

    def get_random_c(self, dice: random.Random) -> Vector3:
        """``c`` times a magnitude in [min_c, max_c] (a ``float`` spill, acclient.c:324652).

        Retail: ParticleEmitterInfo::GetRandomC @ 0x005176D0 (acclient.c:324639)
        """
        return self.c * f32((self.max_c - self.min_c) * _roll(dice, 0.0, 1.0) + self.min_c)

    def should_emit_particle(
        self,
        num_particles: int,
        total_emitted: int,
        emitter_offset: Vector3,
        last_emit_time: float,
        now: float,
    ) -> bool:
        """Below both particle limits, and ``birthrate`` exceeded since the last birth.

        Per second: ``now`` (``Timer::cur_time``) − ``last_emit_time`` >
        ``birthrate``. Per metre: the emitter has moved more than ``birthrate``
        since the last birth. The decompilation of the per-metre compare is
        incomplete (only ``emitter_offset->z`` and the FPU flags survive,
        acclient.c:324513-324515); acphys compares the offset's length, the
        reading the per-metre design and the written account (01-physics §6)
        give.

        Retail: ParticleEmitterInfo::ShouldEmitParticle @ 0x00517420 (acclient.c:324499)
        """
        if self.total_particles > 0 and total_emitted >= self.total_particles:
            return False
        if num_particles >= self.max_particles:
            return False
        if self.emitter_type & EmitterType.BIRTHRATE_PER_SEC:
            return now - last_emit_time > self.birthrate
        if self.emitter_type & EmitterType.BIRTHRATE_PER_METER:
            return emitter_offset.length() > self.birthrate
        return False


#: Infos ``ParticleEmitter.set_info_by_id`` can find (retail: the portal DAT, type 0x2A).
_EMITTER_INFOS: dict[int, ParticleEmitterInfo] = {}


def register_emitter_info(emitter_info_id: int, info: ParticleEmitterInfo) -> None:
    """Make ``info`` known under ``emitter_info_id`` (a non-zero DID)."""
    if not isinstance(emitter_info_id, int) or not 0 < emitter_info_id <= 0xFFFFFFFF:
        raise ValueError(f"register_emitter_info: id must be a non-zero 32-bit id, got {emitter_info_id!r}")
    _EMITTER_INFOS[emitter_info_id] = info


def unregister_emitter_info(emitter_info_id: int) -> None:
    """Forget the info registered under ``emitter_info_id`` (if any)."""
    _EMITTER_INFOS.pop(emitter_info_id, None)


def get_emitter_info(emitter_info_id: int) -> ParticleEmitterInfo | None:
    """The info registered under ``emitter_info_id`` (retail ``DBObj::Get``), or None."""
    return _EMITTER_INFOS.get(emitter_info_id)


class ParticlePart:
    """What retail keeps on a particle's ``CPhysicsPart``: its frame, ``gfxobj_scale`` and translucency."""

    __slots__ = ("frame", "gfxobj_scale", "translucency")

    def __init__(self) -> None:
        self.frame = Frame()
        self.gfxobj_scale = Vector3(1.0, 1.0, 1.0)
        self.translucency = 0.0

    def __repr__(self) -> str:
        return (
            f"ParticlePart({self.frame.origin!r}, scale={self.gfxobj_scale.x!r}, trans={self.translucency!r})"
        )


class Particle:
    """Retail ``Particle`` (acclient.h:52452): one particle's birth data and age.

    ``birthtime`` shares storage with retail's ``last_update_time`` (a union):
    persistent particles move it forward every update. ``offset`` is the
    birth offset turned into the world frame; ``a``, ``b``, ``c`` the path
    vectors (global or as given, per type).
    """

    __slots__ = (
        "a",
        "b",
        "birthtime",
        "c",
        "final_scale",
        "final_trans",
        "lifespan",
        "lifetime",
        "offset",
        "start_frame",
        "start_scale",
        "start_trans",
    )

    def __init__(self) -> None:
        self.birthtime = 0.0
        self.lifespan = 0.0
        self.lifetime = 0.0
        self.start_frame = Frame()
        self.offset = Vector3()
        self.a = Vector3()
        self.b = Vector3()
        self.c = Vector3()
        self.start_scale = self.final_scale = 0.0
        self.start_trans = self.final_trans = 0.0

    def init(
        self,
        parent: PhysicsObj,
        part_index: int,
        parent_offset: Frame,
        part: ParticlePart,
        offset: Vector3,
        particle_type: ParticleType,
        is_persistent: bool,
        a: Vector3,
        b: Vector3,
        c: Vector3,
        start_scale: float,
        final_scale: float,
        start_trans: float,
        final_trans: float,
        lifespan: float,
    ) -> None:
        """Birth: remember the parent's frame, turn the offset and (per type) the path vectors global.

        ``start_frame`` is the parent's frame (its part's, for a part index);
        ``offset`` is ``start_frame``'s rotation of ``parent_offset.origin +
        offset``. Local vectors are rotated by ``start_frame``: ``a`` for
        LOCAL_VELOCITY, PARABOLIC_LVGA, PARABOLIC_LVGAGR and SWARM; ``a`` and
        ``b`` for PARABOLIC_LVLA; all three for PARABOLIC_LVLALR. IMPLODE
        scales the offset by ``c`` per axis and keeps the result as ``c``;
        EXPLODE replaces ``c`` by a random unit direction (two angles in
        [-π, π], axes weighted by ``c``; zero when too short). The part takes
        the start scale and translucency, then the first ``update`` places it.

        The four scale and translucency values are ``float`` parameters (retail's
        ``EmitParticle`` spills them, acclient.c:331053-331057), ``lifespan`` a double.
        The offset sum stays double and is rotated summing the z term first, then the y
        term (acclient.c:330699-330709); the first EXPLODE angle is a ``float`` local, the
        second stays double (330779-330780).

        Retail: Particle::Init @ 0x0051C930 (acclient.c:330648)
        """
        start_scale, final_scale, start_trans, final_trans = unpack4(
            pack4(start_scale, final_scale, start_trans, final_trans)
        )
        now = parent.world.physics_time
        self.lifetime = 0.0
        self.birthtime = now
        self.lifespan = lifespan
        if part_index == -1:
            self.start_frame = parent.position.frame.copy()
        else:
            assert parent.part_array is not None
            self.start_frame = parent.part_array.parts[part_index].pos.frame.copy()
        frame = self.start_frame
        m = frame.m
        po = parent_offset.origin
        ox, oy, oz = offset.x + po.x, po.y + offset.y, po.z + offset.z
        self.offset = Vector3(
            oz * m[6] + oy * m[3] + ox * m[0],
            oz * m[7] + oy * m[4] + ox * m[1],
            oz * m[8] + oy * m[5] + ox * m[2],
        )
        pt = particle_type
        if pt in (ParticleType.LOCAL_VELOCITY, ParticleType.PARABOLIC_LVGA, ParticleType.PARABOLIC_LVGAGR):
            self.a = frame.localtoglobalvec(a)
            if pt != ParticleType.LOCAL_VELOCITY:
                self.b = b.copy()
            if pt == ParticleType.PARABOLIC_LVGAGR:
                self.c = c.copy()
        elif pt in (ParticleType.PARABOLIC_LVLA, ParticleType.PARABOLIC_LVLALR):
            self.a = frame.localtoglobalvec(a)
            self.b = frame.localtoglobalvec(b)
            if pt == ParticleType.PARABOLIC_LVLALR:
                self.c = frame.localtoglobalvec(c)
        elif pt in (ParticleType.GLOBAL_VELOCITY, ParticleType.PARABOLIC_GVGA, ParticleType.PARABOLIC_GVGAGR):
            self.a = a.copy()
            if pt != ParticleType.GLOBAL_VELOCITY:
                self.b = b.copy()
            if pt == ParticleType.PARABOLIC_GVGAGR:
                self.c = c.copy()
        elif pt == ParticleType.SWARM:
            self.a = frame.localtoglobalvec(a)
            self.b = b.copy()
            self.c = c.copy()
        elif pt == ParticleType.IMPLODE:
            self.a = a.copy()
            self.b = b.copy()
            self.offset = Vector3(self.offset.x * c.x, self.offset.y * c.y, self.offset.z * c.z)
            self.c = self.offset.copy()
        elif pt == ParticleType.EXPLODE:
            self.a = a.copy()
            self.b = b.copy()
            yaw = f32(_roll(parent.world.dice, -_PI32, _PI32))
            pitch = _roll(parent.world.dice, -_PI32, _PI32)
            direction = Vector3(
                math.cos(yaw) * c.x * math.cos(pitch),
                math.sin(yaw) * c.y * math.cos(pitch),
                math.sin(pitch) * c.z,
            )
            self.c = Vector3() if direction.normalize_check_small() else direction
        elif pt != ParticleType.STILL:
            self.a = a.copy()
            self.b = b.copy()
            self.c = c.copy()
        self.start_scale = start_scale
        self.final_scale = final_scale
        self.final_trans = final_trans
        self.start_trans = start_trans
        part.gfxobj_scale = Vector3(start_scale, start_scale, start_scale)
        part.translucency = start_trans
        self.update(particle_type, is_persistent, part, self.start_frame, now)

    def update(
        self,
        particle_type: ParticleType,
        is_persistent: bool,
        part: ParticlePart,
        parent_frame: Frame,
        now: float,
    ) -> None:
        """Age the particle to ``now`` (the physics timer) and place ``part`` by the closed form of its type.

        With ``t`` the lifetime and ``p`` = ``parent_frame.origin + offset``:
        STILL ``p``; LOCAL/GLOBAL_VELOCITY ``p + t·a``; PARABOLIC_LVGA / LVLA /
        GVGA ``p + t·a + ½·t²·b``; PARABOLIC_*GR / LR the same origin on a copy
        of ``parent_frame`` turned by ``rotate(t·c)`` (the whole frame is the
        part's); SWARM ``p + t·a + (c.x·cos(b.x·t), c.y·sin(b.y·t),
        c.z·cos(b.z·t))``; EXPLODE ``p + t·(t·b + a.x·c) + (0, 0, t·a.z)``;
        IMPLODE ``p + cos(a.x·t)·c + t²·b``. Other types leave the part where it
        is. Scale and translucency ramp linearly from start to final over the
        lifespan and hold at final after it.

        Each closed form is summed in retail's order, with the ``float`` spills the
        decompilation shows (acclient.c:330409-330532): the velocity and parabolic forms
        spill most of their terms (and the parabolic ones a float32 copy of ``t``), the
        SWARM, IMPLODE and EXPLODE forms sum in registers and store once. The scale and
        the translucency are ``float`` stores; the lifetime and ``t / lifespan`` stay double.

        Retail: Particle::Update @ 0x0051C290 (acclient.c:330312)
        """
        elapsed = now - self.birthtime
        if is_persistent:
            self.lifetime = elapsed + self.lifetime
            self.birthtime = now
        else:
            self.lifetime = elapsed
        t = self.lifetime
        p = parent_frame.origin
        o, a, b, c = self.offset, self.a, self.b, self.c
        pt = particle_type
        if pt == ParticleType.STILL:
            part.frame.origin = p + o
        elif pt in (ParticleType.LOCAL_VELOCITY, ParticleType.GLOBAL_VELOCITY):
            tax, tay, bay, baz = unpack4(pack4(t * a.x, t * a.y, o.y + p.y, o.z + p.z))
            origin = part.frame.origin = _new(Vector3)
            origin.x, origin.y, origin.z = unpack3(pack3(p.x + o.x + tax, bay + tay, baz + t * a.z))
        elif pt in (ParticleType.PARABOLIC_LVGA, ParticleType.PARABOLIC_LVLA, ParticleType.PARABOLIC_GVGA):
            # b·0.5 of a float32 is a float32: its spills change nothing.
            hbx, hby, hbz = b.x * 0.5, b.y * 0.5, b.z * 0.5
            t32, qy, qz, tay = unpack4(pack4(t, hby * t, hbz * t, t * a.y))
            taz, bay, baz = unpack3(pack3(t * a.z, o.y + p.y, o.z + p.z))
            sx, sy, sz, wy = unpack4(pack4(hbx * t * t32, qy * t32, qz * t32, bay + tay))
            wz = f32(f32(baz + taz) + sz)
            origin = part.frame.origin = _new(Vector3)
            origin.x, origin.y, origin.z = unpack3(pack3(t * a.x + (o.x + p.x) + sx, wy + sy, wz))
        elif pt in (
            ParticleType.PARABOLIC_LVGAGR,
            ParticleType.PARABOLIC_LVLALR,
            ParticleType.PARABOLIC_GVGAGR,
        ):
            frame = parent_frame.copy()
            hbx, hby, hbz = b.x * 0.5, b.y * 0.5, b.z * 0.5
            t32, qy, qz, tay = unpack4(pack4(t, hby * t, hbz * t, t * a.y))
            taz = f32(t * a.z)
            sz, ry, rz, wx = unpack4(pack4(qz * t32, tay + o.y, taz + o.z, t * a.x + o.x + hbx * t * t32))
            fo = frame.origin
            fo.x, fo.y, fo.z = unpack3(pack3(fo.x + wx, fo.y + ry + qy * t32, fo.z + rz + sz))
            frame.rotate(c * t)
            part.frame = frame
        elif pt == ParticleType.SWARM:
            origin = part.frame.origin = _new(Vector3)
            origin.x, origin.y, origin.z = unpack3(
                pack3(
                    math.cos(b.x * t) * c.x + t * a.x + o.x + p.x,
                    math.sin(b.y * t) * c.y + t * a.y + o.y + p.y,
                    math.cos(b.z * t) * c.z + t * a.z + o.z + p.z,
                )
            )
        elif pt == ParticleType.IMPLODE:
            k = math.cos(a.x * t)
            tt = t * t
            origin = part.frame.origin = _new(Vector3)
            origin.x, origin.y, origin.z = unpack3(
                pack3(
                    k * c.x + tt * b.x + o.x + p.x,
                    k * c.y + tt * b.y + o.y + p.y,
                    k * c.z + tt * b.z + o.z + p.z,
                )
            )
        elif pt == ParticleType.EXPLODE:
            origin = part.frame.origin = _new(Vector3)
            origin.x, origin.y, origin.z = unpack3(
                pack3(
                    (t * b.x + c.x * a.x) * t + o.x + p.x,
                    (t * b.y + c.y * a.x) * t + o.y + p.y,
                    (t * b.z + c.z * a.x + a.z) * t + o.z + p.z,
                )
            )
        fraction = t / self.lifespan if t < self.lifespan else 1.0
        scale, part.translucency = _unpack2(
            _pack2(
                (self.final_scale - self.start_scale) * fraction + self.start_scale,
                (self.final_trans - self.start_trans) * fraction + self.start_trans,
            )
        )
        gfxobj_scale = part.gfxobj_scale = _new(Vector3)
        gfxobj_scale.x = gfxobj_scale.y = gfxobj_scale.z = scale


class ParticleEmitter:
    """Retail ``ParticleEmitter`` (acclient.h:52469): one effect playing on ``parent``.

    ``particles`` and ``part_storage`` have ``max_particles`` slots; ``parts[i]``
    is ``part_storage[i]`` while slot ``i``'s particle lives and None
    otherwise. Times ``last_update_time`` / ``last_emit_time`` start at the
    world clock (``Timer::cur_time``) and then follow the physics timer.

    Retail: ParticleEmitter::ParticleEmitter @ 0x0051C7E0 (acclient.c:330553)
    """

    __slots__ = (
        "creation_time",
        "degrade_distance",
        "degraded_out",
        "id",
        "info",
        "last_emit_offset",
        "last_emit_time",
        "last_update_time",
        "no_draw",
        "num_particles",
        "parent",
        "parent_offset",
        "part_index",
        "part_storage",
        "particles",
        "parts",
        "stopped",
        "total_emitted",
    )

    def __init__(self, parent: PhysicsObj) -> None:
        self.parent = parent
        self.part_index = -1
        self.id = 0
        self.parent_offset = Frame()
        self.info: ParticleEmitterInfo | None = None
        self.particles: list[Particle] = []
        self.part_storage: list[ParticlePart] = []
        self.parts: list[ParticlePart | None] = []
        self.degraded_out = False
        self.degrade_distance = 0.0
        self.creation_time = 0.0
        self.num_particles = 0
        self.total_emitted = 0
        self.stopped = False
        self.no_draw = False
        self.last_emit_offset = Vector3()
        self.last_update_time = parent.world.cur_time
        self.last_emit_time = parent.world.cur_time

    def __repr__(self) -> str:
        return f"ParticleEmitter(id={self.id:#x}, live={self.num_particles}, stopped={self.stopped})"

    # -- the particle object (retail makeParticleObject, parented to the body) ----------------

    def get_frame(self) -> Frame:
        """The particle object's frame: the parent's (or its part's) frame combined with ``parent_offset``.

        Retail keeps this on the child ``CPhysicsObj`` that ``SetParenting``
        attaches to the body; acphys computes it when asked.
        """
        frame = Frame()
        frame.combine(self._parent_frame(), self.parent_offset)
        return frame

    def _parent_frame(self) -> Frame:
        if self.part_index == -1:
            return self.parent.position.frame
        assert self.parent.part_array is not None
        return self.parent.part_array.parts[self.part_index].pos.frame

    def viewer_distance(self) -> float:
        """``CYpt`` of the particle object: its distance from the viewer (``world.player``; 0 without one).

        A ``float`` field, the squares summed z first (acclient.c:317936-317939).

        Retail: CPhysicsObj::UpdateViewerDistance @ 0x00510B30 (acclient.c:317912)
        """
        viewer = self.parent.world.player
        if viewer is None:
            return 0.0
        here = Position(self.parent.position.objcell_id, self.get_frame())
        v = viewer.position.get_offset(here)
        return f32(math.sqrt(v.z * v.z + v.x * v.x + v.y * v.y))

    def should_draw_particles(self) -> bool:
        """The particle object is within ``degrade_distance`` of the viewer and in a cell.

        Retail: CPhysicsObj::ShouldDrawParticles @ 0x0050FE60 (acclient.c:317183)
        """
        if self.viewer_distance() > self.degrade_distance:
            return False
        return self.parent.cell is not None

    # -- set-up ---------------------------------------------------------------------------------

    def set_info(self, info: ParticleEmitterInfo) -> bool:
        """Take ``info``: one part and one particle slot per ``max_particles``; False without graphics.

        Retail: ParticleEmitter::SetInfo @ 0x0051CE90 (acclient.c:330908)
        """
        self.destroy()
        self.info = info
        if not info.hw_gfxobj_id:
            self.destroy()
            return False
        # The fresh particle object is not parented yet: its origin is zero (acclient.c:330927-330929).
        self.last_emit_offset = Vector3()
        self.part_storage = [ParticlePart() for _ in range(info.max_particles)]
        self.parts = [None] * info.max_particles
        self.particles = [Particle() for _ in range(info.max_particles)]
        self.degrade_distance = info.degrade_distance
        return True

    def set_info_by_id(self, emitter_info_id: int) -> bool:
        """Retail: ParticleEmitter::SetInfo @ 0x0051D3C0 (acclient.c:331247)"""
        info = get_emitter_info(emitter_info_id) if emitter_info_id else None
        return info is not None and self.set_info(info)

    def set_parenting(self, part_index: int, frame: Frame) -> bool:
        """Attach to the parent at ``part_index`` (-1: the body itself) and ``frame``.

        Retail ``CPhysicsObj::set_parent`` refuses a part index the parent does
        not have; so does acphys.

        Retail: ParticleEmitter::SetParenting @ 0x0051C190 (acclient.c:330251)
        """
        parts = self.parent.part_array.parts if self.parent.part_array is not None else []
        if part_index != -1 and not 0 <= part_index < len(parts):
            return False
        self.part_index = part_index
        self.parent_offset = frame.copy()
        return True

    def init_end(self) -> bool:
        """Note the creation time (world clock) and emit ``initial_particles`` at once.

        Retail: ParticleEmitter::InitEnd @ 0x0051D400 (acclient.c:331264)
        """
        assert self.info is not None
        self.creation_time = self.parent.world.cur_time
        for _ in range(self.info.initial_particles):
            self.emit_particle()
        return True

    def destroy(self) -> None:
        """Drop every particle and the info.

        Retail: ParticleEmitter::Destroy @ 0x0051CDB0 (acclient.c:330846)
        """
        self.part_storage = []
        self.parts = []
        self.particles = []
        self.info = None
        self.num_particles = 0
        self.last_update_time = self.parent.world.physics_time

    # -- births and deaths ----------------------------------------------------------------------

    def emit_particle(self) -> None:
        """Start a particle in the first free slot (none when all are in use).

        The random draws are taken in retail's order: lifespan, final and
        start translucency, final and start scale, ``c``, ``b``, ``a``, offset.

        Retail: ParticleEmitter::EmitParticle @ 0x0051D010 (acclient.c:331002)
        """
        info = self.info
        assert info is not None
        index = next((i for i, part in enumerate(self.parts) if part is None), len(self.parts))
        if index == len(self.parts):
            return
        part = self.part_storage[index]
        self.parts[index] = part
        dice = self.parent.world.dice
        lifespan = info.get_random_lifespan(dice)
        final_trans = info.get_random_final_trans(dice)
        start_trans = info.get_random_start_trans(dice)
        final_scale = info.get_random_final_scale(dice)
        start_scale = info.get_random_start_scale(dice)
        c = info.get_random_c(dice)
        b = info.get_random_b(dice)
        a = info.get_random_a(dice)
        offset = info.get_random_offset(dice)
        self.particles[index].init(
            self.parent,
            self.part_index,
            self.parent_offset,
            part,
            offset,
            info.particle_type,
            info.is_persistent(),
            a,
            b,
            c,
            start_scale,
            final_scale,
            start_trans,
            final_trans,
            lifespan,
        )
        self.record_particle_emission()

    def record_particle_emission(self) -> None:
        """Count a birth and note where (the particle object's origin) and when (physics timer).

        Retail: ParticleEmitter::RecordParticleEmission @ 0x0051C870 (acclient.c:330592)
        """
        self.num_particles += 1
        self.total_emitted += 1
        self.last_emit_offset = self.get_frame().origin
        self.last_emit_time = self.parent.world.physics_time

    def should_emit_particle(self) -> bool:
        """Ask the info, with the emitter's travel since the last birth for per-metre emitters.

        Retail: ParticleEmitter::ShouldEmitParticle @ 0x0051C8B0 (acclient.c:330612)
        """
        info = self.info
        assert info is not None
        moved = Vector3()
        if info.emitter_type & EmitterType.BIRTHRATE_PER_METER:
            moved = self.get_frame().origin - self.last_emit_offset
        return info.should_emit_particle(
            self.num_particles, self.total_emitted, moved, self.last_emit_time, self.parent.world.cur_time
        )

    def kill_particle(self, index: int) -> bool:
        """Free slot ``index`` once its particle has reached its lifespan.

        Retail: ParticleEmitter::KillParticle @ 0x0051C1E0 (acclient.c:330273)
        """
        particle = self.particles[index]
        if particle.lifetime < particle.lifespan:
            return False
        self.parts[index] = None
        self.num_particles -= 1
        return True

    def stop_emitter(self) -> bool:
        """Stop after ``total_seconds`` (from creation) or ``total_particles`` births.

        Retail: ParticleEmitter::StopEmitter @ 0x0051C230 (acclient.c:330294)
        """
        info = self.info
        assert info is not None
        if not self.stopped:
            if (
                info.total_seconds > 0.0
                and self.creation_time + info.total_seconds < self.parent.world.physics_time
            ):
                self.stopped = True
            if info.total_particles and self.total_emitted >= info.total_particles:
                self.stopped = True
        return self.stopped

    # -- the tick -------------------------------------------------------------------------------

    def update_particles(self) -> bool:
        """Move, kill and emit for one tick; False once the emitter is finished.

        Drawn (within degrade distance): every live particle is updated against
        its birth frame (the parent's current frame when ``is_parent_local``)
        and killed at its lifespan, then a running emitter emits if due and
        checks its stop limits; a stopped one lives while particles do.

        Degraded (beyond it): the particle object is hidden and nothing moves.
        A limited emitter ages and kills its particles and counts births it
        does not make (``RecordParticleEmission``); an unlimited one sets every
        slot's birth time to now, freezing its persistent particles.

        Retail: ParticleEmitter::UpdateParticles @ 0x0051D180 (acclient.c:331096)
        """
        info = self.info
        if info is None:
            return False
        now = self.parent.world.physics_time
        if not self.should_draw_particles():
            if not self.degraded_out:
                self.no_draw = True
                self.degraded_out = True
            self.last_update_time = now
            if info.is_persistent():
                for particle in self.particles:
                    particle.birthtime = now
                return True
            for index, part in enumerate(self.parts):
                if part is not None:
                    particle = self.particles[index]
                    particle.lifetime = now - particle.birthtime
                    self.kill_particle(index)
            if self.stopped:
                return self.num_particles != 0
            if self.should_emit_particle():
                self.record_particle_emission()
            self.stop_emitter()
            return True
        if self.degraded_out:
            self.degraded_out = False
            self.no_draw = False
        persistent = info.is_persistent()
        for index, part in enumerate(self.parts):
            if part is None:
                continue
            particle = self.particles[index]
            frame = self._parent_frame() if info.is_parent_local else particle.start_frame
            particle.update(info.particle_type, persistent, part, frame, now)
            self.kill_particle(index)
        alive = True
        if self.stopped:
            alive = self.num_particles != 0
        else:
            if self.should_emit_particle():
                self.emit_particle()
            self.stop_emitter()
        self.last_update_time = now
        return alive

    def live_particles(self) -> list[tuple[int, ParticlePart]]:
        """The live slots and their parts, for traces (acphys helper)."""
        return [(index, part) for index, part in enumerate(self.parts) if part is not None]


class ParticleManager:
    """Retail ``ParticleManager``: the body's emitters by id.

    The table is retail's two-bucket ``LongNIHash``: an id goes to bucket
    ``(id ^ id >> 16) % 2``, newest first, and updates walk bucket 0 then
    bucket 1. Ids handed out start at 0xFFFF0000.

    Retail: ParticleManager::ParticleManager @ 0x0051B5D0 (acclient.c:329303)
    """

    __slots__ = ("next_emitter_id", "particle_table")

    def __init__(self) -> None:
        self.next_emitter_id = FIRST_EMITTER_ID
        self.particle_table: list[list[ParticleEmitter]] = [[] for _ in range(EMITTER_TABLE_SIZE)]

    @staticmethod
    def _bucket(emitter_id: int) -> int:
        return (emitter_id ^ (emitter_id >> 16)) % EMITTER_TABLE_SIZE

    def get_emitter(self, emitter_id: int) -> ParticleEmitter | None:
        """The emitter with ``emitter_id``, or None."""
        for emitter in self.particle_table[self._bucket(emitter_id)]:
            if emitter.id == emitter_id:
                return emitter
        return None

    def emitters(self) -> list[ParticleEmitter]:
        """Every emitter in retail's walk order."""
        return [emitter for bucket in self.particle_table for emitter in bucket]

    def _remove(self, emitter_id: int) -> ParticleEmitter | None:
        bucket = self.particle_table[self._bucket(emitter_id)]
        for index, emitter in enumerate(bucket):
            if emitter.id == emitter_id:
                del bucket[index]
                return emitter
        return None

    def get_num_emitters(self) -> int:
        """Retail: ParticleManager::GetNumEmitters @ 0x0051B580 (acclient.c:329273)"""
        return sum(len(bucket) for bucket in self.particle_table)

    def create_particle_emitter(
        self, physobj: PhysicsObj, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int:
        """Start emitter ``emitter_info_id`` on ``physobj``; its id, or 0 when it cannot start.

        A non-zero ``emitter_id`` first destroys the emitter holding that id
        and is then the new one's id; 0 takes the next free id.

        Retail: ParticleManager::CreateParticleEmitter @ 0x0051B6C0 (acclient.c:329374)
        """
        if emitter_id:
            old = self._remove(emitter_id)
            if old is not None:
                old.destroy()
        emitter = ParticleEmitter(physobj)
        if not (emitter.set_info_by_id(emitter_info_id) and emitter.set_parenting(part_index, offset)):
            emitter.destroy()
            return 0
        emitter.init_end()
        if not emitter_id:
            emitter_id = self.next_emitter_id
            self.next_emitter_id = (self.next_emitter_id + 1) & 0xFFFFFFFF
        emitter.id = emitter_id
        self.particle_table[self._bucket(emitter_id)].insert(0, emitter)
        return emitter_id

    def create_blocking_particle_emitter(
        self, physobj: PhysicsObj, emitter_info_id: int, part_index: int, offset: Frame, emitter_id: int
    ) -> int:
        """As ``create_particle_emitter``, but 0 (and nothing done) while ``emitter_id`` is in use.

        Retail: ParticleManager::CreateBlockingParticleEmitter @ 0x0051B8A0 (acclient.c:329527)
        """
        if emitter_id and self.get_emitter(emitter_id) is not None:
            return 0
        return self.create_particle_emitter(physobj, emitter_info_id, part_index, offset, emitter_id)

    def destroy_particle_emitter(self, emitter_id: int) -> bool:
        """Remove emitter ``emitter_id`` and its particles at once; False when there is none.

        Retail: ParticleManager::DestroyParticleEmitter @ 0x0051B770 (acclient.c:329415)
        """
        if not emitter_id:
            return False
        emitter = self._remove(emitter_id)
        if emitter is None:
            return False
        emitter.destroy()
        return True

    def stop_particle_emitter(self, emitter_id: int) -> bool:
        """Stop emitter ``emitter_id`` emitting; its particles live out their lifespans.

        Retail: ParticleManager::StopParticleEmitter @ 0x0051B7B0 (acclient.c:329441)
        """
        emitter = self.get_emitter(emitter_id) if emitter_id else None
        if emitter is None:
            return False
        emitter.stopped = True
        return True

    def update_particles(self) -> None:
        """Update every emitter, dropping the ones that report themselves finished.

        Retail: ParticleManager::UpdateParticles @ 0x0051B800 (acclient.c:329481)
        """
        for emitter in self.emitters():
            if not emitter.update_particles():
                self._remove(emitter.id)
                emitter.destroy()
