"""Run one scenario on both engines and compare their traces byte for byte.

The fast engine is held to the reference engine's exact output: the two traces of a scenario
must be the same bytes past their headers, and the headers the same but for the ``engine`` they
name. :func:`compare_engines` runs both and, when they differ, names the first
record, body and field (``acphys diff --tol 0``), or the first differing line when the values are
equal but their text is not (``-0.0`` against ``0.0``).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from acphys.simulation import Simulation
from acphys.trace_diff import diff_traces


@dataclass
class Comparison:
    """The outcome of one scenario on both engines."""

    identical: bool
    records: int
    kernel_steps: int
    reference_steps: int
    #: Where the traces first differ (empty when identical).
    divergence: str = ""
    #: The kernel's body-steps whose sweep met another body.
    touching: int = 0
    #: The body updates the fast engine left to the reference path, by reason.
    reasons: dict[str, int] = field(default_factory=dict)


def split_trace(path: Path) -> tuple[dict[str, Any] | None, bytes]:
    """A trace's header without its ``engine`` (None for a v1 trace), and the bytes after it."""
    data = path.read_bytes()
    if not data.startswith(b'{"schema"'):
        return None, data
    line, _, rest = data.partition(b"\n")
    header = json.loads(line)
    header.pop("engine", None)
    return header, rest


def same_run(a: Path, b: Path) -> bool:
    """Whether two traces record the same run: equal headers but for the engine, and the same
    bytes after them."""
    return split_trace(a) == split_trace(b)


def _first_line_difference(a: Path, b: Path) -> str:
    with a.open("rb") as fa, b.open("rb") as fb:
        for number, (line_a, line_b) in enumerate(zip(fa, fb, strict=False), start=1):
            if line_a != line_b:
                return f"line {number} differs: {line_a[:300]!r} vs {line_b[:300]!r}"
    return "one trace is longer"


def compare_engines(
    load: Callable[[str], Simulation], folder: Path, until: float | None = None
) -> Comparison:
    """Run ``load(engine)`` on the reference and the fast engine (to ``until``, or the scenario's
    duration) with traces written into ``folder``; compare them byte for byte."""
    traces = {}
    counts = None
    for engine in ("reference", "fast"):
        sim = load(engine)
        path = folder / f"{engine}.jsonl"
        sim.run(until=until, trace=path)
        traces[engine] = path
        if engine == "fast":
            counts = sim.physics.counts  # type: ignore[attr-defined]
    assert counts is not None
    a, b = traces["reference"], traces["fast"]
    identical = same_run(a, b)
    text = ""
    if not identical:
        divergence = diff_traces(a, b, tol=0.0)
        text = divergence.describe() if divergence is not None else _first_line_difference(a, b)
    records = sum(1 for _ in a.open("rb"))
    return Comparison(
        identical, records, counts.kernel, counts.reference, text, counts.touching, dict(counts.reasons)
    )
