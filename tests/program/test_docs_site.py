"""The documentation site builds with warnings as errors, and its tutorials run.

``make docs`` builds the same site: every page (the user guide, the physics, the validation
tables, the API reference from the docstrings) and the tutorials, MyST notebooks executed at
every build, so a tutorial that no longer runs fails here.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
pytest.importorskip("myst_nb")

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("site")
    build = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
         "-d", str(out / "doctrees"), str(ROOT / "docs"), str(out / "html")],
        capture_output=True, text=True, cwd=ROOT, timeout=900,
    )  # fmt: skip
    assert build.returncode == 0, build.stderr[-4000:]
    return out / "html"


@pytest.mark.slow
def test_every_page_is_built(site):
    guide = [f"guide/{p.stem}" for p in (ROOT / "docs" / "guide").glob("*.md")]
    assert "guide/index" in guide and len(guide) > 10
    for page in ["index", *guide, "physics", "contact", "validation", "api", "architecture",
                 "tutorials/humid_pads", "tutorials/scan_to_stiction"]:  # fmt: skip
        assert (site / f"{page}.html").is_file(), page


@pytest.mark.slow
def test_the_api_reference_documents_the_public_names(site):
    text = (site / "api.html").read_text()
    for name in ["mcsim.simulate", "mcsim.sweep", "mcsim.pad_report", "mcsim.Surface",
                 "mcsim.physics.laws.seed"]:  # fmt: skip
        assert f'id="{name}' in text, name


@pytest.mark.slow
def test_the_humid_tutorial_ran_and_drew_its_figure(site):
    text = (site / "tutorials" / "humid_pads.html").read_text()
    assert "RH_dry = 0.30" in text  # an executed cell's printed output
    assert re.search(r'<img alt="[^"]*_images/[0-9a-f]{20,}\.png"', text)  # its figure
    assert "Traceback" not in text


@pytest.mark.slow
def test_links_between_the_files_point_at_site_pages(site):
    guide = [f"guide/{p.stem}" for p in (ROOT / "docs" / "guide").glob("*.md")]
    for page in [*guide, "physics", "contact", "validation", "performance"]:
        hrefs = re.findall(r'href="([^"]*)"', (site / f"{page}.html").read_text())
        local = [h for h in hrefs if not h.startswith(("http:", "https:", "#"))]
        assert not [h for h in local if ".md" in h], page  # every GitHub link rewritten
    assert any(h.startswith("../validation.html#") for h in re.findall(
        r'href="([^"]*)"', (site / "guide" / "exact-contact.html").read_text()))  # fmt: skip
    assert any(h.startswith("../architecture.html") for h in re.findall(
        r'href="([^"]*)"', (site / "guide" / "development.html").read_text()))  # fmt: skip
