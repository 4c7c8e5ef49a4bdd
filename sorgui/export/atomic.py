"""Atomic file writes: a file is either the old one or the complete new one, never half of each.

Every export goes through here. The new content is written to a temporary file in the same
folder (so the final rename never crosses a file system), flushed and ``fsync``-ed, and then
moved over the target with ``os.replace``, which POSIX and Windows both perform atomically.
If anything fails on the way — the folder is read-only, the disk is full, a writer raises
half-way, a signal arrives — the temporary file is removed and the old file stays exactly as it
was; the error propagates as the ``OSError`` (or the writer's own exception) for the caller to
report. A character device or a FIFO named as the target (``-o /dev/null``) is written in
place, never replaced by a regular file; any other kind of file is refused.
"""

from __future__ import annotations

import contextlib
import errno
import os
import signal
import stat
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
    in_place = _special(target)
    folder = Path(tempfile.gettempdir()) if in_place else (target.parent if str(target.parent) else Path("."))
    # Ctrl+C or SIGTERM between creating the temporary file and the clean-up below would leave it
    # behind: the ending signals wait until the clean-up is in place.
    blocked = signal.pthread_sigmask(signal.SIG_BLOCK, _ENDING) if _MASKABLE else None
    try:
        prefix, suffix = temporary_affixes(target, folder)
        fd, name = tempfile.mkstemp(prefix=prefix, suffix=suffix, dir=folder)
        os.close(fd)
        temporary = Path(name)
        try:
            if blocked is not None:
                signal.pthread_sigmask(signal.SIG_SETMASK, blocked)
                blocked = None
            yield temporary
            if in_place:
                _copy_into(temporary, target)
                temporary.unlink()
                return
            with open(temporary, "rb+") as stream:
                stream.flush()
                os.fsync(stream.fileno())
            _keep_mode(target, temporary)
            os.replace(temporary, target)
        except BaseException:
            with contextlib.suppress(OSError):
                temporary.unlink()
            raise
    finally:
        if blocked is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, blocked)
    _fsync_directory(folder)


_ENDING = {signal.SIGTERM, signal.SIGHUP, signal.SIGINT}

RANDOM_PART = 8
"""Characters ``tempfile.mkstemp`` puts between the prefix and the suffix."""


def temporary_affixes(target: Path, folder: Path) -> tuple[str, str]:
    """The prefix and suffix of the temporary file of ``target``: ``.NAME.`` and
    ``.PID.tmpSUFFIX``, the process's id naming whose it is (:func:`remove_leftovers`) and the
    suffix kept for writers that choose the format by it. ``NAME`` is shortened so that the whole
    name fits the folder's limit (255 bytes on most file systems) when the target's own does."""
    suffix = f".{os.getpid()}.tmp{target.suffix}"
    room = _name_max(folder) - len(suffix.encode()) - RANDOM_PART - 2
    name = target.name.encode()[: max(room, 1)].decode(errors="ignore") or "x"
    return f".{name}.", suffix


def _name_max(folder: Path) -> int:
    """The longest file name ``folder`` takes, in bytes (255 where the system does not say)."""
    try:
        return int(os.pathconf(folder, "PC_NAME_MAX"))
    except (OSError, ValueError, AttributeError):
        return 255


def remove_leftovers(folder: str | Path, pid: int | None) -> None:
    """Remove the temporary files that the process ``pid`` left in ``folder`` (and in the
    temporary folder, where a device's content is prepared) when it was killed while writing:
    the targets themselves are untouched (the old files stay as they were)."""
    if pid is None:
        return
    for place in {Path(folder), Path(tempfile.gettempdir())}:
        try:
            leftovers = list(place.glob(f".*.{pid}.tmp*"))
        except OSError:
            continue
        for leftover in leftovers:
            with contextlib.suppress(OSError):
                leftover.unlink()


_MASKABLE = hasattr(signal, "pthread_sigmask")


def _special(target: Path) -> bool:
    """Whether ``target`` is a character device or a FIFO (``/dev/null``, a named pipe), which is
    written in place: renaming a regular file over it would replace the device itself. Anything
    else that is not a regular file (a folder, a block device, a socket) is refused."""
    try:
        mode = target.stat().st_mode
    except FileNotFoundError:
        return False
    if stat.S_ISREG(mode):
        return False
    if stat.S_ISCHR(mode) or stat.S_ISFIFO(mode):
        return True
    raise (
        IsADirectoryError(errno.EISDIR, "not a regular file", str(target))
        if stat.S_ISDIR(mode)
        else OSError(errno.EINVAL, "not a regular file, a character device or a pipe", str(target))
    )


def _copy_into(source: Path, target: Path) -> None:
    """The bytes of ``source`` written into the existing ``target`` (a device or a pipe)."""
    with open(source, "rb") as reading, open(target, "wb") as writing:
        while chunk := reading.read(1 << 20):
            writing.write(chunk)


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
            for chunk in [chunks] if isinstance(chunks, bytes) else chunks():
                stream.write(chunk)
            stream.flush()
            os.fsync(stream.fileno())

    return atomic_write(path, write)


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` as UTF-8 to ``path`` atomically."""
    return atomic_write_bytes(path, text.encode("utf-8"))
