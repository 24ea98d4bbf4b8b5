"""The data ``acphys view --html`` embeds: the scene, the records and the page around them.

The page itself is drawn in a real browser by ``tests/browser/test_viewer_browser.py``; here the
description and blob it carries are read back (:func:`acphys.viewer.page.read_page`) and checked
against the world and the trace they came from.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import acphys
from acphys.cli import main
from acphys.scenario import load_scenario
from acphys.trace import TraceError, read_trace
from acphys.viewer import is_trace, records, write_html
from acphys.viewer.page import FORMAT, array_of, body_columns, read_page
from acphys.viewer.scene import gather_scene
from viewer_traces import write_synthetic_trace

MB = 1_000_000


@pytest.fixture(scope="module")
def yard(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """The yard run to its end: its trace, and the page made from the scenario."""
    folder = tmp_path_factory.mktemp("yard")
    trace = folder / "yard.jsonl"
    load_scenario("yard").run(trace=trace)
    page = folder / "yard.html"
    assert main(["view", "yard", "--html", str(page)]) == 0
    return trace, page


def page_of(path: Path) -> tuple[dict, bytes]:
    return read_page(path.read_text(encoding="utf-8"))


def body_of(data: dict, name: str) -> dict:
    return next(body for body in data["bodies"] if body["name"] == name)


# -- the scene -----------------------------------------------------------------------------------


def test_the_yard_scene_is_its_walls_pillar_ledge_and_stairs(yard: tuple[Path, Path]) -> None:
    data, blob = page_of(yard[1])
    assert data["format"] == FORMAT
    assert data["base"] == {"landblock": "0xA9B4", "x": 0xA9, "y": 0xB4}
    scene = data["scene"]
    names = [o["name"] for o in scene["objects"]]
    assert names == ["north-wall", "south-wall", "east-wall", "west-wall", "pillar", "ledge", "stairs"]
    triangles = array_of(blob, scene["solids"]["triangles"]).reshape(-1, 3, 3)
    owner = array_of(blob, scene["solids"]["owner"])
    # Boxes are 12 triangles each: four walls, the ledge and the stairs' four steps.
    assert np.bincount(owner, minlength=7).tolist() == [12, 12, 12, 12, 0, 12, 48]

    def extent(index: int) -> list[list[float]]:
        points = triangles[owner == index].reshape(-1, 3)
        points = points.astype(float)
        return [points.min(axis=0).round(3).tolist(), points.max(axis=0).round(3).tolist()]

    # One landblock: the scene frame is its own, 0-192 m.
    assert extent(0) == [[80.0, 111.75, 50.0], [112.0, 112.25, 52.5]]  # north wall
    assert extent(2) == [[111.75, 80.0, 50.0], [112.25, 112.0, 52.5]]  # east wall: turned by heading 90
    assert extent(5) == [[86.0, 103.0, 50.0], [90.0, 105.0, 51.0]]  # ledge
    assert extent(6) == [[103.0, 86.0, 50.0], [105.0, 88.0, 51.2]]  # stairs
    cylinders = array_of(blob, scene["cylinders"]["values"]).reshape(-1, 5)
    assert cylinders.tolist() == [[96.0, 100.0, 50.0, 1.0, 3.0]]  # the pillar: low point, radius, height
    assert array_of(blob, scene["cylinders"]["owner"]).tolist() == [4]
    assert array_of(blob, scene["spheres"]["values"]).size == 0
    assert scene["shells"]["triangles"][2] == scene["rooms"]["triangles"][2] == 0


def test_terrain_is_the_worlds_vertices_cuts_and_water() -> None:
    sim = load_scenario("hills")
    scene = gather_scene(sim.world, (0xA9, 0xB4))
    (block,) = scene.terrain
    terrain = sim.world.landscape.get_landblock(0xA9B40000).terrain
    assert (block.x, block.y) == (0.0, 0.0)
    assert block.heights == [v.z for v in terrain.vertices]
    assert len(set(block.heights)) > 10  # hills
    assert 0 < sum(block.water) < 81  # a lake
    # The page rebuilds the triangles from heights and cuts as ConstructPolygons does (viewer.js).
    for cx in range(8):
        for cy in range(8):

            def v(ix: int, iy: int) -> tuple[float, float, float]:
                return (24.0 * ix, 24.0 * iy, block.heights[9 * ix + iy])

            sw, se, ne, nw = v(cx, cy), v(cx + 1, cy), v(cx + 1, cy + 1), v(cx, cy + 1)
            rebuilt = [sw, se, ne, sw, ne, nw] if block.cut[8 * cx + cy] else [sw, se, nw, ne, nw, se]
            polygons = terrain.cell_polygons(cx, cy)
            world = [(p.x, p.y, p.z) for poly in polygons for p in poly.vertices]
            assert rebuilt == world


def test_two_landblocks_sit_side_by_side_from_the_first() -> None:
    sim = load_scenario("seam")
    blocks = sorted(sim.world.landscape.landblocks())
    scene = gather_scene(sim.world, (min(b >> 8 for b in blocks), min(b & 0xFF for b in blocks)))
    assert sorted((t.landblock, t.x, t.y) for t in scene.terrain) == [
        (0xA9B4, 0.0, 0.0),
        (0xAAB4, 192.0, 0.0),
    ]


def test_a_house_has_a_translucent_shell_and_rooms_without_their_doorways() -> None:
    sim = load_scenario("house")
    scene = gather_scene(sim.world, (0xA9, 0xB4))
    kinds = [o.kind for o in scene.objects]
    assert kinds.count("building") == 1 and kinds.count("room") == 2
    assert len(scene.shells) > 0 and len(scene.rooms) > 0
    # Each room is a box of 6 faces (walls cut around doorways into more pieces); a doorway
    # (a portal) is an opening, not drawn.
    env = sim.world.landscape.env_cells(0xA9B4)
    expected = sum(
        len(poly.vertices) - 2
        for cell in env
        for poly in cell.structure.polygons
        if not any(poly is portal for portal in cell.structure.portals)
    )
    assert len(scene.rooms) // 9 == expected


# -- the records ---------------------------------------------------------------------------------


def test_the_records_are_the_traces(yard: tuple[Path, Path]) -> None:
    trace, page = yard
    data, blob = page_of(page)
    by_body: dict[str, list[dict]] = {}
    for _line, record in read_trace(trace):
        by_body.setdefault(record["body"], []).append(record)
    assert [b["name"] for b in data["bodies"]] == list(by_body)
    transient_names, motions = data["tables"]["transient"], data["tables"]["motion"]
    for name, expected in by_body.items():
        body = body_of(data, name)
        columns = body_columns(data, blob, body)
        assert body["records"] == len(expected) and body["stride"] == 1
        assert columns["t"].tolist() == [r["t"] for r in expected]  # float64: exact
        for key in ("origin", "orientation", "velocity", "cached_velocity", "omega"):
            assert columns[key].tolist() == [r[key] for r in expected]  # float32: exact
        assert [f"0x{cell:08X}" for cell in columns["cell"]] == [r["cell"] for r in expected]
        for mask, record in zip(columns["transient"], expected, strict=True):
            assert [n for bit, n in enumerate(transient_names) if mask >> bit & 1] == record["transient"]
        for index, frame, record in zip(columns["motion"], columns["frame"], expected, strict=True):
            motion = dict(record["motion"])
            assert frame == pytest.approx(motion.pop("frame"), abs=1e-6)
            assert motions[index] == motion
        normals = columns["contact_normal"]
        for normal, record in zip(normals, expected, strict=True):
            if record["contact_normal"] is None:
                assert np.isnan(normal).all()  # not in contact
            else:
                assert normal.tolist() == record["contact_normal"]
    # Events in the trace's order, each with its body, time and place (scene frame: the block's own).
    events = data["events"]
    names = [b["name"] for b in data["bodies"]]
    got = list(
        zip(
            [names[i] for i in array_of(blob, events["body"])],
            array_of(blob, events["t"]).tolist(),
            [events["strings"][i] for i in array_of(blob, events["text"])],
            array_of(blob, events["position"]).reshape(-1, 3).tolist(),
            strict=True,
        )
    )
    want = [(r["body"], r["t"], e, r["origin"]) for _l, r in read_trace(trace) for e in r["events"]]
    assert got == want
    assert {"hit_ground", "collision:environment", "motion:WalkForward"} <= {e for _b, _t, e, _p in got}
    assert data["time"] == [0.0, max(r["t"] for rs in by_body.values() for r in rs)]


def test_bodies_are_drawn_as_their_setups_spheres() -> None:
    sim = load_scenario("default")
    from acphys.viewer import _shapes

    shapes = _shapes(sim, [b.name for b in sim.bodies])
    assert shapes["walker"].spheres == [(0.0, 0.0, pytest.approx(0.475), pytest.approx(0.48))] * 1 + [
        (0.0, 0.0, pytest.approx(1.35), pytest.approx(0.48))
    ]
    assert shapes["walker"].source == "setup"
    assert shapes["ball"].spheres == [(0.0, 0.0, pytest.approx(0.1), pytest.approx(0.1))]
    # The spinner's setup has no spheres: its sorting sphere stands in.
    assert shapes["spinner"].source == "sorting" and len(shapes["spinner"].spheres) == 1


def test_thinned_when_over_the_record_budget(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    trace = tmp_path / "t.jsonl"
    count = write_synthetic_trace(trace, bodies=4, seconds=10.0)
    monkeypatch.setattr(records, "MAX_RECORDS", 500)
    warnings: list[str] = []
    collected = records.collect_records(trace, warn=warnings.append)
    kept = sum(len(b) for b in collected.bodies.values())
    assert kept <= 500 and kept < count
    strides = {b.stride for b in collected.bodies.values()}
    assert len(strides) == 1 and strides.pop() >= 2
    assert any("records" in w for w in warnings)
    # Kept records are every stride-th, in order, and every event is still there.
    body = collected.bodies["body-0"]
    all_t = [r["t"] for _l, r in read_trace(trace) if r["body"] == "body-0"]
    assert list(body.columns["t"]) == all_t[:: body.stride]
    assert len(collected.events) == sum(len(r["events"]) for _l, r in read_trace(trace))


def test_a_body_going_back_in_time_is_refused(tmp_path: Path) -> None:
    trace = tmp_path / "back.jsonl"
    rec = {"t": 1.0, "body": "a", "cell": "0xA9B40001", "origin": [1.0, 2.0, 3.0]}
    trace.write_text(json.dumps(rec) + "\n" + json.dumps({**rec, "t": 0.5}) + "\n")
    with pytest.raises(TraceError, match="back in time"):
        records.collect_records(trace)


def test_a_minimal_v1_record_is_enough(tmp_path: Path) -> None:
    trace = tmp_path / "v1.jsonl"
    trace.write_text(
        json.dumps({"t": 0.0, "body": "a", "cell": "0xA9B40001", "origin": [1.0, 2.0, 3.0]}) + "\n"
    )
    collected = records.collect_records(trace)
    columns = collected.bodies["a"].columns
    assert list(columns["orientation"]) == [1.0, 0.0, 0.0, 0.0]
    assert np.isnan(columns["velocity"]).all() and list(columns["motion"]) == [-1]


# -- the page ------------------------------------------------------------------------------------


def test_the_page_loads_nothing_from_anywhere(yard: tuple[Path, Path]) -> None:
    html = yard[1].read_text(encoding="utf-8")
    assert "Content-Security-Policy" in html and "default-src 'none'" in html
    assert not re.search(r"https?://|wss?://|//[a-z0-9.-]+\.[a-z]{2,}/", html, re.IGNORECASE)
    assert not re.search(r"<(link|img|iframe|object|embed|base)\b|\bsrc=|@import|url\(", html, re.IGNORECASE)
    assert not re.search(r"\bfetch\(|XMLHttpRequest|WebSocket|EventSource|sendBeacon", html)
    assert html.count("<script") == 3 and html.count("</script>") == 3


def test_names_cannot_break_out_of_the_page(tmp_path: Path) -> None:
    name = "</script><script>alert(1)</script><!--"
    trace = tmp_path / "evil.jsonl"
    record = {
        "t": 0.0,
        "body": name,
        "cell": "0xA9B40001",
        "origin": [1.0, 2.0, 3.0],
        "events": ["x</script>"],
    }
    trace.write_text(json.dumps(record) + "\n")
    page = tmp_path / "evil.html"
    write_html(str(trace), page)
    html = page.read_text(encoding="utf-8")
    assert html.count("</script>") == 3 and "<!--" not in html
    data, _blob = read_page(html)
    assert data["bodies"][0]["name"] == name and data["events"]["strings"] == ["x</script>"]


def test_the_same_run_gives_the_same_page(yard: tuple[Path, Path], tmp_path: Path) -> None:
    again = tmp_path / "again.html"
    write_html(str(yard[0]), again)  # from the trace: the header names the built-in yard
    data, _ = page_of(again)
    assert data["scene"] is not None and data["notes"] == []
    first = tmp_path / "one.html"
    write_html(str(yard[0]), first)
    assert first.read_bytes() == again.read_bytes()


def test_a_trace_alone_is_drawn_without_a_world(tmp_path: Path) -> None:
    trace = tmp_path / "syn.jsonl"
    write_synthetic_trace(trace, bodies=3, seconds=1.0)
    page = tmp_path / "syn.html"
    notes: list[str] = []
    result = write_html(str(trace), page, warn=notes.append)
    data, _ = page_of(page)
    assert data["scene"] is None and result.bodies == 3
    assert len(notes) == 1 and "no world" in notes[0] and data["notes"] == notes
    assert [data["shapes"][b["shape"]]["source"] for b in data["bodies"]] == ["unknown"] * 3
    assert len(data["shapes"]) == 1  # shared
    # With a scenario for its world: drawn in it (bodies it does not know stay markers).
    write_html(str(trace), page, scenario="yard")
    data, _ = page_of(page)
    assert len(data["scene"]["objects"]) == 7


@pytest.mark.parametrize(("bodies", "limit_mb"), [(20, 5.0), (100, 10.0)])
def test_page_size_for_20_seconds(tmp_path: Path, bodies: int, limit_mb: float) -> None:
    """20 s at 30 Hz: 12,000 records for 20 bodies, well under 5 MB (the issue's bound); 100 bodies
    stay well under 10 MB. The synthetic trace is noisier than a real run (which compresses better)."""
    trace = tmp_path / "big.jsonl"
    count = write_synthetic_trace(trace, bodies=bodies, seconds=20.0)
    assert count == bodies * 601
    result = write_html(str(trace), tmp_path / "big.html", scenario="yard")
    assert result.records == count
    print(f"{bodies} bodies x 20 s: {count:,} records, page {result.bytes / MB:.2f} MB")
    assert result.bytes < limit_mb * MB / 2


# -- the command line ----------------------------------------------------------------------------


def test_command_line(yard: tuple[Path, Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    trace = str(yard[0])
    out = tmp_path / "v.html"
    assert main(["view", trace, "--html", str(out), "--bodies", "walker,leaner"]) == 0
    data, _ = page_of(out)
    assert [b["name"] for b in data["bodies"]] == ["walker", "leaner"]
    assert "view:" in capsys.readouterr().out
    assert main(["view", "yard", "--html", str(out), "--until", "1.0"]) == 0
    assert page_of(out)[0]["time"][1] == pytest.approx(1.0, abs=0.04)
    capsys.readouterr()
    for argv, message in [
        (["view", trace, "--html", str(tmp_path / "v.txt")], ".html"),
        (["view", "yard", "--html", str(out), "--scenario", "yard"], "--scenario is for a trace"),
        (["view", "yard"], "text view reads a trace"),
        (["view", trace, "--scenario", "yard"], "--scenario is for --html"),
        (["view", trace, "--html", str(out), "--bodies", "nobody"], "nobody"),
        (["view", "no-such-scenario", "--html", str(out)], "no such file"),
        (["view", trace, "--html", str(out), "--until", "2"], "--until: is for a scenario"),
        (["view", trace, "--html", str(out), "--engine", "fast"], "--engine: is for a scenario"),
        (["view", "yard", "--html", str(out), "--until", "1e9"], "MAX_DRIVER_TICKS"),
        (["view", "yard", "--html", str(out), "--until", "nan"], "--until"),
    ]:
        assert main(argv) == 2, argv
        err = capsys.readouterr().err
        assert err.startswith("acphys: error:") and message in err, (argv, err)
    assert main(["view", trace]) == 0  # the text view is still there
    assert "walker" in capsys.readouterr().out


def test_is_trace(yard: tuple[Path, Path], tmp_path: Path) -> None:
    assert is_trace(str(yard[0]))
    assert not is_trace("yard")
    toml = tmp_path / "s.toml"
    toml.write_text(acphys.scenario.builtin_scenario_text("yard"))
    assert not is_trace(str(toml))
