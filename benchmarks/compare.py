"""Compare the speed of two acphys checkouts in the same run.

Runs ``acphys bench --json`` alternately for a baseline checkout and for this one,
``--rounds`` times each, and reports every workload's best rate for both and their
ratio. Alternating rounds and taking the best of each side keeps a busy machine's
noise out of the ratio::

    git worktree add ../acphys-before HEAD~1          # or any checkout
    .venv/bin/python benchmarks/compare.py ../acphys-before --rounds 5

On a machine too noisy for times, ``--instructions`` counts instructions instead
(``valgrind --tool=callgrind``, the same count every run): each workload runs for
``--seconds`` and for three times that, and the difference, divided by the extra
body-steps, is the cost of one body-step without the start-up and the building::

    .venv/bin/python benchmarks/compare.py ../acphys-before --instructions --bodies 20 --seconds 0.5

The baseline runs with this checkout's interpreter and ``PYTHONPATH`` pointing at
the baseline's ``src``. Nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]


def bench(src: Path, bodies: int, seconds: float, engine: str = "reference") -> dict[str, float]:
    """One ``acphys bench`` of the checkout whose sources are ``src``: ``engine``'s rate by workload."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "bench.json"
        env = {**os.environ, "PYTHONPATH": str(src)}
        command = [sys.executable, "-m", "acphys.cli", "bench", "--bodies", str(bodies)]
        command += ["--seconds", str(seconds), "--json", str(out)]
        done = subprocess.run([*command, "--engine", engine], env=env, stdout=subprocess.DEVNULL, check=False)
        if done.returncode == 2 and engine == "reference":  # a checkout from before the engines
            subprocess.run(command, env=env, check=True, stdout=subprocess.DEVNULL)
        elif done.returncode:
            raise SystemExit(f"acphys bench failed in {src}")
        figures = json.loads(out.read_text(encoding="utf-8"))
    if isinstance(figures, list):  # a checkout from before the engines: one row per workload
        return {row["name"]: row["rate"] for row in figures}
    return {row["workload"]: row["steps_per_s"] for row in figures["results"] if row["engine"] == engine}


#: Runs one workload to its end (the body of a ``python -c`` under callgrind).
_WORKLOAD = (
    "import sys; from acphys.bench import WORKLOADS; "
    "WORKLOADS[sys.argv[1]][1](int(sys.argv[2]), float(sys.argv[3])).run()"
)


def instructions(src: Path, workload: str, bodies: int, seconds: float) -> float:
    """Instructions per body-step of ``workload`` for the checkout whose sources are ``src``."""

    def count(duration: float) -> int:
        command = ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"]
        command += [sys.executable, "-c", _WORKLOAD, workload, str(bodies), str(duration)]
        env = {**os.environ, "PYTHONPATH": str(src)}
        run = subprocess.run(command, env=env, check=True, capture_output=True, text=True)
        line = next(line for line in run.stderr.splitlines() if "Collected :" in line)
        return int(line.rsplit(":", 1)[1])

    extra_steps = bodies * round(2 * seconds * 30.0)  # the bench's 30-Hz driver
    return (count(3 * seconds) - count(seconds)) / extra_steps


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("baseline", type=Path, help="the checkout to compare against (its root)")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--bodies", type=int, default=100)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--instructions", action="store_true", help="count instructions (callgrind)")
    parser.add_argument("--engine", choices=("reference", "fast"), default="reference")
    parser.add_argument("--workload", action="append", help="only this workload (repeatable)")
    args = parser.parse_args(argv)
    sides = {"baseline": args.baseline.resolve() / "src", "this": HERE / "src"}
    if args.instructions:
        from acphys.bench import WORKLOADS

        print(f"{'workload':10} {'baseline instr/step':>20} {'this instr/step':>16} {'this/baseline':>14}")
        for name in args.workload or WORKLOADS:
            before, after = (instructions(src, name, args.bodies, args.seconds) for src in sides.values())
            print(f"{name:10} {before:20,.0f} {after:16,.0f} {after / before:14.3f}")
        return 0
    best: dict[str, dict[str, float]] = {side: {} for side in sides}
    for _ in range(args.rounds):
        for side, src in sides.items():
            for name, rate in bench(src, args.bodies, args.seconds, args.engine).items():
                best[side][name] = max(rate, best[side].get(name, 0.0))
    print(f"{'workload':10} {'baseline steps/s':>17} {'this steps/s':>13} {'this/baseline':>14}")
    for name, rate in best["this"].items():
        before = best["baseline"].get(name)
        ratio = f"{rate / before:14.3f}" if before else f"{'-':>14}"
        print(f"{name:10} {before or 0.0:17,.0f} {rate:13,.0f} {ratio}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
