"""What defines a Monte Carlo run, and so its numbers: :class:`MonteCarloSpec`, checked
on construction, with what follows from it (its law set with the environment's caps, the
law parameters and edges of each band of heights, its rows, the lowest height sampled).
The engine that runs one is :mod:`mcsim.engine.montecarlo`.
"""

from __future__ import annotations

import dataclasses
import functools
import weakref
from dataclasses import dataclass

import numpy as np

from mcsim.engine.kernels import sum_columns
from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface, check_range, check_separations
from mcsim.physics.environment import Environment
from mcsim.physics.laws import BRANCHES, Edges, LawSet, get_law_set
from mcsim.physics.surfaceenvironment import vdw_share, with_environment

COUNT_MODES = ("poisson", "fixed")

#: Where the blocks are sampled and summed: NumPy + numba on the CPU, or the GPU
#: (:mod:`mcsim.engine.cuda`, other random streams: the numbers differ from the CPU's).
DEVICES = ("cpu", "cuda")

#: Most expected summits per patch, E[N] = ηA: NumPy's Poisson sampler stops near 9.2e18,
#: and 1e18 summits would take decades at ~3e8 summits per second.
MAX_SUMMITS = 1e18

#: Most memory, bytes, that one run's per-realization state may take (its sums, counts and
#: plans, :func:`state_bytes`): the state is held whole, so a run past it is refused before
#: anything is planned rather than left to swap (10⁸ realizations at two separations would
#: need 20 GB). Runs that need more realizations are several runs with other seeds.
MAX_STATE_BYTES = 2**30


#: The specs unpickled in this process, each under its value while it lives (:func:`_unpickled`).
_UNPICKLED: weakref.WeakValueDictionary = weakref.WeakValueDictionary()


@dataclass(frozen=True, eq=False)
class MonteCarloSpec:
    """Everything that defines a Monte Carlo run (and so its numbers).

    Parameters
    ----------
    surface : Surface
        Summit population.
    material : Material
        Material pair.
    h : ndarray
        Dimensionless separations d/σ, any order.
    area : float
        Nominal area of one patch, m².
    realizations : int
        Number of independent patches.
    entropy : int
        Seed entropy of the root :class:`numpy.random.SeedSequence`.
    law : str
        Law-set name.
    count : {"poisson", "fixed"}
        N ~ Poisson(ηA) or N = round(ηA).
    cycle : bool
        Approach over ``h`` and then retraction back over the same ``h`` after the
        closest approach min(h) (both branches stored); approach only by default.
    device : {"cpu", "cuda"}
        Where the heights are drawn and the blocks summed (:data:`DEVICES`).
    environment : Environment or None
        Van der Waals and capillary attraction: each summit's cap adds the outputs ``vdw`` and
        ``capillary`` to the law set (:mod:`mcsim.physics.surfaceenvironment`), so the summits
        drawn reach down to the caps' band edge; the open gaps are a deterministic curve, not
        sampled. None (default): the contact alone.
    """

    surface: Surface
    material: Material
    h: np.ndarray
    area: float
    realizations: int
    entropy: int
    law: str = "seed"
    count: str = "poisson"
    cycle: bool = False
    device: str = "cpu"
    environment: Environment | None = None

    def __post_init__(self) -> None:
        h = check_separations(self.h).copy()  # its own, read-only: the spec's hash is cached
        h.flags.writeable = False
        object.__setattr__(self, "h", h)
        object.__setattr__(self, "area", check_range("area", self.area, "m^2", low=0))
        if self.surface.eta * self.area > MAX_SUMMITS:
            raise ParameterError(
                f"area = {self.area:.6g} m^2 holds E[N] = eta*area = {self.surface.eta * self.area:.3g} "
                f"summits per patch (allowed: at most {MAX_SUMMITS:.0e})"
            )
        check_count("realizations", self.realizations)
        if self.count not in COUNT_MODES:
            raise ParameterError(f"count = {self.count!r} is not one of {', '.join(COUNT_MODES)}")
        if self.count == "fixed" and round(self.surface.eta * self.area) < 1:
            raise ParameterError(
                f"area = {self.area!r} m^2 holds {self.surface.eta * self.area:.3g} summits: "
                "round(eta*area) must be >= 1 for count='fixed'"
            )
        law = get_law_set(self.law)
        if self.environment is not None and not isinstance(self.environment, Environment):
            raise ParameterError(f"environment = {self.environment!r} must be an Environment")
        if self.environment is not None and not self.environment.active:
            object.__setattr__(self, "environment", None)
        vdw_share(self.material.gamma, self.environment)  # one interface: refused if above w
        if self.environment is None:  # fields only the environment reads: not the run's inputs
            bare = dataclasses.replace(self.surface, rq=None, summit_offset=None, map_heights=None)
            object.__setattr__(self, "surface", bare)
        if not isinstance(self.cycle, bool | np.bool_):
            raise ParameterError(f"cycle = {self.cycle!r} must be True or False")
        object.__setattr__(self, "cycle", bool(self.cycle))
        if self.cycle:
            law.check_branch("retract")
        law.parameters(self.surface, self.material)  # required material fields
        per_realization = state_bytes(self, 1)
        if per_realization * self.realizations > MAX_STATE_BYTES:
            raise ParameterError(
                f"realizations = {self.realizations} need {per_realization * self.realizations:.3g} "
                f"bytes of per-realization state at {self.rows()[0].size} rows (allowed: at most "
                f"{MAX_STATE_BYTES // per_realization} realizations, {MAX_STATE_BYTES / 2**30:g} GiB; "
                "run several seeds instead)"
            )
        if self.device not in DEVICES:
            raise ParameterError(f"device = {self.device!r} is not one of {', '.join(DEVICES)}")
        if self.surface.radius_by_height is not None and self.device != "cpu":
            raise ParameterError(f"device = {self.device!r}: a summit radius by height is summed "
                                 "on the CPU only (device = 'cpu')")  # fmt: skip

    def fields(self) -> dict:
        """The defining inputs, comparable with ``==`` (h as a tuple)."""
        return {f.name: (tuple(self.h.tolist()) if f.name == "h" else getattr(self, f.name))
                for f in dataclasses.fields(self)}  # fmt: skip

    def __eq__(self, other: object) -> bool:
        return isinstance(other, MonteCarloSpec) and self.fields() == other.fields()

    def __hash__(self) -> int:
        return self._hash

    @functools.cached_property
    def _hash(self) -> int:
        """The hash of :meth:`fields`, computed once (the caches keyed by a spec look it up
        many times a pad, and the fields are immutable)."""
        return hash(tuple(self.fields().values()))

    def __getstate__(self) -> dict:
        """What pickles (a run sent to Dask's workers): not the cached hash, which another
        process (hashing strings with another seed) computes again."""
        return {k: v for k, v in self.__dict__.items() if k != "_hash"}

    def __reduce__(self) -> tuple:
        """Pickled as its :meth:`__getstate__`, unpickled by :func:`_unpickled`."""
        return _unpickled, (self.__getstate__(),)

    def differences(self, other: MonteCarloSpec) -> list[str]:
        """Names of the inputs that differ from ``other``."""
        a, b = self.fields(), other.fields()
        return [k for k in a if a[k] != b[k]]

    @property
    def d(self) -> np.ndarray:
        """Separations in m."""
        return self.h * self.surface.sigma

    @functools.cached_property
    def law_set(self) -> LawSet:
        """The law set, with the environment's per-summit outputs if there is one."""
        return with_environment(get_law_set(self.law), self.environment)

    @functools.cached_property
    def arguments(self) -> tuple[tuple, ...]:
        """The law functions' parameters (``law.arguments``), computed once per spec
        (a law set's constants may be a tabulated curve)."""
        return self.law_set.arguments(self.surface, self.material)

    @functools.cached_property
    def edges(self) -> Edges:
        """The law set's :class:`~mcsim.physics.laws.Edges` for these inputs, m; with a
        radius by height, the widest of its bands' (:meth:`Edges.widest`): where any summit
        may carry force."""
        return Edges.widest([edges for _, edges in self.parts])

    @functools.cached_property
    def parts(self) -> tuple[tuple[tuple, Edges], ...]:
        """The law functions' parameters and edges of each band of heights
        (:meth:`~mcsim.model.params.Surface.components`): one pair, or one per band of a
        radius by height (:func:`mcsim.engine.montecarlo.sums` sorts the summits into them)."""
        if self.surface.radius_by_height is None:
            return ((self.arguments, self.law_set.edges_for(self.surface, self.material)),)
        return tuple((self.law_set.arguments(part, self.material),
                      self.law_set.edges_for(part, self.material))
                     for part in self.surface.components())  # fmt: skip

    @property
    def branches(self) -> tuple[str, ...]:
        """``("approach",)``, or ``("approach", "retract")`` for a cycle."""
        return BRANCHES if self.cycle else BRANCHES[:1]

    @property
    def turn(self) -> float:
        """Closest approach of a cycle, min(h) (dimensionless, d/σ)."""
        return float(self.h.min())

    def rows(self) -> tuple[np.ndarray, np.ndarray]:
        """Separation d and closest approach d_turn (m) of every row of the sums: the
        approach rows (d_turn = d) in the order of ``h``, then with ``cycle`` the
        retraction rows (d_turn = σ·min(h)) in the same order."""
        d = self.d
        if not self.cycle:
            return d, d
        return np.concatenate([d, d]), np.concatenate([d, np.full_like(d, d.min())])

    @property
    def row_branch(self) -> np.ndarray:
        """Branch name of every row (see :meth:`rows`)."""
        return np.repeat(np.array(self.branches), self.h.size)

    @property
    def row_h(self) -> np.ndarray:
        """d/σ of every row (see :meth:`rows`)."""
        return np.tile(self.h, len(self.branches))

    @property
    def row_s(self) -> np.ndarray:
        """Lowest standardized summit height that can carry force at each row (for the
        seed, h itself): h + (threshold − d)/σ (:meth:`mcsim.physics.laws.Edges.threshold`)."""
        d, d_turn = self.rows()
        return self.row_h + (self.edges.threshold(d, d_turn) - d) / self.surface.sigma

    @functools.cached_property
    def s_min(self) -> float:
        """Lowest standardized height sampled: below it no summit carries force at any row."""
        return float(self.row_s.min())

    @property
    def expected_summits(self) -> float:
        """E[N] per patch."""
        n = self.surface.eta * self.area
        return float(round(n)) if self.count == "fixed" else n


def state_bytes(spec: MonteCarloSpec, realizations: int) -> int:
    """Bytes of the per-realization state of a run of ``spec`` with ``realizations``: the
    float64 sums (rows × columns), three int64 counts and a :class:`PatchPlan` (~100 bytes)."""
    columns = len(sum_columns(spec.law_set))
    return realizations * (8 * spec.rows()[0].size * columns + 3 * 8 + 100)


def check_count(name: str, value) -> None:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ParameterError(f"{name} = {value!r} is out of range (allowed: integer >= 1)")


def _unpickled(state: dict) -> MonteCarloSpec:
    """The spec of ``state``, or the equal one already unpickled in this process: a worker
    sent one chunk of pads after another holds one object, which the caches keyed by a spec
    (:mod:`mcsim.engine.pads`, looked up dozens of times a pad) find by identity; an equal
    but distinct spec costs a comparison of its fields (~12 µs) at every lookup, a quarter
    more time a pad (measured on the few-summit pads of validation/tail_benchmark.py)."""
    spec = object.__new__(MonteCarloSpec)
    spec.__dict__.update(state)
    return _UNPICKLED.setdefault(spec, spec)
