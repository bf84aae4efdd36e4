"""Opening user files safely: regular files only, never a blocking open.

Every user file tuibrdf reads (a MERL ``.binary``, a preset) goes through :func:`open_regular`.
A FIFO given as a file would block ``open()`` until a writer appears (and a read until it
writes), a directory or a device is not data: so the path is checked with :func:`os.stat`
before it is opened, it is opened with ``O_NONBLOCK`` (a FIFO swapped in between the check and
the open cannot block either), and the open descriptor is checked again with :func:`os.fstat`.

The errors are :class:`OSError` with a readable ``strerror`` ("is a FIFO (named pipe), not a
regular file"), so callers that already turn ``OSError`` into one line keep working.
"""

from __future__ import annotations

import errno
import io
import os
import stat

#: what each kind of non-regular file is called in messages
_KINDS = (
    (stat.S_ISDIR, "a directory", errno.EISDIR),
    (stat.S_ISFIFO, "a FIFO (named pipe)", errno.EINVAL),
    (stat.S_ISSOCK, "a socket", errno.EINVAL),
    (stat.S_ISCHR, "a character device", errno.EINVAL),
    (stat.S_ISBLK, "a block device", errno.EINVAL),
)



class UserFileError(ValueError):
    """A user file that cannot be used: the message names the file (and line) and the
    problem, in one line.  Here, below every reader, so that the readers and the resolver
    (:mod:`.userfiles`) can all raise it without importing each other."""

def kind_of(mode: int) -> tuple[str, int]:
    """``(description, errno)`` of a non-regular file mode (``("", 0)`` for a regular file)."""
    if stat.S_ISREG(mode):
        return "", 0
    for test, text, code in _KINDS:
        if test(mode):
            return text, code
    return "not a regular file", errno.EINVAL


def not_regular(path: str, mode: int) -> OSError:
    text, code = kind_of(mode)
    return OSError(code, f"is {text}, not a regular file", path)


def describe(path: str | os.PathLike) -> str:
    """Why ``path`` cannot be read as a file, as a message fragment, or ``""`` when it is a
    readable regular file: ``"no such file"``, ``"is a directory, not a regular file"``,
    ``"permission denied"``...  Never blocks (only ``stat`` and ``access``)."""
    name = os.fspath(path)
    try:
        st = os.stat(name)
    except OSError as e:
        if e.errno == errno.ENOENT:
            return "no such file" if not os.path.islink(name) else "broken symbolic link"
        return (e.strerror or str(e)).lower()
    except ValueError:  # an embedded NUL byte
        return "invalid file name (contains a NUL byte)"
    if not stat.S_ISREG(st.st_mode):
        return f"is {kind_of(st.st_mode)[0]}, not a regular file"
    if not os.access(name, os.R_OK):
        return "permission denied"
    return ""


def open_regular(path: str | os.PathLike, max_bytes: int | None = None) -> io.BufferedReader:
    """Open ``path`` for binary reading if it is a regular file (symbolic links followed).

    Raises :class:`OSError` (``strerror`` says what the path is) for a directory, FIFO,
    socket or device, without ever blocking, and for a file larger than ``max_bytes`` (a
    preset of gigabytes is not a preset).  ``ValueError`` from a NUL byte in the name becomes
    an ``OSError`` too.
    """
    name = os.fspath(path)
    try:
        st = os.stat(name)
        if not stat.S_ISREG(st.st_mode):  # check first: never even open a FIFO or a device
            raise not_regular(name, st.st_mode)
        # O_NONBLOCK: if the path became a FIFO since the stat, open() returns at once
        fd = os.open(name, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except ValueError:
        raise OSError(errno.EINVAL, "invalid file name (contains a NUL byte)", name) from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):  # what was actually opened
            raise not_regular(name, st.st_mode)
        if max_bytes is not None and st.st_size > max_bytes:
            raise OSError(errno.EFBIG, f"too large ({st.st_size:,} bytes, at most "
                                       f"{max_bytes:,})", name)
        os.set_blocking(fd, True)  # a regular file: ordinary reads from here on
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def read_regular(path: str | os.PathLike, max_bytes: int) -> bytes:
    """The whole content of a regular file of at most ``max_bytes`` (see
    :func:`open_regular`); a file that grows past the limit while read is refused too."""
    with open_regular(path, max_bytes) as f:
        data = f.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise OSError(errno.EFBIG, f"too large (more than {max_bytes:,} bytes)", os.fspath(path))
    return data


__all__ = ["describe", "kind_of", "open_regular", "read_regular"]
