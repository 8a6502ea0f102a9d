"""The environment: van der Waals attraction across the gaps and capillary condensation.

See docs/physics.md, sections 'The environment' and 'The environment: summits and open gaps'.

The medium (:class:`Environment`) and the local laws below (the proximity model over a
height distribution) are the building blocks. mcsim applies them in two parts that never
count one area twice, each summit's cap and the open gaps between the caps:
:mod:`mcsim.physics.surfaceenvironment`.

Proximity (pixel-by-pixel Derjaguin) model over the height distribution of the combined
rough surface (DelRio et al., Nature Materials 4, 629, 2005; DelRio et al., Appl. Phys.
Lett. 90, 163104, 2007). Heights z about the mean plane are
Gaussian with rms Rq, or a measured height histogram (:class:`~mcsim.empirical.Empirical`,
a piecewise-constant density). At mean-plane gap D the local gap is g = D − z; where
g < D0 (the cutoff) the surfaces touch and the contact law rules, elsewhere, per nominal
area and positive when attractive:

* van der Waals between locally flat regions (Israelachvili, *Intermolecular and Surface
  Forces*, 3rd ed., Eq. 13.11, p = A/(6π g³)): p_vdW(D) = (A/6π) E[g⁻³; g ≥ D0], and its
  work from D_t outward W_vdW(D_t) = (A/12π) E[max(D_t − z, D0)⁻²];
* capillary condensation in equilibrium with the vapour: Kelvin radius
  r_K = γ_L V_m / (R_g T ln(1/RH)) (Kelvin equation, Israelachvili Eq. 17.19); each face
  carries an adsorbed film of thickness t (:mod:`mcsim.physics.films`), liquid bridges the
  films across the gaps g < g_K = 2 r_K cos θ + 2t and pulls with the Laplace pressure
  γ_L/r_K where f ≤ g < g_K, above the wet floor f = max(D0, 2t) (below it the two films
  are pressed into each other and their disjoining pressure balances the pull):
  p_cap(D) = (γ_L/r_K) P(f ≤ g < g_K), W_cap(D_t) = (γ_L/r_K) E[(g_K − max(f, D_t − z))⁺].

Both works satisfy −dW/dD = p. Gaussian heights: p_cap and W_cap in closed form (normal
CDFs and densities); the van der Waals moments E[g⁻ⁿ; g ≥ D0] by one fixed composite
Gauss–Legendre rule, vectorised over every point (see :func:`_gaussian_gap_moment`).
Histogram heights: every quantity is an exact integral over each bin.

Not in this model: elastic deformation of the non-contacting surface, correlation between
the two topographies, menisci that conserve volume, the adsorbed films' own disjoining
pressure outside the bridges.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy import special

from mcsim.model.errors import ParameterError
from mcsim.model.params import check_range
from mcsim.model.units import has_unit, parse_quantity
from mcsim.physics import films

#: Molar gas constant R_g, J/(mol K) (CODATA 2018, exact).
GAS_CONSTANT = 8.314462618

#: Default cutoff D0, m: Israelachvili's "universal" 0.165 nm, with which A/(24π D0²) gives
#: the surface energy of many solids (Intermolecular and Surface Forces, 3rd ed., §13.5).
DEFAULT_CUTOFF = 0.165e-9

#: Largest Hamaker constant accepted, J: real ones lie between ~1e-21 and ~5e-19 J (metals
#: across vacuum; Israelachvili, Intermolecular and Surface Forces, ch. 13); 1e-16 J is 200× the largest, and keeps every
#: attraction a finite float.
MAX_HAMAKER = 1e-16

# Composite Gauss–Legendre rule on [0, 1] for the Gaussian van der Waals moments:
# _PANELS equal panels of _NODES_PER_PANEL nodes in the mapped variable ξ = τ + ln τ.
_PANELS = 12
_NODES_PER_PANEL = 12
# The Gaussian weight is cut where it has fallen by e^-_TAIL (≈ 1e-26) from its peak.
_TAIL = 60.0


def _unit_rule() -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre nodes and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(_NODES_PER_PANEL)
    half = 0.5 / _PANELS
    mid = (np.arange(_PANELS) + 0.5) / _PANELS
    return (mid[:, None] + half * x).ravel(), np.tile(half * w, _PANELS)


_NODES, _WEIGHTS = _unit_rule()


@dataclass(frozen=True)
class Environment:
    """The medium between the surfaces: van der Waals and a condensing vapour (SI).

    Parameters
    ----------
    hamaker : float or None
        Hamaker constant A across the medium, J, in [0, 1e-16]; None (default) or 0: no van der
        Waals term. Silicon across air ≈ 1.6–2.0e-19 J (Israelachvili's tables).
    cutoff : float
        Cutoff gap D0, m, > 0: gaps below it are contact. Default
        :data:`DEFAULT_CUTOFF` = 0.165 nm.
    rh : float
        Relative humidity of the vapour, in [0, 1); 0 (default): dry, no condensation.
    contact_angle : float
        Contact angle θ of the liquid on the solid, rad, in [0, π); θ >= π/2: the liquid
        does not condense in the gaps.
    temperature : float
        Temperature T, K, > 0 (default 298.15).
    surface_tension : float
        Surface tension γ_L of the liquid, J/m², > 0 (default water, 0.072).
    molar_volume : float
        Molar volume V_m of the liquid, m³/mol, > 0 (default water, 1.80e-5).
    film_thickness : float or None
        Adsorbed film t on each face, m, >= 0; None (default): the isotherm t(RH) of
        :func:`mcsim.physics.films.film_thickness` (water on silicon oxide). A value replaces
        t(RH) everywhere, in the condensation gap, the wet floor and the bridges' onset.
    structured_film : float
        Thickness t_s of the structured (ice-like) first layers, m, >= 0 (default
        :data:`mcsim.physics.films.STRUCTURED_FILM`, 0.84 nm): liquid bridges form only
        where t > t_s, with liquid-like water on top (RH > RH_dry = 0.30 on the isotherm);
        0: no structured layers, bridges at any RH > 0 (with ``film_thickness`` = 0 the Kelvin
        band D0 <= g < 2 r_K cos θ, no film).

    Raises
    ------
    ParameterError
        A field outside its range; the message names the field, value and range.
    """

    hamaker: float | None = None
    cutoff: float = DEFAULT_CUTOFF
    rh: float = 0.0
    contact_angle: float = 0.0
    temperature: float = 298.15
    surface_tension: float = 0.072
    molar_volume: float = 1.80e-5
    film_thickness: float | None = None
    structured_film: float = films.STRUCTURED_FILM

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        if self.hamaker is not None:
            set_(self, "hamaker", check_range("hamaker", self.hamaker, "J", low=0, high=MAX_HAMAKER,
                                              low_open=False, high_open=False))  # fmt: skip
        set_(self, "cutoff", check_range("cutoff", self.cutoff, "m", low=0))
        set_(self, "rh", check_range("rh", self.rh, "1", low=0, high=1, low_open=False))
        angle = check_range("contact_angle", self.contact_angle, "rad", low=0, high=math.pi,
                            low_open=False)  # fmt: skip
        set_(self, "contact_angle", angle)
        set_(self, "temperature", check_range("temperature", self.temperature, "K", low=0))
        for name, unit in (("surface_tension", "J/m^2"), ("molar_volume", "m^3/mol")):
            set_(self, name, check_range(name, getattr(self, name), unit, low=0))
        for name in ("film_thickness", "structured_film"):
            if getattr(self, name) is not None:
                set_(self, name, check_range(name, getattr(self, name), "m", low=0,
                                             low_open=False))  # fmt: skip

    @classmethod
    def from_user(
        cls,
        *,
        hamaker=None,
        cutoff=DEFAULT_CUTOFF,
        rh=0.0,
        contact_angle=0.0,
        temperature=298.15,
        surface_tension=0.072,
        molar_volume=1.80e-5,
        film_thickness=None,
        structured_film=films.STRUCTURED_FILM,
    ) -> Environment:
        """An environment from values as users write them (numbers SI, or strings with units).

        Every field is parsed by :func:`mcsim.model.units.parse_quantity`: ``hamaker`` an
        energy (``"1.6e-19 J"``, ``"0.16 aJ"``), ``cutoff`` a length (``"0.2 nm"``),
        ``rh`` a bare fraction, ``contact_angle`` an angle (``"20 deg"``, ``"0.35 rad"``;
        a bare number is in **degrees**), ``temperature`` in K (no °C), ``surface_tension``
        an energy per area (``"72 mJ/m^2"``), ``molar_volume`` (``"18 cm^3/mol"``),
        ``film_thickness`` (None: the isotherm) and ``structured_film`` lengths
        (``"0.8 nm"``).

        Raises
        ------
        UnitError, ParameterError
            An unreadable value or unit, or a value out of range.
        """
        if has_unit(contact_angle):
            angle = parse_quantity(contact_angle, "angle", "contact_angle")
        else:  # a bare number is in degrees
            angle = math.radians(parse_quantity(contact_angle, "dimensionless", "contact_angle"))
        if not 0 <= angle < math.pi:
            raise ParameterError(f"contact_angle = {math.degrees(angle)!r} deg is out of range "
                                 "(allowed: [0, 180) deg)")  # fmt: skip
        return cls(
            hamaker=None if hamaker is None else parse_quantity(hamaker, "energy", "hamaker"),
            cutoff=parse_quantity(cutoff, "length", "cutoff"),
            rh=parse_quantity(rh, "dimensionless", "rh"),
            contact_angle=angle,
            temperature=parse_quantity(temperature, "temperature", "temperature"),
            surface_tension=parse_quantity(surface_tension, "energy_per_area", "surface_tension"),
            molar_volume=parse_quantity(molar_volume, "molar_volume", "molar_volume"),
            film_thickness=None if film_thickness is None
            else parse_quantity(film_thickness, "length", "film_thickness"),
            structured_film=parse_quantity(structured_film, "length", "structured_film"),
        )  # fmt: skip

    @property
    def has_vdw(self) -> bool:
        """Whether a van der Waals term acts (a Hamaker constant > 0)."""
        return bool(self.hamaker)

    @property
    def is_dry(self) -> bool:
        """Whether the vapour is absent (RH = 0)."""
        return self.rh == 0

    @property
    def film(self) -> float:
        """Adsorbed film t on each face, m: ``film_thickness`` if given, else the isotherm
        t(RH) (:func:`mcsim.physics.films.film_thickness`; 0 when dry)."""
        if self.film_thickness is not None:
            return self.film_thickness
        return float(films.film_thickness(self.rh))

    @property
    def no_condensation_reason(self) -> str | None:
        """Why no liquid bridges form (dry vapour, non-wetting liquid, a film no thicker than
        its structured layers), or None if they can."""
        if self.is_dry:
            return "no capillary condensation: the vapour is dry (rh = 0)"
        if self.contact_angle >= math.pi / 2:
            return (
                f"no capillary condensation: contact angle {math.degrees(self.contact_angle):g} "
                "deg >= 90 deg (the liquid does not wet the gaps)"
            )
        if self.film <= self.structured_film and self.structured_film > 0:
            onset = (f"; on the isotherm above RH {float(films.film_humidity(self.structured_film)):.3g}"
                     if self.film_thickness is None else "")  # fmt: skip
            return (
                f"no capillary bridges: adsorbed film t = {self.film * 1e9:.3g} nm <= structured "
                f"film {self.structured_film * 1e9:.3g} nm (rh = {self.rh:g}): the first, "
                f"ice-like layers form no liquid bridges{onset}"
            )
        return None

    @property
    def has_capillary(self) -> bool:
        """Whether liquid bridges form (RH > 0, θ < 90° and t > the structured film t_s, or
        t_s = 0)."""
        return self.no_condensation_reason is None

    @property
    def active(self) -> bool:
        """Whether any environment term acts."""
        return self.has_vdw or self.has_capillary

    @property
    def kelvin_radius(self) -> float:
        """Kelvin radius r_K, m (0 when dry): see :func:`kelvin_radius`."""
        return float(kelvin_radius(self.rh, self.temperature, self.surface_tension,
                                   self.molar_volume))  # fmt: skip

    @property
    def condensation_gap(self) -> float:
        """Largest gap bridged by liquid g_K = 2 r_K cos θ + 2t, m; 0 without condensation."""
        if not self.has_capillary:
            return 0.0
        return 2 * self.kelvin_radius * math.cos(self.contact_angle) + 2 * self.film

    @property
    def wet_floor(self) -> float:
        """Smallest gap the bridges pull across, max(D0, 2t), m (the films pressed into each
        other below it); D0 without condensation."""
        return max(self.cutoff, 2 * self.film) if self.has_capillary else self.cutoff

    @property
    def laplace_pressure(self) -> float:
        """Laplace pressure γ_L/r_K of the menisci, Pa; 0 without condensation."""
        return self.surface_tension / self.kelvin_radius if self.has_capillary else 0.0


def as_environment(value) -> Environment | None:
    """The ``environment`` argument of the Python API: None, an :class:`Environment`, or a
    mapping of its fields as users write them in TOML files (:meth:`Environment.from_user`,
    e.g. ``{"rh": 0.5, "hamaker": "1.6e-19 J", "contact_angle": "20 deg"}``; there a bare
    ``contact_angle`` is in degrees, where ``Environment(contact_angle=...)`` takes radians).

    Raises
    ------
    ParameterError
        Anything else, or a mapping with a key that is not a field.
    """
    if value is None or isinstance(value, Environment):
        return value
    fields = [f.name for f in dataclasses.fields(Environment)]
    if isinstance(value, Mapping):
        unknown = [k for k in value if k not in fields]
        if unknown:
            raise ParameterError(f"environment: unknown field {unknown[0]!r} "
                                 f"(allowed: {', '.join(fields)})")  # fmt: skip
        return Environment.from_user(**value)
    raise ParameterError(f"environment must be an Environment or a mapping of its fields "
                         f"({', '.join(fields)}), got {type(value).__name__} {value!r}")  # fmt: skip


def kelvin_radius(rh, temperature=298.15, surface_tension=0.072, molar_volume=1.80e-5):
    """Kelvin radius r_K = γ_L V_m / (R_g T ln(1/RH)), m, vectorised (Kelvin equation).

    Israelachvili, *Intermolecular and Surface Forces*, 3rd ed., Eq. 17.19.
    Water at 25 °C: 0.525 nm / ln(1/RH).

    Parameters
    ----------
    rh : array_like
        Relative humidity, in [0, 1); r_K = 0 at RH = 0.
    temperature : array_like
        K.
    surface_tension : array_like
        γ_L, J/m².
    molar_volume : array_like
        V_m, m³/mol.

    Returns
    -------
    ndarray
        r_K, m.
    """
    rh = np.asarray(rh, dtype=float)
    with np.errstate(divide="ignore"):
        return surface_tension * molar_volume / (GAS_CONSTANT * temperature * -np.log(rh))


# -- height distributions: E over z of the four kernels ------------------------------------


def _prob_between(lo, hi):
    """P(lo < X <= hi) for a standard normal X, from the nearer tail (no cancellation)."""
    upper = special.ndtr(-lo) - special.ndtr(-hi)
    return np.where(lo > 0, upper, special.ndtr(hi) - special.ndtr(lo))


def _gaussian_gap_moment(D, rq, cutoff, n: int):
    """E[g⁻ⁿ; g >= D0], m⁻ⁿ, for g = D − z, z ~ N(0, Rq²), by a fixed quadrature.

    With t = (g − D0)/Rq >= 0 and a = (D − D0)/Rq the integral is
    ∫₀^∞ (D0 + Rq t)⁻ⁿ φ(a − t) dt. Its two scales, the pole of (D0 + Rq t)⁻ⁿ at
    distance τ = t + D0/Rq from it and the unit width of the Gaussian, are both resolved
    by the map ξ = τ + ln τ (geometric near the pole, uniform far from it; inverse
    τ = ω(ξ), the Wright omega function, analytic in a strip of half-width π). The
    Gaussian is cut where it falls by e^-60, and [ξ(t_lo), ξ(t_hi)] is split into equal
    Gauss–Legendre panels: ~1e-14 relative against 40-digit mpmath over Rq/D0 from
    1e-3 to 1e3 and a from −30 to 30 (tests/physics/test_environment.py).
    """
    a = (D - cutoff) / rq
    shift = cutoff / rq
    t_lo = np.maximum(a - math.sqrt(2 * _TAIL), 0.0)
    # Above a the weight φ(a − t) falls by e^-_TAIL at t² − 2 a t = 2 _TAIL (a < 0: steeply).
    t_hi = np.where(a >= 0, a + math.sqrt(2 * _TAIL), 2 * _TAIL / (np.sqrt(a * a + 2 * _TAIL) - a))
    tau_lo, tau_hi = t_lo + shift, t_hi + shift
    xi_lo = tau_lo + np.log(tau_lo)
    span = tau_hi + np.log(tau_hi) - xi_lo
    tau = special.wrightomega(xi_lo[..., None] + span[..., None] * _NODES).real
    t = tau - shift[..., None]
    gap = rq[..., None] * tau  # = D0 + Rq t
    density = np.exp(-0.5 * (a[..., None] - t) ** 2) / math.sqrt(2 * math.pi)
    return span * np.sum(_WEIGHTS * gap**-n * density * tau / (1 + tau), axis=-1)


def _partial_mean(h):
    """F_1(h) = E[(X − h)⁺] = φ(h) − h Q(h) for a standard normal X and h >= 0 (GW F_1,
    docs/physics.md), as φ(h) (1 − h M(h)) with the Mills ratio M = Q/φ = √(π/2) erfcx(h/√2),
    so the far tail keeps its relative accuracy."""
    mills = math.sqrt(math.pi / 2) * special.erfcx(h / math.sqrt(2))
    return np.exp(-0.5 * h * h) / math.sqrt(2 * math.pi) * (1 - h * mills)


def _gaussian_condensate(D, rq, cutoff, gap_k):
    """P(D0 <= g < g_K) and E[(g_K − max(D0, g))⁺], m, for Gaussian z (closed forms).

    With x = z/Rq, a = (D − D0)/Rq and b = (D − g_K)/Rq < a: the filled fraction is
    Φ(a) − Φ(b), and (g_K − max(D0, D − z))⁺ = Rq [(x − b)⁺ − (x − a)⁺], so the depth is
    Rq [F_1(b) − F_1(a)], evaluated with F_1 at non-negative arguments only
    (F_1(h) = −h + F_1(−h)): for a <= 0 as Rq [a − b + F_1(−b) − F_1(−a)].
    """
    a = (D - cutoff) / rq
    b = (D - gap_k) / rq
    filled = _prob_between(b, a)
    # F_1(h) = max(−h, 0) + F_1(|h|) for either sign (F_1(h) − F_1(−h) = −h).
    depth = np.where(
        a <= 0,
        a - b + _partial_mean(np.abs(b)) - _partial_mean(np.abs(a)),
        np.maximum(-b, 0) + _partial_mean(np.abs(b)) - _partial_mean(np.abs(a)),
    )
    return filled, rq * depth


def _histogram(heights) -> tuple[np.ndarray, np.ndarray]:
    """Bin edges (m, about the mean plane) and densities (m⁻¹) of an Empirical-like object."""
    return heights.sigma * heights.edges, heights.densities / heights.sigma


def _histogram_bins(D, heights, cutoff):
    """Per bin of the histogram: the gap interval [g_a, g_b] out of contact, the contact length
    and the density (m⁻¹), with the bins on a new last axis (g_a, g_b >= D0)."""
    edges, density = _histogram(heights)
    D = np.asarray(D, dtype=float)[..., None]
    g_lo, g_hi = D - edges[1:], D - edges[:-1]
    g_a, g_b = np.maximum(g_lo, cutoff), np.maximum(g_hi, cutoff)
    return g_a, g_b, np.diff(edges) - (g_b - g_a), density


def _is_histogram(heights) -> bool:
    return hasattr(heights, "densities")


def _gap_moment(D, heights, cutoff, n: int):
    """E[g⁻³; g >= D0] (n = 3) or E[max(g, D0)⁻²] (n = 2), m⁻ⁿ, for g = D − z.

    Histogram: exact over each bin of the piecewise-constant density,
    ∫ g⁻³ dg = (g_a⁻² − g_b⁻²)/2 and ∫ g⁻² dg = 1/g_a − 1/g_b, written as products of
    g_b − g_a (no cancellation for narrow bins), plus D0⁻² times the contact length.
    """
    cutoff = np.asarray(cutoff, dtype=float)
    if _is_histogram(heights):
        g_a, g_b, contact, density = _histogram_bins(D, heights, cutoff[..., None])
        if n == 3:
            per_bin = (g_b - g_a) * (g_b + g_a) / (2 * g_a**2 * g_b**2)
        else:
            per_bin = (g_b - g_a) / (g_a * g_b) + contact / cutoff[..., None] ** 2
        return np.sum(density * per_bin, axis=-1)
    D, rq, cutoff = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (D, heights, cutoff)))
    moment = _gaussian_gap_moment(D, rq, cutoff, n)
    if n == 3:
        return moment
    return moment + special.ndtr(-(D - cutoff) / rq) / cutoff**2


def _condensate(D, heights, cutoff, gap_k):
    """P(D0 <= g < g_K) and E[(g_K − max(D0, g))⁺] (m) for g = D − z, g_K > D0.

    Histogram: exact over each bin; the filled part [g_a, g_c] (g_c = g_K clipped to the
    bin) adds (g_c − g_a)(2 g_K − g_a − g_c)/2, the contact length times g_K − D0.
    """
    if not _is_histogram(heights):
        D, rq, cutoff, gap_k = np.broadcast_arrays(
            *(np.asarray(x, dtype=float) for x in (D, heights, cutoff, gap_k))
        )
        return _gaussian_condensate(D, rq, cutoff, gap_k)
    cutoff = np.asarray(cutoff, dtype=float)[..., None]
    gap_k = np.asarray(gap_k, dtype=float)[..., None]
    g_a, g_b, contact, density = _histogram_bins(D, heights, cutoff)
    g_c = np.clip(gap_k, g_a, g_b)
    filled = np.sum(density * (g_c - g_a), axis=-1)
    depth = (g_c - g_a) * (2 * gap_k - g_a - g_c) / 2 + contact * (gap_k - cutoff)
    return filled, np.sum(density * depth, axis=-1)


# -- the four terms ----------------------------------------------------------------------------


def vdw_pressure(D, heights, hamaker, cutoff):
    """Van der Waals attraction across the non-contacting gaps, Pa (positive: attractive).

    p_vdW(D) = (A/6π) E[g⁻³; g >= D0], g = D − z (DelRio et al. 2005; the
    flat-flat pressure A/(6π g³), Israelachvili Eq. 13.11).

    Parameters
    ----------
    D : array_like
        Gap between the mean planes, m.
    heights : array_like or Empirical
        Gaussian heights: their rms Rq, m (> 0, broadcast with ``D``); or a measured
        height histogram (an :class:`~mcsim.empirical.Empirical`: ``edges``,
        ``densities``, ``sigma``), whose bins go on a last axis summed over.
    hamaker : array_like
        Hamaker constant A, J.
    cutoff : array_like
        Cutoff gap D0, m: smaller gaps are contact.

    Returns
    -------
    ndarray
        p_vdW, Pa, of the broadcast shape of the arguments.
    """
    return hamaker / (6 * math.pi) * _gap_moment(D, heights, cutoff, 3)


def vdw_work(D_t, heights, hamaker, cutoff):
    """Van der Waals work of separation from ``D_t`` to infinity, J/m².

    W_vdW(D_t) = (A/12π) E[max(D_t − z, D0)⁻²] (DelRio et al. 2005's
    Σ A/(12π D_i²)); −dW/dD = :func:`vdw_pressure`. Flat surfaces at contact:
    A/(12π D0²).

    Parameters
    ----------
    D_t : array_like
        Mean-plane gap at the closest approach, m.
    heights, hamaker, cutoff
        As for :func:`vdw_pressure`.

    Returns
    -------
    ndarray
        W_vdW, J/m².
    """
    return hamaker / (12 * math.pi) * _gap_moment(D_t, heights, cutoff, 2)


def _capillary(D, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film,
               which: int):  # fmt: skip
    """Laplace pressure times the filled fraction (0) or the mean filled depth (1), over the
    band max(D0, 2t) <= g < g_K = 2 r_K cos θ + 2t."""
    r_k = np.asarray(kelvin_radius, dtype=float)
    film = np.asarray(film, dtype=float)
    gap_k = 2 * r_k * np.cos(contact_angle) + 2 * film
    floor = np.maximum(cutoff, 2 * film)
    active = gap_k > floor
    r_safe = np.where(active, r_k, 1.0)
    gap_safe = np.where(active, gap_k, 2 * floor)
    value = _condensate(D, heights, floor, gap_safe)[which]
    return np.where(active, surface_tension / r_safe * value, 0.0)


def capillary_pressure(D, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film=0.0):
    """Capillary attraction of the condensed liquid, Pa (positive: attractive).

    p_cap(D) = (γ_L/r_K) P(f <= g < g_K), g_K = 2 r_K cos θ + 2t, f = max(D0, 2t): Laplace
    pressure on the area whose gap is bridged by liquid between the two adsorbed films of
    thickness t (DelRio et al. 2007 with t = 0), down to the wet floor f, below which the
    films are pressed into each other. Zero where g_K <= f (dry, θ >= 90°, or too little
    vapour to fill any open gap).

    Parameters
    ----------
    D : array_like
        Gap between the mean planes, m.
    heights : array_like or Empirical
        As for :func:`vdw_pressure`.
    cutoff : array_like
        Cutoff gap D0, m.
    surface_tension : array_like
        γ_L, J/m².
    kelvin_radius : array_like
        r_K, m (:func:`kelvin_radius`; 0 when dry).
    contact_angle : array_like
        θ, rad.
    film : array_like
        Adsorbed film t on each face, m (:attr:`Environment.film`; default 0: no film, the
        band D0 <= g < 2 r_K cos θ).

    Returns
    -------
    ndarray
        p_cap, Pa, of the broadcast shape of the arguments.
    """
    return _capillary(D, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film, 0)


def capillary_work(D_t, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film=0.0):
    """Capillary work of separation from ``D_t`` to infinity, J/m².

    W_cap(D_t) = (γ_L/r_K) E[(g_K − max(f, D_t − z))⁺]; −dW/dD =
    :func:`capillary_pressure`. Flat surfaces at contact:
    (γ_L/r_K)(g_K − f) = 2γ_L cos θ − γ_L (D0 − 2t)⁺/r_K <= 2γ_L cos θ, the ceiling of
    DelRio et al. 2007, reached once 2t >= D0 (and as RH → 1).

    Parameters
    ----------
    D_t : array_like
        Mean-plane gap at the closest approach, m.
    heights, cutoff, surface_tension, kelvin_radius, contact_angle, film
        As for :func:`capillary_pressure`.

    Returns
    -------
    ndarray
        W_cap, J/m².
    """
    return _capillary(D_t, heights, cutoff, surface_tension, kelvin_radius, contact_angle, film,
                      1)  # fmt: skip
