"""Crash-safe file writing: atomic replace, fsync, and a fault-injection hook for tests.

Atomic write = write a temporary file in the *same directory* (a rename is atomic only within one
file system), flush, ``fsync`` it, ``os.replace`` it over the target, ``fsync`` the directory (so
the rename itself survives a power cut). A process killed at any moment leaves either the old
file or the new one, never a mix.

HDF5 and full disks: when a write fails inside the HDF5 library (disk full, file too large, I/O
error), the file object is left half closed and closing it, freeing it or leaving the interpreter
makes the library crash (segfault). Two defences: (1) space is reserved with ``posix_fallocate``
*before* HDF5 writes (:func:`reserve`, :func:`new_h5`), so a full disk shows up as a clean
``OSError`` in plain Python code and HDF5 writes land in blocks already allocated (the library
cuts the file back to its real end when it closes it); (2) should HDF5 still fail, the file object
is kept alive (:func:`poison`) and the CLI leaves through ``os._exit`` after its one-line message.

Fault injection: ``ROTORLANDING_FAULT=point`` or ``point:N`` (N: the chunk index, for the
coast-down's per-chunk points) makes :func:`fault` kill the process with SIGKILL when the write
path passes that named point. Only tests and ``benchmarks/fault_injection.py`` set it.
"""

from __future__ import annotations

import errno
import itertools
import os
import signal
import sys
from pathlib import Path

FAULT_ENV = "ROTORLANDING_FAULT"


class WriteError(Exception):
    """A result file could not be written (disk full, file too large, I/O error, ...).

    The CLI prints ``str(err)`` on one line and exits with :data:`rotorlanding.cli.EXIT_IO`."""

    def __init__(self, path, exc: BaseException, hint: str = ""):
        self.path = str(path)
        self.exc = exc
        self.hint = hint
        if isinstance(exc, OSError) and exc.errno:  # "No space left on device", not HDF5's page
            reason = os.strerror(exc.errno)
        else:
            reason = (str(exc).splitlines() or [type(exc).__name__])[0]
        super().__init__(f"cannot write {self.path}: {reason}{'; ' + hint if hint else ''}".replace("\n", " "))


def fault(point: str, chunk: int | None = None) -> None:
    """Kill this process (SIGKILL: no cleanup, no flush, like a crash) if the environment asks for
    ``point`` (and ``chunk``); a no-op otherwise."""
    want = os.environ.get(FAULT_ENV)
    if not want:
        return
    name, _, n = want.partition(":")
    if name == point and (not n or chunk is None or int(n) == chunk):
        os.kill(os.getpid(), signal.SIGKILL)


_POISONED: list = []
_image_ids = itertools.count()


def poison(obj) -> None:
    """Keep an HDF5 object whose write failed alive: freeing or closing it can crash the library."""
    _POISONED.append(obj)


def poisoned() -> bool:
    """True if an HDF5 write failed in this process (exit with os._exit, see the module doc)."""
    return bool(_POISONED)


def hard_exit(code: int) -> None:
    """Flush Python's streams and leave without the HDF5 library's shutdown (see the module doc)."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)


class h5_guard:
    """``with h5_guard(h5, path):`` closes an HDF5 file opened for writing; if a write or the close
    fails inside the library (OSError / RuntimeError from h5py), the file object is kept alive
    instead (closing it again would crash the library: safeio.poison) and a WriteError naming
    ``path`` is raised."""

    def __init__(self, h5, path):
        self.h5, self.path = h5, path

    def __enter__(self):
        return self.h5

    def __exit__(self, typ, exc, tb):
        if exc is None:
            try:
                self.h5.close()
            except (OSError, RuntimeError) as err:
                poison(self.h5)
                raise WriteError(self.path, err) from None
            return False
        if isinstance(exc, (OSError, RuntimeError)) and not isinstance(exc, WriteError):
            # the traceback holds the frames whose datasets and groups are still open: freeing
            # them would flush into the failed file as well
            poison((self.h5, exc, tb))
            raise WriteError(self.path, exc) from None
        self.h5.close()
        return False


def reserve(path, nbytes: int) -> None:
    """Allocate ``nbytes`` of disk beyond the end of ``path`` (before HDF5 opens it), so a full
    disk or a file-size limit fails here, cleanly, with an OSError (ENOSPC, EFBIG). HDF5 ignores
    bytes past its end-of-allocation and truncates them when it closes the file. A file system
    without fallocate is skipped (glibc emulates it elsewhere)."""
    if nbytes <= 0 or not hasattr(os, "posix_fallocate"):
        return
    fd = os.open(path, os.O_WRONLY)
    try:
        os.posix_fallocate(fd, os.fstat(fd).st_size, int(nbytes))
    except OSError as exc:
        if exc.errno not in (errno.EOPNOTSUPP, errno.EINVAL, errno.ENOSYS):
            raise
    finally:
        os.close(fd)


def new_h5(path, reserve_bytes: int, **create):
    """A new, empty HDF5 file at ``path`` opened for writing, with ``reserve_bytes`` of disk
    reserved. The empty file is built in memory and written with plain I/O (h5py's "w" mode would
    truncate a reservation); ``create``: file-creation keywords of h5py.File (fs_strategy, ...)."""
    import h5py

    with h5py.File(f"rotorlanding-image-{os.getpid()}-{next(_image_ids)}", "w", driver="core",
                   backing_store=False, **create) as mem:
        mem.flush()
        image = mem.id.get_file_image()
    try:
        with open(path, "wb") as fh:
            fh.write(image)
        reserve(path, reserve_bytes)
    except OSError:
        _unlink(path)
        raise
    return h5py.File(path, "a")


def check_out_dir(out, option: str = "--out") -> Path:
    """Validate an output folder before any work is done: an existing non-folder (a regular
    file, /dev/null), a folder that cannot be created or written to is bad input (InputError,
    exit 2); a full disk found by the probe is a WriteError. Creates the folder."""
    from .errors import InputError

    if not str(out).strip():
        # '' is the current folder to Path: a run would write (and first clear a results.h5) there
        raise InputError(option, repr(str(out)), "must name a folder (results go into a folder)")
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(option, str(out), "exists and is not a folder (results go into a folder)")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(option, str(out), f"cannot be created: {exc.strerror or exc}") from None
    _probe_writable(out, option, str(out), "is not writable")
    return out


def check_out_file(path, option: str = "--out") -> Path:
    """Validate an output file before any work is done: a name in an existing folder that can be
    written to, not a folder itself (InputError, exit 2); a full disk found by the probe is a
    WriteError. Creates nothing."""
    from .errors import InputError

    if not str(path).strip():
        raise InputError(option, repr(str(path)), "must name a file")
    path = Path(path)
    if path.is_dir():
        raise InputError(option, str(path), "is a folder; give a file name")
    folder = path.parent
    if not folder.is_dir():
        raise InputError(option, str(path), f"its folder {folder} does not exist")
    _probe_writable(folder, option, str(path), f"its folder {folder} is not writable")
    return path


def _probe_writable(folder: Path, option: str, shown: str, what: str) -> None:
    """Write and remove one byte in ``folder``: a folder the user cannot write to is bad input
    (InputError naming ``option`` = ``shown``, "``what``: reason"); a full disk is a WriteError."""
    from .errors import InputError

    probe = folder / f".rotorlanding-probe-{os.getpid()}"
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            os.write(fd, b"x")
        finally:
            os.close(fd)
    except OSError as exc:
        _unlink(probe)
        if exc.errno in (errno.EACCES, errno.EPERM, errno.EROFS, errno.ENOTDIR, errno.EISDIR, errno.ENOENT):
            raise InputError(option, shown, f"{what}: {exc.strerror}") from None
        raise WriteError(folder, exc) from None
    _unlink(probe)


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


def write_atomically(path, write, *, tag: str = "tmp", point: str | None = None) -> Path:
    """The one write-then-rename of the project: ``write(tmp)`` fills a temporary file beside
    ``path`` (:func:`tmp_name`), which is fsynced and renamed onto ``path``, so a kill or a full
    disk leaves the previous file or the new one, never a mix; on any failure the temporary is
    removed. ``point``: a fault point between the fsync and the rename (kill tests)."""
    path = Path(path)
    tmp = tmp_name(path, tag)
    try:
        write(tmp)
        fsync_path(tmp)
        if point:
            fault(point)
        os.replace(tmp, path)
    except BaseException:
        _unlink(tmp)
        raise
    fsync_dir(path.parent)
    return path


def atomic_write_text(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (:func:`write_atomically`)."""
    write_atomically(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"), point="summary-json")


def save_figure(fig, path, **savefig_kw) -> Path:
    """Save a matplotlib figure atomically (:func:`write_atomically`), its format from ``path``'s
    suffix: a kill or a full disk leaves the previous picture or the new one, never a truncated PNG."""
    fmt = Path(path).suffix.lstrip(".") or "png"
    return write_atomically(path, lambda tmp: fig.savefig(tmp, format=fmt, **savefig_kw), tag="part", point="figure")


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
