# SPDX-License-Identifier: LGPL-2.1-or-later
"""Files the workbench writes are never lost: output folders are checked before any work, and
every file is written atomically (a temporary file in the same folder, flushed and synced, then
renamed over the target), so a failed or interrupted write leaves the previous file intact.
The same rules as the solver's own writer (NativeSolver/include/lightsolver/output_file.hpp).
No FreeCAD import: usable (and tested) anywhere."""
from __future__ import annotations

import itertools
import os
import shutil
from typing import Callable, IO

_counter = itertools.count()


def _temporary(path: str) -> str:
    """A name next to ``path`` for a temporary file (hidden, ending in ``.tmp``)."""
    folder, name = os.path.split(os.path.abspath(path))
    return os.path.join(folder, f".{name}.{os.getpid()}.{next(_counter)}.tmp")


def _open_temporary(path: str) -> tuple:
    """(file descriptor, name) of a new, exclusive temporary file next to ``path``; mode 0666
    minus the umask like any new file, or the mode of the file it will replace."""
    folder = os.path.dirname(os.path.abspath(path))
    for _ in range(100):
        tmp = _temporary(path)
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0),
                         0o666)
        except FileExistsError:
            continue
        except OSError as exc:
            raise OSError(f"'{path}': cannot create files in '{folder}' "
                          f"({exc.strerror or exc})") from exc
        try:
            os.chmod(tmp, os.stat(path).st_mode & 0o7777)
        except FileNotFoundError:
            pass
        return fd, tmp
    raise FileExistsError(f"'{path}': cannot create a temporary file in '{folder}'")


def _check_target(path: str) -> str:
    """The file really replaced (a symbolic link's target); refuses folders, devices and
    missing folders with an OSError whose text names the path and the reason."""
    real = os.path.realpath(path) if os.path.islink(path) else path
    if os.path.isdir(real) or not os.path.basename(real):
        raise IsADirectoryError(f"'{path}': it is a folder")
    if os.path.exists(real) and not os.path.isfile(real):
        raise OSError(f"'{path}': it exists and is not a regular file")
    folder = os.path.dirname(os.path.abspath(real))
    if not os.path.exists(folder):
        raise FileNotFoundError(f"'{path}': the folder '{folder}' does not exist")
    if not os.path.isdir(folder):
        raise NotADirectoryError(f"'{path}': '{folder}' is not a folder")
    return real


def _write_with(path: str, fill: Callable[[IO[bytes]], None]) -> None:
    try:
        real = _check_target(path)
        fd, tmp = _open_temporary(real)
    except OSError as exc:
        raise OSError(f"cannot write {exc}") from exc
    try:
        with os.fdopen(fd, "wb") as stream:
            fill(stream)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(tmp, real)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    try:  # make the rename itself durable; some file systems refuse fsync on folders
        dir_fd = os.open(os.path.dirname(os.path.abspath(real)), os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)
    except OSError:
        pass


def write_bytes(path: str, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically; the previous file survives any failure."""
    _write_with(path, lambda stream: stream.write(data))


def write_text(path: str, text: str) -> None:
    """Write UTF-8 ``text`` to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def copy_file(source: str, path: str) -> None:
    """Copy ``source`` to ``path`` atomically."""
    with open(source, "rb") as src:
        _write_with(path, lambda stream: shutil.copyfileobj(src, stream))


def check_writable(path: str, what: str = "file") -> None:
    """Before any work: ``path`` can be written (its folder exists and accepts new files - tried
    by creating and removing a temporary file, so read-only mounts are seen as they are - and
    it is not a folder). Raises OSError naming ``what`` and the path."""
    try:
        real = _check_target(path)
        fd, tmp = _open_temporary(real)
    except OSError as exc:
        raise OSError(f"cannot write the {what} {exc}") from exc
    os.close(fd)
    os.unlink(tmp)


def check_folder(directory: str, what: str = "output folder") -> None:
    """Create ``directory`` if needed and check that files can be written in it."""
    try:
        os.makedirs(directory, exist_ok=True)
    except OSError as exc:
        raise OSError(f"cannot create the {what} '{directory}': {exc}") from exc
    check_writable(os.path.join(directory, ".lighting-write-test"), what)
