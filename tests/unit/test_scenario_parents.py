"""The set_parent / unset_parent events and setup holding locations, on the built-in "carry" scenario.

The porter holds the lantern at holding location 1, (0.7, 0.3, 1.1) from its own frame
(CPhysicsObj::set_parent @ 0x00515A90, acclient.c:322951; add_child @ 0x0050F870, 316728), and
lets go at 2 s (unset_parent @ 0x00513470, 320479); a set_velocity at 2.05 s tosses it.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import acphys
from acphys.precision import f32
from support import step_records

HAND = (0.7, 0.3, 1.1)


@pytest.fixture(scope="module")
def records(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[dict]]:
    trace = tmp_path_factory.mktemp("carry") / "carry.jsonl"
    acphys.load_scenario("carry").run(trace=trace)
    result: dict[str, list[dict]] = {}
    for record in step_records(Path(trace)):
        result.setdefault(record["body"], []).append(record)
    return result


def test_while_held_the_lantern_is_at_the_hand_and_takes_no_steps() -> None:
    sim = acphys.load_scenario("carry")
    steps: list[float] = []
    sim.body("lantern").observer = lambda _body, quantum: steps.append(quantum)
    for until in (0.5, 1.0, 1.9):
        sim.run(until=until)
        porter, lantern = sim.body("porter"), sim.body("lantern")
        assert lantern.parent is porter
        # Heading 0 is the identity rotation, so the hand is at the porter's origin + HAND, each
        # sum stored as a float (Frame::combine, acclient.c:319448).
        expected = tuple(f32(a + f32(b)) for a, b in zip(porter.position.frame.origin, HAND, strict=True))
        assert tuple(lantern.position.frame.origin) == expected
        assert lantern.position.objcell_id == porter.position.objcell_id
    assert sim.body("porter").position.frame.origin.y > 80.0 + 5.0  # it walked on, carrying it
    assert steps == []


def test_the_trace_shows_the_hold_and_the_release(records) -> None:
    porter, lantern = records["porter"], records["lantern"]
    assert "holds:lantern" in porter[0]["events"]
    # No record while held: the first comes with the first step after the release at 2 s.
    assert lantern[0]["t"] > 2.0
    assert {"set_parent:porter", "unset_parent"} <= set(lantern[0]["events"])
    # Let go where the hand was at the last porter step before 2 s.
    released = max((r for r in porter if r["t"] <= 2.0), key=lambda r: r["t"])
    expected = [f32(a + f32(b)) for a, b in zip(released["origin"], HAND, strict=True)]
    assert lantern[0]["origin"] == expected
    # unset_parent cleared the transient states; nothing wakes it before the toss.
    assert lantern[0]["transient"] == []


def test_the_tossed_lantern_lands_and_rests_on_the_ground(records) -> None:
    lantern = records["lantern"]
    last = lantern[-1]
    assert {"contact", "on_walkable"} <= set(last["transient"])
    assert last["origin"][2] == pytest.approx(50.0, abs=1e-9)  # the sphere (r 0.1, centre 0.1 up) on z 50
    assert last["origin"][0] > 96.7 + 2.0  # thrown east
    assert all(r["origin"][2] >= 50.0 - 1e-9 for r in lantern)


def test_holding_ones_holder_is_refused_in_the_trace(tmp_path: Path) -> None:
    text = """
[scenario]
duration = 1.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[body]]
name = "a"
landblock = "0xA9B4"
origin = [96.0, 96.0, 50.0]

[[body]]
name = "b"
landblock = "0xA9B4"
origin = [90.0, 96.0, 50.0]

[[event]]
at = 0.1
body = "b"
action = "set_parent"
target = "a"
origin = [0.7, 0.0, 1.0]

[[event]]
at = 0.5
body = "a"
action = "set_parent"
target = "b"
"""
    trace = tmp_path / "cycle.jsonl"
    sim = acphys.parse_scenario(text, source="cycle.toml")
    sim.run(trace=trace)
    events = [e for record in step_records(trace) for e in record["events"]]
    assert "set_parent:b:cycle" in events
    assert sim.body("b").parent is sim.body("a") and sim.body("a").parent is None
