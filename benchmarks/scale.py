"""How building, checking and running grow with the number of bodies (issue 13).

For each count of bodies it prints, for two populations of the built-in human on one flat
landblock,

- ``walkers``: the layout of ``acphys bench``'s walkers (ten columns 15 m apart, rows spread over
  150 m), half walking, half running;
- ``standing``: humans standing on a square grid 1.5 m apart, no events;

the processor seconds to build the scenario from its text (``parse_scenario``), of
``acphys check`` on the file (a subprocess, start-up included) and of ``run(until=0.1)``; then
the memory one walker costs: the traced allocations (``tracemalloc``) of building N and 2N
walkers, the difference over N. Nothing here asserts a time::

    .venv/bin/python benchmarks/scale.py                       # 1,000, 5,000 and 10,000 bodies
    .venv/bin/python benchmarks/scale.py --counts 2000 --memory 500
"""

from __future__ import annotations

import argparse
import gc
import math
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Callable
from pathlib import Path

from acphys.scenario import parse_scenario

HEADER = (
    '[scenario]\nname = "scale"\nduration = 0.1\ndriver_hz = 30.0\n'
    '[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
)


def walkers_text(count: int) -> str:
    """``acphys bench``'s walkers: ten columns 15 m apart, rows over 150 m, half of them running."""
    rows = (count + 9) // 10
    bodies = "".join(
        f'[[body]]\nname = "w{i}"\nlandblock = "0xA9B4"\non_ground = true\n'
        f"origin = [{20.0 + 15.0 * (i % 10)}, {20.0 + 150.0 * (i // 10) / rows}, 50.0]\n"
        for i in range(count)
    )
    events = "".join(
        f'[[event]]\nat = 0.0\nbody = "w{i}"\naction = "motion"\nmotion = "WalkForward"\n'
        f"hold_run = {'true' if i % 2 else 'false'}\n"
        for i in range(count)
    )
    return HEADER + bodies + events


def standing_text(count: int) -> str:
    """Humans standing on a square grid 1.5 m apart (100 by 100 for 10,000), no events."""
    side = max(1, math.ceil(math.sqrt(count)))
    return HEADER + "".join(
        f'[[body]]\nname = "s{i}"\nlandblock = "0xA9B4"\non_ground = true\n'
        f"origin = [{20.0 + 1.5 * (i % side)}, {20.0 + 1.5 * (i // side)}, 50.0]\n"
        for i in range(count)
    )


POPULATIONS: dict[str, Callable[[int], str]] = {"walkers": walkers_text, "standing": standing_text}


def seconds(action: Callable[[], object]) -> tuple[float, object]:
    """The processor seconds ``action`` takes (``process_time``: on a shared machine, what it
    would take alone) and what it returns."""
    start = time.process_time()
    result = action()
    return time.process_time() - start, result


def check_seconds(text: str) -> float:
    """The processor seconds of ``acphys check`` on ``text`` written to a file, as a user runs
    it (start-up included)."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "scale.toml"
        path.write_text(text, encoding="utf-8")
        command = [sys.executable, "-m", "acphys.cli", "check", str(path)]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        done = subprocess.run(command, capture_output=True, text=True, check=False)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if done.returncode != 0:
            raise SystemExit(f"acphys check failed: {done.stderr.strip()}")
        return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def traced_bytes(text: str) -> int:
    """The bytes still allocated (``tracemalloc``) once the scenario of ``text`` is built."""
    gc.collect()
    tracemalloc.start()
    sim = parse_scenario(text)
    gc.collect()
    current, _peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    del sim
    return current


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", default="1000,5000,10000", help="numbers of bodies, comma separated")
    parser.add_argument("--memory", type=int, default=1000, help="N for the memory figure (N and 2N walkers)")
    args = parser.parse_args()
    counts = [int(count) for count in args.counts.split(",")]

    print("processor seconds")
    print(f"{'population':10s} {'bodies':>7s} {'build':>8s} {'check':>8s} {'run 0.1 s':>9s}")
    for name, make in POPULATIONS.items():
        for count in counts:
            text = make(count)
            build, sim = seconds(lambda text=text: parse_scenario(text))
            run, _ = seconds(lambda sim=sim: sim.run(until=0.1))
            del sim
            check = check_seconds(text)
            print(f"{name:10s} {count:7d} {build:8.2f} {check:8.2f} {run:9.2f}", flush=True)

    n = args.memory
    small, large = traced_bytes(walkers_text(n)), traced_bytes(walkers_text(2 * n))
    print(f"memory per walker: {(large - small) / n / 1024:.1f} KB (built {n} and {2 * n} walkers)")


if __name__ == "__main__":
    main()
