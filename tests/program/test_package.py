"""The packaged release (issue 43): ``pip install .`` builds a wheel that installs and runs.

The wheel is built from a copy of the source tree (the tree itself is left untouched: a
build writes ``build/`` and ``mcsim/_build_version.py`` into the folder it builds) with the
version setuptools-scm derives from this checkout's git tags (handed to the copy, which has
no git, as ``SETUPTOOLS_SCM_PRETEND_VERSION_FOR_MCSIM``), and installed with
``--no-deps`` into a fresh virtual environment that sees the test interpreter's
site-packages for the dependencies only (a path in a ``.pth`` file: that folder's own
``.pth`` files, among them an editable install's finder of the source tree, are not
read). The installed ``mcsim`` then runs from a folder outside the repository: ``mcsim
ingest`` of the example scan, and the README's ``mcsim report`` of it.
"""

from __future__ import annotations

import email.parser
import json
import os
import re
import shutil
import site
import subprocess
import sys
import sysconfig
import tomllib
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())

#: A version setuptools-scm writes (PEP 440): ``0.3.0`` on a tag, ``0.3.0.dev12+g1a2b3c4``
#: after it, ``.dYYYYMMDD`` more for uncommitted changes.
VERSION = re.compile(r"\d+\.\d+\.\d+(\.dev\d+)?(\+[0-9a-z.]+)?")


def _run(args: list, cwd: Path, env: dict | None = None) -> str:
    done = subprocess.run(
        [str(a) for a in args], capture_output=True, text=True, cwd=cwd, env=env, timeout=300
    )
    assert done.returncode == 0, f"{args}\n{done.stdout}\n{done.stderr}"
    return done.stdout.strip()


def _source_files() -> list[Path]:
    """The files of the source tree a checkout builds from: git's tracked and untracked,
    not ignored, files; every file outside a git checkout (an unpacked sdist)."""
    if (REPO / ".git").exists():
        listed = _run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], REPO)
        return [REPO / name for name in listed.splitlines() if (REPO / name).is_file()]
    return [p for p in REPO.rglob("*") if p.is_file() and "__pycache__" not in p.parts]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> tuple[Path, str]:
    """The wheel ``pip wheel`` builds from the source, and the version of the checkout."""
    pytest.importorskip(
        "setuptools_scm",
        reason="setuptools-scm, a build requirement, is in the test extra: pip install -e .[test]",
    )
    tmp = tmp_path_factory.mktemp("package")
    version = _run([sys.executable, "-m", "setuptools_scm"], REPO)
    source = tmp / "source"
    for path in _source_files():
        (source / path.relative_to(REPO)).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, source / path.relative_to(REPO))
    env = os.environ | {"SETUPTOOLS_SCM_PRETEND_VERSION_FOR_MCSIM": version}
    _run([sys.executable, "-m", "pip", "wheel", source, "--no-deps", "--no-build-isolation",
          "--no-index", "--quiet", "--wheel-dir", tmp / "wheel"], tmp, env)  # fmt: skip
    (built,) = (tmp / "wheel").glob("*.whl")
    return built, version


@pytest.fixture(scope="module")
def installed(wheel, tmp_path_factory) -> tuple[Path, str]:
    """A fresh virtual environment with the wheel installed: its bin folder, and the
    folder the wheel was installed into."""
    venv = tmp_path_factory.mktemp("venv")
    _run([sys.executable, "-m", "venv", "--without-pip", venv], venv)
    python = venv / "bin" / "python"
    _run([sys.executable, "-m", "pip", "--python", python, "install", "--no-deps",
          "--no-index", "--quiet", wheel[0]], venv)  # fmt: skip
    purelib = _run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"], venv)
    dependencies = [*site.getsitepackages(), sysconfig.get_path("purelib")]
    Path(purelib, "dependencies.pth").write_text("\n".join(dict.fromkeys(dependencies)) + "\n")
    return venv / "bin", purelib


def test_the_wheel_is_named_by_the_checkouts_version(wheel):
    """The version of the checkout (PEP 440, as :data:`VERSION`) names the wheel."""
    built, version = wheel
    assert VERSION.fullmatch(version), version
    assert built.name.startswith(f"mcsim-{version}-py3-none-any")


def test_the_wheel_holds_the_package_and_nothing_else(wheel):
    """Every module of the package, the version file the build writes, and metadata: no
    tests, validation scripts, docs or examples (mcsim reads no data files at run time)."""
    built, version = wheel
    names = set(zipfile.ZipFile(built).namelist())
    package = {n for n in names if not n.startswith(f"mcsim-{version}.dist-info/")}
    modules = {p.relative_to(REPO).as_posix() for p in (REPO / "mcsim").rglob("*.py")}
    assert package == modules | {"mcsim/_build_version.py"}


def test_the_wheel_requires_no_cuda_outside_the_gpu_extra(wheel):
    built, version = wheel
    metadata = zipfile.ZipFile(built).read(f"mcsim-{version}.dist-info/METADATA").decode()
    requires = email.parser.Parser().parsestr(metadata).get_all("Requires-Dist")
    cuda = [r for r in requires if re.search(r"cuda|nvidia", r, re.IGNORECASE)]
    assert cuda and all(r.endswith('; extra == "gpu"') for r in cuda), cuda
    plain = [r for r in requires if "; extra ==" not in r]
    assert plain == PYPROJECT["project"]["dependencies"]


def test_the_installed_command_runs_outside_the_repository(installed, wheel, tmp_path, monkeypatch):
    """``mcsim --version`` prints the wheel's version; ``mcsim ingest`` of the example scan
    writes the surface the source tree writes, and loads no module from the source tree."""
    bin_folder, purelib = installed
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    assert _run([bin_folder / "mcsim", "--version"], tmp_path, env) == f"mcsim {wheel[1]}"

    scan = REPO / "examples" / "scan.npy"
    args = ["ingest", str(scan), "--unit", "m", "--pixel-size", "10nm", "--out", "scan.toml",
            "--quiet"]  # fmt: skip
    # the folder above the package of every mcsim module loaded, printed last, at exit
    where = (
        "import atexit, pathlib, sys\n"
        "atexit.register(lambda: print(sorted({str(pathlib.Path(m.__file__).parents["
        "n.count('.') + m.__file__.endswith('__init__.py')]) for n, m in sys.modules.items()"
        " if n.split('.')[0] == 'mcsim'})))\n"
        f"sys.argv = ['mcsim', *{args!r}]\n"
        "from importlib.metadata import entry_points\n"
        "entry_points(group='console_scripts')['mcsim'].load()()\n"
    )
    (installed_run := tmp_path / "installed").mkdir()
    printed = _run([bin_folder / "python", "-c", where], installed_run, env)
    assert printed.splitlines()[-1] == repr([purelib])

    from mcsim.cli.main import main

    (source_run := tmp_path / "source").mkdir()
    monkeypatch.chdir(source_run)
    assert main(args) == 0

    def written(folder: Path, name: str) -> list[str]:
        """The lines of a written file below its comments (which say when and by what)."""
        return [line for line in (folder / name).read_text().splitlines() if line[:1] != "#"]

    for name in ("scan.toml", "scan-heights.csv", "scan-map-heights.csv"):
        assert written(installed_run, name) == written(source_run, name)
    header = (installed_run / "scan.toml").read_text().splitlines()[0]
    assert header.startswith(f"# written by mcsim {wheel[1]} (mcsim ingest)")


@pytest.mark.slow  # half a minute of CPU: started first (tests/conftest.py)
def test_the_installed_command_writes_a_stiction_report(installed, wheel, tmp_path):
    """The README's ``mcsim report examples/scan.npy ...`` from the installed wheel, outside
    the repository, at two of its humidities with 20 jkr pads each (jkr: the pads' static
    friction too, and a faster law set than the Maugis-Dugdale that ``auto`` picks;
    tests/studies/test_report.py checks a report's numbers): both files, the JSON naming
    the wheel's version and the inputs, and at each RH a p_stick of the 20 pads inside its
    95 % interval, the lot's numbers of it and the pads' static friction."""
    bin_folder, _ = installed
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"} | {"MPLBACKEND": "Agg"}
    _run([bin_folder / "mcsim", "report", REPO / "examples" / "scan.npy", "--unit", "m",
          "--pixel-size", "10nm", "--pad-area", "10um^2", "--preload", "0", "--restoring-force",
          "10uN", "--rh", "0,0.5", "--pads", "20", "--law", "jkr", "--devices", "1000",
          "--seed", "1", "--out", "scan-report.html", "--quiet"], tmp_path, env)  # fmt: skip
    html = (tmp_path / "scan-report.html").read_text()
    assert html.startswith("<!DOCTYPE html>") and wheel[1] in html
    data = json.loads((tmp_path / "scan-report.json").read_text())
    assert data["version"] == wheel[1]
    inputs = data["inputs"]
    assert (inputs["pads"], inputs["devices"], inputs["seed"]) == (20, 1000, 1)
    assert [row["rh"] for row in data["rows"]] == [0.0, 0.5]
    for row in data["rows"]:
        assert 0 <= row["p_stick_low"] <= row["p_stick"] <= row["p_stick_high"] <= 1, row
        # fewer than 100 pads: the fraction of the 20 pads, never importance sampling
        assert row["p_stick_method"] == "pads" and round(row["p_stick"] * 20, 9).is_integer()
        assert row["expected_stuck"] == pytest.approx(1000 * row["p_stick"])
        assert row["p_any_low"] <= row["p_any"] <= row["p_any_high"]
        assert row["static_friction_mean"] > 0 and row["pull_off_mean"] >= 0


def test_versions_between_and_on_tags(tmp_path):
    """The scheme of pyproject.toml on a repository of two commits: the next minor version's
    dev release after a tag, the tag's version on it, the fallback as the base without
    tags (a shallow clone), a date for uncommitted changes."""
    pytest.importorskip(
        "setuptools_scm",
        reason="setuptools-scm, a build requirement, is in the test extra: pip install -e .[test]",
    )
    shutil.copy(REPO / "pyproject.toml", tmp_path)
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-c", "commit.gpgsign=false"]
    _run(["git", "init", "--quiet"], tmp_path)

    def version() -> str:
        return _run([sys.executable, "-m", "setuptools_scm"], tmp_path)

    def commit(name: str) -> str:
        (tmp_path / name).write_text(name)
        _run(["git", "add", name], tmp_path)
        _run([*git, "commit", "--quiet", "-m", name], tmp_path)
        return _run(["git", "rev-parse", "--short=9", "HEAD"], tmp_path)

    first = commit("a")
    fallback = PYPROJECT["tool"]["setuptools_scm"]["fallback_version"]  # X.Y.0.dev0
    assert version() == f"{fallback.removesuffix('.dev0')}.dev1+g{first}"
    _run([*git, "tag", "v0.2.0"], tmp_path)
    assert version() == "0.2.0"
    second = commit("b")
    assert version() == f"0.3.0.dev1+g{second}"
    (tmp_path / "b").write_text("changed")
    assert re.fullmatch(rf"0\.3\.0\.dev1\+g{second}\.d\d{{8}}", version())
    _run(["git", "checkout", "--quiet", "b"], tmp_path)
    _run([*git, "tag", "v0.3.0"], tmp_path)
    assert version() == "0.3.0"
