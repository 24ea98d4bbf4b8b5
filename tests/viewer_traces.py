"""Synthetic traces for the viewer's tests: many bodies for many seconds without running the physics.

Every record has every field an acphys trace writes, with values as varied as a real run's or more
(float32 positions on a random walk, a turning orientation, velocities that change every step,
motion frames that count up), so the page sizes measured from them are an upper bound for real
runs of the same length, where resting bodies repeat themselves and compress to little.
"""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import numpy as np

MOTIONS = ("Ready", "WalkForward", "RunForward", "TurnRight")


def f32(value: float) -> float:
    return float(np.float32(value))


def write_synthetic_trace(path: Path, bodies: int, seconds: float, hz: float = 30.0, seed: int = 1) -> int:
    """Write a trace of ``bodies`` bodies for ``seconds`` at ``hz`` steps a second; returns the records."""
    rnd = random.Random(seed)
    steps = round(seconds * hz)
    state = []
    for i in range(bodies):
        state.append(
            {
                "x": 10.0 + (i % 10) * 17.0 + rnd.random(),  # a grid within the landblock
                "y": 10.0 + (i // 10 % 10) * 17.0 + rnd.random(),
                "z": 50.0,
                "heading": rnd.uniform(0, 2 * math.pi),
                "speed": rnd.choice((0.0, 1.5, 4.0)),
                "motion": rnd.randrange(len(MOTIONS)),
                "frame": 0.0,
            }
        )
    count = 0
    with path.open("w", encoding="utf-8") as out:
        header = {
            "schema": "acphys.trace/2",
            "acphys": "0.1.0",
            "engine": "reference",
            "driver_hz": 60.0,
            "scenario": {"name": "synthetic", "sha256": "0" * 64},
        }
        out.write(json.dumps(header) + "\n")
        for step in range(steps + 1):
            t = step / hz
            for i, s in enumerate(state):
                events: list[str] = []
                if step:
                    s["heading"] += rnd.uniform(-0.08, 0.08)
                    if rnd.random() < 0.01:
                        s["speed"] = rnd.choice((0.0, 1.5, 4.0))
                        s["motion"] = rnd.randrange(len(MOTIONS))
                        events.append(f"motion:{MOTIONS[s['motion']]}")
                    s["x"] = min(180.0, max(5.0, s["x"] + math.sin(s["heading"]) * s["speed"] / hz))
                    s["y"] = min(180.0, max(5.0, s["y"] + math.cos(s["heading"]) * s["speed"] / hz))
                    s["z"] = 50.0 + 0.05 * math.sin(t + i)
                    s["frame"] = (s["frame"] + 1.0) % 30.0
                    if rnd.random() < 0.004:
                        events += (
                            ["leave_ground"]
                            if rnd.random() < 0.5
                            else ["hit_ground", "collision:environment"]
                        )
                half = -s["heading"] / 2.0
                velocity = [
                    f32(math.sin(s["heading"]) * s["speed"]),
                    f32(math.cos(s["heading"]) * s["speed"]),
                    0.0,
                ]
                record = {
                    "t": t,
                    "body": f"body-{i}",
                    "id": f"0x{0x80000001 + i:08X}",
                    "quantum": 1.0 / hz if step else 0.0,
                    "cell": f"0xA9B4{8 * int(s['x'] // 24) + int(s['y'] // 24) + 1:04X}",
                    "origin": [f32(s["x"]), f32(s["y"]), f32(s["z"])],
                    "orientation": [f32(math.cos(half)), 0.0, 0.0, f32(math.sin(half))],
                    "heading": f32(math.degrees(s["heading"]) % 360.0),
                    "velocity": velocity,
                    "cached_velocity": velocity,
                    "omega": [0.0, 0.0, f32(rnd.uniform(-0.1, 0.1))],
                    "transient": ["contact", "on_walkable", "active"],
                    "contact_normal": [0.0, 0.0, 1.0],
                    "motion": {
                        "style": "NonCombat",
                        "forward": MOTIONS[s["motion"]],
                        "forward_speed": 1.0,
                        "sidestep": None,
                        "sidestep_speed": 1.0,
                        "turn": None,
                        "turn_speed": 1.0,
                        "hold_key": "run",
                        "animation": f"motion_table.humanoid.cycle[{s['motion']}]",
                        "frame": s["frame"],
                    },
                    "events": events,
                }
                out.write(json.dumps(record) + "\n")
                count += 1
    return count
