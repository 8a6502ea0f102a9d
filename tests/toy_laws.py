"""A test-local contact law set with every feature the engine must handle.

JKR-like break-off below the jump-in (a square-root edge), DMT-like van der Waals
attraction out of contact down to a reach, and a declared kink: a stand-in for the
real contact models in tests of the integrals, the adhesion summary and the CLI.
"""

import dataclasses

import numpy as np

from mcsim import Empirical
from mcsim.model.presets import MATERIALS
from mcsim.physics.laws import Edges, LawSet, Output

Z0 = 0.3e-9
MATERIAL = dataclasses.replace(MATERIALS["silicon"], z0=Z0, tau=1e8)


def toy_load(delta, delta_max, R, E_star, gamma, z0):
    """Compressive when pressed, tensile at the edge, a van der Waals tail out of contact, N."""
    c = 0.5 * z0
    contact = (delta_max > 0.0) * (delta > -c)
    x = np.maximum(delta + c, 0.0)
    kink = np.maximum(delta - 2 * z0, 0.0)
    pressed = 4 / 3 * E_star * np.sqrt(R) * (x * np.sqrt(x) + kink * np.sqrt(kink))
    pressed = pressed - np.pi * gamma * R * (2.0 - np.sqrt(x / c))
    gap = z0 - np.minimum(delta, 0.0)
    attraction = (delta > -9 * z0) * (-2 * np.pi * gamma * R * (z0 / gap) ** 2)
    return contact * pressed + (1 - contact) * attraction


def toy_area(delta, delta_max, R, z0):
    """π R (δ − δ_c) in contact, m²."""
    c = 0.5 * z0
    contact = (delta_max > 0.0) * (delta > -c)
    return contact * np.pi * R * np.maximum(delta + c, 0.0)


def toy_edges(params):
    z0 = params["z0"]
    return Edges(reach=-9 * z0, jump_in=0.0, break_off=-0.5 * z0, breakpoints=(2 * z0,))


TOY = LawSet(
    name="toy",
    description="test-local contact model with branches",
    outputs=(Output("load", "N", toy_load), Output("area", "m^2", toy_area)),
    edges=toy_edges,
    requires=("z0",),
    friction=True,
)


def skewed_histogram() -> Empirical:
    edges = np.linspace(-2.5, 3.5, 25)
    centre = (edges[:-1] + edges[1:]) / 2
    return Empirical.from_histogram(edges, np.exp(-0.5 * (centre - 0.3) ** 2) * (1 + centre / 4))
