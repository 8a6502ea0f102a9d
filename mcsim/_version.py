"""mcsim's version, from the git tags (CHANGELOG.md: how a release is tagged).

setuptools-scm writes ``mcsim/_build_version.py`` when the package is built or installed
(``pip install .``, ``pip install -e .``): ``0.3.0`` on the commit tagged ``v0.3.0``,
``0.3.0.devN+g<hash>`` N commits after ``v0.2.0``. A source tree imported without being
installed (``PYTHONPATH=...``) has no such file and reports ``0+unknown``; an editable
install keeps the version of its install until it is installed again.
"""

import os.path

# Only the file beside this one: an editable install of another source tree in the same
# environment would lend its own, since its import finder answers for mcsim's modules too.
if os.path.exists(os.path.join(os.path.dirname(__file__), "_build_version.py")):
    from mcsim._build_version import __version__
else:  # a source tree that was never built or installed
    __version__ = "0+unknown"

__all__ = ["__version__"]
