"""Count the fast engine's instructions per body-step, split by kernel function.

Times on a shared machine swing by 2x from minute to minute; instruction counts do not. This
runs a workload on the fast engine under ``valgrind --tool=callgrind`` with instrumentation off
while Python starts and the kernels load, warms the bodies up (``--warm`` ticks: links
played, walks under way), then counts ``--ticks`` ticks only, and prints the instructions per
body-step: in all (the engine's per-tick Python included), in the kernels, and per kernel
function (own instructions, calls per body-step, instructions per call) and by kind of
instruction (loads and stores, the stack's among them, float32 roundings, arithmetic, branches,
calls), and how much code a step executes (the 64-byte lines holding an instruction run at least
every other step, in all and by function; ``benchmarks/code_fetch.py`` gives this core's rate on
straight-line code of a size); ``--annotate FUNCTION`` lists that function's most executed
instructions (``objdump`` of the kernels' object code)::

    .venv/bin/python benchmarks/kernel_instructions.py                    # hills, 529 bodies
    .venv/bin/python benchmarks/kernel_instructions.py --workload crowd --bodies 100 --json out.json
    .venv/bin/python benchmarks/kernel_instructions.py --annotate sweep.check_other_cells --lines 60

The kernels are loaded once natively first, so callgrind never watches a compile, and the run
under valgrind loads this machine's code. Needs ``valgrind`` (with ``callgrind_control``) and
binutils (``nm``, ``objdump``) on the PATH; about 30 s once the kernels are compiled, mostly
Python's start under valgrind.
"""

from __future__ import annotations

import argparse
import bisect
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]


# -- the child: runs under valgrind ----------------------------------------------------------


def _remember_cached_objects() -> dict[int, bytes]:
    """Keep the object code of every library Numba loads from its cache (by the library's id)."""
    from numba.core import codegen

    objects: dict[int, bytes] = {}
    unserialize = codegen.CPUCodeLibrary._unserialize.__func__

    def keeping(cls: type, code_generator: object, state: tuple) -> object:
        library = unserialize(cls, code_generator, state)
        if state[1] == "object":
            objects[id(library)] = state[2][0]
        return library

    codegen.CPUCodeLibrary._unserialize = classmethod(keeping)
    return objects


def _write_symbols(objects: dict[int, bytes], path: Path) -> None:
    """``address name`` of every function linked into ``run_bodies``, from its object code (kept
    beside ``path`` as ``kernels.o``, with the address its offset 0 is loaded at in ``base``)."""
    from acphys.fast.kernels import tick

    compiled = tick.run_bodies.overloads[tick.run_bodies.signatures[0]]
    library = compiled.library
    code = objects.get(id(library)) or library._get_compiled_object()
    with tempfile.NamedTemporaryFile(suffix=".o") as obj:
        obj.write(code)
        obj.flush()
        listing = subprocess.run(
            ["nm", "-n", "--defined-only", obj.name], capture_output=True, text=True, check=True
        ).stdout
    offsets = {}
    for line in listing.splitlines():
        fields = line.split()
        if len(fields) == 3 and fields[1] in "tTwW":
            offsets[fields[2]] = int(fields[0], 16)
    main = compiled.fndesc.mangled_name
    base = library.get_pointer_to_function(main) - offsets[main]
    path.write_text("".join(f"{base + offset:x} {name}\n" for name, offset in offsets.items()))
    (path.parent / "kernels.o").write_bytes(code)
    (path.parent / "base").write_text(f"{base:x}")


def _wait_for(path: Path, process: subprocess.Popen | None = None) -> None:
    """Wait until ``path`` exists; if ``process`` (the run under valgrind) stops first, say so."""
    while not path.exists():
        if process is not None and process.poll() is not None:
            raise SystemExit("kernel_instructions: the run under valgrind stopped early")
        time.sleep(0.05)


def child(workdir: Path, workload: str, bodies: int, ticks: int, warm: int) -> None:
    objects = _remember_cached_objects()
    from acphys.bench import WORKLOADS

    sim = WORKLOADS[workload][1](bodies, 1e6, "fast")
    for _ in range(warm):
        sim.step(sync=False)
    _write_symbols(objects, workdir / "symbols")
    counts = sim.physics.counts
    before = counts.kernel + counts.reference
    (workdir / "ready").write_text("")
    _wait_for(workdir / "go")
    for _ in range(ticks):
        sim.step(sync=False)
    (workdir / "done").write_text(str(counts.kernel + counts.reference - before))
    _wait_for(workdir / "end")


# -- the parent: drives valgrind and reads its counts --------------------------------------------


def _function_name(symbol: str) -> str:
    """``module.function`` of a Numba-mangled kernel symbol (``_ZN6acphys4fast7kernels4tick...``)."""
    rest = symbol.split("kernels", 1)[1] if "kernels" in symbol else symbol
    names = []
    while rest[:1].isdigit():
        digits = re.match(r"\d+", rest).group(0)
        start = len(digits)
        names.append(rest[start : start + int(digits)])
        rest = rest[start + int(digits) :]
    name = ".".join(names[:2]) or symbol[:60]
    return name + " (wrapper)" if symbol.startswith(("_ZN7cpython", "cfunc.")) else name


def instruction_costs(profile: Path) -> tuple[dict[int, int], dict[int, int]]:
    """``(instructions executed at each address, calls made to each address)`` of a callgrind
    profile written with ``--dump-instr=yes --dump-line=no``."""
    costs: dict[int, int] = {}
    calls: dict[int, int] = {}
    position = 0
    call_line = False
    for line in profile.read_text().splitlines():
        if line.startswith("calls="):
            count, target = line[6:].split()[:2]
            if target.startswith("0x"):
                calls[int(target, 16)] = calls.get(int(target, 16), 0) + int(count)
            call_line = True
            continue
        fields = line.split()
        if len(fields) != 2 or line[:1] not in "0x+-*":
            continue
        where, cost = fields
        if where.startswith("0x"):
            position = int(where, 16)
        elif where[0] in "+-":
            position += int(where)
        if call_line:  # the call's inclusive cost, counted in its callee already
            call_line = False
            continue
        costs[position] = costs.get(position, 0) + int(cost)
    return costs, calls


class Symbols:
    """The kernel functions' start addresses (the ``symbols`` file the child writes)."""

    def __init__(self, path: Path) -> None:
        self.table = sorted(
            (int(address, 16), _function_name(name))
            for address, name in (line.split(None, 1) for line in path.read_text().splitlines())
        )
        self.starts = [address for address, _ in self.table]

    def locate(self, address: int) -> tuple[int, str] | None:
        """``(start, name)`` of the kernel function holding ``address`` (the last one: within
        64 KiB), or None."""
        k = bisect.bisect_right(self.starts, address) - 1
        if 0 <= k < len(self.table) - 1 or (k == len(self.table) - 1 and address - self.starts[k] < 1 << 16):
            return self.table[k]
        return None

    def owner(self, address: int) -> str | None:
        """The name of the kernel function holding ``address``, or None."""
        found = self.locate(address)
        return found[1] if found is not None else None

    def starting_at(self, address: int) -> str | None:
        """The name of the kernel function that starts at ``address``, or None."""
        found = self.locate(address)
        return found[1] if found is not None and found[0] == address else None


#: A cache line of code, in bytes: what the core fetches into its instruction cache.
CODE_LINE = 64


def hot_lines(costs: dict[int, int], steps: int, symbols: Symbols) -> tuple[int, dict[str, int]]:
    """``(lines, lines by kernel function)``: the cache lines of code a body-step executes (some
    instruction in them at least every other step), in all and by the kernel function holding
    them (``(outside)``: Python, libc, libm)."""
    lines: dict[int, int] = {}
    for address, cost in costs.items():
        line = address // CODE_LINE
        lines[line] = max(lines.get(line, 0), cost)
    by_name: dict[str, int] = {}
    hot = [line for line, cost in lines.items() if cost * 2 >= steps]
    for line in hot:
        start = line * CODE_LINE
        name = symbols.owner(start) or symbols.owner(start + CODE_LINE - 1) or "(outside)"
        by_name[name] = by_name.get(name, 0) + 1
    return len(hot), by_name


def attribute(
    costs: dict[int, int], calls: dict[int, int], symbols: Symbols
) -> tuple[int, dict[str, int], dict[str, int]]:
    """``(all instructions, own instructions by kernel function, calls by kernel function)``."""
    own: dict[str, int] = {}
    for address, cost in costs.items():
        name = symbols.owner(address)
        if name is not None:
            own[name] = own.get(name, 0) + cost
    by_name: dict[str, int] = {}
    for address, count in calls.items():
        name = symbols.starting_at(address)
        if name is not None:
            by_name[name] = by_name.get(name, 0) + count
    return sum(costs.values()), own, by_name


def disassemble(workdir: Path) -> dict[int, str]:
    """The kernels' instructions by the address they run at (``objdump`` of the kept object code)."""
    base = int((workdir / "base").read_text(), 16)
    listing = subprocess.run(
        ["objdump", "-d", "--no-show-raw-insn", str(workdir / "kernels.o")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    code = {}
    for line in listing.splitlines():
        found = re.match(r"\s+([0-9a-f]+):\s+(\S.*)", line)
        if found:
            code[base + int(found.group(1), 16)] = re.sub(r"\s+<.*>$", "", found.group(2))
    return code


#: What the kernels' instructions do, tested in this order on the mnemonic and its operands.
KINDS = (
    ("float32 rounding (to float and back)", r"^vcvt(sd2ss|ss2sd)"),
    ("stack load or store (spills, tuples)", r"^v?mov.*\(%rsp\)"),
    ("other load or store", r"^v?mov.*\("),
    ("register copy or constant", r"^v?mov"),
    (
        "float arithmetic",
        r"^v(add|sub|mul|div|sqrt|fn?m(add|sub)|min|max|xor|and|or|round|blend|unpck|perm|broadcast)",
    ),
    ("compare, test, branch", r"^(v?u?comi|cmp|test|j|set|vcmp|cmov)"),
    ("call, return, push, pop", r"^(call|ret|push|pop)"),
    (
        "integer and address arithmetic",
        r"^(add|sub|lea|imul|inc|dec|and|or|xor|shl|shr|sar|neg|not|bzhi|sbb|adc)",
    ),
)


def kinds(costs: dict[int, int], code: dict[int, str]) -> dict[str, int]:
    """The kernels' instructions executed, by :data:`KINDS` (``other`` for the rest)."""
    patterns = [(name, re.compile(pattern)) for name, pattern in KINDS]
    counted: dict[str, int] = {}
    for address, cost in costs.items():
        text = code.get(address)
        if text is None:
            continue
        kind = next((name for name, pattern in patterns if pattern.search(text)), "other")
        counted[kind] = counted.get(kind, 0) + cost
    return counted


def hottest(
    function: str, costs: dict[int, int], code: dict[int, str], symbols: Symbols, lines: int
) -> list[tuple[int, int, str]]:
    """``(offset in the function, instructions, text)`` of its ``lines`` most executed
    instructions, in address order (a name compiled twice counts both copies, each instruction's
    offset from its own copy's start)."""
    if all(name != function for _, name in symbols.table):
        raise SystemExit(f"kernel_instructions: no kernel function {function!r} in the code")
    mine = []
    for address, cost in costs.items():
        found = symbols.locate(address)
        if found is not None and found[1] == function:
            mine.append((address, cost, address - found[0]))
    top = sorted(mine, key=lambda item: -item[1])[:lines]
    return [(offset, cost, code.get(address, "?")) for address, cost, offset in sorted(top)]


#: Instruction sets valgrind 3.19 cannot decode (EVEX-encoded AVX-512, AMX).
UNDECODABLE = ("avx512", "amx", "evex512", "avx10")


def decodable(features: str) -> str:
    """An LLVM feature string (``+avx2,+avx512f,...``) with the sets valgrind cannot run off."""
    kept = []
    for feature in features.split(","):
        if feature[:1] == "+" and feature[1:].startswith(UNDECODABLE):
            feature = "-" + feature[1:]
        kept.append(feature)
    return ",".join(kept)


def valgrind_cpu() -> dict[str, str]:
    """The ``NUMBA_CPU_NAME`` and ``NUMBA_CPU_FEATURES`` to compile the counted kernels for: this
    machine's CPU, less the instruction sets valgrind cannot run (on a core with AVX-512 the
    counts are those of the AVX2 code, compiled once into Numba's cache beside the native)."""
    from llvmlite import binding

    features = decodable(binding.get_host_cpu_features().flatten())
    return {"NUMBA_CPU_NAME": binding.get_host_cpu_name(), "NUMBA_CPU_FEATURES": features}


def measure(
    workload: str, bodies: int, ticks: int, warm: int, annotate: str | None = None, lines: int = 40
) -> dict:
    """The figures of one counted run: per body-step in all, in the kernels, by kernel function
    and by kind of instruction; with ``annotate``, that function's most executed instructions."""
    for tool in ("valgrind", "callgrind_control", "nm", "objdump"):
        if shutil.which(tool) is None:
            raise SystemExit(f"kernel_instructions: {tool} is not on the PATH")
    # Load (or compile) the kernels natively first: callgrind must not watch a compile. Valgrind
    # shows Python another CPU (a Haswell), whose code Numba would compile afresh: the run under
    # it names this machine's CPU, so that it loads and counts the code that runs natively.
    cpu = valgrind_cpu()
    load = "from acphys.bench import warm_up; warm_up()"
    subprocess.run([sys.executable, "-c", load], check=True, env={**os.environ, **cpu})
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        profile = workdir / "callgrind.out"
        command = ["valgrind", "--tool=callgrind", "--instr-atstart=no", "--dump-instr=yes"]
        command += ["--dump-line=no", f"--callgrind-out-file={profile}", sys.executable, __file__]
        command += ["--child", tmp, "--workload", workload, "--bodies", str(bodies)]
        command += ["--ticks", str(ticks), "--warm", str(warm)]
        process = subprocess.Popen(
            command, env={**os.environ, **cpu}, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
        try:
            _wait_for(workdir / "ready", process)
            control = ["callgrind_control"]
            subprocess.run([*control, "--instr=on", str(process.pid)], check=True, capture_output=True)
            (workdir / "go").write_text("")
            _wait_for(workdir / "done", process)
            subprocess.run([*control, "--dump", str(process.pid)], check=True, capture_output=True)
            (workdir / "end").write_text("")
            process.wait()
        finally:
            if process.poll() is None:
                process.kill()
        steps = int((workdir / "done").read_text())
        dumps = sorted(workdir.glob("callgrind.out.*"))
        costs, called = instruction_costs(dumps[-1])
        symbols = Symbols(workdir / "symbols")
        code = disassemble(workdir)
    total, own, calls = attribute(costs, called, symbols)
    kernel = sum(own.values())
    lines, lines_by_name = hot_lines(costs, steps, symbols)
    functions = [
        {
            "function": name,
            "per_step": cost / steps,
            "calls_per_step": calls.get(name, 0) / steps,
            "per_call": cost / calls[name] if calls.get(name) else None,
            "hot_code_kb": lines_by_name.get(name, 0) * CODE_LINE / 1024,
        }
        for name, cost in sorted(own.items(), key=lambda item: -item[1])
    ]
    return {
        "workload": workload,
        "bodies": bodies,
        "ticks": ticks,
        "body_steps": steps,
        "per_step": total / steps,
        "kernel_per_step": kernel / steps,
        "hot_code_kb": lines * CODE_LINE / 1024,
        "hot_code_outside_kb": lines_by_name.get("(outside)", 0) * CODE_LINE / 1024,
        "functions": functions,
        "kinds": {
            kind: count / steps
            for kind, count in sorted(kinds(costs, code).items(), key=lambda item: -item[1])
        },
        "annotated": [
            {"offset": offset, "per_step": cost / steps, "instruction": text}
            for offset, cost, text in (hottest(annotate, costs, code, symbols, lines) if annotate else [])
        ],
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--workload", default="hills")
    parser.add_argument("--bodies", type=int, default=529)
    parser.add_argument("--ticks", type=int, default=10, help="ticks counted")
    parser.add_argument("--warm", type=int, default=60, help="ticks run before counting")
    parser.add_argument("--top", type=int, default=30, help="kernel functions listed")
    parser.add_argument(
        "--annotate", metavar="FUNCTION", help="list this kernel function's hottest instructions"
    )
    parser.add_argument("--lines", type=int, default=40, help="instructions listed by --annotate")
    parser.add_argument("--json", type=Path, help="also write the figures here")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        child(Path(args.child), args.workload, args.bodies, args.ticks, args.warm)
        return 0
    figures = measure(args.workload, args.bodies, args.ticks, args.warm, args.annotate, args.lines)
    print(
        f"{figures['workload']}, {figures['bodies']} bodies, {figures['body_steps']:,} body-steps counted: "
        f"{figures['per_step']:,.0f} instructions a body-step, "
        f"{figures['kernel_per_step']:,.0f} in the kernels; {figures['hot_code_kb']:.1f} KB of code "
        f"executed a step ({figures['hot_code_outside_kb']:.1f} KB outside the kernels)"
    )
    print(f"{'kernel function':40} {'instr/step':>10} {'calls/step':>10} {'instr/call':>10} {'hot KB':>7}")
    for row in figures["functions"][: args.top]:
        per_call = f"{row['per_call']:10.1f}" if row["per_call"] is not None else f"{'-':>10}"
        print(
            f"{row['function']:40} {row['per_step']:10.1f} {row['calls_per_step']:10.2f} {per_call}"
            f" {row['hot_code_kb']:7.1f}"
        )
    print(f"\n{'kind of instruction (kernels)':40} {'instr/step':>10}")
    for kind, per_step in figures["kinds"].items():
        print(f"{kind:40} {per_step:10.1f}")
    if args.annotate:
        print(f"\n{args.annotate}: its {len(figures['annotated'])} most executed instructions")
        for row in figures["annotated"]:
            print(f"  +{row['offset']:<6x} {row['per_step']:8.2f}  {row['instruction']}")
    if args.json:
        args.json.write_text(json.dumps(figures, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
