"""Safe HDF5 files: output paths, checkpoints beside them, locks, atomic writes, checksums.

Shared by run files (:mod:`mcsim.store.runfile`) and sweep files (:mod:`mcsim.store.sweepfile`):
a file is written to a temporary beside its path and linked into place only when complete,
under ``<name>.lock``, with a SHA-256 checksum over every dataset and attribute that every
reader verifies; its large datasets are compressed (:func:`storage`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import glob
import hashlib
import os
import socket
import tempfile
from pathlib import Path

import numpy as np

from mcsim.model.errors import RunFileError
from mcsim.store.outputs import check_replaceable


def file_path(value, field: str = "path") -> Path:
    """``value`` as a Path: a non-empty ``str`` or path-like without NUL bytes, else a
    RunFileError naming ``field`` (an API caller's ``read_run(5)`` or ``out=""``)."""
    if not isinstance(value, str | os.PathLike):
        raise RunFileError(f"{field} must be a file path (str or pathlib.Path), got {value!r}")
    text = os.fspath(value)
    if not isinstance(text, str) or not text or "\0" in text:
        raise RunFileError(f"{field} = {value!r} is not a valid file path")
    return Path(text)


def checkpoint_path(path: str | Path) -> Path:
    """Where a run writing ``path`` keeps its checkpoints: ``<stem>.partial<suffix>`` beside it."""
    path = Path(path)
    return path.with_name(f"{path.stem}.partial{path.suffix}")


def check_output_path(path: str | Path, overwrite: bool = False, resume: bool = False) -> Path:
    """Fail early (before any work) if ``path`` cannot receive this run.

    An existing file at ``path``, or an unfinished run's checkpoint beside it, is
    replaced only with ``overwrite``. With ``resume`` both pass: the caller continues
    the checkpoint, or checks that the file holds the run asked for (see
    :func:`first_difference`), in which case there is nothing to do.
    """
    path = file_path(path, "out")
    if check_replaceable(path) and path.is_symlink():  # the rule of every output: follow it
        path = Path(os.path.realpath(path))
    folder = path.parent
    if not folder.is_dir():
        raise RunFileError(f"{path}: output folder {folder} does not exist")
    if not os.access(folder, os.W_OK):
        raise RunFileError(f"{path}: output folder {folder} is not writable")
    if overwrite or resume:
        return path
    if path.exists():
        raise RunFileError(f"{path}: file exists (pass --overwrite / overwrite=True to replace it)")
    if checkpoint_path(path).exists():
        raise RunFileError(
            f"{path}: an unfinished run's checkpoint {checkpoint_path(path).name} is beside it "
            "(pass --resume to continue it, or --overwrite to start again)"
        )
    return path


def first_difference(recorded: dict, asked: dict) -> str | None:
    """The first of the ``asked`` inputs whose value differs from the ``recorded`` one, as
    ``"name (file: a, asked: b)"``; None when all are equal.

    Dataclasses (a surface, a material) and dicts are compared field by field, so the
    innermost field that differs is named (``"surface sigma"``).
    """
    for name in [*asked, *(k for k in recorded if k not in asked)]:
        old, value = recorded.get(name), asked.get(name)
        if old == value:
            continue
        if dataclasses.is_dataclass(old) and type(old) is type(value):
            old, value = (
                {f.name: getattr(x, f.name) for f in dataclasses.fields(x)} for x in (old, value)
            )
        inner = isinstance(old, dict) and isinstance(value, dict) and first_difference(old, value)
        if inner:
            return f"{name} {inner}"
        return f"{name} (file: {_short(old)}, asked: {_short(value)})"
    return None


def _short(value) -> str:
    """A value on one short line, for messages."""
    text = " ".join(repr(value).split())
    return text if len(text) <= 60 else text[:57] + "..."


@contextlib.contextmanager
def lock(path: str | Path):
    """Hold ``<path>.lock`` while writing ``path``; refuse if another process holds it.

    The lock is an ``flock`` on that file, which the system releases when its process
    ends, however it ends: a lock file left by a killed process is simply free. The
    holder removes the file before releasing it; a process that locked the file just
    as it was removed sees that the path no longer names its file, and tries again.
    """
    import fcntl

    lock_path = Path(f"{path}.lock")
    while True:
        fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            owner = os.read(fd, 200).decode(errors="replace").split()
            os.close(fd)
            raise RunFileError(
                f"{path}: another mcsim process ({' pid '.join(owner) or 'starting'}) is writing it "
                f"(lock file {lock_path.name})"
            ) from None
        try:
            same = os.path.samestat(os.fstat(fd), os.stat(lock_path))
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)  # removed by its previous holder while we waited: take the new one
    try:
        os.ftruncate(fd, 0)
        os.write(fd, f"{socket.gethostname()} {os.getpid()}".encode())
        for name in (Path(path).name, checkpoint_path(path).name):
            for stale in Path(path).parent.glob(f".{glob.escape(name)}.*.tmp"):
                stale.unlink(missing_ok=True)  # left by a killed writer; we hold the lock
        yield
    finally:
        lock_path.unlink(missing_ok=True)  # ours: we hold its flock
        os.close(fd)


#: Datasets of more bytes than this are stored chunked, byte-shuffled and gzip-compressed
#: (HDF5's built-in filters: any HDF5 reader, plain h5py and netCDF included, reads them);
#: smaller ones contiguous, where compression would save nothing worth its chunk index.
COMPRESS_ABOVE = 16 * 1024

#: gzip (deflate) level of compressed datasets: h5py's default (level 9 saves under 1 % more
#: of a run file's sums, in three times the writing time).
GZIP_LEVEL = 4


def storage(data: np.ndarray) -> dict:
    """Options of ``h5py.Group.create_dataset`` for ``data``: chunked, shuffled and
    gzip-compressed above :data:`COMPRESS_ABOVE` bytes, else none (contiguous)."""
    if data.nbytes <= COMPRESS_ABOVE:
        return {}
    return {"chunks": True, "compression": "gzip", "compression_opts": GZIP_LEVEL, "shuffle": True}


def checksum(f) -> str:
    """SHA-256 over every dataset (name, shape, dtype, bytes) and every attribute but
    the checksum itself, in name order."""
    digest = hashlib.sha256()
    names: list[str] = [""]
    f.visit(names.append)
    for name in sorted(names):
        obj = f[name] if name else f
        for key in sorted(k for k in obj.attrs if k != "checksum"):
            digest.update(f"{name}@{key}={np.asarray(obj.attrs[key]).tolist()!r}|".encode())
        if hasattr(obj, "shape"):
            data = np.ascontiguousarray(obj[()])
            digest.update(f"{name}|{data.shape}|{data.dtype.str}|".encode())
            digest.update(data.tobytes())
    return digest.hexdigest()


def atomic_write(path: Path, fill) -> None:
    """Build the file through ``fill(h5file)`` in memory, then write it to a temporary
    file and rename that onto ``path``.

    HDF5 never writes to disk: a full disk or a size limit fails in a plain ``write``
    (one clean error, the temporary removed), never inside the HDF5 library.
    """
    import h5py

    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with h5py.File(tmp, "w", driver="core", backing_store=False) as f:
            fill(f)
            f.attrs["checksum"] = checksum(f)
            f.flush()
            image = memoryview(f.id.get_file_image())
        umask = os.umask(0)
        os.umask(umask)
        os.fchmod(fd, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
        while image:
            image = image[os.write(fd, image) :]
        os.fsync(fd)
        os.close(fd)
        fd = -1
        os.replace(tmp, path)
    except OSError as err:
        Path(tmp).unlink(missing_ok=True)
        raise RunFileError(f"{path}: cannot write the run file ({_reason(err)})") from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    finally:
        if fd >= 0:
            os.close(fd)


def _reason(err: Exception) -> str:
    """The system's words for a failed write, on one line."""
    return " ".join((getattr(err, "strerror", None) or str(err)).split())
