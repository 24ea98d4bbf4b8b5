"""A seeded corpus of random worlds for comparing the two engines.

Each seed gives one scenario: one or two landblocks of random rolling terrain (sometimes with a
wet corner), a few pillars, and a mix of bodies: balls thrown in every direction with random
spin, friction and elasticity (some inelastic, some missiles), balls dropped into a pile, humans
standing, walking, running, turning and jumping, and a small crowd walking into each other.
"""

from __future__ import annotations

import random


def _heights(rng: random.Random) -> list[int]:
    base = rng.randint(20, 60)
    slope_x, slope_y = rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)
    return [
        max(0, min(200, int(base + slope_x * x + slope_y * y + rng.randint(-2, 2))))
        for x in range(9)
        for y in range(9)
    ]


def _vector(values: tuple[float, ...]) -> str:
    return "[" + ", ".join(f"{v:.3f}" for v in values) + "]"


def random_scenarios(seed: int, duration: float = 4.0) -> str:
    """The scenario text of corpus world ``seed``."""
    rng = random.Random(seed)
    blocks = ["0xA9B4"] if rng.random() < 0.6 else ["0xA9B4", "0xAAB4"]
    driver_hz = rng.choice([30.0, 60.0, 45.0])
    parts = [f'[scenario]\nname = "corpus-{seed}"\nduration = {duration}\ndriver_hz = {driver_hz}\n']
    for block in blocks:
        parts.append(f'[[landblock]]\nid = "{block}"\nheights = {_heights(rng)}\n')
        if rng.random() < 0.3:
            words = [0x44 if x < 3 and y < 3 else 0x04 for x in range(9) for y in range(9)]
            parts.append(f"water = {words}\n")
    parts.append("[setup.ball]\nspheres = [{ center = [0, 0, 0.2], radius = 0.2 }]\n")
    parts.append(
        "[setup.pair]\nspheres = [{ center = [0, 0, 0.3], radius = 0.3 },"
        " { center = [0, 0, 0.9], radius = 0.3 }]\n"
    )
    parts.append("[setup.pillar]\ncylspheres = [{ low_pt = [0, 0, 0], radius = 0.8, height = 4.0 }]\n")
    for n in range(rng.randint(0, 2)):
        x, y = rng.uniform(30, 160), rng.uniform(30, 160)
        parts.append(
            f'[[object]]\nname = "pillar-{n}"\nsetup = "pillar"\nlandblock = "{blocks[0]}"\n'
            f"origin = [{x:.2f}, {y:.2f}, 0.0]\n"
        )
    events: list[str] = []
    count = rng.randint(4, 14)
    for n in range(count):
        block = rng.choice(blocks)
        kind = rng.choice(["thrown", "thrown", "dropped", "pair", "human", "walker"])
        x, y = rng.uniform(8, 184), rng.uniform(8, 184)
        name = f"{kind}-{n}"
        body = f'[[body]]\nname = "{name}"\nlandblock = "{block}"\n'
        if kind in ("thrown", "dropped", "pair"):
            z = rng.uniform(70, 140)
            state = ['"gravity"', '"report_collisions"']
            if rng.random() < 0.2:
                state.append('"inelastic"')
            if rng.random() < 0.15:
                state.append('"missile"')
            if rng.random() < 0.3:
                state.append('"edge_slide"')
            velocity = (0.0, 0.0, 0.0)
            if kind != "dropped":
                velocity = (rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(-5, 15))
            omega = (0.0, 0.0, 0.0)
            if rng.random() < 0.5:
                omega = (rng.uniform(-90, 90), rng.uniform(-90, 90), rng.uniform(-180, 180))
            body += (
                f'setup = "{"pair" if kind == "pair" else "ball"}"\n'
                f"origin = [{x:.2f}, {y:.2f}, {z:.2f}]\nstate = [{', '.join(state)}]\n"
                f"velocity = {_vector(velocity)}\nomega = {_vector(omega)}\n"
                f"friction = {rng.uniform(0.0, 1.0):.3f}\nelasticity = {rng.uniform(0.0, 0.1):.3f}\n"
                f"heading = {rng.uniform(0, 360):.1f}\n"
            )
        else:
            body += f"origin = [{x:.2f}, {y:.2f}, 200.0]\nheading = {rng.uniform(0, 360):.1f}\n"
            if kind == "walker":
                motion = rng.choice(["WalkForward", "WalkBackwards", "SideStepRight", "TurnLeft"])
                events.append(
                    f'[[event]]\nat = {rng.uniform(0.0, 1.0):.2f}\nbody = "{name}"\naction = "motion"\n'
                    f'motion = "{motion}"\nhold_run = {"true" if rng.random() < 0.5 else "false"}\n'
                )
                if rng.random() < 0.4:
                    at = rng.uniform(1.0, 3.0)
                    jump = f'at = {at:.2f}\nbody = "{name}"\naction = "jump"\nextent = 0.5\n'
                    events.append(f"[[event]]\n{jump}")
        parts.append(body)
    return "".join(parts) + "".join(events)
