"""The suite's set-up: the fast engine's kernels are compiled once, in the background.

A cold compile of the kernels takes minutes on one core, and every xdist worker that meets a test
of the fast engine would compile them itself, all at once. Instead the session's first process
starts one compile (:func:`acphys.bench.warm_up`) in a child that holds a lock until it ends; the
tests that run the kernels (every test under ``tests/fast``, and those marked ``kernels``) go to
the end of the order and wait for the lock, then load the kernels from Numba's cache, while the
others run meanwhile. Nothing depends on the wait for its result: a test that runs before the
compile ends merely compiles the kernels itself.
"""

from __future__ import annotations

import fcntl
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

#: The lock file's path, handed from the session's first process to the xdist workers.
LOCK = "ACPHYS_TEST_KERNEL_LOCK"
FAST_TESTS = Path(__file__).parent / "fast"
#: How much less the xdist workers ask of the CPU than the compile.
WORKER_NICENESS = 10

_compile: subprocess.Popen[bytes] | None = None
_ready = False


def pytest_configure(config: pytest.Config) -> None:
    global _compile
    config.addinivalue_line("markers", "kernels: the test runs the fast engine's compiled kernels")
    if hasattr(config, "workerinput"):
        # The compile is the session's longest task: it gets a core, the workers share the rest.
        os.nice(WORKER_NICENESS)
        return
    if LOCK in os.environ or config.option.collectonly:
        return
    fd, path = tempfile.mkstemp(prefix="acphys-kernels-", suffix=".lock")
    fcntl.flock(fd, fcntl.LOCK_EX)  # held by the child (it shares the open file) until it ends
    os.environ[LOCK] = path
    code = "from acphys.bench import warm_up; warm_up()"
    _compile = subprocess.Popen(
        [sys.executable, "-c", code], pass_fds=(fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    os.close(fd)


def pytest_unconfigure(config: pytest.Config) -> None:
    if _compile is None:
        return
    if _compile.poll() is None:  # the session needed no kernels, or stopped early
        _compile.terminate()
        _compile.wait()
    os.unlink(os.environ.pop(LOCK))


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if item.path.is_relative_to(FAST_TESTS):
            item.add_marker("kernels")
    items.sort(key=lambda item: item.get_closest_marker("kernels") is not None)  # stable


@pytest.fixture(autouse=True)
def _kernels_compiled(request: pytest.FixtureRequest) -> None:
    """Before a test of the kernels: wait until the session's compile has ended."""
    global _ready
    if _ready or request.node.get_closest_marker("kernels") is None:
        return
    path = os.environ.get(LOCK)
    if path is not None and os.path.exists(path):
        with open(path) as lock:
            fcntl.flock(lock, fcntl.LOCK_SH)
    _ready = True
