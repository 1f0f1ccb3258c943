"""Crash-safe file writing: atomic replace, fsync, and a fault-injection hook for tests.

Atomic write = write a temporary file in the *same directory* (a rename is atomic only within one
file system), flush, ``fsync`` it, ``os.replace`` it over the target, ``fsync`` the directory (so
the rename itself survives a power cut). A process killed at any moment leaves either the old
file or the new one, never a mix.

Fault injection: ``ROTORLANDING_FAULT=point`` or ``point:N`` (N: the chunk index, for the
coast-down's per-chunk points) makes :func:`fault` kill the process with SIGKILL when the write
path passes that named point. Only tests and ``benchmarks/fault_injection.py`` set it.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

FAULT_ENV = "ROTORLANDING_FAULT"


class WriteError(Exception):
    """A result file could not be written (disk full, file too large, I/O error, ...).

    The CLI prints ``str(err)`` on one line and exits with :data:`rotorlanding.cli.EXIT_IO`."""

    def __init__(self, path, exc: BaseException):
        self.path = str(path)
        self.exc = exc
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        super().__init__(f"cannot write {self.path}: {reason}".replace("\n", " "))


def fault(point: str, chunk: int | None = None) -> None:
    """Kill this process (SIGKILL: no cleanup, no flush, like a crash) if the environment asks for
    ``point`` (and ``chunk``); a no-op otherwise."""
    want = os.environ.get(FAULT_ENV)
    if not want:
        return
    name, _, n = want.partition(":")
    if name == point and (not n or chunk is None or int(n) == chunk):
        os.kill(os.getpid(), signal.SIGKILL)


def fsync_path(path) -> None:
    """fsync a file (its data and size) by name."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def fsync_dir(path) -> None:
    """fsync a directory so renames in it are durable (not possible on every platform)."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:  # some file systems refuse fsync on a directory; the rename is still atomic
        pass
    finally:
        os.close(fd)


def tmp_name(path: Path, tag: str = "tmp") -> Path:
    """A temporary name beside ``path`` (same directory, hence same file system), hidden."""
    return path.with_name(f".{path.name}.{tag}")


def atomic_write_text(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (temp name, flush, fsync, os.replace, fsync dir)."""
    path = Path(path)
    tmp = tmp_name(path)
    try:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        fault("summary-json")
        os.replace(tmp, path)
    except OSError:
        _unlink(tmp)
        raise
    fsync_dir(path.parent)


def copy_file(src, dst, *, point: str | None = None, chunk: int | None = None) -> None:
    """Copy ``src`` to ``dst`` and fsync it (``point``: a fault point halfway through the copy)."""
    size = os.path.getsize(src)
    done = 0
    try:
        with open(src, "rb") as fi, open(dst, "wb") as fo:
            while True:
                buf = fi.read(1 << 20)
                if not buf:
                    break
                fo.write(buf)
                done += len(buf)
                if point and done >= size // 2:
                    fo.flush()
                    fault(point, chunk)
                    point = None
            fo.flush()
            os.fsync(fo.fileno())
    except OSError:
        _unlink(dst)
        raise


def _unlink(path) -> None:
    try:
        os.unlink(path)
    except OSError:
        pass


def unlink_quietly(path) -> None:
    _unlink(path)
