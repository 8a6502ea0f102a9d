"""Parameters of a contact: the material pair and the rough surface (paper, Eqs. 2-7).

Small frozen dataclasses, SI units, validated on construction. Derived quantities
(K, G, E*, the dimensionless groups of Eq. 5, the plasticity index) are properties,
never stored twice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from mcsim.model.distributions import GAUSSIAN, Band, HeightDistribution
from mcsim.model.errors import ParameterError
from mcsim.model.units import SI_UNITS, parse_quantity

#: Dimension of each SI unit a range is stated in (to read quantity strings).
_DIMENSION = {unit: dimension for dimension, unit in SI_UNITS.items()}

#: Accepted ranges (closed, SI) of the inputs: wide enough for any real solid and rough
#: surface (soft gels to diamond; sub-ångström to centimetre roughness), narrow enough
#: that every analytic and Monte Carlo output is a finite float (tests/test_edges.py
#: checks the corners). Values outside are refused, not silently turned into inf or NaN.
RANGES: dict[str, tuple[float, float, str]] = {
    "E": (1.0, math.inf, "Pa"),  # a huge E2 models a rigid counterface
    "K": (0.0, 1e14, "Pa"),  # so K and G (at most ~K) stay below this
    "H": (1.0, 1e13, "Pa"),
    "gamma": (0.0, 1e3, "J/m^2"),
    "sigma": (1e-12, 1e-2, "m"),
    "R": (1e-10, 10.0, "m"),
    "eta": (1.0, 1e20, "m^-2"),
}
#: Largest |h| = |d|/σ accepted: the quadrature of the GW integrals keeps ~1e-11 relative
#: accuracy up to here (it loses digits as |h| grows; see tests/test_analytic.py), and
#: no physical separation is a million σ.
MAX_ABS_H = 1e6


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
    A string is read as a quantity with a unit (``"160 GPa"``, ``"1.4nm"``; a bare number
    is SI), as on the command line and in TOML files (:func:`mcsim.model.units.parse_quantity`).
    """
    if isinstance(value, bool | np.bool_):  # a flag, not a number: float(True) would be 1
        raise ParameterError(f"{name} must be a number, got {value!r}")
    if isinstance(value, str):
        value = parse_quantity(value, _DIMENSION[unit], name)
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number, got {value!r}") from None
    except OverflowError:  # an integer beyond the largest float
        value = math.inf if value > 0 else -math.inf
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


def check_seed(seed) -> int | None:
    """A root seed as NumPy's ``SeedSequence`` takes it: None (fresh entropy) or a whole
    number >= 0; anything else raises, naming the field."""
    if seed is None:
        return None
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise ParameterError(f"seed = {seed!r} is out of range (allowed: None or an integer >= 0)")
    return int(seed)


def _in_range(name: str, value: float, kind: str | None = None) -> float:
    """``value`` checked against :data:`RANGES` (``kind`` names the entry, default ``name``)."""
    low, high, unit = RANGES[kind or name]
    high = None if high == math.inf else high
    return check_range(name, value, unit, low=low, high=high, low_open=False, high_open=False)


def check_separations(h) -> np.ndarray:
    """Separations h = d/σ as a non-empty 1-D float array; raise unless finite with |h| <= 1e6.

    Parameters
    ----------
    h : array_like
        Dimensionless separations d/σ.
    """
    if h is None:
        raise ParameterError("h must be a list of separations d/sigma, got None")
    try:
        values = np.atleast_1d(np.asarray(h, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError(f"h must be a list of numbers, got {h!r}") from None
    if values.ndim != 1 or values.size == 0:
        raise ParameterError(f"h must be a non-empty list of separations (1-D), got {h!r}")
    allowed = f"-{MAX_ABS_H:g} <= h <= {MAX_ABS_H:g}"
    if not np.all(np.isfinite(values)):
        bad = float(values[~np.isfinite(values)][0])
        raise ParameterError(f"h must be finite, got {bad!r} (allowed: {allowed})")
    bad = values[~(np.abs(values) <= MAX_ABS_H)]
    if bad.size:
        raise ParameterError(f"h = {float(bad[0])!r} is out of range (allowed: {allowed})")
    return values


def _both(name: str, value, first: str, one, second: str, two) -> tuple:
    """``(one, two)``, or ``(value, value)`` where the shared ``name`` (``E``, ``nu``: two
    identical solids) is given instead; exactly one way, else a ParameterError."""
    if value is None:
        if one is None or two is None:
            missing = first if one is None else second
            raise ParameterError(f"{missing}: missing (give {first} and {second}, or {name} "
                                 "for two identical solids)")  # fmt: skip
        return one, two
    if one is not None or two is not None:
        raise ParameterError(f"{name}: give either {name} (both solids) or {first} and "
                             f"{second}, not both")  # fmt: skip
    return value, value


@dataclass(frozen=True)
class Material:
    """Elastic and adhesive properties of a pair of contacting solids.

    Every quantity may also be given as a string with a unit (``E1="160 GPa"``,
    ``w="500 mJ/m^2"``, ``z0="0.3 nm"``); numbers are SI.

    Parameters
    ----------
    E1, E2 : float or str
        Young's moduli of the two solids, Pa, >= 1 (:data:`RANGES`); the derived K
        and G must stay <= 1e14 Pa (a huge E2 models a rigid counterface).
    nu1, nu2 : float
        Poisson's ratios, in (-1, 0.5).
    E, nu : float or str, keyword only
        Both solids at once (two identical solids, as ``E`` and ``nu`` in a TOML
        file): instead of ``E1`` and ``E2``, or ``nu1`` and ``nu2``.
    gamma : float
        Work of adhesion w used by Eqs. 4 and 6, J/m², in [0, 1e3]: give it as ``w`` (keyword)
        or as ``gamma``, the paper's symbol, which is the field's name (``Material.w`` reads
        it). The paper calls it the work of adhesion in the introduction and a "surface
        energy" in the results; its formulas use it as the work of adhesion (for two
        identical clean surfaces w = 2 γ_s). mcsim uses it as written.
    H : float or None
        Indentation hardness of the softer solid, Pa, in [1, 1e13]. Given in the paper
        but unused by its elastic model; used by the ``elastic-plastic`` law set and
        the plasticity index.
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

    def __init__(self, E1=None, E2=None, nu1=None, nu2=None, gamma=None, H=None, name="",
                 z0=None, tau=None, *, w=None, E=None, nu=None) -> None:  # fmt: skip
        E1, E2 = _both("E", E, "E1", E1, "E2", E2)
        nu1, nu2 = _both("nu", nu, "nu1", nu1, "nu2", nu2)
        if (gamma is None) == (w is None):
            given = "neither" if w is None else f"both (w = {w!r}, gamma = {gamma!r})"
            raise ParameterError(f"w: give the work of adhesion once, as w or its alias gamma "
                                 f"(J/m^2, in [0, 1e3]); got {given}")  # fmt: skip
        if w is not None:  # checked under the name the caller used
            w = _in_range("w", w, "gamma")
        fields = dict(E1=E1, E2=E2, nu1=nu1, nu2=nu2, gamma=w if gamma is None else gamma,
                      H=H, name=name, z0=z0, tau=tau)  # fmt: skip
        for attr, value in fields.items():
            object.__setattr__(self, attr, value)
        self.__post_init__()

    def __post_init__(self) -> None:
        for attr in ("E1", "E2"):
            object.__setattr__(self, attr, _in_range(attr, getattr(self, attr), "E"))
        for attr in ("nu1", "nu2"):
            object.__setattr__(
                self, attr, check_range(attr, getattr(self, attr), "1", low=-1, high=0.5)
            )
        object.__setattr__(self, "gamma", _in_range("gamma", self.gamma))
        for name, modulus in (("K", self.K), ("G", self.G)):
            if not modulus <= RANGES["K"][1]:
                raise ParameterError(
                    f"{name} = {modulus:.4g} Pa (from E1, E2, nu1, nu2) is out of range "
                    f"(allowed: <= {RANGES['K'][1]:g} Pa): one solid needs E <= about 1e13 Pa "
                    "and nu away from -1"
                )
        if self.H is not None:
            object.__setattr__(self, "H", _in_range("H", self.H))
        if self.z0 is not None:
            object.__setattr__(self, "z0", check_range("z0", self.z0, "m", low=0))
        if self.tau is not None:
            object.__setattr__(self, "tau", check_range("tau", self.tau, "Pa", low=0))

    @property
    def w(self) -> float:
        """Work of adhesion w, J/m²: the field ``gamma`` by its name (the paper writes γ)."""
        return self.gamma

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


#: Most bands of a :class:`RadiusByHeight` (as many as ``mcsim ingest`` writes histogram bins;
#: every band is a GW population of its own in the integrals and the sums).
MAX_BANDS = 256


@dataclass(frozen=True)
class RadiusByHeight:
    """A summit radius that depends on the summit's height: R·factor_k in band k.

    The summits of a real surface are not all alike: the taller ones are sharper (Nayak,
    J. Lubr. Technol. 93, 398, 1971, for Gaussian surfaces; measured on a map by
    ``mcsim ingest``, docs/contact.md). GW's one radius is then a mixture of GW populations,
    one per band of heights, each with its own radius (:meth:`Surface.components`).

    Parameters
    ----------
    edges : tuple of float
        Band edges in s = z/σ (the surface's standardized summit heights), strictly
        increasing, at least two. The outermost bands extend to ±inf.
    factors : tuple of float
        Radius of each band over the surface's R, one per band (``len(edges) - 1``),
        each in [1e-3, 1e3].
    """

    edges: tuple[float, ...]
    factors: tuple[float, ...]

    def __post_init__(self) -> None:
        try:
            edges = tuple(float(e) for e in self.edges)
            factors = tuple(float(f) for f in self.factors)
        except (TypeError, ValueError):
            raise ParameterError("radius_by_height: edges and factors must be numbers") from None
        if len(factors) > MAX_BANDS:
            raise ParameterError(f"radius_by_height: {len(factors)} bands is out of range "
                                 f"(allowed: at most {MAX_BANDS}, as many as histogram bins)")  # fmt: skip
        if len(edges) < 2 or len(factors) != len(edges) - 1:
            raise ParameterError(f"radius_by_height: {len(factors)} factors need "
                                 f"{len(factors) + 1} edges, got {len(edges)} (at least 2)")  # fmt: skip
        if not all(math.isfinite(e) for e in edges) or any(np.diff(edges) <= 0):
            raise ParameterError(f"radius_by_height: edges = {list(edges)} must be finite and "
                                 "strictly increasing")  # fmt: skip
        for f in factors:
            if not (math.isfinite(f) and 1e-3 <= f <= 1e3):
                raise ParameterError(f"radius_by_height: factor = {f!r} is out of range "
                                     "(allowed: 1e-3 to 1e3)")  # fmt: skip
        object.__setattr__(self, "edges", edges)
        object.__setattr__(self, "factors", factors)

    def bands(self) -> list[tuple[float, float, float]]:
        """(lo, hi, factor) of each band, the outermost open to ±inf."""
        cuts = (-math.inf, *self.edges[1:-1], math.inf)
        return list(zip(cuts[:-1], cuts[1:], self.factors))

    def band_of(self, s) -> np.ndarray:
        """Index of the band holding each standardized height ``s`` (bands are (lo, hi])."""
        return np.searchsorted(np.asarray(self.edges[1:-1]), np.asarray(s, float), side="left")


@dataclass(frozen=True)
class Surface:
    """A Greenwood–Williamson population of spherical summits (the combined surface).

    Every quantity may also be given as a string with a unit (``sigma="1.4 nm"``,
    ``R="1.7 um"``, ``eta="17 um^-2"``); numbers are SI.

    Parameters
    ----------
    sigma : float or str
        Standard deviation of the summit heights σ, m, in [1e-12, 1e-2] (:data:`RANGES`).
    R : float
        Summit radius of curvature, m, in [1e-10, 10].
    eta : float
        Areal density of summits η, m⁻², in [1, 1e20].
    heights : HeightDistribution
        Shape of the summit-height distribution in units of σ (zero mean, unit
        standard deviation). Gaussian by default, as in the paper.
    name : str
        Label for output files and plots.
    rq : float or str or None
        Rms height of the combined surface about its mean plane, m, in [1e-12, 1e-2]:
        only the environment (:mod:`mcsim.physics.environment`) uses it. None: estimated
        from σ, R, η (Nayak's relations) where needed.
    summit_offset : float or str or None
        Height of the mean summit plane above the mean plane, m, in [0, 1e-2]: the GW
        separation d is measured from the summit plane, the environment's gaps from the
        mean plane. None: estimated with ``rq``.
    map_heights : HeightDistribution or None
        Shape of the heights of the whole surface about its mean plane in units of
        ``rq`` (a measured map's height histogram); None: Gaussian.
    radius_by_height : RadiusByHeight or None
        A summit radius that depends on height (R times a factor per band of heights);
        None: every summit has the radius R, as in GW and the paper.
    """

    sigma: float
    R: float
    eta: float
    heights: HeightDistribution = field(default=GAUSSIAN)
    name: str = ""
    rq: float | None = None
    summit_offset: float | None = None
    map_heights: HeightDistribution | None = None
    radius_by_height: RadiusByHeight | None = None

    def __post_init__(self) -> None:
        for attr in ("sigma", "R", "eta"):
            object.__setattr__(self, attr, _in_range(attr, getattr(self, attr)))
        if self.rq is not None:
            object.__setattr__(self, "rq", _in_range("rq", self.rq, "sigma"))
        if self.summit_offset is not None:
            _, high, unit = RANGES["sigma"]
            offset = check_range("summit_offset", self.summit_offset, unit, low=0.0, high=high,
                                 low_open=False, high_open=False)  # fmt: skip
            object.__setattr__(self, "summit_offset", offset)

        if self.radius_by_height is not None:
            if not isinstance(self.radius_by_height, RadiusByHeight):
                raise ParameterError(f"radius_by_height = {self.radius_by_height!r} must be a "
                                     "RadiusByHeight or None")  # fmt: skip
            for factor in self.radius_by_height.factors:
                _in_range("R", self.R * factor)

    def components(self) -> tuple[Surface, ...]:
        """The plain GW populations this surface is a sum of: itself, or with
        :attr:`radius_by_height` one per band of heights, each with its radius and its part
        of the height distribution (:class:`~mcsim.model.distributions.Band`). Quantities
        that are sums over summits (loads, areas, counts, works) are the sums of theirs."""
        if self.radius_by_height is None:
            return (self,)
        bands = self.radius_by_height.bands()
        return tuple(
            replace(self, R=self.R * f, heights=Band(self.heights, lo, hi), radius_by_height=None)
            for lo, hi, f in bands
        )

    @property
    def mean_curvature_radius(self) -> float:
        """Radius of the summits' mean curvature, m: R, or with a radius by height
        1/Σ_k p_k/R_k over its bands (p_k the band's share of the summits). What relations
        written for one radius (Nayak's estimates, the caps' mean band edge) take."""
        parts = self.components()
        if len(parts) == 1:
            return self.R
        mass = np.array([float(part.heights.sf(-np.inf)) for part in parts])
        return float(1 / np.sum(mass / np.array([part.R for part in parts])))

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
    if first.radius_by_height is not None or second.radius_by_height is not None:
        raise ParameterError("combine: a surface with a radius by height cannot be combined "
                             "(the rule is for one radius per surface)")  # fmt: skip
    sigma = math.hypot(first.sigma, second.sigma)
    R = (first.R**-2 + second.R**-2) ** -0.5
    return Surface(sigma=sigma, R=R, eta=eta, name=name)
