"""Atomic file writes: a file is either the old one or the complete new one, never half of each.

Every export goes through here. The new content is written to a temporary file in the same
folder (so the final rename never crosses a file system), flushed and ``fsync``-ed, and then
moved over the target with ``os.replace``, which POSIX and Windows both perform atomically.
If anything fails on the way — the folder is read-only, the disk is full, a writer raises
half-way — the temporary file is removed and the old file stays exactly as it was; the error
propagates as the ``OSError`` (or the writer's own exception) for the caller to report.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path


def _fsync_directory(folder: Path) -> None:
    """Make the rename itself durable (a no-op where folders cannot be opened, e.g. Windows)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """A temporary path beside ``path`` for a writer that wants a file name (pyvista, VTK).

    On a normal exit of the ``with`` block the temporary file is ``fsync``-ed and renamed to
    ``path``; on an exception it is deleted and ``path`` is untouched. The temporary name keeps
    the suffix of ``path``, since some writers choose the format by it.
    """
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    fd, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=f".tmp{target.suffix}", dir=folder)
    os.close(fd)
    temporary = Path(name)
    try:
        yield temporary
        with open(temporary, "rb+") as stream:
            stream.flush()
            os.fsync(stream.fileno())
        _keep_mode(target, temporary)
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            temporary.unlink()
        raise
    _fsync_directory(folder)


def _keep_mode(target: Path, temporary: Path) -> None:
    """Give the new file the old file's permissions, or the usual ones for a new file."""
    try:
        mode = target.stat().st_mode & 0o7777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    os.chmod(temporary, mode)


def atomic_write(path: str | Path, write: Callable[[Path], None]) -> Path:
    """Call ``write(temporary_path)`` and move the result to ``path`` atomically."""
    with atomic_path(path) as temporary:
        write(temporary)
    return Path(path)


def atomic_write_bytes(path: str | Path, chunks: bytes | Callable[[], Iterator[bytes]]) -> Path:
    """Write ``chunks`` (bytes, or a function yielding pieces) to ``path`` atomically.

    A generator that raises half-way leaves ``path`` as it was.
    """
    def write(temporary: Path) -> None:
        with open(temporary, "wb") as stream:
            for chunk in ([chunks] if isinstance(chunks, bytes) else chunks()):
                stream.write(chunk)
            stream.flush()
            os.fsync(stream.fileno())

    return atomic_write(path, write)


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` as UTF-8 to ``path`` atomically."""
    return atomic_write_bytes(path, text.encode("utf-8"))
