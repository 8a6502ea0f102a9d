"""The README and the user guide run as written: every command of their ```bash blocks and
every ```python block.

Each page (README.md and every page of docs/guide/) is one test, run on its own in a fresh
temporary copy of the repository's tracked files (a fresh clone, as a new user has it), so
that pytest-xdist spreads the pages over its workers and a page cannot lean on what another
page wrote: a page that reads a file makes it first. Its steps run in the page's order, with
the ``mcsim`` of this interpreter's environment on PATH (``source .venv/bin/activate`` in the
README). Each python block runs on its own, in a fresh namespace (as pasted into a new
notebook): it imports and defines what it uses. A command fails the test with its page and
line, the command and its stderr.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import traceback
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
GUIDE = ROOT / "docs" / "guide"

#: The pages whose commands run as written: the README (the landing page) and the guide.
PAGES = ("README.md", *sorted(p.relative_to(ROOT).as_posix() for p in GUIDE.glob("*.md")))

#: Set-up commands, not run: they build or use the environment this test already runs
#: in (``make run`` and ``make test`` create .venv and would run the paper or this very
#: suite again, ``make test-portable`` is part of ``make test``, ``make lint`` is CI's own
#: step, ``make docs`` is tests/program/test_docs_site.py's, ``source`` only puts .venv/bin
#: on PATH, which the test does itself).
SETUP = ("make run", "make test", "make test-portable", "make lint", "make docs",
         "source .venv/bin/activate")  # fmt: skip

#: Smaller runs than the pages show, so that the test stays short: (page text, what runs
#: instead). Each must occur exactly once in all the pages together (checked): the table
#: cannot rot.
SMALLER = (
    # the paper's Monte Carlo patches (0.1 mm² each) are what make run shows; the analytic
    # figures go through the same command
    ("mcsim paper --out runs/paper --seed 2026 --overwrite", "mcsim paper --out runs/paper --seed 2026 --overwrite --no-mc"),
    # a 2-core machine: 8 Dask worker processes only compete for the cores, and one worker
    # process takes the same path (scheduler, worker, results) as several
    ("--dask local --workers 8", "--dask local --workers 1"),
    # the sweeps on fewer points over the same ranges (each point is the same computation)
    ("--vary sigma=0.3nm:20nm:40:log --vary gamma=0.05:1:5", "--vary sigma=0.3nm:20nm:8:log --vary gamma=0.05:1:2"),
    ("--vary sigma=0.3nm:20nm:40:log --vary tau=100MPa \\\n    --mc --area 100um^2 --realizations 10",
     "--vary sigma=0.3nm:20nm:8:log --vary tau=100MPa \\\n    --mc --area 100um^2 --realizations 2"),
    ("--vary sigma=0.3nm:100nm:25:log \\\n    --vary gamma=0.002:5:13:log", "--vary sigma=0.3nm:100nm:5:log \\\n    --vary gamma=0.002:5:3:log"),
    ('{"sigma": "0.3nm:20nm:40:log", "gamma": [0.1, 0.5]}', '{"sigma": "0.3nm:20nm:8:log", "gamma": [0.1, 0.5]}'),
    # the friction sweep on fewer preloads and pads
    ("--vary preload=0.1MPa:10MPa:5:log \\\n    --vary rh=0,0.6 --pads 40",
     "--vary preload=0.1MPa:10MPa:2:log \\\n    --vary rh=0,0.6 --pads 4"),
    ("--vary rh=0.05:0.95:10 --out rh.h5", "--vary rh=0.05:0.95:3 --out rh.h5"),
    # the Monte Carlo sweep with 2 patches per point instead of 20
    ("--realizations 20 \\\n    --seed 1 --out mc.h5", "--realizations 2 \\\n    --seed 1 --out mc.h5"),
    # The runs below are also run as written, with their numbers checked, by
    # tests/program/test_readme_numbers.py (each named there); here smaller ones take the
    # same code path for the commands that read them. The exact adhesive cycle on 10 of the
    # 30 positions (test_adhesive_contact_of_the_shipped_scan):
    ("--pressure 100MPa --plot runs/scan-adhesion.png", "--pressure 100MPa --steps 10 --plot runs/scan-adhesion.png"),
    # the 300 pads (the fixture pads_run, and test_pad_statistics for `mcsim pads`): 30 pads
    # for the commands that summarise, plot and list them
    ("--area 10um^2 \\\n    --realizations 300 --seed 1 --out pads.h5", "--area 10um^2 \\\n    --realizations 30 --seed 1 --out pads.h5"),
    # the run to interrupt: a third of the pads (its plan and each checkpoint scale with
    # them), its first checkpoint after 0.2 s of work and Ctrl-C within a tenth of a second
    # after it (fewer completed pads for `mcsim pads --partial`): stopped five times sooner,
    # it keeps at least the share of its work still to do that the README's run keeps
    ("--realizations 30000 --seed 1 --checkpoint-every 1 --out many.h5 & \\\n  until [ -e many.partial.h5 ]; do sleep 1; done",
     "--realizations 10000 --seed 1 --checkpoint-every 0.2 --out many.h5 & \\\n  until [ -e many.partial.h5 ]; do sleep 0.1; done"),
    # the p_stick sweep (test_p_stick_table, whose σ = 1.5 nm switches to importance sampling
    # by itself) at its two ends with 20 pads each, for `mcsim plot`
    ("--vary sigma=1.5nm:3nm:4 --preload 1MPa \\\n    --pads 100", "--vary sigma=1.5nm:3nm:2 --preload 1MPa \\\n    --pads 20"),
    # importance sampling with --tail: test_tail_example runs it as written (its pilot
    # stages and final pads have a floor, mcsim.studies.rareevent.TAIL_PILOT and TAIL_PADS, that
    # no smaller --pads lowers); here 20 plain pads, the sweep's path without it
    ("--pads 2000 \\\n    --area 30um^2 --restoring-force 83uN --tail", "--pads 20 \\\n    --area 30um^2 --restoring-force 83uN"),
    # the humid sweep (test_humid_p_stick_table) dry and at its most humid point, 4 pads each
    ("--vary rh=0,0.3,0.4,0.45,0.5,0.55,0.7,0.9 --preload 0 --pads 40", "--vary rh=0,0.9 --preload 0 --pads 4"),
    # the stiction report at two of its humidities, 4 pads each (tests/studies/test_report.py
    # checks a report's numbers; most of the report's time is the scan's calibration and
    # exact contact, which fewer pads leave as they are)
    ("--rh 0,0.3,0.5,0.7,0.9 --devices 1000", "--rh 0,0.5 --pads 4 --devices 1000"),
)  # fmt: skip

_BLOCK = re.compile(r"^```(bash|python)\n(.*?)^```", re.MULTILINE | re.DOTALL)


def readme_steps(text: str) -> list[tuple[str, int, str]]:
    """(language, line, code): each bash command, and each python block, in page order."""
    steps = []
    for block in _BLOCK.finditer(text):
        language, body = block.groups()
        first = text.count("\n", 0, block.start(2)) + 1
        if language == "python":
            steps.append(("python", first, body))
            continue
        command, start = "", first
        for number, line in enumerate(body.splitlines(), start=first):
            if not command:
                start = number
                if not line.strip() or line.lstrip().startswith("#"):
                    continue
            command += line + "\n"
            if not line.rstrip().endswith("\\"):
                steps.append(("bash", start, command))
                command = ""
    return steps


def _is_setup(command: str) -> bool:
    return command.strip().split("#")[0].strip() in SETUP


def _copy_tracked_files(destination: Path) -> set[str]:
    """The repository as a fresh clone has it: its tracked files only (their names)."""
    listed = subprocess.run(
        ["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True
    ).stdout.decode()
    copied = set()
    for name in filter(None, listed.split("\0")):
        source = ROOT / name
        if source.is_file():  # a file deleted in the work tree is not in a fresh clone either
            (destination / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, destination / name)
            copied.add(name)
    return copied


def not_ignored(folder: Path, tracked: set[str]) -> list[str]:
    """The files under ``folder`` (a copy of the repository) that are neither ``tracked`` nor
    ignored by the repository's .gitignore: what ``git status`` would show a user."""
    new = sorted(
        p.relative_to(folder).as_posix()
        for p in folder.rglob("*")
        if p.is_file() and not {"__pycache__", ".git"} & set(p.parts)
    )
    new = [name for name in new if name not in tracked]
    checked = subprocess.run(
        ["git", "check-ignore", "--no-index", "--stdin", "-z"], cwd=ROOT,
        input="\0".join(new), capture_output=True, text=True,
    )  # fmt: skip
    assert checked.returncode in (0, 1), checked.stderr  # 1: none of them is ignored
    return sorted(set(new) - set(filter(None, checked.stdout.split("\0"))))


def page_steps(page: str) -> list[tuple[str, int, str]]:
    """The steps of ``page`` (a path relative to the repository) as written."""
    return readme_steps((ROOT / page).read_text())


def all_steps() -> list[tuple[str, str, int, str]]:
    """(page, language, line, code) of every page."""
    return [(page, *step) for page in PAGES for step in page_steps(page)]


def test_the_pages_are_the_readme_and_the_guide():
    assert PAGES[0] == "README.md" and len(PAGES) > 10
    assert "docs/guide/index.md" in PAGES and not (ROOT / "docs" / "guide.md").exists()


def test_every_substitution_matches_the_pages_once():
    texts = [(ROOT / page).read_text() for page in PAGES]
    counts = {readme: sum(text.count(readme) for text in texts) for readme, _ in SMALLER}
    assert all(n == 1 for n in counts.values()), f"each SMALLER entry once in the pages: {counts}"


def unbound_names(code: str) -> set[str]:
    """Names a python block reads that it neither imports nor assigns, nor are builtins."""
    import ast
    import builtins

    bound, read = set(dir(builtins)), set()
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.Name):
            (read if isinstance(node.ctx, ast.Load) else bound).add(node.id)
        elif isinstance(node, ast.alias):
            bound.add((node.asname or node.name).split(".")[0])
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            bound.add(node.name)
        elif isinstance(node, ast.arg):
            bound.add(node.arg)
    return read - bound


def test_every_python_block_imports_and_defines_what_it_uses():
    """A block copied alone into a notebook runs: no name from an earlier block (the
    README's blocks used to share smooth, silicon, np, mcsim and h)."""
    blocks = [(page, line, code) for page, lang, line, code in all_steps() if lang == "python"]
    assert len(blocks) >= 5
    missing = {f"{page}:{line}": sorted(unbound_names(code)) for page, line, code in blocks}
    assert not any(missing.values()), missing


def test_setup_lines_are_only_the_listed_ones():
    skipped = [c for _, lang, _, c in all_steps() if lang == "bash" and _is_setup(c)]
    assert {c.split("#")[0].strip() for c in skipped} <= set(SETUP)
    readme = [c.split("#")[0].strip() for lang, _, c in page_steps("README.md") if lang == "bash"]
    assert {"make run", "make test", "source .venv/bin/activate"} <= set(readme)


def runs(page: str) -> bool:
    """Whether ``page`` has a step that runs (not only set-up commands)."""
    return any(lang == "python" or not _is_setup(c) for lang, _, c in page_steps(page))


@pytest.mark.slow
@pytest.mark.parametrize("page", [p for p in PAGES if runs(p)])
def test_page_runs_as_written(page, tmp_path, monkeypatch):
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("needs the git checkout (git ls-files) to copy the tracked files")
    tracked = _copy_tracked_files(tmp_path)
    text = (ROOT / page).read_text()
    for readme, smaller in SMALLER:
        text = text.replace(readme, smaller)
    env = dict(os.environ, MPLBACKEND="Agg")
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    for language, line, code in readme_steps(text):
        if language == "bash":
            if _is_setup(code):
                continue
            done = subprocess.run(
                ["bash", "-e", "-o", "pipefail", "-c", code],
                cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
            )  # fmt: skip
            if done.returncode != 0:
                pytest.fail(
                    f"{page}:{line}: exit status {done.returncode}\n{code}\n{done.stderr}",
                    pytrace=False,
                )
        else:
            try:  # a fresh namespace: the block runs on its own
                exec(compile(code, f"{page}:{line}", "exec"), {"__name__": "__readme__"})
            except Exception:
                pytest.fail(f"{page}:{line}: python block failed\n{traceback.format_exc()}",
                            pytrace=False)  # fmt: skip
    # what the commands wrote is all covered by .gitignore: `git status` stays clean
    assert not not_ignored(tmp_path, tracked), f"{page}: outputs that .gitignore does not cover"
