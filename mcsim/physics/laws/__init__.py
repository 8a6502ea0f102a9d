"""Law sets: the per-summit contact models, interchangeable parts of the engine.

See docs/physics.md, section 'Contact law sets'.

A :class:`LawSet` names pure, vectorised functions of the interference δ = z − d (m),
its **outputs** (the seed: P, F, T; the new sets: ``load`` and ``area``), and its
**edges**: where a summit carries force at all. The analytic integrals and the
Monte Carlo kernel call the same functions, so a law set plugs in here without
touching either.

Calling convention of an output function::

    f(delta, *params)              # stateless laws (the seed)
    f(delta, delta_max, *params)   # contact models with approach and retraction

``params`` are looked up by name in :func:`contact_parameters` merged with the law
set's own ``constants(surface, material)``. ``delta_max`` is the largest interference
the summit has reached: δ itself on approach, z − d_turn on retraction after the
closest approach d_turn. A summit is *in contact* when ``delta_max > jump_in`` and
``delta > break_off`` (:class:`Edges`); out of contact it may still feel a
non-contact attraction down to ``delta > reach``. Every function must return finite
values for every finite input (the kernel and the quadrature evaluate them only where
the edges say a force may act, but vectorised callers evaluate everywhere).

**Pads.** A law set with a retraction and an output ``load`` (a pad's contact law,
:mod:`mcsim.engine.pads.curves`) must also have, on each branch, a *quasiconvex* load: as δ
grows it is 0 up to the branch's lowest edge (``reach`` on approach, min(``reach``,
``break_off``) on retraction), then does not rise (it may jump down and fall) to its
minimum, then does not fall. On retraction a summit in contact at the turn (δ_max >
``jump_in``) follows a branch that does not depend on δ_max, and one out of contact keeps
its approach load. A humid pad's search bounds its load on these
(:func:`mcsim.engine.pads.bounds.branches`); tests/engine/test_padcurves.py checks them for
every registered law set.

Law functions are restricted to a small vocabulary so that the same source also
compiles as a CUDA device function: arithmetic, comparisons, ``np.sqrt``,
``np.cbrt``, ``np.exp``, ``np.log``, ``np.abs``, ``np.maximum``, ``np.minimum``,
``np.floor``, ``np.arctan``, ``np.cos``, ``np.arccos``, ``np.pi``, ``np.int64``, the bit
casts of :mod:`mcsim.physics.laws.ieee` and integer shifts and masks, and indexing 1-D float
arrays passed as parameters. No ``np.where``, no Python ``if``/``while`` on array
values.

A law function may call **helpers**: functions defined at module level in its own law
file, written in the same vocabulary (and which may call further helpers there), so that
a formula two outputs share is written once (the JKR inversion, the elastic–plastic
power). :func:`helpers` finds them by the names the function uses. As written they are
NumPy like the laws; the CPU kernel compiles each into the law that calls it (numba,
inlined), the GPU kernel as a CUDA device function (:mod:`mcsim.engine.kernels`,
:mod:`mcsim.engine.cuda`). No other Python function may be called.
"""

from __future__ import annotations

import difflib
import functools
import inspect
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface
from mcsim.physics.laws import seed

Law = Callable[..., np.ndarray]
BRANCHES = ("approach", "retract")


def helpers(fn: Law) -> tuple[Callable, ...]:
    """The helpers law function ``fn`` calls, directly or through one another: the
    functions of ``fn``'s own module that it names as globals, in the order first named
    (the module docstring)."""
    found: list[Callable] = []
    pending = [fn]
    while pending:
        f = pending.pop(0)
        for name in f.__code__.co_names:
            value = f.__globals__.get(name)
            if (
                inspect.isfunction(value)
                and value.__module__ == fn.__module__
                and value is not fn
                and value not in found
            ):
                found.append(value)
                pending.append(value)
    return tuple(found)


def contact_parameters(surface: Surface, material: Material) -> dict[str, float | None]:
    """The named parameters a law may take after δ (and δ_max), in SI units.

    ``R`` (m), ``K``, ``G``, ``E_star`` (Pa), ``gamma`` (the work of adhesion w,
    J/m²), ``nu`` (softer solid), and the optional ``H`` (Pa), ``z0`` (m), ``tau`` (Pa).
    """
    return {
        "R": surface.R,
        "K": material.K,
        "G": material.G,
        "E_star": material.E_star,
        "gamma": material.gamma,
        "nu": material.nu,
        "H": material.H,
        "z0": material.z0,
        "tau": material.tau,
    }


@dataclass(frozen=True)
class Output:
    """One per-summit quantity of a law set.

    Attributes
    ----------
    name : str
        Column name (``P``, ``load``, ``area``, ...).
    unit : str
        SI unit of one summit's value (``N``, ``m^2``).
    law : callable
        The per-summit function (see the module docstring for its signature).
    description : str
        One line for help texts and run files.
    """

    name: str
    unit: str
    law: Law
    description: str = ""

    @property
    def stateful(self) -> bool:
        """Whether the function takes ``delta_max`` (a contact model with branches)."""
        params = _parameters(self.law)
        return len(params) > 1 and params[1] == "delta_max"

    @property
    def parameter_names(self) -> tuple[str, ...]:
        """Names of the parameters after δ (and δ_max)."""
        return _parameters(self.law)[2 if self.stateful else 1 :]


@functools.cache
def _parameters(fn: Law) -> tuple[str, ...]:
    """Names of law function ``fn``'s parameters, read once (``inspect.signature`` costs
    ~50 µs, and every call of the kernel asks)."""
    return tuple(inspect.signature(fn).parameters)


@dataclass(frozen=True)
class Edges:
    """Interferences bounding where a summit carries force, m.

    Attributes
    ----------
    reach : float
        Most negative δ at which a summit out of contact still feels a force
        (non-contact attraction); no force for δ ≤ reach. ``reach <= jump_in``.
    jump_in : float
        On approach a summit is in contact for δ > jump_in.
    break_off : float
        On retraction a summit that was in contact (δ_max > jump_in) stays in
        contact for δ > break_off (``break_off <= jump_in``; JKR: δ_c < 0).
    breakpoints : tuple of float
        Interferences where an output is not smooth (kinks, jumps, table ends), for
        the quadrature's panel edges. The edges above need not be repeated.
    """

    reach: float = 0.0
    jump_in: float = 0.0
    break_off: float = 0.0
    breakpoints: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        if not (self.reach <= self.jump_in and self.break_off <= self.jump_in):
            raise ValueError(f"inconsistent edges {self}")

    def threshold(self, d, d_turn):
        """Lowest summit height z that can carry force at separation ``d`` after the
        closest approach ``d_turn`` (``d_turn = d`` on approach), m.

        A pair carries force if δ > reach, or if it is in contact on retraction:
        z − d_turn > jump_in and z − d > break_off. The union is z > threshold.
        """
        return np.minimum(d + self.reach, np.maximum(d_turn + self.jump_in, d + self.break_off))

    def in_contact(self, delta, delta_max):
        """Whether a summit at ``delta`` with history ``delta_max`` is in contact."""
        return (delta_max > self.jump_in) & (delta > self.break_off)

    @staticmethod
    def widest(edges: list[Edges]) -> Edges:
        """Edges that every summit of any of ``edges`` lies within: the lowest reach, jump-in
        and break-off (a threshold at or below each one's), all breakpoints. One: itself."""
        if len(edges) == 1:
            return edges[0]
        return Edges(min(e.reach for e in edges), min(e.jump_in for e in edges),
                     min(e.break_off for e in edges),
                     tuple(sorted({b for e in edges for b in e.breakpoints})))  # fmt: skip


def _no_constants(surface: Surface, material: Material) -> dict:
    return {}


def _touching(params: Mapping) -> Edges:
    return Edges()


@dataclass(frozen=True)
class LawSet:
    """A contact model: per-summit outputs, their parameters and their edges.

    Attributes
    ----------
    name : str
        Registry name (``--law``).
    description : str
        One line for help texts and run files.
    outputs : tuple of Output
        The per-summit quantities, in column order.
    edges : callable
        ``edges(params) -> Edges`` from the merged parameter mapping (SI).
    constants : callable
        ``constants(surface, material) -> dict`` of derived parameters (floats or 1-D
        float arrays, e.g. a tabulated dimensionless curve), merged into the
        parameters the output functions take by name.
    requires : tuple of str
        Material fields that must be given (``"z0"``, ``"H"``, ...); ``z0`` only with
        adhesion (w > 0).
    retract : bool
        Whether the retraction branch is implemented (elastic-plastic: no).
    friction : bool
        Whether friction is τ·area (Bowden–Tabor) when the material gives τ.
    legacy_kernel : bool
        Compile the Monte Carlo kernel exactly as mcsim 0.1 did (numba's default error
        model, each output's parameter tuple passed whole): the seed's sums are pinned
        bit for bit, and the other kernel's code, vectorised differently, adds them in
        another order (see :mod:`mcsim.engine.kernels`).
    """

    name: str
    description: str
    outputs: tuple[Output, ...]
    edges: Callable[[Mapping], Edges] = _touching
    constants: Callable[[Surface, Material], dict] = _no_constants
    requires: tuple[str, ...] = ()
    retract: bool = True
    friction: bool = False
    legacy_kernel: bool = False

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(o.name for o in self.outputs)

    @property
    def laws(self) -> tuple[Law, ...]:
        return tuple(o.law for o in self.outputs)

    @property
    def stateful(self) -> bool:
        """Whether the outputs take ``delta_max`` (approach and retraction differ)."""
        return any(o.stateful for o in self.outputs)

    def parameters(self, surface: Surface, material: Material) -> dict:
        """All named parameters (SI), after checking the required material fields."""
        for req in self.requires:
            # z0 is the range of the attraction: without adhesion (w = 0) nothing to range
            if getattr(material, req) is None and not (req == "z0" and material.gamma == 0):
                raise ParameterError(
                    f"law set {self.name!r} needs material field {req!r}, which is not given"
                )
        return {**contact_parameters(surface, material), **self.constants(surface, material)}

    def arguments(self, surface: Surface, material: Material) -> tuple[tuple, ...]:
        """Positional parameters after δ (and δ_max) for each output function."""
        params = self.parameters(surface, material)
        return tuple(tuple(params[p] for p in o.parameter_names) for o in self.outputs)

    def edges_for(self, surface: Surface, material: Material) -> Edges:
        """The :class:`Edges` of this law set for a surface and material, m."""
        return self.edges(self.parameters(surface, material))

    def check_branch(self, branch: str) -> None:
        if branch not in BRANCHES:
            raise ParameterError(f"branch = {branch!r} is not one of {', '.join(BRANCHES)}")
        if branch == "retract" and not self.retract:
            raise ParameterError(
                f"law set {self.name!r} has no retraction branch (history-dependent "
                "unloading is not implemented); use --law jkr, dmt or maugis-dugdale"
            )

    def evaluate(
        self,
        delta,
        surface: Surface,
        material: Material,
        branch: str = "approach",
        delta_max=None,
    ) -> dict[str, np.ndarray]:
        """Per-summit outputs at interference ``delta`` (m), vectorised.

        Parameters
        ----------
        delta : array_like
            Interference δ = z − d, m.
        surface, material : Surface, Material
            The contact.
        branch : {"approach", "retract"}
            On approach δ_max = δ. On retraction δ_max defaults to +inf (the summit
            was pressed in at the turn), or give it.
        delta_max : array_like, optional
            Largest interference reached, m (retraction only).

        Returns
        -------
        dict
            Output name → value per summit in its unit (see :attr:`outputs`).
        """
        self.check_branch(branch)
        delta = np.asarray(delta, dtype=float)
        if branch == "approach" or delta_max is None:
            delta_max = delta if branch == "approach" else np.full_like(delta, np.inf)
        delta_max = np.broadcast_to(np.asarray(delta_max, dtype=float), delta.shape)
        out = {}
        for o, args in zip(self.outputs, self.arguments(surface, material)):
            value = o.law(delta, delta_max, *args) if o.stateful else o.law(delta, *args)
            out[o.name] = np.asarray(value, dtype=float)
        return out

    def forces(self, delta, surface: Surface, material: Material) -> np.ndarray:
        """All outputs on approach, stacked: shape ``(len(outputs), ...)``."""
        return np.stack(list(self.evaluate(delta, surface, material).values()))


SEED = LawSet(
    name="seed",
    description="the paper as written: Hertz (Eq. 2), Johnson (Eq. 4), Savkoor-Briggs (Eq. 6)",
    outputs=(
        Output("P", "N", seed.hertz_load, "Hertz load (Eq. 2)"),
        Output("F", "N", seed.johnson_adhesion, "JKR adhesion term P1 - P (Eq. 4)"),
        Output("T", "N", seed.savkoor_briggs_friction, "Savkoor-Briggs friction (Eq. 6)"),
    ),
    legacy_kernel=True,
)

LAW_SETS: dict[str, LawSet] = {SEED.name: SEED}


def register(law: LawSet) -> LawSet:
    """Add a law set to the registry (``--law NAME``)."""
    LAW_SETS[law.name] = law
    return law


def get_law_set(law: str | LawSet) -> LawSet:
    """Look up a law set by name (or pass one through)."""
    if isinstance(law, LawSet):
        return law
    try:
        return LAW_SETS[law]
    except (KeyError, TypeError):
        close = difflib.get_close_matches(str(law), LAW_SETS, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ParameterError(
            f"unknown law set {law!r} (allowed: {', '.join(sorted(LAW_SETS))}){hint}"
        ) from None


# The contact models beyond the seed register themselves here (``--law NAME``).
from mcsim.physics.laws import dmt, elastic_plastic, jkr, maugis_dugdale  # noqa: E402

register(jkr.LAW_SET)
register(dmt.LAW_SET)
register(maugis_dugdale.LAW_SET)
register(elastic_plastic.LAW_SET)
