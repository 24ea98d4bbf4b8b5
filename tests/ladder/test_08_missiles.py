"""Ladder rung 8: missiles hit a pillar (cylsphere) and a sphere object; each collision is reported once.

The arrows fly east at 12 m/s: 12·dt = 0.40000002 m a step (dt = f32(1/30)), which
``CTransition::calc_num_steps`` (acclient.c:311763) cuts into ceil(4.0000002) = 5 sub-steps of
0.08 m, one more than the nominal 0.4/0.1 because dt is float32.
"""

from __future__ import annotations

import pytest

import acphys
from acphys.flags import PhysicsState
from acphys.physics_obj import CollisionKind, CollisionReport, PhysicsObj
from acphys.precision import f32
from support import walk_tolerance

DT = f32(1.0 / 30.0)
SPEED = 12.0


class _Run:
    """The scenario run step by step, with every report and every body's per-step state kept."""

    def __init__(self) -> None:
        self.sim = acphys.load_scenario("ladder-08-missiles")
        self.reports: list[tuple[float, str, CollisionReport]] = []
        self.steps: dict[str, list[tuple[float, float, float, list[str]]]] = {}
        for body in self.sim.bodies:
            body.on_collision = self._on_collision
            body.observer = self._observe
        self.sim.run()

    def _on_collision(self, body: PhysicsObj, report: CollisionReport) -> None:
        self.reports.append((body.world.physics_time, body.name, report))

    def _observe(self, body: PhysicsObj, quantum: float) -> None:
        origin = body.position.frame.origin
        self.steps.setdefault(body.name, []).append(
            (body.world.physics_time, origin.x, body.velocity.x, list(body.step_events))
        )

    def reports_to(self, name: str) -> list[tuple[float, CollisionKind, str]]:
        return [
            (t, r.kind, r.other.name if r.other is not None else "") for t, n, r in self.reports if n == name
        ]


@pytest.fixture(scope="module")
def run() -> _Run:
    return _Run()


def _hit_step(steps: list[tuple[float, float, float, list[str]]]) -> int:
    return next(i + 1 for i, s in enumerate(steps) if s[3])


def test_the_missile_stops_at_the_pillar_and_reports_the_environment_once(run: _Run) -> None:
    arrow = run.steps["arrow-1"]
    # Pillar face at x = 100 - 1 = 99; a 0.1-m sphere touches it past x = 98.9. Step 23 starts at
    # 90 + 22·0.4 = 98.8; its sub-steps are 98.88 (clear) and 98.96 (hits): a PATH_CLIPPED sweep
    # stops at the last clear sub-step (CTransition::find_transitional_position, acclient.c:313170).
    assert _hit_step(arrow) == 23
    t_hit, x_hit, vx_hit, events = arrow[22]
    # 111 float32 sub-step stores (five 0.08-m sub-steps a step) near 95 m, each rounding the
    # same way: within their drift of the double sum.
    assert x_hit == pytest.approx(90.0 + 22 * SPEED * DT + SPEED * DT / 5, abs=walk_tolerance(98.88, 111))
    # Bounce off the side normal (-1, 0, 0): v = -e·12 with the default e = 0.05
    # (CPhysicsObj::handle_all_collisions, acclient.c:321807).
    assert vx_hit == pytest.approx(-0.05 * SPEED, rel=1e-6)
    # A static object reports as the environment (CPhysicsObj::track_object_collision,
    # acclient.c:321216), once: colliding_with_environment holds until a step without it
    # (CPhysicsObj::report_environment_collision, acclient.c:320193).
    assert events == ["collision:environment"]
    assert [e for s in arrow for e in s[3]] == ["collision:environment"]
    assert run.reports_to("arrow-1") == [(t_hit, CollisionKind.ENVIRONMENT, "")]
    # No longer a missile, and it drifts back west at 0.6 m/s (0.02 m a step).
    assert not run.sim.body("arrow-1").state & PhysicsState.MISSILE
    drift_steps = len(arrow) - 23
    assert arrow[-1][1] == pytest.approx(
        x_hit - drift_steps * 0.05 * SPEED * DT, abs=walk_tolerance(x_hit, drift_steps)
    )


def test_the_missile_hits_the_orb_and_both_hear_of_it_once(run: _Run) -> None:
    arrow = run.steps["arrow-2"]
    # Orb face at x = 100 - 0.5 = 99.5; the arrow touches it past 99.4. Step 24 starts at 99.2:
    # sub-steps 99.28, 99.36 (clear), 99.44 (hits): the arrow stops at 99.36 (acclient.c:313170).
    assert _hit_step(arrow) == 24
    t_hit, x_hit, vx_hit, events = arrow[23]
    assert x_hit == pytest.approx(99.36, abs=walk_tolerance(99.36, 118))
    # The sphere-sphere normal runs from the orb's centre to the arrow's: (-1, 0, 0).
    assert vx_hit == pytest.approx(-0.05 * SPEED, rel=1e-6)
    assert events == ["collision:orb"]
    # The missile hears an ATTACK report and the orb an OBJECT one
    # (CPhysicsObj::report_object_collision, acclient.c:320227), each once: the collision table
    # keeps the orb's record (CPhysicsObj::track_object_collision, acclient.c:321216).
    starts = [(t, n, r.kind) for t, n, r in run.reports if r.kind is not CollisionKind.END]
    t_pillar = run.steps["arrow-1"][22][0]
    assert starts == [
        (t_pillar, "arrow-1", CollisionKind.ENVIRONMENT),
        (t_hit, "arrow-2", CollisionKind.ATTACK),
        (t_hit, "orb", CollisionKind.OBJECT),
    ]
    assert run.reports_to("orb")[0] == (t_hit, CollisionKind.OBJECT, "arrow-2")
    # The orb never moves: it is not a missile, has no gravity and was not pushed.
    assert all(s[1] == 100.0 and s[2] == 0.0 for s in run.steps["orb"])


def test_the_orb_record_expires_after_one_second(run: _Run) -> None:
    arrow = run.steps["arrow-2"]
    t_hit = arrow[23][0]
    # report_collision_end (acclient.c:321712) drops a record untouched for more than 1 s, at the
    # first committed step after that, and both bodies hear the END once.
    end_step = next(i for i, s in enumerate(arrow) if s[0] - t_hit > 1.0)
    assert arrow[end_step][3] == ["collision_end:orb"]
    ends = [(t, n) for t, n, r in run.reports if r.kind is CollisionKind.END]
    t_end = arrow[end_step][0]
    assert ends == [(t_end, "arrow-2"), (t_end, "orb")]
