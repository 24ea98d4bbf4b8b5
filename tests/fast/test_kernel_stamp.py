"""Numba's cache of the kernels is stamped by every source they are compiled from
(:mod:`acphys.fast.kernels.stamp`): an edit in one kernel module compiles the kernels of the
others again, which Numba alone would keep."""

from __future__ import annotations

import importlib
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

from numba import njit
from numba.core.registry import CPUDispatcher

from acphys.fast.kernels import stamp

KERNEL_MODULES = sorted(path.stem for path in stamp.KERNELS.glob("*.py") if path.stem != "__init__")


@njit(cache=True)
def _elsewhere(x):
    return x + 1.0


def test_the_sources_are_the_kernels_and_the_modules_they_import_from() -> None:
    names = {path.relative_to(stamp.ACPHYS).as_posix() for path in stamp.sources()}
    assert {f"fast/kernels/{name}.py" for name in KERNEL_MODULES} <= names
    # the records' layouts, the constants and flags, the terrain's water types
    assert {"fast/layout.py", "constants.py", "flags.py", "world/terrain.py"} <= names
    # not the reference's tick or sweep: editing them compiles no kernel again
    assert not {"simulation.py", "physics_obj.py", "transition/transition.py"} & names
    assert all(path.is_file() for path in stamp.sources())


def test_every_kernel_is_cached_under_the_stamp_and_nothing_else_is() -> None:
    kernels = 0
    for name in KERNEL_MODULES:
        module = importlib.import_module(f"acphys.fast.kernels.{name}")
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.__module__ == module.__name__:
                locator = value._cache._impl.locator
                assert isinstance(locator, stamp.LOCATORS), f"{name}.{value.__name__}"
                assert locator.get_source_stamp() == stamp.STAMP
                kernels += 1
    assert kernels > 100  # every @njit(cache=True) of the package
    assert not isinstance(_elsewhere._cache._impl.locator, stamp.LOCATORS)
    assert _elsewhere(1.0) == 2.0


def test_the_digest_changes_with_any_byte_and_any_name(tmp_path: Path) -> None:
    first, second = tmp_path / "a.py", tmp_path / "b.py"
    first.write_text("X = 1\n")
    second.write_text("Y = 2\n")
    before = stamp.digest([first, second])
    assert stamp.digest([first, second]) == before and len(before) == 64
    second.write_text("Y = 3\n")
    assert stamp.digest([first, second]) != before
    second.write_text("Y = 2\n")
    renamed = second.rename(tmp_path / "c.py")
    assert stamp.digest([first, renamed]) != before


_TURN = """
import json, sys
import numpy as np
from acphys.fast.kernels.sequence import apply_physics
origin, q, m = apply_physics(
    (1.0, 0.0, 0.0), (0.0, 0.0, 2.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0),
    (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0), 0.5, 0.5, np.zeros(4),
)
print(json.dumps(q))
"""


def test_an_edit_of_frame_py_reaches_a_cached_kernel_of_sequence_py(tmp_path: Path) -> None:
    """``sequence.apply_physics`` turns its frame through ``frame.grotate_remembered``. Compiled
    once and cached, then the angle's terms in ``frame.py`` edited to turn by nothing: the next
    process must turn by nothing. Numba alone would load the cached ``apply_physics`` (its own
    file is unchanged)."""
    source = Path(stamp.ACPHYS)
    copy = tmp_path / "src" / "acphys"
    shutil.copytree(source, copy, ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PYTHONPATH": str(copy.parent), "NUMBA_CACHE_DIR": str(tmp_path / "cache")}

    def turned() -> list[float]:
        command = [sys.executable, "-c", _TURN]
        done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)
        assert done.returncode == 0, done.stderr
        return json.loads(done.stdout)

    assert turned()[3] != 0.0  # a turn about z
    frame = copy / "fast" / "kernels" / "frame.py"
    text = frame.read_text("utf-8")
    terms = "return f32(1.0 / theta), math.sin(theta * 0.5), f32(math.cos(theta * 0.5))"
    assert text.count(terms) == 1
    frame.write_text(text.replace(terms, "return f32(1.0 / theta), 0.0, 1.0"), "utf-8")
    assert turned() == [1.0, 0.0, 0.0, 0.0]
