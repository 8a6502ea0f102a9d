"""Law sets: the per-summit force laws, interchangeable parts of the model.

A :class:`LawSet` names three pure functions of the interference δ: the load carried
by a summit, its adhesion term and its adhesional friction. The analytic integrals
and the Monte Carlo engine call the same functions, so a new law set (DMT, exact
JKR, ...) plugs in here without touching either. Each law takes δ first, then any
of the named contact parameters of :func:`contact_parameters`.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..params import Material, Surface
from . import seed

Law = Callable[..., np.ndarray]


def contact_parameters(surface: Surface, material: Material) -> dict[str, float]:
    """The named parameters a law may take after δ, in SI units.

    ``R`` (m), ``K``, ``G``, ``E_star`` (Pa) and ``gamma`` (J/m²).
    """
    return {
        "R": surface.R,
        "K": material.K,
        "G": material.G,
        "E_star": material.E_star,
        "gamma": material.gamma,
    }


@dataclass(frozen=True)
class LawSet:
    """Three per-summit laws of δ that together define a contact model.

    Attributes
    ----------
    name : str
        Registry name (``--law``).
    description : str
        One line for help texts and run files.
    load, adhesion, friction : callable
        ``f(delta, **params) -> force`` in N, zero for δ ≤ 0, vectorised.
    """

    name: str
    description: str
    load: Law
    adhesion: Law
    friction: Law

    @property
    def laws(self) -> tuple[Law, Law, Law]:
        return (self.load, self.adhesion, self.friction)

    def arguments(self, surface: Surface, material: Material) -> tuple[tuple[float, ...], ...]:
        """Positional parameters after δ for each of the three laws."""
        params = contact_parameters(surface, material)
        return tuple(
            tuple(params[p] for p in list(inspect.signature(law).parameters)[1:])
            for law in self.laws
        )

    def forces(self, delta, surface: Surface, material: Material) -> np.ndarray:
        """Load, adhesion and friction of summits pressed by ``delta`` (m), shape ``(3, ...)``, N."""
        return np.stack(
            [law(delta, *args) for law, args in zip(self.laws, self.arguments(surface, material))]
        )


SEED = LawSet(
    name="seed",
    description="the paper as written: Hertz (Eq. 2), Johnson (Eq. 4), Savkoor-Briggs (Eq. 6)",
    load=seed.hertz_load,
    adhesion=seed.johnson_adhesion,
    friction=seed.savkoor_briggs_friction,
)

LAW_SETS: dict[str, LawSet] = {SEED.name: SEED}


def get_law_set(law: str | LawSet) -> LawSet:
    """Look up a law set by name (or pass one through)."""
    if isinstance(law, LawSet):
        return law
    try:
        return LAW_SETS[law]
    except KeyError:
        raise ParameterError(
            f"unknown law set {law!r} (allowed: {', '.join(sorted(LAW_SETS))})"
        ) from None
