"""Fingerprint every body-step of the bundled scenarios and the bench workloads.

A performance change must not change behaviour: run this before and after
and compare the digests (they must be identical)::

    .venv/bin/python benchmarks/fingerprint.py > before.txt
    ... change ...
    .venv/bin/python benchmarks/fingerprint.py | diff before.txt -

Each line is a scenario's name, its body-step count and a SHA-256 over the
exact bits (``float.hex``) of every body's origin, orientation, velocities,
omega, cell, transient flags and events after every step.
"""

from __future__ import annotations

import hashlib
import sys

from acphys.bench import WORKLOADS
from acphys.scenario import builtin_scenarios, load_scenario
from acphys.simulation import Simulation


def fingerprint(sim: Simulation) -> tuple[int, str]:
    """Run ``sim`` to its end; return the body-step count and the digest of every step."""
    digest = hashlib.sha256()
    steps = 0

    def record(body: object, _quantum: float) -> None:
        nonlocal steps
        steps += 1
        frame = body.position.frame
        values = (
            *frame.origin,
            frame.qw,
            frame.qx,
            frame.qy,
            frame.qz,
            *body.velocity,
            *body.cached_velocity,
            *body.omega,
        )
        digest.update(body.name.encode())
        digest.update(" ".join(float(v).hex() for v in values).encode())
        digest.update(f"{body.position.objcell_id:08X}{int(body.transient_state)}".encode())
        digest.update(repr(body.step_events).encode())

    for body in sim.bodies:
        body.observer = record
    sim.run()
    return steps, digest.hexdigest()


def main() -> None:
    for name in builtin_scenarios():
        steps, digest = fingerprint(load_scenario(name))
        print(f"{name:28s} {steps:7d} {digest}")
    for name, (_description, build) in WORKLOADS.items():
        steps, digest = fingerprint(build(100, 3.0))
        print(f"bench-{name:22s} {steps:7d} {digest}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
