"""Reproduce the paper's Figs. 2-6: the four MEMS surfaces of Table 1 on silicon.

:func:`reproduce_paper` computes the analytic GW curves (Eqs. 1, 3, 5, 7, 8) of the
paper's simulations A-D, draws the five figures, writes the curves as one tidy CSV
and reports μ at a few separations and the plasticity index of each surface.
"""

from __future__ import annotations

import csv
from collections.abc import Callable, Mapping
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from mcsim._version import __version__
from mcsim.model.errors import MCSimError
from mcsim.model.params import check_seed, plasticity_index
from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.analytic import QUANTITIES, analytic_curves
from mcsim.store.outputs import check_output, write_atomic

#: Version of the layout of the CSV files written here (separate from the package version).
SCHEMA_VERSION = 1

#: Figure files, in the paper's order, and the quantity each one plots.
FIGURE_FILES = {
    "fig2_external_force.png": "P",
    "fig3_adhesive_force.png": "F",
    "fig4_total_force.png": "total",
    "fig5_friction_force.png": "T",
    "fig6_friction_coefficient.png": "mu",
}

#: Columns of ``paper_curves.csv``: forces divided by A_n K, μ = T̄/(P̄ + F̄).
CURVE_COLUMNS = ("surface", "h", *QUANTITIES)

#: Separations h = d/σ of the μ table.
MU_TABLE_H = (3.0, 2.0, 1.0, 0.0, -1.0)

#: Plasticity index above which contacts are mostly plastic (Greenwood & Williamson 1966).
PLASTIC_PSI = 1.0


def reproduce_paper(
    out_dir="runs/paper",
    h=None,
    mc: Mapping[str, Mapping] | None = None,
    log: Callable[[str], object] | None = print,
    overwrite: bool = False,
    command: str | None = None,
) -> dict:
    """Compute and plot the paper's Figs. 2-6 for its four surfaces on silicon.

    Writes into ``out_dir`` (created if missing):

    * ``fig2_external_force.png`` … ``fig6_friction_coefficient.png`` (P̄, F̄,
      P̄ + F̄, T̄, μ versus h; see :func:`mcsim.figures.curves.curve_figure`);
    * ``paper_curves.csv``: one row per surface and h, columns
      ``surface, h, contact_fraction, P, F, T, mu`` (forces divided by A_n K);
    * ``mu_table.csv``: μ per surface at h = 3, 2, 1, 0, −1.

    Both CSV files start with ``#`` provenance lines (schema and mcsim versions,
    time, command line, inputs with units): read them with
    ``pandas.read_csv(path, comment="#")``.

    Parameters
    ----------
    out_dir : str or Path
        Output folder.
    h : array_like, optional
        Dimensionless separations d/σ of the curves; ``np.linspace(4, -1, 201)``
        (the paper's range) by default.
    mc : mapping, optional
        Monte Carlo results by surface name, overlaid on every figure; see
        :func:`mcsim.figures.curves.curve_figure` for the layout (``few`` flags points
        with too few expected contacts for a z-score: drawn as crosses).
    log : callable or None
        Receives the μ table and the plasticity report line by line; ``None`` is
        silent.
    overwrite : bool
        Replace files left by an earlier reproduction; without it an existing output
        is an error, raised before anything is written (:mod:`mcsim.store.outputs`).
    command : str, optional
        The command line recorded in the provenance lines (the CLI passes the one it
        parsed); by default the Python call is named.

    Returns
    -------
    dict
        ``curves`` (surface name → :class:`~mcsim.physics.analytic.AnalyticCurves`),
        ``figures`` (quantity → PNG path), ``curves_csv`` and ``mu_table_csv``
        (paths), ``mu_table`` (surface → {h: μ}), ``plasticity_index``
        (surface → ψ) and ``report`` (the lines sent to ``log``).

    Raises
    ------
    MCSimError
        If ``out_dir`` cannot be created, an output exists (without ``overwrite``) or
        is not a regular file, or a file in it cannot be written.
    """
    from mcsim.figures.curves import curve_figure
    from mcsim.figures.style import save

    h = np.linspace(4.0, -1.0, 201) if h is None else np.atleast_1d(np.asarray(h, dtype=float))
    if h.ndim != 1 or h.size == 0 or not np.all(np.isfinite(h)):
        raise MCSimError("`h` must be a non-empty one-dimensional array of finite numbers.")
    out = _output_folder(out_dir)
    for path in paper_outputs(out, monte_carlo=False):
        check_output(path, overwrite=overwrite)
    material = MATERIALS["silicon"]
    surfaces = {name: SURFACES[name] for name in PAPER_SURFACES}

    curves = {name: analytic_curves(s, material, h) for name, s in surfaces.items()}
    at_table = {name: analytic_curves(s, material, MU_TABLE_H) for name, s in surfaces.items()}
    mu_table = {name: dict(zip(MU_TABLE_H, c.mu.tolist())) for name, c in at_table.items()}
    psi = {name: plasticity_index(s, material) for name, s in surfaces.items()}

    figures = {}
    for filename, quantity in FIGURE_FILES.items():
        figures[quantity] = save(
            curve_figure(quantity, curves, mc), out / filename, overwrite=overwrite
        )

    header = _provenance(material, surfaces, h, command)
    curves_csv = _write_csv(
        out / "paper_curves.csv",
        overwrite,
        header,
        CURVE_COLUMNS,
        (
            [name, *(repr(float(v)) for v in row)]
            for name, c in curves.items()
            for row in zip(c.h, *(getattr(c, q) for q in QUANTITIES))
        ),
    )
    mu_table_csv = _write_csv(
        out / "mu_table.csv",
        overwrite,
        header,
        ("surface", *(f"mu_h={x:g}" for x in MU_TABLE_H)),
        ([name, *(repr(mu) for mu in row.values())] for name, row in mu_table.items()),
    )

    report = _report(mu_table, psi, surfaces)
    if log is not None:
        for line in report:
            log(line)
    return {
        "curves": curves,
        "figures": figures,
        "curves_csv": curves_csv,
        "mu_table_csv": mu_table_csv,
        "mu_table": mu_table,
        "plasticity_index": psi,
        "report": report,
    }


def _output_folder(out_dir) -> Path:
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise MCSimError(
            f"cannot create output folder {str(out)!r}: {error.strerror or error}"
        ) from None
    return out


def _write_csv(path: Path, overwrite: bool, header: list[str], columns, rows) -> Path:
    def write(tmp: Path) -> None:
        with tmp.open("w", newline="", encoding="utf-8") as f:
            f.writelines(f"# {line}\n" for line in header)
            writer = csv.writer(f)
            writer.writerow(columns)
            writer.writerows(rows)

    return write_atomic(path, write, overwrite=overwrite)


def paper_outputs(out_dir, monte_carlo: bool = True) -> list[Path]:
    """Every file ``mcsim paper`` writes into ``out_dir`` (with or without Monte Carlo)."""
    out = Path(out_dir)
    files = [out / name for name in (*FIGURE_FILES, "paper_curves.csv", "mu_table.csv")]
    if monte_carlo:
        files += [out / f"mc_{name}.h5" for name in PAPER_SURFACES]
    return files


def _provenance(material, surfaces: Mapping, h: np.ndarray, command: str | None) -> list[str]:
    """Provenance lines: schema, versions, time, command line (or the Python call) and inputs
    in SI units."""
    lines = [
        f"schema: mcsim-paper-curves {SCHEMA_VERSION}",
        f"mcsim: {__version__}",
        f"created: {datetime.now(UTC).isoformat(timespec='seconds')}",
        f"command: {command or 'mcsim.studies.paper.reproduce_paper(...)'}",
        "model: analytic Greenwood-Williamson, law set 'seed' (paper Eqs. 1-8); "
        "P, F, T divided by A_n*K; mu = T/(P + F)",
        f"material: {material.name} E1 = {material.E1:g} Pa, E2 = {material.E2:g} Pa, "
        f"nu1 = {material.nu1:g}, nu2 = {material.nu2:g}, gamma = {material.gamma:g} J/m^2, "
        f"H = {material.H:g} Pa, K = {material.K:.6g} Pa, G = {material.G:.6g} Pa",
    ]
    lines += [
        f"surface: {name} sigma = {s.sigma:g} m, R = {s.R:g} m, eta = {s.eta:g} m^-2"
        for name, s in surfaces.items()
    ]
    lines.append(f"h: {h.size} values from {h[0]:g} to {h[-1]:g}")
    return lines


def _report(mu_table: Mapping, psi: Mapping, surfaces: Mapping) -> list[str]:
    """The μ table and one plasticity line per surface, as text lines."""
    width = max(len(name) for name in mu_table)
    lines = [
        "Friction coefficient mu = T/(P + F) (Eq. 8), silicon:",
        f"{'surface':<{width}}" + "".join(f"{f'h = {x:g}':>10}" for x in MU_TABLE_H),
    ]
    lines += [
        f"{name:<{width}}" + "".join(f"{mu:10.4f}" for mu in row.values())
        for name, row in mu_table.items()
    ]
    lines.append("Plasticity index psi = (E*/H) sqrt(sigma/R) (Greenwood & Williamson 1966):")
    for name, value in psi.items():
        s = surfaces[name]
        if value > PLASTIC_PSI:
            verdict = (
                "WARNING: psi > 1, contacts mostly plastic; the paper's purely elastic "
                "model is questionable for this surface"
            )
        elif value > 0.6:
            verdict = "elastic-plastic transition (0.6 < psi <= 1)"
        else:
            verdict = "contacts mostly elastic"
        lines.append(
            f"{name:<{width}}  psi = {value:.3g} "
            f"(sigma = {s.sigma * 1e9:.3g} nm, R = {s.R * 1e6:.3g} um): {verdict}"
        )
    return lines


#: Separations of the Monte Carlo points on the paper's figures.
MC_H = np.linspace(4.0, -1.0, 21)

#: Nominal area of the one Monte Carlo patch per surface: 0.1 mm², 1.1-2.6 million summits.
MC_AREA = 1e-7


def paper_monte_carlo(
    out_dir,
    seed: int = 2026,
    log: Callable[[str], object] | None = print,
    overwrite: bool = False,
    command: str | None = None,
) -> dict:
    """One Monte Carlo patch per paper surface, stored as HDF5 runs, as an ``mc`` overlay.

    Each surface gets a patch of :data:`MC_AREA` at the separations :data:`MC_H`,
    written to ``out_dir/mc_<surface>.h5``; existing runs are replaced only with
    ``overwrite`` (checked for all four before the first is computed). Surface i is
    seeded with ``SeedSequence(seed).spawn(4)[i].generate_state(1)[0]``. ``command`` is
    recorded in each run file (the CLI passes its command line; by default
    :func:`~mcsim.studies.simulation.simulate` records its own Python call).

    Returns
    -------
    dict
        The ``mc`` mapping of :func:`mcsim.figures.curves.curve_figure`, including the
        total force P̄ + F̄ with its standard error.
    """
    from mcsim.engine.statistics import MIN_CONTACTS, force_estimate
    from mcsim.studies.simulation import simulate

    out = _output_folder(out_dir)
    runs = [out / f"mc_{name}.h5" for name in PAPER_SURFACES]
    for path in runs:
        check_output(path, overwrite=overwrite)
    material = MATERIALS["silicon"]
    seeds = np.random.SeedSequence(check_seed(seed)).spawn(len(PAPER_SURFACES))
    mc = {}
    for name, child, path in zip(PAPER_SURFACES, seeds, runs):
        run = simulate(SURFACES[name], material, MC_H, MC_AREA, seed=int(child.generate_state(1)[0]), workers=2,
                       out=path, overwrite=overwrite, command=command)  # fmt: skip
        if log is not None:
            log(
                f"Monte Carlo {name}: N = {run.n_summits[0]} summits on {MC_AREA * 1e12:g} um^2 -> {run.path}"
            )
        mean, se = dict(run.summary.mean), dict(run.summary.se)
        mean["total"], se["total"] = force_estimate(run.spec, run.n_summits, run.sums, (1, 1, 0))
        few = run.summary.expected_contacts < MIN_CONTACTS  # z withheld: drawn apart
        mc[name] = {"h": run.h, "mean": mean, "se": se, "few": few}
    return mc
