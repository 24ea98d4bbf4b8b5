"""The manager events of scenarios (interpolate_to, stick_to, unstick, constrain_to, play_script) on the
built-in "remote" scenario, and the order in which the tick runs the managers."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

import acphys
from acphys.managers.detection import DetectionManager
from acphys.managers.particles import ParticleManager
from acphys.managers.position import PositionManager
from acphys.managers.scripts import ScriptManager
from acphys.managers.target import TargetManager
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion import commands
from acphys.motion.movement import MovementParameters
from acphys.motion.movement_manager import MovementManager
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.scenario import ScenarioError, parse_scenario
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.setup import human_setup
from acphys.world.world import World
from support import LANDBLOCK, step_records, ulp32

GLIDE = 8.0 / 30.0  # 2 × adjusted max speed (4 m/s, no weenie) per 1/30-s step (acclient.c:389237-389240)


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> tuple[acphys.Simulation, dict[str, list[dict]]]:
    sim = acphys.load_scenario("remote")
    trace = tmp_path_factory.mktemp("remote") / "remote.jsonl"
    sim.run(trace=trace)
    records: dict[str, list[dict]] = {}
    for record in step_records(Path(trace)):
        records.setdefault(record["body"], []).append(record)
    return sim, records


def _at(records: list[dict], t: float) -> dict:
    return min(records, key=lambda r: abs(r["t"] - t))


def test_the_remote_body_glides_to_each_server_position_and_snaps_past_the_blip(run) -> None:
    _sim, records = run
    remote = records["remote"]
    first = next(i for i, r in enumerate(remote) if "interpolate_to" in r["events"])
    xs = [r["origin"][0] for r in remote[first : first + 8]]
    # InterpolationManager::adjust_offset replaces the offset with a glide of GLIDE a step along the
    # way to the node (acclient.c:389178-389260) ...
    # (each step the difference of two float32 positions near 96 m)
    glides = [b - a for a, b in itertools.pairwise(xs)][:5]
    assert glides == pytest.approx([GLIDE] * 5, abs=2 * ulp32(96.0))
    # ... and ends within 0.05 m of it (NodeCompleted, acclient.c:389217).
    assert abs(_at(remote, 1.2)["origin"][0] - 99.0) < 0.05
    assert abs(_at(remote, 3.4)["origin"][1] - 104.0) < 0.05
    # 111 m is past the 100-m outdoor blip distance (GetAutonomyBlipDistance): one step puts it there.
    blip = next(r for r in remote if r["t"] > 3.5 - 1e-6 and "interpolate_to" in r["events"])
    after = remote[remote.index(blip) + 1]
    assert after["origin"][:2] == [20.0, 180.0]
    assert after["cell"] == "0xA9B40008"


def test_the_pet_keeps_the_standoff_while_renewed_and_stays_when_released(run) -> None:
    _sim, records = run
    owner = {round(r["t"], 4): r["origin"][0] for r in records["owner"]}
    for record in records["pet"]:
        gap = owner[round(record["t"], 4)] - record["origin"][0] - 2 * 0.48
        if 0.45 < record["t"] < 2.95:
            # StickyManager::adjust_offset stops 0.3 m from the target's cylinder (acclient.c:388559).
            # (float32 positions near 100 m and float32 radii: a couple of spacings there)
            assert gap == pytest.approx(0.3, abs=2 * ulp32(100.0))
    stopped = [r["origin"][0] for r in records["pet"] if r["t"] > 3.05]
    assert len(set(stopped)) == 1


def test_the_leashed_body_slows_and_stops_at_the_max_distance(run) -> None:
    sim, records = run
    ys = [r["origin"][1] for r in records["leashed"]]
    steps = [b - a for a, b in itertools.pairwise(ys)]
    # Full walk frames until 1 m, then damped by (3 - total) / (3 - 1), never past 3 m of offsets
    # (ConstraintManager::adjust_offset, acclient.c:389477).
    assert steps[0] == pytest.approx(3.12 / 30.0, abs=1e-6)
    assert all(b <= a + 1e-9 for a, b in itertools.pairwise(steps))
    assert 2.9 < sim.body("leashed").position.frame.origin.y - 60.0 <= 3.0


def test_the_script_scales_the_body_up_and_back() -> None:
    sim = acphys.load_scenario("remote")
    grower = sim.body("grower")
    sim.run(until=1.6)
    # Scale hook at 0.0 of a script played at 0.5 s: an FPHook to 2.0 over 1 s (ScaleHook::Execute,
    # acclient.c:342473; CPhysicsObj::SetScale, 320621).
    assert grower.scale == pytest.approx(2.0)
    sim.run(until=2.7)
    assert grower.scale == pytest.approx(1.0)


def test_manager_events_name_their_targets() -> None:
    body = '[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 1.0]\n'
    with pytest.raises(ScenarioError, match=r"event\[0\].target: no other body named 'b'"):
        parse_scenario(body + '[[event]]\nat = 0.0\nbody = "a"\naction = "stick_to"\ntarget = "b"\n')
    with pytest.raises(ScenarioError, match=r"event\[0\].script: no script named 'x'"):
        parse_scenario(body + '[[event]]\nat = 0.0\nbody = "a"\naction = "play_script"\nscript = "x"\n')
    with pytest.raises(ScenarioError, match=r"event\[0\].max: must be more than start"):
        parse_scenario(
            body + '[[event]]\nat = 0.0\nbody = "a"\naction = "constrain_to"\n'
            "origin = [1.0, 1.0, 1.0]\nstart = 3.0\nmax = 1.0\n"
        )


def test_the_tick_runs_the_managers_in_retail_order() -> None:
    # CPhysicsObj::UpdateObjectInternal (acclient.c:322718): after the commit, detection, targeting,
    # movement, the part array's motion table, the position manager; then particles and scripts.
    order: list[str] = []

    def recording(cls: type, *methods: str) -> type:
        """A subclass of the real manager whose ``methods`` note their call, then run as usual."""

        def wrap(method: str):
            def recorded(self, *args, **kwargs):
                order.append(f"{cls.__name__}.{method}")
                return getattr(cls, method)(self, *args, **kwargs)

            return recorded

        return type(f"Recording{cls.__name__}", (cls,), {m: wrap(m) for m in methods})

    world = World()
    world.set_flat_ground(LANDBLOCK, 50.0)
    origin = Vector3(96.0, 96.0, 50.0)
    body = PhysicsObj(world, "walker", recording(PartArray, "handle_movement")(human_setup()))
    body.enter_world(Position(outdoor_cell_id(LANDBLOCK, origin), Frame(origin)))
    body.set_motion_table(builtin_motion_table("humanoid"))
    body.movement_manager = recording(MovementManager, "use_time")(body, None)
    body.movement_manager.enter_default_state()
    body.detection_manager = recording(DetectionManager, "check_detection")(body)
    body.target_manager = recording(TargetManager, "handle_targetting")(body)
    body.position_manager = recording(PositionManager, "adjust_offset", "use_time")(body)
    body.particle_manager = recording(ParticleManager, "update_particles")()
    body.script_manager = recording(ScriptManager, "update_scripts")(body)
    body.do_motion(commands.WALK_FORWARD, MovementParameters())
    order.clear()
    world.cur_time = 0.05
    body.update_object()
    # UpdatePositionInternal asks the position manager for its offset first (acclient.c:319988).
    assert order == [
        "PositionManager.adjust_offset",
        "DetectionManager.check_detection",
        "TargetManager.handle_targetting",
        "MovementManager.use_time",
        "PartArray.handle_movement",
        "PositionManager.use_time",
        "ParticleManager.update_particles",
        "ScriptManager.update_scripts",
    ]


def test_a_scenario_repeats_exactly(tmp_path: Path) -> None:
    # All randomness comes from the world's seeded dice (World.dice), so two runs of one scenario give
    # identical traces, byte for byte.
    first, second = tmp_path / "a.jsonl", tmp_path / "b.jsonl"
    acphys.load_scenario("remote").run(trace=first)
    acphys.load_scenario("remote").run(trace=second)
    assert first.read_bytes() == second.read_bytes()


def test_the_world_dice_follow_the_seed() -> None:
    assert World(seed=7).dice.random() == World(seed=7).dice.random()
    assert World(seed=7).dice.random() != World(seed=8).dice.random()
    with pytest.raises(ScenarioError, match=r"scenario\.seed: expected a non-negative whole number"):
        parse_scenario(
            '[scenario]\nseed = -1\n[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 1.0]\n'
        )
