"""HDF5 run files: write atomically, read back as a :class:`Run`.

Layout (schema version :data:`SCHEMA_VERSION`; every quantity carries a ``unit``
attribute, dimensionless ones ``"1"`` with a ``normalised_by`` note):

    /                      attrs: schema_version, mcsim_version, created, command,
                           seed_entropy, law, count, area [m^2], realizations, block_size
    /input/surface         attrs: sigma [m], R [m], eta [m^-2], name, heights (JSON)
    /input/material        attrs: E1, E2 [Pa], nu1, nu2, gamma [J/m^2], H [Pa], name
    /h, /d                 separations: d/σ and d [m]
    /realizations/N        summits per patch
    /realizations/sums     (R, M, 10) raw sums, columns in attrs (forces in N)
    /realizations/<q>      (R, M) dimensionless curves, q in contact_fraction,P,F,T,mu
    /summary/<stat>/<q>    (M,) stat in mean, se, std, se_between
    /summary/expected_contacts
    /analytic/<q>          (M,) GW curves for the same inputs (expected values)
    /heights/<r>           optional: sampled heights above h_min [m]

The file is written under a temporary name in the target folder and moved into place
only when complete; an existing file is replaced only with ``overwrite=True``.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import tempfile
from pathlib import Path

import numpy as np

from ._version import __version__
from .analytic import QUANTITIES
from .distributions import GAUSSIAN
from .errors import RunFileError
from .kernels import SUM_COLUMNS
from .montecarlo import MonteCarloSpec
from .params import Material, Surface
from .statistics import Summary

SCHEMA_VERSION = 1
STATS = ("mean", "se", "std", "se_between")
NORMALISED = {
    "contact_fraction": "N_c/N",
    "P": "P/(A K)",
    "F": "F/(A K)",
    "T": "T/(A K)",
    "mu": "T/(P + F)",
}


def check_output_path(path: str | Path, overwrite: bool = False) -> Path:
    """Fail early (before any work) if ``path`` cannot receive a new run file."""
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise RunFileError(f"{path}: output folder {folder} does not exist")
    if not os.access(folder, os.W_OK):
        raise RunFileError(f"{path}: output folder {folder} is not writable")
    if path.exists() and not overwrite:
        raise RunFileError(f"{path}: file exists (pass --overwrite / overwrite=True to replace it)")
    return path


def _heights_to_json(surface: Surface) -> str:
    heights = surface.heights
    if heights == GAUSSIAN:
        return json.dumps({"name": "gaussian"})
    return json.dumps({"name": heights.name, **heights.to_dict()})


def _heights_from_json(text: str):
    data = json.loads(text)
    if data["name"] == "gaussian":
        return GAUSSIAN
    from .empirical import Empirical

    return Empirical.from_dict({k: v for k, v in data.items() if k != "name"})


def write_run(path: str | Path, run, *, command: str, overwrite: bool = False):
    """Write ``run`` (a :class:`mcsim.simulation.Run`) atomically; return it with path and attrs."""
    import dataclasses

    import h5py

    path = check_output_path(path, overwrite)
    spec = run.spec
    attrs = {
        "schema_version": SCHEMA_VERSION,
        "mcsim_version": __version__,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "command": command,
        "seed_entropy": str(spec.entropy),
        "law": spec.law,
        "count": spec.count,
        "area": spec.area,
        "area_unit": "m^2",
        "realizations": spec.realizations,
        "block_size": _block_size(),
    }
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    try:
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
        with h5py.File(tmp, "w") as f:
            f.attrs.update(attrs)
            s = f.create_group("input/surface")
            s.attrs.update(sigma=spec.surface.sigma, R=spec.surface.R, eta=spec.surface.eta,
                           name=spec.surface.name, heights=_heights_to_json(spec.surface))  # fmt: skip
            s.attrs["units"] = json.dumps({"sigma": "m", "R": "m", "eta": "m^-2"})
            m = f.create_group("input/material")
            mat = spec.material
            m.attrs.update(E1=mat.E1, E2=mat.E2, nu1=mat.nu1, nu2=mat.nu2, gamma=mat.gamma,
                           H=np.nan if mat.H is None else mat.H, name=mat.name)  # fmt: skip
            m.attrs["units"] = json.dumps(
                {"E1": "Pa", "E2": "Pa", "nu1": "1", "nu2": "1", "gamma": "J/m^2", "H": "Pa"}
            )
            _dataset(f, "h", spec.h, "1", "d/sigma")
            _dataset(f, "d", spec.d, "m", "mean separation")
            _dataset(f, "realizations/N", run.n_summits, "1", "summits in the patch")
            sums = _dataset(f, "realizations/sums", run.sums, "N", "raw per-separation sums")
            sums.attrs["columns"] = list(SUM_COLUMNS)
            for q in QUANTITIES:
                _dataset(f, f"realizations/{q}", run.realizations[q], "1", NORMALISED[q])
                _dataset(f, f"analytic/{q}", run.analytic[q], "1", NORMALISED[q])
                for stat in STATS:
                    _dataset(
                        f, f"summary/{stat}/{q}", getattr(run.summary, stat)[q], "1", NORMALISED[q]
                    )
            _dataset(
                f, "summary/expected_contacts", run.summary.expected_contacts, "1", "R E[N] S(h)"
            )
            if run.heights is not None:
                for r, z in enumerate(run.heights):
                    ds = f.create_dataset(f"heights/{r}", data=z, compression="gzip", shuffle=True)
                    ds.attrs["unit"] = "m"
        if overwrite:
            os.replace(tmp, path)
        else:
            try:
                os.link(tmp, path)  # atomic, and fails rather than replace a file made meanwhile
            except FileExistsError:
                raise RunFileError(
                    f"{path}: file exists (pass --overwrite to replace it)"
                ) from None
            os.unlink(tmp)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return dataclasses.replace(run, path=path, attrs=attrs)


def _block_size() -> int:
    from .montecarlo import BLOCK

    return BLOCK


def _dataset(f, name: str, data, unit: str, description: str):
    ds = f.create_dataset(name, data=np.asarray(data))
    ds.attrs["unit"] = unit
    ds.attrs["description"] = description
    return ds


def read_run(path: str | Path):
    """Open a run file as a :class:`mcsim.simulation.Run`; refuse other schema versions."""
    import h5py

    from .simulation import Run

    path = Path(path)
    if not path.is_file():
        raise RunFileError(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise RunFileError(f"{path}: not an HDF5 file (or truncated)") from None
    with f:
        version = f.attrs.get("schema_version")
        if version is None:
            raise RunFileError(f"{path}: not an mcsim run file (no schema_version)")
        if int(version) != SCHEMA_VERSION:
            raise RunFileError(
                f"{path}: run-file schema version {int(version)} is not supported "
                f"(this mcsim {__version__} reads version {SCHEMA_VERSION})"
            )
        try:
            attrs = {k: (v.item() if hasattr(v, "item") else v) for k, v in f.attrs.items()}
            s, m = f["input/surface"].attrs, f["input/material"].attrs
            surface = Surface(sigma=float(s["sigma"]), R=float(s["R"]), eta=float(s["eta"]),
                              heights=_heights_from_json(s["heights"]), name=str(s["name"]))  # fmt: skip
            H = float(m["H"])
            material = Material(E1=float(m["E1"]), E2=float(m["E2"]), nu1=float(m["nu1"]), nu2=float(m["nu2"]),
                                gamma=float(m["gamma"]), H=None if np.isnan(H) else H, name=str(m["name"]))  # fmt: skip
            h = f["h"][()]
            spec = MonteCarloSpec(surface, material, h, float(attrs["area"]), int(attrs["realizations"]),
                                  int(attrs["seed_entropy"]), str(attrs["law"]), str(attrs["count"]))  # fmt: skip
            stats = {stat: {q: f[f"summary/{stat}/{q}"][()] for q in QUANTITIES} for stat in STATS}
            summary = Summary(**stats, expected_contacts=f["summary/expected_contacts"][()])
            heights = (
                [f[f"heights/{r}"][()] for r in sorted(f["heights"], key=int)]
                if "heights" in f
                else None
            )
            return Run(
                spec=spec,
                n_summits=f["realizations/N"][()],
                sums=f["realizations/sums"][()],
                realizations={q: f[f"realizations/{q}"][()] for q in QUANTITIES},
                summary=summary,
                analytic={q: f[f"analytic/{q}"][()] for q in QUANTITIES},
                attrs=attrs,
                path=path,
                heights=heights,
            )
        except KeyError as err:
            raise RunFileError(f"{path}: incomplete run file, missing {err}") from None
