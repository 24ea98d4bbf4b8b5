"""The files a user gives acphys to read (scenarios, traces, DAT files): regular files only,
read with a bound, and named in one-line messages.

A FIFO blocks its reader until something writes to it and a device such as ``/dev/zero`` never
ends, so an input that is not a regular file is refused before it is read, and what is read
whole is read up to a limit. Every refusal is an :class:`InputError`.
"""

from __future__ import annotations

import os
import stat
from typing import BinaryIO

#: What the file types other than a regular file are called in messages.
_FILE_TYPES = {
    stat.S_IFDIR: "a directory",
    stat.S_IFCHR: "a character device",
    stat.S_IFBLK: "a block device",
    stat.S_IFIFO: "a FIFO",
    stat.S_IFSOCK: "a socket",
}


def one_line(text: str) -> str:
    """``text`` with its control and separator characters (a newline in a key, a NUL in a path)
    escaped as Python writes them (``\\n``, ``\\x00``), so that a message stays one line."""
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else repr(char)[1:-1] for char in text)


class OptionError(ValueError):
    """A command-line option's value acphys cannot use; ``str()`` is one line naming the option."""


def split_names(text: str | None, option: str, noun: str = "name") -> list[str] | None:
    """A comma-separated option (``--bodies a,b``) as a list of names; None for None. An option
    that names nothing (``--bodies ,``) is an :class:`OptionError` asking for one ``noun``."""
    if text is None:
        return None
    names = [name.strip() for name in text.split(",") if name.strip()]
    if not names:
        raise OptionError(f"{option} needs at least one {noun}, like {option} a,b")
    return names


class InputError(OSError):
    """An input file acphys refuses; ``str()`` is one line: the path, then the problem.

    An ``OSError`` (``filename`` is the path, ``strerror`` the problem), so code that reports
    the errors of ``open`` reports these too; ``errno`` is that of the failed system call, so a
    caller can still tell a missing file (``ENOENT``) from one it may not read.
    """

    def __init__(self, path: str | os.PathLike[str], problem: str, errno: int | None = None) -> None:
        super().__init__(problem)
        self.filename = os.fspath(path)
        self.strerror = problem
        #: The ``errno`` of the failed call behind the refusal (``ENOENT`` for a missing file), if any.
        self.errno = errno

    def __str__(self) -> str:
        return f"{one_line(self.filename)}: {self.strerror}"


def _problem(error: OSError) -> str:
    """An ``OSError``'s reason in the lower case of acphys's messages ("permission denied")."""
    if isinstance(error, FileNotFoundError):
        return "no such file"
    reason = error.strerror or str(error)
    return reason[:1].lower() + reason[1:]


def _refuse_special(path: str | os.PathLike[str], mode: int) -> None:
    if not stat.S_ISREG(mode):
        raise InputError(path, f"not a regular file ({_FILE_TYPES.get(stat.S_IFMT(mode), 'a special file')})")


def check_regular(path: str | os.PathLike[str]) -> None:
    """Refuse (:class:`InputError`) a path that holds a NUL byte, does not exist, or is not a
    regular file (a directory, a FIFO, a device), without opening it; for readers that open
    the file themselves. :func:`open_regular` also closes the gap between the check and the open.
    """
    try:
        mode = os.stat(path).st_mode
    except ValueError:  # os.stat's "embedded null byte"
        raise InputError(path, "a path cannot hold a NUL byte") from None
    except OSError as error:
        raise InputError(path, _problem(error), error.errno) from None
    _refuse_special(path, mode)


def open_regular(path: str | os.PathLike[str]) -> BinaryIO:
    """Open a regular file for reading in binary, or refuse it as :func:`check_regular` does.

    The file is opened without blocking and checked once open (``fstat``), so that a FIFO put
    in its place is refused rather than waited on.
    """
    check_regular(path)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY)
    except OSError as error:
        raise InputError(path, _problem(error), error.errno) from None
    try:
        _refuse_special(path, os.fstat(fd).st_mode)
    except InputError:
        os.close(fd)
        raise
    return os.fdopen(fd, "rb")


def read_limited(path: str | os.PathLike[str], limit: int, what: str) -> bytes:
    """The bytes of the regular file ``path``; one of more than ``limit`` bytes is refused
    (reading at most ``limit + 1``), the message naming the limit as ``what`` ("the scenario
    size limit")."""
    with open_regular(path) as file:
        try:
            data = file.read(limit + 1)
        except OSError as error:
            raise InputError(path, _problem(error), error.errno) from None
    if len(data) > limit:
        raise InputError(path, f"larger than {what} ({limit:,} bytes)")
    return data


__all__ = ["InputError", "check_regular", "one_line", "open_regular", "read_limited"]
