"""Make every figure in docs/ (``make docs``) and record what each was made from.

Each figure is made by the mcsim commands the guide shows (listed in ``FIGURES``), run
from the repository root into a temporary folder; the PNG is then copied into docs/.
``docs/figures.json`` records, per figure, those commands and a SHA-256 digest of its
inputs: every number in the files the commands wrote before plotting (run and sweep files'
datasets, CSV tables), each written with ``DIGITS`` significant digits. It is a digest of
what is plotted, not of the PNG (matplotlib's bytes are not stable across versions).
``tests/program/test_docs_figures.py`` recomputes the digests and fails when a figure's
inputs changed without ``make docs``.

Usage, from the repository root: ``python docs/make_figures.py [NAME.png ...]`` (all
figures when no name is given; about 3 minutes on a busy 2-core machine, 50 s of CPU).
"""

from __future__ import annotations

import csv
import hashlib
import json
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
MANIFEST = DOCS / "figures.json"

#: Significant digits of every number digested: well above what a figure shows, well below
#: double precision, so that rounding in the last bits (another CPU adds the Monte Carlo
#: sums in another order) leaves the digest unchanged except at a rare rounding boundary.
DIGITS = 7


@dataclass(frozen=True)
class Figure:
    """One figure of docs/: the commands that make it and the files they plot.

    Attributes
    ----------
    data : tuple of tuple of str
        mcsim commands (arguments after ``mcsim``) that write the plotted numbers;
        ``{work}`` is the temporary folder. A command whose last element is ``> FILE``
        has its standard output written to FILE.
    plot : tuple of tuple of str
        mcsim commands that draw ``{work}/<name>`` from those files.
    inputs : tuple of str
        Files (in ``{work}``) whose numbers are digested.
    made : str
        The PNG the plot commands write, in ``{work}``.
    slow : bool
        True where the data commands take more than a few seconds (a Monte Carlo run or a
        large sweep): the test recomputes those only with ``MCSIM_DOCS_FIGURES=1``.
    """

    data: tuple[tuple[str, ...], ...]
    plot: tuple[tuple[str, ...], ...]
    inputs: tuple[str, ...]
    made: str
    slow: bool


_PAPER_SURFACES = ("rough", "intermediate", "smooth", "super-smooth")

FIGURES = {
    "fig6_friction_coefficient.png": Figure(
        data=(("paper", "--out", "{work}/paper", "--seed", "2026", "--quiet"),),
        plot=(),
        inputs=("paper/paper_curves.csv", *(f"paper/mc_{s}.h5" for s in _PAPER_SURFACES)),
        made="paper/fig6_friction_coefficient.png",
        slow=True,
    ),
    "load_control_analytic.png": Figure(
        data=(
            ("analytic", "--surface", "smooth", "--material", "runs/silicon-friction.toml",
             "--law", "maugis-dugdale", "--pressure", "10kPa:100MPa:21:log", "--format", "csv",
             "> {work}/load_control.csv"),
        ),
        plot=(
            ("analytic", "--surface", "smooth", "--material", "runs/silicon-friction.toml",
             "--law", "maugis-dugdale", "--pressure", "10kPa:100MPa:21:log", "--quiet",
             "--plot", "{work}/load_control_analytic.png", "> /dev/null"),
        ),
        inputs=("load_control.csv",),
        made="load_control_analytic.png",
        slow=False,
    ),
    "load_control_mc.png": Figure(
        data=(
            ("simulate", "--surface", "smooth", "--material", "runs/silicon-friction.toml",
             "--law", "maugis-dugdale", "--pressure", "100kPa:100MPa:7:log", "--area",
             "100um^2", "--realizations", "50", "--seed", "1", "--out", "{work}/load.h5",
             "--quiet"),
        ),
        plot=(("plot", "{work}/load.h5", "--out", "{work}/load_control_mc.png", "--quiet"),),
        inputs=("load.h5",),
        made="load_control_mc.png",
        slow=True,
    ),
    "stiction_pads.png": Figure(
        data=(
            ("simulate", "--surface", "smooth", "--law", "maugis-dugdale", "--cycle",
             "--h=4:0:41", "--area", "10um^2", "--realizations", "300", "--seed", "1",
             "--out", "{work}/pads.h5", "--quiet"),
        ),
        plot=(
            ("pads", "{work}/pads.h5", "--restoring-force", "130uN", "--quiet",
             "--plot", "{work}/stiction_pads.png", "> /dev/null"),
        ),
        inputs=("pads.h5",),
        made="stiction_pads.png",
        slow=False,
    ),
    "stiction_sweep.png": Figure(
        data=(
            ("sweep", "--surface", "smooth", "--law", "jkr", "--vary", "sigma=1.5nm:3nm:4",
             "--preload", "1MPa", "--pads", "100", "--area", "30um^2", "--restoring-force",
             "20uN", "--seed", "1", "--out", "{work}/stick.h5", "--quiet"),
        ),
        plot=(("plot", "{work}/stick.h5", "--out", "{work}/stiction_sweep.png", "--quiet"),),
        inputs=("stick.h5",),
        made="stiction_sweep.png",
        slow=True,
    ),
    "adhesion_loop.png": Figure(
        data=(
            ("contact", "examples/scan.npy", "--unit", "m", "--pixel-size", "10nm", "--adhesion",
             "--w", "0.1J/m^2", "--range", "1nm", "--pressure", "100MPa", "--quiet", "--format",
             "csv", "> {work}/adhesion.csv"),
        ),
        plot=(
            ("contact", "examples/scan.npy", "--unit", "m", "--pixel-size", "10nm", "--adhesion",
             "--w", "0.1J/m^2", "--range", "1nm", "--pressure", "100MPa", "--quiet",
             "--plot", "{work}/adhesion_loop.png", "> /dev/null"),
        ),
        inputs=("adhesion.csv",),
        made="adhesion_loop.png",
        slow=True,
    ),
    "stiction_humid.png": Figure(
        data=(
            ("sweep", "--surface", "smooth", "--law", "maugis-dugdale", "--hamaker", "1.6e-19J",
             "--asperity-roughness", "0.5nm", "--vary", "rh=0,0.3,0.4,0.45,0.5,0.55,0.7,0.9",
             "--preload", "0", "--pads", "40", "--area",
             "30um^2", "--restoring-force", "450uN", "--seed", "1", "--out", "{work}/humid.h5",
             "--quiet"),
        ),
        plot=(("plot", "{work}/humid.h5", "--out", "{work}/stiction_humid.png", "--quiet"),),
        inputs=("humid.h5",),
        made="stiction_humid.png",
        slow=True,
    ),
    "friction_slip.png": Figure(
        data=(
            ("sweep", "--surface", "smooth", "--law", "jkr", "--hamaker", "1.6e-19J", "--vary",
             "preload=0.1MPa:10MPa:5:log", "--vary", "rh=0,0.6", "--pads", "40", "--area",
             "30um^2", "--tangential-force", "1.75mN", "--seed", "1", "--out",
             "{work}/slip.h5", "--quiet"),
        ),
        plot=(("plot", "{work}/slip.h5", "--out", "{work}/friction_slip.png", "--quiet"),),
        inputs=("slip.h5",),
        made="friction_slip.png",
        slow=True,
    ),
    "design_sigma.png": Figure(
        data=(
            ("sweep", "--surface", "smooth", "--law", "auto", "--vary",
             "sigma=0.3nm:20nm:40:log", "--vary", "tau=100MPa", "--mc", "--area", "100um^2",
             "--realizations", "10", "--seed", "1", "--out", "{work}/sigma.h5", "--quiet"),
        ),
        plot=(("plot", "{work}/sigma.h5", "--out", "{work}/design_sigma.png", "--quiet"),),
        inputs=("sigma.h5",),
        made="design_sigma.png",
        slow=True,
    ),
    "design_map.png": Figure(
        data=(
            ("sweep", "--surface", "smooth", "--law", "auto", "--vary",
             "sigma=0.3nm:100nm:25:log", "--vary", "gamma=0.002:5:13:log",
             "--out", "{work}/map.h5", "--quiet"),
        ),
        plot=(("plot", "{work}/map.h5", "--out", "{work}/design_map.png", "--quiet"),),
        inputs=("map.h5",),
        made="design_map.png",
        slow=True,
    ),
}  # fmt: skip


def run_mcsim(command: tuple[str, ...], work: Path) -> None:
    """Run one ``mcsim`` command of ``FIGURES`` from the repository root.

    Parameters
    ----------
    command : tuple of str
        Arguments after ``mcsim``; ``{work}`` stands for `work`, a last ``> FILE`` sends
        the standard output to FILE.
    work : Path
        The temporary folder the figure's files go to.
    """
    args = [a.format(work=work) for a in command]
    stdout = None
    if args[-1].startswith("> "):
        stdout = Path(args.pop()[2:])
    mcsim = Path(sys.executable).parent / "mcsim"
    done = subprocess.run(
        [str(mcsim), *args], cwd=ROOT, capture_output=True, text=True, check=False
    )
    if done.returncode != 0:
        raise RuntimeError(f"mcsim {' '.join(args)}: exit {done.returncode}\n{done.stderr}")
    if stdout is not None:
        stdout.write_text(done.stdout)


def _numbers(path: Path) -> list[tuple[str, np.ndarray]]:
    """Every numeric array of a run/sweep file (by dataset name) or of a CSV table (by column)."""
    if path.suffix == ".csv":
        rows = list(csv.reader(path.read_text().splitlines()))
        columns = []
        for j, name in enumerate(rows[0]):
            try:
                values = np.array([float(r[j]) if r[j] else np.nan for r in rows[1:]])
            except ValueError:
                values = np.array([r[j] for r in rows[1:]])
            columns.append((name, values))
        return columns
    found = []
    with h5py.File(path, "r") as f:

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiub":
                found.append((name, np.asarray(obj[()])))

        f.visititems(visit)
    return found


def commands(name: str) -> list[str]:
    """A figure's commands as the manifest records them, one string each."""
    return [" ".join(("mcsim", *c)) for c in (*FIGURES[name].data, *FIGURES[name].plot)]


def inputs_digest(name: str, work: Path) -> str:
    """SHA-256 of a figure's commands and of every number its input files hold.

    Parameters
    ----------
    name : str
        The figure's file name, a key of ``FIGURES``.
    work : Path
        The folder the figure's data commands wrote to.

    Returns
    -------
    str
        Hex digest; numbers enter as ``DIGITS`` significant digits, NaN as ``nan``.
    """
    figure = FIGURES[name]
    digest = hashlib.sha256(json.dumps([figure.data, figure.plot]).encode())
    for file in figure.inputs:
        for key, values in _numbers(work / file):
            digest.update(f"{file}:{key}:{values.shape}".encode())
            if values.dtype.kind in "fiub":
                text = " ".join(f"{v:.{DIGITS - 1}e}" for v in values.astype(float).ravel())
            else:
                text = " ".join(map(str, values.ravel()))
            digest.update(text.encode())
    return digest.hexdigest()


def compute_inputs(name: str, work: Path) -> str:
    """Run a figure's data commands into `work` and return its inputs' digest."""
    for command in FIGURES[name].data:
        run_mcsim(command, work)
    return inputs_digest(name, work)


def make_figure(name: str) -> str:
    """Make docs/`name` and return its inputs' digest."""
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        (work / "paper").mkdir()
        digest = compute_inputs(name, work)
        for command in FIGURES[name].plot:
            run_mcsim(command, work)
        shutil.copyfile(work / FIGURES[name].made, DOCS / name)
    return digest


def main(names: list[str]) -> None:
    """Make the named figures (all when none) and update docs/figures.json."""
    unknown = sorted(set(names) - set(FIGURES))
    if unknown:
        raise SystemExit(f"make_figures: unknown figure(s) {unknown}; known: {sorted(FIGURES)}")
    manifest = json.loads(MANIFEST.read_text()) if MANIFEST.exists() else {}
    for name in names or FIGURES:
        manifest[name] = {
            "commands": commands(name),
            "inputs_sha256": make_figure(name),
        }
        MANIFEST.write_text(json.dumps(manifest, indent=2, sort_keys=True) + "\n")
        print(f"wrote docs/{name}")


if __name__ == "__main__":
    main(sys.argv[1:])
