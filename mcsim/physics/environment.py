"""The environment: the medium between the surfaces, van der Waals and a condensing vapour.

See docs/physics.md, sections 'The environment' and 'The environment: summits and open gaps'.

The medium (:class:`Environment`: its Hamaker constant, cutoff and retardation, the vapour's
humidity and the liquid's constants, the adsorbed films), as users write it
(:func:`environment_fields`, :func:`as_environment`), with the Kelvin radius of its menisci
(:func:`kelvin_radius`) and the retardation of its van der Waals attraction
(:func:`retardation`). The local laws over a height distribution build on it: van der Waals
attraction across the gaps (:mod:`mcsim.physics.vanderwaals`) and capillary condensation
(:mod:`mcsim.physics.capillary`). mcsim applies them in two parts that never count one area
twice, each summit's cap and the open gaps between the caps:
:mod:`mcsim.physics.surfaceenvironment`.

Both laws are a proximity (pixel-by-pixel Derjaguin) model over the height distribution of
the combined rough surface (DelRio et al., Nature Materials 4, 629, 2005; DelRio et al.,
Appl. Phys. Lett. 90, 163104, 2007). Heights z about the mean plane are Gaussian with rms Rq,
or a measured height histogram (:class:`~mcsim.empirical.Empirical`, a piecewise-constant
density: :func:`mcsim.physics.gapheights.histogram_gaps`). At mean-plane gap D the local gap
is g = D − z; where g < D0 (the cutoff) the surfaces touch and the contact law rules,
elsewhere each law gives a pressure p(D) and a work of separation W(D_t) per nominal area,
positive when attractive, with −dW/dD = p.

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
        The flats' energy A/(12πg²) is reduced by 1/(1 + 5.32 g/λ)
        (:func:`~mcsim.physics.vanderwaals.vdw_flat_energy`).

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
        else:  # a bare number is in degrees: the same float as the string "<number> deg"
            degrees = parse_quantity(contact_angle, "dimensionless", "contact_angle")
            angle = parse_quantity(f"{degrees!r} deg", "angle", "contact_angle")
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

    def acting(self) -> Environment:
        """This environment as it acts: without liquid bridges (:attr:`has_capillary` False)
        the humidity enters none of its terms (the capillary ones are off, the van der Waals
        ones do not read it), and it acts as it does at RH 0, which this returns."""
        return self if self.has_capillary or self.rh == 0 else dataclasses.replace(self, rh=0.0)

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
