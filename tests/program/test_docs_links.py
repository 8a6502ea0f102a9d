"""The documentation stays inside the repository: its links resolve, and nothing points outside.

* Every relative link of README.md, ARCHITECTURE.md, validation/README.md, docs/*.md and
  docs/*/*.md (the guide, the tutorials) names a tracked file, and its ``#anchor`` (if any)
  a heading of that file, as GitHub makes anchors from headings.
* No tracked file refers to the development notes outside the repository (the shared
  folder next to a checkout, or their physics notes file): a clone does not have them.
* Every "docs/physics.md, section 'X'" in the package names a heading of docs/physics.md,
  and the modules whose physics it documents point to it.
"""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PHYSICS = "docs/physics.md"

#: Markdown files whose links are checked (besides docs/*.md).
DOCUMENTS = ("README.md", "ARCHITECTURE.md", "validation/README.md")

#: References to what only the development checkout has. Written in two parts so that this
#: file does not contain them itself.
OUTSIDE = ("../" + "shared", "PHYSICS" + ".md")

#: Modules whose docstring must point to their section of docs/physics.md.
DOCUMENTED_MODULES = (
    "mcsim/physics/__init__.py",
    "mcsim/physics/adhesion.py",
    "mcsim/physics/analytic.py",
    "mcsim/physics/environment.py",
    "mcsim/physics/vanderwaals.py",
    "mcsim/physics/capillary.py",
    "mcsim/physics/films.py",
    "mcsim/physics/surfaceenvironment.py",
    "mcsim/physics/gapheights.py",
    "mcsim/physics/loadcontrol.py",
    "mcsim/physics/laws/__init__.py",
    "mcsim/physics/laws/dmt.py",
    "mcsim/physics/laws/elastic_plastic.py",
    "mcsim/physics/laws/ieee.py",
    "mcsim/physics/laws/jkr.py",
    "mcsim/physics/laws/maugis_dugdale.py",
    "mcsim/physics/laws/seed.py",
    "mcsim/engine/statistics.py",
    "mcsim/model/counterface.py",
    "mcsim/topography/summits.py",
    "mcsim/studies/stiction.py",
)

# [text](target) or ![alt](target "title"); the target has no spaces.
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^(```|~~~)")
# "docs/physics.md, section 'A'" or "docs/physics.md, sections 'A' and 'B'" (one line each)
SECTION = re.compile(r"docs/physics\.md, sections? ('[^'\n]+'(?:(?:,| and) '[^'\n]+')*)")


def sections(text: str) -> list[str]:
    """The section names that ``text`` refers to in docs/physics.md."""
    return [name for match in SECTION.findall(text) for name in re.findall(r"'([^']+)'", match)]


@pytest.fixture(scope="module")
def tracked() -> list[str]:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("needs the git checkout (git ls-files) to know the tracked files")
    out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True)
    return [p for p in out.stdout.decode().split("\0") if p]


def _outside_fences(text: str) -> list[str]:
    """The lines of Markdown outside fenced code blocks."""
    kept, fenced = [], False
    for line in text.splitlines():
        if FENCE.match(line.lstrip()):
            fenced = not fenced
        elif not fenced:
            kept.append(line)
    return kept


def links(text: str) -> list[str]:
    """Link and image targets of Markdown, outside code blocks and inline code spans."""
    prose = "\n".join(re.sub(r"`[^`]*`", "", line) for line in _outside_fences(text))
    return LINK.findall(prose)


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip().lower())  # links: their text
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def headings(path: Path) -> list[str]:
    """The heading texts of a Markdown file, outside code blocks."""
    lines = _outside_fences(path.read_text(encoding="utf-8"))
    return [m.group(1) for line in lines if (m := re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line))]


def anchors(path: Path) -> set[str]:
    """Anchors GitHub gives the headings of ``path``: a repeated one gets -1, -2, ..."""
    seen: dict[str, int] = {}
    out = set()
    for heading in headings(path):
        base = slug(heading)
        n = seen.get(base, 0)
        out.add(base if n == 0 else f"{base}-{n}")
        seen[base] = n + 1
    return out


def documents() -> list[str]:
    return [
        *DOCUMENTS,
        *sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "docs").glob("*.md")),
        *sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "docs").glob("*/*.md")),
    ]


def test_the_slug_is_githubs_anchor_of_a_heading():
    assert slug("GPU: `--device cuda`") == "gpu---device-cuda"
    assert slug("Maugis-Dugdale law set") == "maugis-dugdale-law-set"
    assert slug("Where the paper is ambiguous, and what mcsim does") == (
        "where-the-paper-is-ambiguous-and-what-mcsim-does"
    )


def test_sections_are_read_from_one_or_two_quoted_names():
    assert sections("See docs/physics.md, section 'JKR law set'.") == ["JKR law set"]
    assert sections("docs/physics.md, sections 'A b' and 'C'") == ["A b", "C"]


@pytest.mark.parametrize("document", documents())
def test_every_relative_link_names_a_tracked_file_and_an_existing_heading(document, tracked):
    source = ROOT / document
    files = set(tracked)
    folders = {str(Path(p).parent.as_posix()) for p in tracked}
    broken = []
    for target in links(source.read_text(encoding="utf-8")):
        if re.match(r"[a-z][a-z0-9+.-]*:", target):  # https:, mailto:: not a file
            continue
        path, _, anchor = target.partition("#")
        resolved = source if not path else (source.parent / path).resolve()
        try:
            name = resolved.relative_to(ROOT).as_posix()
        except ValueError:
            broken.append(f"{target}: outside the repository")
            continue
        if name not in files and name.rstrip("/") not in folders:
            broken.append(f"{target}: {name} is not a tracked file")
        elif anchor and (resolved.suffix != ".md" or anchor not in anchors(resolved)):
            broken.append(f"{target}: no heading with the anchor #{anchor} in {name}")
    assert not broken, f"{document}: " + "; ".join(broken)


def test_no_tracked_file_refers_to_the_notes_outside_the_repository(tracked):
    found = [
        f"{name}: {ref}"
        for name in tracked
        if (ROOT / name).is_file()
        for ref in OUTSIDE
        if ref.encode() in (ROOT / name).read_bytes()
    ]
    assert not found, "references outside the repository (a clone lacks them): " + "; ".join(found)


def test_every_section_the_package_names_is_a_heading_of_the_physics_document(tracked):
    known = set(headings(ROOT / PHYSICS))
    missing = [
        f"{name}: '{section}'"
        for name in tracked
        if name.startswith("mcsim/") and name.endswith(".py")
        for section in sections((ROOT / name).read_text(encoding="utf-8"))
        if section not in known
    ]
    assert not missing, f"sections not in {PHYSICS}: " + "; ".join(missing)


@pytest.mark.parametrize("module", DOCUMENTED_MODULES)
def test_the_module_docstring_points_to_its_section_of_the_physics_document(module):
    docstring = ast.get_docstring(ast.parse((ROOT / module).read_text(encoding="utf-8"))) or ""
    assert sections(docstring), f"{module}: its docstring names no section of {PHYSICS}"


def test_the_guide_links_the_physics_document_from_the_model_page():
    model = (ROOT / "docs" / "guide" / "model.md").read_text(encoding="utf-8")
    assert "](../physics.md)" in model or "](../physics.md#" in model
