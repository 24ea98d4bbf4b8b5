"""The ``acphys`` command (contract 3): run, check, diff, plot, view, bench and dat.

Every error prints one line starting ``acphys: error:`` and exits non-zero
(2 for bad input); no command ever shows a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import NoReturn

from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn
from rich.table import Table
from rich.text import Text

from acphys import __version__
from acphys.bench import ENGINE_CHOICES, WORKLOADS, run_suite
from acphys.corpus import CaseResult, CorpusError, check_corpus, export_corpus, read_manifest
from acphys.dat import REGION_ID, DatError, DatFile, unpack_region, unpack_setup
from acphys.flags import TransientState, flag_names
from acphys.inputs import InputError, OptionError, one_line, split_names
from acphys.math.cell_id import format_cell_id
from acphys.math.vector import Vector3
from acphys.plot import (
    VIEWS,
    PathRecorder,
    PlotError,
    check_output,
    read_paths,
    select_bodies,
    shown_name,
    trace_world,
    write_plot,
)
from acphys.scenario import ScenarioError, builtin_scenario_text, builtin_scenarios, load_scenario
from acphys.scenario.motion_tables import builtin_motion_table_text, builtin_motion_tables
from acphys.simulation import ENGINES, Simulation
from acphys.trace import TraceError, brief, trace_schema
from acphys.trace_diff import DiffError, DiffReport, Divergence, compare_traces
from acphys.view import show
from acphys.world_sketch import sketch_world

#: The bodies ``acphys run``'s summary lists (rich lays out about a row a millisecond; a run of
#: thousands of bodies is read from its trace).
SUMMARY_ROWS = 200
#: Runs with more driver ticks than this show a progress bar (on a terminal).
PROGRESS_TICKS = 20_000
#: The most bodies and simulated seconds ``acphys bench`` takes, and the most of their product: a
#: workload runs some 3,000 body-steps a second (30 a body-second), so 100,000 body-seconds are
#: about half an hour a workload; more is a mistake, refused rather than started.
MAX_BENCH_BODIES = 100_000
MAX_BENCH_SECONDS = 3600.0
MAX_BENCH_BODY_SECONDS = 100_000
#: The fast engine alone steps some hundred times faster: 10 million body-seconds (100,000 bodies
#: for 100 s) take minutes.
MAX_FAST_BENCH_BODY_SECONDS = 10_000_000
#: The most records of a body ``acphys diff --context`` shows before a divergence (each body keeps
#: as many while it is compared).
MAX_DIFF_CONTEXT = 1000

EXIT_DIVERGED = 1
EXIT_BAD_INPUT = 2
EXIT_INTERNAL = 3


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line."""

    def error(self, message: str) -> NoReturn:
        print(f"acphys: error: {message} (see acphys --help)", file=sys.stderr)
        sys.exit(EXIT_BAD_INPUT)


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="acphys", description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--version", action="version", version=f"acphys {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    run = commands.add_parser("run", help="run a scenario (the embedded default when none is given)")
    run.add_argument(
        "scenario",
        nargs="?",
        help=f"a scenario file, or a built-in name ({', '.join(builtin_scenarios())})",
    )
    run.add_argument("--trace", metavar="FILE", help="write a JSON Lines trace of every step")
    run.add_argument("--until", metavar="SECONDS", type=float, help="stop at this time instead")
    run.add_argument(
        "--plot", metavar="FILE", help="draw the run over its world: a .png, .svg or .pdf (as acphys plot)"
    )
    run.add_argument(
        "--engine",
        choices=ENGINES,
        default="reference",
        help="reference (plain Python, the truth; default) or fast (compiled, the same traces)",
    )

    check = commands.add_parser("check", help="validate a scenario file")
    check.add_argument("scenario")

    show_ = commands.add_parser(
        "show", help="print a built-in scenario or motion table as TOML to start from"
    )
    show_.add_argument("name", help=f"one of: {', '.join([*builtin_scenarios(), *builtin_motion_tables()])}")

    schema = commands.add_parser("schema", help="print the JSON Schema of a file acphys writes")
    schema.add_argument("kind", choices=["trace"], help="trace: one line of a trace (acphys.trace/2)")

    diff = commands.add_parser("diff", help="where two traces differ, their records paired per body")
    diff.add_argument("a")
    diff.add_argument("b")
    diff.add_argument("--tol", type=float, default=1e-6, help="absolute tolerance (default 1e-6)")
    diff.add_argument("--bodies", metavar="A,B", help="only these bodies (comma-separated names)")
    diff.add_argument("--fields", metavar="F,G", help="only these fields (origin, motion.forward, ...)")
    diff.add_argument("--ignore", metavar="F,G", help="every field but these")
    diff.add_argument(
        "--all",
        action="store_true",
        dest="all_bodies",
        help="read to the ends: every diverging body's first divergence, and counts per field",
    )
    diff.add_argument(
        "--context", type=int, default=2, metavar="N", help="records shown before a divergence (default 2)"
    )
    diff.add_argument("--json", metavar="FILE", help="also write the report as JSON (-: on stdout, alone)")

    plot = commands.add_parser(
        "plot", help="a picture of a trace over its world: paths from above, height over time, events"
    )
    plot.add_argument("trace")
    plot.add_argument(
        "-o", "--output", metavar="FILE", required=True, help="the picture to write: .png, .svg or .pdf"
    )
    plot.add_argument(
        "--scenario",
        metavar="S",
        help="draw this scenario's world (a file or a built-in name; default: the built-in the trace names)",
    )
    plot.add_argument("--bodies", metavar="A,B", help="only these bodies (comma-separated names)")
    plot.add_argument("--view", choices=VIEWS, help="one panel only (default: top and height)")

    view = commands.add_parser(
        "view", help="a trace as text (a table per body and a map), or a 3-D replay page (--html)"
    )
    view.add_argument(
        "trace", metavar="TRACE_OR_SCENARIO", help="a trace, or (with --html) a scenario to run"
    )
    view.add_argument("--bodies", metavar="A,B", help="only these bodies (comma-separated names)")
    view.add_argument("--html", metavar="OUT.html", help="write a self-contained 3-D replay page (WebGL)")
    view.add_argument(
        "--scenario",
        metavar="S",
        help="--html of a trace: draw this scenario's world (default: the built-in the trace names)",
    )
    view.add_argument("--until", metavar="SECONDS", type=float, help="--html of a scenario: run to this time")
    view.add_argument(
        "--engine", choices=ENGINES, help="--html of a scenario: the engine to run (default reference)"
    )

    bench = commands.add_parser("bench", help="the performance suite: rates and ratios to a baseline")
    bench.add_argument("--bodies", type=int, default=100, help="bodies per workload (default 100)")
    bench.add_argument("--seconds", type=float, default=5.0, help="simulated seconds (default 5)")
    bench.add_argument(
        "--engine", choices=ENGINE_CHOICES, default="both", help="which engine to measure (default both)"
    )
    bench.add_argument(
        "--workload", action="append", choices=list(WORKLOADS), help="only this workload (repeatable)"
    )
    bench.add_argument("--json", metavar="FILE", help="also write the figures as JSON")

    dat = commands.add_parser("dat", help="read the user's retail DAT files")
    dat_commands = dat.add_subparsers(dest="dat_command", required=True, parser_class=_Parser)
    info = dat_commands.add_parser("info", help="the header and the number of records")
    info.add_argument("file")
    listing = dat_commands.add_parser("list", help="record ids and sizes")
    listing.add_argument("file")
    listing.add_argument("--type", metavar="0xNN", type=_dat_type, help="only ids with this high byte")
    setup = dat_commands.add_parser("setup", help="a setup's physics fields")
    setup.add_argument("file")
    setup.add_argument("id", type=_dat_id, help="the setup's id (0x02xxxxxx)")
    heights = dat_commands.add_parser("heights", help=f"the region's land height table ({REGION_ID:#010x})")
    heights.add_argument("file")

    corpus = commands.add_parser("corpus", help="the conformance corpus: scenarios and golden traces")
    corpus_commands = corpus.add_subparsers(dest="corpus_command", required=True, parser_class=_Parser)
    export = corpus_commands.add_parser("export", help="write the scenarios, golden traces and manifest")
    export.add_argument("dir", help="a new or empty folder, or an earlier corpus to replace")
    export.add_argument("--cases", metavar="A,B", help="only these cases (comma-separated names)")
    corpus_check = corpus_commands.add_parser("check", help="re-run the cases (or read --trace-dir) and diff")
    corpus_check.add_argument("dir")
    corpus_check.add_argument("--cases", metavar="A,B", help="only these cases (comma-separated names)")
    corpus_check.add_argument("--engine", choices=ENGINES, default="reference", help="the engine to re-run")
    corpus_check.add_argument("--tol", type=float, default=0.0, help="absolute tolerance (default 0)")
    corpus_check.add_argument("--ignore", metavar="F,G", help="leave these fields out (as acphys diff does)")
    corpus_check.add_argument(
        "--trace-dir", metavar="DIR", help="diff the traces DIR/NAME.jsonl (a port's) instead of re-running"
    )
    return parser


def _dat_id(text: str) -> int:
    """A 32-bit id in hex (``0x`` optional) for argparse."""
    try:
        value = int(text, 16)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a hex id: {text!r}") from None
    if not 0 <= value <= 0xFFFFFFFF:
        raise argparse.ArgumentTypeError(f"not a 32-bit id: {text!r}")
    return value


def _dat_type(text: str) -> int:
    """An id's high byte in hex (``0x02`` for setups) for argparse."""
    value = _dat_id(text)
    if value > 0xFF:
        raise argparse.ArgumentTypeError(f"a type is one byte (like 0x02), got {text!r}")
    return value


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command; returns the exit code (argument errors too, rather than raising)."""
    try:
        args = _build_parser().parse_args(argv)
    except SystemExit as exit_:  # argparse's --help, --version and its (one-line) errors
        return exit_.code if isinstance(exit_.code, int) else EXIT_BAD_INPUT
    console = Console()
    if not console.is_terminal:
        console = Console(width=120)  # piped output: do not squeeze the summary into 80 columns
    try:
        if args.command == "run":
            return _run(console, args.scenario, args.trace, args.until, args.plot, args.engine)
        if args.command == "check":
            return _check(console, args.scenario)
        if args.command == "show":
            return _show(args.name)
        if args.command == "schema":
            sys.stdout.write(json.dumps(trace_schema(), indent=2) + "\n")
            return 0
        if args.command == "plot":
            return _plot(console, args.trace, args.output, args.bodies, args.view, args.scenario)
        if args.command == "view":
            return _view(console, args)
        if args.command == "bench":
            return _bench(console, args.bodies, args.seconds, args.engine, args.workload, args.json)
        if args.command == "dat":
            return _dat(console, args)
        if args.command == "corpus":
            return _corpus(console, args)
        return _diff(console, args)
    except ScenarioError as error:
        return _fail("\n".join(one_line(problem) for problem in error.problems), EXIT_BAD_INPUT)
    except (TraceError, PlotError, DatError, OptionError) as error:
        return _fail(one_line(str(error)), EXIT_BAD_INPUT)
    except OSError as error:
        return _fail(one_line(f"{error.filename or ''}: {error.strerror or error}"), EXIT_BAD_INPUT)
    except KeyboardInterrupt:
        return _fail("interrupted", EXIT_BAD_INPUT)
    except Exception as error:  # an acphys bug: still one line, but say so
        return _fail(
            one_line(f"internal error ({type(error).__name__}: {error}); please report it"), EXIT_INTERNAL
        )


def _fail(message: str, code: int) -> int:
    """Print ``message``, one ``acphys: error:`` line per problem (a scenario can have several);
    what the message quotes of the user's (a path, a name) is escaped to one line before."""
    for line in message.splitlines() or [""]:
        print(f"acphys: error: {line}", file=sys.stderr)
    return code


def _run(
    console: Console,
    scenario: str | None,
    trace: str | None,
    until: float | None,
    plot: str | None = None,
    engine: str = "reference",
) -> int:
    sim = load_scenario(scenario, engine=engine)
    _warn(sim)
    end = sim.duration if until is None else until
    if not (math.isfinite(end) and end >= 0.0):
        return _fail(f"--until must be a non-negative number of seconds, got {until}", EXIT_BAD_INPUT)
    try:
        sim.check_until(end)
    except ValueError as error:
        return _fail(f"--until: {error}", EXIT_BAD_INPUT)
    if plot is not None:
        check_output(plot)
    # --plot without --trace keeps the paths in memory; with it, reads them back from the trace.
    recorder = PathRecorder() if plot is not None and trace is None else None
    if recorder is not None:
        recorder.attach(sim.bodies)
    try:
        _drive(console, sim, end, trace)
    finally:
        if recorder is not None:
            recorder.detach(sim.bodies)
    console.print(_summary(sim))
    counts = getattr(sim.physics, "counts", None)
    if counts is not None:
        taken = counts.kernel + counts.reference
        _say(
            console,
            f"fast engine: {taken:,} body-steps, {counts.reference:,} of them "
            f"({100.0 * counts.reference_share:.1f}%) on the reference path",
        )
    if trace is not None:
        _say(console, f"trace: {trace}")
    if plot is not None:
        paths = recorder.paths if recorder is not None else read_paths(str(trace))
        write_plot(paths, plot, title=sim.name, world=sketch_world(sim))
        _say(console, f"plot: {plot}")
    return 0


def _drive(console: Console, sim: Simulation, end: float, trace: str | None) -> None:
    """Run ``sim`` to ``end``, with a progress bar on long runs at a terminal."""
    ticks = end * sim.driver_hz
    if ticks > PROGRESS_TICKS and console.is_terminal:
        with Progress(
            TextColumn("[bold]{task.description}"),
            BarColumn(),
            TextColumn("{task.completed:.1f}/{task.total:.1f} s"),
            TimeRemainingColumn(),
            console=console,
            transient=True,
        ) as progress:
            task = progress.add_task(sim.name, total=end)
            sim.run(until=end, trace=trace, progress=lambda now, _: progress.update(task, completed=now))
    else:
        sim.run(until=end, trace=trace)


def _say(console: Console, text: str) -> None:
    """Print one line that holds the user's text (a path, a name): escaped to one line, never read
    as rich markup (``[/]`` in a name would be a MarkupError) nor highlighted."""
    console.print(one_line(text), markup=False, highlight=False, soft_wrap=True)


def _summary(sim: Simulation) -> Table:
    """A row per body, for the first ``SUMMARY_ROWS`` (rich lays out about a row a millisecond: a
    10,000-body summary would take longer than the run); a caption says how many are left out."""
    bodies = _count(len(sim.bodies), "body", "bodies")
    left_out = len(sim.bodies) - SUMMARY_ROWS
    caption = f"the first {SUMMARY_ROWS:,} bodies; --trace records them all" if left_out > 0 else None
    table = Table(title=Text(one_line(f"{sim.name}: {sim.time:g} s simulated, {bodies}")), caption=caption)
    for column in ("body", "cell", "origin (m)", "heading", "velocity (m/s)", "transient"):
        table.add_column(column, no_wrap=column != "transient")
    for body in sim.bodies[:SUMMARY_ROWS]:
        table.add_row(
            Text(one_line(body.name)),
            format_cell_id(body.position.objcell_id),
            _triple(body.position.frame.origin),
            f"{body.position.frame.get_heading():.1f}°",
            _triple(body.velocity),
            " ".join(flag_names(body.transient_state, TransientState)) or "-",
        )
    return table


def _count(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


def _triple(v: Vector3) -> str:
    return f"{v.x:.2f} {v.y:.2f} {v.z:.2f}"


def _warn(sim: Simulation) -> None:
    for warning in sim.warnings:
        print(f"acphys: warning: {warning}", file=sys.stderr)


def _check(console: Console, scenario: str) -> int:
    sim = load_scenario(scenario)
    _warn(sim)
    bodies = _count(len(sim.bodies), "body", "bodies")
    events = _count(len(sim.events), "event", "events")
    _say(console, f"ok: {sim.name}: {bodies}, {events}, {sim.duration:g} s at {sim.driver_hz:g} Hz")
    return 0


def _show(name: str) -> int:
    """Print the TOML of a built-in scenario, or of a built-in motion table as a scenario's
    ``[motion_table.NAME]`` section."""
    if name in builtin_scenarios():
        sys.stdout.write(builtin_scenario_text(name))
        return 0
    if name in builtin_motion_tables():
        sys.stdout.write(builtin_motion_table_text(name))
        return 0
    known = ", ".join([*builtin_scenarios(), *builtin_motion_tables()])
    return _fail(
        f"{shown_name(name)}: no built-in scenario or motion table (built-in: {known})", EXIT_BAD_INPUT
    )


def _diff(console: Console, args: argparse.Namespace) -> int:
    """``acphys diff``: compare two traces and print the report (or write it as JSON)."""
    tol = args.tol
    if not (math.isfinite(tol) and tol >= 0.0):
        return _fail(f"--tol must be a non-negative number, got {tol}", EXIT_BAD_INPUT)
    if not 0 <= args.context <= MAX_DIFF_CONTEXT:
        return _fail(
            f"--context must be between 0 and {MAX_DIFF_CONTEXT}, got {args.context}", EXIT_BAD_INPUT
        )
    if args.json not in (None, "-"):
        _check_output_file(args.json)
    try:
        report = compare_traces(
            args.a,
            args.b,
            tol,
            bodies=split_names(args.bodies, "--bodies"),
            fields=split_names(args.fields, "--fields"),
            ignore=split_names(args.ignore, "--ignore") or (),
            all_bodies=args.all_bodies,
            context=args.context,
        )
    except DiffError as error:
        return _fail(one_line(str(error)), EXIT_BAD_INPUT)
    for warning in report.warnings:
        print(f"acphys: warning: {one_line(warning)}", file=sys.stderr)
    code = 0 if report.identical else EXIT_DIVERGED
    if args.json is not None:
        text = json.dumps(report.as_dict(), indent=2, allow_nan=False) + "\n"
        if args.json == "-":
            sys.stdout.write(text)
            return code
        Path(args.json).write_text(text, encoding="utf-8")
    _show_diff(console, report, args.all_bodies)
    if args.json is not None:
        _say(console, f"report: {args.json}")
    return code


def _show_diff(console: Console, report: DiffReport, all_bodies: bool) -> None:
    """The report as text: each divergence with its context, then (``--all``) the counts."""
    if report.identical:
        console.print(f"identical within {report.tolerance:g}")
    for divergence in report.divergences:
        console.print(divergence.describe(), markup=False, highlight=False, soft_wrap=True)
        if divergence.context:
            console.print(_context_table(divergence))
    if report.stopped is not None:
        _say(console, report.stopped)
    if not all_bodies:
        return
    missing = report.missing_bodies or {}
    for side, bodies in missing.items():
        for body in bodies:
            _say(console, f"body {body!r} is not in {side}")
    bodies = _count(report.bodies_compared, "body", "bodies")
    pairs = f"{report.records_compared:,} record pairs compared"
    _say(console, f"{len(report.divergences)} of {bodies} diverge; {pairs}")
    for column, counts in (("field", report.field_counts), ("body", report.body_counts)):
        if counts:
            table = Table(box=None, padding=(0, 1), pad_edge=False)
            table.add_column(column)
            table.add_column("diverging records", justify="right")
            for name, count in counts.most_common():
                table.add_row(Text(one_line(name)), f"{count:,}")
            console.print(table)


def _context_table(divergence: Divergence) -> Table:
    """The records of a diverging body before its divergence, then its own (marked >), from both
    traces: their lines, the time, and the values that diverge and their difference."""
    table = Table(box=None, padding=(0, 1), pad_edge=False)
    field = one_line(divergence.field)
    for column in ("", "line a", "line b", "t", f"{field} in a", f"{field} in b", "difference"):
        table.add_column(Text(column), justify="left" if column.startswith(field) else "right")
    rows = [(" ", row.line_a, row.line_b, row.t, row.a, row.b, row.difference) for row in divergence.context]
    last = divergence
    rows.append((">", last.line_a, last.line_b, last.t, last.a, last.b, last.difference))
    for mark, line_a, line_b, t, a, b, difference in rows:
        time = f"{t:.6g}" if isinstance(t, float) else brief(t, 20)
        shown = "" if difference is None else f"{difference:.3g}"
        table.add_row(
            mark, str(line_a), str(line_b), Text(time), Text(brief(a, 40)), Text(brief(b, 40)), shown
        )
    return table


def _corpus(console: Console, args: argparse.Namespace) -> int:
    """``acphys corpus export`` and ``acphys corpus check``: a line per case, or a table of them."""
    try:
        names = split_names(args.cases, "--cases")
        if args.corpus_command == "export":
            manifest = export_corpus(args.dir, names, on_case=lambda name: _say(console, f"exporting {name}"))
            cases = _count(len(manifest["cases"]), "case", "cases")
            records = sum(case["records"] for case in manifest["cases"])
            _say(console, f"corpus: {cases}, {records:,} golden records in {args.dir}")
            return 0
        if not (math.isfinite(args.tol) and args.tol >= 0.0):
            return _fail(f"--tol must be a non-negative number, got {args.tol}", EXIT_BAD_INPUT)
        exported_by = read_manifest(args.dir).get("acphys")
        if exported_by != __version__:
            print(
                f"acphys: warning: {one_line(args.dir)}: exported by acphys {one_line(str(exported_by))}, "
                f"checked by {__version__}",
                file=sys.stderr,
            )
        ignore = split_names(args.ignore, "--ignore") or ()
        results = check_corpus(args.dir, args.engine, args.tol, args.trace_dir, names, ignore)
    except (CorpusError, DiffError) as error:
        return _fail(one_line(str(error)), EXIT_BAD_INPUT)
    against = f"the traces in {args.trace_dir}" if args.trace_dir else f"the {args.engine} engine's"
    console.print(_corpus_table(results, f"{args.dir}: golden traces against {against}"))
    failed = sum(not result.passed for result in results)
    _say(console, f"{len(results) - failed} passed, {failed} failed (--tol {args.tol:g})")
    return EXIT_DIVERGED if failed else 0


def _corpus_table(results: list[CaseResult], title: str) -> Table:
    """A row per case: its group, pass or fail, the seconds it took, and its first divergence."""
    table = Table(title=Text(one_line(title)))
    for column in ("case", "group", "result", "s", "first divergence"):
        wrap = column == "first divergence"
        table.add_column(column, justify="right" if column == "s" else "left", no_wrap=not wrap)
    for result in results:
        table.add_row(
            Text(result.name),
            Text(result.group),
            Text("pass", style="green") if result.passed else Text("FAIL", style="bold red"),
            f"{result.seconds:.2f}",
            Text("" if result.passed else one_line(result.describe())),
        )
    return table


def _plot(
    console: Console,
    trace: str,
    output: str,
    bodies: str | None,
    view: str | None,
    scenario: str | None = None,
) -> int:
    names = split_names(bodies, "--bodies", "body name")
    check_output(output)
    paths = read_paths(trace)
    found = trace_world(trace, scenario)
    if found.note is not None:
        _say(console, f"note: {found.note}")
    write_plot(paths, output, bodies=names, view=view, title=found.title, world=found.world)
    _say(console, f"plot: {output}")
    return 0


def _view(console: Console, args: argparse.Namespace) -> int:
    """``acphys view``: the text view of a trace, or with ``--html`` the replay page of a trace or
    a scenario (:mod:`acphys.viewer`)."""
    trace, bodies = args.trace, args.bodies
    names = split_names(bodies, "--bodies", "body name")
    if args.html is not None:
        from acphys.viewer import write_html

        result = write_html(
            trace,
            args.html,
            scenario=args.scenario,
            bodies=names,
            until=args.until,
            engine=args.engine,
            warn=lambda message: print(f"acphys: warning: {one_line(message)}", file=sys.stderr),
        )
        records = f"{result.records:,} records, {result.events:,} events"
        _say(
            console,
            f"view: {args.html} ({_count(result.bodies, 'body', 'bodies')}, {records}, "
            f"{result.bytes / 1e6:.2f} MB)",
        )
        return 0
    for option in ("scenario", "until", "engine"):
        if getattr(args, option) is not None:
            return _fail(f"--{option} is for --html (the text view reads a trace)", EXIT_BAD_INPUT)
    if (trace in builtin_scenarios() and not Path(trace).exists()) or trace.endswith(".toml"):
        return _fail(
            f"{one_line(trace)}: a scenario; the text view reads a trace (acphys run --trace), "
            "--html runs the scenario into a replay page",
            EXIT_BAD_INPUT,
        )
    paths = read_paths(trace)
    selected = select_bodies(paths, names)
    show(console, selected, title=f"{Path(trace).name}: {len(selected)} bodies")
    return 0


def _bench(
    console: Console,
    bodies: int,
    seconds: float,
    engine: str,
    workloads: list[str] | None,
    json_file: str | None,
) -> int:
    if not 1 <= bodies <= MAX_BENCH_BODIES:
        return _fail(f"--bodies must be between 1 and {MAX_BENCH_BODIES}, got {bodies}", EXIT_BAD_INPUT)
    if not (math.isfinite(seconds) and 0.0 < seconds <= MAX_BENCH_SECONDS):
        return _fail(f"--seconds must be in (0, {MAX_BENCH_SECONDS:g}], got {seconds}", EXIT_BAD_INPUT)
    limit = MAX_BENCH_BODY_SECONDS if engine != "fast" else MAX_FAST_BENCH_BODY_SECONDS
    if bodies * seconds > limit:
        return _fail(
            f"--bodies {bodies} for --seconds {seconds:g} is {bodies * seconds:,.0f} body-seconds, "
            f"more than the {limit:,} a bench may take on the {engine} engine"
            + (" (the reference engine's share would take hours)" if engine != "fast" else ""),
            EXIT_BAD_INPUT,
        )
    if json_file is not None:
        _check_output_file(json_file)
    names = sorted(set(workloads), key=list(WORKLOADS).index) if workloads else None
    results = run_suite(bodies, seconds, engine, names)
    title = f"acphys bench: {bodies:,} bodies, {seconds:g} s simulated, {engine} engine" + (
        "s" if engine == "both" else ""
    )
    table = Table(title=title)
    columns = ("workload", "engine", "body-steps", "seconds", "steps/s", "vs baseline", "vs real time")
    for column in (*columns, "fast/ref", "fallback", "write-back s"):
        table.add_column(column, justify="left" if column in ("workload", "engine") else "right")
    for result in results:
        ratio = "" if result.fast_vs_reference is None else f"{result.fast_vs_reference:,.1f}x"
        fallback = "" if result.fallback_share is None else f"{100.0 * result.fallback_share:.2f}%"
        write_back = f"{result.write_back_seconds:.3f}" if result.engine == "fast" else ""
        table.add_row(
            result.workload,
            result.engine,
            f"{result.body_steps:,}",
            f"{result.seconds:.3f}",
            f"{result.steps_per_s:,.0f}",
            f"{result.vs_baseline:.4f}",
            f"{result.vs_realtime:.2f}x",
            ratio,
            fallback,
            write_back,
        )
    console.print(table)
    if json_file is not None:
        figures = {
            "acphys": __version__,
            "bodies": bodies,
            "seconds": seconds,
            "engine": engine,
            "results": [result.as_dict() for result in results],
        }
        Path(json_file).write_text(json.dumps(figures, indent=2) + "\n", encoding="utf-8")
        _say(console, f"figures: {json_file}")
    return 0


def _check_output_file(path: str) -> None:
    """Refuse (InputError) an output path that is not a regular file or has no folder, before the work
    that fills it is done (a FIFO would block the write until something reads it)."""
    target = Path(path)
    if target.exists() and not target.is_file():
        raise InputError(path, "cannot write: not a regular file")
    if not target.parent.is_dir():
        raise InputError(path, f"cannot write: no folder {target.parent}")


def _dat(console: Console, args: argparse.Namespace) -> int:
    with DatFile(args.file) as dat:
        if args.dat_command == "info":
            _dat_info(console, dat)
        elif args.dat_command == "list":
            for entry in dat.entries():
                if args.type is None or entry.object_id >> 24 == args.type:
                    flag = " compressed" if entry.compressed else ""
                    console.print(f"{entry.object_id:#010x} {entry.size:>9}{flag}", highlight=False)
        elif args.dat_command == "setup":
            _dat_setup(console, dat, args.id)
        else:
            table = unpack_region(dat.read(REGION_ID)).height_table
            for row in range(0, len(table), 8):
                cells = " ".join(f"{value:8.2f}" for value in table[row : row + 8])
                console.print(f"{row:3d}: {cells}", highlight=False)
    return 0


def _dat_info(console: Console, dat: DatFile) -> None:
    header = dat.header
    lines = [
        one_line(f"file: {dat.path}"),
        f"data set: {header.data_set_name} (subset {header.data_subset})",
        f"block size: {header.block_size} bytes; file size: {header.file_size} bytes",
        f"free blocks: {header.free_blocks} (first {header.first_free:#x}, last {header.final_free:#x})",
        f"directory root: {header.btree_root:#x}; master map: {header.master_map_id:#010x}",
        f"pack versions: engine {header.eng_pack_vnum}, game {header.game_pack_vnum}; "
        f"iteration stamp {header.id_vnum}",
        f"records: {sum(1 for _ in dat.entries())}",
    ]
    for line in lines:
        console.print(line, markup=False, highlight=False, soft_wrap=True)


def _dat_setup(console: Console, dat: DatFile, setup_id: int) -> None:
    record = unpack_setup(dat.read(setup_id))
    console.print(f"setup {record.did:#010x}: {_count(len(record.parts), 'part', 'parts')}", highlight=False)
    for sphere in record.spheres:
        console.print(f"  sphere: center {_g(sphere.center)}, radius {sphere.radius:.4g}", highlight=False)
    for cyl in record.cylspheres:
        console.print(
            f"  cylsphere: low {_g(cyl.low_pt)}, radius {cyl.radius:.4g}, height {cyl.height:.4g}",
            highlight=False,
        )
    sort = record.sorting_sphere
    for line in (
        f"  height {record.height:.4g}, radius {record.radius:.4g}",
        f"  step up {record.step_up_height:.4g}, step down {record.step_down_height:.4g}",
        f"  sorting sphere: center {_g(sort.center)}, radius {sort.radius:.4g}",
        f"  allow free heading: {'yes' if record.allow_free_heading else 'no'}; "
        f"physics BSP: {'yes' if record.has_physics_bsp else 'no'}",
        f"  motion table {record.default_mtable_id:#010x}",
    ):
        console.print(line, highlight=False)


def _g(v: Vector3) -> str:
    """A DAT vector: float32 values to 4 significant figures."""
    return f"{v.x:.4g} {v.y:.4g} {v.z:.4g}"


if __name__ == "__main__":
    sys.exit(main())
