"""How fast this core runs straight-line code as the code grows: where its instruction caches end.

A fast-engine step runs its code about once (a sweep's passes, the commit, the sequence: few
loops), and more of it than the instruction caches hold, so fetching the code could bound it
(measured on 2026-12-03: it does not, see ``benchmarks/README.md``). This builds
functions of ``--sizes`` kilobytes of straight-line code shaped like the kernels' (a load with a
32-bit displacement, a multiply and an add on it, the float32 round trip, a store, a compare and
branch: 53 bytes, 8 instructions), calls each many times, and prints the instructions and code
bytes it runs a cycle. The clock is measured first (four dependent adds an iteration, one a cycle).
Below the caches' size the rate is the core's (about 4 instructions a cycle on a Zen 3); past it,
what the next cache delivers::

    .venv/bin/python benchmarks/code_fetch.py
    .venv/bin/python benchmarks/code_fetch.py --sizes 16 20 24 28 32

Compare with ``benchmarks/kernel_instructions.py``, which gives the kilobytes of code a step
executes. Needs a C compiler (``cc``) that assembles AT&T syntax with AVX; x86-64 only.
"""

from __future__ import annotations

import argparse
import platform
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

#: Bytes and instructions of one block of the generated code.
BLOCK_BYTES = 53
BLOCK_INSTRUCTIONS = 8

_MAIN = r"""
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
void straight(double *p);
static double data[2048] __attribute__((aligned(64)));
static double seconds(struct timespec a, struct timespec b) {
  return (b.tv_sec - a.tv_sec) + (b.tv_nsec - a.tv_nsec) * 1e-9;
}
int main(int argc, char **argv) {
  long calls = atol(argv[1]), adds = 400000000L, x = 0;
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  for (long i = 0; i < adds / 4; i++)
    __asm__ volatile("add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0" : "+r"(x));
  clock_gettime(CLOCK_MONOTONIC, &b);
  double hz = adds / seconds(a, b);
  for (int k = 0; k < 2048; k++) data[k] = 1.0;
  for (long i = 0; i < 1000; i++) straight(data);
  clock_gettime(CLOCK_MONOTONIC, &a);
  for (long i = 0; i < calls; i++) straight(data);
  clock_gettime(CLOCK_MONOTONIC, &b);
  printf("%.6e %.6e %ld\n", hz, seconds(a, b) / calls, x);
  return 0;
}
"""


def straight_code(kilobytes: int) -> tuple[str, int]:
    """Assembly of a function ``straight(double *p)`` of about ``kilobytes`` KB of blocks, and
    its block count. Blocks use eight registers in turn (no chain longer than a block) and read
    and write a 25-KB window of ``p`` (the first-level data cache holds it)."""
    lines = [".text", ".globl straight", ".p2align 6", "straight:"]
    blocks = kilobytes * 1024 // BLOCK_BYTES
    for i in range(blocks):
        r, o = i % 8, (i * 40) % 3000 + 256
        lines += [
            f"vmovsd {o}(%rdi),%xmm{r}",
            f"vmulsd {o + 8}(%rdi),%xmm{r},%xmm{r}",
            f"vaddsd {o + 16}(%rdi),%xmm{r},%xmm{r}",
            f"vcvtsd2ss %xmm{r},%xmm{r},%xmm{r}",
            f"vcvtss2sd %xmm{r},%xmm{r},%xmm{r}",
            f"vmovsd %xmm{r},{o + 3200}(%rdi)",
            f"cmpl $0,{o}(%rdi)",
            "js 1f",
        ]
    lines += ["1:", "ret", '.section .note.GNU-stack,"",@progbits']
    return "\n".join(lines) + "\n", blocks


def measure(kilobytes: int, compiler: str, folder: Path) -> dict:
    """Build and run the ``kilobytes`` function; its figures."""
    code, blocks = straight_code(kilobytes)
    (folder / "straight.S").write_text(code)
    (folder / "main.c").write_text(_MAIN)
    program = folder / "fetch"
    subprocess.run(
        [compiler, "-O1", "-o", str(program), str(folder / "main.c"), str(folder / "straight.S")],
        check=True,
        capture_output=True,
    )
    calls = max(2000, 300_000_000 // (blocks * BLOCK_INSTRUCTIONS))
    hz, per_call, _ = subprocess.run(
        [str(program), str(calls)], check=True, capture_output=True, text=True
    ).stdout.split()
    cycles = float(per_call) * float(hz)
    return {
        "kilobytes": kilobytes,
        "ghz": float(hz) / 1e9,
        "instructions_per_cycle": blocks * BLOCK_INSTRUCTIONS / cycles,
        "bytes_per_cycle": blocks * BLOCK_BYTES / cycles,
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[8, 16, 20, 24, 28, 32, 40, 48, 64])
    args = parser.parse_args(argv)
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None or platform.machine() not in ("x86_64", "AMD64"):
        print("code_fetch: needs a C compiler (cc) on an x86-64 machine", file=sys.stderr)
        return 2
    if any(size < 1 or size > 4096 for size in args.sizes):
        print("code_fetch: --sizes are kilobytes from 1 to 4096", file=sys.stderr)
        return 2
    print(f"{'code KB':>8} {'GHz':>5} {'instr/cycle':>12} {'bytes/cycle':>12}")
    with tempfile.TemporaryDirectory() as tmp:
        for size in args.sizes:
            row = measure(size, compiler, Path(tmp))
            print(
                f"{row['kilobytes']:8d} {row['ghz']:5.2f} {row['instructions_per_cycle']:12.2f}"
                f" {row['bytes_per_cycle']:12.1f}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
