"""The variables of a sweep file (:mod:`mcsim.store.sweepfile`): the inputs a sweep can vary,
the summary, regime, pads and string variables and the curves, each with its unit and
meaning (the file's ``units`` and ``long_name``).
"""

from __future__ import annotations

import numpy as np

from mcsim.model.units import SI_UNITS

#: Inputs a sweep can vary: dimension of their values, the fields they set, meaning.
INPUTS: dict[str, tuple[str, tuple[str, ...], str]] = {
    "sigma": ("length", ("sigma",), "standard deviation of the summit heights"),
    "R": ("length", ("R",), "summit radius"),
    "eta": ("density", ("eta",), "summit density"),
    "E": ("pressure", ("E1", "E2"), "Young's modulus of both solids"),
    "E1": ("pressure", ("E1",), "Young's modulus of solid 1"),
    "E2": ("pressure", ("E2",), "Young's modulus of solid 2"),
    "nu": ("dimensionless", ("nu1", "nu2"), "Poisson's ratio of both solids"),
    "nu1": ("dimensionless", ("nu1",), "Poisson's ratio of solid 1"),
    "nu2": ("dimensionless", ("nu2",), "Poisson's ratio of solid 2"),
    "gamma": ("energy_per_area", ("gamma",), "work of adhesion"),
    "w": ("energy_per_area", ("gamma",), "work of adhesion"),
    "z0": ("length", ("z0",), "equilibrium spacing"),
    "tau": ("pressure", ("tau",), "interfacial shear strength"),
    "H": ("pressure", ("H",), "hardness"),
    "law": ("", ("law",), "law set"),
    "area": ("area", ("area",), "nominal pad area of the Monte Carlo patches"),
    "rh": ("dimensionless", ("rh",), "relative humidity of the environment"),
    "hamaker": ("energy", ("hamaker",), "Hamaker constant across the gaps"),
    "contact_angle": ("angle", ("contact_angle",), "contact angle of the condensing liquid"),
    "cutoff": ("length", ("cutoff",), "cutoff gap D0 of the environment (contact below it)"),
    "temperature": ("temperature", ("temperature",), "temperature of the environment"),
    "film_thickness": ("length", ("film_thickness",), "adsorbed film on each face (given)"),
    "structured_film": ("length", ("structured_film",), "ice-like first layers of the film"),
    "asperity_roughness": (
        "length",
        ("asperity_roughness",),
        "rms of the asperities' nanoscale roughness",
    ),
    "retardation_wavelength": (
        "length",
        ("retardation_wavelength",),
        "retardation wavelength of the van der Waals attraction",
    ),
    "restoring_force": ("force", ("restoring_force",), "restoring force pulling each pad off"),
    "preload": ("pressure", ("preload",), "nominal pressure pressing each pad (force control)"),
    "tangential_force": ("force", ("tangential_force",), "tangential force on each pad"),
}

#: Inputs of :data:`INPUTS` that only the pads take (:func:`mcsim.sweep` with ``pads``).
PAD_INPUTS = ("restoring_force", "tangential_force")

#: Inputs of :data:`INPUTS` that set the environment (:class:`mcsim.physics.environment.Environment`).
ENVIRONMENT_INPUTS = ("rh", "hamaker", "contact_angle", "cutoff", "temperature", "film_thickness",
                      "structured_film", "asperity_roughness", "retardation_wavelength")  # fmt: skip


#: Dimension name of each input whose name is taken by an output.
DIMENSION = {"area": "pad_area"}


#: Adhesion-summary variables: unit and meaning.
SUMMARY = {
    "pull_off": ("1", "pull-off force/(A_n K): most tensile load on retraction (magnitude)"),
    "h_pull_off": ("1", "separation d/sigma of the pull-off"),
    "pull_off_pressure": ("Pa", "pull-off force per nominal area"),
    "work_of_separation": ("J/m^2", "integral of the tensile load over d on retraction"),
    "hysteresis": ("J/m^2", "integral of (approach - retraction load) over d"),
    "turn": ("1", "closest approach h_turn = d_turn/sigma before retraction"),
}


#: Adhesion-summary variables of a sweep with an environment: unit and meaning.
ENVIRONMENT_SUMMARY = {
    "work_of_separation_contact": ("J/m^2", "contact part of work_of_separation"),
    "work_of_separation_vdw": (
        "J/m^2",
        "van der Waals work of separation from the turn to infinity",
    ),
    "work_of_separation_capillary": (
        "J/m^2",
        "capillary work of separation from the turn to infinity",
    ),
    "kelvin_radius": ("m", "Kelvin radius r_K = gamma_L V_m/(R T ln(1/RH))"),
    "rq": ("m", "rms height about the mean plane used by the environment"),
    "summit_offset": ("m", "mean summit plane above the mean plane used by the environment"),
}

#: Per-point variables of a pads sweep (``mcsim sweep --pads``): unit and meaning.
PADS = {
    "p_stick": (
        "1",
        "probability that a pad's pull-off exceeds the restoring force (p_stick_method)",
    ),
    "p_stick_low": (
        "1",
        "lower end of the 95 % interval of p_stick (pads: Clopper-Pearson; importance: Clopper-Pearson on the effective sample size)",
    ),
    "p_stick_high": (
        "1",
        "upper end of the 95 % interval of p_stick (pads: Clopper-Pearson; importance: Clopper-Pearson on the effective sample size)",
    ),
    "p_stick_ess": (
        "1",
        "effective number of pads on the rarer side, sticking or not (pads: their count)",
    ),
    "pull_off_mean": ("N", "mean pull-off force of the pads"),
    "pull_off_std": ("N", "standard deviation of the pads' pull-off force (ddof = 1)"),
    "pull_off_q05": ("N", "5 % quantile of the pads' pull-off force"),
    "pull_off_q50": ("N", "median of the pads' pull-off force"),
    "pull_off_q95": ("N", "95 % quantile of the pads' pull-off force"),
    "work_of_separation_mean": ("J/m^2", "mean work of separation of the pads, -int F dd / A"),
    "work_of_separation_std": ("J/m^2", "standard deviation of the pads' work of separation"),
    "work_of_separation_q05": ("J/m^2", "5 % quantile of the pads' work of separation"),
    "work_of_separation_q50": ("J/m^2", "median of the pads' work of separation"),
    "work_of_separation_q95": ("J/m^2", "95 % quantile of the pads' work of separation"),
    "pull_off_analytic": (
        "N",
        "GW mean pull-off of one pad: pull_off x A K after the mean-field turn",
    ),
    "p_stick_model": (
        "1",
        "model p_stick: compound-Poisson pull-off, Lugannani-Rice saddlepoint tail (mcsim.studies.stiction)",
    ),
    "contacting_summits": (
        "1",
        "expected summits per pad above the mean-field turn, eta A S(h_turn)",
    ),
}

#: Variables of :data:`PADS` that a pads sweep holds only with a restoring force.
STICK = ("p_stick", "p_stick_low", "p_stick_high", "p_stick_ess", "p_stick_model")

#: Text variables of a pads sweep: meaning.
PAD_STRINGS = {
    "p_stick_method": "how p_stick was estimated: pads (fraction of the pads) or importance "
    "(importance sampling, mcsim.studies.tail)",
}

#: Text variables of a pads sweep with a tangential force: meaning.
SLIP_STRINGS = {
    "p_slip_method": "how p_slip was estimated: pads (fraction of the pads) or importance "
    "(importance sampling, mcsim.studies.tail)",
}

#: Per-point variables of a pads sweep with friction (``--friction`` or a tangential force).
FRICTION = {
    "static_friction_mean": ("N", "mean static friction T_s of the pads at their turns: sum of "
                             "the touching summits' friction (Savkoor-Briggs, or tau x area)"),
    "static_friction_std": ("N", "standard deviation of the pads' static friction (ddof = 1)"),
    "static_friction_q05": ("N", "5 % quantile of the pads' static friction"),
    "static_friction_q50": ("N", "median of the pads' static friction"),
    "static_friction_q95": ("N", "95 % quantile of the pads' static friction"),
    "mu_static_mean": ("1", "mean static friction coefficient mu_s = T_s/W of the pads, W the "
                       "preload force P A (at P = 0 the environment's pull at the turn)"),
    "mu_static_std": ("1", "standard deviation of the pads' mu_s (ddof = 1)"),
    "mu_static_q05": ("1", "5 % quantile of the pads' mu_s"),
    "mu_static_q50": ("1", "median of the pads' mu_s"),
    "mu_static_q95": ("1", "95 % quantile of the pads' mu_s"),
}  # fmt: skip

#: Per-point variables of a pads sweep with a tangential force.
SLIP = {
    "p_slip": ("1", "probability that a pad's static friction is below the tangential force "
               "(p_slip_method)"),
    "p_slip_low": ("1", "lower end of the 95 % interval of p_slip (as p_stick_low)"),
    "p_slip_high": ("1", "upper end of the 95 % interval of p_slip (as p_stick_high)"),
    "p_slip_ess": ("1", "effective number of pads on the rarer side, slipping or not (pads: "
                   "their count)"),
}  # fmt: skip


#: Regime numbers of one summit: meaning (all dimensionless).
REGIME = {
    "tabor": "Tabor mu_T = (R w^2/(E*^2 z0^3))^(1/3)",
    "maugis_lambda": "Maugis lambda = 2 sigma0 (R/(pi w K^2))^(1/3), sigma0 = w/(0.97 z0)",
    "adhesion_parameter": "Fuller-Tabor theta = E* sigma^(3/2)/(R^(1/2) w)",
    "plasticity_index": "psi = (E*/H) sqrt(sigma/R)",
}


#: Per-point strings.
STRINGS = {
    "law_used": "law set of the point (auto resolved on the adhesion map)",
    "regime_warning": "regime warnings of the point, joined by '; ' (empty: none)",
    "error": "why the point failed (empty: it did not)",
}


#: Normalisation of each curve (its long_name).
CURVES = {
    "contact_fraction": "N_c/N, fraction of summits in contact",
    "P": "Hertz load P/(A_n K) (Eq. 3)",
    "F": "JKR adhesion term F/(A_n K) (Eq. 5)",
    "T": "adhesional friction T/(A_n K) (Eq. 7)",
    "mu": "friction coefficient: T/(P + F) (seed, Eq. 8), friction/load (other law sets)",
    "load": "net normal force/(A_n K), positive when compressive",
    "area": "real contact area A_r/A_n",
    "friction": "friction tau A_r/(A_n K) (Bowden-Tabor)",
    "vdw": "van der Waals attraction across the gaps per nominal area/K, > 0 attractive",
    "capillary": "capillary attraction per nominal area/K, > 0 attractive",
}


def plain(value):
    """A NumPy scalar as a Python number (what :func:`parse_quantity` takes)."""
    return value.item() if isinstance(value, np.generic) else value


def dimension_name(name: str) -> str:
    """Name of the file's dimension for the varied input ``name`` (``area`` → ``pad_area``)."""
    return DIMENSION.get(name, name)


def input_unit(name: str) -> str:
    """SI unit of the varied input ``name`` (``"1"`` for the law set's name)."""
    dimension = INPUTS[name][0]
    return "1" if name == "law" else SI_UNITS[dimension]
