"""A test-only law set exercising everything the engine must follow beyond the seed.

Stateful outputs (``delta_max``), a non-contact attraction (reach < 0), a break-off
below the jump-in (hysteresis), a stateless output beside stateful ones, a 1-D array
constant (a table, as Maugis–Dugdale passes one), and helpers (:func:`in_contact`, which
both stateful outputs call, and :func:`pressed`, which reads the table and calls
:func:`overlap`). No physics: only the kernel contract. Importable by the generated kernel
module (``tests`` is on ``sys.path``).
"""

import numpy as np

from mcsim.physics.laws import Edges, LawSet, Output


def in_contact(delta, delta_max, c):
    """1 in contact, 0 outside (a helper both stateful outputs call)."""
    return (delta_max > 0.0) * (delta > -c)


def overlap(delta, c):
    """max(δ + c, 0), m (a helper another helper calls)."""
    return np.maximum(delta + c, 0.0)


def pressed(delta, c, table):
    """x^{3/2} times the table's entry at x/c, x = :func:`overlap`, m^{3/2} (a helper
    taking an array)."""
    x = overlap(delta, c)
    i = np.int64(np.floor(np.minimum(x / c, 3.0)))
    return x * np.sqrt(x) * table[i]


def toy_load(delta, delta_max, R, K, c, table):
    """Signed load, N: compressive in contact, tensile within ``2c`` outside it."""
    contact = in_contact(delta, delta_max, c)
    near = (delta > -2.0 * c) * (1.0 - contact)
    return K * np.sqrt(R) * (contact * (pressed(delta, c, table) - c * np.sqrt(c))
                             - 30.0 * near * (delta + 2.0 * c) * np.sqrt(c))  # fmt: skip


def toy_area(delta, delta_max, R, c):
    """Contact area, m²: only in contact."""
    return in_contact(delta, delta_max, c) * np.pi * R * (delta + c)


def toy_grip(delta, R, gamma):
    """A stateless output, N."""
    return np.maximum(delta, 0.0) * np.pi * R * gamma / (1.0 + np.abs(delta) / R)


def toy_constants(surface, material):
    return {"c": 0.3 * surface.sigma, "table": np.array([1.0, 1.5, 2.0, 2.5])}


def toy_edges(params):
    c = params["c"]
    return Edges(reach=-2.0 * c, jump_in=0.0, break_off=-c, breakpoints=(-c,))


#: The same without a retraction branch (as elastic-plastic).
def _approach_only():
    import dataclasses

    return dataclasses.replace(TOY, name="toy-approach", retract=False)


TOY = LawSet(
    name="toy",
    description="test-only: stateful, attraction, hysteresis, array constant",
    outputs=(
        Output("load", "N", toy_load),
        Output("area", "m^2", toy_area),
        Output("grip", "N", toy_grip),
    ),
    edges=toy_edges,
    constants=toy_constants,
    friction=True,
)

TOY_APPROACH_ONLY = _approach_only()
