"""The conformance corpus (issue 15): the scenarios that matter to a port, with golden traces.

:func:`export_corpus` writes, into a folder, each case's scenario (``scenarios/NAME.toml``), the
trace the reference engine writes for it (``golden/NAME.jsonl``), the built-in setup, motion
table and land height table the scenarios use (``builtins/``), ``manifest.json`` (what each case
exercises, how long it runs, its driver rate, bodies and records, and the sha256 of every file)
and a ``README.md`` telling a port how to use them. :func:`check_corpus` checks the files
against the manifest, then re-runs every case (or takes a port's traces from a folder) and diffs
it against its golden trace.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import stat
import string
import tempfile
import textwrap
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy

from acphys import __version__
from acphys.inputs import check_regular, one_line, open_regular, read_limited
from acphys.scenario import BUILTIN_SETUP_TABLES, builtin_scenario_text, load_scenario
from acphys.scenario.motion_tables import builtin_motion_table_text
from acphys.setup import human_setup
from acphys.trace import RECORD_KEYS, SCHEMA, TraceError, read_trace, trace_schema
from acphys.trace_diff import Divergence, compare_traces

#: What a corpus manifest names as its format.
FORMAT = "acphys.corpus/1"
#: The manifest's file name, in the corpus folder.
MANIFEST = "manifest.json"
#: The largest manifest read. Each case takes about 600 bytes; a MiB holds well over a thousand.
MAX_MANIFEST_BYTES = 1 << 20
#: A case's name: also its files' names, so it cannot climb out of their folders.
CASE_NAME = re.compile(r"[a-z0-9][a-z0-9-]{0,63}\Z")
_SHA256 = re.compile(r"[0-9a-f]{64}\Z")
#: The path of a file the manifest lists besides the cases': ``folder/name.ext``, no way up.
_FILE_PATH = re.compile(r"[a-z0-9-]+/[a-z0-9_-]+(\.[a-z0-9]+)+\Z")


class CorpusError(ValueError):
    """A corpus that cannot be exported or checked as asked; the message is one line that names
    the file or folder."""


@dataclass(frozen=True)
class Case:
    """A corpus case: a built-in scenario or one of ``acphys.data.corpus``, by its file name."""

    name: str
    group: str
    exercises: str
    #: How long to run, when shorter than the scenario's ``duration`` (None: the duration).
    until: float | None = None


def _random(seed: int, why: str) -> Case:
    return Case(f"random-{seed}", "random", f"tests/engine_corpus.py world {seed}: {why}")


#: The corpus, in the order it is exported and checked.
CASES: tuple[Case, ...] = (
    Case("ladder-01-fall", "ladder", "free fall onto flat terrain, a bounce, friction, rest, deactivation"),
    Case("ladder-02-slopes", "ladder", "slopes just inside and just outside floor_z"),
    Case("ladder-03-wall", "ladder", "walking into a wall stops; at an angle it slides along it"),
    Case("ladder-04-steps", "ladder", "a step under the step-up height is climbed, a higher one blocks"),
    Case("ladder-05-ledge", "ladder", "walking off a ledge: falls without edge_slide, stops at it with"),
    Case("ladder-06-step-down", "ladder", "down a staircase and gentle terrain in contact (step-down)"),
    Case("ladder-07-bounce", "ladder", "a bouncing ball and an inelastic missile"),
    Case("ladder-08-missiles", "ladder", "missiles against a pillar (cylsphere) and a sphere object"),
    Case("ladder-09-bodies", "ladder", "two bodies walking into each other stop; an ethereal one passes"),
    Case("ladder-10-seam-and-door", "ladder", "across a landblock seam, through a doorway, and back"),
    Case("ladder-11-pit", "ladder", "a ball wedged in a pit: the stationary-fall sequence"),
    Case("ladder-12-commits", "ladder", "the commits that do not sweep, or whose sweep fails"),
    Case("default", "locomotion", "integration, the terminal clamp, a projectile, walking, running, a jump"),
    Case("locomotion", "locomotion", "the human's motions, the run key, a weenie's jump, an npc, the cull"),
    Case("yard", "locomotion", "walls, a pillar, a ledge and a staircase the human climbs (BSP solids)"),
    Case("hills", "locomotion", "walking over a hill of rolling terrain; a stone dropped in a lake", 20.0),
    Case("move-to", "managers", "move_to, turn_to, move_to_object and turn_to_object (MoveToManager)"),
    Case("remote", "managers", "interpolation, sticky, constraint and a script"),
    Case("carry", "managers", "set_parent and unset_parent: a held body carried, let go and tossed"),
    Case("f32-step-up", "arithmetic", "a step of exactly 1.5 step heights, blocked in float32 only"),
    Case("f32-dart", "arithmetic", "ceil(|offset| / radius) sub-steps on float32 positions and radius"),
    Case("f32-slow-walk", "arithmetic", "animation frames crossed on a float32 framerate (speed 0.64)"),
    Case("f32-awkward-inputs", "arithmetic", "every kind of scenario number, none a float32 as written"),
    Case("clock-slices", "arithmetic", "a 3-Hz driver: each tick sliced into a 0.2-s step and the rest"),
    Case("clock-odd-rate", "arithmetic", "a 144-Hz driver: bodies step every fifth tick, off the 30-Hz grid"),
    Case("seam", "seams-and-doors", "walking uphill across a landblock seam on continuous terrain"),
    Case("house", "seams-and-doors", "through a front door into a room and on into the next (env cells)"),
    _random(0, "two landblocks, a lake corner, a pillar, a jump, inelastic balls, 60 Hz"),
    _random(3, "a crowd of 13 bodies, a missile, a jump, 45 Hz"),
    _random(5, "two landblocks, water, two pillars, 45 Hz"),
    _random(7, "water, two pillars, three jumps, 30 Hz"),
)


def case_names() -> list[str]:
    """The names of the corpus's cases, in order."""
    return [case.name for case in CASES]


def scenario_text(name: str) -> str:
    """The TOML text of case ``name``'s scenario (a KeyError for a name that is not a case)."""
    if name not in case_names():
        raise KeyError(f"no corpus case {name!r}")
    data = resources.files("acphys.data.corpus").joinpath(f"{name}.toml")
    return data.read_text("utf-8") if data.is_file() else builtin_scenario_text(name)


def select_cases(names: Iterable[str] | None) -> list[Case]:
    """The cases named (all of them for None), in corpus order; an unknown name is a CorpusError."""
    if names is None:
        return list(CASES)
    wanted = set(names)
    unknown = sorted(wanted - set(case_names()))
    if unknown:
        raise CorpusError(f"no corpus case {one_line(unknown[0])!r} (cases: {', '.join(case_names())})")
    return [case for case in CASES if case.name in wanted]


# -- export -----------------------------------------------------------------------------------


def export_corpus(
    directory: str | Path,
    names: Iterable[str] | None = None,
    on_case: Callable[[str], Any] | None = None,
) -> dict[str, Any]:
    """Write the corpus (the cases ``names``, or all) into ``directory``; returns the manifest.

    The folder is made if need be. One that is not empty must hold a corpus already (a
    ``manifest.json`` of this format), whose listed files are replaced; a file in the way that
    its manifest does not list is refused, before anything is removed. ``on_case(name)`` is
    called as each case starts.
    """
    cases = select_cases(names)
    root = Path(directory)
    replaced = _earlier_corpus(root)
    files = _reference_files()
    targets = [root / "README.md", root / MANIFEST, *(root / path for path in files)]
    for case in cases:
        targets += [root / "scenarios" / f"{case.name}.toml", root / "golden" / f"{case.name}.jsonl"]
    _own_folders(root, targets)
    for path in targets:
        if os.path.lexists(path) and path not in replaced:
            raise CorpusError(
                f"{one_line(str(path))}: is in the way and not listed in the corpus's {MANIFEST}; "
                "remove it or export into a new folder"
            )
    for path in replaced:
        path.unlink()
    for folder in {"scenarios", "golden", *(path.split("/")[0] for path in files)}:
        (root / folder).mkdir(exist_ok=True)
    listed = []
    for path, (text, what) in files.items():
        (root / path).write_bytes(text.encode("utf-8"))
        listed.append({**_file_entry(root, root / path), "what": what})
    entries = []
    for case in cases:
        if on_case is not None:
            on_case(case.name)
        scenario = root / "scenarios" / f"{case.name}.toml"
        scenario.write_bytes(scenario_text(case.name).encode("utf-8"))
        sim = load_scenario(scenario)  # the file as written, as a port reads it
        until = sim.duration if case.until is None else case.until
        golden = root / "golden" / f"{case.name}.jsonl"
        sim.run(until=until, trace=golden)
        entries.append(
            {
                "name": case.name,
                "group": case.group,
                "exercises": case.exercises,
                "until": until,
                "duration": sim.duration,
                "driver_hz": sim.driver_hz,
                "bodies": len(sim.bodies),
                "records": sum(1 for _ in read_trace(golden)),
                "scenario": _file_entry(root, scenario),
                "golden": _file_entry(root, golden),
            }
        )
    manifest = {
        "format": FORMAT,
        "acphys": __version__,
        "trace_schema": SCHEMA,
        "files": listed,
        "cases": entries,
    }
    (root / "README.md").write_text(_readme(manifest), encoding="utf-8")
    # The manifest last: a folder holding one is a whole corpus.
    (root / MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    return manifest


def _earlier_corpus(root: Path) -> set[Path]:
    """Make ``root`` a folder if it is not one yet, and return the files an export there replaces:
    none in a new or empty folder, the regular files an earlier corpus's manifest lists (and its
    README) in one; any other folder is a CorpusError."""
    if root.exists() and not root.is_dir():
        raise CorpusError(f"{one_line(str(root))}: not a folder")
    root.mkdir(parents=True, exist_ok=True)
    if not any(root.iterdir()):
        return set()
    if not os.path.lexists(root / MANIFEST):
        raise CorpusError(
            f"{one_line(str(root))}: not empty and not an acphys corpus (no {MANIFEST}); "
            "export into a new or empty folder"
        )
    manifest = read_manifest(root)
    listed = [root / "README.md", root / MANIFEST, *(root / item["path"] for item in manifest["files"])]
    listed += [root / entry[key]["path"] for entry in manifest["cases"] for key in ("scenario", "golden")]
    _own_folders(root, listed)  # what is removed is the corpus's own
    return {path for path in listed if path.is_file() and not path.is_symlink()}


def _own_folders(root: Path, paths: Iterable[Path]) -> None:
    """Refuse a folder of ``paths`` in the corpus that is a link (out of it) or not a folder."""
    for folder in {path.parent for path in paths} - {root}:
        if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
            raise CorpusError(f"{one_line(str(folder))}: not a folder (a corpus holds its own folders)")


def _reference_files() -> dict[str, tuple[str, str]]:
    """What a port needs besides the scenarios, by path in the corpus: each file's text and what
    it is (the manifest's ``what``)."""
    return {
        "builtins/human.toml": (
            _human_setup_text(),
            "the built-in setup `human`, the default of a body without `setup`, as a scenario section",
        ),
        "builtins/humanoid.toml": (
            builtin_motion_table_text("humanoid"),
            "the built-in motion table `humanoid` (the human's), as a scenario section",
        ),
        "builtins/land_height_table.toml": (
            resources.files("acphys.data").joinpath("land_height_table.toml").read_text("utf-8"),
            "the land height table (bytes 0-200) of a landblock's `heights` without a `height_table`",
        ),
        "schema/trace.schema.json": (
            json.dumps(trace_schema(), indent=2) + "\n",
            "the JSON Schema (draft 2020-12) of one line of a trace (`acphys schema trace`)",
        ),
    }


def _human_setup_text() -> str:
    """The built-in human (:func:`acphys.setup.human_setup`) as a ``[setup.human]`` section."""
    setup = human_setup()

    def number(value: float) -> str:  # the shortest text of the float32
        return str(numpy.float32(value))

    spheres = ", ".join(
        f"{{ center = [{', '.join(map(number, sphere.center))}], radius = {number(sphere.radius)} }}"
        for sphere in setup.spheres
    )
    return (
        "# The built-in human setup (acphys.setup.human_setup): a scenario's body without `setup`,\n"
        '# or with `setup = "human"`, is this body; its sorting sphere is the sphere around its two.\n'
        "[setup.human]\n"
        f"spheres = [{spheres}]\n"
        f"height = {number(setup.height)}\n"
        f"radius = {number(setup.radius)}\n"
        f"step_up_height = {number(setup.step_up_height)}\n"
        f"step_down_height = {number(setup.step_down_height)}\n"
        f'motion_table = "{BUILTIN_SETUP_TABLES["human"]}"\n'
    )


def _file_entry(root: Path, path: Path) -> dict[str, str]:
    return {"path": path.relative_to(root).as_posix(), "sha256": _sha256(path)}


def _sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open_regular(path) as file:
        while chunk := file.read(1 << 20):
            digest.update(chunk)
    return digest.hexdigest()


# -- the manifest -----------------------------------------------------------------------------


def read_manifest(directory: str | Path) -> dict[str, Any]:
    """The manifest of the corpus in ``directory``, its form checked (not its files: see
    :func:`verify_files`); a CorpusError (or an ``InputError``) names what is wrong."""
    path = Path(directory) / MANIFEST
    label = one_line(str(path))
    if not Path(directory).is_dir():
        problem = "not a folder" if os.path.lexists(directory) else "no such folder"
        raise CorpusError(f"{one_line(str(directory))}: {problem}")
    if not os.path.lexists(path):
        raise CorpusError(f"{one_line(str(directory))}: not an acphys corpus (no {MANIFEST})")
    _regular(path, in_folder=False)
    data = read_limited(path, MAX_MANIFEST_BYTES, "the manifest size limit")
    try:
        manifest = json.loads(data.decode("utf-8"))
    except UnicodeDecodeError as error:
        byte = data[error.start]
        raise CorpusError(f"{label}: not UTF-8: byte {byte:#04x} at offset {error.start}") from None
    except json.JSONDecodeError as error:
        where = f"line {error.lineno} column {error.colno}"
        raise CorpusError(f"{label}: not JSON: {error.msg} at {where}") from None
    except ValueError as error:  # an integer past Python's digit limit
        raise CorpusError(f"{label}: not JSON acphys reads: {error}") from None
    except RecursionError:
        raise CorpusError(f"{label}: not JSON: nested too deeply") from None
    if not isinstance(manifest, dict) or manifest.get("format") != FORMAT:
        raise CorpusError(f'{label}: not an acphys corpus manifest (no "format": "{FORMAT}")')
    files = manifest.get("files")
    if not isinstance(files, list):
        raise CorpusError(f'{label}: "files" must be a list')
    for index, item in enumerate(files):
        path = item.get("path") if isinstance(item, dict) else None
        if not isinstance(path, str) or not _FILE_PATH.match(path):
            raise CorpusError(f"{label}: files[{index}]: path must be FOLDER/NAME.EXT, within the corpus")
        _check_sha256(f"{label}: files[{index}]", item)
    cases = manifest.get("cases")
    if not isinstance(cases, list) or not cases:
        raise CorpusError(f'{label}: "cases" must be a non-empty list')
    seen: set[str] = set()
    for index, entry in enumerate(cases):
        name = _check_case(label, index, entry)
        if name in seen:
            raise CorpusError(f"{label}: two cases are named {name!r}")
        seen.add(name)
    return manifest


def _check_case(label: str, index: int, entry: Any) -> str:
    """Check one manifest case's form and return its name."""
    where = f"{label}: cases[{index}]"
    if not isinstance(entry, dict):
        raise CorpusError(f"{where}: expected an object")
    name = entry.get("name")
    if not isinstance(name, str) or not CASE_NAME.match(name):
        shown = one_line(repr(name))[:80]
        raise CorpusError(f"{where}: name {shown} is not a case name (lower-case letters, digits, -)")
    where = f"{label}: case {name!r}"
    until = entry.get("until")
    number = isinstance(until, (int, float)) and not isinstance(until, bool)
    if not (number and math.isfinite(until) and until >= 0):
        raise CorpusError(f"{where}: until must be a non-negative number of seconds")
    for key, folder, suffix in (("scenario", "scenarios", ".toml"), ("golden", "golden", ".jsonl")):
        item = entry.get(key)
        expected = f"{folder}/{name}{suffix}"
        if not isinstance(item, dict) or item.get("path") != expected:
            raise CorpusError(f"{where}: {key}.path must be {expected!r}")
        _check_sha256(f"{where}: {key}", item)
    return name


def _check_sha256(where: str, item: dict[str, Any]) -> None:
    if not isinstance(item.get("sha256"), str) or not _SHA256.match(item["sha256"]):
        raise CorpusError(f"{where}: sha256 must be 64 lower-case hex digits")


def verify_files(directory: str | Path, manifest: dict[str, Any], cases: Iterable[dict[str, Any]]) -> None:
    """Check that the files of ``manifest`` and of its ``cases`` (some of its entries) are regular
    files in the corpus whose sha256 is the manifest's (a CorpusError or ``InputError`` names the
    first that is not)."""
    root = Path(directory)
    listed = [(item, "") for item in manifest["files"]]
    listed += [
        (entry[key], f" (case {entry['name']!r})") for entry in cases for key in ("scenario", "golden")
    ]
    for item, case in listed:
        path = root / item["path"]
        _regular(path)
        if _sha256(path) != item["sha256"]:
            raise CorpusError(
                f"{one_line(str(path))}: altered: its sha256 is not the one in {MANIFEST}{case}; "
                "restore it or export the corpus again"
            )


def _regular(path: Path, in_folder: bool = True) -> None:
    """Refuse a corpus file that is missing, a symbolic link, in a folder of the corpus that is a
    link (``in_folder``: a file in one of its folders, not the manifest), or not a regular file."""
    if in_folder and path.parent.is_symlink():
        raise CorpusError(f"{one_line(str(path.parent))}: a symbolic link; a corpus holds its own folders")
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        raise CorpusError(f"{one_line(str(path))}: missing from the corpus") from None
    if stat.S_ISLNK(mode):
        raise CorpusError(f"{one_line(str(path))}: a symbolic link; a corpus holds regular files only")
    check_regular(path)


# -- check ------------------------------------------------------------------------------------


@dataclass
class CaseResult:
    """The outcome of one case: where its trace first left the golden one, if it did."""

    name: str
    group: str
    divergence: Divergence | None
    #: Why the trace could not be compared (a trace that is not one), if it could not.
    error: str | None
    seconds: float

    @property
    def passed(self) -> bool:
        return self.divergence is None and self.error is None

    def describe(self) -> str:
        if self.error is not None:
            return self.error
        return "identical" if self.divergence is None else self.divergence.describe()


def check_corpus(
    directory: str | Path,
    engine: str = "reference",
    tol: float = 0.0,
    trace_dir: str | Path | None = None,
    names: Iterable[str] | None = None,
    ignore: Sequence[str] = (),
) -> list[CaseResult]:
    """Check the corpus in ``directory``: its manifest and files, then each case (those of
    ``names``, or all), re-run on ``engine`` or read from ``trace_dir/NAME.jsonl`` (a port's
    traces), diffed against its golden trace within ``tol``, every field but those of ``ignore``
    (as ``acphys diff --ignore`` takes them).

    A corpus that is damaged (a file missing, altered, or not a regular file; a manifest that
    is not one) is a CorpusError or ``InputError`` before any case runs; a trace that diverges
    or cannot be read is a failed :class:`CaseResult`.
    """
    root = Path(directory)
    manifest = read_manifest(root)
    entries = manifest["cases"]
    if names is not None:
        wanted = set(names)
        known = {entry["name"] for entry in entries}
        unknown = sorted(wanted - known)
        if unknown:
            raise CorpusError(
                f"{one_line(str(root / MANIFEST))}: no case {one_line(unknown[0])!r} "
                f"(cases: {', '.join(entry['name'] for entry in entries)})"
            )
        entries = [entry for entry in entries if entry["name"] in wanted]
    verify_files(root, manifest, entries)
    if trace_dir is not None and not Path(trace_dir).is_dir():
        raise CorpusError(f"{one_line(str(trace_dir))}: not a folder of traces")
    results = []
    with tempfile.TemporaryDirectory(prefix="acphys-corpus-") as scratch:
        for entry in entries:
            start = time.perf_counter()
            if trace_dir is None:
                trace = Path(scratch) / f"{entry['name']}.jsonl"
                sim = load_scenario(root / entry["scenario"]["path"], engine=engine)
                try:
                    sim.check_until(entry["until"])
                except ValueError as problem:
                    label = one_line(str(root / MANIFEST))
                    raise CorpusError(f"{label}: case {entry['name']!r}: until: {problem}") from None
                sim.run(until=entry["until"], trace=trace)
            else:
                trace = Path(trace_dir) / f"{entry['name']}.jsonl"
            divergence, error = None, None
            try:
                golden = root / entry["golden"]["path"]
                divergence = compare_traces(golden, trace, tol, ignore=ignore, context=0).first
            except TraceError as problem:
                error = str(problem)
            group = one_line(str(entry.get("group", "")))
            results.append(CaseResult(entry["name"], group, divergence, error, time.perf_counter() - start))
    return results


# -- the README -------------------------------------------------------------------------------

_README = string.Template("""\
# acphys conformance corpus

Golden traces of the retail Asheron's Call client's physics (build 11.4186), written by acphys
$version on its reference engine, for $count scenarios that matter to a port of that physics:
the collision ladder, locomotion, the managers, arithmetic boundaries (float32 storage, the
clock), landblock seams and doors, and a sample of random worlds. A port that reads these
scenarios and writes its traces in acphys's trace schema ($schema) is checked against them
record by record.

## What is here

- `scenarios/NAME.toml`: each case's scenario, in acphys's scenario format (TOML: a header,
  landblocks, shapes, bodies and a timeline of events; see "Scenarios" in acphys's README, or
  `acphys check scenarios/NAME.toml`). Its comments say what happens.
- `golden/NAME.jsonl`: the trace acphys writes for it, as `acphys run scenarios/NAME.toml
  --until UNTIL --trace golden/NAME.jsonl` does.
- `builtins/`: what acphys builds in and the scenarios use without spelling out, as scenario
  sections: `human.toml`, the `human` setup (a body without `setup` is a human), with its
  motion table `humanoid.toml`, and `land_height_table.toml`, the metres of a landblock's
  `heights` bytes (0-200) when it gives no `height_table`. A scenario that pasted them in
  would run the same.
- `schema/trace.schema.json`: the JSON Schema (draft 2020-12) every line of a trace (the
  goldens', and yours) validates against: the header, then the records; what each field is.
- `manifest.json`: its `format` ($format), the `acphys` version and `trace_schema`, the
  `files` above (`path`, `sha256`, `what`), and per case its `name`, `group`, what it
  `exercises`, `until` (the simulated seconds to run: the scenario's `duration` unless the
  corpus runs it shorter), `duration`, `driver_hz`, the number of `bodies` and of trace
  `records` (header excluded), and the `path` and `sha256` of its `scenario` and `golden`
  files.

## How a port uses it

For each case of `manifest.json`:

1. Read `scenarios/NAME.toml` and build its world, bodies and events (with `builtins/`).
2. Drive the clock as acphys does: driver tick `k` sets the time to `k * tick`, where `tick` is
   `1 / driver_hz` rounded up to the 2^-30-s grid (`ceil(2^30 / driver_hz) / 2^30`); each tick
   applies the events due by then (`at` <= the time, in file order), then calls
   `CPhysics::UseTime`, which runs every body's `update_object` once at least 1/30 s has passed.
   Stop after the first tick at or past `until`.
3. Write a trace, as the golden ones are written: a header line naming the schema,
   `{"schema": "$schema", ...}` (the other keys are the writer's own: acphys writes its
   version, engine, driver rate and the scenario's name and sha256), then one record per body
   as the run starts (`t` 0, `quantum` 0, no events), then one record per body after every
   `update_object_internal` call, in the order they happen: tick by tick, the bodies in the
   order of retail's object table (by bucket `(id ^ (id >> 8)) & 127`, newest first within a
   bucket: the order they are declared in, for the default ids), each body's quanta in order.
   A body writes no records while it is held (`set_parent`). Without the header a trace is
   read as schema 1, and its comparison skips the start records, `id`, `heading` and `motion`.
4. Compare it with the golden trace:

   ```sh
   acphys corpus check CORPUS --trace-dir YOUR_TRACES        # every case (YOUR_TRACES/NAME.jsonl)
   acphys diff CORPUS/golden/NAME.jsonl YOUR_TRACES/NAME.jsonl --tol 0   # one case, in detail
   ```

   `acphys corpus check` checks the corpus's files against the manifest, prints a table of the
   cases that pass and fail (the first divergence of each: line, time, body, field, both
   values) and exits 0 when every case passes, 1 when one does not, 2 when the corpus or a
   command line is wrong. `--cases a,b` checks only those, `--tol` allows an absolute
   difference, and `--ignore motion,heading` leaves fields out (a port that has not got to
   them yet). From a port's CI: install acphys (`pip install acphys`, or from its repository)
   and run the first command. `acphys diff` shows more of one case (`--all` for every
   diverging body, `--context N` for the records before a divergence, `--json`).

## What is compared

The header line is not compared (it names the schema and what wrote the trace). Records are
paired per body, the k-th record of a body with the k-th record of that body in the golden
trace, and compared key by key, every key of the schema:

$keys

Numbers are compared by absolute difference (`--tol`, 0 by default: retail stores float32 and
computes in double, and a port that does the same reproduces every bit), every other value
exactly: cell ids, flag and motion names, events, and missing or extra keys. A trace that
lacks a record, or has one more, diverges there. The fields' meanings are in "Traces" in
acphys's README (`t` is the physics time after the step, `quantum` the float32 step, `origin`
local to the landblock of `cell`, `orientation` a quaternion w, x, y, z, `omega` in radians
per second, `motion` the motion interpreter's state and the animation playing).

`acphys corpus check CORPUS` (without `--trace-dir`) re-runs every scenario on acphys and diffs
it with its golden trace: the corpus checks itself.

## The cases

| case | group | runs (s) | Hz | bodies | records | exercises |
| --- | --- | ---: | ---: | ---: | ---: | --- |
$table
""")


def _readme(manifest: dict[str, Any]) -> str:
    rows = "\n".join(
        f"| {c['name']} | {c['group']} | {c['until']:g} | {c['driver_hz']:g} | {c['bodies']} "
        f"| {c['records']:,} | {c['exercises']} |"
        for c in manifest["cases"]
    )
    return _README.substitute(
        version=manifest["acphys"],
        count=len(manifest["cases"]),
        schema=manifest["trace_schema"],
        format=FORMAT,
        keys=textwrap.fill(", ".join(f"`{key}`" for key in RECORD_KEYS), width=96),
        table=rows,
    )


__all__ = [
    "CASES",
    "Case",
    "CaseResult",
    "CorpusError",
    "case_names",
    "check_corpus",
    "export_corpus",
    "read_manifest",
    "scenario_text",
    "select_cases",
    "verify_files",
]
