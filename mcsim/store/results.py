"""The result of a Monte Carlo run: its sums, statistics and GW expectation (:class:`Run`).

Layering: this module sits above the engine (:mod:`mcsim.engine.montecarlo`), the statistics
and the analytic integrals, and below storage (:mod:`mcsim.store.runfile`) and
:func:`mcsim.studies.simulation.simulate`, so that reading a run file needs no simulation code.
"""

from __future__ import annotations

import inspect
import types
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np

from mcsim.engine.montecarlo import EnsembleSums
from mcsim.engine.spec import MonteCarloSpec
from mcsim.engine.statistics import (
    Summary,
    compare_table,
    expected_values,
    per_realization,
    quantities,
    summarize,
)
from mcsim.model.errors import ParameterError
from mcsim.physics.analytic import analytic_curves
from mcsim.physics.environment import Environment
from mcsim.physics.gapheights import GapHeights, gap_heights
from mcsim.physics.surfaceenvironment import active_terms, open_gap_pressures

#: Normalisation of each dimensionless quantity, spelled out (the ``unit`` of tables and files).
NORMALISED = {
    "contact_fraction": "N_c/N",
    "P": "P/(A K)",
    "F": "F/(A K)",
    "T": "T/(A K)",
    "mu": "T/(P + F)",
}

#: Unit of each column of the seed's raw sums (:data:`mcsim.engine.kernels.SUM_COLUMNS`): the
#: count of contacting summits, the forces P, F, T and their second moments (any law set:
#: :func:`mcsim.engine.kernels.sum_units`).
SUM_UNITS = ("1", "N", "N", "N", "N^2", "N^2", "N^2", "N^2", "N^2", "N^2")

#: Ensemble statistics stored per quantity.
STATS = ("mean", "se", "std", "se_between")


@dataclass(frozen=True)
class PullOff:
    """Per-patch pull-off force of a cycle run: the most tensile load on retraction.

    Attributes
    ----------
    force : ndarray, shape (R,)
        Magnitude of the most tensile total load of each patch on retraction, N (0 where
        it is nowhere tensile): exact, the minimum of the pad's own curve in continuous h
        (:func:`mcsim.engine.pads.curves.pull_off`, to 1e-7 in h, retracted until every
        summit has let go), or where ``exact`` is False the minimum over the run's grid.
    normalised : ndarray, shape (R,)
        The same divided by A K (the ``load`` normalisation).
    h : ndarray, shape (R,)
        d/σ where it occurs (NaN where ``force`` is 0).
    resolution : float
        Largest spacing of the swept grid in d/σ (of ``grid_force``).
    grid_force, grid_h : ndarray, shape (R,)
        The most tensile load on the run's grid of retraction rows (N, a magnitude) and
        its d/σ: biased low, and stuck at the grid's top where the pad is still tensile there.
    top : float
        The grid's largest separation d/σ.
    h_turn : ndarray, shape (R,)
        Each pad's closest approach d/σ: the run's min(h), a given common turn, or under
        force control the pad's own (:func:`mcsim.engine.pads.curves.force_turn`).
    turn_load : ndarray, shape (R,) or None
        Under force control, the approach load each pad reached at its turn, N.
    preload : float or None
        The nominal pressure P (Pa) of force control: each pad pressed with P·A.
    exact : bool
        False for a GPU run (its heights cannot be drawn again): ``force`` is the grid's.
    static_friction : ndarray, shape (R,) or None
        With ``friction``: each pad's static friction T_s at its turn, N
        (:func:`mcsim.engine.pads.friction.static_friction`).
    normal_load : ndarray, shape (R,) or None
        With ``friction``: the normal load W its μ_s = T_s/W is taken on, N (P·A under force
        control, else the pad's net approach load at the turn; where that is not positive,
        the environment's pull; NaN dry: :func:`mcsim.engine.pads.friction.normal_load`).
    """

    force: np.ndarray
    normalised: np.ndarray
    h: np.ndarray
    resolution: float
    grid_force: np.ndarray
    grid_h: np.ndarray
    h_turn: np.ndarray
    turn_load: np.ndarray | None = None
    preload: float | None = None
    exact: bool = True

    top: float = np.inf
    static_friction: np.ndarray | None = None
    normal_load: np.ndarray | None = None

    @property
    def mu_static(self) -> np.ndarray | None:
        """μ_s = T_s/W of each pad (NaN where W is undefined); None without ``friction``."""
        if self.static_friction is None:
            return None
        return self.static_friction / self.normal_load

    #: Columns of :meth:`to_dataframe` (those of ``mcsim pads --format csv``): name, unit,
    #: meaning.
    COLUMNS = (
        ("pull_off_N", "N", "most tensile retraction load of the pad, a magnitude"),
        ("h_pull_off", "1", "its separation d/sigma"),
        ("h_turn", "1", "the pad's closest approach d/sigma"),
        ("turn_load_N", "N", "approach load reached there under a preload"),
        ("grid_pull_off_N", "N", "the most tensile load on the run's grid"),
        ("grid_h_pull_off", "1", "its separation d/sigma"),
        ("static_friction_N", "N", "T_s at the turn"),
        ("normal_load_N", "N", "W, the load of mu_s; NaN where undefined"),
        ("mu_static", "1", "T_s/W"),
    )

    def columns(self) -> list[tuple[str, str, str, np.ndarray]]:
        """(name, unit, meaning, values per pad) of each column of :meth:`to_dataframe`."""
        nan = np.full(self.force.shape, np.nan)
        values = [self.force, self.h, self.h_turn,
                  nan if self.turn_load is None else self.turn_load, self.grid_force, self.grid_h]  # fmt: skip
        if self.static_friction is not None:
            values += [self.static_friction, self.normal_load, self.mu_static]
        return [(*column, v) for column, v in zip(self.COLUMNS, values)]

    def to_dataframe(self):
        """One row per pad (index ``pad``, the realization), the columns of :data:`COLUMNS`
        (the friction columns only with ``friction``); ``df.attrs["units"]`` and
        ``df.attrs["long_names"]`` give each column's unit and meaning."""
        import pandas as pd

        table = self.columns()
        columns = [(name, unit, meaning) for name, unit, meaning, _ in table]
        values = [v for *_, v in table]
        df = pd.DataFrame({name: v for (name, _, _), v in zip(columns, values)},
                          index=pd.RangeIndex(len(self.force), name="pad"))  # fmt: skip
        df.attrs["units"] = {name: unit for name, unit, _ in columns}
        df.attrs["long_names"] = {name: meaning for name, _, meaning in columns}
        return df

    @property
    def past_grid_top(self) -> int:
        """Pads whose pull-off lies beyond ``top``, the run's largest separation: the grid
        could not hold their minimum (its value there is wrong, often 0)."""
        return int(np.count_nonzero(self.h > self.top))


@dataclass(frozen=True)
class EnvironmentRun:
    """The environment's part of a run that is not summed over summits.

    The summits' caps are outputs of the run's law set (``vdw``, ``capillary`` in
    ``summary``, with standard errors and GW expected values like the loads); the open
    gaps between the caps add a deterministic pressure (no sampling, no error).

    Attributes
    ----------
    environment : Environment
        The medium.
    gap : GapHeights
        Heights about the mean plane (rq, summit offset, their source) used by the open gaps.
    open_gaps : dict of ndarray
        ``"vdw"``, ``"capillary"``: the open gaps' pressures divided by K, per row
        (:func:`mcsim.physics.surfaceenvironment.open_gap_pressures`).
    """

    environment: Environment
    gap: GapHeights
    open_gaps: dict


def environment_run(spec: MonteCarloSpec) -> EnvironmentRun | None:
    """The open gaps' curves of a run with an environment, at every row (None: no environment)."""
    env = spec.environment
    if env is None:
        return None
    gaps = open_gap_pressures(spec.row_h, spec.surface, env)
    open_gaps = {t: gaps[t] / spec.material.K for t in active_terms(env)}
    return EnvironmentRun(env, gap_heights(spec.surface), open_gaps)


class Estimate(NamedTuple):
    """A curve's estimate and standard error, one value per row (dimensionless)."""

    mean: np.ndarray
    se: np.ndarray


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
        Provenance (command, versions, creation time) once written or read; in memory, the
        run's further attributes (``preload``, ``load_control``; see :func:`mcsim.simulate`).
    path : Path or None
        The run file, if any.
    heights : list of ndarray or None
        Sampled heights above h_min (m), when kept.
    complete : bool
        False for the completed part of an unfinished run.
    environment : EnvironmentRun or None
        The environment's inputs and its open gaps' curves, when the run had one (its
        summits' caps are outputs of the law set, in ``summary``).
    """

    ensemble: EnsembleSums
    realizations: dict
    summary: Summary
    analytic: dict
    attrs: dict = field(default_factory=dict)
    path: Path | None = None
    heights: list | None = field(default=None, repr=False)
    complete: bool = True
    environment: EnvironmentRun | None = None

    def _term(self, term: str) -> Estimate:
        env = self.environment
        if env is None or term not in env.open_gaps:
            raise ParameterError(
                f"this run has no {term} term (no environment, or it does not act)"
            )
        caps = self.summary.mean[term]
        return Estimate(caps + env.open_gaps[term], self.summary.se[term])

    @property
    def vdw(self) -> Estimate:
        """Van der Waals attraction per nominal area over K per row (attractive positive):
        the summits' caps (sampled) plus the open gaps (deterministic, no error)."""
        return self._term("vdw")

    @property
    def capillary(self) -> Estimate:
        """Capillary attraction per nominal area over K per row (attractive positive): the
        summits' menisci (sampled) plus the condensate in the open gaps (deterministic)."""
        return self._term("capillary")

    @property
    def spec(self) -> MonteCarloSpec:
        return self.ensemble.spec

    @property
    def n_summits(self) -> np.ndarray:
        """Summits per patch."""
        return self.ensemble.n_summits

    @property
    def sums(self) -> np.ndarray:
        """Raw sums, shape (R, M, 10): :data:`mcsim.engine.kernels.SUM_COLUMNS` in :data:`SUM_UNITS`."""
        return self.ensemble.sums

    @property
    def h(self) -> np.ndarray:
        return self.spec.h

    @property
    def d(self) -> np.ndarray:
        return self.spec.d

    def _summary(self) -> tuple[str, list[tuple[str, str]]]:
        from mcsim.model import display as _display

        spec = self.spec
        n = self.n_summits
        drawn = f" (drawn: {np.min(n)} to {np.max(n)})" if n.size else ""
        rows = _display.inputs(spec.surface, spec.material, spec.law, spec.h)
        if spec.cycle:
            rows.append(("branches", f"approach, then retraction from h = {np.min(spec.h):g}"))
        env = spec.environment
        if env is not None:
            terms = " and ".join({"vdw": f"van der Waals (A = {env.hamaker or 0:.3g} J, "
                                         f"{env.retardation_label})",
                                  "capillary": f"menisci (RH = {env.rh:g})"}[t]
                                 for t in active_terms(env))  # fmt: skip
            rows.append(("environment", f"{terms}: on the summits' caps (sampled), and across "
                                        "the open gaps (deterministic)"))  # fmt: skip
        preload = self.attrs.get("preload")
        if preload is not None and np.isfinite(preload):
            rows.append(("preload", f"{float(preload) / 1e6:.4g} MPa (force control)"))
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
        from mcsim.model import display as _display

        return _display.text(*self._summary())

    def _repr_html_(self) -> str:
        from mcsim.model import display as _display

        return _display.table(*self._summary())

    @property
    def quantities(self) -> tuple[str, ...]:
        """Names of the estimated curves (see :func:`mcsim.engine.statistics.quantities`)."""
        return tuple(self.summary.mean)

    def normalisation(self, quantity: str) -> str:
        """How ``quantity`` is made dimensionless (``"P/(A K)"``, ``"area/A"``, ...)."""
        return quantities(self.spec.law_set, self.spec.material)[quantity].normalisation

    def compare(self):
        """DataFrame ``h, branch, quantity, mc_mean, mc_se, analytic, z, note``, one row
        per separation, branch and quantity (see :mod:`mcsim.engine.statistics`); with an
        environment, the summits' caps ``vdw`` and ``capillary`` (force/(A K)) among them:
        outputs of the law set like the loads (the open gaps are not sampled)."""
        import pandas as pd

        return pd.DataFrame(self.compare_rows())

    def compare_rows(self) -> list[dict]:
        """The rows of :meth:`compare`, each a dict of Python floats and strings (without
        pandas: ``mcsim compare`` and ``mcsim show`` print them)."""
        spec = self.spec
        return compare_table(self.summary, self.analytic, spec.row_h, spec.row_branch)

    def pull_off(self, turn: float | None = None, *, friction: bool = False,
                 progress: bool = False, pool=None) -> PullOff:  # fmt: skip
        """Per-patch pull-off of a cycle run (the law set must have a signed ``load``).

        Each pad's summits are drawn again from the seed (:mod:`mcsim.engine.pads.curves`;
        checked against the stored approach sums) and its pull-off located on its own
        curve. The closest approach: ``turn`` (d/σ, common to all pads, ≥ min(h)) if
        given; else each pad's own under force control where the run was pressed with a
        preload (attribute ``preload``, Pa); else the run's min(h). With ``friction`` also
        each pad's static friction at that turn and the normal load of its μ_s
        (:mod:`mcsim.engine.pads.friction`; a ParameterError for a law set without friction).
        With ``progress`` a progress bar over the pads on stderr. With ``pool`` (a
        :class:`mcsim.studies.padpool.PadPool`: ``pool.map(fn, calls)`` evaluates
        ``fn(*call)`` of each call on its ``pool.workers`` worker processes) the pads go to it
        in contiguous ranges, one a worker at a time, joined in order: the same values.
        """
        from mcsim.engine.pads import friction as padfriction
        from mcsim.engine.pads import load as padload

        spec = self.spec
        if not spec.cycle or "load" not in spec.law_set.names:
            raise ParameterError(
                f"pull-off needs a cycle run (--cycle) of a law set with a signed load; "
                f"this run has law = {spec.law!r}, cycle = {spec.cycle}"
            )
        if turn is not None and not turn >= spec.turn:
            raise ParameterError(f"turn = {turn!r}: allowed >= the run's lowest separation "
                                 f"h = {spec.turn:g} (no summit below it is drawn)")  # fmt: skip
        M, R = spec.h.size, self.sums.shape[0]
        load = padload.net_load(spec, self.sums, spec.rows()[0])
        j = np.argmin(load[:, M:], axis=1)
        grid_force = np.maximum(-load[np.arange(R), M + j], 0.0)
        grid = np.unique(spec.h)
        preload = self.attrs.get("preload") if turn is None else None
        preload = None if preload is None or not np.isfinite(preload) else float(preload)
        force, h, h_turn = grid_force.copy(), spec.h[j].astype(float), np.full(R, spec.turn)
        turn_load = np.full(R, np.nan) if preload is not None else None
        exact = spec.device == "cpu"
        if turn is not None:
            h_turn[:] = turn
        static = normal = None
        if friction:
            padfriction.check_friction(spec)
            if not exact:
                raise ParameterError("static friction needs the pads' heights, which a GPU run "
                                     "cannot draw again")  # fmt: skip
            static, normal = np.empty(R), np.empty(R)
        if exact:
            bar = None
            if progress:
                import sys

                from tqdm import tqdm

                bar = tqdm(total=R, unit=" pads", file=sys.stderr, leave=False)
            step = 1 if pool is None else pool.workers  # ranges evaluated at a time
            calls = [(spec, load[lo:hi, :M], lo, turn, preload, friction)
                     for lo, hi in _ranges(R, R if pool is None else step * _ROUNDS)]  # fmt: skip
            done = []
            for i in range(0, len(calls), step):
                wave = calls[i : i + step]
                done += (
                    [_pad_range(*c) for c in wave] if pool is None else pool.map(_pad_range, wave)
                )
                if bar is not None:
                    bar.update(sum(len(c[1]) for c in wave))
            if bar is not None:
                bar.close()
            if R:
                cols = [np.concatenate([d[k] for d in done]) for k in range(6)]
                force, h, h_turn[:] = cols[0], cols[1], cols[2]
                if preload is not None:
                    turn_load[:] = cols[3]
                if friction:
                    static, normal = cols[4], cols[5]
        elif preload is not None:
            raise ParameterError("force control (preload) needs the pads' heights, which a GPU "
                                 "run cannot draw again")  # fmt: skip
        return PullOff(force=force, normalised=force / (spec.area * spec.material.K), h=h,
                       resolution=float(np.max(np.diff(grid))) if grid.size > 1 else np.inf,
                       grid_force=grid_force, grid_h=spec.h[j], h_turn=h_turn,
                       turn_load=turn_load, preload=preload, exact=exact, top=float(grid[-1]),
                       static_friction=static, normal_load=normal)  # fmt: skip

    def pads(self, turn: float | None = None) -> PullOff:
        """Each pad of a cycle run (one per realization): its turn, its pull-off and its static
        friction there, :meth:`pull_off` with ``friction`` (``static_friction``,
        ``normal_load``, ``mu_static``; docs/physics.md, 'Friction of pads')."""
        return self.pull_off(turn, friction=True)

    def to_dataframe(self):
        """Tidy table: one row per (source, realization, h, quantity).

        Columns: ``source`` (``realization``, ``mean``, ``se``, ``std``, ``se_between``
        or ``analytic``), ``realization`` (index, -1 for the others), ``h`` (d/σ), ``d``
        (m), for a cycle run ``branch`` (``approach``/``retract``), ``quantity``,
        ``value``, ``unit``. Values are dimensionless: N_c/N (Eq. 1), force/(A·K) for
        P, F, T (Eqs. 3, 5, 7) and T/(P+F) for μ (Eq. 8); for the other law sets
        load/(A K), area/A, friction/(A K) and friction/load; ``unit`` spells out the
        normalisation.
        """
        import pandas as pd

        spec = self.spec
        rows = {"h": spec.row_h, "d": np.tile(self.d, len(spec.branches))}
        if spec.cycle:
            rows["branch"] = spec.row_branch

        def frame(source, realization, q, values):
            return pd.DataFrame({"source": source, "realization": realization, **rows,
                                 "quantity": q, "value": values, "unit": self.normalisation(q)})  # fmt: skip

        frames = []
        for q in self.quantities:
            frames += [
                frame("realization", r, q, row) for r, row in enumerate(self.realizations[q])
            ]
            frames += [frame(stat, -1, q, getattr(self.summary, stat)[q]) for stat in STATS]
            frames.append(frame("analytic", -1, q, self.analytic[q]))
        return pd.concat(frames, ignore_index=True)


#: Progress-bar steps of :meth:`Run.pull_off` on a pool: the pads in that many waves of one
#: contiguous range a worker (in this process: one pad a step).
_ROUNDS = 4


def _ranges(n: int, parts: int) -> list[tuple[int, int]]:
    """``parts`` contiguous ranges of ``range(n)`` (fewer where ``n`` is smaller), in order."""
    k = max(1, min(n, parts))
    return [(i * n // k, (i + 1) * n // k) for i in range(k)]


def _pad_range(spec: MonteCarloSpec, stored: np.ndarray, lo: int, turn: float | None,
               preload: float | None, friction: bool) -> tuple[np.ndarray, ...]:  # fmt: skip
    """Pads ``lo`` … ``lo + len(stored)`` − 1 of :meth:`Run.pull_off` (``stored``: their
    approach sums): pull-off (N), its d/σ, the turn d/σ, the load there (N, NaN without
    ``preload``), static friction and normal load (N, NaN without ``friction``)."""
    from mcsim.engine.pads import curves as padcurves
    from mcsim.engine.pads import friction as padfriction
    from mcsim.engine.pads import load as padload

    sigma, n = spec.surface.sigma, len(stored)
    out = [np.empty(n), np.empty(n), np.full(n, spec.turn if turn is None else turn)]
    out += [np.full(n, np.nan) for _ in range(3)]
    force, h, h_turn, turn_load, static, normal = out
    for i in range(n):
        z = padload.patch_heights(spec, lo + i)
        _check_regenerated(spec, lo + i, z, stored[i])
        if preload is not None:
            d_t, turn_load[i] = padcurves.force_turn(spec, z, preload * spec.area)
            h_turn[i] = d_t / sigma
        force[i], d_off = padcurves.pull_off(spec, z, h_turn[i] * sigma)
        h[i] = d_off / sigma
        if friction:
            applied = None if preload is None else preload * spec.area
            static[i] = padfriction.static_friction(spec, z, h_turn[i] * sigma)
            normal[i] = padfriction.normal_load(spec, z, h_turn[i] * sigma, applied)
    return force, h, h_turn, turn_load, static, normal


def _check_regenerated(spec: MonteCarloSpec, r: int, z: np.ndarray, stored: np.ndarray) -> None:
    """Refuse heights drawn again that do not give the run's own approach sums (1e-9 relative)."""
    from mcsim.engine.pads.load import pad_load

    again = pad_load(spec, z, spec.d)
    scale = np.max(np.abs(stored), initial=0.0)
    if not np.allclose(again, stored, rtol=1e-9, atol=1e-9 * scale):
        raise ParameterError(f"realization {r}: the summit heights drawn again from the seed do "
                             "not reproduce the run's sums (another NumPy version's sampler?)")  # fmt: skip


def assemble(ens: EnsembleSums, **kwargs) -> Run:
    """Statistics and GW expectations of a complete ensemble, as a :class:`Run` (with an
    environment, its open gaps' curves too)."""
    spec = ens.spec
    return Run(
        environment=environment_run(spec),
        ensemble=ens,
        realizations=per_realization(ens),
        summary=summarize(ens),
        analytic=expected_values(spec, branch_curves(spec)),
        heights=ens.heights,
        **kwargs,
    )


def branch_curves(spec: MonteCarloSpec, h=None) -> list:
    """GW curves of each branch of ``spec`` (at ``h``, by default the run's), with
    retraction after the closest approach min(spec.h).

    Where :func:`mcsim.physics.analytic.analytic_curves` cannot give a law set's curves (no
    branches), the values are NaN (no comparison; the table says so).
    """
    h = spec.h if h is None else np.asarray(h, dtype=float)
    if "branch" in inspect.signature(analytic_curves).parameters:
        return [
            analytic_curves(
                spec.surface,
                spec.material,
                h,
                law=spec.law_set,
                branch=b,
                **({"turn": spec.turn} if b == "retract" else {}),
            )
            for b in spec.branches
        ]
    if spec.law_set.stateful or not {"P", "F", "T"} <= set(spec.law_set.names):
        nan = np.full(h.shape, np.nan)
        names = quantities(spec.law_set, spec.material)
        return [types.SimpleNamespace(**dict.fromkeys(names, nan)) for _ in spec.branches]
    return [analytic_curves(spec.surface, spec.material, h, spec.law)] * len(spec.branches)
