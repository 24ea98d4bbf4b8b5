"""``acphys plot``, ``acphys run --plot`` and ``acphys view`` (README "The command line").

The pictures are made from a 4-s trace of the default scenario, long enough for the
drifter (2 m/s east from x = 186 in landblock 0xA9B4) to cross the seam into 0xAAB4, and
(issue 16) 1-s traces of yard, house and hills, whose worlds are drawn under their paths: the
tests read the figure's matplotlib artists (collections by gid, lines, texts, legends).
Nothing in acphys is mocked; matplotlib draws on its Agg canvas.
"""

from __future__ import annotations

import hashlib
import json
import re
import struct
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from acphys.cli import main
from acphys.constants import BLOCK_LENGTH
from acphys.plot import (
    VIEWS,
    BodyPath,
    PathCollector,
    PathRecorder,
    PlotError,
    PlotFrame,
    body_colours,
    global_xy,
    make_figure,
    plot_frame,
    read_paths,
    select_bodies,
    trace_world,
    write_plot,
)
from acphys.scenario import builtin_scenario_text, load_scenario
from acphys.view import ascii_map, summarise
from acphys.world_sketch import sketch_world
from support import step_records, ulp32

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
DEFAULT_BODIES = ("skydiver", "ball", "spinner", "drifter", "sitter", "walker", "runner")


def invoke(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_error_line(code: int, out: str, err: str) -> str:
    assert code == 2, (code, out, err)
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("acphys: error: "), err
    assert "Traceback" not in out + err
    return lines[0]


def assert_png(path: Path) -> tuple[int, int]:
    """A PNG matplotlib drew: the signature, a sensible size, and more than a blank canvas."""
    from matplotlib.image import imread

    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert data[12:16] == b"IHDR"
    width, height = struct.unpack(">II", data[16:24])
    assert width >= 300 and height >= 300, (width, height)
    pixels = imread(path)
    assert pixels.shape[:2] == (height, width)
    colours = {tuple(row) for row in pixels.reshape(-1, pixels.shape[2])[::7].round(2).tolist()}
    assert len(colours) > 20, len(colours)  # lines, markers, text: not an empty white figure
    not_white = (pixels[..., :3] < 0.95).any(axis=-1).mean()
    assert 0.01 < not_white < 0.6, not_white
    return width, height


@pytest.fixture(scope="module")
def trace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A 4-s trace of the default scenario, written by the command."""
    path = tmp_path_factory.mktemp("plot") / "default.jsonl"
    assert main(["run", "--trace", str(path), "--until", "4"]) == 0
    return path


def drifter_records(trace: Path) -> list[dict]:
    return [record for record in step_records(trace) if record["body"] == "drifter"]


# -- paths ------------------------------------------------------------------------------------


def test_global_xy_puts_each_landblock_at_192_m_times_its_x_y() -> None:
    assert global_xy(0xA9B4003D, 186.0, 100.0) == (0xA9 * BLOCK_LENGTH + 186.0, 0xB4 * BLOCK_LENGTH + 100.0)
    assert global_xy(0xAAB40005, 2.0, 100.0) == (0xAA * 192.0 + 2.0, 0xB4 * 192.0 + 100.0)
    assert global_xy(0xA9B40100, 5.0, 6.0) == (0xA9 * 192.0 + 5.0, 0xB4 * 192.0 + 6.0)  # an env cell


def test_the_drifter_crosses_the_seam_in_one_continuous_path(trace: Path) -> None:
    records = drifter_records(trace)
    assert records[0]["cell"].startswith("0xA9B4") and records[-1]["cell"].startswith("0xAAB4")
    path = read_paths(trace)["drifter"]
    for i in range(1, len(path)):  # 2 m/s: no 192-m jump at the seam
        # (the difference of two float32 landblock-local x up to 192 m)
        assert path.x[i] - path.x[i - 1] == pytest.approx(
            2.0 * (path.t[i] - path.t[i - 1]), abs=2 * ulp32(192.0)
        )
    assert set(path.y) == {0xB4 * 192.0 + 100.0}


def test_paths_recorded_in_memory_match_the_trace(trace: Path) -> None:
    sim = load_scenario()
    recorder = PathRecorder()
    recorder.attach(sim.bodies)
    sim.run(until=4.0)
    recorder.detach(sim.bodies)
    assert all(body.observer is None for body in sim.bodies)
    assert recorder.paths == read_paths(trace)


def one_sample_path() -> BodyPath:
    collector = PathCollector()
    collector.add({"t": 0.1, "body": "a", "cell": "0xA9B40001", "origin": [1.0, 2.0, 3.0]}, "x:1")
    return collector.paths["a"]


def test_unknown_bodies_are_named() -> None:
    with pytest.raises(PlotError, match=r"no body named 'nobody' in the trace \(it has: a\)"):
        select_bodies({"a": one_sample_path()}, ["nobody"])


# -- plot -------------------------------------------------------------------------------------


def test_plot_writes_a_png(trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "default.png"
    code, stdout, err = invoke(["plot", str(trace), "-o", str(out)], capsys)
    assert code == 0, err
    assert err == ""
    assert f"plot: {out}" in stdout
    width, height = assert_png(out)
    assert width > height  # two panels side by side


def test_the_figure_has_a_path_per_body_and_marks_events(trace: Path) -> None:
    figure = make_figure(read_paths(trace))
    top, height = figure.axes
    assert top.get_title() == "from above" and height.get_title() == "height over time"
    for ax in (top, height):
        labels = [line.get_label() for line in ax.get_lines() if not line.get_label().startswith("_")]
        assert labels == list(DEFAULT_BODIES)
    bodies, key = ([text.get_text() for text in legend.get_texts()] for legend in figure.legends)
    assert bodies == list(DEFAULT_BODIES)
    assert {"start", "end", "hit_ground", "collision", "leave_ground"} <= set(key)  # the key, below
    assert {"_hit_ground", "_collision", "_leave_ground"} <= {c.get_label() for c in top.collections}


def test_bodies_filters(trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    figure = make_figure(read_paths(trace), bodies=["drifter", "ball"])
    labels = [line.get_label() for line in figure.axes[0].get_lines() if not line.get_label().startswith("_")]
    assert labels == ["drifter", "ball"]
    every, two = tmp_path / "every.png", tmp_path / "two.png"
    assert invoke(["plot", str(trace), "-o", str(every)], capsys)[0] == 0
    code, _, err = invoke(["plot", str(trace), "-o", str(two), "--bodies", "drifter, ball"], capsys)
    assert code == 0, err
    assert_png(two)
    assert two.read_bytes() != every.read_bytes()


@pytest.mark.parametrize("view", VIEWS)
def test_view_picks_one_panel(
    view: str, trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    figure = make_figure(read_paths(trace), view=view)
    assert len(figure.axes) == 1
    assert figure.axes[0].get_title() == {"top": "from above", "side": "from the south"}.get(
        view, "height over time"
    )
    out = tmp_path / f"{view}.png"
    assert invoke(["plot", str(trace), "-o", str(out), "--view", view], capsys)[0] == 0
    assert_png(out)


def test_run_plot_draws_the_run(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run.png"
    code, stdout, err = invoke(["run", "--until", "1", "--plot", str(out)], capsys)
    assert code == 0, err
    assert f"plot: {out}" in stdout
    assert_png(out)
    traced = tmp_path / "traced.png"
    trace = tmp_path / "run.jsonl"
    code, _, err = invoke(["run", "--until", "1", "--trace", str(trace), "--plot", str(traced)], capsys)
    assert code == 0, err
    assert traced.read_bytes() == out.read_bytes()  # in memory or from the trace: the same picture


def test_run_plot_to_a_missing_directory_fails_before_running(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    line = assert_one_error_line(*invoke(["run", "--plot", str(tmp_path / "no" / "such.png")], capsys))
    assert "cannot write" in line


# -- bad input: one line, exit 2 ---------------------------------------------------------------


def test_plot_of_a_missing_trace(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    missing = tmp_path / "missing.jsonl"
    line = assert_one_error_line(*invoke(["plot", str(missing), "-o", str(tmp_path / "x.png")], capsys))
    assert str(missing) in line and "cannot open" in line
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(
    ("content", "problem"),
    [
        ("{not json\n", "not JSON"),
        ('{"t": 0.1, "body": "a", "cell": "0xA9B40001"}\n', "origin must be 3 numbers"),
        ('{"t": 0.1, "body": "a", "cell": "nowhere", "origin": [1, 2, 3]}\n', "cell must be a hex cell id"),
        ('{"t": "soon", "body": "a", "cell": "0xA9B40001", "origin": [1, 2, 3]}\n', "t must be a number"),
        ("\n", "no records"),
    ],
)
def test_a_malformed_trace_names_file_and_line(
    content: str, problem: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text(content, encoding="utf-8")
    for argv in (["plot", str(bad), "-o", str(tmp_path / "x.png")], ["view", str(bad)]):
        line = assert_one_error_line(*invoke(argv, capsys))
        assert str(bad) in line and problem in line, line


@pytest.mark.parametrize("bodies", ["drifter,nobody", ",", ""])
def test_bad_bodies(bodies: str, trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for argv in (["plot", str(trace), "-o", str(tmp_path / "x.png")], ["view", str(trace)]):
        line = assert_one_error_line(*invoke([*argv, f"--bodies={bodies}"], capsys))
        assert "'nobody'" in line if "nobody" in bodies else "at least one body" in line
    assert not (tmp_path / "x.png").exists()


def test_unwritable_output(trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    line = assert_one_error_line(*invoke(["plot", str(trace), "-o", str(tmp_path / "no" / "x.png")], capsys))
    assert "cannot write" in line
    line = assert_one_error_line(*invoke(["plot", str(trace), "-o", str(tmp_path)], capsys))
    assert "is a directory" in line


@pytest.mark.parametrize(
    "argv",
    [["plot"], ["plot", "t.jsonl"], ["plot", "t.jsonl", "-o", "x.png", "--view", "front"], ["view"]],
)
def test_bad_arguments(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert_one_error_line(*invoke(argv, capsys))


# -- view -------------------------------------------------------------------------------------


def test_view_prints_the_table_and_the_map(trace: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(["view", str(trace)], capsys)
    assert code == 0, err
    assert err == ""
    records = drifter_records(trace)
    expected = 2.0 * records[-1]["t"]  # 2 m/s east, from where it starts at t = 0 to its last step
    row = next(line for line in out.splitlines() if " drifter " in line)
    cells = [cell.strip() for cell in re.split(r"[│|]", row) if cell.strip()]
    assert cells[0] == "D drifter"
    assert cells[1].startswith("0xA9B4 186.0") and cells[2].startswith("0xAAB4 2.0")
    assert float(cells[3]) == pytest.approx(expected, abs=0.005)  # distance across the seam
    assert float(cells[4]) == pytest.approx(2.0, abs=0.005)  # max speed
    assert float(cells[5]) == 0.0  # never in contact
    for name in DEFAULT_BODIES:
        assert name in out
    # The map: a border, the drifter's trail ending at its symbol, the extent and a legend.
    assert re.search(r"^\+-+\+", out, re.MULTILINE)
    assert re.search(r"d+D\|", out)
    assert "landblock-global" in out
    assert "A skydiver  B ball  C spinner  D drifter" in out


def test_view_bodies(trace: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = invoke(["view", str(trace), "--bodies", "ball"], capsys)
    assert code == 0, err
    assert "A ball" in out and "drifter" not in out


def test_summary_counts_time_in_contact_and_events(trace: Path) -> None:
    paths = read_paths(trace)
    sitter = summarise(paths["sitter"])
    assert sitter.distance == 0.0 and sitter.max_speed == 0.0
    assert sitter.contact_time == pytest.approx(4.0, abs=1e-6)  # at rest on the ground throughout
    ball = summarise(paths["ball"])
    assert ball.events["hit_ground"] >= 1 and ball.events["collision"] >= 1
    skydiver = summarise(paths["skydiver"])
    assert skydiver.contact_time == 0.0 and skydiver.max_speed > 30.0


def test_a_body_at_rest_is_one_symbol_on_the_map(trace: Path) -> None:
    lines = [line.plain for line in ascii_map([read_paths(trace)["sitter"]], width=40, height=10)]
    grid = [line for line in lines if line.startswith("|")]
    assert "".join(grid).replace("|", "").strip() == "A"


# -- the world under the paths, the frame, markers, legends, title and formats (issue 16) --------


def run_trace(tmp_path_factory: pytest.TempPathFactory, scenario: str, until: str = "1") -> Path:
    path = tmp_path_factory.mktemp(scenario) / f"{scenario}.jsonl"
    assert main(["run", scenario, "--trace", str(path), "--until", until]) == 0
    return path


@pytest.fixture(scope="module")
def yard(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return run_trace(tmp_path_factory, "yard")


@pytest.fixture(scope="module")
def house(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return run_trace(tmp_path_factory, "house")


@pytest.fixture(scope="module")
def hills(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return run_trace(tmp_path_factory, "hills")


def trace_figure(trace: Path, **options: Any) -> Any:
    """The figure ``acphys plot`` draws of ``trace`` (its world from the header)."""
    found = trace_world(trace)
    return make_figure(read_paths(trace), title=found.title, world=found.world, **options)


def by_gid(ax: Any, gid: str) -> list[Any]:
    return [artist for artist in ax.collections if artist.get_gid() == gid]


def scatter(ax: Any, label: str) -> Any:
    (found,) = [artist for artist in ax.collections if artist.get_label() == label]
    return found


def test_a_one_landblock_run_is_drawn_in_its_landblock_metres(yard: Path) -> None:
    figure = trace_figure(yard, view="top")
    (top,) = figure.axes
    for low, high in (top.get_xlim(), top.get_ylim()):
        assert 0.0 <= low < high <= BLOCK_LENGTH
    walker = next(line for line in top.get_lines() if line.get_label() == "walker")
    assert (walker.get_xdata()[0], walker.get_ydata()[0]) == (96.0, 92.0)  # as the scenario places it
    assert "landblock 0xA9B4" in top.get_xlabel() and "landblock 0xA9B4" in top.get_ylabel()
    assert plot_frame(list(read_paths(yard).values())) == PlotFrame(
        (0xA9 * 192.0, 0xB4 * 192.0), (0xA9, 0xA9, 0xB4, 0xB4)
    )


def test_several_landblocks_are_drawn_from_the_south_west_corner_with_named_seams(trace: Path) -> None:
    figure = trace_figure(trace, view="top")
    (top,) = figure.axes
    drifter = next(line for line in top.get_lines() if line.get_label() == "drifter")
    assert drifter.get_xdata()[0] == 186.0 and drifter.get_xdata()[-1] > BLOCK_LENGTH  # across the seam
    seams = [line for line in top.get_lines() if list(line.get_xdata()) == [BLOCK_LENGTH, BLOCK_LENGTH]]
    assert len(seams) == 1
    assert {"0xA9B4", "0xAAB4"} <= {text.get_text() for text in top.texts}
    assert "from 0xA9B4's south-west corner" in top.get_xlabel()


def test_the_yard_draws_its_objects_from_above_and_from_the_south(yard: Path) -> None:
    top, side = (trace_figure(yard, view=view).axes[0] for view in ("top", "side"))
    (faces,) = by_gid(top, "object")[:1]
    assert len(faces.get_paths()) >= 6  # the walls', ledge's and stairs' faces seen from above
    circles = [c for c in by_gid(top, "object") if len(c.get_paths()) == 1]
    assert circles, "the pillar (a cylsphere) is a circle from above"
    names = {text.get_text() for text in top.texts}
    assert {"north-wall", "south-wall", "east-wall", "west-wall", "pillar", "ledge", "stairs"} <= names
    assert by_gid(top, "ground")
    assert by_gid(side, "object")  # and their profiles from the south, over the ground's
    assert any(c.get_gid() == "ground" for c in side.collections)
    assert side.get_ylim()[1] >= 53.0  # the 3-m pillar on the 50-m ground


def test_the_house_draws_its_rooms_doorways_and_shell(house: Path) -> None:
    figure = trace_figure(house, view="top")
    (top,) = figure.axes
    assert by_gid(top, "room") and by_gid(top, "room lines") and by_gid(top, "building lines")
    (doorways,) = by_gid(top, "doorway lines")
    assert len(doorways.get_segments()) == 2  # the front door and the inner door, once each
    xs = sorted({round(float(x), 3) for segment in doorways.get_segments() for x in segment[:, 0]})
    assert xs == [104.0, 108.0]  # in the house's local metres
    assert {"room 0x0100", "room 0x0101"} <= {text.get_text() for text in top.texts}
    key = {text.get_text() for text in figure.legends[1].get_texts()}
    assert {"room", "doorway", "building"} <= key


def test_the_hills_draw_contours_and_water(hills: Path) -> None:
    figure = trace_figure(hills, view="top")
    (top,) = figure.axes
    (contours, *_) = by_gid(top, "contours")
    assert list(contours.levels) == [float(level) for level in range(42, 62, 2)]  # 40-62 m: every 2 m
    (water,) = by_gid(top, "water")
    alphas = sorted(round(float(colour[3]), 2) for colour in water.get_facecolors())
    assert alphas == [0.22] * 5 + [0.55] * 4  # the lake: 4 cells wholly under water, 5 in part
    assert {"height contour", "water (paler: in part)"} <= {
        t.get_text() for t in figure.legends[1].get_texts()
    }


def test_every_body_has_a_start_circle_and_an_end_square_over_its_events(trace: Path) -> None:
    paths = read_paths(trace)
    figure = make_figure(paths)
    for ax in figure.axes:
        starts, ends = scatter(ax, "_start"), scatter(ax, "_end")
        top = ax.get_title() == "from above"
        for marks, index in ((starts, 0), (ends, -1)):
            expected = [
                (path.x[index] - 0xA9 * 192.0, path.y[index] - 0xB4 * 192.0)
                if top
                else (path.t[index], path.z[index])
                for path in paths.values()
            ]
            assert np.array(marks.get_offsets()).ravel().tolist() == pytest.approx(
                np.ravel(expected).tolist()
            )
        assert starts.get_sizes()[0] > ends.get_sizes()[0]  # a body that does not move shows both
        events = [
            c for c in ax.collections if c.get_label() in ("_hit_ground", "_collision", "_leave_ground")
        ]
        assert events and all(c.get_zorder() < starts.get_zorder() == ends.get_zorder() for c in events)
        assert all(c.get_alpha() < 1.0 for c in events)


def many_paths(count: int) -> dict[str, BodyPath]:
    collector = PathCollector()
    for index in range(count):
        for step in range(3):
            origin = [float(index % 190), float(step + index // 190), 50.0]
            collector.add({"t": step / 30, "body": f"b{index}", "cell": "0xA9B40001", "origin": origin}, "x")
    return collector.paths


@pytest.mark.parametrize(("count", "named", "columns"), [(7, 7, 1), (25, 25, 2), (30, 30, 2), (45, 30, 2)])
def test_the_legend_names_every_body_in_columns_or_says_how_many_it_leaves_out(
    count: int, named: int, columns: int
) -> None:
    figure = make_figure(many_paths(count))
    legend = figure.legends[0]
    names = [text.get_text() for text in legend.get_texts()]
    assert len(names) == named and legend._ncols == columns
    title = legend.get_title().get_text()
    assert title.startswith(f"{count} bodies")
    if named < count:
        assert names[0] == "b0" and names[-1] == f"b{count - 1}"  # spread from the first to the last
        assert f"{count - named} not named" in title
    else:
        assert names == [f"b{index}" for index in range(count)] and "not named" not in title
    colours = [line.get_color() for line in legend.get_lines()]
    assert len(set(map(tuple, colours))) == named  # every body its own colour, past tab20 too


def test_body_colours_scale_past_twenty() -> None:
    for count in (1, 10, 11, 20, 21, 500):
        assert len(set(body_colours(count))) == count


def test_the_title_is_the_scenario_and_the_time_span(yard: Path, tmp_path: Path) -> None:
    figure = trace_figure(yard)
    name, subtitle = figure.get_suptitle().splitlines()
    assert name == "yard"
    assert subtitle == "t 0.00 to 1.00 s · 4 bodies · landblock 0xA9B4"
    sim = load_scenario("yard")
    recorder = PathRecorder()
    recorder.attach(sim.bodies)
    sim.run(until=1.0)
    out = tmp_path / "run.png"
    write_plot(recorder.paths, out, title=sim.name, world=sketch_world(sim))
    assert out.read_bytes()[:8] == PNG_SIGNATURE


@pytest.mark.parametrize(
    ("name", "signature"),
    [
        ("yard.png", PNG_SIGNATURE),
        ("yard.PNG", PNG_SIGNATURE),
        ("yard.svg", b"<?xml"),
        ("yard.pdf", b"%PDF-"),
    ],
)
def test_the_format_follows_the_extension(
    name: str, signature: bytes, yard: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / name
    code, _, err = invoke(["plot", str(yard), "-o", str(out)], capsys)
    assert (code, err) == (0, "")
    data = out.read_bytes()
    assert data.startswith(signature)
    if name.endswith(".svg"):
        assert b"<svg" in data
    again = tmp_path / f"again-{name}"
    assert invoke(["plot", str(yard), "-o", str(again)], capsys)[0] == 0
    assert again.read_bytes() == data  # no date in the file: the same picture, the same bytes


@pytest.mark.parametrize("name", ["yard.jpg", "yard", "yard.png.txt"])
def test_another_extension_is_one_error_line(
    name: str, yard: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / name
    line = assert_one_error_line(*invoke(["plot", str(yard), "-o", str(out)], capsys))
    assert str(out) in line and ".png, .svg or .pdf" in line
    line = assert_one_error_line(*invoke(["run", "yard", "--plot", str(out)], capsys))
    assert ".png, .svg or .pdf" in line
    assert not out.exists()


def test_a_v1_trace_still_plots_its_paths(
    trace: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    v1 = tmp_path / "v1.jsonl"
    records = []
    for record in step_records(trace):  # no header, no start records, no id, heading or motion
        records.append(
            {key: value for key, value in record.items() if key not in ("id", "heading", "motion")}
        )
    v1.write_text("".join(json.dumps(record) + "\n" for record in records), encoding="utf-8")
    out = tmp_path / "v1.png"
    code, stdout, err = invoke(["plot", str(v1), "-o", str(out)], capsys)
    assert (code, err) == (0, "")
    assert "note: " in stdout and "names no scenario: paths only" in stdout
    assert_png(out)
    figure = trace_figure(v1)
    assert figure.get_suptitle().splitlines()[0] == "v1.jsonl"
    assert not by_gid(figure.axes[0], "ground")
    code, stdout, err = invoke(["plot", str(v1), "-o", str(out), "--scenario", "default"], capsys)
    assert (code, err) == (0, "") and "note" not in stdout


def rewrite_header(trace: Path, out: Path, **scenario: Any) -> Path:
    lines = trace.read_text(encoding="utf-8").splitlines(keepends=True)
    header = json.loads(lines[0])
    header["scenario"].update(scenario)
    out.write_text(json.dumps(header) + "\n" + "".join(lines[1:]), encoding="utf-8")
    return out


def test_the_world_comes_from_a_built_in_scenario_only_when_its_text_is_the_same(
    yard: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    found = trace_world(yard)
    assert found.note is None and found.title == "yard" and found.world is not None
    assert json.loads(yard.read_text(encoding="utf-8").splitlines()[0])["scenario"]["sha256"] == (
        hashlib.sha256(builtin_scenario_text("yard").encode("utf-8")).hexdigest()
    )
    changed = rewrite_header(yard, tmp_path / "changed.jsonl", sha256="0" * 64)
    found = trace_world(changed)
    assert found.world is None and found.title == "yard"
    assert "not the built-in text" in (found.note or "")
    mine = rewrite_header(yard, tmp_path / "mine.jsonl", name="my-yard")
    found = trace_world(mine)
    assert found.world is None and "'my-yard' is not built in" in (found.note or "")
    scenario = tmp_path / "my-yard.toml"
    scenario.write_text(builtin_scenario_text("yard").replace('name = "yard"', 'name = "my-yard"'), "utf-8")
    out = tmp_path / "mine.png"
    code, stdout, err = invoke(["plot", str(mine), "-o", str(out), "--scenario", str(scenario)], capsys)
    assert (code, err) == (0, "")
    assert "another text" in stdout  # the header's sha256 is yard's, not this file's
    found = trace_world(mine, str(scenario))
    assert found.title == "my-yard" and len(found.world.of_kind("object")) == 7
    line = assert_one_error_line(
        *invoke(["plot", str(mine), "-o", str(out), "--scenario", "nowhere"], capsys)
    )
    assert "nowhere" in line


def test_a_sketch_holds_the_scenario_s_geometry_in_global_metres() -> None:
    corner = np.array([0xA9 * 192.0, 0xB4 * 192.0, 0.0])
    yard = sketch_world(load_scenario("yard"))
    assert yard.landblocks == {0xA9B4} and yard.faces_left_out == 0
    objects = {shape.name: shape for shape in yard.of_kind("object")}
    assert len(objects) == 7 and not yard.of_kind("room")
    (pillar,) = objects["pillar"].cylinders
    assert pillar == (corner[0] + 96.0, corner[1] + 100.0, 50.0, 1.0, 3.0)
    low, high = objects["east-wall"].bounds()  # turned by its heading of 90: 0.5 m by 32 m
    assert (low - corner).tolist() == pytest.approx([111.75, 80.0, 50.0])
    assert (high - corner).tolist() == pytest.approx([112.25, 112.0, 52.5])
    house = sketch_world(load_scenario("house"))
    assert [len(house.of_kind(kind)) for kind in ("building", "room", "doorway")] == [1, 2, 2]
    hills = sketch_world(load_scenario("hills"))
    (terrain,) = hills.terrain
    assert terrain.triangles.shape == (128, 3) and terrain.z.min() == 40.0 and terrain.z.max() == 62.0
    assert terrain.water.count(2) == 4 and terrain.water.count(1) == 5
