"""Parameters of a contact: the material pair and the rough surface (paper, Eqs. 2-7).

Small frozen dataclasses, SI units, validated on construction. Derived quantities
(K, G, E*, the dimensionless groups of Eq. 5, the plasticity index) are properties,
never stored twice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .distributions import GAUSSIAN, HeightDistribution
from .errors import ParameterError


def check_range(
    name: str,
    value: float,
    unit: str,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = True,
    high_open: bool = True,
) -> float:
    """Return ``value`` as a float if it is finite and inside the range, else raise.

    The message names the field, the value (with its SI unit) and the allowed range.
    """
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number, got {value!r}") from None
    if low is not None and high is not None:
        allowed = f"{'(' if low_open else '['}{low:g}, {high:g}{')' if high_open else ']'}"
    elif low is not None:
        allowed = f"{'>' if low_open else '>='} {low:g}"
    else:
        allowed = "finite"
    bad = not math.isfinite(value)
    bad |= low is not None and (value <= low if low_open else value < low)
    bad |= high is not None and (value >= high if high_open else value > high)
    if bad:
        u = "" if unit == "1" else f" {unit}"
        raise ParameterError(f"{name} = {value!r}{u} is out of range (allowed: {allowed}{u})")
    return value


@dataclass(frozen=True)
class Material:
    """Elastic and adhesive properties of a pair of contacting solids.

    Parameters
    ----------
    E1, E2 : float
        Young's moduli of the two solids, Pa.
    nu1, nu2 : float
        Poisson's ratios, in (-1, 0.5).
    gamma : float
        Work of adhesion w used by Eqs. 4 and 6, J/m². The paper calls it the work
        of adhesion in the introduction and a "surface energy" in the results; its
        formulas use it as the work of adhesion (for two identical clean surfaces
        w = 2 γ_s). mcsim uses it as written.
    H : float or None
        Indentation hardness of the softer solid, Pa. Given in the paper but unused
        by its elastic model; used by the ``elastic-plastic`` law set and the
        plasticity index.
    z0 : float or None
        Equilibrium spacing of the surface interaction, m (``dmt``,
        ``maugis-dugdale`` and the Tabor parameter).
    tau : float or None
        Interfacial shear strength, Pa: friction τ·A_r of the new law sets
        (Bowden–Tabor); no friction is reported without it.
    name : str
        Label for output files and plots.
    """

    E1: float
    E2: float
    nu1: float
    nu2: float
    gamma: float
    H: float | None = None
    name: str = ""
    z0: float | None = None
    tau: float | None = None

    def __post_init__(self) -> None:
        for attr in ("E1", "E2"):
            object.__setattr__(self, attr, check_range(attr, getattr(self, attr), "Pa", low=0))
        for attr in ("nu1", "nu2"):
            object.__setattr__(
                self, attr, check_range(attr, getattr(self, attr), "1", low=-1, high=0.5)
            )
        object.__setattr__(
            self, "gamma", check_range("gamma", self.gamma, "J/m^2", low=0, low_open=False)
        )
        if self.H is not None:
            object.__setattr__(self, "H", check_range("H", self.H, "Pa", low=0))
        if self.z0 is not None:
            object.__setattr__(self, "z0", check_range("z0", self.z0, "m", low=0))
        if self.tau is not None:
            object.__setattr__(self, "tau", check_range("tau", self.tau, "Pa", low=0))

    @property
    def nu(self) -> float:
        """Poisson's ratio of the softer solid (the lower E), as used by Kogut & Etsion."""
        return self.nu1 if self.E1 <= self.E2 else self.nu2

    @property
    def K(self) -> float:
        """Paper's elastic constant K, Pa: 1/K = ¾[(1−ν1²)/E1 + (1−ν2²)/E2] (after Eq. 2).

        K = (4/3) E*, so that the Hertz load is P = K R^½ δ^{3/2}.
        """
        return 1.0 / (0.75 * ((1 - self.nu1**2) / self.E1 + (1 - self.nu2**2) / self.E2))

    @property
    def E_star(self) -> float:
        """Contact modulus E* = ¾ K, Pa (Johnson's 1/E* = Σ (1−ν²)/E)."""
        return 0.75 * self.K

    @property
    def G(self) -> float:
        """Combined shear modulus of Eq. 7, Pa: 1/G = (2−ν1)/G1 + (2−ν2)/G2, G_i = E_i/(2(1+ν_i))."""
        G1 = self.E1 / (2 * (1 + self.nu1))
        G2 = self.E2 / (2 * (1 + self.nu2))
        return 1.0 / ((2 - self.nu1) / G1 + (2 - self.nu2) / G2)


@dataclass(frozen=True)
class Surface:
    """A Greenwood–Williamson population of spherical summits (the combined surface).

    Parameters
    ----------
    sigma : float
        Standard deviation of the summit heights σ, m.
    R : float
        Summit radius of curvature, m.
    eta : float
        Areal density of summits η, m⁻².
    heights : HeightDistribution
        Shape of the summit-height distribution in units of σ (zero mean, unit
        standard deviation). Gaussian by default, as in the paper.
    name : str
        Label for output files and plots.
    """

    sigma: float
    R: float
    eta: float
    heights: HeightDistribution = field(default=GAUSSIAN)
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "sigma", check_range("sigma", self.sigma, "m", low=0))
        object.__setattr__(self, "R", check_range("R", self.R, "m", low=0))
        object.__setattr__(self, "eta", check_range("eta", self.eta, "m^-2", low=0))

    @property
    def A0(self) -> float:
        """Dimensionless roughness parameter A0 = η R σ (Eq. 5)."""
        return self.eta * self.R * self.sigma

    @property
    def R0(self) -> float:
        """Dimensionless radius R0 = R/σ (Eq. 5)."""
        return self.R / self.sigma


def surface_energy_parameter(surface: Surface, material: Material) -> float:
    """Dimensionless surface-energy parameter B0 = γ/(K σ) (Eq. 5)."""
    return material.gamma / (material.K * surface.sigma)


def plasticity_index(surface: Surface, material: Material) -> float | None:
    """Greenwood–Williamson plasticity index ψ = (E*/H) √(σ/R), or None without H.

    ψ ≲ 0.6: contacts mostly elastic; ψ ≳ 1: mostly plastic, where the paper's
    purely elastic model is questionable (Greenwood & Williamson 1966).
    """
    if material.H is None:
        return None
    return material.E_star / material.H * math.sqrt(surface.sigma / surface.R)


def combine_surfaces(first: Surface, second: Surface, eta: float, name: str = "") -> Surface:
    """Combined surface of two rough surfaces, as in the paper's Table 1.

    σ = √(σ1² + σ2²) and R = (R1⁻² + R2⁻²)^(−½): these reproduce every combined row
    of Table 1 (the usual sum-of-curvatures rule 1/R = 1/R1 + 1/R2 does not). The
    combined summit density cannot be derived from the two surfaces: give it.

    Parameters
    ----------
    first, second : Surface
        The two rough surfaces (Gaussian heights).
    eta : float
        Summit density of the combined surface, m⁻².
    name : str
        Label of the result.
    """
    sigma = math.hypot(first.sigma, second.sigma)
    R = (first.R**-2 + second.R**-2) ** -0.5
    return Surface(sigma=sigma, R=R, eta=eta, name=name)
