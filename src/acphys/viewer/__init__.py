"""``acphys view ... --html``: a self-contained 3-D replay of a run in one HTML file.

:func:`write_html` runs a scenario (or reads a trace), gathers the world (:mod:`.scene`) and the
records (:mod:`.records`) into a compact description and blob (:mod:`.page`) and writes them into
the page template (``template/``: the HTML, its style and a small WebGL2 renderer of our own),
so the page needs nothing but a browser: no network, no other file.

In the page, ``#t=SECONDS`` opens it at that time, and ``window.acphysViewer`` drives it from a
script: ``setTime(t)``, ``play()``, ``pause()``, ``select(name)``, and reads ``ready``, ``time``,
``bodies`` and ``frames`` (frames drawn); ``<html data-state="ready" data-time="...">`` says the
same to a tool that only reads the DOM.
"""

from __future__ import annotations

import hashlib
import math
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from acphys.inputs import InputError, one_line
from acphys.scenario import builtin_scenario_text, builtin_scenarios, load_scenario
from acphys.simulation import Simulation
from acphys.trace import read_header
from acphys.viewer.page import BodyShape, page_data, render_html
from acphys.viewer.records import collect_records, records_cells
from acphys.viewer.scene import block_index, gather_scene, world_landblocks

__all__ = ["ViewResult", "is_trace", "write_html"]


@dataclass
class ViewResult:
    """What :func:`write_html` wrote: the page, its size, and what it holds."""

    path: Path
    bytes: int
    bodies: int
    records: int
    events: int
    notes: list[str]


def is_trace(source: str) -> bool:
    """Whether ``source`` names a trace (a file whose first non-blank byte is ``{``) rather than
    a scenario (a TOML file or a built-in name)."""
    path = Path(source)
    if not path.is_file():
        return False
    try:
        with path.open("rb") as handle:
            head = handle.read(4096).lstrip()
    except OSError:
        return False
    return head.startswith(b"{") or (not head and path.suffix in (".jsonl", ".json"))


def check_html_output(output: str | Path) -> Path:
    """The page's path, if it can be written there (checked before any work is done)."""
    path = Path(output)
    if path.exists() and not path.is_file():
        raise InputError(str(path), "cannot write: not a regular file")
    if not path.parent.is_dir():
        raise InputError(str(path), f"cannot write: no folder {one_line(str(path.parent))}")
    if path.suffix.lower() not in (".html", ".htm"):
        raise InputError(str(path), "the page must be an .html (or .htm) file")
    return path


def write_html(
    source: str,
    output: str | Path,
    *,
    scenario: str | None = None,
    bodies: Sequence[str] | None = None,
    until: float | None = None,
    engine: str | None = None,
    warn: Callable[[str], None] | None = None,
) -> ViewResult:
    """Write the replay page of ``source`` to ``output``.

    ``source`` is a scenario (a file or a built-in name: it is run, to ``until`` or its
    duration, on ``engine``) or a trace file (its world from ``scenario``, or from the built-in
    scenario its header names when the text's SHA-256 matches; without one the page shows the
    bodies and their trails alone, and says so). ``bodies`` keeps those bodies only.
    ``until`` and ``engine`` (default ``"reference"``) are for a scenario; with a trace they are
    refused (:class:`~acphys.inputs.InputError`), as ``scenario`` is with a scenario.
    """
    path = check_html_output(output)
    notes: list[str] = []

    def note(message: str) -> None:
        notes.append(message)
        if warn is not None:
            warn(message)

    if is_trace(source):
        for option, value in (("--until", until), ("--engine", engine)):
            if value is not None:
                raise InputError(option, "is for a scenario (a trace has run already)")
        world_sim = _trace_world(source, scenario, note)
        collector = collect_records(source, bodies, note)
        title = Path(source).name
        info = {"kind": "trace", "trace": one_line(Path(source).name)}
        if world_sim is not None:
            info["scenario"] = one_line(world_sim.name)
    else:
        if scenario is not None:
            raise InputError(
                str(scenario), "--scenario is for a trace; the scenario given runs in its own world"
            )
        engine = engine or "reference"
        world_sim = load_scenario(source, engine=engine)
        for message in world_sim.warnings:
            if warn is not None:
                warn(message)
        end = world_sim.duration if until is None else until
        if not (math.isfinite(end) and end >= 0.0):
            raise InputError("--until", f"must be a non-negative number of seconds, got {until}")
        try:
            world_sim.check_until(end)
        except ValueError as error:
            raise InputError("--until", str(error)) from None
        with tempfile.TemporaryDirectory(prefix="acphys-view-") as folder:
            trace = Path(folder) / "run.jsonl"
            world_sim.run(until=end, trace=trace)
            collector = collect_records(trace, bodies, note)
        title = f"{world_sim.name}: {end:g} s"
        info = {"kind": "scenario", "scenario": one_line(world_sim.name), "engine": engine, "until": end}

    cells = list(records_cells(collector))
    blocks = [block_index(cell) for cell in cells]
    if world_sim is not None:
        blocks += [block_index(block) for block in world_landblocks(world_sim.world)]
    base = (min(b[0] for b in blocks), min(b[1] for b in blocks)) if blocks else (0, 0)
    scene = gather_scene(world_sim.world, base) if world_sim is not None else None
    if scene is not None:
        for message in scene.notes:
            note(message)
    shapes = _shapes(world_sim, collector.bodies) if world_sim is not None else {}
    unknown = [name for name in collector.bodies if name not in shapes]
    if world_sim is not None and unknown:
        note(
            f"{len(unknown)} bodies are not in the scenario ({one_line(unknown[0])!r}"
            f"{', ...' if len(unknown) > 1 else ''}): drawn as 0.5-m spheres"
        )
    data, blob = page_data(title, collector, shapes, scene, base, notes, info)
    html = render_html(data, blob)
    path.write_text(html, encoding="utf-8")
    return ViewResult(
        path=path,
        bytes=len(html.encode("utf-8")),
        bodies=len(collector.bodies),
        records=sum(len(body) for body in collector.bodies.values()),
        events=len(collector.events),
        notes=notes,
    )


def _trace_world(trace: str, scenario: str | None, note: Callable[[str], None]) -> Simulation | None:
    """The scenario whose world a trace is shown in: ``scenario`` when given (built, not run), else
    the built-in one the header names (by name and text hash), else None."""
    header = read_header(trace)
    named = header.get("scenario") if isinstance(header, dict) else None
    name = named.get("name") if isinstance(named, dict) else None
    sha = named.get("sha256") if isinstance(named, dict) else None
    if scenario is not None:
        sim = load_scenario(scenario)
        if isinstance(sha, str) and sim.scenario_sha256 not in (None, sha):
            note(
                f"the trace was written from another scenario text than {one_line(scenario)} "
                "(another SHA-256): drawn in its world all the same"
            )
        return sim
    if isinstance(name, str) and name in builtin_scenarios():
        text = builtin_scenario_text(name)
        if hashlib.sha256(text.encode("utf-8")).hexdigest() == sha:
            return load_scenario(name)
        note(
            f"the trace names scenario {one_line(name)!r} but not the built-in one's text: "
            "no world drawn (give --scenario FILE)"
        )
        return None
    note("no world: the bodies and their trails alone (give --scenario FILE for the terrain and objects)")
    return None


def _shapes(sim: Simulation, names: Sequence[str] | dict) -> dict[str, BodyShape]:
    """The shapes of the bodies of ``sim`` named in ``names``, in their frames, scaled."""
    shapes: dict[str, BodyShape] = {}
    by_name = {body.name: body for body in sim.bodies}
    for name in names:
        body = by_name.get(name)
        if body is None or body.part_array is None:
            continue
        parts = body.part_array
        setup = parts.setup
        scale = parts.scale
        spheres = [
            (s.center.x * scale, s.center.y * scale, s.center.z * scale, s.radius * scale)
            for s in setup.spheres
        ]
        cylinders = [
            (c.low_pt.x * scale, c.low_pt.y * scale, c.low_pt.z * scale, c.radius * scale, c.height * scale)
            for c in setup.cylspheres
        ]
        source = "setup"
        if not spheres and not cylinders:
            sort = setup.sorting_sphere
            radius = sort.radius * scale if sort.radius > 0.0 else 0.25
            c = sort.center
            spheres = [(c.x * scale, c.y * scale, c.z * scale if sort.radius > 0.0 else radius, radius)]
            source = "sorting"
        shapes[name] = BodyShape(spheres, cylinders, source)
    return shapes
