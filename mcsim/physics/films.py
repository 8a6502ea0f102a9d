"""Adsorbed water films: their thickness on each face against relative humidity.

See docs/physics.md, section 'Water below the Kelvin gate: adsorbed films'.

A hydrophilic solid in humid air carries a film of water of thickness t(RH) on each face,
long before a meniscus of Kelvin radius r_K can form. mcsim describes it by the
Frenkel–Halsey–Hill (FHH) isotherm

    t(RH) = t_ref (ln(1/RH_ref) / ln(1/RH))^(1/n),

t(0) = 0, t → ∞ as RH → 1, fitted to two measured anchors on silicon oxide, in layers of
one water molecule (:data:`WATER_LAYER`, 0.28 nm):

* Asay & Kim, J. Phys. Chem. B 109, 16760 (2005): about 3 layers, ice-like, by RH 0.30
  (:data:`REFERENCE_RH`, :data:`REFERENCE_FILM`);
* Verdaguer et al., Langmuir 23, 9699 (2007): 6–7 layers at ~90 % RH; 6.5 layers at 0.90
  (:data:`HUMID_RH`, :data:`HUMID_FILM`).

Their exponent n = ln(ln(1/0.30)/ln(1/0.90)) / ln(6.5/3) ≈ 3.15 (:data:`FHH_EXPONENT`) is
close to FHH's 3 for a film held by van der Waals forces, and the isotherm predicts
t(0.75) ≈ 4.7 layers, inside Verdaguer et al.'s 4–5 up to ~75 % RH: a check out of sample
(tests/physics/test_films.py). The first ~3 layers are structured (ice-like, Asay & Kim) and
form no liquid bridges: :data:`STRUCTURED_FILM`, the thickness above which the film is
liquid-like enough to (:attr:`mcsim.physics.environment.Environment.no_condensation_reason`).
"""

from __future__ import annotations

import math

import numpy as np

#: Thickness of one layer of water, m: the diameter of a water molecule, 0.28 nm (its
#: nearest-neighbour O–O distance in ice and liquid water; Israelachvili, *Intermolecular and
#: Surface Forces*, 3rd ed., 2011).
WATER_LAYER = 0.28e-9

#: The isotherm's reference humidity RH_ref and film t_ref = t(RH_ref), m: about 3 layers by
#: RH 0.30 (Asay & Kim, J. Phys. Chem. B 109, 16760, 2005), 0.84 nm.
REFERENCE_RH = 0.30
REFERENCE_FILM = 3 * WATER_LAYER

#: The second anchor: 6.5 layers at RH 0.90 (Verdaguer et al., Langmuir 23, 9699, 2007:
#: 6–7 layers at ~90 %), m.
HUMID_RH = 0.90
HUMID_FILM = 6.5 * WATER_LAYER

#: The FHH exponent n through both anchors, ≈ 3.15.
FHH_EXPONENT = math.log(math.log(1 / REFERENCE_RH) / math.log(1 / HUMID_RH)) / math.log(
    HUMID_FILM / REFERENCE_FILM
)

#: Thickness of the structured (ice-like) first layers, m: 3 layers, 0.84 nm (Asay & Kim
#: 2005: ice-like up to ~3 layers, complete near RH 0.30). Only a film thicker than this
#: carries liquid-like water that forms capillary bridges.
STRUCTURED_FILM = 3 * WATER_LAYER


def film_thickness(rh, reference=REFERENCE_FILM, reference_rh=REFERENCE_RH, exponent=FHH_EXPONENT):
    """Adsorbed film on each face, t = t_ref (ln(1/RH_ref)/ln(1/RH))^(1/n), m, vectorised.

    Parameters
    ----------
    rh : array_like
        Relative humidity, in [0, 1]: t(0) = 0, t(1) = inf.
    reference : float
        t_ref = t(RH_ref), m (default :data:`REFERENCE_FILM`, 0.84 nm).
    reference_rh : float
        RH_ref, in (0, 1) (default :data:`REFERENCE_RH`, 0.30).
    exponent : float
        FHH exponent n > 0 (default :data:`FHH_EXPONENT`, ≈ 3.15).

    Returns
    -------
    ndarray
        t, m.
    """
    rh = np.asarray(rh, dtype=float)
    with np.errstate(divide="ignore"):
        return reference * (math.log(1 / reference_rh) / np.log(1 / rh)) ** (1 / exponent)


def film_humidity(thickness, reference=REFERENCE_FILM, reference_rh=REFERENCE_RH,
                  exponent=FHH_EXPONENT):  # fmt: skip
    """The humidity at which the film of :func:`film_thickness` is ``thickness`` thick, its
    inverse: RH = RH_ref^((t_ref/t)^n), vectorised (0 at t = 0, 1 as t → ∞).

    Parameters
    ----------
    thickness : array_like
        t, m, >= 0.
    reference, reference_rh, exponent
        As for :func:`film_thickness`.

    Returns
    -------
    ndarray
        RH.
    """
    thickness = np.asarray(thickness, dtype=float)
    with np.errstate(divide="ignore"):
        return reference_rh ** ((reference / thickness) ** exponent)
