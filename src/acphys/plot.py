"""Pictures of a run (contract 3): a trace's paths over the world they ran in, as PNG, SVG or PDF.

A trace's ``origin`` is local to the landblock named by its ``cell``; here
every sample is moved into the landblock-global frame (landblock ``0xXXYY``'s
south-west corner at ``(XX · 192, YY · 192)`` metres), so a body that crosses
a seam draws one continuous path. :func:`read_paths` reads a trace file,
:class:`PathRecorder` collects the same paths from a running simulation, and
:func:`write_plot` draws them with matplotlib's non-interactive Agg backend:
the paths from above (``top``), from the south (``side``: east against
height) and height over time (``height``), each body's start a circle and its
end a square, with ``hit_ground``, ``leave_ground`` and collision events as
small marks.

The picture's frame (:func:`plot_frame`) is the landblock's own metres for a run
in one landblock, and metres from the south-west landblock's corner for a run
over several, the seams drawn and each landblock named. Under the paths goes
the world (:mod:`acphys.world_sketch`: terrain contours, water, static objects,
buildings, rooms and doorways) of the run at hand, of ``--scenario``, or of the
built-in scenario a trace's header names (:func:`trace_world`).
"""

from __future__ import annotations

import hashlib
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

from acphys.constants import BLOCK_LENGTH, CELL_LENGTH, CELLS_PER_BLOCK
from acphys.inputs import one_line
from acphys.math.cell_id import landblock_of
from acphys.physics_obj import PhysicsObj
from acphys.trace import TraceError, brief, read_header, read_trace, step_record
from acphys.world.terrain import WaterType
from acphys.world_sketch import MAX_SKETCH_FACES, SHAPE_KINDS, ShapeSketch, WorldSketch, sketch_world

#: The panels ``--view`` can pick; without it the figure has ``top`` and ``height``.
VIEWS = ("top", "side", "height")
DEFAULT_VIEWS = ("top", "height")

#: Picture formats by file extension (matplotlib's ``savefig`` format names).
FORMATS = {".png": "png", ".svg": "svg", ".pdf": "pdf"}

#: Events marked on the figure: (label, marker, colour, size), by event kind: small and
#: translucent (:data:`EVENT_ALPHA`), so that a run of them does not hide the path.
EVENT_MARKERS = {
    "hit_ground": ("hit_ground", "v", "#1b7837", 18),
    "leave_ground": ("leave_ground", "^", "#762a83", 18),
    "collision": ("collision", "x", "#d7191c", 22),
}
EVENT_ALPHA = 0.6


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
#: The most bodies the legend names (each its own line, in columns of :data:`LEGEND_ROWS`); more
#: are drawn as one collection, and the legend's title says how many it leaves unnamed.
LEGEND_BODIES = 30
LEGEND_ROWS = 15
#: The most body names an error message lists.
MESSAGE_NAMES = 12
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
    """The first :data:`MESSAGE_NAMES` names as a message shows them (one line), and how many more."""
    shown = ", ".join(shown_name(name) for name in islice(names, MESSAGE_NAMES)) or "none"
    more = len(names) - MESSAGE_NAMES
    return f"{shown} and {more:,} more" if more > 0 else shown


def picture_format(output: str | Path) -> str:
    """The format a picture at ``output`` is written in, by its extension (:data:`FORMATS`); any
    other extension is a :class:`PlotError` naming the ones acphys writes."""
    path = Path(output)
    fmt = FORMATS.get(path.suffix.lower())
    if fmt is None:
        what = f"a {path.suffix!r} file" if path.suffix else "a file without an extension"
        raise PlotError(
            f"{one_line(str(path))}: cannot write {what}: a picture is .png, .svg or .pdf "
            "(the extension picks the format)"
        )
    return fmt


def check_output(output: str | Path) -> Path:
    """The picture's path, if it can be written there in a format acphys writes (checked before
    any work is done)."""
    path = Path(output)
    label = one_line(str(path))
    if path.is_dir():
        raise PlotError(f"{label}: is a directory, not a picture file")
    if path.is_fifo() or path.is_socket():  # a pipe would block the write until someone reads it
        raise PlotError(f"{label}: cannot write: not a regular file")
    picture_format(path)
    parent = path.parent
    if not parent.is_dir():
        raise PlotError(f"{label}: cannot write: no directory {one_line(str(parent))!r}")
    return path


def print_warning(message: str) -> None:
    """Print a warning as the command line does: one ``acphys: warning:`` line on stderr."""
    print(f"acphys: warning: {message}", file=sys.stderr)


# -- the world under a trace ------------------------------------------------------------------


@dataclass
class TraceWorld:
    """What :func:`trace_world` found for a trace: the world to draw (None: paths only), the
    picture's title and a note for the user (None when there is nothing to say)."""

    world: WorldSketch | None
    title: str
    note: str | None = None


def scenario_sha256(name: str) -> str:
    """The SHA-256 a trace header gives for the built-in scenario ``name`` (of its text, UTF-8)."""
    from acphys.scenario import builtin_scenario_text

    return hashlib.sha256(builtin_scenario_text(name).encode("utf-8")).hexdigest()


def trace_world(trace: str | Path, scenario: str | None = None) -> TraceWorld:
    """The world a trace was run in, for its picture.

    With ``scenario`` (a file or a built-in name, as ``acphys run`` takes it) that scenario is
    built and drawn under the paths. Without it, the trace's header names the scenario: a
    built-in one whose SHA-256 is the header's is built; anything else (a scenario of the
    user's, a changed built-in, a v1 trace without a header) leaves the paths alone, with a
    note saying so. A scenario that cannot be built is a :class:`ScenarioError`.
    """
    from acphys.scenario import builtin_scenarios, load_scenario

    label = one_line(str(trace))
    header = read_header(trace)
    named = header.get("scenario") if isinstance(header, dict) else None
    name = named.get("name") if isinstance(named, dict) else None
    sha = named.get("sha256") if isinstance(named, dict) else None
    name = name if isinstance(name, str) and name else None
    if scenario is not None:
        sim = load_scenario(scenario)
        note = None
        if isinstance(sha, str) and sim.scenario_sha256 is not None and sha != sim.scenario_sha256:
            note = (
                f"{label}: the trace was written from another text than {one_line(scenario)!r} "
                f"(its scenario {shown_name(name or '?')!r} has another sha256): drawn over it all the same"
            )
        return TraceWorld(sketch_world(sim), sim.name or name or Path(trace).name, note)
    hint = "give --scenario FILE to draw its world"
    if name is None:
        return TraceWorld(
            None, Path(trace).name, f"{label}: the trace names no scenario: paths only ({hint})"
        )
    if name not in builtin_scenarios():
        return TraceWorld(
            None, name, f"{label}: scenario {shown_name(name)!r} is not built in: paths only ({hint})"
        )
    if sha != scenario_sha256(name):
        return TraceWorld(
            None,
            name,
            f"{label}: scenario {name!r} is not the built-in text (another sha256): paths only ({hint})",
        )
    return TraceWorld(sketch_world(load_scenario(name)), name)


# -- the picture ------------------------------------------------------------------------------


def write_plot(
    paths: dict[str, BodyPath],
    output: str | Path,
    bodies: Sequence[str] | None = None,
    view: str | None = None,
    title: str = "",
    warn: Callable[[str], None] = print_warning,
    world: WorldSketch | None = None,
) -> Path:
    """Draw the paths of ``bodies`` (default: all) over ``world`` (if given) to ``output``, a PNG,
    SVG or PDF by its extension; returns its path.

    ``view`` is one of :data:`VIEWS` for a single panel; by default the figure
    has the paths from above and height over time side by side. ``title`` is
    the scenario's name. What the picture leaves out (samples past
    :data:`MAX_POINTS`, faces past the sketch's limit, characters the font
    lacks) is told to ``warn`` once, by default as an ``acphys: warning:`` line
    on stderr.
    """
    output = check_output(output)
    fmt = picture_format(output)
    label = one_line(str(output))
    with warnings.catch_warnings(record=True) as caught, _user_text_is_plain():
        warnings.simplefilter("always")
        figure = make_figure(paths, bodies, view, title, world=world)
        try:
            figure.savefig(output, format=fmt, metadata=_REPRODUCIBLE.get(fmt))
        except OSError as error:
            raise PlotError(f"{label}: cannot write: {error.strerror or error}") from None
    thinned = [path for path in select_bodies(paths, bodies) if path.stride > 1]
    if thinned:
        warn(f"{label}: {thinning(thinned)}")
    if world is not None and world.faces_left_out:
        warn(
            f"{label}: the world has more faces than a picture keeps ({MAX_SKETCH_FACES:,}): "
            f"{world.faces_left_out:,} left out"
        )
    for message in _matplotlib_warnings(caught):
        warn(f"{label}: {message}")
    return output


#: What each format's file records of when it was made: nothing, so one picture is one file.
_REPRODUCIBLE: dict[str, dict[str, Any]] = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}


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
    names in a picture are the user's (``$x^$`` is a name, not a formula); SVG ids are salted
    the same way every time."""
    import matplotlib

    return matplotlib.rc_context({"text.parse_math": False, "text.usetex": False, "svg.hashsalt": "acphys"})


@dataclass(frozen=True)
class PlotFrame:
    """The frame a picture's x and y are in: metres from ``origin`` (landblock-global metres).

    ``blocks`` is ``(x0, x1, y0, y1)``, the landblock columns and rows the picture spans
    (inclusive), and ``origin`` the south-west corner of landblock ``(x0, y0)``: for a run in one
    landblock, its own local metres. None when the paths reach past the map (a hand-made trace):
    then the frame is landblock-global.
    """

    origin: tuple[float, float] = (0.0, 0.0)
    blocks: tuple[int, int, int, int] | None = None

    @property
    def single(self) -> bool:
        return (
            self.blocks is not None and self.blocks[0] == self.blocks[1] and self.blocks[2] == self.blocks[3]
        )

    def describe(self) -> str:
        """What an axis label says of the frame."""
        if self.blocks is None:
            return "landblock-global"
        block = f"0x{self.blocks[0]:02X}{self.blocks[2]:02X}"
        return f"in landblock {block}" if self.single else f"from {block}'s south-west corner"


#: The most landblock seams a panel draws along each axis, and the most landblocks it labels.
MAX_SEAMS = 40
MAX_BLOCK_LABELS = 64


def plot_frame(selected: Sequence[BodyPath], world: WorldSketch | None = None) -> PlotFrame:
    """The frame for ``selected`` over ``world``: the landblocks they reach (see :class:`PlotFrame`)."""
    xs = [value for path in selected if len(path) for value in (min(path.x), max(path.x))]
    ys = [value for path in selected if len(path) for value in (min(path.y), max(path.y))]
    if world is not None:
        for terrain in world.terrain:
            x, y = terrain.corner
            xs.append(x)
            ys.append(y)
        for shape in world.shapes:
            xs.append(shape.anchor[0])
            ys.append(shape.anchor[1])
    if not xs:
        return PlotFrame()
    x0, x1 = math.floor(min(xs) / BLOCK_LENGTH), math.floor(max(xs) / BLOCK_LENGTH)
    y0, y1 = math.floor(min(ys) / BLOCK_LENGTH), math.floor(max(ys) / BLOCK_LENGTH)
    if not all(0 <= value <= 0xFF for value in (x0, x1, y0, y1)):
        return PlotFrame()
    return PlotFrame((x0 * BLOCK_LENGTH, y0 * BLOCK_LENGTH), (x0, x1, y0, y1))


def body_colours(count: int) -> list[Any]:
    """A colour per body: tab10 up to 10 bodies, tab20 up to 20, past that evenly along a
    continuous colormap (neighbours in the run order still differ)."""
    from matplotlib import colormaps

    if count <= 10:
        return [colormaps["tab10"](index) for index in range(count)]
    if count <= 20:
        return [colormaps["tab20"](index) for index in range(count)]
    import numpy as np

    table = colormaps["turbo"](np.linspace(0.0, 1.0, 256))  # interpolated: past 256 bodies still distinct
    where = np.linspace(0.05, 0.95, count) * 255
    channels = [np.interp(where, np.arange(256), table[:, channel]) for channel in range(4)]
    return [tuple(float(value) for value in rgba) for rgba in zip(*channels, strict=True)]


def make_figure(
    paths: dict[str, BodyPath],
    bodies: Sequence[str] | None = None,
    view: str | None = None,
    title: str = "",
    world: WorldSketch | None = None,
) -> Any:
    """The matplotlib ``Figure`` :func:`write_plot` saves (on an Agg canvas; pyplot is not used).

    The paths are drawn in the frame of :func:`plot_frame` over ``world``'s terrain (contours,
    water), objects, buildings, rooms and doorways; each body's start is a circle and its end a
    square. No text of the figure is read as maths, so a body named ``$x^$`` is drawn as it is
    named.
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
        figure = Figure(figsize=(6.5 * len(views) + 1.5, 7.0), dpi=100, layout="constrained")
        FigureCanvasAgg(figure)
        axes = figure.subplots(1, len(views), squeeze=False)[0]
        selected = [path for path in selected if len(path)]
        colours = body_colours(len(selected))
        frame = plot_frame(selected, world)
        drawn: set[str] = set()
        for ax, panel in zip(axes, views, strict=True):
            if panel == "top":
                drawn |= _draw_top(ax, selected, colours, frame, world)
            elif panel == "side":
                drawn |= _draw_side(ax, selected, colours, frame, world)
            else:
                drawn |= _draw_height(ax, selected, colours)
        _legends(figure, selected, colours, drawn)
        figure.suptitle(_title(title, selected, frame), fontsize="large")
    return figure


def _title(title: str, selected: Sequence[BodyPath], frame: PlotFrame) -> str:
    """The scenario's name, and under it the time span, the bodies and the landblocks."""
    start = min(path.t[0] for path in selected)
    end = max(path.t[-1] for path in selected)
    count = f"{len(selected):,} {'body' if len(selected) == 1 else 'bodies'}"
    where = ""
    if frame.blocks is not None:
        x0, x1, y0, y1 = frame.blocks
        where = (
            f"landblock 0x{x0:02X}{y0:02X}"
            if frame.single
            else f"landblocks 0x{x0:02X}{y0:02X} to 0x{x1:02X}{y1:02X}"
        )
    span = f"t {_number_text(start)} to {_number_text(end)} s"
    name = shown_name(title, limit=2 * SHOWN_NAME) if title else "(unnamed)"
    return f"{name}\n" + " · ".join(part for part in (span, count, where) if part)


def _number_text(value: float) -> str:
    return f"{value:.2f}" if abs(value) < PLAIN_TICKS else f"{value:.3g}"


# -- panels -----------------------------------------------------------------------------------

#: Styles of the world's things: face colour, edge colour, edge width, line colour and width
#: (a face seen edge-on is a line), and the stacking order.
_SHAPE_STYLES: dict[str, dict[str, Any]] = {
    "building": {
        "face": "none",
        "edge": "#757575",
        "width": 0.8,
        "line": "#616161",
        "line_width": 1.2,
        "z": 1.2,
    },
    "room": {
        "face": "#ecdcc0",
        "edge": "#8d6e63",
        "width": 0.6,
        "line": "#5d4037",
        "line_width": 1.6,
        "z": 1.3,
    },
    "object": {
        "face": "#b8b8b8",
        "edge": "#4a4a4a",
        "width": 0.7,
        "line": "#4a4a4a",
        "line_width": 1.0,
        "z": 1.5,
    },
    "doorway": {
        "face": "#ffb74d",
        "edge": "#e65100",
        "width": 0.8,
        "line": "#ef6c00",
        "line_width": 2.6,
        "z": 1.6,
    },
}
_GROUND = "#f6f3ea"
_GROUND_EDGE = "#a1887f"
_CONTOUR = "#8d6e63"
_WATER = "#4f8fd6"
#: The shading of the ground by height (the pale part of this colormap): pale yellow low, light brown high.
_ELEVATION = "YlOrBr"
#: The opacity of the world's faces seen from the south.
SIDE_ALPHA = 0.3
#: How many of the world's things a panel names (more would hide the paths).
MAX_SHAPE_LABELS = 40
#: Below this spread of heights (m) the ground is flat: no contours.
FLAT = 0.01


def _shifted(points: Points, panel: str, frame: PlotFrame) -> tuple[Any, Any]:
    """A series' coordinates in a panel, in the picture's frame."""
    import numpy as np

    if panel == "top":
        return np.asarray(points.x) - frame.origin[0], np.asarray(points.y) - frame.origin[1]
    if panel == "side":
        return np.asarray(points.x) - frame.origin[0], np.asarray(points.z)
    return np.asarray(points.t), np.asarray(points.z)


def _draw_paths(
    ax: Any, panel: str, selected: list[BodyPath], colours: list[Any], frame: PlotFrame
) -> set[str]:
    """The paths, their events, where each starts (a circle) and ends (a square); returns the
    event kinds drawn."""
    import numpy as np
    from matplotlib.collections import LineCollection

    data = [_shifted(path, panel, frame) for path in selected]
    width = 1.6 if len(selected) <= LEGEND_BODIES else 1.0
    if len(selected) <= LEGEND_BODIES:
        for path, (xs, ys), colour in zip(selected, data, colours, strict=True):
            ax.plot(xs, ys, color=colour, linewidth=width, label=shown_name(path.name), zorder=3)
    else:  # one collection: a Line2D per body would take minutes for thousands of bodies
        lines = [np.column_stack(xy) for xy in data]
        ax.add_collection(LineCollection(lines, colors=colours, linewidths=width, zorder=3))
    kinds: set[str] = set()
    for kind, (_, marker, colour, size) in EVENT_MARKERS.items():
        marks = [_shifted(path.marks[kind], panel, frame) for path in selected if kind in path.marks]
        if marks:
            kinds.add(kind)
            line_marker = marker in ("x", "+")
            ax.scatter(
                np.concatenate([xs for xs, _ in marks]),
                np.concatenate([ys for _, ys in marks]),
                marker=marker,
                s=size,
                c=colour,
                alpha=EVENT_ALPHA,
                linewidths=1.0 if line_marker else 0.4,
                **({} if line_marker else {"edgecolors": "white"}),
                zorder=4,
                label=f"_{kind}",
            )
    # The start circle is larger than the end square: a body that ends where it started shows both.
    few = len(selected) <= LEGEND_BODIES
    size, edge = (30, 0.7) if few else (12, 0.25)
    starts = np.array([(xs[0], ys[0]) for xs, ys in data])
    ends = np.array([(xs[-1], ys[-1]) for xs, ys in data])
    ax.scatter(
        starts[:, 0],
        starts[:, 1],
        marker="o",
        s=2.2 * size,
        c=colours,
        edgecolors="black",
        linewidths=edge,
        zorder=5,
        label="_start",
    )
    ax.scatter(
        ends[:, 0],
        ends[:, 1],
        marker="s",
        s=size,
        c=colours,
        edgecolors="black",
        linewidths=edge,
        zorder=5,
        label="_end",
    )
    return kinds


def _draw_top(
    ax: Any, selected: list[BodyPath], colours: list[Any], frame: PlotFrame, world: WorldSketch | None
) -> set[str]:
    """The paths from above, over the ground, water and the world's things; returns what was drawn."""
    drawn = _draw_paths(ax, "top", selected, colours, frame)
    xlim, ylim = _top_limits(selected, frame, world)
    if world is not None:
        drawn |= _draw_terrain(ax, world, frame)
        drawn |= _draw_shapes(ax, world, frame, (0, 1), xlim, ylim)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_aspect("equal", adjustable="box")
    _seams(ax, frame, xlim, ylim, horizontal=True)
    _tick_labels(ax)
    ax.grid(True, color="0.85", linewidth=0.5, zorder=0)
    ax.set_axisbelow(True)
    ax.set_title("from above")
    ax.set_xlabel(f"x: east (m, {frame.describe()})")
    ax.set_ylabel(f"y: north (m, {frame.describe()})")
    return drawn


def _draw_side(
    ax: Any, selected: list[BodyPath], colours: list[Any], frame: PlotFrame, world: WorldSketch | None
) -> set[str]:
    """The paths from the south (east against height) over the ground's profile and the world's things."""
    drawn = _draw_paths(ax, "side", selected, colours, frame)
    xlim, _ = _top_limits(selected, frame, world, square=False)
    zs = [value for path in selected for value in (min(path.z), max(path.z))]
    if world is not None:
        drawn |= _draw_profile(ax, world, frame, selected, xlim, zs)
        drawn |= _draw_shapes(ax, world, frame, (0, 2), xlim, None, zs)
    zlim = _padded(min(zs), max(zs), minimum=2.0)
    ax.set_xlim(*xlim)
    ax.set_ylim(*zlim)
    _seams(ax, frame, xlim, zlim, horizontal=False)
    _tick_labels(ax)
    ax.grid(True, color="0.85", linewidth=0.5)
    ax.set_axisbelow(True)
    ax.set_title("from the south")
    ax.set_xlabel(f"x: east (m, {frame.describe()})")
    ax.set_ylabel("z: height (m)")
    return drawn


def _draw_height(ax: Any, selected: list[BodyPath], colours: list[Any]) -> set[str]:
    """Height over time."""
    drawn = _draw_paths(ax, "height", selected, colours, PlotFrame())
    _tick_labels(ax)
    ax.grid(True, color="0.85", linewidth=0.5)
    ax.set_axisbelow(True)
    ax.set_title("height over time")
    ax.set_xlabel("t: physics time (s)")
    ax.set_ylabel("z: height (m)")
    return drawn


def _padded(low: float, high: float, minimum: float) -> tuple[float, float]:
    """``low`` to ``high`` with a margin, at least ``minimum`` wide."""
    span = high - low
    pad = max(0.06 * span, (minimum - span) / 2 if span < minimum else 0.0, 0.5)
    return low - pad, high + pad


def _top_limits(
    selected: Sequence[BodyPath], frame: PlotFrame, world: WorldSketch | None, square: bool = True
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The x and y a panel shows, in the picture's frame: the paths and the world's things with a
    margin, at least half as tall as wide (and wide as tall), within the landblocks when they are."""
    xs = [value for path in selected for value in (min(path.x), max(path.x))]
    ys = [value for path in selected for value in (min(path.y), max(path.y))]
    if world is not None:
        for shape in world.shapes:
            low, high = shape.bounds()
            xs += [float(low[0]), float(high[0])]
            ys += [float(low[1]), float(high[1])]
    x0, x1 = min(xs) - frame.origin[0], max(xs) - frame.origin[0]
    y0, y1 = min(ys) - frame.origin[1], max(ys) - frame.origin[1]
    xlim, ylim = _padded(x0, x1, minimum=6.0), _padded(y0, y1, minimum=6.0)
    if square:
        xlim, ylim = _at_least_half(xlim, ylim), _at_least_half(ylim, xlim)
    if frame.blocks is not None:
        bx0, bx1, by0, by1 = frame.blocks
        area_x = (0.0, (bx1 - bx0 + 1) * BLOCK_LENGTH)
        area_y = (0.0, (by1 - by0 + 1) * BLOCK_LENGTH)
        if area_x[0] <= x0 and x1 <= area_x[1]:
            xlim = (max(xlim[0], area_x[0]), min(xlim[1], area_x[1]))
        if area_y[0] <= y0 and y1 <= area_y[1]:
            ylim = (max(ylim[0], area_y[0]), min(ylim[1], area_y[1]))
    return xlim, ylim


def _at_least_half(limits: tuple[float, float], other: tuple[float, float]) -> tuple[float, float]:
    span, wanted = limits[1] - limits[0], (other[1] - other[0]) / 2
    if span >= wanted:
        return limits
    middle = (limits[0] + limits[1]) / 2
    return middle - wanted / 2, middle + wanted / 2


def _draw_terrain(ax: Any, world: WorldSketch, frame: PlotFrame) -> set[str]:
    """Each landblock's ground (a pale square), its height contours (labelled in metres) and its
    water (cells wholly under water dark, partly light)."""
    import numpy as np
    from matplotlib import colormaps
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import ListedColormap, Normalize, to_rgba
    from matplotlib.patches import Rectangle
    from matplotlib.ticker import MaxNLocator
    from matplotlib.tri import Triangulation

    drawn: set[str] = set()
    squares, water, shades = [], [], []
    size = CELL_LENGTH
    for terrain in world.terrain:
        x, y = terrain.corner[0] - frame.origin[0], terrain.corner[1] - frame.origin[1]
        squares.append(
            [(x, y), (x + BLOCK_LENGTH, y), (x + BLOCK_LENGTH, y + BLOCK_LENGTH), (x, y + BLOCK_LENGTH)]
        )
        for index, kind in enumerate(terrain.water):
            if kind != WaterType.NOT_WATER:
                cx = x + (index // CELLS_PER_BLOCK) * size
                cy = y + (index % CELLS_PER_BLOCK) * size
                water.append([(cx, cy), (cx + size, cy), (cx + size, cy + size), (cx, cy + size)])
                shades.append(to_rgba(_WATER, 0.55 if kind == WaterType.ENTIRELY_WATER else 0.22))
    if squares:
        ground = PolyCollection(
            squares, facecolors=_GROUND, edgecolors=_GROUND_EDGE, linewidths=0.6, zorder=0.5, gid="ground"
        )
        ax.add_collection(ground)
        drawn.add("ground")
    if water:
        ax.add_collection(
            PolyCollection(water, facecolors=shades, edgecolors="none", zorder=0.9, gid="water")
        )
        drawn.add("water")
    heights = np.concatenate([terrain.z for terrain in world.terrain]) if world.terrain else np.zeros(0)
    if heights.size and heights.max() - heights.min() > FLAT:
        levels = MaxNLocator(nbins=12, steps=[1, 2, 2.5, 5, 10]).tick_values(heights.min(), heights.max())
        levels = levels[(levels > heights.min()) & (levels < heights.max())]
        margin = 1e-3 * (heights.max() - heights.min())  # ground flat at the lowest or highest is shaded too
        bands = [heights.min() - margin, *levels, heights.max() + margin]
        if levels.size:
            elevation = ListedColormap(
                colormaps[_ELEVATION](np.linspace(0.0, 0.45, 64)), name="acphys-ground"
            )
            norm = Normalize(heights.min(), heights.max())
            for terrain in world.terrain:
                x, y = terrain.corner[0] - frame.origin[0], terrain.corner[1] - frame.origin[1]
                if terrain.z.max() - terrain.z.min() <= FLAT:  # a flat landblock: one shade, no contour
                    square = Rectangle((x, y), BLOCK_LENGTH, BLOCK_LENGTH, zorder=0.6, gid="elevation")
                    square.set(facecolor=elevation(norm(terrain.z.mean())), edgecolor="none")
                    ax.add_patch(square)
                    continue
                mesh = Triangulation(
                    terrain.x - frame.origin[0], terrain.y - frame.origin[1], terrain.triangles
                )
                shading = ax.tricontourf(
                    mesh, terrain.z, levels=bands, cmap=elevation, norm=norm, zorder=0.6, antialiased=False
                )
                shading.set_gid("elevation")
                contours = ax.tricontour(
                    mesh, terrain.z, levels=levels, colors=_CONTOUR, linewidths=0.7, alpha=0.8, zorder=0.8
                )
                contours.set_gid("contours")
                if len(world.terrain) <= MAX_BLOCK_LABELS // 4:
                    ax.clabel(contours, fontsize=6.5, fmt="%g m", inline=True, inline_spacing=2)
            drawn.add("contours")
    return drawn


def _heights_at(world: WorldSketch, xs: Any, ys: Any) -> Any:
    """The ground's height at global ``(xs, ys)`` (NaN where there is no terrain)."""
    import numpy as np
    from matplotlib.tri import LinearTriInterpolator, Triangulation

    heights = np.full(np.shape(xs), np.nan)
    for terrain in world.terrain:
        inside = (
            (xs >= terrain.corner[0])
            & (xs <= terrain.corner[0] + BLOCK_LENGTH)
            & (ys >= terrain.corner[1])
            & (ys <= terrain.corner[1] + BLOCK_LENGTH)
        )
        if inside.any():
            mesh = Triangulation(terrain.x, terrain.y, terrain.triangles)
            found = LinearTriInterpolator(mesh, terrain.z)(xs[inside], ys[inside])
            heights[inside] = np.ma.filled(found, np.nan)
    return heights


def _draw_profile(
    ax: Any,
    world: WorldSketch,
    frame: PlotFrame,
    selected: list[BodyPath],
    xlim: tuple[float, float],
    zs: list[float],
) -> set[str]:
    """The ground seen from the south over the strip of y the paths cover: the band between its
    lowest and highest there, with its top drawn."""
    import numpy as np

    if not world.terrain:
        return set()
    low_y = min(min(path.y) for path in selected)
    high_y = max(max(path.y) for path in selected)
    xs = np.linspace(xlim[0], xlim[1], 241) + frame.origin[0]
    strip = np.linspace(low_y, high_y, 9 if high_y > low_y else 1)
    grid_x, grid_y = np.meshgrid(xs, strip)
    heights = _heights_at(world, grid_x, grid_y)
    if np.isnan(heights).all():
        return set()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # columns with no terrain: NaN
        low, high = np.nanmin(heights, axis=0), np.nanmax(heights, axis=0)
    x = xs - frame.origin[0]
    ax.fill_between(
        x,
        np.nanmin(low) - 1.0 if np.isfinite(low).any() else 0.0,
        high,
        color=_GROUND,
        edgecolor="none",
        zorder=0.5,
        gid="ground",
    )
    ax.fill_between(x, low, high, color=_GROUND_EDGE, alpha=0.35, edgecolor="none", zorder=0.6)
    ax.plot(x, high, color=_GROUND_EDGE, linewidth=1.0, zorder=0.7, label="_ground")
    zs += [float(np.nanmin(low)), float(np.nanmax(high))]
    return {"ground"}


def _project(face: Any, dims: tuple[int, int]) -> tuple[Any, bool]:
    """A face seen along the third axis: its outline, or (edge-on) the segment it covers."""
    import numpy as np

    flat = face[:, dims]
    x, y = flat[:, 0], flat[:, 1]
    area = 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
    if area > 1e-4:
        return flat, True
    distances = ((flat[:, None, :] - flat[None, :, :]) ** 2).sum(axis=-1)
    i, j = np.unravel_index(int(np.argmax(distances)), distances.shape)
    return flat[[i, j]], False


def _draw_shapes(
    ax: Any,
    world: WorldSketch,
    frame: PlotFrame,
    dims: tuple[int, int],
    xlim: tuple[float, float],
    ylim: tuple[float, float] | None,
    zs: list[float] | None = None,
) -> set[str]:
    """The world's things seen from above (``dims`` (0, 1)) or from the south ((0, 2)): faces
    filled, faces seen edge-on as lines, spheres and cylinders as circles (and from the south,
    cylinders as rectangles); objects and rooms named."""
    import numpy as np
    from matplotlib.collections import LineCollection, PatchCollection, PolyCollection
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Circle, Rectangle

    shift = np.array([frame.origin[0] if d == 0 else frame.origin[1] if d == 1 else 0.0 for d in dims])
    drawn: set[str] = set()
    labels = 0
    top = dims == (0, 1)
    for kind in SHAPE_KINDS:
        shapes = world.of_kind(kind)
        if not shapes:
            continue
        style = _SHAPE_STYLES[kind]
        polygons, lines, patches, anchors = [], [], [], []
        for shape in shapes:
            for face in shape.faces:
                outline, filled = _project(face, dims)
                (polygons if filled else lines).append(outline - shift)
            for x, y, z, r in shape.spheres:
                centre = (x, y) if top else (x, z)
                patches.append(Circle((centre[0] - shift[0], centre[1] - shift[1]), r))
            for x, y, z, r, h in shape.cylinders:
                if top:
                    patches.append(Circle((x - shift[0], y - shift[1]), r))
                else:
                    patches.append(Rectangle((x - r - shift[0], z), 2 * r, h))
            if shape.empty:
                anchor = (shape.anchor[0], shape.anchor[1] if top else shape.anchor[2])
                anchors.append((anchor[0] - shift[0], anchor[1] - shift[1]))
            if zs is not None:
                low, high = shape.bounds()
                zs += [float(low[2]), float(high[2])]
        z = style["z"]
        # From the south, faces one behind another: translucent, so the nearer hide nothing.
        face = style["face"] if top or style["face"] == "none" else to_rgba(style["face"], SIDE_ALPHA)
        filled = {"facecolors": face, "edgecolors": style["edge"], "linewidths": style["width"]}
        if polygons:
            ax.add_collection(PolyCollection(polygons, **filled, zorder=z, gid=kind))
        if lines:
            ax.add_collection(
                LineCollection(
                    lines,
                    colors=style["line"],
                    linewidths=style["line_width"],
                    zorder=z + 0.01,
                    gid=f"{kind} lines",
                )
            )
        if patches:
            ax.add_collection(PatchCollection(patches, **filled, zorder=z, gid=kind))
        if anchors:
            ax.scatter(*np.array(anchors).T, marker="+", s=30, c=style["edge"], zorder=z, label=f"_{kind}")
        drawn.add(kind)
        if top and kind in ("object", "room"):
            labels += _name_shapes(ax, shapes, shift, xlim, ylim, MAX_SHAPE_LABELS - labels)
    return drawn


def _name_shapes(
    ax: Any,
    shapes: list[ShapeSketch],
    shift: Any,
    xlim: tuple[float, float],
    ylim: tuple[float, float] | None,
    room: int,
) -> int:
    """Name the shapes inside the panel at their middles (from above), at most ``room`` of them."""
    inside = []
    for shape in shapes:
        low, high = shape.bounds()
        x = (low[0] + high[0]) / 2 - shift[0]
        # A room's name near its north wall, out of the way of a path through its doors.
        y = low[1] + (0.8 if shape.kind == "room" else 0.5) * (high[1] - low[1]) - shift[1]
        if xlim[0] <= x <= xlim[1] and (ylim is None or ylim[0] <= y <= ylim[1]):
            inside.append((shape, x, y))
    if len(inside) > room:
        return 0
    for shape, x, y in inside:
        ax.annotate(
            shown_name(shape.name, limit=24),
            (x, y),
            fontsize=6.5,
            color="0.15",
            ha="center",
            va="center",
            zorder=2.5,
            annotation_clip=True,
            bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "edgecolor": "none", "alpha": 0.6},
        )
    return len(inside)


def _seams(
    ax: Any, frame: PlotFrame, xlim: tuple[float, float], ylim: tuple[float, float], horizontal: bool
) -> None:
    """Dashed lines on the landblock edges inside the panel, each landblock named (from above),
    or each column of landblocks (from the south)."""
    if frame.blocks is None or frame.single:
        return
    bx0, bx1, by0, by1 = frame.blocks
    if bx1 - bx0 > MAX_SEAMS or by1 - by0 > MAX_SEAMS:
        return
    style = {"color": "0.45", "linestyle": (0, (6, 4)), "linewidth": 0.9, "zorder": 2}
    columns = [(bx, bx - bx0) for bx in range(bx0, bx1 + 1)]
    rows = [(by, by - by0) for by in range(by0, by1 + 1)]
    for _, offset in columns[1:]:
        if xlim[0] < offset * BLOCK_LENGTH < xlim[1]:
            ax.axvline(offset * BLOCK_LENGTH, **style)
    if horizontal:
        for _, offset in rows[1:]:
            if ylim[0] < offset * BLOCK_LENGTH < ylim[1]:
                ax.axhline(offset * BLOCK_LENGTH, **style)
    text = {
        "fontsize": 7,
        "color": "0.3",
        "zorder": 2,
        "bbox": {"boxstyle": "round,pad=0.2", "facecolor": "white", "edgecolor": "0.6", "alpha": 0.8},
    }
    labels = 0
    for bx, column in columns:
        left = max(column * BLOCK_LENGTH, xlim[0])
        if left >= min((column + 1) * BLOCK_LENGTH, xlim[1]):
            continue
        if not horizontal:
            ax.text(
                left, 0.99, f" 0x{bx:02X}··", transform=ax.get_xaxis_transform(), va="top", ha="left", **text
            )
            continue
        for by, row in rows:
            bottom = max(row * BLOCK_LENGTH, ylim[0])
            if bottom >= min((row + 1) * BLOCK_LENGTH, ylim[1]) or labels == MAX_BLOCK_LABELS:
                continue
            labels += 1
            ax.annotate(
                f"0x{bx:02X}{by:02X}",
                (left, bottom),
                xytext=(3, 3),
                textcoords="offset points",
                va="bottom",
                ha="left",
                **text,
            )


#: Tick labels are plain numbers (no offset, no exponent) below this magnitude: a landblock-global
#: coordinate is at most 49,152 m; past it they are written in scientific notation.
PLAIN_TICKS = 1e7


def _tick_labels(ax: Any) -> None:
    for axis, limits in (("x", ax.get_xlim()), ("y", ax.get_ylim())):
        plain = max(abs(limit) for limit in limits) < PLAIN_TICKS
        ax.ticklabel_format(axis=axis, useOffset=False, style="plain" if plain else "sci")


_KEY_LABELS = {
    "ground": ("patch", {"facecolor": _GROUND, "edgecolor": _GROUND_EDGE}, "ground"),
    "contours": ("line", {"color": _CONTOUR, "linewidth": 0.8}, "height contour"),
    "water": ("patch", {"facecolor": _WATER, "alpha": 0.55, "edgecolor": "none"}, "water (paler: in part)"),
    "building": ("patch", {"facecolor": "none", "edgecolor": _SHAPE_STYLES["building"]["edge"]}, "building"),
    "room": (
        "patch",
        {"facecolor": _SHAPE_STYLES["room"]["face"], "edgecolor": _SHAPE_STYLES["room"]["line"]},
        "room",
    ),
    "object": (
        "patch",
        {"facecolor": _SHAPE_STYLES["object"]["face"], "edgecolor": _SHAPE_STYLES["object"]["edge"]},
        "object",
    ),
    "doorway": ("line", {"color": _SHAPE_STYLES["doorway"]["line"], "linewidth": 2.6}, "doorway"),
}


def legend_entries(count: int) -> list[int]:
    """Which of ``count`` bodies the legend names, by index: all up to :data:`LEGEND_BODIES`, past
    that :data:`LEGEND_BODIES` of them spread evenly from the first to the last."""
    if count <= LEGEND_BODIES:
        return list(range(count))
    return sorted({round(k * (count - 1) / (LEGEND_BODIES - 1)) for k in range(LEGEND_BODIES)})


def _legends(figure: Any, selected: list[BodyPath], colours: list[Any], drawn: set[str]) -> None:
    """The bodies' legend (right of the panels: every name up to :data:`LEGEND_BODIES`, in columns
    of :data:`LEGEND_ROWS`; past that as many spread evenly over the run order, so their colours
    span the colormap, its title saying how many are not named), and the key (below): start,
    end, each event kind and each kind of world thing drawn."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    count = len(selected)
    shown = legend_entries(count)
    handles = [
        Line2D([], [], color=colours[index], linewidth=2.0, label=shown_name(selected[index].name))
        for index in shown
    ]
    title = f"{count:,} {'body' if count == 1 else 'bodies'}"
    if count > len(shown):
        title += f": {len(shown)} named\n(spread over the run order),\n{count - len(shown):,} not named"
    columns = max(1, math.ceil(len(handles) / LEGEND_ROWS))
    figure.legend(
        handles=handles,
        title=title,
        fontsize="small",
        title_fontsize="small",
        loc="outside right upper",
        ncols=columns,
    )
    key = [
        Line2D([], [], marker="o", color="0.6", markeredgecolor="black", linestyle="", label="start"),
        Line2D([], [], marker="s", color="0.6", markeredgecolor="black", linestyle="", label="end"),
    ]
    for kind, (label, marker, colour, _) in EVENT_MARKERS.items():
        if kind in drawn:
            key.append(
                Line2D([], [], marker=marker, color=colour, linestyle="", alpha=EVENT_ALPHA, label=label)
            )
    for item, (how, style, label) in _KEY_LABELS.items():
        if item in drawn:
            key.append(
                Patch(label=label, **style) if how == "patch" else Line2D([], [], label=label, **style)
            )
    figure.legend(
        handles=key, fontsize="small", loc="outside lower center", ncols=min(len(key), 8), frameon=False
    )
