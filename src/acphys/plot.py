"""Pictures of a run (contract 3): a trace's paths in one global frame, and a PNG of them.

A trace's ``origin`` is local to the landblock named by its ``cell``; here
every sample is moved into the landblock-global frame (landblock ``0xXXYY``'s
south-west corner at ``(XX · 192, YY · 192)`` metres), so a body that crosses
a seam draws one continuous path. :func:`read_paths` reads a trace file,
:class:`PathRecorder` collects the same paths from a running simulation, and
:func:`write_plot` draws them with matplotlib's non-interactive Agg backend:
the paths from above (``top``), from the south (``side``: east against
height) and height over time (``height``), with ``hit_ground``,
``leave_ground`` and collision events marked.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from acphys.constants import BLOCK_LENGTH
from acphys.math.cell_id import landblock_of
from acphys.physics_obj import PhysicsObj
from acphys.trace import TraceError, read_trace, step_record

#: The panels ``--view`` can pick; without it the figure has ``top`` and ``height``.
VIEWS = ("top", "side", "height")
DEFAULT_VIEWS = ("top", "height")

#: Events marked on the figure: (label, marker, edge colour, size), by event kind; the
#: smaller collision cross sits inside the hit_ground triangle when both happen at once.
EVENT_MARKERS = {
    "hit_ground": ("hit_ground", "v", "black", 90),
    "leave_ground": ("leave_ground", "^", "black", 90),
    "collision": ("collision", "X", "red", 35),
}


class PlotError(ValueError):
    """A picture that cannot be made: an unknown body, nothing to draw, an unwritable file."""


@dataclass
class BodyPath:
    """One body's samples, one per trace record, in the landblock-global frame."""

    name: str
    t: list[float] = field(default_factory=list)
    quantum: list[float] = field(default_factory=list)
    x: list[float] = field(default_factory=list)
    y: list[float] = field(default_factory=list)
    z: list[float] = field(default_factory=list)
    contact: list[bool] = field(default_factory=list)
    #: ``(sample index, event)`` for every event of every record, in order.
    events: list[tuple[int, str]] = field(default_factory=list)
    #: The first and last records' cells and landblock-local origins, as the trace has them.
    first_cell: str = ""
    first_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    last_cell: str = ""
    last_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __len__(self) -> int:
        return len(self.t)


def event_kind(event: str) -> str:
    """``collision:pillar`` -> ``collision``, ``motion:RunForward:error:0x43`` -> ``motion``."""
    return event.split(":", 1)[0]


def global_xy(cell_id: int, x: float, y: float) -> tuple[float, float]:
    """A landblock-local ``(x, y)`` in the cell's landblock, in landblock-global metres."""
    block = landblock_of(cell_id)
    return (block >> 8) * BLOCK_LENGTH + x, (block & 0xFF) * BLOCK_LENGTH + y


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


class PathCollector:
    """Builds :class:`BodyPath` s from trace records, checking the keys a picture needs."""

    def __init__(self) -> None:
        self.paths: dict[str, BodyPath] = {}

    def add(self, record: dict[str, Any], where: str) -> None:
        """Add one record; ``where`` (``file:line``) prefixes any :class:`TraceError`."""
        t, body, quantum = record.get("t"), record.get("body"), record.get("quantum", 0.0)
        if not _number(t):
            raise TraceError(f"{where}: t must be a number, got {t!r}")
        if not isinstance(body, str):
            raise TraceError(f"{where}: body must be a string, got {body!r}")
        if not _number(quantum):
            raise TraceError(f"{where}: quantum must be a number, got {quantum!r}")
        cell = record.get("cell")
        try:
            cell_id = int(cell, 16) if isinstance(cell, str) else -1
        except ValueError:
            cell_id = -1
        if not 0 <= cell_id <= 0xFFFFFFFF:
            raise TraceError(f'{where}: cell must be a hex cell id like "0xA9B40021", got {cell!r}')
        origin = record.get("origin")
        if not (isinstance(origin, list) and len(origin) == 3 and all(_number(v) for v in origin)):
            raise TraceError(f"{where}: origin must be 3 numbers, got {origin!r}")
        transient = record.get("transient", [])
        events = record.get("events", [])
        for key, value in (("transient", transient), ("events", events)):
            if not (isinstance(value, list) and all(isinstance(item, str) for item in value)):
                raise TraceError(f"{where}: {key} must be a list of strings, got {value!r}")
        path = self.paths.get(body)
        if path is None:
            path = self.paths[body] = BodyPath(body, first_cell=cell, first_origin=tuple(origin))
        gx, gy = global_xy(cell_id, origin[0], origin[1])
        index = len(path.t)
        path.t.append(float(t))
        path.quantum.append(float(quantum))
        path.x.append(gx)
        path.y.append(gy)
        path.z.append(float(origin[2]))
        path.contact.append("contact" in transient)
        path.events.extend((index, event) for event in events)
        path.last_cell, path.last_origin = cell, tuple(origin)


def read_paths(trace: str | Path) -> dict[str, BodyPath]:
    """Every body's path in a trace file, in order of first appearance.

    Raises :class:`TraceError` (naming the file and line) for a missing or
    malformed trace, and for one with no records.
    """
    collector = PathCollector()
    for line, record in read_trace(trace):
        collector.add(record, f"{trace}:{line}")
    if not collector.paths:
        raise TraceError(f"{trace}: the trace has no records")
    return collector.paths


class PathRecorder:
    """Collects the paths of a running simulation in memory (what ``--trace`` would write).

    ``attach`` makes it the bodies' step observer, like :class:`acphys.trace.TraceWriter`;
    the two cannot both observe a body.
    """

    def __init__(self) -> None:
        self._collector = PathCollector()

    @property
    def paths(self) -> dict[str, BodyPath]:
        return self._collector.paths

    def attach(self, bodies: Iterable[PhysicsObj]) -> None:
        for body in bodies:
            body.observer = self.record_step

    def detach(self, bodies: Iterable[PhysicsObj]) -> None:
        for body in bodies:
            if body.observer == self.record_step:
                body.observer = None

    def record_step(self, body: PhysicsObj, quantum: float) -> None:
        self._collector.add(step_record(body, quantum), f"<run>:{body.name}")


def parse_bodies(text: str | None) -> list[str] | None:
    """``--bodies a,b`` as a list of names (None: every body)."""
    if text is None:
        return None
    names = [name.strip() for name in text.split(",") if name.strip()]
    if not names:
        raise PlotError("--bodies needs at least one body name, like --bodies ball,drifter")
    return names


def select_bodies(paths: dict[str, BodyPath], names: Sequence[str] | None) -> list[BodyPath]:
    """The paths of ``names`` (in that order), or every path; an unknown name is a :class:`PlotError`."""
    if names is None:
        return list(paths.values())
    unknown = [name for name in names if name not in paths]
    if unknown:
        have = ", ".join(paths) or "none"
        raise PlotError(f"no body named {', '.join(map(repr, unknown))} in the trace (it has: {have})")
    return [paths[name] for name in dict.fromkeys(names)]


def check_output(output: str | Path) -> Path:
    """The picture's path, if it can be written there (checked before any work is done)."""
    path = Path(output)
    if path.is_dir():
        raise PlotError(f"{path}: is a directory, not a PNG file")
    parent = path.parent
    if not parent.is_dir():
        raise PlotError(f"{path}: cannot write: no directory {str(parent)!r}")
    return path


def write_plot(
    paths: dict[str, BodyPath],
    output: str | Path,
    bodies: Sequence[str] | None = None,
    view: str | None = None,
    title: str = "",
) -> Path:
    """Draw the paths of ``bodies`` (default: all) to a PNG at ``output``; returns its path.

    ``view`` is one of :data:`VIEWS` for a single panel; by default the figure
    has the paths from above and height over time side by side.
    """
    output = check_output(output)
    figure = make_figure(paths, bodies, view, title)
    try:
        figure.savefig(output, format="png")
    except OSError as error:
        raise PlotError(f"{output}: cannot write: {error.strerror or error}") from None
    return output


def make_figure(
    paths: dict[str, BodyPath], bodies: Sequence[str] | None = None, view: str | None = None, title: str = ""
) -> Any:
    """The matplotlib ``Figure`` :func:`write_plot` saves (on an Agg canvas; pyplot is not used)."""
    if view is not None and view not in VIEWS:
        raise PlotError(f"--view must be one of {', '.join(VIEWS)}, got {view!r}")
    selected = select_bodies(paths, bodies)
    if not any(len(path) for path in selected):
        raise PlotError("nothing to draw: the selected bodies have no records")
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:  # pragma: no cover - matplotlib is a dependency
        raise PlotError("plotting needs matplotlib: pip install 'matplotlib>=3.7'") from None

    views = DEFAULT_VIEWS if view is None else (view,)
    figure = Figure(figsize=(6.5 * len(views), 6.0), dpi=100, layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.subplots(1, len(views), squeeze=False)[0]
    colours = [f"C{index % 10}" for index in range(len(selected))]
    for ax, panel in zip(axes, views, strict=True):
        _draw_panel(ax, panel, selected, colours)
    _legend(figure, selected, colours)
    if title:
        figure.suptitle(title)
    return figure


def _panel_data(panel: str, path: BodyPath) -> tuple[list[float], list[float]]:
    if panel == "top":
        return path.x, path.y
    if panel == "side":
        return path.x, path.z
    return path.t, path.z


def _draw_panel(ax: Any, panel: str, selected: list[BodyPath], colours: list[str]) -> None:
    for path, colour in zip(selected, colours, strict=True):
        xs, ys = _panel_data(panel, path)
        if not xs:
            continue
        ax.plot(xs, ys, color=colour, linewidth=1.5, label=path.name)
        ax.plot(xs[:1], ys[:1], marker="o", color=colour, markersize=5)  # where it starts
        for kind, (_, marker, edge, size) in EVENT_MARKERS.items():
            hits = [index for index, event in path.events if event_kind(event) == kind]
            if hits:
                ax.scatter(
                    [xs[i] for i in hits],
                    [ys[i] for i in hits],
                    marker=marker,
                    s=size,
                    facecolors="none" if kind != "collision" else "red",
                    edgecolors=edge,
                    linewidths=1.0,
                    zorder=3,
                )
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.grid(True, color="0.9")
    if panel == "top":
        ax.set_title("from above")
        ax.set_xlabel("x: east (m, landblock-global)")
        ax.set_ylabel("y: north (m, landblock-global)")
        ax.set_aspect("equal", adjustable="datalim")
        _landblock_seams(ax, selected)
    elif panel == "side":
        ax.set_title("from the south")
        ax.set_xlabel("x: east (m, landblock-global)")
        ax.set_ylabel("z: height (m)")
    else:
        ax.set_title("height over time")
        ax.set_xlabel("t: physics time (s)")
        ax.set_ylabel("z: height (m)")


def _landblock_seams(ax: Any, selected: list[BodyPath]) -> None:
    """Dashed lines on the landblock edges the paths reach (at most a few dozen)."""
    xs = [x for path in selected for x in path.x]
    ys = [y for path in selected for y in path.y]
    for values, draw in ((xs, ax.axvline), (ys, ax.axhline)):
        low = math.floor(min(values) / BLOCK_LENGTH)
        high = math.ceil(max(values) / BLOCK_LENGTH)
        if high - low <= 40:
            for edge in range(low + 1, high):
                draw(edge * BLOCK_LENGTH, color="0.6", linestyle="--", linewidth=0.8)


def _legend(figure: Any, selected: list[BodyPath], colours: list[str]) -> None:
    from matplotlib.lines import Line2D

    handles = []
    if len(selected) <= 12:
        handles += [Line2D([], [], color=c, label=p.name) for p, c in zip(selected, colours, strict=True)]
    handles.append(Line2D([], [], marker="o", color="0.4", linestyle="", label="start"))
    seen = {event_kind(event) for path in selected for _, event in path.events}
    for kind, (label, marker, edge, _) in EVENT_MARKERS.items():
        if kind in seen:
            face = "red" if kind == "collision" else "none"
            handles.append(
                Line2D([], [], marker=marker, color=face, markeredgecolor=edge, linestyle="", label=label)
            )
    figure.legend(handles=handles, fontsize="small", loc="outside right upper")
