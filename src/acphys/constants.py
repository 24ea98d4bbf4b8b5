"""Retail physics constants, each with the place it is defined or read.

Retail stores float32 and computes in double on the x87 (see
:mod:`acphys.precision`); each constant here has the value retail holds (for
float32 globals and literals, the float32 value widened to float64). A literal
the decompiler prints with about eight significant digits (``0.00019999999``)
is a float32 constant; double literals print with sixteen. Line numbers are
into the monolithic ``acclient.c`` of build 11.4186 (see ``retail_index.tsv``).
"""

from __future__ import annotations

import math

from acphys.precision import f32

#: ``PhysicsGlobals::gravity`` (acclient_data.h; read by calc_acceleration, acclient.c:317814).
GRAVITY: float = f32(-9.8000002)

#: ``PhysicsGlobals::floor_z = cos(3437.746770784939)`` (sub_70D920, acclient.c:800530).
#: The literal is 60 × 180/π: a degrees/radians slip, so the steepest walkable
#: slope is acos(0.66417414) ≈ 48.38°, not the intended 60°.
FLOOR_Z: float = f32(math.cos(3437.746770784939))

#: ``z_for_landing`` = sin 5°: walkable allowance when not on walkable ground (acclient.c:40376).
LANDING_Z: float = f32(0.0871557)
#: The step-down (and step-up) height of a body not on walkable ground (acclient.c:312807, 312966).
SMALL_STEP_DOWN_HEIGHT: float = f32(0.039999999)

#: The retail epsilon written as ``0.00019999999`` throughout the decompilation: the float32
#: ``F_EPSILON`` (``const float F_EPSILON_37``, acclient_data.h:598), i.e. float32(0.0002).
EPSILON: float = f32(0.00019999999)

#: Terminal speed: ``velocity_mag2 > 50.0 * 50.0`` normalises to 50
#: (UpdatePhysicsInternal, acclient.c:317740).
MAX_VELOCITY: float = 50.0

#: Deadband speed: velocity is zeroed when ``velocity_mag2 - 0.25 * 0.25 < EPSILON`` (acclient.c:317750).
SMALL_VELOCITY: float = 0.25

#: ``MIN_QUANTUM_93`` / ``MIN_QUANTUM_97`` = 1/30 s (static init, acclient.c:783714 and 784226).
MIN_QUANTUM: float = 1.0 / 30.0

#: ``MAX_QUANTUM_97`` = 1/5 s (static init, acclient.c:784232). ACE uses 0.1; retail is 0.2.
MAX_QUANTUM: float = 1.0 / 5.0

#: Elapsed time above which ``update_object`` drops the interval (acclient.c:323127).
HUGE_QUANTUM: float = 2.0

#: Distance from the player beyond which ``update_object`` deactivates a body (acclient.c:323114).
ACTIVITY_DISTANCE: float = 96.0

#: ``DEFAULT_FRICTION`` (acclient_data.h:1430), set by the CPhysicsObj constructor (acclient.c:319489).
DEFAULT_FRICTION: float = f32(0.94999999)

#: ``DEFAULT_ELASTICITY`` (acclient_data.h:1431); ``set_elasticity`` clamps to [0, 0.1] (acclient.c:317060).
DEFAULT_ELASTICITY: float = f32(0.050000001)

#: Upper bound ``set_elasticity`` clamps to (the literal 1036831949 = 0x3DCCCCCD, float32 0.1).
MAX_ELASTICITY: float = f32(0.1)

#: ``SLEDDING_PS`` friction on steep fast slides (calc_friction, acclient.c:316090).
SLEDDING_FRICTION: float = f32(0.2)

#: ``SLEDDING_PS``: below this squared speed the friction factor is 1.0, a full stop (1.25 m/s).
SLEDDING_STOP_SPEED2: float = 1.5625

#: ``SLEDDING_PS``: at or above this squared speed steep slopes use SLEDDING_FRICTION (2.5 m/s).
SLEDDING_FAST_SPEED2: float = 6.25

#: ``cos(0.1745329251994329)`` = cos 10°: the contact-normal z below which a fast sled uses 0.2.
SLEDDING_STEEP_Z: float = math.cos(0.1745329251994329)

#: Landblock and land-cell sizes (LandDefs: 24 m cells, 8 per block side).
CELL_LENGTH: float = 24.0
CELLS_PER_BLOCK: int = 8
BLOCK_LENGTH: float = CELL_LENGTH * CELLS_PER_BLOCK

#: ``LandDefs`` world extent in land cells (x, y < 2040; acclient.c:218181).
MAX_LCOORD: int = 2040
