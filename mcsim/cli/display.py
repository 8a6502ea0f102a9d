"""What the commands print: inputs, tables, notes."""

from __future__ import annotations

import contextlib
import json
import sys


def describe_inputs(surface, material) -> list[str]:
    from mcsim.model.params import plasticity_index, surface_energy_parameter

    psi = plasticity_index(surface, material)
    lines = [
        f"surface {surface.name or '(file)'}: sigma = {surface.sigma * 1e9:.4g} nm, R = {surface.R * 1e6:.4g} um, "
        f"eta = {surface.eta * 1e-12:.4g} um^-2, heights {surface.heights.name}"
        + (
            ""
            if surface.radius_by_height is None
            else f", radius by height (R x {min(surface.radius_by_height.factors):.3g} .. "
            f"{max(surface.radius_by_height.factors):.3g} in {len(surface.radius_by_height.factors)} bands)"
        ),
        f"material {material.name or '(file)'}: K = {material.K / 1e9:.4g} GPa, G = {material.G / 1e9:.4g} GPa, "
        f"w = {material.gamma:.4g} J/m^2 (work of adhesion)",
        f"A0 = eta R sigma = {surface.A0:.4g}, B0 = gamma/(K sigma) = {surface_energy_parameter(surface, material):.4g}, "
        f"R0 = R/sigma = {surface.R0:.4g}",
    ]
    if psi is not None:
        note = (
            " (> 1: mostly plastic contacts; the elastic model is questionable)" if psi > 1 else ""
        )
        lines.append(f"plasticity index psi = (E*/H) sqrt(sigma/R) = {psi:.3g}{note}")
    return lines


def print_rows(
    rows: list[dict], columns: list[str], fmt: str, header: list[str] | None = None
) -> None:
    if fmt == "json":
        clean = [
            {k: (None if isinstance(v, float) and v != v else v) for k, v in r.items()}
            for r in rows
        ]
        print(json.dumps(clean, indent=1, allow_nan=False))  # undefined values are null
        return
    if fmt == "csv":
        import csv

        writer = csv.DictWriter(
            sys.stdout, fieldnames=columns, extrasaction="ignore", lineterminator="\n"
        )
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if isinstance(v, float) and v != v else (repr(v) if isinstance(v, float) else v))
                             for k, v in row.items()})  # fmt: skip
        return
    for line in header or []:
        print(f"# {line}")

    def cell(v):
        if isinstance(v, float):
            return "undefined" if v != v else f"{v:.6g}"
        return str(v)

    table = [[cell(r.get(c, "")) for c in columns] for r in rows]
    widths = [
        max(len(c), *(len(t[i]) for t in table)) if table else len(c) for i, c in enumerate(columns)
    ]
    print("  ".join(c.rjust(w) for c, w in zip(columns, widths)).rstrip())
    for t in table:
        print("  ".join(v.rjust(w) for v, w in zip(t, widths)).rstrip())


def cutoff_notes(surface, material, law: str, h) -> list[str]:
    """For ``dmt``: how much of the attraction its tail cutoff drops at separations ``h``
    (nothing to say without adhesion: no attraction, no tail)."""
    if law != "dmt" or material.gamma == 0:
        return []
    import numpy as np

    from mcsim.physics.laws import dmt

    h = np.atleast_1d(np.asarray(h, dtype=float))
    h = h[np.isfinite(h)]  # no pull-off: no separation to speak of
    if not h.size:
        return []
    frac = dmt.truncated_fraction(surface, material, h)
    where = (f"at h = {h[0]:g}" if h.size == 1 else
             f"from {frac.min():.3g} to {frac.max():.3g} over h = {h.min():g} .. {h.max():g}")  # fmt: skip
    if h.size == 1:
        where = f"{frac[0]:.3g} {where}"
    return [f"note: dmt cuts the van der Waals tail at a gap of {dmt.DEFAULT_CUTOFF:g} z0: "
            f"it drops {where} of the attraction (mcsim.physics.laws.dmt.truncated_fraction)"]  # fmt: skip


#: Share of the attraction the dmt tail cutoff may drop at a pull-off before the pull-off
#: is the cutoff's (a numerical choice), not the law's: more than half of it.
CUTOFF_DECIDES = 0.5


def cutoff_flag(surface, material, summary) -> str | None:
    """Why a dmt pull-off is decided by the tail cutoff, or None if it is not.

    Far out in the tail of the heights the few summits' van der Waals tails make the mean
    approach load tensile by a vanishing amount (1e-21 K on the intermediate surface);
    where the cutoff drops most of the attraction there, the "pull-off" is the cutoff's.
    """
    if summary.law != "dmt" or not summary.pull_off > 0:
        return None
    from mcsim.physics.laws import dmt

    frac = float(dmt.truncated_fraction(surface, material, summary.h_pull_off)[0])
    if frac <= CUTOFF_DECIDES:
        return None
    return (
        f"decided by the dmt tail cutoff, which drops {frac:.3g} of the attraction at h = "
        f"{summary.h_pull_off:.6g}: no physical pull-off (treat it as none)"
    )


def announce(path, detail: str = "", *, quiet: bool = False) -> None:
    """The one line every written file gets, on stderr: ``mcsim: wrote PATH (detail)``;
    none with ``--quiet``. Standard output keeps the results."""
    if not quiet:
        print(f"mcsim: wrote {path}" + (f" ({detail})" if detail else ""), file=sys.stderr)


def counterface_notes(surface, counter, correlation: float, combined) -> list[str]:
    """One note on a rough counter-surface: the two surfaces, ρ and the gap's surface run
    (none with a flat counter-surface)."""
    if counter is None:
        return []

    def gw(s) -> str:
        return f"sigma = {s.sigma * 1e9:.4g} nm, R = {s.R * 1e6:.4g} um, eta = {s.eta * 1e-12:.4g} um^-2"

    return [f"note: counter-surface {counter.name or '(file)'} ({gw(counter)}) facing surface "
            f"{surface.name or '(file)'} ({gw(surface)}), correlation {correlation:g}: the gap's "
            f"surface {combined.name} has {gw(combined)}, rq = {combined.rq * 1e9:.4g} nm "
            "(spectral moments combined; docs/physics.md, section 'Two rough surfaces')"]  # fmt: skip


#: What a negative work of separation means (:mod:`mcsim.physics.adhesion`: the signed
#: integral -∫ F_net dd of the retraction from the turn to infinity).
NEGATIVE_WORK = ("it is signed, -int F_net dd from the turn to infinity: the elastic energy the "
                 "pressed summits give back while the load falls from the turn's to zero exceeds "
                 "the adhesive work of the tensile part after it, so the whole retraction releases "
                 "energy on balance; the surfaces still stick until the pull-off force pulls them "
                 "apart")  # fmt: skip


def work_notes(work, where: str = "") -> list[str]:
    """A line on what a negative work of separation (J/m², one value or one per point of a
    sweep) means; none where every one is >= 0 or undefined."""
    import numpy as np

    work = np.atleast_1d(np.asarray(work, dtype=float))
    negative = work < 0
    if not negative.any():
        return []
    if work.size == 1:
        return [f"note: the work of separation is negative ({work[0]:.4g} J/m^2): {NEGATIVE_WORK}"]
    return [f"note: at {int(negative.sum())} of {work.size} points{where} the work of separation "
            f"is negative (lowest {np.nanmin(work):.4g} J/m^2): {NEGATIVE_WORK}"]  # fmt: skip


def print_lines(lines: list[str]) -> None:
    for line in lines:
        print(f"mcsim: {line}", file=sys.stderr)


def contact_inputs(material) -> str:
    def given(value, scale, unit):
        return "not given" if value is None else f"{value * scale:.4g} {unit}"

    return (f"z0 = {given(material.z0, 1e9, 'nm')}, tau = {given(material.tau, 1e-6, 'MPa')}, "
            f"H = {given(material.H, 1e-9, 'GPa')}")  # fmt: skip


def dimensional(curves, area: float) -> dict:
    """Dimensional columns for a nominal area: N_c and forces in N, the area in m^2."""
    forces = curves.forces(area)
    return {("area_m2" if k == "area" else k if k == "N_c" else f"{k}_N"): v
            for k, v in forces.items()}  # fmt: skip


def file_state(path) -> tuple | None:
    """Device, inode, size and modification time of ``path`` (None if absent): the same
    before and after a command exactly when the command left the file alone (the
    writers replace a file by renaming a new one onto it)."""
    import os

    try:
        st = os.stat(path)
    except FileNotFoundError:
        return None
    return st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns


@contextlib.contextmanager
def log_notes(quiet: bool):
    """Print the library's log records (notices, estimates) as ``mcsim: ...`` lines on stderr."""
    import logging

    logger = logging.getLogger("mcsim")
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("mcsim: %(message)s"))
    handler.setLevel(logging.WARNING if quiet else logging.INFO)
    level, propagate = logger.level, logger.propagate
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    logger.propagate = False
    try:
        yield
    finally:
        logger.removeHandler(handler)
        logger.setLevel(level)
        logger.propagate = propagate


def _film_note(env, varied) -> str:
    """The adsorbed films and the band the bridges pull on (docs/physics.md, 'Water below the
    Kelvin gate: adsorbed films'): t, its source, the structured film, f and g_K."""
    source = "given" if env.film_thickness is not None else "isotherm t(RH)"
    film = f"{env.film * 1e9:.4g} nm ({source})"
    if "film_thickness" in varied or (env.film_thickness is None and "rh" in varied):
        film = "per point"
    structured = ("varied (--vary structured_film)" if "structured_film" in varied
                  else f"{env.structured_film * 1e9:.4g} nm")  # fmt: skip
    band = (f"{env.wet_floor * 1e9:.4g} nm <= g < {env.condensation_gap * 1e9:.4g} nm"
            if env.has_capillary else "none")  # fmt: skip
    thresholds = f"RH_dry = {env.bridging_rh:.3g}, RH_cr = {env.critical_rh:.3g}"
    if set(varied) & {"rh", "temperature", "contact_angle", "cutoff", "film_thickness",
                      "structured_film", "asperity_roughness"}:  # fmt: skip
        band = "per point"
    if set(varied) & {"temperature", "contact_angle", "film_thickness", "structured_film",
                      "asperity_roughness"}:  # fmt: skip
        thresholds = "per point"
    nano = ("varied (--vary asperity_roughness)" if "asperity_roughness" in varied
            else f"{env.asperity_roughness * 1e9:.4g} nm")  # fmt: skip
    return (f"environment films: adsorbed film t = {film} on each face, structured (ice-like) "
            f"film {structured} (bridges only where t exceeds it), bridges pull on "
            f"max(D0, 2t) <= g < g_K = 2 r_K cos(theta) + 2t: {band}; asperities' nanoscale "
            f"roughness sigma_n = {nano} (menisci spread once 2 r_K cos(theta) >= 3 sigma_n): "
            f"{thresholds}")  # fmt: skip


def environment_notes(surface, environment, varied=(), material=None) -> list[str]:
    """The environment's inputs, the heights it uses (given or estimated), why no liquid
    condenses, if none does, and with ``material`` how its w is shared with the van der Waals
    attraction (:func:`mcsim.physics.surfaceenvironment.interface_notes`), and where the model
    leaves its ground (:func:`~mcsim.physics.surfaceenvironment.environment_warnings`, not
    for a sweep that varies what they depend on; these last with ``material`` only, which a
    Monte Carlo run logs itself): one line each (empty
    without an environment). The inputs in ``varied`` (a sweep's ``--vary`` names) are said to
    be varied, not given their base value; at RH = 0 there is no Kelvin radius."""
    if environment is None:
        return []
    import math

    from mcsim.physics.gapheights import gap_heights

    env, gap = environment, gap_heights(surface)

    def value(name: str, text: str) -> str:
        return f"varied (--vary {name})" if name in varied else text

    hamaker = "none" if not env.has_vdw else f"{env.hamaker:.4g} J"
    kelvin = (f"{env.kelvin_radius * 1e9:.4g} nm" if not env.is_dry
              else "none (RH = 0: no condensation)")  # fmt: skip
    if {"rh", "temperature"} & set(varied):
        kelvin = "per point (kelvin_radius in the sweep file)"
    wavelength = ("none (non-retarded)" if env.retardation_wavelength is None
                  else f"{env.retardation_wavelength * 1e9:.4g} nm")  # fmt: skip
    lines = [f"environment: Hamaker A = {value('hamaker', hamaker)}, cutoff D0 = "
             f"{value('cutoff', f'{env.cutoff * 1e9:.4g} nm')}, retardation wavelength = "
             f"{value('retardation_wavelength', wavelength)}, RH = {value('rh', f'{env.rh:.4g}')}, "
             f"contact angle = {value('contact_angle', f'{math.degrees(env.contact_angle):.4g} deg')}, "
             f"T = {value('temperature', f'{env.temperature:.5g} K')}, gamma_L = "
             f"{env.surface_tension:.4g} J/m^2, V_m = {env.molar_volume:.4g} m^3/mol, "
             f"Kelvin radius = {kelvin}",
             f"environment heights: rq = {gap.rq * 1e9:.4g} nm, summit_offset = "
             f"{gap.summit_offset * 1e9:.4g} nm ({gap.source})"]  # fmt: skip
    if gap.source != "given":
        lines[-1] += (
            ": estimates from sigma, R, eta; give rq and summit_offset to use measured values"
        )
    if not env.is_dry or "rh" in varied:
        lines.append(_film_note(env, varied))
    if not env.is_dry and not env.has_capillary:
        lines.append(env.no_condensation_reason)
    if material is None:  # a run's own log says the rest (mcsim.studies.simulation)
        return lines
    from mcsim.physics.surfaceenvironment import (
        EQUILIBRIUM_NOTE,
        environment_warnings,
        interface_notes,
    )

    if not {"hamaker", "cutoff", "gamma", "retardation_wavelength"} & set(varied):  # the vdW share
        lines += [f"note: {w}" for w in interface_notes(surface, material, env)]
    if not {"rh", "temperature", "contact_angle", "cutoff"} & set(varied):
        lines += [f"warning: {w}" for w in environment_warnings(surface, env)]
    if env.has_capillary or "rh" in varied:
        lines.append(f"note: {EQUILIBRIUM_NOTE}")
    return lines
