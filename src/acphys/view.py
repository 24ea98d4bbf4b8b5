"""``acphys view``: a text picture of a trace, for terminals without a display.

A table per body (first and last position, distance travelled, top speed,
time in contact, event counts) and an ASCII map of the paths from above, in
the landblock-global frame of :mod:`acphys.plot`.
"""

from __future__ import annotations

import math
import string
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from rich.console import Console
from rich.table import Table
from rich.text import Text

from acphys.plot import SHOWN_NAME, BodyPath, print_warning, shown_name, thinning

#: Map symbols, one per body: its path in lower case, where it ends in upper case.
SYMBOLS = string.ascii_uppercase + string.digits
#: Where two bodies' paths share a map cell.
CROSSING = "*"
#: The most rows the table prints: rich lays out about a row a millisecond, so a 100,000-body
#: trace would take minutes (the map still draws every body).
TABLE_ROWS = 1000
STYLES = ("red", "green", "yellow", "blue", "magenta", "cyan", "bright_red", "bright_green")


@dataclass
class BodySummary:
    """One body's path in figures; positions landblock-local, as its trace records have them."""

    name: str
    steps: int
    duration: float
    start_cell: str
    start: tuple[float, float, float]
    end_cell: str
    end: tuple[float, float, float]
    #: Metres along the path, from the first record to the last (3-D, in the global frame).
    distance: float
    #: The fastest the path moved between two records (m/s): root-motion walking counts.
    max_speed: float
    #: Seconds of steps that ended in contact with something.
    contact_time: float
    #: Events by kind (``collision:pillar`` counts as ``collision``).
    events: Counter[str]


def summarise(path: BodyPath) -> BodySummary:
    return BodySummary(
        name=path.name,
        steps=path.added,
        duration=path.t[-1] - path.t[0] if len(path) else 0.0,
        start_cell=path.first_cell,
        start=path.first_origin,
        end_cell=path.last_cell,
        end=path.last_origin,
        distance=path.distance,
        max_speed=path.max_speed,
        contact_time=path.contact_time,
        events=Counter(path.events),
    )


def summary_table(paths: Sequence[BodyPath], title: str = "") -> Table:
    """A row per body (the first :data:`TABLE_ROWS`); positions are the first and last records'
    landblocks and local origins.

    Every name is shown as plain text (a ``[red]`` in it is not rich markup).
    """
    table = Table(title=Text(shown_name(title, limit=3 * SHOWN_NAME)) if title else None)
    table.add_column("body", no_wrap=True)
    table.add_column("start: block x y z", no_wrap=True)
    table.add_column("end: block x y z", no_wrap=True)
    table.add_column("distance m", justify="right")
    table.add_column("max m/s", justify="right")
    table.add_column("contact s", justify="right")
    table.add_column("events", no_wrap=True)
    for index, path in enumerate(paths[:TABLE_ROWS]):
        s = summarise(path)
        name = Text(_symbol(index), style=f"bold {_style(index)}")
        name.append(f" {shown_name(s.name)}", style="")
        events = "\n".join(f"{shown_name(kind)} {count}" for kind, count in sorted(s.events.items()))
        table.add_row(
            name,
            Text(_where(s.start_cell, s.start)),
            Text(_where(s.end_cell, s.end)),
            Text(_figure(s.distance)),
            Text(_figure(s.max_speed)),
            Text(_figure(s.contact_time)),
            Text(events or "-"),
        )
    return table


def ascii_map(paths: Sequence[BodyPath], width: int = 64, height: int = 20) -> list[Text]:
    """The paths from above on a character grid, north up; each body ends at its upper-case symbol.

    A character is taken as twice as tall as it is wide, so distances look the
    same across and down. The last lines give the extent and the scale.
    """
    points = [(x, y) for path in paths for x, y in zip(path.x, path.y, strict=True)]
    x0, x1 = min(p[0] for p in points), max(p[0] for p in points)
    y0, y1 = min(p[1] for p in points), max(p[1] for p in points)
    width, height = max(width, 8), max(height, 4)
    scale = max((x1 - x0) / (width - 1), (y1 - y0) / (2 * (height - 1)), 1e-9)  # metres per column
    if x1 - x0 < 1.0 and y1 - y0 < 1.0:
        scale = max(scale, 0.5)  # a body at rest: a dot, not a magnified jitter
    columns = min(width, math.floor((x1 - x0) / scale) + 1)
    rows = min(height, math.floor((y1 - y0) / (2 * scale)) + 1)
    grid: list[list[int | None]] = [[None] * columns for _ in range(rows)]  # body index, or -1 when shared

    def cell(x: float, y: float) -> tuple[int, int]:
        column = min(columns - 1, round((x - x0) / scale))
        row = rows - 1 - min(rows - 1, round((y - y0) / (2 * scale)))
        return row, column

    def mark(row: int, column: int, index: int) -> None:
        here = grid[row][column]
        grid[row][column] = index if here is None or here == index else -1

    for index, path in enumerate(paths):
        previous: tuple[int, int] | None = None
        for x, y in zip(path.x, path.y, strict=True):
            row, column = cell(x, y)
            if previous is None:
                mark(row, column, index)
            else:
                steps = max(abs(row - previous[0]), abs(column - previous[1]))
                for k in range(1, steps + 1):
                    mark(
                        previous[0] + round((row - previous[0]) * k / steps),
                        previous[1] + round((column - previous[1]) * k / steps),
                        index,
                    )
            previous = (row, column)
    ends = {cell(path.x[-1], path.y[-1]): index for index, path in enumerate(paths) if len(path)}

    lines = [Text("+" + "-" * columns + "+  N ^")]
    for row in range(rows):
        line = Text("|")
        for column in range(columns):
            index = grid[row][column]
            if (row, column) in ends and index is not None:
                end = ends[(row, column)]
                line.append(_symbol(end), style=f"bold {_style(end)}")
            elif index is None:
                line.append(" ")
            elif index < 0:
                line.append(CROSSING)
            else:
                line.append(_symbol(index).lower(), style=_style(index))
        line.append("|")
        lines.append(line)
    lines.append(Text("+" + "-" * columns + "+"))
    lines.append(
        Text(
            f"x (east) {_metres(x0)} to {_metres(x1)} m, y (north) {_metres(y0)} to {_metres(y1)} m, "
            "landblock-global; "
            f"one column {scale:.3g} m, one row {2 * scale:.3g} m; {CROSSING}: paths share a cell"
        )
    )
    legend = Text()
    for index, path in enumerate(paths[: len(SYMBOLS)]):
        if index:
            legend.append("  ")
        legend.append(_symbol(index), style=f"bold {_style(index)}")
        legend.append(f" {shown_name(path.name)}")
    if len(paths) > len(SYMBOLS):
        legend.append(f"  # the other {len(paths) - len(SYMBOLS):,}")
    lines.append(legend)
    return lines


def show(
    console: Console, paths: Sequence[BodyPath], title: str = "", warn: Callable[[str], None] = print_warning
) -> None:
    """Print the table and the map; paths drawn from part of their records are told to ``warn``
    (by default an ``acphys: warning:`` line on stderr)."""
    console.print(summary_table(paths, title))
    map_width = max(8, min(72, console.width - 10))
    for line in ascii_map(paths, width=map_width):
        console.print(line, soft_wrap=True, highlight=False)
    if len(paths) > TABLE_ROWS:
        warn(f"the table lists the first {TABLE_ROWS} of {len(paths):,} bodies; pick others with --bodies")
    thinned = [path for path in paths if path.stride > 1]
    if thinned:
        warn(f"the map: {thinning(thinned)}")


def _symbol(index: int) -> str:
    return SYMBOLS[index] if index < len(SYMBOLS) else "#"


def _style(index: int) -> str:
    return STYLES[index % len(STYLES)]


def _where(cell: str, origin: tuple[float, float, float]) -> str:
    return f"{cell[:6]} {_metres(origin[0])} {_metres(origin[1])} {_metres(origin[2])}"


#: Figures below this magnitude are written with fixed decimals, larger ones in scientific notation.
PLAIN_FIGURES = 1e7


def _metres(value: float) -> str:
    """A coordinate to a tenth of a metre (three figures when it is huge)."""
    return f"{value:.1f}" if abs(value) < PLAIN_FIGURES else f"{value:.3g}"


def _figure(value: float) -> str:
    """A distance, speed or time to the hundredth (three figures when it is huge)."""
    return f"{value:.2f}" if abs(value) < PLAIN_FIGURES else f"{value:.3g}"
