"""``acphys plot``, ``acphys run --plot`` and ``acphys view`` (README "The command line").

The pictures are made from a 4-s trace of the default scenario, long enough for the
drifter (2 m/s east from x = 186 in landblock 0xA9B4) to cross the seam into 0xAAB4.
Nothing in acphys is mocked; matplotlib draws on its Agg canvas.
"""

from __future__ import annotations

import re
import struct
from pathlib import Path

import pytest

from acphys.cli import main
from acphys.constants import BLOCK_LENGTH
from acphys.plot import (
    VIEWS,
    BodyPath,
    PathCollector,
    PathRecorder,
    PlotError,
    global_xy,
    make_figure,
    read_paths,
    select_bodies,
)
from acphys.scenario import load_scenario
from acphys.view import ascii_map, summarise
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
    legend = [text.get_text() for text in figure.legends[0].get_texts()]
    assert {"hit_ground", "collision", "leave_ground"} <= set(legend)
    assert len(top.collections) > 0  # the event markers


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
