"""Resuming a sweep: its checkpoint and the finished file a claimed output may hold.

:func:`mcsim.studies.sweeps.sweep` claims its output (:mod:`mcsim.store.claim`); where the
claim finds a checkpoint of the same sweep it restores the completed points
(:func:`restore`), where it finds the finished sweep asked for it returns it
(:func:`already_finished`), and a sweep of other inputs is refused with what differs.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mcsim.model.errors import RunFileError
from mcsim.store.sweepfile import Sweep, read_partial


def read_checkpoint(partial: Path) -> tuple[dict, dict]:
    """A sweep checkpoint (:func:`mcsim.store.sweepfile.read_partial`) and its attributes."""
    previous = read_partial(partial)
    return previous, previous["attrs"]


def recorded_seed(claim) -> int | None:
    """The seed of the finished sweep or checkpoint a resume found (None: neither, or no seed)."""
    if claim.finished is not None:
        recorded = claim.finished.attrs.get("seed_entropy")
    else:
        recorded = claim.checkpoint_attrs.get("seed_entropy")
    return int(recorded) if recorded else None


def restore(claim, result: Sweep, attrs: dict, shape: tuple) -> np.ndarray:
    """The points a checkpoint completed, copied into ``result``, once its inputs are those
    asked for (``attrs``); which points are done."""
    previous = claim.checkpoint
    claim.check_checkpoint(_inputs(claim.partial, previous["attrs"]), _inputs(claim.out, attrs))
    done = _recorded(claim.partial, previous, result, shape)
    for k in result.data:
        result.data[k][done] = previous["data"][k][done]
    return done


#: The names a resume's message gives the entries of a sweep's ``definition``.
_INPUT_NAMES = {"seed_entropy": "seed", "mcsim_version": "mcsim version",
                "sweep_schema_version": "schema version", "values": "varied values"}  # fmt: skip


def _inputs(path: Path, attrs: dict) -> dict:
    """What defines the sweep of ``attrs`` (its ``definition``: everything but the time
    and the command line), as a resume compares it; ``path`` names a damaged file."""
    try:
        inputs = json.loads(attrs["definition"])
        for k in ("surface", "material", "varied"):
            inputs[k] = json.loads(inputs[k])
        if inputs.get("seed_entropy") is not None:
            inputs["seed_entropy"] = int(inputs["seed_entropy"])
    except (KeyError, TypeError, ValueError):
        raise RunFileError(f"{path}: damaged sweep file: its definition is not readable") from None
    return {_INPUT_NAMES.get(k, k): v for k, v in inputs.items()}


def already_finished(claim, attrs: dict, seed_given: bool) -> Sweep:
    """The complete sweep at the claimed output, if it is the sweep asked for (the same
    ``definition`` as ``attrs``; see :meth:`mcsim.store.claim.Claim.already_finished`)."""
    out = claim.out
    if not claim.finished.attrs.get("complete"):
        raise RunFileError(f"{out}: damaged sweep file: it holds an unfinished sweep")
    seed = attrs.get("seed_entropy")
    return claim.already_finished(
        _inputs(out, claim.finished.attrs), _inputs(out, attrs),
        own_checkpoint=lambda partial: read_partial(partial)["attrs"].get("definition") == attrs["definition"],
        seed_note=f" (no seed given: taken as the file's, {seed})" if seed and not seed_given else "",
    )  # fmt: skip


def _recorded(partial: Path, previous: dict, result: Sweep, shape: tuple) -> np.ndarray:
    """The completed points of a checkpoint, once its variables are those of ``result``
    (a checkpoint rewritten elsewhere, checksum included, may lack some)."""
    variables = {"done": (previous["done"], shape)}
    variables |= {k: (previous["data"].get(k), v.shape) for k, v in result.data.items()}
    for k, (values, wanted) in variables.items():
        if values is None or values.shape != wanted:
            found = "is missing" if values is None else f"has shape {values.shape}"
            raise RunFileError(f"{partial}: damaged sweep file: dataset {k} {found}, "
                               f"the inputs ask for {wanted}")  # fmt: skip
    return previous["done"]
