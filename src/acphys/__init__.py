"""acphys: the retail Asheron's Call client physics (build 11.4186), one object tick at a time.

>>> import acphys
>>> sim = acphys.load_scenario()          # the embedded default scenario
>>> sim.run(until=1.0)
>>> sim.body("skydiver").velocity.z < 0
True
>>> sim.body("walker").position.frame.origin.y > 60.0   # walking: animation root motion
True
"""

from acphys.arrays import BodyArrays
from acphys.body.reports import CollisionKind, CollisionReport
from acphys.flags import ObjectInfoState, PhysicsState, TransientState, TransitionState
from acphys.math import Frame, Position, Vector3
from acphys.motion import commands
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.motion_table import MotionData, MotionTable
from acphys.motion.movement import HoldKey, MovementParameters
from acphys.motion.weenie import Weenie
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.scenario import ScenarioError, load_scenario, parse_scenario
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.setup import Setup
from acphys.simulation import Event, Physics, Simulation
from acphys.trace import TraceWriter, read_header, read_trace, trace_schema
from acphys.trace_diff import DiffReport, Divergence, compare_traces, diff_traces
from acphys.world import ObjCell, World

__version__ = "0.1.0"

__all__ = [
    "AnimData",
    "AnimFrame",
    "Animation",
    "BodyArrays",
    "CollisionKind",
    "CollisionReport",
    "DiffReport",
    "Divergence",
    "Event",
    "Frame",
    "HoldKey",
    "MotionData",
    "MotionTable",
    "MovementParameters",
    "ObjCell",
    "ObjectInfoState",
    "PartArray",
    "Physics",
    "PhysicsObj",
    "PhysicsState",
    "Position",
    "ScenarioError",
    "Setup",
    "Simulation",
    "TraceWriter",
    "TransientState",
    "TransitionState",
    "Vector3",
    "Weenie",
    "World",
    "builtin_motion_table",
    "commands",
    "compare_traces",
    "diff_traces",
    "load_scenario",
    "parse_scenario",
    "read_header",
    "read_trace",
    "trace_schema",
]
