"""One pad's static friction at its own turn, and the normal load its μ_s is taken on.

See docs/physics.md, section 'Friction of pads'.

A pad's summits (:func:`mcsim.engine.pads.load.patch_heights`) stand still at the pad's closest
approach d_t (under force control its own turn, :func:`mcsim.engine.pads.curves.force_turn`).
Its static friction is the sum over the summits in contact there of each one's friction on
approach (δ_i = z_i − d_t), by the law set's rule (:func:`mcsim.physics.friction.friction_rule`:
Savkoor–Briggs or τ·area): T_s = Σ T_a(δ_i). With an environment the menisci and van der
Waals press the summits deeper, so their loads and areas, and T_s, rise: the environment is
in T_s through the turn and the contact law's loads, not as a term of its own. One NumPy
evaluation over the touching summits: a few per cent of a pad's pull-off search
(validation/pad_benchmark.py).

μ_s = T_s/W, W the normal load at the turn (:func:`normal_load`): the force pressing the pad,
P·A under force control (the pad's own net approach load at a common turn); where that is 0
(a pad resting under its own attraction, ``--preload 0``), the environment's pull at the turn,
which the contacts carry instead (:func:`attraction`); dry and unpressed there is no normal
load and μ_s is undefined (NaN).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from mcsim.engine.pads.load import contact_load, pad_load, summit_bands
from mcsim.engine.spec import MonteCarloSpec
from mcsim.physics.friction import friction_rule, summit_friction
from mcsim.physics.laws import LawSet, get_law_set
from mcsim.physics.surfaceenvironment import contact_law


@functools.lru_cache(maxsize=16)
def _parts(spec: MonteCarloSpec) -> tuple[str, LawSet, tuple[dict, ...]]:
    """The friction rule, the contact law (with an environment, less its van der Waals share)
    and its parameters for each band of heights of ``spec``."""
    law = contact_law(get_law_set(spec.law), spec.environment)
    rule = friction_rule(law, spec.material)
    params = tuple(law.parameters(part, spec.material) for part in spec.surface.components())
    return rule, law, params


def check_friction(spec: MonteCarloSpec) -> str:
    """The friction rule of ``spec``'s law set and material (raises ParameterError without one)."""
    return _parts(spec)[0]


def static_friction(spec: MonteCarloSpec, z: np.ndarray, d_turn: float) -> float:
    """T_s (N): the static friction of the pad of summits ``z`` (m) at its turn ``d_turn`` (m),
    the sum of its touching summits' (module docstring)."""
    rule, law, params = _parts(spec)
    band = summit_bands(spec, z)
    return float(sum(np.sum(summit_friction(law, p, z[band == k] - d_turn, rule))
                     for k, p in enumerate(params)))  # fmt: skip


def attraction(spec: MonteCarloSpec, z: np.ndarray, d_turn: float) -> float:
    """The environment's pull (N, > 0 attractive) on the pad of summits ``z`` (m) at ``d_turn``
    (m): its caps' and open gaps' attraction, the contact load less the net load; 0 dry."""
    if spec.environment is None:
        return 0.0
    return float(contact_load(spec, z, [d_turn])[0] - pad_load(spec, z, [d_turn])[0])


def normal_load(spec: MonteCarloSpec, z: np.ndarray, d_turn: float,
                applied: float | None = None) -> float:  # fmt: skip
    """W (N), the normal load μ_s is taken on (module docstring): ``applied`` (P·A under force
    control; default the pad's net approach load at ``d_turn``) where it is positive, else the
    environment's pull at the turn (:func:`attraction`); NaN where that is 0 too."""
    if applied is None:
        applied = float(pad_load(spec, z, [d_turn])[0])
    if applied > 0:
        return float(applied)
    pull = attraction(spec, z, d_turn)
    return pull if pull > 0 else math.nan
