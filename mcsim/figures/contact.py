"""The exact contact of a map beside GW's: the contact map and the real area against load."""

from __future__ import annotations

import numpy as np


def contact_figure(result):
    """Contact map at the highest load, and A_r/A_n against p/E*, exact and GW.

    Parameters
    ----------
    result : ContactResult
        From :func:`mcsim.studies.maps.contact.contact_map` with ``keep_fields=True``.

    Returns
    -------
    matplotlib.figure.Figure
        Left: the contact pressure at the highest load, MPa, over the map (x, y in µm; white:
        no contact). Right: real over nominal contact area against nominal pressure over E*,
        log–log, exact (boundary elements, at the map's pixel size) and GW (Hertz summits).
    """
    from matplotlib.figure import Figure

    from mcsim.figures.style import COLOURS

    fig = Figure(figsize=(10, 4.2), layout="constrained")
    left, right = fig.subplots(1, 2)
    factor, unit = _pressure_scale(result.pressure_fields[-1])
    field = result.pressure_fields[-1] / factor
    ny, nx = result.shape
    extent = (0, nx * result.dx * 1e6, 0, ny * result.dy * 1e6)
    image = left.imshow(np.ma.masked_equal(field, 0.0), origin="lower", extent=extent,
                        cmap="viridis", interpolation="nearest")  # fmt: skip
    fig.colorbar(image, ax=left, label=f"Contact pressure ({unit})")
    left.set_xlabel(r"$x$ (µm)")
    left.set_ylabel(r"$y$ (µm)")
    left.set_title(f"$p$ = {_pressure_text(result.pressure[-1])}, $A_r/A_n$ = "
                   f"{result.area_fraction[-1]:.3g}", fontsize="medium")  # fmt: skip
    x = result.pressure / result.E_star
    pixel = f"{result.dx * 1e9:.3g} nm pixels, {'periodic' if result.periodic else 'zero-padded'}"
    right.loglog(x, result.area_fraction, "o-", color=COLOURS[0], label=f"exact ({pixel})")
    right.loglog(x, result.gw_area_fraction, "s--", color=COLOURS[1], label="GW (Hertz summits)")
    right.set_xlabel(r"Nominal pressure over contact modulus $p/E^*$")
    right.set_ylabel(r"Real contact area $A_r/A_n$")
    right.legend(fontsize="small")
    fig.suptitle(f"{result.source.name}: exact elastic contact and GW", fontsize="medium")
    return fig


def _pressure_text(value: float) -> str:
    """A pressure (Pa) to 3 significant digits in the largest unit that needs no exponent
    (1e9 Pa: "1 GPa", not "1e+03 MPa")."""
    for factor, unit in ((1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa"), (1.0, "Pa")):
        text = f"{value / factor:.3g}"
        if abs(float(text)) >= 1 and "e" not in text:
            return f"{text} {unit}"
    return f"{value:.3g} Pa"


def _pressure_scale(values) -> tuple[float, str]:
    """A pressure unit that shows ``values`` (Pa) in plain numbers: (factor, unit)."""
    largest = float(np.nanmax(np.abs(values))) if np.size(values) else 1.0
    for factor, unit in ((1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa")):
        if largest >= 10 * factor:
            return factor, unit
    return 1.0, "Pa"


def adhesion_figure(result):
    """The exact adhesive loop of a map, its jumps, and GW's pull-offs beside it.

    Parameters
    ----------
    result : AdhesiveContactResult
        From :func:`mcsim.studies.maps.adhesivecontact.adhesive_contact`.

    Returns
    -------
    matplotlib.figure.Figure
        Left: mean pressure against the flat's height above the map's mean plane (nm),
        approach and retraction, each jump as a dotted step, the exact pull-off marked.
        Right: the tensile end of the retraction, magnified, with GW's mean retraction curve of
        each adhesive law set (pressed to the same largest pressure; its flat's height above
        the mean plane is σh plus the summits' offset).
    """
    from matplotlib.figure import Figure

    from mcsim.figures.style import COLOURS

    cycle = result.cycle
    fig = Figure(figsize=(10, 4.4), layout="constrained")
    left, right = fig.subplots(1, 2)
    approach = np.array([(s.position, s.mean_pressure) for s in cycle.approach])
    retract = np.array([(s.position, s.mean_pressure) for s in cycle.retraction])
    summary = result.summary()
    for ax, values in ((left, np.concatenate([approach[:, 1], retract[:, 1]])),
                       (right, [summary["pull_off"], *(g.pull_off for g in result.gw)])):  # fmt: skip
        factor, unit = _pressure_scale(values)
        ax.plot(approach[:, 0] * 1e9, approach[:, 1] / factor, "v-", ms=3, color=COLOURS[0],
                label="exact, approach")  # fmt: skip
        ax.plot(retract[:, 0] * 1e9, retract[:, 1] / factor, "^-", ms=3, color=COLOURS[1],
                label="exact, retraction")  # fmt: skip
        for j in cycle.jumps:
            ax.plot([j.position_before * 1e9, j.position_after * 1e9],
                    [j.pressure_before / factor, j.pressure_after / factor], ":", color="0.3")  # fmt: skip
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set_xlabel("Flat above the mean plane $d$ (nm)")
        ax.set_ylabel(f"Mean pressure $\\bar p$ ({unit}; compressive > 0)")
        if ax is right:
            if summary["pull_off"] > 0:
                ax.plot(result.pull_off_position * 1e9, -summary["pull_off"] / factor, "o",
                        mfc="none", ms=10, color="k",
                        label=f"exact pull-off {summary['pull_off'] / factor:.3g} {unit}")  # fmt: skip
            for k, g in enumerate(result.gw):
                ax.plot(g.position * 1e9, g.pressure / factor, "--", color=COLOURS[2 + k],
                        label=f"GW {g.law} (retraction), pull-off {g.pull_off / factor:.3g} {unit}")  # fmt: skip
            pulling = retract[retract[:, 1] < -0.01 * summary["pull_off"], 0]
            if pulling.size:  # where the exact loop pulls by more than 1 % of its pull-off
                margin = 0.3 * (pulling.max() - pulling.min())
                ax.set_xlim((pulling.min() - margin) * 1e9, (pulling.max() + margin) * 1e9)
            low = min(-summary["pull_off"], *(-g.pull_off for g in result.gw))
            # room below the curves for the legend
            ax.set_ylim(2.2 * low / factor if low < 0 else -1.0, max(-0.5 * low / factor, 1e-12))
    left.legend(fontsize="small", loc="upper right")
    right.legend(fontsize="small", loc="lower right")
    right.set_title("tensile end, with GW's pull-off", fontsize="medium")
    law = result.interaction
    fig.suptitle(f"{result.source.name}: exact adhesive contact ({result.law_name}, w = "
                 f"{law.w:.3g} J/m², range {law.range * 1e9:.3g} nm; {result.dx * 1e9:.3g} nm "
                 f"pixels) and GW", fontsize="medium")  # fmt: skip
    return fig
