"""``benchmarks/kernel_instructions.py``: how a callgrind profile becomes instructions per kernel
function and per kind of instruction (the run under valgrind itself is too slow for the suite)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "benchmarks" / "kernel_instructions.py"


@pytest.fixture(scope="module")
def tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("kernel_instructions", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


#: Two kernel functions (tick.run_bodies at 0x1000, sweep.find_collisions at 0x1100) and a
#: libc function past them, as the child writes them.
SYMBOLS = (
    "1000 _ZN6acphys4fast7kernels4tick10run_bodiesB2v6B40c8tJTIe\n"
    "1100 _ZN6acphys4fast7kernels5sweep15find_collisionsB4v693B40c8tJTIe\n"
)

#: A profile in callgrind's format with --dump-instr=yes --dump-line=no: absolute and relative
#: positions, and a call whose line after it holds the callee's inclusive cost at the call site.
PROFILE = """\
version: 1
positions: instr
events: Ir
fn=(1) 0x1000
0x1000 3
+4 2
calls=5 0x1100
* 700
+6 1
fn=(2) 0x1100
0x1100 100
+2 40
fn=(3) memcpy
0x7f0000 9
"""


def test_costs_by_address_and_a_call_line_not_counted_twice(tool: ModuleType, tmp_path: Path) -> None:
    profile = tmp_path / "callgrind.out.1"
    profile.write_text(PROFILE)
    costs, calls = tool.instruction_costs(profile)
    # 0x1000: 3; +4 -> 0x1004: 2; the call's 700 at 0x1004 skipped; +6 -> 0x100a: 1.
    assert costs == {0x1000: 3, 0x1004: 2, 0x100A: 1, 0x1100: 100, 0x1102: 40, 0x7F0000: 9}
    assert calls == {0x1100: 5}


def test_instructions_and_calls_go_to_the_function_that_holds_them(tool: ModuleType, tmp_path: Path) -> None:
    (tmp_path / "symbols").write_text(SYMBOLS)
    symbols = tool.Symbols(tmp_path / "symbols")
    assert symbols.owner(0x1004) == "tick.run_bodies"
    assert symbols.owner(0x1102) == "sweep.find_collisions"
    assert symbols.owner(0x0FFF) is None
    assert symbols.owner(0x1100 + (1 << 16)) is None  # past the last function's 64 KiB
    assert symbols.starting_at(0x1100) == "sweep.find_collisions"
    assert symbols.starting_at(0x1102) is None
    profile = tmp_path / "callgrind.out.1"
    profile.write_text(PROFILE)
    total, own, calls = tool.attribute(*tool.instruction_costs(profile), symbols)
    assert total == 155  # the libc function's 9 counted in all, not in a kernel
    assert own == {"tick.run_bodies": 6, "sweep.find_collisions": 140}
    assert calls == {"sweep.find_collisions": 5}


def test_instructions_are_sorted_into_kinds(tool: ModuleType) -> None:
    code = {
        1: "vcvtsd2ss %xmm3,%xmm3,%xmm3",
        2: "vcvtss2sd %xmm3,%xmm3,%xmm3",
        3: "vmovsd %xmm6,0x38(%rsp)",
        4: "vmovsd 0x3a(%r14),%xmm1",
        5: "mov    %rcx,%r14",
        6: "vmulsd %xmm15,%xmm15,%xmm4",
        7: "vucomisd %xmm0,%xmm1",
        8: "jne    5c94",
        9: "push   %rbp",
        10: "lea    0x8(%rax),%rdx",
        11: "nopl   0x0(%rax)",
    }
    costs = {address: 10 * address for address in code} | {99: 5}  # 99: not kernel code
    assert tool.kinds(costs, code) == {
        "float32 rounding (to float and back)": 30,
        "stack load or store (spills, tuples)": 30,
        "other load or store": 40,
        "register copy or constant": 50,
        "float arithmetic": 60,
        "compare, test, branch": 150,
        "call, return, push, pop": 90,
        "integer and address arithmetic": 100,
        "other": 110,
    }


def test_a_functions_hottest_instructions_in_address_order(tool: ModuleType, tmp_path: Path) -> None:
    (tmp_path / "symbols").write_text(SYMBOLS)
    symbols = tool.Symbols(tmp_path / "symbols")
    costs = {0x1100: 4, 0x1104: 9, 0x1108: 1, 0x110C: 9, 0x1000: 50}
    code = {0x1100: "push %rbp", 0x1104: "vaddsd", 0x1108: "ret", 0x110C: "vmulsd"}
    rows = tool.hottest("sweep.find_collisions", costs, code, symbols, 3)
    assert rows == [(0x0, 4, "push %rbp"), (0x4, 9, "vaddsd"), (0xC, 9, "vmulsd")]
    with pytest.raises(SystemExit, match=r"no kernel function 'sweep\.nothing'"):
        tool.hottest("sweep.nothing", costs, code, symbols, 3)


def test_a_function_compiled_twice_counts_both_copies_from_their_own_starts(
    tool: ModuleType, tmp_path: Path
) -> None:
    """Numba can compile one function twice (``_insert_level_2``, one per caller's types): both
    copies carry its name, and each instruction's offset is from its own copy's start."""
    second = "1200 _ZN6acphys4fast7kernels5sweep15find_collisionsB5v1239B40c8tJTIe\n"
    (tmp_path / "symbols").write_text(SYMBOLS + second)
    symbols = tool.Symbols(tmp_path / "symbols")
    costs = {0x1104: 9, 0x1204: 7, 0x1208: 2}
    code = {0x1104: "vaddsd", 0x1204: "vmulsd", 0x1208: "ret"}
    rows = tool.hottest("sweep.find_collisions", costs, code, symbols, 2)
    assert rows == [(0x4, 9, "vaddsd"), (0x4, 7, "vmulsd")]


def test_hot_code_is_the_lines_run_at_least_every_other_step(tool: ModuleType, tmp_path: Path) -> None:
    (tmp_path / "symbols").write_text(SYMBOLS)
    symbols = tool.Symbols(tmp_path / "symbols")
    steps = 10
    costs = {
        0x1000: 10,  # run_bodies' first line, every step
        0x1004: 10,  # the same line: counted once
        0x1040: 5,  # its second line, every other step: hot
        0x1080: 4,  # its third, less often: cold
        0x10F8: 20,  # the line 0x10c0-0x10ff, the last before find_collisions: run_bodies'
        0x1140: 30,  # find_collisions, three times a step
        0x7F0000: 10,  # libc: outside
    }
    lines, by_name = tool.hot_lines(costs, steps, symbols)
    assert lines == 5
    assert by_name == {"tick.run_bodies": 3, "sweep.find_collisions": 1, "(outside)": 1}


def test_the_counted_kernels_leave_out_what_valgrind_cannot_decode(tool: ModuleType) -> None:
    """Valgrind 3.19 stops at the first EVEX-encoded instruction: on a core with AVX-512 the
    counted kernels are compiled without it (and without AMX), every other feature as it was."""
    features = "+avx2,+avx512f,-avx512vp2intersect,+avx512vl,+amx-tile,+fma,+evex512,-sse4a"
    assert tool.decodable(features) == (
        "+avx2,-avx512f,-avx512vp2intersect,-avx512vl,-amx-tile,+fma,-evex512,-sse4a"
    )
