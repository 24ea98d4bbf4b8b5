"""One freshness stamp in Numba's cache for every kernel: the sources they are compiled from.

Numba keeps a cached function while its own file is unchanged. But a kernel's machine code also
holds what it inlined or called from other modules, the constants it read there and the record
layouts it was compiled against; edit ``frame.py`` and the cached ``sweep.py`` functions that
inline its frame compositions would go on running the old ones. So every function of this package
is stamped with one digest of the package's modules and of the acphys modules they import from
(:func:`sources`): any change to any of them compiles every kernel again. Not retail: plumbing.

:func:`install` puts the stamping locators first in Numba's list; the package's ``__init__`` calls
it before any kernel is defined.
"""

from __future__ import annotations

import hashlib
import re
from pathlib import Path
from typing import Any

from numba.core import caching

#: This package's folder.
KERNELS = Path(__file__).resolve().parent
#: The ``acphys`` package's folder.
ACPHYS = KERNELS.parents[1]


def _module_file(module: str) -> Path:
    """The source file of the acphys module named ``module``."""
    base = ACPHYS.joinpath(*module.split(".")[1:])
    return base / "__init__.py" if base.is_dir() else base.with_suffix(".py")


#: A line importing from an acphys module (``from acphys.x import ...``, ``import acphys.x``).
_IMPORT = re.compile(r"^(?:from|import)\s+(acphys(?:\.\w+)+)", re.MULTILINE)


def sources() -> list[Path]:
    """The kernel modules and every acphys module one of them imports from, sorted (read line by
    line: parsing them takes a tenth of a second, and this runs at every start)."""
    kernels = sorted(KERNELS.glob("*.py"))
    found = set(kernels)
    for path in kernels:
        found.update(_module_file(name) for name in _IMPORT.findall(path.read_text("utf-8")))
    return sorted(found)


def digest(paths: list[Path]) -> str:
    """The SHA-256 of the files ``paths``: each one's name within acphys (or its own name) and
    its bytes."""
    sha = hashlib.sha256()
    for path in paths:
        name = path.relative_to(ACPHYS).as_posix() if path.is_relative_to(ACPHYS) else path.name
        sha.update(name.encode() + b"\0" + path.read_bytes() + b"\0")
    return sha.hexdigest()


#: The stamp of every kernel in Numba's cache.
STAMP = digest(sources())


class _StampedByTheKernelSources:
    """A locator of a kernel's cache whose freshness is :data:`STAMP` (a function defined
    elsewhere is left to the next locator)."""

    def get_source_stamp(self) -> str:
        return STAMP

    @classmethod
    def from_function(cls, py_func: Any, py_file: str) -> Any:
        if Path(py_file).resolve().parent != KERNELS:
            return None
        return super().from_function(py_func, py_file)  # type: ignore[misc]


def _numba(name: str) -> Any:
    """A class of ``numba.core.caching`` (before Numba 0.61 its name began with an underscore)."""
    return getattr(caching, name, None) or getattr(caching, f"_{name}")


#: Numba's locators of a source file's cache (``NUMBA_CACHE_DIR``, the ``__pycache__`` beside it,
#: the user's cache folder), each stamped by the kernel sources.
LOCATORS = tuple(
    type(f"Kernel{name}", (_StampedByTheKernelSources, _numba(name)), {"__module__": __name__})
    for name in ("UserProvidedCacheLocator", "InTreeCacheLocator", "UserWideCacheLocator")
)


def install() -> None:
    """Put :data:`LOCATORS` first in Numba's list of cache locators (once)."""
    classes = _numba("CacheImpl")._locator_classes
    if classes[: len(LOCATORS)] != list(LOCATORS):
        classes[:0] = LOCATORS
