"""The weenie side of a body: what the motion interpreter asks about skills, burden and kind.

In the retail client ``CMotionInterp`` holds a ``CWeenieObject`` and calls a
handful of its virtuals: ``IsThePlayer``, ``IsCreature``, ``InqRunRate``,
``InqJumpVelocity``, ``CanJump`` and ``JumpStaminaCost``. ``ACCWeenieObject``
answers the last four only for the player's own character (the only object
whose qualities the client holds) and asks ``CACQualities``, which turns the
effective Run / Jump skill and the burden into rates through
``MovementSystem`` and ``EncumbranceSystem``. Every other object answers
"unknown", and the interpreter falls back to its own defaults.

:class:`Weenie` takes the inputs the client reads from its qualities: the
effective skills (base, ranks, buffs and augmentations already added), the
load (burden over capacity; a ``float`` local of the qualities code, kept as a
float32), whether stamina is above zero and whether a PK attack happened in the
last 20 seconds.

The collision code (``CPhysicsObj::FindObjCollisions``, ``OBJECTINFO::init``) asks four more
virtuals, each one bit of the object's public description (``pwd._bitfield``):
``IsPlayer`` (slot 4, bit 0x8), ``IsPK`` (slot 8, bit 0x20), ``IsPKLite`` (slot 9, bit
0x2000000) and ``IsImpenetrable`` (slot 10, bit 0x200000). The slots are pinned by
``OBJECTINFO::init`` (acclient.c:314132-314143), which turns them into the ``OBJECTINFO`` bits
named for them (IS_IMPENETRABLE 0x80, IS_PLAYER 0x100, IS_PK 0x800, IS_PKLITE 0x1000).
``IsCreature`` is slot 11 and ``IsThePlayer`` slot 5.
"""

from __future__ import annotations

import math

from acphys.precision import f32, pack3, unpack3

#: ``GetJumpHeight`` constants as the binary holds them (float32).
_JUMP_SKILL_SPAN = f32(22.200001)
_JUMP_HEIGHT_BASE = f32(0.050000001)
_JUMP_HEIGHT_MIN = f32(0.34999999)
#: ``InqJumpVelocity``: v_z = sqrt(height * 19.6), i.e. sqrt(2 g h) with g = 9.8.
_TWO_G = 19.6


def load_mod(load: float) -> float:
    """The burden factor on run and jump: 1 under full load, falling to 0 at twice the capacity.

    Retail: EncumbranceSystem::LoadMod @ 0x004FCC70 (acclient.c:296776)
    """
    if load < 1.0:
        return 1.0
    if load < 2.0:
        return 2.0 - load
    return 0.0


def encumbrance_capacity(strength: int, encumbrance_augmentations: int = 0) -> int:
    """Burden units a character of ``strength`` carries at load 1.0.

    Retail: EncumbranceSystem::EncumbranceCapacity @ 0x004FCC00 (acclient.c:296730)
    """
    if strength <= 0:
        return 0
    bonus = 30 * encumbrance_augmentations
    if bonus < 0:
        return 150 * strength
    return 150 * strength + strength * min(bonus, 150)


def encumbrance_load(capacity: int, burden: int) -> float:
    """The load fraction ``burden / capacity`` (3.0 with no capacity, 0 for a negative burden).

    Retail: EncumbranceSystem::Load @ 0x004FCC40 (acclient.c:296757)
    """
    if capacity <= 0:
        return 3.0
    if burden < 0:
        return 0.0
    return burden / capacity


def get_run_rate(load: float, run_skill: int, scaling: float = 1.0) -> float:
    """The run rate (animation speed multiplier) for an effective Run skill.

    Exactly 800 skill gives 18/4 = 4.5; every other value follows the curve,
    which tends to 15/4 (retail tests equality, not ``>=``). ``load`` is a ``float`` parameter.

    Retail: MovementSystem::GetRunRate @ 0x006B0950 (acclient.c:713789)
    """
    load = f32(load)
    skill = float(run_skill)
    if skill == 800.0:
        return 18.0 / 4.0
    return (load_mod(load) * (skill / (skill + 200.0) * 11.0) + 4.0) / scaling / 4.0


def get_jump_height(load: float, jump_skill: int, power: float, scaling: float = 1.0) -> float:
    """Jump height in metres for an effective Jump skill and a charge ``power`` (clamped to [0, 1]).

    Never below 0.35 m. ``load`` and ``power`` are ``float`` parameters, and so is the skill
    once converted (``_powera``, acclient.c:713822; exact for any real skill); the height stays double.

    Retail: MovementSystem::GetJumpHeight @ 0x006B09B0 (acclient.c:713805)
    """
    load, power, _ = unpack3(pack3(load, power, 0.0))
    power = min(max(power, 0.0), 1.0)
    skill = float(jump_skill)
    height = (
        load_mod(load) * (skill / (skill + 1300.0) * _JUMP_SKILL_SPAN + _JUMP_HEIGHT_BASE) * power / scaling
    )
    return max(height, _JUMP_HEIGHT_MIN)


def jump_stamina_cost(power: float, load: float, pk: bool) -> int:
    """Stamina a jump of ``power`` costs: ``(power + 1) * 100`` right after PK combat, else a burden curve.

    ``power`` and ``load`` are ``float`` parameters.

    Retail: MovementSystem::JumpStaminaCost @ 0x006B0A40 (acclient.c:713829)
    """
    power, load, _ = unpack3(pack3(power, load, 0.0))
    if pk:
        return int((power + 1.0) * 100.0)
    return math.ceil((load + 0.5) * power * 8.0 + 2.0)


class Weenie:
    """What the motion interpreter asks of a body's weenie object (retail ``ACCWeenieObject``).

    ``the_player`` marks the client's own character: only it has qualities,
    so only it answers the run-rate, jump and stamina questions. Another
    creature (``the_player=False``) answers none of them; the interpreter
    then uses ``my_run_rate``, a jump velocity of 0 and refuses to charge a jump.

    ``player``, ``pk``, ``pk_lite`` and ``impenetrable`` are the description bits the collision code
    reads; they default to clear, as in an empty ``PublicWeenieDesc``.
    """

    __slots__ = (
        "creature",
        "impenetrable",
        "jump_skill",
        "load",
        "pk",
        "pk_lite",
        "player",
        "recent_pk",
        "run_skill",
        "stamina",
        "the_player",
    )

    def __init__(
        self,
        *,
        creature: bool = True,
        the_player: bool = True,
        run_skill: int = 0,
        jump_skill: int = 0,
        load: float = 0.0,
        stamina: int = 1,
        recent_pk: bool = False,
        player: bool = False,
        pk: bool = False,
        pk_lite: bool = False,
        impenetrable: bool = False,
    ) -> None:
        for name, skill in (("run_skill", run_skill), ("jump_skill", jump_skill)):
            if not isinstance(skill, int) or skill < 0:
                raise ValueError(f"Weenie {name} must be a non-negative integer, got {skill!r}")
        if not math.isfinite(load) or load < 0.0:
            raise ValueError(f"Weenie load must be a finite fraction >= 0, got {load!r}")
        if not isinstance(stamina, int) or stamina < 0:
            raise ValueError(f"Weenie stamina must be a non-negative integer, got {stamina!r}")
        self.creature = creature
        self.the_player = the_player
        self.run_skill = run_skill
        self.jump_skill = jump_skill
        self.load = f32(load)
        self.stamina = stamina
        #: A PK or PK-lite whose last PK attack was under 20 s ago (prices jumps by power).
        self.recent_pk = recent_pk
        self.player = player
        self.pk = pk
        self.pk_lite = pk_lite
        self.impenetrable = impenetrable

    def is_the_player(self) -> bool:
        """Retail: ACCWeenieObject::IsThePlayer @ 0x0058C3D0 (acclient.c:436872)"""
        return self.the_player

    def is_creature(self) -> bool:
        """Retail: ACCWeenieObject::IsCreature @ 0x0058C3F0 (acclient.c:436878)"""
        return self.creature

    def is_player(self) -> bool:
        """Any player character (not only the client's own: that is ``is_the_player``).

        Retail: ACCWeenieObject::IsPlayer @ 0x0058C890 (acclient.c:437198)
        """
        return self.player

    def is_pk(self) -> bool:
        """Retail: ACCWeenieObject::IsPK @ 0x0058C8B0 (acclient.c:437210)"""
        return self.pk

    def is_pk_lite(self) -> bool:
        """Retail: ACCWeenieObject::IsPKLite @ 0x0058C8A0 (acclient.c:437204)"""
        return self.pk_lite

    def is_impenetrable(self) -> bool:
        """Retail: ACCWeenieObject::IsImpenetrable @ 0x0058C8C0 (acclient.c:437216)"""
        return self.impenetrable

    def inq_run_rate(self) -> float | None:
        """The run rate from the Run skill and load (skill 0 when out of stamina); None if not the player.

        The rate is stored into a float, hence the float32 rounding.

        The qualities side is CACQualities::InqRunRate @ 0x00592800 (acclient.c:443695).

        Retail: ACCWeenieObject::InqRunRate @ 0x0058C560 (acclient.c:436990)
        """
        if not self.the_player:
            return None
        skill = self.run_skill if self.stamina else 0
        return f32(get_run_rate(self.load, skill, 1.0))

    def inq_jump_velocity(self, extent: float) -> float | None:
        """Upward launch speed ``sqrt(19.6 * height)`` for a jump of ``extent``; None if not the player.

        The qualities side is CACQualities::InqJumpVelocity @ 0x00592980 (acclient.c:443772).

        Retail: ACCWeenieObject::InqJumpVelocity @ 0x0058C520 (acclient.c:436975)
        """
        if not self.the_player:
            return None
        skill = self.jump_skill if self.stamina else 0
        return f32(math.sqrt(get_jump_height(self.load, skill, extent, 1.0) * _TWO_G))

    def can_jump(self, extent: float) -> bool:
        """The player can jump under twice their capacity; nobody else can.

        The qualities side is CACQualities::CanJump @ 0x00591B50 (acclient.c:442877).

        Retail: ACCWeenieObject::CanJump @ 0x0058C400 (acclient.c:436884)
        """
        return self.the_player and self.load < 2.0

    def jump_stamina_cost(self, extent: float) -> int | None:
        """Stamina a jump of ``extent`` costs the player; None for anyone else.

        The qualities side is CACQualities::JumpStaminaCost @ 0x00591B90 (acclient.c:442886).

        Retail: ACCWeenieObject::JumpStaminaCost @ 0x0058C440 (acclient.c:436899)
        """
        if not self.the_player:
            return None
        return jump_stamina_cost(extent, self.load, self.recent_pk)
