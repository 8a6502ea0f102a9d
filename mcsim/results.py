"""The result of a Monte Carlo run: its sums, statistics and GW expectation (:class:`Run`).

Layering: this module sits above the engine (:mod:`mcsim.montecarlo`), the statistics
and the analytic integrals, and below storage (:mod:`mcsim.runfile`) and
:func:`mcsim.simulation.simulate`, so that reading a run file needs no simulation code.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .analytic import QUANTITIES, gw_curves
from .montecarlo import EnsembleSums, MonteCarloSpec
from .statistics import Summary, compare_table, expected_values, per_realization, summarize

#: Normalisation of each dimensionless quantity, spelled out (the ``unit`` of tables and files).
NORMALISED = {
    "contact_fraction": "N_c/N",
    "P": "P/(A K)",
    "F": "F/(A K)",
    "T": "T/(A K)",
    "mu": "T/(P + F)",
}

#: Unit of each column of the raw sums (:data:`mcsim.kernels.SUM_COLUMNS`): the count of
#: contacting summits, the forces P, F, T and their second moments.
SUM_UNITS = ("1", "N", "N", "N", "N^2", "N^2", "N^2", "N^2", "N^2", "N^2")

#: Ensemble statistics stored per quantity.
STATS = ("mean", "se", "std", "se_between")


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
        """Raw sums, shape (R, M, 10): :data:`mcsim.kernels.SUM_COLUMNS` in :data:`SUM_UNITS`."""
        return self.ensemble.sums

    @property
    def h(self) -> np.ndarray:
        return self.spec.h

    @property
    def d(self) -> np.ndarray:
        return self.spec.d

    def _summary(self) -> tuple[str, list[tuple[str, str]]]:
        from . import _display

        spec = self.spec
        n = self.n_summits
        drawn = f" (drawn: {np.min(n)} to {np.max(n)})" if n.size else ""
        rows = _display.inputs(spec.surface, spec.material, spec.law, spec.h)
        rows.append(
            ("patch", f"A = {spec.area * 1e12:.4g} µm², N ~ {spec.count} with E[N] = "
                      f"{spec.expected_summits:.4g}{drawn}")
        )  # fmt: skip
        done = "complete" if self.complete else "completed part of an unfinished run"
        rows.append(("realizations", f"{spec.realizations}, {done}; seed entropy {spec.entropy}"))
        if self.path is not None:
            rows.append(("file", str(self.path)))
        return "Monte Carlo run", rows

    def __repr__(self) -> str:
        from . import _display

        return _display.text(*self._summary())

    def _repr_html_(self) -> str:
        from . import _display

        return _display.table(*self._summary())

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
                                 "quantity": q, "value": values, "unit": NORMALISED[q]})  # fmt: skip

        frames = []
        for q in QUANTITIES:
            frames += [
                frame("realization", r, q, row) for r, row in enumerate(self.realizations[q])
            ]
            frames += [frame(stat, -1, q, getattr(self.summary, stat)[q]) for stat in STATS]
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
