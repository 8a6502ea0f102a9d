"""The one rule for every file a command writes (run and sweep files too: ``simulate``,
``sweep``, through :func:`mcsim.store.files.check_output_path`).

* An existing file is replaced only with ``overwrite`` (``--overwrite``).
* A command never writes onto one of its own inputs, even with ``overwrite``
  (same file: :func:`os.path.samefile`, so symbolic and hard links count too).
* Only regular files are ever replaced: a folder, a device, a pipe, a socket or a
  broken symbolic link is refused, even with ``overwrite``. A symbolic link to a
  regular file is followed: its target is replaced and the link kept.
* Files are written under a temporary name in the destination folder and renamed
  into place when complete (:func:`write_atomic`): the path holds the old file or
  the new one, never half a file, and the temporary is removed on any error.
"""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

from mcsim.model.errors import MCSimError


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISFIFO(mode):
        return "a pipe"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def check_replaceable(path: Path) -> bool:
    """Whether ``path`` exists; raise unless it is absent or a regular file (or a symbolic
    link to one), whatever ``overwrite`` says (module docstring)."""
    if not os.path.lexists(path):
        return False
    try:
        mode = os.stat(path).st_mode  # follows a symbolic link to its target
    except FileNotFoundError:
        raise MCSimError(f"{path}: is a broken symbolic link: not replaced") from None
    except OSError as err:
        raise MCSimError(f"{path}: cannot check it ({err.strerror})") from None
    if not stat.S_ISREG(mode):
        raise MCSimError(f"{path}: is {_kind(mode)}: mcsim replaces only regular files")
    return True


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist (yet)
        return os.path.realpath(a) == os.path.realpath(b)


def check_output(
    path: str | Path, *, inputs: Iterable[str | Path] = (), overwrite: bool = False
) -> Path:
    """Refuse a path this command must not write (module docstring); return it.

    Parameters
    ----------
    path : path-like
        The file to be written.
    inputs : iterable of path-like
        The command's input files: never written, even with ``overwrite``.
    overwrite : bool
        Allow replacing an existing regular file.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    MCSimError
        One line naming the path and the reason.
    """
    path = Path(path)
    for source in inputs:
        if _same_file(path, Path(source)):
            raise MCSimError(f"{path}: is an input of this command ({source}): write elsewhere")
    if check_replaceable(path) and not overwrite:
        raise MCSimError(f"{path}: file exists (pass --overwrite to replace it)")
    if not path.parent.is_dir():
        raise MCSimError(f"{path}: folder {path.parent} does not exist")
    return path


def write_atomic(
    path: str | Path,
    write: Callable[[Path], object],
    *,
    inputs: Iterable[str | Path] = (),
    overwrite: bool = False,
) -> Path:
    """Write a file through ``write(temporary_path)``, then move it onto ``path``.

    The temporary file (``.<name>.<random>.tmp``) sits in the destination folder, so
    the final rename is atomic; it is removed on any error or interruption. Without
    ``overwrite`` the file is linked into place, which fails if ``path`` appeared in
    the meantime (no file is ever replaced without ``overwrite``).

    Parameters
    ----------
    path : path-like
        Destination; checked by :func:`check_output` (a symbolic link to a regular
        file is followed and its target replaced).
    write : callable
        Writes the complete content to the path it is given.
    inputs, overwrite
        As in :func:`check_output`.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    MCSimError
        A refused path, or a failed write (one line, with the system's reason).
    """
    path = check_output(path, inputs=inputs, overwrite=overwrite)
    target = Path(os.path.realpath(path)) if path.is_symlink() else path
    try:
        fd, name = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as err:
        raise MCSimError(f"{path}: cannot write it ({err.strerror or err})") from None
    os.close(fd)
    tmp = Path(name)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
        write(tmp)
        with open(tmp, "rb") as f:
            os.fsync(f.fileno())
        check_output(path, inputs=inputs, overwrite=overwrite)  # still allowed?
        if overwrite:
            os.replace(tmp, target)
        else:
            _link_new(tmp, target)
    except OSError as err:
        raise MCSimError(f"{path}: cannot write it ({err.strerror or err})") from None
    finally:
        tmp.unlink(missing_ok=True)
    return path


def _link_new(tmp: Path, target: Path) -> None:
    """Put ``tmp`` at ``target`` only if nothing is there (atomically where links work)."""
    try:
        os.link(tmp, target)
    except FileExistsError:
        raise MCSimError(f"{target}: file exists (pass --overwrite to replace it)") from None
    except OSError as err:
        if err.errno not in (errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EMLINK):
            raise
        os.replace(tmp, target)  # no hard links here: checked just above instead
