"""The exact contact of a map beside GW's: the contact map and the real area against load."""

from __future__ import annotations

import numpy as np


def contact_figure(result):
    """Contact map at the highest load, and A_r/A_n against p/E*, exact and GW.

    Parameters
    ----------
    result : ContactResult
        From :func:`mcsim.studies.contact.contact_map` with ``keep_fields=True``.

    Returns
    -------
    matplotlib.figure.Figure
        Left: the contact pressure at the highest load, MPa, over the map (x, y in µm; white:
        no contact). Right: real over nominal contact area against nominal pressure over E*,
        log–log, exact (boundary elements, at the map's pixel size) and GW (Hertz summits).
    """
    from matplotlib.figure import Figure

    from mcsim.figures.style import _COLOURS

    fig = Figure(figsize=(10, 4.2), layout="constrained")
    left, right = fig.subplots(1, 2)
    field = result.pressure_fields[-1] / 1e6
    ny, nx = result.shape
    extent = (0, nx * result.dx * 1e6, 0, ny * result.dy * 1e6)
    image = left.imshow(np.ma.masked_equal(field, 0.0), origin="lower", extent=extent,
                        cmap="viridis", interpolation="nearest")  # fmt: skip
    fig.colorbar(image, ax=left, label="Contact pressure (MPa)")
    left.set_xlabel(r"$x$ (µm)")
    left.set_ylabel(r"$y$ (µm)")
    left.set_title(f"p = {result.pressure[-1] / 1e6:.3g} MPa, A$_r$/A$_n$ = "
                   f"{result.area_fraction[-1]:.3g}", fontsize="medium")  # fmt: skip
    x = result.pressure / result.E_star
    pixel = f"{result.dx * 1e9:.3g} nm pixels, {'periodic' if result.periodic else 'zero-padded'}"
    right.loglog(x, result.area_fraction, "o-", color=_COLOURS[0], label=f"exact ({pixel})")
    right.loglog(x, result.gw_area_fraction, "s--", color=_COLOURS[1], label="GW (Hertz summits)")
    right.set_xlabel(r"Nominal pressure over contact modulus $p/E^*$")
    right.set_ylabel(r"Real contact area $A_r/A_n$")
    right.legend(fontsize="small")
    fig.suptitle(f"{result.source.name}: exact elastic contact and GW", fontsize="medium")
    return fig
