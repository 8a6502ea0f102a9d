"""The paper's inputs: silicon and the MEMS surfaces of its Table 1 (Tayebi & Polycarpou 2006).

The four *combined* surfaces are the paper's simulations A-D. The four individual
surfaces are Table 1's first half; combining them with
:func:`mcsim.model.params.combine_surfaces` reproduces the combined σ and R (η is given).
"""

from mcsim.model.errors import ParameterError
from mcsim.model.params import Material, Surface

#: Silicon on silicon as in the paper (E, ν, w = γ, H). The paper gives no equilibrium
#: spacing: z0 = 0.3 nm is an assumed default of the order of an interatomic distance
#: (the value issue 10 quotes; with it the Tabor parameter of the four Table-1
#: surfaces is 0.53–1.64, between DMT and JKR). Give ``z0`` in a material file to
#: change it. No τ: the new law sets report friction only when one is given.
MATERIALS: dict[str, Material] = {
    "silicon": Material(
        E1=160e9, E2=160e9, nu1=0.22, nu2=0.22, gamma=0.5, H=12.5e9, z0=0.3e-9, name="silicon"
    ),
}

#: Combined surfaces of Table 1 (simulations A-D) and the four individual surfaces.
SURFACES: dict[str, Surface] = {
    s.name: s
    for s in (
        Surface(sigma=15.8e-9, R=0.116e-6, eta=14.7e12, name="rough"),
        Surface(sigma=6.8e-9, R=0.45e-6, eta=11.1e12, name="intermediate"),
        Surface(sigma=1.4e-9, R=1.7e-6, eta=17e12, name="smooth"),
        Surface(sigma=0.42e-9, R=3.36e-6, eta=26e12, name="super-smooth"),
        Surface(sigma=14.3e-9, R=0.12e-6, eta=15e12, name="deposited-polysilicon"),
        Surface(sigma=6.7e-9, R=0.46e-6, eta=11e12, name="typical-substrate"),
        Surface(sigma=1.0e-9, R=2.4e-6, eta=17e12, name="polished-polysilicon"),
        Surface(sigma=0.3e-9, R=4.75e-6, eta=26e12, name="single-crystal-silicon"),
    )
}

#: The paper's four simulations, in its order (roughest first).
PAPER_SURFACES = ("rough", "intermediate", "smooth", "super-smooth")

#: Which individual surfaces make each combined one (Table 1, "1 on 2" etc.).
PAPER_PAIRS = {
    "rough": ("deposited-polysilicon", "typical-substrate"),
    "intermediate": ("typical-substrate", "polished-polysilicon"),
    "smooth": ("polished-polysilicon", "polished-polysilicon"),
    "super-smooth": ("single-crystal-silicon", "single-crystal-silicon"),
}


def as_surface(value: Surface | str, field: str = "surface") -> Surface:
    """``value`` if it is a :class:`Surface`, the preset of that name if it is one
    (``"smooth"``), else a ParameterError naming ``field`` and the presets."""
    return _as(value, Surface, SURFACES, field)


def as_material(value: Material | str, field: str = "material") -> Material:
    """``value`` if it is a :class:`Material`, the preset of that name (``"silicon"``), else
    a ParameterError naming ``field``."""
    return _as(value, Material, MATERIALS, field)


def _as(value, kind: type, presets: dict, field: str):
    if isinstance(value, kind):
        return value
    if isinstance(value, str) and value in presets:
        return presets[value]
    raise ParameterError(f"{field} must be a {kind.__name__} or a preset name "
                         f"({', '.join(presets)}), got {value!r}")  # fmt: skip
