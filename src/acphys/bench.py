"""The performance suite behind ``acphys bench``: rates, and ratios against baselines run alongside.

Each workload builds a population of bodies and runs it through the real tick on one engine, or
on both (``engine="both"``), reporting how many body-steps (one ``update_object_internal`` each)
the engine manages per second of stepping. Figures measured in the same run put it in
proportion, so results compare across machines:

- ``baseline``: a fixed pure-Python loop doing the arithmetic of one free-fall Euler step, the
  speed of the interpreter itself; every workload's ``vs_baseline`` is its rate over the
  baseline's.
- ``landblock``: the rate a whole landblock needs in real time, 100 bodies at 30 Hz (3,000
  body-steps per second); ``vs_realtime`` is the rate over that.

The timed stepping starts after the first driver tick, which applies the events that set the
bodies going (in the reference path's Python, on either engine): it is set-up, as building is.
It ends with the last tick: the fast engine then writes its records back into the bodies' objects
once (the run's end, whatever its length), timed apart as ``write_back_seconds``.

- with both engines, the fast engine's row has ``fast_vs_reference``: its rate over the reference
  engine's on the same workload, bodies and duration.

The fast engine's rows also give the time its compiled kernels took to load (or compile, the
first time) apart from the stepping (``compile_seconds``), the share of body-steps that ran on the
reference path and why (``fallback_share``, ``fallback_reasons``), and the bytes of kernel arrays
per body (``memory_per_body``). Building a workload is timed apart too (``build_seconds``).

Nothing here asserts a time: the figures are reported, never checked.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

from acphys.math.vector import Vector3
from acphys.scenario import build_scenario, parse_scenario
from acphys.simulation import Simulation

#: Body-steps per second a landblock of 100 bodies needs at 30 Hz.
LANDBLOCK_RATE = 100 * 30.0
#: What ``engine`` may be: one engine, or both in turn.
ENGINE_CHOICES = ("reference", "fast", "both")


@dataclass
class BenchResult:
    """One workload's figures on one engine."""

    workload: str
    engine: str
    description: str
    bodies: int
    body_steps: int
    seconds: float
    steps_per_s: float
    vs_baseline: float
    vs_realtime: float
    build_seconds: float = 0.0
    compile_seconds: float | None = None
    fallback_share: float | None = None
    fallback_reasons: dict[str, int] = field(default_factory=dict)
    memory_per_body: float | None = None
    fast_vs_reference: float | None = None
    #: Seconds after the last tick writing the fast engine's records back into the bodies' objects
    #: (once per run, whatever its length; timed apart from stepping, as building is).
    write_back_seconds: float = 0.0

    def as_dict(self) -> dict[str, object]:
        return asdict(self)


def _baseline(steps: int) -> tuple[int, float]:
    """A free-fall Euler step in plain floats, ``steps`` times: the interpreter's own speed."""
    x = y = z = 0.0
    vx, vy, vz = 1.0, 0.5, 0.0
    dt = 1.0 / 30.0
    g = -9.8
    start = time.perf_counter()
    for _ in range(steps):
        speed2 = vx * vx + vy * vy + vz * vz
        if speed2 > 2500.0:
            scale = 50.0 / speed2**0.5
            vx, vy, vz = vx * scale, vy * scale, vz * scale
        x += vx * dt
        y += vy * dt
        z += vz * dt + 0.5 * g * dt * dt
        vz += g * dt
    return steps, time.perf_counter() - start


def _population(count: int, body: Callable[[int], str], events: Callable[[int], str], seconds: float) -> str:
    rows = (count + 9) // 10
    return (
        f'[scenario]\nname = "bench"\nduration = {seconds}\ndriver_hz = 30.0\n'
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        + "".join(
            body(i) + f"origin = [{20.0 + 15.0 * (i % 10)}, {20.0 + 150.0 * (i // 10) / rows}, 50.0]\n"
            for i in range(count)
        )
        + "".join(events(i) for i in range(count))
    )


def _walkers(count: int, seconds: float, engine: str = "reference") -> Simulation:
    """Humans with the humanoid table, half walking, half running, on flat ground (ten columns
    15 m apart, rows over 150 m: past a few hundred they stand in each other)."""

    def body(i: int) -> str:
        return f'[[body]]\nname = "w{i}"\nlandblock = "0xA9B4"\non_ground = true\n'

    def events(i: int) -> str:
        run = "true" if i % 2 else "false"
        return (
            f'[[event]]\nat = 0.0\nbody = "w{i}"\naction = "motion"\n'
            f'motion = "WalkForward"\nhold_run = {run}\n'
        )

    text = _population(count, body, events, seconds)
    return parse_scenario(text, source="<bench walkers>", engine=engine)


def _fallers(count: int, seconds: float, engine: str = "reference") -> Simulation:
    """Balls thrown upwards with no motion table: integration and the sweep, no animation."""

    def body(i: int) -> str:
        return (
            f'[[body]]\nname = "b{i}"\nsetup = "ball"\nlandblock = "0xA9B4"\n'
            f'state = ["gravity"]\nvelocity = [0.0, 0.0, {5.0 + (i % 7)}]\n'
        )

    text = _population(count, body, lambda i: "", seconds)
    text = text.replace(
        "[[landblock]]",
        "[setup.ball]\nspheres = [{ center = [0, 0, 0.1], radius = 0.1 }]\n\n[[landblock]]",
        1,
    )
    return parse_scenario(text, source="<bench fallers>", engine=engine)


def _crowd(count: int, seconds: float, engine: str = "reference") -> Simulation:
    """Humans 1.5 m apart in a square, columns facing north and east by turns, walking through each
    other's paths: every sweep meets the shadows of its neighbours (the object-object checks)."""
    side = max(1, math.ceil(math.sqrt(count)))

    def body(i: int) -> str:
        row, column = divmod(i, side)
        return (
            f'[[body]]\nname = "c{i}"\nlandblock = "0xA9B4"\non_ground = true\n'
            f"heading = {90.0 * (column % 2)}\norigin = [{80.0 + 1.5 * column}, {80.0 + 1.5 * row}, 50.0]\n"
        )

    def event(i: int) -> str:
        return f'[[event]]\nat = 0.0\nbody = "c{i}"\naction = "motion"\nmotion = "WalkForward"\n'

    text = (
        f'[scenario]\nname = "bench"\nduration = {seconds}\ndriver_hz = 30.0\n'
        '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        + "".join(body(i) for i in range(count))
        + "".join(event(i) for i in range(count))
    )
    return parse_scenario(text, source="<bench crowd>", engine=engine)


#: How far apart the hills workload's walkers stand, in metres: their circles (about 4 m across
#: walking, 5.3 m running) never meet.
HILLS_SPACING = 8.0
#: Walkers a side of a landblock in the hills workload (23 × 23 = 529 a landblock, 6 m from its edges).
HILLS_PER_BLOCK_SIDE = 23


def _hill_heights(bx: int, by: int) -> list[int]:
    """Height bytes of rolling hills, continuous across landblock seams (slopes up to about 14°)."""
    heights = []
    for x in range(9):
        for y in range(9):
            gx, gy = 8 * bx + x, 8 * by + y
            wave = 4.0 * math.sin(gx * 0.7) + 3.0 * math.cos(gy * 0.55) + 2.0 * math.sin((gx + gy) * 0.3)
            heights.append(round(40.0 + wave))
    return heights


def _hills_document(count: int, seconds: float, name: str) -> dict[str, Any]:
    """The hills workload's scenario as Python values (see :func:`_hills`)."""
    blocks = max(1, math.ceil(count / HILLS_PER_BLOCK_SIDE**2))
    side = math.ceil(math.sqrt(blocks))
    landblocks = [
        {"id": f"0x{0x80 + bx:02X}{0x80 + by:02X}", "heights": _hill_heights(bx, by)}
        for bx in range(side)
        for by in range(side)
    ][:blocks]
    bodies = []
    events: list[dict[str, Any]] = []
    for i in range(count):
        block, slot = divmod(i, HILLS_PER_BLOCK_SIDE**2)
        row, column = divmod(slot, HILLS_PER_BLOCK_SIDE)
        x, y = 6.0 + HILLS_SPACING * column, 6.0 + HILLS_SPACING * row
        name_i = f"h{i}"
        bodies.append(
            {
                "name": name_i,
                "landblock": landblocks[block]["id"],
                "origin": [x, y, 0.0],  # under the hills: placement lifts it onto them
                "heading": float((i * 47) % 360),
                "on_ground": True,
            }
        )
        walk = {
            "at": 0.0,
            "body": name_i,
            "action": "motion",
            "motion": "WalkForward",
            "hold_run": i % 2 == 1,
        }
        events.append(walk)
        events.append({"at": 0.0, "body": name_i, "action": "motion", "motion": "TurnRight"})
    return {
        "scenario": {"name": name, "duration": seconds, "driver_hz": 30.0},
        "landblock": landblocks,
        "body": bodies,
        "event": events,
    }


def _hills(count: int, seconds: float, engine: str = "reference") -> Simulation:
    """Humans walking and running in circles (a turn held with the walk) over rolling hills, 8 m
    apart, over as many landblocks as they need (529 a landblock); their circles never meet, so they
    walk on their own for as long as they run. Built from Python values (``build_scenario``), as a
    server would make its population."""
    return build_scenario(
        _hills_document(count, seconds, "bench-hills"), source="<bench hills>", engine=engine
    )


#: In the server workload, one body in ``SERVER_EVERY`` is a remote one gliding to interpolation
#: nodes, and one a walker told to turn left and right by turns, each ``SERVER_RATE`` times a second.
SERVER_EVERY = 100
SERVER_RATE = 10.0
#: The remote bodies' circles: radius (m) and the angle between two nodes (radians).
SERVER_CIRCLE = 2.0
SERVER_STEP = 0.15


def _server(count: int, seconds: float, engine: str = "reference") -> Simulation:
    """The hills walkers as a server drives them: one in 100 a remote body gliding round a 2-m
    circle to interpolation nodes sent ten times a second (its position manager's interpolation,
    which the kernel runs), one in 100 told to turn left and right by turns ten times a second
    (events that change its motion alone)."""
    document = _hills_document(count, seconds, "bench-server")
    remote = {f"h{i}" for i in range(count) if i % SERVER_EVERY == SERVER_EVERY // 2}
    told = [f"h{i}" for i in range(count) if i % SERVER_EVERY == SERVER_EVERY // 4]
    events = [event for event in document["event"] if event["body"] not in remote]
    sends = [k / SERVER_RATE for k in range(1, int(seconds * SERVER_RATE) + 1)]
    for name in told:
        for k, at in enumerate(sends):
            events.append(
                {"at": at, "body": name, "action": "motion", "motion": "TurnLeft" if k % 2 else "TurnRight"}
            )
    document["event"] = events
    sim = build_scenario(document, source="<bench server>", engine=engine)
    for name in sorted(remote):
        body = sim.body(name)
        cell_id, start = body.position.objcell_id, body.position.frame.origin
        for k, at in enumerate(sends, start=1):
            angle = k * SERVER_STEP
            x = start.x + SERVER_CIRCLE * (math.cos(angle) - 1.0)
            y = start.y + SERVER_CIRCLE * math.sin(angle)
            ground = sim.world.ground_height(cell_id, Vector3(x, y, 0.0))
            z = start.z if ground is None else ground + 0.005
            sim.add_event(at, name, "interpolate_to", origin=[x, y, z])
    return sim


#: Bodies a landblock of the mixed workload holds (25 of each kind); more bodies take more
#: landblocks, each with its own house and pillars.
MIXED_PER_BLOCK = 100

_HOUSE = (
    "origin = [156.0, 156.0, 50.0]\nrooms = [\n"
    '    { name = "hall", min = [-6, -4, 0], max = [0, 4, 3] },\n'
    '    { name = "parlour", min = [0, -4, 0], max = [6, 4, 3] },\n]\n'
    "doorways = [\n"
    '    { between = ["hall", "outside"], min = [-6, -0.6, 0], max = [-6, 0.6, 2.2] },\n'
    '    { between = ["hall", "parlour"], min = [0, -0.6, 0], max = [0, 0.6, 2.2] },\n]\n'
)


def _mixed(count: int, seconds: float, engine: str = "reference") -> Simulation:
    """Flat landblocks of everything at once: walkers and runners, balls thrown about, a crowd
    walking through itself, pillars, and a house some walkers walk into; 100 bodies a landblock
    (the first is 0xA9B4), as many landblocks as the bodies need. What the fast engine does not
    cover runs on the reference path; its rows report the share."""
    blocks = max(1, math.ceil(count / MIXED_PER_BLOCK))
    side = math.ceil(math.sqrt(blocks))
    text = [
        f'[scenario]\nname = "bench-mixed"\nduration = {seconds}\ndriver_hz = 30.0\n',
        "[setup.ball]\nspheres = [{ center = [0, 0, 0.15], radius = 0.15 }]\n",
        "[setup.pillar]\ncylspheres = [{ low_pt = [0, 0, 0], radius = 0.8, height = 4.0 }]\n",
    ]
    events = []
    for block in range(blocks):
        bx, by = divmod(block, side)
        landblock = f"0x{0xA9 + bx:02X}{0xB4 + by:02X}"
        text.append(f'[[landblock]]\nid = "{landblock}"\nheight = 50.0\n')
        text.append(f'[[building]]\nlandblock = "{landblock}"\n{_HOUSE}')
        for n, (x, y) in enumerate(((40.0, 150.0), (100.0, 40.0), (130.0, 110.0))):
            name = f"pillar-{n}" if block == 0 else f"pillar-{block}-{n}"
            text.append(f'[[object]]\nname = "{name}"\nsetup = "pillar"\nlandblock = "{landblock}"\n')
            text.append(f"origin = [{x}, {y}, 50.0]\n")
        first = block * MIXED_PER_BLOCK
        here = min(MIXED_PER_BLOCK, count - first)
        crowd_side = max(1, math.ceil(math.sqrt(here // 4)))
        for i in range(first, first + here):
            kind, n = (i - first) % 4, (i - first) // 4
            name = f"m{i}"
            body = f'[[body]]\nname = "{name}"\nlandblock = "{landblock}"\n'
            walk = f'[[event]]\nat = 0.0\nbody = "{name}"\naction = "motion"\nmotion = "WalkForward"\n'
            if kind == 0:  # walkers and runners
                x, y = 10.0 + 6.0 * (n % 18), 10.0 + 6.0 * (n // 18)
                body += f"origin = [{x}, {y}, 50.0]\non_ground = true\nheading = {(i * 37) % 360}\n"
                events.append(walk + f"hold_run = {'true' if n % 2 else 'false'}\n")
            elif kind == 1:  # balls thrown about
                x, y = 20.0 + 7.0 * (n % 18), 60.0 + 7.0 * (n // 18)
                vx, vy = 3.0 * math.sin(i), 3.0 * math.cos(i)
                body += (
                    f'setup = "ball"\norigin = [{x:.2f}, {y:.2f}, 60.0]\n'
                    'state = ["gravity", "report_collisions"]\n'
                    f"velocity = [{vx:.2f}, {vy:.2f}, {4.0 + i % 5}]\n"
                )
            elif kind == 2:  # a crowd walking through itself
                row, column = divmod(n, crowd_side)
                body += (
                    f"origin = [{120.0 + 1.5 * column}, {20.0 + 1.5 * row}, 50.0]\non_ground = true\n"
                    f"heading = {90.0 * (column % 2)}\n"
                )
                events.append(walk)
            else:  # walkers heading for the house
                x, y = 130.0 + (n % 5) * 2.0, 150.0 + (n // 5) * 2.5
                body += f"origin = [{x}, {y}, 50.0]\non_ground = true\nheading = 90.0\n"
                events.append(walk)
            text.append(body)
    return parse_scenario("".join(text) + "".join(events), source="<bench mixed>", engine=engine)


Build = Callable[..., Simulation]

WORKLOADS: dict[str, tuple[str, Build]] = {
    "walkers": ("humans walking and running: animation root motion, motion tables, the sweep", _walkers),
    "fallers": ("balls in flight and landing: Euler integration and the sweep", _fallers),
    "crowd": ("humans walking into each other 1.5 m apart: the object-object checks", _crowd),
    "hills": ("humans walking and running in circles over rolling hills, 8 m apart, 529 a landblock", _hills),
    "mixed": ("landblocks of walkers, thrown balls, a crowd, pillars and a house, 100 bodies each", _mixed),
    "server": (
        "hills walkers driven by a server: 1 in 100 interpolated, 1 in 100 told to turn, 10 times a second",
        _server,
    ),
}


def _count_steps(sim: Simulation) -> Callable[[], int]:
    """A counter of the body-steps ``sim`` takes from now on."""
    counts = getattr(sim.physics, "counts", None)
    if counts is not None:
        start = counts.kernel + counts.reference
        return lambda: counts.kernel + counts.reference - start
    steps = 0

    def count(_body: object, _quantum: float) -> None:
        nonlocal steps
        steps += 1

    for body in sim.bodies:
        body.observer = count
    return lambda: steps


def warm_up(workload: str = "hills") -> float:
    """Make the fast engine's kernels ready (load them from Numba's cache, or compile them the first
    time: minutes) with a tiny run of ``workload``; return the seconds it took."""
    start = time.perf_counter()
    WORKLOADS[workload][1](2, 0.2, "fast").run()
    return time.perf_counter() - start


def run_workload(workload: str, engine: str, bodies: int, seconds: float, base_rate: float) -> BenchResult:
    """One workload on one engine (``reference`` or ``fast``)."""
    description, build = WORKLOADS[workload]
    compile_seconds = warm_up(workload) if engine == "fast" else None
    start = time.perf_counter()
    sim = build(bodies, seconds, engine)
    build_seconds = time.perf_counter() - start
    steps = _count_steps(sim)
    ticks: list[tuple[float, int]] = []  # the first tick and the last so far

    def after_tick(_now: float, _end: float) -> None:
        # The first tick applies the events that start the motions: set-up, untimed.
        ticks[1:] = [(time.perf_counter(), steps())]
        if len(ticks) == 1:
            ticks.append(ticks[0])

    sim.run(progress=after_tick)
    finished = time.perf_counter()
    (started, before), (stopped, after) = ticks if ticks else [(finished, steps())] * 2
    elapsed = stopped - started
    taken = after - before
    rate = taken / elapsed if elapsed > 0.0 else 0.0
    result = BenchResult(
        workload,
        engine,
        description,
        bodies,
        taken,
        elapsed,
        rate,
        rate / base_rate,
        rate / LANDBLOCK_RATE,
        build_seconds=build_seconds,
        write_back_seconds=finished - stopped,
    )
    physics: Any = sim.physics
    if engine == "fast":
        counts = physics.counts
        result.compile_seconds = compile_seconds
        result.fallback_share = counts.reference_share
        result.fallback_reasons = dict(sorted(counts.reasons.items(), key=lambda item: -item[1]))
        result.memory_per_body = physics.array_bytes() / max(1, bodies)
    return result


def run_suite(
    bodies: int = 100,
    seconds: float = 5.0,
    engine: str = "reference",
    workloads: list[str] | None = None,
) -> list[BenchResult]:
    """The baseline, then every workload (or those named) with ``bodies`` bodies for ``seconds``
    of simulated time on ``engine`` (``"reference"``, ``"fast"`` or ``"both"``)."""
    if bodies < 1 or not seconds > 0.0:
        raise ValueError(f"bench needs at least one body and a positive duration, got {bodies}, {seconds}")
    if engine not in ENGINE_CHOICES:
        raise ValueError(f"engine must be one of {', '.join(ENGINE_CHOICES)}, got {engine!r}")
    names = list(WORKLOADS) if workloads is None else workloads
    unknown = [name for name in names if name not in WORKLOADS]
    if unknown:
        raise ValueError(f"no workload {unknown[0]!r} (workloads: {', '.join(WORKLOADS)})")
    engines = ["reference", "fast"] if engine == "both" else [engine]
    base_steps, base_seconds = _baseline(max(1, min(3_000_000, int(bodies * seconds * 30.0 * 10))))
    base_rate = base_steps / base_seconds
    results = [
        BenchResult(
            "baseline",
            "python",
            "a plain-float free-fall Euler step (the interpreter's speed)",
            0,
            base_steps,
            base_seconds,
            base_rate,
            1.0,
            base_rate / LANDBLOCK_RATE,
        )
    ]
    for name in names:
        rows = [run_workload(name, each, bodies, seconds, base_rate) for each in engines]
        if len(rows) == 2 and rows[0].steps_per_s > 0.0:
            rows[1].fast_vs_reference = rows[1].steps_per_s / rows[0].steps_per_s
        results.extend(rows)
    return results
