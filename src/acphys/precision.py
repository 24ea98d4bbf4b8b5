"""Retail's numbers: float32 at rest, float64 in flight.

The retail client keeps its state in C ``float`` (IEEE single) fields, while
its x87 FPU computes at 53-bit precision: ``ClientMain::ConfigureFPU`` calls
``_control87(0x10000, 0x30000)`` (precision control ``_PC_53``) and
``_control87(0, 0x300)`` (rounding control ``_RC_NEAR``, round to nearest)
(0x00401120, acclient.c:60884), and the Direct3D device is created with
FPU_PRESERVE so it stays that way. Arithmetic between two stores is therefore IEEE double
arithmetic, the same as Python's ``float``; a value is narrowed to float32,
round to nearest even, each time retail stores it into a ``float``: a struct
field, a global, a declared ``float`` local or parameter, or a 4-byte spill
(``ST10_4`` in the decompilation; ``ST20_8`` spills and ``st7`` registers stay
double).

acphys keeps to that rule like this:

* every :class:`~acphys.math.vector.Vector3` holds float32 values: its
  constructor and operators narrow their results (a retail ``Vector3`` is three
  ``float`` fields, and every operator writes a ``Vector3``);
* :class:`~acphys.math.frame.Frame` narrows its quaternion (``set_rotate``
  takes and stores ``float``), its cached matrix and its origin;
* scalar ``float`` fields and locals are narrowed with :func:`f32` at the
  store retail makes; ``double`` fields (``CSequence::frame_number``, the
  timers) and in-flight values are left alone;
* numbers entering from scenarios, presets and events are narrowed where they
  are read (``acphys.scenario.values.float32``), as retail's data files and
  network messages hold them. ``tests/conformance/test_f32_inputs.py`` walks
  everything a simulation holds and fails on any float that is neither a
  float32 nor one of retail's declared doubles.

A contributor writing or changing a port reads the declared types of the
retail function (``acclient.h``, the signature, the local declarations) and
narrows exactly where the decompilation stores a ``float``; a composite
expression retail evaluates in registers is written with plain floats and
narrowed once, not through intermediate vectors. In Hex-Rays' declarations,
``float v8; // ST18_4`` (a 4-byte spill) and ``float x; // [sp+14h]`` are
stores; ``double v6; // st7`` and ``long double b2; // ST08_8`` are not. A
``float`` parameter is narrowed at the call. Literals printed with about eight
significant digits (``0.00019999999``, ``0.050000001``) are float32 constants,
with sixteen doubles. Retail's order of operations is kept too: the rounding
of a double sum depends on it. Three values narrowed together
(``unpack3(pack3(a, b, c))``) cost about as much as one :func:`f32` call.

Residual differences from retail can still come from values the compiler kept
in registers where the decompilation shows a store, and from the last bit of
the x87 transcendentals (``fsin``, ``fcos``, ``fpatan``; ``fsqrt`` is correctly
rounded, as ``math.sqrt`` is) against the C library's ``sin``, ``cos`` and
``atan2``.
"""

from __future__ import annotations

import struct

_F1 = struct.Struct("f")
_F3 = struct.Struct("3f")
_F4 = struct.Struct("4f")
_F9 = struct.Struct("9f")

#: ``pack``/``unpack`` pairs, bound once: hot paths call these directly.
pack1, unpack1 = _F1.pack, _F1.unpack
pack3, unpack3 = _F3.pack, _F3.unpack
pack4, unpack4 = _F4.pack, _F4.unpack
pack9, unpack9 = _F9.pack, _F9.unpack

#: The largest finite float32.
FLT_MAX: float = unpack1(b"\xff\xff\x7f\x7f")[0]


def f32(value: float) -> float:
    """``value`` stored into a C ``float`` and read back: round to nearest even, to float32.

    Beyond the float32 range the result is an infinity, as an x87 ``fstp`` with
    the overflow exception masked gives.
    """
    return unpack1(pack1(value))[0]


def f32x3(x: float, y: float, z: float) -> tuple[float, float, float]:
    """Three values narrowed to float32 at once (a ``Vector3`` store)."""
    return unpack3(pack3(x, y, z))


def is_f32(value: float) -> bool:
    """Whether ``value`` is exactly a float32 (NaN counts as one)."""
    return value != value or unpack1(pack1(value))[0] == value
