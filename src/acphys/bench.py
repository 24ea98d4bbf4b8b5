"""The performance suite behind ``acphys bench``: rates, and ratios against a baseline run alongside.

Each workload runs a scenario-sized population of bodies through the real
tick and reports how many body-steps (one ``update_object_internal`` each)
it manages per second. Two reference figures come from the same run, so
results compare across machines:

- ``baseline``: a fixed pure-Python loop doing the arithmetic of one free-fall
  Euler step, the speed of the interpreter itself; every workload's
  ``vs_baseline`` is its rate over the baseline's.
- ``landblock``: the rate a whole landblock needs in real time, 100 bodies at
  30 Hz (3,000 body-steps per second); ``vs_realtime`` is the rate over that.

Nothing here asserts a time: the figures are reported, never checked.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass

from acphys.scenario import parse_scenario
from acphys.simulation import Simulation

#: Body-steps per second a landblock of 100 bodies needs at 30 Hz.
LANDBLOCK_RATE = 100 * 30.0


@dataclass
class BenchResult:
    """One workload's figures."""

    name: str
    description: str
    body_steps: int
    seconds: float
    rate: float
    vs_baseline: float
    vs_realtime: float

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


def _walkers(count: int, seconds: float) -> Simulation:
    """Humans with the humanoid table, half walking, half running, on flat ground."""

    def body(i: int) -> str:
        return f'[[body]]\nname = "w{i}"\nlandblock = "0xA9B4"\non_ground = true\n'

    def events(i: int) -> str:
        run = "true" if i % 2 else "false"
        return (
            f'[[event]]\nat = 0.0\nbody = "w{i}"\naction = "motion"\n'
            f'motion = "WalkForward"\nhold_run = {run}\n'
        )

    return parse_scenario(_population(count, body, events, seconds), source="<bench walkers>")


def _fallers(count: int, seconds: float) -> Simulation:
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
    return parse_scenario(text, source="<bench fallers>")


def _crowd(count: int, seconds: float) -> Simulation:
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
    return parse_scenario(text, source="<bench crowd>")


WORKLOADS: dict[str, tuple[str, Callable[[int, float], Simulation]]] = {
    "walkers": ("humans walking and running: animation root motion, motion tables, the sweep", _walkers),
    "fallers": ("balls in flight and landing: Euler integration and the sweep", _fallers),
    "crowd": ("humans walking into each other 1.5 m apart: the object-object checks", _crowd),
}


def _measure(sim: Simulation) -> tuple[int, float]:
    steps = 0

    def count(_body: object, _quantum: float) -> None:
        nonlocal steps
        steps += 1

    for body in sim.bodies:
        body.observer = count
    start = time.perf_counter()
    sim.run()
    return steps, time.perf_counter() - start


def run_suite(bodies: int = 100, seconds: float = 5.0) -> list[BenchResult]:
    """Run the baseline and every workload with ``bodies`` bodies for ``seconds`` of simulated time."""
    if bodies < 1 or not seconds > 0.0:
        raise ValueError(f"bench needs at least one body and a positive duration, got {bodies}, {seconds}")
    base_steps, base_seconds = _baseline(max(1, int(bodies * seconds * 30.0 * 10)))
    base_rate = base_steps / base_seconds
    results = [
        BenchResult(
            "baseline",
            "a plain-float free-fall Euler step (the interpreter's speed)",
            base_steps,
            base_seconds,
            base_rate,
            1.0,
            base_rate / LANDBLOCK_RATE,
        )
    ]
    for name, (description, build) in WORKLOADS.items():
        steps, elapsed = _measure(build(bodies, seconds))
        rate = steps / elapsed
        results.append(
            BenchResult(name, description, steps, elapsed, rate, rate / base_rate, rate / LANDBLOCK_RATE)
        )
    return results
