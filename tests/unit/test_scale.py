"""Building is linear in bodies and bodies share what retail shares (issue 13).

Retail objects of one setup share the cached DAT ``CSetup`` and ``CMotionTable``; each keeps its
own state in its part array, sequence and ``MotionTableManager``. acphys looks each name up
once. The figures (seconds for 10,000 bodies, kilobytes a walker) are in
``benchmarks/scale.py``, not here.
"""

from __future__ import annotations

from acphys.scenario import parse_scenario

TEXT = """
[scenario]
name = "share"
duration = 1.0
[[landblock]]
id = "0xA9B4"
height = 50.0
[[body]]
name = "a"
landblock = "0xA9B4"
origin = [90.0, 90.0, 50.0]
on_ground = true
[[body]]
name = "b"
landblock = "0xA9B4"
origin = [100.0, 90.0, 50.0]
on_ground = true
motion_table = "humanoid"
[[body]]
name = "c"
landblock = "0xA9B4"
origin = [110.0, 90.0, 50.0]
on_ground = true
[[event]]
at = 0.0
body = "a"
action = "motion"
motion = "RunForward"
hold_run = true
"""


def test_bodies_of_one_setup_and_table_share_them_and_keep_their_own_state() -> None:
    sim = parse_scenario(TEXT)
    a, b, c = (sim.body(name) for name in "abc")
    managers = [body.part_array.motion_table_manager for body in (a, b, c)]
    assert managers[0].table is managers[1].table is managers[2].table
    assert a.part_array.setup is c.part_array.setup
    assert len({id(manager) for manager in managers}) == 3
    assert len({id(manager.state) for manager in managers}) == 3
    sim.run()
    # a ran; b and c, of the same table, stood still in their own state
    assert a.position.frame.origin.y > 92.0
    assert b.position.frame.origin.y == c.position.frame.origin.y == 90.0
    assert managers[0].state.substate != managers[2].state.substate
