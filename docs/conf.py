"""Sphinx configuration of mcsim's documentation site (``make docs``; the build is checked
with warnings as errors by tests/program/test_docs_site.py)."""

from __future__ import annotations

import mcsim

project = "mcsim"
author = "the mcsim developers"
copyright = "2026, the mcsim developers"
release = mcsim.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "myst_nb",  # Markdown pages (MyST) and the tutorials, executed notebooks written in MyST
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",  # numpydoc-style docstrings
    "sphinx.ext.mathjax",
]
source_suffix = {".md": "myst-nb"}
root_doc = "index"
# docs/ also holds the figures' script and data, not pages
exclude_patterns = ["_build", "make_figures.py", "figures.json", "**/.ipynb_checkpoints"]

myst_heading_anchors = 4  # README-style links to #section-anchors
myst_enable_extensions = ["dollarmath"]
# The tutorials run at every build (small inputs, seconds each); a failing cell fails the build.
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 300
nb_merge_streams = True

autodoc_typehints = "description"
autodoc_member_order = "bysource"
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False

html_theme = "pydata_sphinx_theme"
html_title = f"mcsim {release}"
html_copy_source = False  # no page sources in the site (they are in the repository)
html_theme_options = {"navigation_depth": 2, "show_toc_level": 2}


def _plain_text_math(app, what, name, obj, options, lines) -> None:
    """mcsim's docstrings write physics in plain text, where ``|q|`` is an absolute value and
    never a reStructuredText substitution: escape the bars (outside literal ``code``)."""
    import re

    for i, line in enumerate(lines):
        parts = line.split("``")
        parts[::2] = [re.sub(r"(?<!\\)\|", r"\\|", p) for p in parts[::2]]
        lines[i] = "``".join(parts)


#: Links written for GitHub (between validation/README.md, ARCHITECTURE.md, CHANGELOG.md,
#: docs/*.md and docs/guide/*.md) and the site pages those files become.
_SITE_LINKS = {
    "](../validation/README.md": "](validation.md",
    "](../../validation/README.md": "](../validation.md",
    "](../../ARCHITECTURE.md": "](../architecture.md",
    "](validation/README.md": "](validation.md",
    "](../ARCHITECTURE.md": "](architecture.md",
    "](ARCHITECTURE.md": "](architecture.md",
    "](CHANGELOG.md": "](changelog.md",
    "](../CHANGELOG.md": "](changelog.md",
}


def _site_links(app, *args) -> None:
    """``source-read``/``include-read``: GitHub links to the files the site includes point at
    their pages instead (the last argument holds the text)."""
    text = args[-1]
    for github, site in _SITE_LINKS.items():
        text[0] = text[0].replace(github, site)


def setup(app) -> None:
    app.connect("autodoc-process-docstring", _plain_text_math)
    app.connect("source-read", _site_links)
    app.connect("include-read", _site_links)
