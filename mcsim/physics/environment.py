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

* van der Waals between locally flat regions, retarded (:func:`vdw_flat_energy`,
  :func:`vdw_flat_pressure`): the energy per area of two flats at gap g,
  W(g) = A/(12π g²) · 1/(1 + b g), b = 5.32/λ (Gregory, J. Colloid Interface Sci. 83,
  138, 1981: his flat-plate expression), and its pressure p(g) = −dW/dg; b = 0 (λ None)
  is the non-retarded A/(12π g²), A/(6π g³) (Israelachvili, *Intermolecular and Surface
  Forces*, 3rd ed., Eq. 13.11). Over the heights:
  p_vdW(D) = E[p(g); g ≥ D0], and its work from D_t outward
  W_vdW(D_t) = E[W(max(D_t − z, D0))];
* capillary condensation in equilibrium with the vapour: Kelvin radius
  r_K = γ_L V_m / (R_g T ln(1/RH)) (Kelvin equation, Israelachvili Eq. 17.19); each face
  carries an adsorbed film of thickness t (:mod:`mcsim.physics.films`), liquid bridges the
  films across the gaps g < g_K = 2 r_K cos θ + 2t and pulls with the Laplace pressure
  γ_L/r_K where f ≤ g < g_K, above the wet floor f = max(D0, 2t) (below it the two films
  are pressed into each other and their disjoining pressure balances the pull):
  p_cap(D) = (γ_L/r_K) P(f ≤ g < g_K), W_cap(D_t) = (γ_L/r_K) E[(g_K − max(f, D_t − z))⁺].

Both works satisfy −dW/dD = p. Gaussian heights: p_cap and W_cap in closed form (normal
CDFs and densities); the van der Waals means E[p(g); g ≥ D0] and E[W(g); g ≥ D0] by one
fixed composite Gauss–Legendre rule, vectorised over every point (see
:func:`_gaussian_gap_moment`). Histogram heights: every quantity is an exact integral over
each bin (:func:`_gap_moment`).

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

#: Default retardation wavelength λ of the van der Waals attraction, m: the characteristic
#: wavelength of the dispersion interaction, about 100 nm (Gregory, J. Colloid Interface
#: Sci. 83, 138, 1981). See :func:`retardation`.
DEFAULT_RETARDATION_WAVELENGTH = 100e-9

#: Gregory's constant of two flat plates: their energy A/(12πD²) is retarded by
#: 1/(1 + GREGORY_B·D/λ) (Gregory 1981, flat plates). By Derjaguin a sphere of radius R
#: then pulls with A R/(6D²)·1/(1 + 5.32 D/λ), whose energy is Gregory's sphere–plate
#: −(A R/6D)[1 − (5.32 D/λ) ln(1 + λ/(5.32 D))]. (His 14 belongs to another, simpler fit of
#: that sphere–plate *energy*, −(A R/6D)/(1 + 14 D/λ), within 5 % of it up to D = 10 nm.)
GREGORY_B = 5.32

#: The nano-gap of a contact in units of the asperities' nanoscale roughness σ_n: the tallest
#: nano-asperities, about 3σ_n above their mean plane (the largest of a few hundred Gaussian
#: heights), hold a contacting summit's mean surface that far from the counter-surface, and a
#: meniscus spreads over the summit only once its Kelvin band spans it (DelRio et al.,
#: Langmuir 25, 11727, 2009: bridges confined to the asperity contacts below RH_cr).
NANO_GAP = 3.0

#: Largest Hamaker constant accepted, J: real ones lie between ~1e-21 and ~5e-19 J (metals
#: across vacuum; Israelachvili, Intermolecular and Surface Forces, ch. 13); 1e-16 J is 200× the largest, and keeps every
#: attraction a finite float.
MAX_HAMAKER = 1e-16

# Composite Gauss–Legendre rule on [0, 1] for the Gaussian van der Waals moments:
# _PANELS equal panels of _NODES_PER_PANEL nodes in the mapped variable ξ = τ + ln τ.
_PANELS = 12
_NODES_PER_PANEL = 12
#: The van der Waals moments' Gaussian weight is cut where it has fallen by e^-VDW_TAIL
#: (≈ 1e-26) from its peak (here and in the design map's kernel,
#: :mod:`mcsim.engine.maps.environment`).
VDW_TAIL = 60.0


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
    asperity_roughness : float
        Rms σ_n of the asperities' own nanoscale roughness, m, >= 0 (default 0: smooth
        asperities). Menisci spread from a contact across the interface only once the Kelvin
        band 2 r_K cos θ spans the nano-gap :data:`NANO_GAP` σ_n that the nano-asperities hold
        a contact open by (RH >= :attr:`critical_rh`, DelRio's RH_cr); below, bridges stay
        confined to the nano-contacts and their pull is neglected (docs/physics.md, 'Two
        thresholds').
    retardation_wavelength : float or None
        Retardation wavelength λ of the van der Waals attraction, m, > 0 (default
        :data:`DEFAULT_RETARDATION_WAVELENGTH` = 100 nm, Gregory 1981); None: non-retarded.
        The flats' energy A/(12πg²) is reduced by 1/(1 + 5.32 g/λ) (:func:`vdw_flat_energy`).

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
    asperity_roughness: float = 0.0
    retardation_wavelength: float | None = DEFAULT_RETARDATION_WAVELENGTH

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
        for name in ("film_thickness", "structured_film", "asperity_roughness"):
            if getattr(self, name) is not None:
                set_(self, name, check_range(name, getattr(self, name), "m", low=0,
                                             low_open=False))  # fmt: skip
        if self.retardation_wavelength is not None:
            set_(self, "retardation_wavelength",
                 check_range("retardation_wavelength", self.retardation_wavelength, "m", low=0))  # fmt: skip

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
        asperity_roughness=0.0,
        retardation_wavelength=DEFAULT_RETARDATION_WAVELENGTH,
    ) -> Environment:
        """An environment from values as users write them (numbers SI, or strings with units).

        Every field is parsed by :func:`mcsim.model.units.parse_quantity`: ``hamaker`` an
        energy (``"1.6e-19 J"``, ``"0.16 aJ"``), ``cutoff`` a length (``"0.2 nm"``),
        ``rh`` a bare fraction, ``contact_angle`` an angle (``"20 deg"``, ``"0.35 rad"``;
        a bare number is in **degrees**), ``temperature`` in K (no °C), ``surface_tension``
        an energy per area (``"72 mJ/m^2"``), ``molar_volume`` (``"18 cm^3/mol"``),
        ``film_thickness`` (None: the isotherm), ``structured_film`` and
        ``asperity_roughness`` lengths (``"0.8 nm"``);
        ``retardation_wavelength`` a length (``"100 nm"``), or None or ``"none"``:
        non-retarded.

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
            film_thickness=None
            if film_thickness is None
            else parse_quantity(film_thickness, "length", "film_thickness"),
            structured_film=parse_quantity(structured_film, "length", "structured_film"),
            asperity_roughness=parse_quantity(asperity_roughness, "length", "asperity_roughness"),
            retardation_wavelength=_wavelength(retardation_wavelength),
        )

    @property
    def has_vdw(self) -> bool:
        """Whether a van der Waals term acts (a Hamaker constant > 0)."""
        return bool(self.hamaker)

    @property
    def retardation(self) -> float:
        """Retardation b = 5.32/λ of the van der Waals attraction, m⁻¹: :func:`retardation`."""
        return retardation(self.retardation_wavelength)

    @property
    def retardation_label(self) -> str:
        """``lambda = 100 nm`` or ``non-retarded``: the retardation, for messages."""
        if self.retardation_wavelength is None:
            return "non-retarded"
        return f"lambda = {self.retardation_wavelength * 1e9:.4g} nm"

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
        band = 2 * self.kelvin_radius * math.cos(self.contact_angle)
        if band < NANO_GAP * self.asperity_roughness:
            return (
                f"menisci confined to the asperities' contacts: the Kelvin band 2 r_K cos(theta) "
                f"= {band * 1e9:.3g} nm < {NANO_GAP:g} sigma_n = "
                f"{NANO_GAP * self.asperity_roughness * 1e9:.3g} nm (rh = {self.rh:g}; they "
                f"spread from RH_cr = {self.critical_rh:.3g}); the confined bridges' pull is "
                "neglected"
            )
        return None

    @property
    def bridging_rh(self) -> float:
        """DelRio's RH_dry: the humidity above which liquid bridges form at all, where the
        isotherm's film passes the structured layers (:func:`mcsim.physics.films.film_humidity`);
        0 with no structured layers; with a given ``film_thickness``, 0 if it passes them,
        else 1 (none at any RH)."""
        if self.structured_film == 0:
            return 0.0
        if self.film_thickness is not None:
            return 0.0 if self.film_thickness > self.structured_film else 1.0
        return float(films.film_humidity(self.structured_film))

    @property
    def critical_rh(self) -> float:
        """DelRio's RH_cr: the humidity from which menisci spread across the interface, the
        larger of :attr:`bridging_rh` and the RH at which the Kelvin band 2 r_K cos θ equals
        the nano-gap :data:`NANO_GAP` σ_n (r_K = γ_L V_m/(R_g T ln(1/RH)), inverted); 1 for a
        liquid that does not wet (θ >= 90°)."""
        cos = math.cos(self.contact_angle)
        if cos <= 0:
            return 1.0
        gap = NANO_GAP * self.asperity_roughness
        if gap == 0:
            return self.bridging_rh
        radius = gap / (2 * cos)
        scale = self.surface_tension * self.molar_volume / (GAS_CONSTANT * self.temperature)
        return max(self.bridging_rh, math.exp(-scale / radius))

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


def _wavelength(value) -> float | None:
    """``retardation_wavelength`` as users write it: a length, or None or ``"none"``."""
    if value is None or (isinstance(value, str) and value.strip().lower() == "none"):
        return None
    return parse_quantity(value, "length", "retardation_wavelength")


def retardation(wavelength: float | None) -> float:
    """Retardation b = 5.32/λ of the van der Waals attraction, m⁻¹; 0 (non-retarded) for None.

    Gregory, J. Colloid Interface Sci. 83, 138 (1981): two flat plates attract with the energy
    A/(12π D²) · 1/(1 + b D) per area, b = 5.32/λ (:data:`GREGORY_B`), λ ≈ 100 nm the
    characteristic wavelength of the dispersion interaction.

    Parameters
    ----------
    wavelength : float or None
        Retardation wavelength λ, m, > 0; None: no retardation.
    """
    return 0.0 if wavelength is None else GREGORY_B / wavelength


def vdw_flat_energy(gap, hamaker, retardation):
    """Retarded van der Waals energy per area of two flats, J/m² (> 0 attractive).

    W(g) = A/(12π g²) · 1/(1 + b g), b = 5.32/λ: Gregory's flat plates (J. Colloid
    Interface Sci. 83, 138, 1981); by Derjaguin (F_sphere = 2πR W) a sphere pulls with
    A R/(6 g²) · 1/(1 + b g). b = 0: the non-retarded A/(12π g²) (Israelachvili,
    *Intermolecular and Surface Forces*, 3rd ed., Eq. 13.11).

    Parameters
    ----------
    gap : array_like
        Gap g between the flats, m (> 0).
    hamaker : array_like
        Hamaker constant A, J.
    retardation : array_like
        b = 5.32/λ, m⁻¹ (:func:`retardation`); 0: non-retarded.

    Returns
    -------
    ndarray
        W, J/m².
    """
    return hamaker / (12 * math.pi) * _energy_kernel(np.asarray(gap, dtype=float), retardation)


def vdw_flat_pressure(gap, hamaker, retardation):
    """Retarded van der Waals pressure between two flats, Pa (> 0 attractive).

    p(g) = −dW/dg of :func:`vdw_flat_energy`:
    (A/12π) [2/(g³(1 + b g)) + b/(g²(1 + b g)²)]; b = 0: A/(6π g³) (Israelachvili Eq. 13.11).

    Parameters
    ----------
    gap, hamaker, retardation
        As for :func:`vdw_flat_energy`.

    Returns
    -------
    ndarray
        p, Pa.
    """
    return hamaker / (6 * math.pi) * _pressure_kernel(np.asarray(gap, dtype=float), retardation)


def _energy_kernel(gap, b):
    """W/(A/12π) = g⁻²/(1 + b g), m⁻² (:func:`vdw_flat_energy`)."""
    return gap**-2 / (1 + b * gap)


def _pressure_kernel(gap, b):
    """p/(A/6π) = g⁻³/(1 + b g) + (b/2) g⁻²/(1 + b g)², m⁻³ (:func:`vdw_flat_pressure`;
    minus half the derivative of :func:`_energy_kernel`)."""
    damping = 1 / (1 + b * gap)
    return gap**-3 * damping + b / 2 * gap**-2 * damping**2


#: The names a mapping of the environment may give a field other than its own: the keys of
#: an ``[environment]`` table and the command line's options (``--liquid-surface-tension``)
#: say whose surface tension it is. Both names are read, by :func:`environment_fields`.
KEY_ALIASES = {"liquid_surface_tension": "surface_tension"}


def environment_fields(values: Mapping) -> dict:
    """The :class:`Environment` fields that a mapping as users write it sets: its keys, as in a
    TOML ``[environment]`` table (``liquid_surface_tension``) or as the fields are named
    (``surface_tension``), resolved to the fields; the values untouched.

    The one resolver of the environment's keys, for TOML files, the command line and the
    Python API alike.

    Raises
    ------
    ParameterError
        A key that names no field, or two keys for one field.
    """
    names = {f.name: f.name for f in dataclasses.fields(Environment)} | KEY_ALIASES
    unknown = sorted(str(k) for k in values if k not in names)
    if unknown:
        allowed = [k for k in names if k not in KEY_ALIASES.values()]
        raise ParameterError(f"unknown key(s) {', '.join(unknown)} (allowed: {', '.join(allowed)}; "
                             f"{', '.join(f'{v} for {k}' for k, v in KEY_ALIASES.items())})")  # fmt: skip
    fields: dict = {}
    for key, value in values.items():
        if names[key] in fields:
            first = next(k for k in values if names[k] == names[key])
            raise ParameterError(f"{first} and {key} set the same field: give one")
        fields[names[key]] = value
    return fields


def as_environment(value) -> Environment | None:
    """The ``environment`` argument of the Python API: None, an :class:`Environment`, or a
    mapping as written in a TOML ``[environment]`` table (:func:`environment_fields`, then
    :meth:`Environment.from_user`, e.g. ``{"rh": 0.5, "hamaker": "1.6e-19 J",
    "contact_angle": "20 deg", "liquid_surface_tension": "72 mJ/m^2"}``; there a bare
    ``contact_angle`` is in degrees, where ``Environment(contact_angle=...)`` takes radians).

    Raises
    ------
    ParameterError
        Anything else, or a mapping with a key that names no field (one line starting
        ``environment:``).
    """
    if value is None or isinstance(value, Environment):
        return value
    if isinstance(value, Mapping):
        try:
            fields = environment_fields(value)
        except ParameterError as err:
            raise ParameterError(f"environment: {err}") from None
        return Environment.from_user(**fields)
    fields = [f.name for f in dataclasses.fields(Environment)]
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


def _gaussian_gap_moment(D, rq, cutoff, n: int, b):
    """E[k_n(g); g >= D0] for g = D − z, z ~ N(0, Rq²), by a fixed quadrature: the retarded
    kernels of :func:`_gap_kernel`, k_3 = p/(A/6π) (m⁻³) and k_2 = W/(A/12π) (m⁻²); with
    b = 0, E[g⁻ⁿ; g >= D0].

    With t = (g − D0)/Rq >= 0 and a = (D − D0)/Rq the integral is
    ∫₀^∞ k_n(D0 + Rq t) φ(a − t) dt. Its two scales, the pole of k_n at g = 0, at
    distance τ = t + D0/Rq from it, and the unit width of the Gaussian, are both resolved
    by the map ξ = τ + ln τ (geometric near the pole, uniform far from it; inverse
    τ = ω(ξ), the Wright omega function, analytic in a strip of half-width π). The
    retardation's pole, at g = −1/b, lies farther from the path than g = 0 and maps to
    Im ξ = π, the strip's edge. The Gaussian is cut where it falls by e^-60, and
    [ξ(t_lo), ξ(t_hi)] is split into equal Gauss–Legendre panels: non-retarded ~1e-14
    relative against 40-digit mpmath over Rq/D0 from 1e-3 to 1e3 and a from −30 to 30
    (tests/physics/test_environment.py). Retarded, against 30-digit mpmath over λ = 1 nm,
    100 nm and none, Rq/D0 = 1e-3, 1, 1e3 and a = −3, 0.5, 30: at worst 2.6e-13 (Rq/D0 =
    1e-3, a = −3, the same with and without retardation), ~1e-14 elsewhere
    (tests/physics/test_environment_retarded.py).
    """
    a = (D - cutoff) / rq
    shift = cutoff / rq
    t_lo = np.maximum(a - math.sqrt(2 * VDW_TAIL), 0.0)
    # Above a the weight φ(a − t) falls by e^-VDW_TAIL at t² − 2 a t = 2 VDW_TAIL
    # (a < 0: steeply).
    t_hi = np.where(
        a >= 0, a + math.sqrt(2 * VDW_TAIL), 2 * VDW_TAIL / (np.sqrt(a * a + 2 * VDW_TAIL) - a)
    )
    tau_lo, tau_hi = t_lo + shift, t_hi + shift
    xi_lo = tau_lo + np.log(tau_lo)
    span = tau_hi + np.log(tau_hi) - xi_lo
    tau = special.wrightomega(xi_lo[..., None] + span[..., None] * _NODES).real
    t = tau - shift[..., None]
    gap = rq[..., None] * tau  # = D0 + Rq t
    density = np.exp(-0.5 * (a[..., None] - t) ** 2) / math.sqrt(2 * math.pi)
    kernel = _gap_kernel(gap, b[..., None], n)
    return span * np.sum(_WEIGHTS * kernel * density * tau / (1 + tau), axis=-1)


def _gap_kernel(gap, b, n: int):
    """The retarded flats' pressure over A/6π (n = 3, :func:`_pressure_kernel`, m⁻³) or
    energy over A/12π (n = 2, :func:`_energy_kernel`, m⁻²) at gap g; g⁻ⁿ for b = 0."""
    return _pressure_kernel(gap, b) if n == 3 else _energy_kernel(gap, b)


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
    # The bin's part below the cutoff: exactly 0 for an open bin (the bin's width less its open
    # part, g_b − g_a, would leave D's rounding there, which k(D0)/k(g) then amplifies).
    contact = np.minimum(g_hi, cutoff) - np.minimum(g_lo, cutoff)
    return g_a, g_b, contact, density


def _is_histogram(heights) -> bool:
    return hasattr(heights, "densities")


def _gap_moment(D, heights, cutoff, n: int, b):
    """E[k_3(g); g >= D0] (n = 3, m⁻³) or E[k_2(max(g, D0))] (n = 2, m⁻²) for g = D − z,
    with the retarded kernels of :func:`_gap_kernel` (b, m⁻¹); g⁻ⁿ for b = 0.

    Histogram: exact over each bin [g_a, g_b] of the piecewise-constant density, written as
    products of h = g_b − g_a (no cancellation for narrow bins), plus k_2(D0) times the
    contact length for n = 2. As −dk_2/dg = 2 k_3, ∫ k_3 dg = (k_2(g_a) − k_2(g_b))/2 =
    h [(g_a + g_b) + b (g_a² + g_a g_b + g_b²)] / [2 g_a² g_b² (1 + b g_a)(1 + b g_b)];
    and ∫ k_2 dg = [−1/g + b ln((1 + b g)/g)] from g_a to g_b =
    h/(g_a g_b) − b ln(1 + h/(g_a (1 + b g_b))), which leaves only rounding, ~(1 + b g_b) ε
    relative (the two terms cancel to 1/(1 + b g_b) of the first): 3e-14 for a bin at 1 µm
    with λ = 100 nm. For b = 0 both are the non-retarded (g_a⁻² − g_b⁻²)/2 and 1/g_a − 1/g_b.
    """
    cutoff = np.asarray(cutoff, dtype=float)
    b = np.asarray(b, dtype=float)
    if _is_histogram(heights):
        g_a, g_b, contact, density = _histogram_bins(D, heights, cutoff[..., None])
        h, b = g_b - g_a, b[..., None]
        if n == 3:
            rise = (g_b + g_a) + b * (g_a * g_a + g_a * g_b + g_b * g_b)
            per_bin = h * rise / (2 * g_a**2 * g_b**2 * (1 + b * g_a) * (1 + b * g_b))
        else:
            per_bin = h / (g_a * g_b) - b * np.log1p(h / (g_a * (1 + b * g_b)))
            per_bin = per_bin + contact * _energy_kernel(cutoff[..., None], b)
        return np.sum(density * per_bin, axis=-1)
    D, rq, cutoff, b = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (D, heights, cutoff, b))
    )
    moment = _gaussian_gap_moment(D, rq, cutoff, n, b)
    if n == 3:
        return moment
    return moment + special.ndtr(-(D - cutoff) / rq) * _energy_kernel(cutoff, b)


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


def vdw_pressure(D, heights, hamaker, cutoff, retardation):
    """Van der Waals attraction across the non-contacting gaps, Pa (positive: attractive).

    p_vdW(D) = E[p(g); g >= D0], g = D − z, with p the retarded flat–flat pressure
    (:func:`vdw_flat_pressure`; Gregory 1981) (DelRio et al. 2005, non-retarded: b = 0 gives
    (A/6π) E[g⁻³; g >= D0], Israelachvili Eq. 13.11).

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
    retardation : array_like
        b = 5.32/λ, m⁻¹ (:func:`retardation`, :attr:`Environment.retardation`); 0:
        non-retarded.

    Returns
    -------
    ndarray
        p_vdW, Pa, of the broadcast shape of the arguments.
    """
    return hamaker / (6 * math.pi) * _gap_moment(D, heights, cutoff, 3, retardation)


def vdw_work(D_t, heights, hamaker, cutoff, retardation):
    """Van der Waals work of separation from ``D_t`` to infinity, J/m².

    W_vdW(D_t) = E[W(max(D_t − z, D0))], W the retarded flat–flat energy
    (:func:`vdw_flat_energy`; b = 0: DelRio et al. 2005's Σ A/(12π D_i²));
    −dW/dD = :func:`vdw_pressure`. Flat surfaces at contact: A/(12π D0²)/(1 + b D0).

    Parameters
    ----------
    D_t : array_like
        Mean-plane gap at the closest approach, m.
    heights, hamaker, cutoff, retardation
        As for :func:`vdw_pressure`.

    Returns
    -------
    ndarray
        W_vdW, J/m².
    """
    return hamaker / (12 * math.pi) * _gap_moment(D_t, heights, cutoff, 2, retardation)


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
