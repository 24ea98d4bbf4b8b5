"""``acphys view --html`` pages in a real browser: headless Chromium with software WebGL.

The pages are opened from disk (``file://``) in Chromium driven over its DevTools pipe
(:mod:`browser.chromium`), screenshotted and read back as pixels: the world is drawn (the yard's walls,
pillar, ledge and stairs where the page projects them, its bodies in their colours), the picture
changes between ``#t=0`` and a later time as the bodies walk, and no request leaves the machine.

Without a Chromium these tests skip on a developer's machine, and fail under ``CI=true``
(``.ci/browser.sh`` installs Debian's ``chromium``; ``ACPHYS_CHROMIUM`` names another).
"""

from __future__ import annotations

import io
import os
import time
from collections.abc import Iterator
from pathlib import Path

import matplotlib.image
import numpy as np
import pytest

from acphys.cli import main
from acphys.viewer import write_html
from browser.chromium import BrowserError, Chromium, find_chromium
from viewer_traces import write_synthetic_trace

CHROMIUM = find_chromium()
IN_CI = os.environ.get("CI") == "true"
READY = "['ready', 'error'].includes(document.documentElement.dataset.state) && location.href === {url!r}"
#: The yard's bodies, each walking some metres between 0 and 3.5 s.
YARD_BODIES = ("walker", "climber", "ledger", "leaner")


@pytest.fixture(scope="module")
def browser() -> Iterator[Chromium]:
    if CHROMIUM is None:
        message = "no Chromium found: install Debian's chromium (sh .ci/browser.sh) or set ACPHYS_CHROMIUM"
        if IN_CI:
            pytest.fail(f"CI=true: {message}", pytrace=False)
        pytest.skip(message)
    with Chromium(CHROMIUM, width=1000, height=650) as chromium:
        yield chromium


@pytest.fixture(scope="module")
def yard_page(tmp_path_factory: pytest.TempPathFactory) -> Path:
    page = tmp_path_factory.mktemp("yard") / "y.html"
    assert main(["view", "yard", "--html", str(page)]) == 0
    return page


def load(browser: Chromium, page: Path, fragment: str = "") -> None:
    """Open ``page`` afresh (not a same-document jump) and wait until it has drawn."""
    browser.open("about:blank")
    browser.wait_for("location.href === 'about:blank'")
    browser.requests.clear()
    url = page.as_uri() + fragment
    browser.open(url)
    browser.wait_for(READY.format(url=url))
    error = browser.evaluate("acphysViewer.error")
    assert error is None, f"{error}; console: {browser.console[-5:]}"


def pixels(png: bytes) -> np.ndarray:
    """A screenshot as an (height, width, 3) array of floats in [0, 1]."""
    return matplotlib.image.imread(io.BytesIO(png), format="png")[:, :, :3]


def canvas_box(browser: Chromium) -> tuple[int, int, int, int]:
    left, top, width, height = browser.evaluate(
        "(() => { const r = document.getElementById('scene').getBoundingClientRect();"
        " return [r.left, r.top, r.width, r.height]; })()"
    )
    return round(left), round(top), round(width), round(height)


def patch(image: np.ndarray, at: list[float], size: int = 2) -> np.ndarray:
    """The pixels around the page point ``at`` (a (2·size+1)² square), as rows of RGB."""
    x, y = round(at[0]), round(at[1])
    return image[y - size : y + size + 1, x - size : x + size + 1].reshape(-1, 3)


def is_grey(rgb: np.ndarray) -> np.ndarray:
    """The stone of walls and objects: no channel far from the others, neither dark nor white."""
    spread, mean = rgb.max(axis=-1) - rgb.min(axis=-1), rgb.mean(axis=-1)
    return (spread < 0.12) & (mean > 0.2) & (mean < 0.9)


def is_ground(rgb: np.ndarray) -> np.ndarray:
    """The flat terrain: green above red and blue."""
    return (rgb[..., 1] > rgb[..., 0] + 0.05) & (rgb[..., 1] > rgb[..., 2] + 0.05)


def hue_like(rgb: np.ndarray, colour: list[float]) -> float:
    """How well ``rgb`` (one pixel) points the way ``colour`` does, grey taken out (a cosine)."""
    a, b = np.asarray(rgb) - np.mean(rgb), np.asarray(colour) - np.mean(colour)
    return float(a @ b / (np.linalg.norm(a) * np.linalg.norm(b) + 1e-9))


def test_the_yard_page_draws_the_world_and_its_bodies_walk(browser: Chromium, yard_page: Path) -> None:
    """The acceptance test: ``acphys view yard --html y.html`` opens with no request leaving the
    machine, shows the walls, pillar, ledge, stairs and bodies, and changes from #t=0 to #t=3.5."""
    load(browser, yard_page, "#t=0")
    assert browser.requests == [yard_page.as_uri() + "#t=0"] or all(
        url.startswith("file://") for url in browser.requests
    ), browser.requests
    assert browser.evaluate("acphysViewer.time") == 0
    left, top, width, height = canvas_box(browser)
    before = pixels(browser.screenshot())
    canvas = before[top : top + height, left : left + width]
    # Not blank: many colours, the ground filling much of it.
    assert len(np.unique((canvas * 255).astype(np.uint8).reshape(-1, 3), axis=0)) > 500
    assert is_ground(canvas).mean() > 0.3

    # The yard's things, each where the page projects its middle: stone, not ground.
    middles = {
        "north wall": (96, 112, 51.25),
        "south wall": (96, 80, 51.25),
        "east wall": (112, 96, 51.25),
        "west wall": (80, 96, 51.25),
        "pillar": (96, 100, 2.5 + 50),
        "ledge": (88, 104, 51.0),
        "stairs": (104, 87.6, 51.2),
    }
    for name, (x, y, z) in middles.items():
        at = browser.evaluate(f"acphysViewer.project({x}, {y}, {z})")
        assert at is not None, name
        assert is_grey(patch(before, at, 1)).mean() > 0.5, (name, at, patch(before, at, 1))

    # The bodies, each in its own colour where the page says it is.
    start = {name: browser.evaluate(f"acphysViewer.screenPosition({name!r})") for name in YARD_BODIES}
    for name, at in start.items():
        colour = browser.evaluate(f"acphysViewer.colour({name!r})")
        centre = patch(before, at, 0)[0]
        assert hue_like(centre, colour) > 0.8, (name, centre, colour)

    # Later: a jump of the address to #t=3.5 moves every body (they walk from 0.5 s).
    browser.evaluate("location.hash = '#t=3.5'")
    browser.wait_for("document.documentElement.dataset.time === '3.5000'")
    after = pixels(browser.screenshot())
    end = {name: browser.evaluate(f"acphysViewer.screenPosition({name!r})") for name in YARD_BODIES}
    for name in YARD_BODIES:
        moved = np.hypot(end[name][0] - start[name][0], end[name][1] - start[name][1])
        assert moved > 8, (name, start[name], end[name])
        # Where it stood, the picture changed (ground now), and where it is now, too.
        assert np.abs(patch(after, start[name], 1) - patch(before, start[name], 1)).max() > 0.2, name
        assert np.abs(patch(after, end[name], 1) - patch(before, end[name], 1)).max() > 0.2, name
    changed = np.abs(after - before)[top : top + height, left : left + width].max(axis=-1) > 0.1
    assert changed.sum() > 300
    assert all(url.startswith("file://") for url in browser.requests), browser.requests

    # The same time asked for on load gives the same picture; setTime from a script too.
    load(browser, yard_page, "#t=3.5")
    fresh = pixels(browser.screenshot())
    assert (np.abs(fresh - after).max(axis=-1) > 0.1).mean() < 0.002
    assert browser.evaluate("acphysViewer.setTime(2)") == 2
    assert browser.evaluate("document.documentElement.dataset.time") == "2.0000"


def test_inspector_timeline_and_playback(browser: Chromium, yard_page: Path) -> None:
    load(browser, yard_page, "#t=3.5&body=walker")
    text = browser.evaluate("document.getElementById('inspector').innerText")
    # At 3.5 s the walker presses on against the pillar: in contact, on walkable ground, sliding.
    shown = ("walker", "0x80000008", "0xA9B4", "contact on_walkable sliding active", "WalkForward")
    shown += ("hit_ground",)
    for expected in shown:
        assert expected in text, (expected, text)
    assert "selected" in browser.evaluate("document.querySelector('#body-list li').className")
    # Events are on the timeline: its canvas has coloured marks.
    marked = browser.evaluate(
        "(() => { const c = document.getElementById('marks'), d = c.getContext('2d')"
        ".getImageData(0, 0, c.width, c.height).data; let n = 0;"
        " for (let i = 3; i < d.length; i += 4) if (d[i] > 200) n++; return n; })()"
    )
    assert marked > 20
    # Play from 0 at 2x: time moves on, never ahead of twice the clock (however slowly a busy
    # machine draws the frames).
    started = time.monotonic()
    browser.evaluate("acphysViewer.setTime(0); acphysViewer.play()")
    playing = browser.wait_for("acphysViewer.time > 0.2 && acphysViewer.time", timeout=25)
    elapsed = time.monotonic() - started
    browser.evaluate("acphysViewer.pause()")
    assert 0.2 < playing <= 2.0 * elapsed + 0.1
    paused = browser.evaluate("acphysViewer.time")
    time.sleep(0.3)
    assert browser.evaluate("acphysViewer.time") == paused


def test_a_hundred_bodies_play_smoothly(browser: Chromium, tmp_path: Path) -> None:
    """100 bodies for 20 s (60,100 records) play: frames are drawn and the replay's time moves
    on. How fast (the page's own work a frame, the frame rate, which depends on the GPU:
    SwiftShader, a software rasteriser, is slow, and on what else the machine runs) is printed,
    never asserted (timings belong in benchmarks, not tests): the page plays until it has drawn
    three frames (and 1.5 s), for as long as that takes within 25 s (the browser answers in 30)."""
    trace = tmp_path / "crowd.jsonl"
    write_synthetic_trace(trace, bodies=100, seconds=20.0)
    page = tmp_path / "crowd.html"
    result = write_html(str(trace), page, scenario="yard")
    assert result.bodies == 100 and result.bytes < 5_000_000
    load(browser, page, "#t=2&body=body-7&follow=1")
    stats = browser.evaluate(
        """new Promise((resolve) => {
          const v = acphysViewer, f0 = v.frames, t0 = v.time, c0 = performance.now();
          v.play();
          const check = setInterval(() => {
            const seconds = (performance.now() - c0) / 1000;
            if ((v.frames - f0 >= 3 && seconds >= 1.5) || seconds >= 25) {
              clearInterval(check);
              v.pause();
              resolve({frames: v.frames - f0, advanced: v.time - t0, seconds, frameMs: v.frameMs});
            }
          }, 100);
        })"""
    )
    print(
        f"100 bodies: {stats['frames']} frames in {stats['seconds']:.2f} s "
        f"({stats['frames'] / stats['seconds']:.1f} fps on this renderer), "
        f"{stats['frameMs']:.2f} ms of the page's own work a frame, page {result.bytes / 1e6:.2f} MB"
    )
    assert stats["frames"] >= 3
    assert stats["advanced"] > 0.0


def test_a_trace_without_its_world(browser: Chromium, tmp_path: Path) -> None:
    trace = tmp_path / "alone.jsonl"
    write_synthetic_trace(trace, bodies=3, seconds=2.0)
    page = tmp_path / "alone.html"
    write_html(str(trace), page)
    load(browser, page, "#t=1")
    assert "no world" in browser.evaluate("document.getElementById('notes').innerText")
    left, top, width, height = canvas_box(browser)
    image = pixels(browser.screenshot())
    for name in ("body-0", "body-1", "body-2"):
        at = browser.evaluate(f"acphysViewer.screenPosition({name!r})")
        colour = browser.evaluate(f"acphysViewer.colour({name!r})")
        assert hue_like(patch(image, at, 0)[0], colour) > 0.8, name
    assert left <= at[0] < left + width and top <= at[1] < top + height


def test_chromium_gives_webgl2(browser: Chromium, yard_page: Path) -> None:
    """The renderer the other tests rely on (a page without WebGL2 says so in its notes)."""
    load(browser, yard_page)
    assert browser.evaluate("!!document.createElement('canvas').getContext('webgl2')")
    with pytest.raises(BrowserError):
        browser.evaluate("undefinedFunctionOfNoOne()")
