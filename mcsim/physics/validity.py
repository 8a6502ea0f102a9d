"""Where GW's independent summits stop making sense: the validity warnings of its curves.

Greenwood & Williamson (1966) treat every summit as an independent Hertz (or adhesive)
contact on a rigid substrate. That holds while the contact spots are few and far apart. Two
numbers say when it no longer does:

* **the real contact area fraction** A_r/A_n. Above :data:`INTERACTING_AREA` = 0.1 the spots
  are close enough for each one's elastic field to lower its neighbours' (interaction;
  Ciavarella, Greenwood & Paggi, Wear 265 (2008) 729) and they merge; GW, which leaves both
  out, gives too small an area. Measured with mcsim's exact solver (``mcsim contact``,
  docs/contact.md) on the shipped periodic example: GW's area is 0.98 of the exact one at
  A_r/A_n = 0.003, 0.84 at 0.02 and 0.72 at 0.18. The bound is a conventional one, not a
  sharp edge. Above 1 the summits' areas add up to more than the nominal area: the sum
  counts overlapping spots many times and means nothing.
* **the work of separation of the contact** per nominal area. Separating a complete, flat
  contact needs the work of adhesion w; a rough one, touching on part of its area, needs
  less. GW's summed summit works above w are the same overlap counted many times. (With an
  environment the van der Waals and capillary works across the gaps add to it legitimately,
  up to 2γ_L cos θ for water: the check is on the contact part alone.)

The separation h = d/σ at which GW gives these numbers is in the message: at least the
curves there are outside the model, whatever the law set. ``mcsim analytic`` and ``mcsim
adhesion`` print the lines; :func:`mcsim.physics.adhesion.adhesion_summary` also issues them
as :class:`~mcsim.physics.adhesion.ValidityWarning` and
:meth:`mcsim.physics.analytic.AnalyticCurves.validity_warnings` returns them.
"""

from __future__ import annotations

import math

import numpy as np

#: Real contact area fraction above which neighbouring contacts interact (module docstring).
INTERACTING_AREA = 0.1


def area_warnings(area_fraction, h) -> list[str]:
    """Lines about a real contact area beyond the nominal area or beyond :data:`INTERACTING_AREA`.

    Parameters
    ----------
    area_fraction : array_like
        GW's real over nominal contact area A_r/A_n (dimensionless); NaN entries are skipped.
    h : array_like
        The separations d/σ (dimensionless) they belong to, same shape.

    Returns
    -------
    list of str
        At most one line: the largest area fraction and its separation; empty where every
        area fraction is at most :data:`INTERACTING_AREA`.
    """
    area = np.atleast_1d(np.asarray(area_fraction, dtype=float))
    h = np.broadcast_to(np.asarray(h, dtype=float), area.shape)
    if not np.any(area > INTERACTING_AREA):  # all NaN or small
        return []
    i = int(np.nanargmax(area))
    where = f"A_r/A_n = {area[i]:.3g} at h = {h[i]:.6g}"
    if area[i] > 1:
        return [
            f"GW's real contact area passes the nominal area ({where}): its independent summits "
            "overlap and the sum of their areas means nothing there; the model does not hold at "
            "this separation (mcsim contact solves a measured map exactly)"
        ]
    return [
        f"GW's real contact area is beyond where independent summits hold ({where} > "
        f"{INTERACTING_AREA:g}): neighbouring contacts interact elastically and merge, which GW "
        "leaves out, so its area is too small there (mcsim contact solves a measured map exactly)"
    ]


def work_warnings(work_contact: float, w: float) -> list[str]:
    """A line when the contact's work of separation exceeds the work of adhesion ``w``.

    Parameters
    ----------
    work_contact : float
        Work of separation of the summits' contact law, J/m² of nominal area (without the
        environment's van der Waals and capillary parts).
    w : float
        Work of adhesion of the materials, J/m²: what separating a complete flat contact needs.

    Returns
    -------
    list of str
        Empty unless ``work_contact`` > ``w``.
    """
    if not (math.isfinite(work_contact) and work_contact > w):
        return []
    return [
        f"GW's work of separation of the contact, {work_contact:.3g} J/m^2, exceeds the work of "
        f"adhesion w = {w:.3g} J/m^2 that separating a complete flat contact needs: the summits "
        "overlap at the turn and their works are counted many times; the model does not hold "
        "this deep (a shallower --turn or a --preload keeps it in range)"
    ]
