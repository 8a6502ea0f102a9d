"""The figures in docs/ are current: made by ``make figures`` from today's code and commands.

``docs/figures.json`` (written by ``docs/make_figures.py``) records each figure's commands
and a digest of the numbers it plots. Here the digests are recomputed: the analytic
figures and the pads run always (a few seconds), the other Monte Carlo runs and the large
sweeps (minutes in all) with ``MCSIM_DOCS_FIGURES=1``, as ``make figures`` itself takes.
"""

from __future__ import annotations

import importlib.util
import json
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
_SPEC = importlib.util.spec_from_file_location("make_figures", ROOT / "docs" / "make_figures.py")
make_figures = sys.modules["make_figures"] = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(make_figures)

MANIFEST = json.loads(make_figures.MANIFEST.read_text())


def test_every_figure_in_docs_is_made_by_make_docs():
    shipped = {p.name for p in (ROOT / "docs").glob("*.png")}
    assert shipped == set(make_figures.FIGURES) == set(MANIFEST), (
        "docs/*.png, docs/make_figures.py FIGURES and docs/figures.json list other figures"
    )


@pytest.mark.parametrize("name", sorted(make_figures.FIGURES))
def test_manifest_records_the_current_commands(name):
    assert MANIFEST[name]["commands"] == make_figures.commands(name), (
        f"docs/{name} is stale: its commands changed; run make figures"
    )


def _check_inputs(name: str, work: Path) -> None:
    (work / "paper").mkdir()
    digest = make_figures.compute_inputs(name, work)
    assert digest == MANIFEST[name]["inputs_sha256"], f"docs/{name} is stale: run make figures"


@pytest.mark.parametrize("name", sorted(n for n, f in make_figures.FIGURES.items() if not f.slow))
def test_cheap_figure_inputs_unchanged(name, tmp_path):
    _check_inputs(name, tmp_path)


@pytest.mark.slow
@pytest.mark.skipif(
    os.environ.get("MCSIM_DOCS_FIGURES") != "1",
    reason="minutes of Monte Carlo and sweeps: MCSIM_DOCS_FIGURES=1 recomputes these inputs",
)
@pytest.mark.parametrize("name", sorted(n for n, f in make_figures.FIGURES.items() if f.slow))
def test_slow_figure_inputs_unchanged(name, tmp_path):
    _check_inputs(name, tmp_path)
