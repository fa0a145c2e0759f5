"""Files written whole or not at all: a temporary file beside the target, then renamed.

Every writer that must not leave half a file behind (an interrupted build, a full disk, an
exception in a format library) goes through :func:`write_atomically`. The temporary file
lies in the target's folder, so the rename is atomic on the one file system, and it gets
the mode of an ordinary new file (``mkstemp`` makes ``0600``).

Examples
--------
>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "note.txt"
>>> write_atomically(out, lambda tmp: pathlib.Path(tmp).write_text("hi")).read_text()
'hi'
"""

from __future__ import annotations

import os
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path

__all__ = ["new_file_mode", "write_atomically", "write_bytes"]


_UMASK = threading.Lock()  # reading the umask sets it for a moment: one thread at a time


def new_file_mode() -> int:
    """The mode an ordinary new file gets here: ``0o666`` less the process's umask."""
    with _UMASK:
        mask = os.umask(0)
        os.umask(mask)
    return 0o666 & ~mask


def write_atomically(path, write: Callable[[str], object], *, suffix: str | None = None) -> Path:
    """Call ``write(tmp)`` on a temporary file beside ``path``, then rename it to ``path``.

    Parameters
    ----------
    path : str or Path
        The file to write; its folder must exist.
    write : callable
        Writes the whole content to the file name it is given (a str).
    suffix : str, optional
        The temporary file's suffix (default: ``path``'s, for writers that pick the format
        by it).

    Returns
    -------
    Path
        ``path`` (where ``path`` is a symbolic link: the file it names, which is written and
        the link kept). On any error the temporary file is removed and ``path`` is left as it was.
    """
    path = Path(path)
    if path.is_symlink():
        # write the file the link names (a rename onto the link replaced the link itself)
        path = Path(os.path.realpath(path))
    if path.is_dir():  # os.replace would name the temporary file
        raise IsADirectoryError(21, f"cannot write {path}: is a folder, not a file")
    folder = path.parent if str(path.parent) else Path(".")
    suffix = path.suffix if suffix is None else suffix
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=folder)
    except OSError as exc:  # name the file asked for, not the temporary one
        raise type(exc)(exc.errno, f"cannot write {path}: {exc.strerror}") from None
    os.close(fd)
    try:
        write(tmp)
        os.chmod(tmp, new_file_mode())
        os.replace(tmp, path)
    finally:
        Path(tmp).unlink(missing_ok=True)  # gone after the rename; left only by a failure
    return path


def write_bytes(path, data: bytes) -> Path:
    """:func:`write_atomically` of ``data``."""
    return write_atomically(path, lambda tmp: Path(tmp).write_bytes(data))
