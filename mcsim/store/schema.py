"""What the attributes and datasets of mcsim's HDF5 files must hold, checked on reading.

A file that another tool (or a hand) rewrote, its checksum recomputed, passes the
checksum yet may hold anything: every reader checks each attribute and dataset it uses
against its kind here before using it, and refuses with one line naming the file, the
field and what was expected (a :class:`~mcsim.model.errors.RunFileError`).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from mcsim.model.errors import RunFileError

#: Kinds of attribute value: what the message calls each.
KINDS = {
    "integer": "an integer",
    "number": "a number",
    "boolean": "a boolean",
    "text": "text",
    "digits": "a non-negative integer written as text",
    "JSON object": "a JSON object",
    "JSON list": "a JSON list",
}

#: Kinds of dataset value (NumPy dtype kinds): what the message calls each.
DTYPES = {"f": "floating-point numbers", "iu": "integers", "S": "fixed-length text"}


def shown(value) -> str:
    """A short one-line repr of a value read from a file, for messages."""
    text = repr(value.tolist() if hasattr(value, "tolist") else value)
    return text if len(text) <= 40 else text[:40] + "..."


def refuse(path: Path, what: str, message: str) -> RunFileError:
    """The error for a damaged file: ``PATH: damaged WHAT: MESSAGE``."""
    return RunFileError(f"{path}: damaged {what}: {message}")


def attribute(path: Path, obj, name: str, kind: str, what: str):
    """Attribute ``name`` of the HDF5 object ``obj`` as a Python value of ``kind``.

    Parameters
    ----------
    path : Path
        The file, for messages.
    obj : h5py.Group or h5py.Dataset
        Holder of the attribute.
    name : str
        Attribute name.
    kind : str
        One of :data:`KINDS`.
    what : str
        The file kind, for messages ("run file", "sweep file").

    Returns
    -------
    int, float, bool, str, dict or list
        The value (a JSON kind: parsed).

    Raises
    ------
    RunFileError
        The attribute is missing or not of ``kind`` (one line naming it).
    """
    field = f"{obj.name.strip('/')}@{name}" if obj.name != "/" else name
    if name not in obj.attrs:
        raise refuse(path, what, f"attribute {field} is missing")
    value = obj.attrs[name]
    parsed = _parse(value, kind)
    if parsed is None:
        raise refuse(path, what, f"attribute {field} is {shown(value)}, not {KINDS[kind]}")
    return parsed


def _parse(value, kind: str):
    """``value`` as ``kind``, or None if it is not one."""
    if kind in ("integer", "number", "boolean"):
        if np.ndim(value) != 0 or isinstance(value, (str, bytes)):
            return None
        dtype = np.asarray(value).dtype.kind
        if kind == "boolean":
            return bool(value) if dtype == "b" or (dtype in "iu" and value in (0, 1)) else None
        if kind == "integer":
            return int(value) if dtype in "iu" else None
        return float(value) if dtype in "iuf" else None
    if isinstance(value, bytes):
        try:
            value = value.decode()
        except UnicodeDecodeError:
            return None
    if not isinstance(value, str):
        return None
    if kind == "text":
        return value
    if kind == "digits":
        return value if re.fullmatch(r"[0-9]+", value) else None
    try:
        parsed = json.loads(value)
    except ValueError:  # json.JSONDecodeError, or a number too deep to parse
        return None
    wanted = dict if kind == "JSON object" else list
    return parsed if isinstance(parsed, wanted) else None


def dataset(path: Path, f, name: str, dtype: str, shape: tuple | None, what: str):
    """Dataset ``name`` of ``f``, checked to hold values of ``dtype`` (a key of
    :data:`DTYPES`) in ``shape`` (None: any shape); not read yet.

    Raises
    ------
    RunFileError
        The dataset is missing, a group, of another kind or shape (one line naming it).
    """
    import h5py

    obj = f.get(name)
    if not isinstance(obj, h5py.Dataset):
        raise refuse(path, what, f"dataset {name} is {'missing' if obj is None else 'a group'}")
    if obj.dtype.kind not in dtype:
        raise refuse(path, what, f"dataset {name} holds {obj.dtype}, not {DTYPES[dtype]}")
    if shape is not None and obj.shape != tuple(shape):
        raise refuse(
            path, what, f"dataset {name} has shape {obj.shape}, the inputs ask for {tuple(shape)}"
        )
    return obj


#: A file's uncompressed datasets hold at most this many times the file's size (nothing
#: mcsim writes declares more bytes than the file holds, but the little there is).
MAX_EXPANSION = 64

#: Deflate's largest compression ratio (1032:1, RFC 1951: a 258-byte match in at most 2
#: bits): a gzip-compressed dataset declaring more bytes than this times its stored ones
#: cannot be what it says.
DEFLATE_RATIO = 1032


def check_sizes(path: Path, f, what: str) -> None:
    """Refuse, before reading any data, datasets that are not numbers or fixed-length
    text, or that declare more bytes than the file could hold (a damaged header can
    declare terabytes).

    A contiguous or otherwise filtered dataset counts with its declared bytes, a
    gzip-compressed one with its stored bytes, after checking that deflate could expand
    those to the declared ones.
    """
    import h5py

    budget = MAX_EXPANSION * path.stat().st_size
    total = 0
    found: list[tuple[str, object]] = []
    f.visititems(lambda name, obj: found.append((name, obj)))
    for name, obj in found:
        if not isinstance(obj, h5py.Dataset):
            continue
        if obj.dtype.kind not in "biufS":  # numbers; fixed-length text
            raise refuse(path, what, f"dataset {name} holds {obj.dtype}, not numbers")
        size = int(np.prod(obj.shape, dtype=object)) * obj.dtype.itemsize
        if obj.compression == "gzip":
            stored = obj.id.get_storage_size()
            chunk = int(np.prod(obj.chunks, dtype=object)) * obj.dtype.itemsize
            if size > DEFLATE_RATIO * stored + chunk:
                raise refuse(path, what, f"dataset {name} declares {size} bytes, more than its "
                                         f"{stored} compressed bytes can hold")  # fmt: skip
            size = stored
        total += size
        if total > budget:
            raise refuse(
                path,
                what,
                f"dataset {name} declares {size} bytes ({total} with those before it), "
                f"more than this {path.stat().st_size}-byte file can hold",
            )


def within(
    path: Path, field: str, values, what: str, *, low=-np.inf, high=np.inf, nan: bool = False
):
    """``values`` (a number or an array read from ``field``), checked to lie in [low, high].

    Parameters
    ----------
    path : Path
        The file, for messages.
    field : str
        What holds the values, for messages ("attribute preload", "dataset p_stick").
    values : float or ndarray
        The values, in the units of the file.
    what : str
        The file kind, for messages.
    low, high : float
        The allowed range, ends included (infinite: unbounded, and then infinite values
        are refused too).
    nan : bool
        Whether NaN is allowed (a value not defined there, a failed point).

    Returns
    -------
    float or ndarray
        ``values``, unchanged.

    Raises
    ------
    RunFileError
        A value lies outside the range, is infinite or (without ``nan``) NaN: one line
        naming the field, the first such value and its index.
    """
    v = np.asarray(values)
    bad = ~((v >= max(low, -np.finfo(float).max)) & (v <= min(high, np.finfo(float).max)))
    if nan:
        bad &= ~np.isnan(v)
    if bad.any():
        at = np.unravel_index(np.argmax(bad), v.shape)
        where = f" at index {list(map(int, at))}" if v.ndim else ""
        if np.isfinite(low) and np.isfinite(high):
            allowed = f"{low:g} to {high:g}"
        else:
            allowed = "finite numbers" + f" >= {low:g}" * bool(np.isfinite(low))
            allowed += f" <= {high:g}" * bool(np.isfinite(high))
        allowed += ", or NaN" * nan
        raise refuse(path, what, f"{field} holds {shown(v[at])}{where} (allowed: {allowed})")
    return values
