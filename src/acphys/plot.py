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
import re
import sys
import warnings
from array import array
from collections import Counter
from collections.abc import Callable, Collection, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from itertools import islice
from pathlib import Path
from typing import Any

from acphys.constants import BLOCK_LENGTH
from acphys.inputs import one_line
from acphys.math.cell_id import landblock_of
from acphys.physics_obj import PhysicsObj
from acphys.trace import TraceError, brief, read_trace, step_record

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


#: The most samples a picture keeps, over all its bodies and event marks: more than a PNG panel
#: or a terminal map can tell apart, in 32 MB of float64. A longer trace or run is drawn from
#: every 2nd, 4th, ... record of its longest series, with a warning; the figures of ``view``
#: still count every record.
MAX_POINTS = 1_000_000
#: The most bodies a picture reads: ten times the 10,000-body scenarios acphys builds and runs,
#: and the most ``acphys bench`` drives. Each costs a few hundred bytes.
MAX_BODIES = 100_000
#: The longest body name a picture reads, in characters (a name is held once per body).
MAX_NAME_LENGTH = 1000
#: The most kinds of event (``collision`` for ``collision:pillar``) a picture counts: acphys
#: writes about 25 (README "Traces").
MAX_EVENT_KINDS = 64
#: The largest magnitude of a number drawn (``t``, ``quantum``, ``origin``): the largest float32.
#: acphys writes origins as float32 and no run's time comes near it; within it, every sum and
#: difference the plot and the view take is a finite float64.
MAX_MAGNITUDE = 3.4028234663852886e38
#: The most bodies the legend names (each its own line); more are drawn as one collection.
LEGEND_BODIES = 12
#: How many characters of a name the legend, the table and the map show.
SHOWN_NAME = 40


class PlotError(ValueError):
    """A picture that cannot be made: an unknown body, nothing to draw, an unwritable file."""


def _floats() -> array[float]:
    return array("d")


@dataclass
class Points:
    """Samples ``(t, x, y, z)`` of one series: every ``stride``-th one added, and the latest.

    ``stride`` starts at 1 (every sample) and doubles each time :meth:`thin` runs.
    """

    t: array[float] = field(default_factory=_floats)
    x: array[float] = field(default_factory=_floats)
    y: array[float] = field(default_factory=_floats)
    z: array[float] = field(default_factory=_floats)
    #: How many samples were added (kept or not).
    added: int = 0
    stride: int = 1

    def __len__(self) -> int:
        return len(self.t)

    def add(self, t: float, x: float, y: float, z: float) -> int:
        """Add the latest sample; returns how many more samples are kept (0 or 1)."""
        replace = self.added > 0 and (self.added - 1) % self.stride != 0  # the latest, off the stride
        self.added += 1
        if replace:
            self.t[-1], self.x[-1], self.y[-1], self.z[-1] = t, x, y, z
            return 0
        self.t.append(t)
        self.x.append(x)
        self.y.append(y)
        self.z.append(z)
        return 1

    def thin(self) -> int:
        """Double the stride, keeping every other sample on it and the latest; returns how many went."""
        before = len(self.t)
        on_stride = before if (self.added - 1) % self.stride == 0 else before - 1
        self.stride *= 2
        keep_latest = (self.added - 1) % self.stride != 0
        for name in ("t", "x", "y", "z"):
            values = getattr(self, name)
            kept = values[0:on_stride:2]
            if keep_latest:
                kept.append(values[-1])
            setattr(self, name, kept)
        return before - len(self.t)


@dataclass
class BodyPath(Points):
    """One body's path: its samples in the landblock-global frame, and figures over every record."""

    name: str = ""
    #: Where the marked events (:data:`EVENT_MARKERS`) happened, by kind.
    marks: dict[str, Points] = field(default_factory=dict)
    #: Events by kind (``collision:pillar`` counts as ``collision``), over every record.
    events: Counter[str] = field(default_factory=Counter)
    #: Metres along the path, from the first record to the last (3-D, in the global frame).
    distance: float = 0.0
    #: The fastest the path moved between two records (m/s): root-motion walking counts.
    max_speed: float = 0.0
    #: Seconds of steps that ended in contact with something.
    contact_time: float = 0.0
    #: The first and last records' cells and landblock-local origins, as the trace has them.
    first_cell: str = ""
    first_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    last_cell: str = ""
    last_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def series(self) -> Iterator[Points]:
        """The path's samples and its marks."""
        yield self
        yield from self.marks.values()


def event_kind(event: str) -> str:
    """``collision:pillar`` -> ``collision``, ``motion:RunForward:error:0x43`` -> ``motion``."""
    return event.split(":", 1)[0]


def global_xy(cell_id: int, x: float, y: float) -> tuple[float, float]:
    """A landblock-local ``(x, y)`` in the cell's landblock, in landblock-global metres."""
    block = landblock_of(cell_id)
    return (block >> 8) * BLOCK_LENGTH + x, (block & 0xFF) * BLOCK_LENGTH + y


def shown_name(name: str, limit: int = SHOWN_NAME) -> str:
    """A name as a picture shows it: unprintable characters escaped, cut to ``limit`` characters."""
    text = one_line(name)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _number(value: Any) -> bool:
    """Whether ``value`` is a JSON number a picture draws: finite, within :data:`MAX_MAGNITUDE`."""
    if type(value) is float:  # the common case, first (NaN fails both comparisons)
        return -MAX_MAGNITUDE <= value <= MAX_MAGNITUDE
    return isinstance(value, (int, float)) and not isinstance(value, bool) and abs(value) <= MAX_MAGNITUDE


def _point(value: Any) -> bool:
    """Whether ``value`` is 3 floats a picture draws (:func:`_number`'s common case, in one call)."""
    if type(value) is not list or len(value) != 3:
        return False
    x, y, z = value
    return (
        type(x) is float
        and type(y) is float
        and type(z) is float
        and -MAX_MAGNITUDE <= x <= MAX_MAGNITUDE
        and -MAX_MAGNITUDE <= y <= MAX_MAGNITUDE
        and -MAX_MAGNITUDE <= z <= MAX_MAGNITUDE
    )


def _strings(value: Any) -> bool:
    return isinstance(value, list) and (not value or all(isinstance(item, str) for item in value))


def _at(where: str, line: int | None) -> str:
    return where if line is None else f"{where}:{line}"


#: What a record without ``transient`` or ``events`` has (never changed).
_NO_STRINGS: list[str] = []
_BOUNDED = f"finite and within ±{MAX_MAGNITUDE:.2g} (the float32 range)"
_CELL = re.compile(r"0x[0-9A-Fa-f]{1,8}")
#: How many cells' landblock corners a collector remembers (a trace visits a few; a hostile one
#: could name millions).
_CELL_CACHE = 4096


class PathCollector:
    """Builds :class:`BodyPath` s from trace records, checking the keys a picture needs.

    It keeps at most :data:`MAX_POINTS` samples, thinning the longest series when it would hold more.
    """

    def __init__(self) -> None:
        self.paths: dict[str, BodyPath] = {}
        self._kinds: dict[str, str] = {}
        self._corners: dict[str, tuple[float, float]] = {}
        self._kept = 0

    def add(self, record: dict[str, Any], where: str, line: int | None = None) -> None:
        """Add one record; ``where`` (the file, or ``<run>:body``) and ``line`` prefix any
        :class:`TraceError`."""
        t, body, quantum = record.get("t"), record.get("body"), record.get("quantum", 0.0)
        cell, origin = record.get("cell"), record.get("origin")
        transient, events = record.get("transient", _NO_STRINGS), record.get("events", _NO_STRINGS)
        corner = self._corners.get(cell) if type(cell) is str else None
        if not (  # what acphys writes, checked without a call; anything else by _check
            corner is not None
            and type(t) is float
            and type(quantum) is float
            and type(body) is str
            and -MAX_MAGNITUDE <= t <= MAX_MAGNITUDE
            and -MAX_MAGNITUDE <= quantum <= MAX_MAGNITUDE
            and _point(origin)
            and _strings(transient)
            and (not events or _strings(events))
        ):
            corner = self._check(record, _at(where, line))
        path = self.paths.get(body)
        if path is None:
            path = self._new_path(body, cell, origin, _at(where, line))
        t, gx, gy, z = float(t), corner[0] + origin[0], corner[1] + origin[1], float(origin[2])
        if path.added:
            step = math.dist((path.x[-1], path.y[-1], path.z[-1]), (gx, gy, z))
            path.distance += step
            if t > path.t[-1]:
                path.max_speed = max(path.max_speed, step / (t - path.t[-1]))
        if "contact" in transient:
            path.contact_time += quantum
        self._kept += path.add(t, gx, gy, z)
        if events:
            self._events(path, events, (t, gx, gy, z), where, line)
        path.last_cell, path.last_origin = cell, tuple(origin)
        if self._kept > MAX_POINTS:
            self._thin()

    def _check(self, record: dict[str, Any], where: str) -> tuple[float, float]:
        """Refuse the first key of ``record`` a picture cannot use; returns the corner of its cell's
        landblock, in landblock-global metres (remembered for the next record in that cell)."""
        t, body, quantum = record.get("t"), record.get("body"), record.get("quantum", 0.0)
        if not _number(t):
            raise TraceError(f"{where}: t must be a number, {_BOUNDED}, got {brief(t)}")
        if not isinstance(body, str):
            raise TraceError(f"{where}: body must be a string, got {brief(body)}")
        if not _number(quantum):
            raise TraceError(f"{where}: quantum must be a number, {_BOUNDED}, got {brief(quantum)}")
        cell = record.get("cell")
        if not (isinstance(cell, str) and _CELL.fullmatch(cell)):
            raise TraceError(f'{where}: cell must be a hex cell id like "0xA9B40021", got {brief(cell)}')
        origin = record.get("origin")
        if not (isinstance(origin, list) and len(origin) == 3 and all(_number(v) for v in origin)):
            raise TraceError(f"{where}: origin must be 3 numbers, {_BOUNDED}, got {brief(origin)}")
        for key in ("transient", "events"):
            value = record.get(key, _NO_STRINGS)
            if not _strings(value):
                raise TraceError(f"{where}: {key} must be a list of strings, got {brief(value)}")
        if len(self._corners) == _CELL_CACHE:
            self._corners.clear()
        corner = self._corners[cell] = global_xy(int(cell, 16), 0.0, 0.0)
        return corner

    def _events(
        self,
        path: BodyPath,
        events: list[str],
        sample: tuple[float, float, float, float],
        where: str,
        line: int | None,
    ) -> None:
        """Count a record's events by kind, and mark where the marked kinds happened."""
        for kind, count in Counter(map(event_kind, events)).items():
            kind = self._kind(kind, where, line)
            path.events[kind] += count
            if kind in EVENT_MARKERS:
                marks = path.marks.get(kind)
                if marks is None:
                    marks = path.marks[kind] = Points()
                self._kept += marks.add(*sample)

    def _new_path(self, body: str, cell: str, origin: list[float], where: str) -> BodyPath:
        if len(body) > MAX_NAME_LENGTH:
            raise TraceError(
                f"{where}: a body name of {len(body)} characters; the limit is {MAX_NAME_LENGTH}"
            )
        if len(self.paths) == MAX_BODIES:
            raise TraceError(f"{where}: more than {MAX_BODIES} bodies, the limit for a picture")
        path = self.paths[body] = BodyPath(name=body, first_cell=cell, first_origin=tuple(origin))
        return path

    def _kind(self, kind: str, where: str, line: int | None) -> str:
        """``kind``, one string object for all bodies; a new kind past the limit is refused."""
        known = self._kinds.get(kind)
        if known is None:
            if len(self._kinds) == MAX_EVENT_KINDS:
                raise TraceError(
                    f"{_at(where, line)}: more than {MAX_EVENT_KINDS} kinds of event, the limit for a "
                    f"picture (acphys writes about 25); the next is {brief(kind)}"
                )
            known = self._kinds[kind] = kind
        return known

    def _thin(self) -> None:
        """Thin the longest series until the samples kept are at most half of :data:`MAX_POINTS`."""
        series = [points for path in self.paths.values() for points in path.series()]
        while self._kept > MAX_POINTS // 2:
            mean = self._kept / len(series)
            dropped = sum(points.thin() for points in series if len(points) >= mean and len(points) > 2)
            if not dropped:
                break
            self._kept -= dropped


def read_paths(trace: str | Path) -> dict[str, BodyPath]:
    """Every body's path in a trace file, in order of first appearance.

    Raises :class:`TraceError` (naming the file and line) for a missing or
    malformed trace, and for one with no records.
    """
    collector = PathCollector()
    label = one_line(str(trace))
    for line, record in read_trace(trace):
        collector.add(record, label, line)
    if not collector.paths:
        raise TraceError(f"{label}: the trace has no records")
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
        """Record where each body starts (as a trace's start records do), then its every step."""
        for body in bodies:
            self._collector.add(step_record(body, 0.0), f"<run>:{one_line(body.name)}")
            body.observer = self.record_step

    def detach(self, bodies: Iterable[PhysicsObj]) -> None:
        for body in bodies:
            if body.observer == self.record_step:
                body.observer = None

    def record_step(self, body: PhysicsObj, quantum: float) -> None:
        self._collector.add(step_record(body, quantum), f"<run>:{one_line(body.name)}")


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
        raise PlotError(
            f"no body named {', '.join(map(repr, unknown))} in the trace (it has: {_some(paths)})"
        )
    return [paths[name] for name in dict.fromkeys(names)]


def _some(names: Collection[str]) -> str:
    """The first :data:`LEGEND_BODIES` names as a message shows them (one line), and how many more."""
    shown = ", ".join(shown_name(name) for name in islice(names, LEGEND_BODIES)) or "none"
    more = len(names) - LEGEND_BODIES
    return f"{shown} and {more:,} more" if more > 0 else shown


def check_output(output: str | Path) -> Path:
    """The picture's path, if it can be written there (checked before any work is done)."""
    path = Path(output)
    label = one_line(str(path))
    if path.is_dir():
        raise PlotError(f"{label}: is a directory, not a PNG file")
    if path.is_fifo() or path.is_socket():  # a pipe would block the write until someone reads it
        raise PlotError(f"{label}: cannot write: not a regular file")
    parent = path.parent
    if not parent.is_dir():
        raise PlotError(f"{label}: cannot write: no directory {one_line(str(parent))!r}")
    return path


def print_warning(message: str) -> None:
    """Print a warning as the command line does: one ``acphys: warning:`` line on stderr."""
    print(f"acphys: warning: {message}", file=sys.stderr)


def write_plot(
    paths: dict[str, BodyPath],
    output: str | Path,
    bodies: Sequence[str] | None = None,
    view: str | None = None,
    title: str = "",
    warn: Callable[[str], None] = print_warning,
) -> Path:
    """Draw the paths of ``bodies`` (default: all) to a PNG at ``output``; returns its path.

    ``view`` is one of :data:`VIEWS` for a single panel; by default the figure
    has the paths from above and height over time side by side. What the
    picture leaves out (samples past :data:`MAX_POINTS`, characters the font
    lacks) is told to ``warn`` once, by default as an ``acphys: warning:`` line
    on stderr.
    """
    output = check_output(output)
    label = one_line(str(output))
    with warnings.catch_warnings(record=True) as caught, _user_text_is_plain():
        warnings.simplefilter("always")
        figure = make_figure(paths, bodies, view, title)
        try:
            figure.savefig(output, format="png")
        except OSError as error:
            raise PlotError(f"{label}: cannot write: {error.strerror or error}") from None
    thinned = [path for path in select_bodies(paths, bodies) if path.stride > 1]
    if thinned:
        warn(f"{label}: {thinning(thinned)}")
    for message in _matplotlib_warnings(caught):
        warn(f"{label}: {message}")
    return output


def thinning(paths: Sequence[BodyPath]) -> str:
    """What a warning says of paths drawn from part of their records (their stride is past 1)."""
    longest = max(paths, key=lambda path: path.stride)
    return (
        f"the longest paths are drawn from 1 record in {longest.stride} ({shown_name(longest.name)!r} "
        f"has {longest.added:,} records); a picture keeps at most {MAX_POINTS:,} samples"
    )


def _matplotlib_warnings(caught: list[warnings.WarningMessage]) -> list[str]:
    """matplotlib's warnings, each once and on one line; missing glyphs are one warning."""
    messages = dict.fromkeys(one_line(str(warning.message)) for warning in caught)
    glyphs = [message for message in messages if _MISSING_GLYPH.match(message)]
    found = [message for message in messages if message not in glyphs]
    if glyphs:
        found.append(f"{len(glyphs)} characters of the labels are not in the font: drawn as boxes")
    return found


_MISSING_GLYPH = re.compile(r"Glyph \d+ .* missing from")


def _user_text_is_plain() -> Any:
    """A matplotlib settings context in which no text is read as maths or LaTeX: the
    names in a picture are the user's (``$x^$`` is a name, not a formula)."""
    import matplotlib

    return matplotlib.rc_context({"text.parse_math": False, "text.usetex": False})


def make_figure(
    paths: dict[str, BodyPath], bodies: Sequence[str] | None = None, view: str | None = None, title: str = ""
) -> Any:
    """The matplotlib ``Figure`` :func:`write_plot` saves (on an Agg canvas; pyplot is not used).

    No text of the figure is read as maths, so a body named ``$x^$`` is drawn as it is named.
    """
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

    with _user_text_is_plain():
        views = DEFAULT_VIEWS if view is None else (view,)
        figure = Figure(figsize=(6.5 * len(views), 6.0), dpi=100, layout="constrained")
        FigureCanvasAgg(figure)
        axes = figure.subplots(1, len(views), squeeze=False)[0]
        colours = [f"C{index % 10}" for index in range(len(selected))]
        for ax, panel in zip(axes, views, strict=True):
            _draw_panel(ax, panel, selected, colours)
        _legend(figure, selected, colours)
        if title:
            figure.suptitle(shown_name(title, limit=2 * SHOWN_NAME))
    return figure


def _panel_data(panel: str, points: Points) -> tuple[array[float], array[float]]:
    if panel == "top":
        return points.x, points.y
    if panel == "side":
        return points.x, points.z
    return points.t, points.z


def _draw_panel(ax: Any, panel: str, selected: list[BodyPath], colours: list[str]) -> None:
    import numpy as np
    from matplotlib.collections import LineCollection

    if len(selected) <= LEGEND_BODIES:
        for path, colour in zip(selected, colours, strict=True):
            ax.plot(*_panel_data(panel, path), color=colour, linewidth=1.5, label=shown_name(path.name))
    else:  # one collection: a Line2D per body would take minutes for thousands of bodies
        lines = [np.column_stack(_panel_data(panel, path)) for path in selected]
        ax.add_collection(LineCollection(lines, colors=colours, linewidths=1.5))
        ax.autoscale_view()
    starts = [(xs[0], ys[0]) for xs, ys in (_panel_data(panel, path) for path in selected)]
    ax.scatter(*zip(*starts, strict=True), marker="o", s=25, c=colours, zorder=3)  # where each starts
    for kind, (_, marker, edge, size) in EVENT_MARKERS.items():
        marks = [_panel_data(panel, path.marks[kind]) for path in selected if kind in path.marks]
        if marks:
            ax.scatter(
                np.concatenate([xs for xs, _ in marks]),
                np.concatenate([ys for _, ys in marks]),
                marker=marker,
                s=size,
                facecolors="none" if kind != "collision" else "red",
                edgecolors=edge,
                linewidths=1.0,
                zorder=3,
            )
    _tick_labels(ax)
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


#: Tick labels are plain numbers (no offset, no exponent) below this magnitude: a landblock-global
#: coordinate is at most 49,152 m; past it they are written in scientific notation.
PLAIN_TICKS = 1e7


def _tick_labels(ax: Any) -> None:
    for axis, limits in (("x", ax.get_xlim()), ("y", ax.get_ylim())):
        plain = max(abs(limit) for limit in limits) < PLAIN_TICKS
        ax.ticklabel_format(axis=axis, useOffset=False, style="plain" if plain else "sci")


def _landblock_seams(ax: Any, selected: list[BodyPath]) -> None:
    """Dashed lines on the landblock edges the paths reach (at most a few dozen)."""
    for values, draw in (([p.x for p in selected], ax.axvline), ([p.y for p in selected], ax.axhline)):
        low = math.floor(min(map(min, values)) / BLOCK_LENGTH)
        high = math.ceil(max(map(max, values)) / BLOCK_LENGTH)
        if high - low <= 40:
            for edge in range(low + 1, high):
                draw(edge * BLOCK_LENGTH, color="0.6", linestyle="--", linewidth=0.8)


def _legend(figure: Any, selected: list[BodyPath], colours: list[str]) -> None:
    from matplotlib.lines import Line2D

    handles = []
    if len(selected) <= LEGEND_BODIES:
        handles += [
            Line2D([], [], color=c, label=shown_name(p.name)) for p, c in zip(selected, colours, strict=True)
        ]
    handles.append(Line2D([], [], marker="o", color="0.4", linestyle="", label="start"))
    seen = {kind for path in selected for kind in path.marks}
    for kind, (label, marker, edge, _) in EVENT_MARKERS.items():
        if kind in seen:
            face = "red" if kind == "collision" else "none"
            handles.append(
                Line2D([], [], marker=marker, color=face, markeredgecolor=edge, linestyle="", label=label)
            )
    figure.legend(handles=handles, fontsize="small", loc="outside right upper")
