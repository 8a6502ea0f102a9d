"""``simulate()``: the Monte Carlo engine, its statistics and storage joined, and the result.

>>> from mcsim import simulate
>>> from mcsim.presets import SURFACES, MATERIALS
>>> run = simulate(SURFACES["smooth"], MATERIALS["silicon"], h=[2, 1, 0], area="1000 um^2",
...                realizations=4, seed=1)                                  # doctest: +SKIP
>>> run.compare()                                                           # doctest: +SKIP
"""

from __future__ import annotations

import contextlib
import functools
import shlex
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import runfile
from ._version import __version__
from .analytic import QUANTITIES, gw_curves
from .errors import ParameterError, RunFileError
from .montecarlo import DEFAULT_CHUNK, EnsembleSums, MonteCarloSpec, run_sums
from .params import Material, Surface
from .statistics import (
    Summary,
    compare_table,
    expected_values,
    per_realization,
    summarize,
)
from .units import parse_quantity


@dataclass(frozen=True)
class Run:
    """A Monte Carlo run with its statistics and the GW expectation for the same inputs.

    Attributes
    ----------
    ensemble : EnsembleSums
        The inputs (``ensemble.spec``), the summit counts and the raw sums.
    realizations : dict of ndarray
        (R, M) dimensionless curves per quantity (N_c/N; force/(A·K); μ).
    summary : Summary
        Ensemble estimates and standard errors.
    analytic : dict of ndarray
        GW expected values of the estimators, per quantity.
    attrs : dict
        Provenance (command, versions, creation time) once written or read.
    path : Path or None
        The run file, if any.
    heights : list of ndarray or None
        Sampled heights above h_min (m), when kept.
    complete : bool
        False for the completed part of an unfinished run.
    """

    ensemble: EnsembleSums
    realizations: dict
    summary: Summary
    analytic: dict
    attrs: dict = field(default_factory=dict)
    path: Path | None = None
    heights: list | None = field(default=None, repr=False)
    complete: bool = True

    @property
    def spec(self) -> MonteCarloSpec:
        return self.ensemble.spec

    @property
    def n_summits(self) -> np.ndarray:
        """Summits per patch."""
        return self.ensemble.n_summits

    @property
    def sums(self) -> np.ndarray:
        """Raw sums, shape (R, M, 10) (:data:`mcsim.kernels.SUM_COLUMNS`, forces in N)."""
        return self.ensemble.sums

    @property
    def h(self) -> np.ndarray:
        return self.spec.h

    @property
    def d(self) -> np.ndarray:
        return self.spec.d

    def compare(self):
        """DataFrame ``h, quantity, mc_mean, mc_se, analytic, z, note`` (see :mod:`mcsim.statistics`)."""
        import pandas as pd

        return pd.DataFrame(compare_table(self.summary, self.analytic, self.h))

    def to_dataframe(self):
        """Tidy table: one row per (source, realization, h, quantity).

        Columns: ``source`` (``realization``, ``mean``, ``se``, ``std``, ``se_between``
        or ``analytic``), ``realization`` (index, -1 for the others), ``h`` (d/σ), ``d``
        (m), ``quantity``, ``value``, ``unit``. Values are dimensionless: N_c/N (Eq. 1),
        force/(A·K) for P, F, T (Eqs. 3, 5, 7) and T/(P+F) for μ (Eq. 8); ``unit``
        spells out the normalisation.
        """
        import pandas as pd

        def frame(source, realization, q, values):
            return pd.DataFrame({"source": source, "realization": realization, "h": self.h, "d": self.d,
                                 "quantity": q, "value": values, "unit": runfile.NORMALISED[q]})  # fmt: skip

        frames = []
        for q in QUANTITIES:
            frames += [
                frame("realization", r, q, row) for r, row in enumerate(self.realizations[q])
            ]
            frames += [frame(stat, -1, q, getattr(self.summary, stat)[q]) for stat in runfile.STATS]
            frames.append(frame("analytic", -1, q, self.analytic[q]))
        return pd.concat(frames, ignore_index=True)


def assemble(ens: EnsembleSums, **kwargs) -> Run:
    """Statistics and GW expectations of a complete ensemble, as a :class:`Run`."""
    spec = ens.spec
    return Run(
        ensemble=ens,
        realizations=per_realization(ens),
        summary=summarize(ens),
        analytic=expected_values(spec, gw_curves(spec.surface, spec.material, spec.h, spec.law)),
        heights=ens.heights,
        **kwargs,
    )


def _api_command(**kwargs) -> str:
    shown = ", ".join(f"{k}={v!r}" for k, v in kwargs.items())
    return f"mcsim.simulate({shown})"


def simulate(
    surface: Surface,
    material: Material,
    h,
    area: float | str,
    *,
    realizations: int = 1,
    seed: int | None = None,
    law: str = "seed",
    count: str = "poisson",
    workers: int | None = None,
    scheduler=None,
    chunk_size: int = DEFAULT_CHUNK,
    keep_heights: bool = False,
    out: str | Path | None = None,
    overwrite: bool = False,
    resume: bool = False,
    checkpoint_every: float = 60.0,
    progress: bool = False,
    command: str | None = None,
) -> Run:
    """Simulate ``realizations`` patches of area ``area`` and compare with the GW curves.

    Parameters
    ----------
    surface, material : Surface, Material
        Inputs (see :mod:`mcsim.presets` and :mod:`mcsim.config`).
    h : array_like
        Dimensionless separations d/σ.
    area : float or str
        Nominal patch area, m² or with a unit (``"100 um^2"``).
    realizations : int
        Independent patches.
    seed : int or None
        Root seed; None draws fresh entropy (recorded in the result), or, with
        ``resume``, takes the one recorded in the file.
    law : str
        Law set (``"seed"``: the paper as written).
    count : {"poisson", "fixed"}
        N ~ Poisson(ηA) or N = round(ηA).
    workers : int, optional
        Local worker threads, all cores by default; or worker processes of a local
        Dask cluster. The numbers do not depend on it.
    scheduler : str or dask.distributed.Client, optional
        Run on Dask: ``"local"`` (a local cluster of ``workers`` processes), the
        address of an existing scheduler (``"tcp://host:8786"``) or a client.
    chunk_size : int
        Summits per task; the numbers do not depend on it.
    keep_heights : bool
        Keep the sampled heights (above h_min) in the result and file (no checkpoints).
    out : path, optional
        Write the run to this HDF5 file. While it runs, the file holds an incomplete,
        resumable run, rewritten atomically every ``checkpoint_every`` seconds and on
        interruption; at the end, the complete run. An existing file is refused
        unless ``overwrite`` (or ``resume``, for an incomplete run of the same inputs).
    resume : bool
        Continue the incomplete run in ``out``; the result is bit-identical to an
        uninterrupted run.
    checkpoint_every : float
        Seconds between checkpoints.
    progress : bool
        Show a progress bar on stderr.
    command : str, optional
        Provenance string stored in the file (the CLI passes its command line).

    Returns
    -------
    Run
    """
    area_m2 = parse_quantity(area, "area", "area")
    if resume and out is None:
        raise ParameterError("resume needs the run file to continue (out=...)")
    with contextlib.ExitStack() as stack:
        previous = None
        if out is not None:
            out = runfile.check_output_path(out, overwrite=overwrite, resume=resume)
            stack.enter_context(runfile.lock(out))
            if resume:
                previous, attrs = runfile.read_state(out)
                if previous.complete:
                    raise RunFileError(f"{out}: the run is already complete; nothing to resume")
                if attrs.get("mcsim_version") != __version__:
                    raise RunFileError(
                        f"{out}: written by mcsim {attrs.get('mcsim_version')}; resume it with that version"
                    )
                seed = previous.spec.entropy if seed is None else seed
        entropy = np.random.SeedSequence(seed).entropy
        spec = MonteCarloSpec(surface, material, h, area_m2, realizations, entropy, law, count)
        if previous is not None and previous.spec != spec:
            raise ParameterError(
                f"cannot resume {out}: {', '.join(previous.spec.differences(spec))} differ(s) from the recorded run"
            )
        if command is None:
            command = _api_command(surface=surface.name or surface, material=material.name or material,
                                   h=[float(x) for x in spec.h], area=area_m2, realizations=realizations,
                                   seed=seed, law=law, count=count)  # fmt: skip
        checkpoint = None
        if out is not None and not keep_heights:
            checkpoint = functools.partial(runfile.write_checkpoint, out, command=command)
        if progress:
            from tqdm import tqdm

            total = (
                spec.realizations * spec.expected_summits * float(surface.heights.sf(spec.h.min()))
            )
            bar = stack.enter_context(
                tqdm(
                    total=round(total),
                    unit=" summits",
                    unit_scale=True,
                    file=sys.stderr,
                    leave=False,
                )
            )
        client = scheduler
        if isinstance(scheduler, str):
            from .cluster import dask_client

            client = stack.enter_context(dask_client(scheduler, workers))
        ens = run_sums(spec, workers=workers, chunk_size=chunk_size, keep_heights=keep_heights,
                       progress=bar.update if progress else None, client=client, resume=previous,
                       checkpoint=checkpoint, checkpoint_every=checkpoint_every)  # fmt: skip
        run = assemble(ens)
        if out is None:
            return run
        return runfile.write_run(out, run, command=command)


def cli_command() -> str:
    """The current command line, quoted, for provenance."""
    return " ".join(shlex.quote(a) for a in ["mcsim", *sys.argv[1:]])
