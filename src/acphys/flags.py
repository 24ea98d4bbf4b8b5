"""Retail state bits as ``IntFlag``s, with the values of ``acclient.h`` (11.4186).

Scenario files and traces name flags in lower case without their retail
suffix (``GRAVITY_PS`` → ``gravity``, ``ON_WALKABLE_TS`` → ``on_walkable``);
:func:`flag_names` and :func:`parse_flag_names` convert both ways.
"""

from __future__ import annotations

import enum
import types
from collections.abc import Iterable
from typing import TypeVar


class PhysicsState(enum.IntFlag):
    """``enum PhysicsState`` (acclient.h:2815): ``CPhysicsObj::state``."""

    STATIC = 0x1
    UNUSED1 = 0x2
    ETHEREAL = 0x4
    REPORT_COLLISIONS = 0x8
    IGNORE_COLLISIONS = 0x10
    NODRAW = 0x20
    MISSILE = 0x40
    PUSHABLE = 0x80
    ALIGN_PATH = 0x100  # ALIGNPATH_PS
    PATH_CLIPPED = 0x200  # PATHCLIPPED_PS
    GRAVITY = 0x400
    LIGHTING_ON = 0x800
    PARTICLE_EMITTER = 0x1000
    UNUSED2 = 0x2000
    HIDDEN = 0x4000
    SCRIPTED_COLLISION = 0x8000
    HAS_PHYSICS_BSP = 0x10000
    INELASTIC = 0x20000
    HAS_DEFAULT_ANIM = 0x40000
    HAS_DEFAULT_SCRIPT = 0x80000
    CLOAKED = 0x100000
    REPORT_COLLISIONS_AS_ENVIRONMENT = 0x200000
    EDGE_SLIDE = 0x400000
    SLEDDING = 0x800000
    FROZEN = 0x1000000


#: The state ``CPhysicsObj::CPhysicsObj`` starts with: 4197384 = 0x400C08 (acclient.c:319489).
DEFAULT_PHYSICS_STATE = (
    PhysicsState.EDGE_SLIDE | PhysicsState.LIGHTING_ON | PhysicsState.GRAVITY | PhysicsState.REPORT_COLLISIONS
)


class TransientState(enum.IntFlag):
    """``enum TransientState`` (acclient.h:3688): ``CPhysicsObj::transient_state``."""

    CONTACT = 0x1
    ON_WALKABLE = 0x2
    SLIDING = 0x4
    WATER_CONTACT = 0x8
    STATIONARY_FALL = 0x10
    STATIONARY_STOP = 0x20
    STATIONARY_STUCK = 0x40
    ACTIVE = 0x80
    CHECK_ETHEREAL = 0x100


#: The three stationary bits, cleared together by ``handle_all_collisions`` (mask 0xFFFFFF8F).
STATIONARY_MASK = (
    TransientState.STATIONARY_FALL | TransientState.STATIONARY_STOP | TransientState.STATIONARY_STUCK
)


class ObjectInfoState(enum.IntFlag):
    """``enum ObjectInfoEnum`` (acclient.h:6180): ``OBJECTINFO::state`` for a transition."""

    DEFAULT = 0x0
    CONTACT = 0x1
    ON_WALKABLE = 0x2
    IS_VIEWER = 0x4
    PATH_CLIPPED = 0x8
    FREE_ROTATE = 0x10
    PERFECT_CLIP = 0x40
    IS_IMPENETRABLE = 0x80
    IS_PLAYER = 0x100
    EDGE_SLIDE = 0x200
    IGNORE_CREATURES = 0x400
    IS_PK = 0x800
    IS_PKLITE = 0x1000


class TransitionState(enum.IntEnum):
    """``enum TransitionState`` (acclient.h:6100): the result of one sweep step."""

    INVALID = 0x0
    OK = 0x1
    COLLIDED = 0x2
    ADJUSTED = 0x3
    SLID = 0x4


def _use_int_operators(*classes: type[enum.IntFlag]) -> None:
    """Give ``classes`` ``int``'s bit operators: fast, with plain-int results.

    The tick tests and combines state bits many times a step, and ``IntFlag``'s
    own operators build flag members in Python on every ``&``. Members keep
    their names (:func:`flag_names` reads them); bit operations give plain
    integers of the same value.
    """
    for cls in classes:
        for op in ("__and__", "__rand__", "__or__", "__ror__", "__xor__", "__rxor__", "__invert__"):
            setattr(cls, op, getattr(int, op))


_use_int_operators(PhysicsState, TransientState, ObjectInfoState)


def member_namespace(cls: type[enum.Enum]) -> types.SimpleNamespace:
    """``cls``'s members as the attributes of a plain namespace (the member objects themselves).

    In Python 3.11 every ``Flag.MEMBER`` read through the class runs the
    metaclass's ``__getattr__`` hook: about 100 ns, seven times a plain
    attribute. The tick reads members hundreds of times a step, so the hot
    modules bind their short aliases (``TS``, ``PS``, ``OI``) to these
    namespaces; anything that needs the class itself uses its full name.
    """
    return types.SimpleNamespace(**cls.__members__)


def flag_names(value: int, cls: type[enum.IntFlag] | None = None) -> list[str]:
    """The lower-case names of the bits of ``cls`` set in ``value``, lowest bit first.

    ``cls`` defaults to the type of ``value`` (pass it for a plain ``int``).
    """
    flags = type(value) if cls is None else cls
    if not issubclass(flags, enum.Flag):
        raise TypeError(f"flag_names needs the flag class for a plain {type(value).__name__}")
    return [member.name.lower() for member in flags if member.value and value & member.value]


F = TypeVar("F", bound=enum.IntFlag)


def parse_flag_names(cls: type[F], names: Iterable[str]) -> F:
    """Combine lower-case flag names into a value of ``cls``.

    Raises ``KeyError`` carrying the first unknown name.
    """
    by_name = {member.name.lower(): member for member in cls if member.name}
    result = cls(0)
    for name in names:
        if name not in by_name:
            raise KeyError(name)
        result |= by_name[name]
    return result
