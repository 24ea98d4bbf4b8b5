"""``on_ground = true`` means on the ground: the body is dropped onto what is under it, never hovers."""

from __future__ import annotations

import pytest

import acphys
from acphys.flags import TransientState
from acphys.precision import f32
from acphys.scenario import ScenarioError

FLAT = '[scenario]\nname = "g"\nduration = 1.0\n[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'


def _body(z: float, extra: str = "") -> str:
    return (
        f'[[body]]\nname = "h"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, {z}]\non_ground = true\n{extra}'
    )


def _on_walkable(body: acphys.PhysicsObj) -> bool:
    return bool(
        body.transient_state & TransientState.CONTACT and body.transient_state & TransientState.ON_WALKABLE
    )


def test_a_body_declared_on_the_ground_above_it_is_put_on_it() -> None:
    sim = acphys.parse_scenario(FLAT + _body(50.3), source="g.toml")
    body = sim.body("h")
    # The human's sphere 0 (centre 0.475, radius 0.48) rests on the terrain: its origin 0.005 up.
    assert body.position.frame.origin.z == f32(50.005)
    assert _on_walkable(body)
    assert body.contact_plane.N.z == 1.0 and body.contact_plane.d == -50.0
    sim.run()
    assert body.position.frame.origin.z == f32(50.005)
    assert _on_walkable(body)


def test_a_body_on_a_box_is_put_on_its_top() -> None:
    text = FLAT + (
        "[setup.crate]\nboxes = [{ min = [-1.0, -1.0, 0.0], max = [1.0, 1.0, 0.5] }]\n"
        '[[object]]\nname = "crate"\nsetup = "crate"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 50.0]\n'
    )
    body = acphys.parse_scenario(text + _body(50.8), source="g.toml").body("h")
    assert body.position.frame.origin.z == pytest.approx(50.505, abs=1e-5)
    assert _on_walkable(body)


@pytest.mark.parametrize("z", [49.9, 45.0, -100.0])
def test_a_body_below_the_terrain_is_lifted_onto_it(z: float) -> None:
    # Retail's own placement (SetPosition with PLACEMENT, enter_world) lifts it: no harness step.
    body = acphys.parse_scenario(FLAT + _body(z), source="g.toml").body("h")
    assert body.position.frame.origin.z == pytest.approx(50.005, abs=1e-5)
    assert _on_walkable(body)


def test_a_body_too_far_above_the_ground_is_refused_naming_the_gap() -> None:
    with pytest.raises(ScenarioError, match=r"body\[0\]\.origin: on_ground, but 3 m above the terrain"):
        acphys.parse_scenario(FLAT + _body(53.0), source="g.toml")


def test_a_body_whose_drop_is_blocked_is_refused_saying_so() -> None:
    # Humans declared in layers on a 3 x 3 grid of spots 2 m apart (as the old mixed bench stacked
    # its house walkers): the 59th's drop onto the terrain right under it meets the 6 humans
    # already standing there and finds no ground. Not "out of reach" (the old message): it is
    # 0 m above the terrain.
    text = FLAT
    for n in range(63):
        x, y = 130.0 + (n % 3) * 2.0, 150.0 + (n // 3 % 3) * 2.5
        text += f'[[body]]\nname = "m{n}"\nlandblock = "0xA9B4"\norigin = [{x}, {y}, 50.0]\n'
        text += "on_ground = true\n"
    blocked = r"body\[58\]\.origin: on_ground, but its drop onto the terrain 0 m below \(z 50\) finds nothing"
    with pytest.raises(ScenarioError, match=blocked):
        acphys.parse_scenario(text, source="g.toml")


def test_without_terrain_the_body_stands_on_a_level_floor_at_its_origin() -> None:
    text = '[scenario]\nname = "void"\nduration = 1.0\n' + _body(12.0)
    body = acphys.parse_scenario(text, source="void.toml").body("h")
    assert body.position.frame.origin.z == 12.0
    assert _on_walkable(body)
    assert body.contact_plane.d == -12.0
