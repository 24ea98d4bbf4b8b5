"""Writing scenarios: every problem at once with its line, templates to start from, warnings.

``acphys check`` (and ``run``) report every independent problem of a scenario, one line each,
with the key path, the TOML line and the body or event it belongs to; what only depends on a
part that already failed says nothing more. ``acphys show NAME`` prints a built-in scenario or
motion table. Things that load but look like mistakes are warnings.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import acphys
from acphys.cli import main
from acphys.scenario import ScenarioError, builtin_scenarios

THREE_MISTAKES = """\
[scenario]
name = "three"
duration = 2.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[body]]
name = "walker"
landblock = "0xA9B4"
origin = [96.0, 96.0]
on_ground = true

[[body]]
name = "runner"
landblock = "0xA9B4"
origin = [90.0, 96.0, 50.0]
friction = 2.0

[[event]]
at = 0.5
body = "runner"
action = "motoin"
"""


def test_check_reports_three_independent_mistakes_on_three_lines(tmp_path: Path, capsys) -> None:
    path = tmp_path / "three.toml"
    path.write_text(THREE_MISTAKES, encoding="utf-8")
    code = main(["check", str(path)])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert err.splitlines() == [
        f"acphys: error: {path}: body[0].origin: expected a list of 3 numbers, got a list of 2 "
        "(line 12, body 'walker')",
        f"acphys: error: {path}: body[1].friction: expected a number in [0, 1], got 2 "
        "(line 19, body 'runner')",
        f"acphys: error: {path}: event[0].action: unknown action 'motoin' (expected one of: set_velocity, "
        "set_omega, set_state, motion, stop_motion, jump, move_to, turn_to, move_to_object, turn_to_object, "
        "interpolate_to, stick_to, unstick, constrain_to, unconstrain, play_script, set_parent, "
        "unset_parent) (line 24, motoin of 'runner')",
    ]


def test_what_depends_on_a_failed_part_says_nothing_more() -> None:
    # The setup is broken: the body using it and the event for the body add no lines of their own.
    text = THREE_MISTAKES.replace("friction = 2.0\n", 'setup = "crate"\n').replace("motoin", "jump")
    text += "[setup.crate]\nspheres = [{ center = [0.0, 0.0, 0.5], radius = -1.0 }]\n"
    with pytest.raises(ScenarioError) as caught:
        acphys.parse_scenario(text, source="s.toml")
    assert caught.value.problems == [
        "s.toml: setup.crate.spheres[0].radius: expected a number in (0, 1000], got -1 (line 26)",
        "s.toml: body[0].origin: expected a list of 3 numbers, got a list of 2 (line 12, body 'walker')",
    ]
    assert str(caught.value).splitlines() == caught.value.problems


def test_a_scenario_read_without_its_text_still_reports_every_problem() -> None:
    import tomllib

    document = tomllib.loads(THREE_MISTAKES)
    with pytest.raises(ScenarioError) as caught:
        acphys.scenario.build_scenario(document, source="doc")
    assert [p.split(":")[1].strip() for p in caught.value.problems] == [
        "body[0].origin",
        "body[1].friction",
        "event[0].action",
    ]
    assert all("(line" not in p for p in caught.value.problems)


@pytest.mark.parametrize("name", builtin_scenarios())
def test_show_prints_a_built_in_scenario_that_checks(name: str, tmp_path: Path, capsys) -> None:
    assert main(["show", name]) == 0
    text = capsys.readouterr().out
    path = tmp_path / "copy.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["check", str(path)]) == 0
    assert capsys.readouterr().out.startswith(f"ok: {name}:")


def test_show_prints_a_motion_table_a_scenario_can_use(capsys) -> None:
    assert main(["show", "humanoid"]) == 0
    section = capsys.readouterr().out.replace("motion_table.humanoid", "motion_table.mine")
    text = (
        '[scenario]\nname = "mine"\nduration = 1.0\n[[landblock]]\nid = "0xA9B4"\nheight = 50.0\n'
        '[[body]]\nname = "b"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 50.0]\non_ground = true\n'
        'motion_table = "mine"\n' + section
    )
    sim = acphys.parse_scenario(text, source="mine.toml")
    assert sim.body("b").movement_manager is not None


def test_show_and_run_name_the_built_ins_when_the_name_is_unknown(capsys) -> None:
    assert main(["show", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("acphys: error: nope: no built-in scenario or motion table (built-in: carry, ")
    assert "humanoid" in err
    assert main(["run", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("acphys: error: nope: no such file nor built-in scenario (built-in: carry, default")


WARNED = """\
[scenario]
name = "warn"
duration = 1.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[body]]
name = "far"
landblock = "A9B5"
origin = [10.0, 10.0, 50.0]
id = 50000001

[[body]]
name = "near"
landblock = 0xA9B4
origin = [10.0, 10.0, 50.0]
id = 0x50000002
"""


def test_warnings_for_landblocks_outside_the_world_and_ids_that_look_hex(tmp_path: Path, capsys) -> None:
    sim = acphys.parse_scenario(WARNED, source="w.toml")
    assert sim.warnings == [
        'w.toml: body[0].landblock: "A9B5" is read as hex, 0xA9B5: write "0xA9B5" to say so '
        "(line 11, body 'far')",
        'w.toml: body[0].id: 50000001 is read as decimal, 0x2FAF081: write "0x50000001" if hex was meant '
        "(line 13, body 'far')",
        "w.toml: body[0].landblock: 0xA9B5 is none of the declared landblocks (0xA9B4): no terrain there "
        "(line 11, body 'far')",
    ]
    # The second body's hex literals and declared landblock raise nothing.
    path = tmp_path / "w.toml"
    path.write_text(WARNED, encoding="utf-8")
    assert main(["check", str(path)]) == 0
    out, err = capsys.readouterr()
    assert out.startswith("ok: warn:")
    assert [line.split(": ", 2)[1] for line in err.splitlines()] == ["warning"] * 3


def test_a_world_without_landblocks_warns_of_nothing() -> None:
    text = '[scenario]\nname = "void"\n[[body]]\nname = "b"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 1.0]\n'
    assert acphys.parse_scenario(text).warnings == []
