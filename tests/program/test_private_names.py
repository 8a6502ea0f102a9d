"""No private name crosses a module of mcsim (ARCHITECTURE.md): a name that another module
needs is public, documented, in the module that owns it.

Every module of ``mcsim/`` is parsed (nothing is imported) and refused where it

* imports a private name (``_x``, not a dunder) from another mcsim module:
  ``from mcsim.a.b import _x`` or, relative, ``from .b import _x``;
* imports a private module, or from one, outside the package that holds it (``from
  mcsim.model import _rejection`` or ``from mcsim.model._rejection import ...`` in
  ``mcsim.physics``; inside ``mcsim.model`` it is the package's own);
* reads a private attribute of an mcsim module it imported: ``b._x`` after ``from mcsim.a
  import b`` or ``import mcsim.a.b as b``.

Tests and validation scripts may reach into private names; the package may not.
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _is_module(dotted: str, root: Path) -> bool:
    path = root.joinpath(*dotted.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def _inside(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def crossings(source: str, module: str, is_package: bool = False, root: Path = ROOT) -> list[str]:
    """The private names that the source of mcsim module ``module`` (dotted; ``is_package``:
    its ``__init__.py``) takes from other mcsim modules, one ``line: what`` each."""
    package = module if is_package else module.rpartition(".")[0]
    tree = ast.parse(source)
    modules: dict[str, str] = {}  # local name -> the mcsim module it is bound to
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "mcsim":
                    modules[alias.asname or alias.name] = alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                parts = parts[: len(parts) - node.level + 1]
                source_module = ".".join([*parts, *([node.module] if node.module else [])])
            else:
                source_module = node.module or ""
            if source_module.split(".")[0] != "mcsim":
                continue
            parts = source_module.split(".")
            if any(_private(p) and not _inside(package, ".".join(parts[:i]))
                   for i, p in enumerate(parts)):  # fmt: skip
                found.append(f"{node.lineno}: from {source_module} import ...")
                continue
            for alias in node.names:
                full = f"{source_module}.{alias.name}"
                if _is_module(full, root):
                    modules[alias.asname or alias.name] = full
                    if _private(alias.name) and not _inside(package, source_module):
                        found.append(f"{node.lineno}: from {source_module} import {alias.name}")
                elif _private(alias.name) and source_module != module:
                    found.append(f"{node.lineno}: from {source_module} import {alias.name}")
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Name)
            and node.value.id in modules
            and modules[node.value.id] != module
            and _private(node.attr)
        ):
            found.append(f"{node.lineno}: {node.value.id}.{node.attr}")
    return found


def test_no_module_of_mcsim_takes_a_private_name_from_another():
    hits = []
    for path in sorted((ROOT / "mcsim").rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        package = parts[-1] == "__init__"
        module = ".".join(parts[:-1] if package else parts)
        hits += [f"{path.relative_to(ROOT)}:{hit}" for hit in
                 crossings(path.read_text(encoding="utf-8"), module, package)]  # fmt: skip
    assert not hits, "private names that cross modules (make them public where they live):\n" + (
        "\n".join(hits)
    )


def test_the_check_finds_each_kind_of_crossing():
    # real modules of mcsim, so that the check knows which imported names are modules
    module = "mcsim.figures.stiction"
    assert crossings("from mcsim.figures.style import _COLOURS\n", module) == [
        "1: from mcsim.figures.style import _COLOURS"
    ]
    assert crossings("from .style import _COLOURS\n", module) == [
        "1: from mcsim.figures.style import _COLOURS"
    ]
    assert crossings("from mcsim.figures import style\nstyle._x()\n", module) == ["2: style._x"]
    assert crossings("import mcsim.figures.style as s\ns._x\n", module) == ["2: s._x"]
    assert crossings("from mcsim.model import _rejection\n", module) == [
        "1: from mcsim.model import _rejection"
    ]
    assert crossings("from mcsim.model._rejection import sample\n", module) == [
        "1: from mcsim.model._rejection import ..."
    ]


def test_the_check_lets_public_names_dunders_and_a_package_own_private_module_pass():
    module = "mcsim.figures.stiction"
    assert not crossings("from mcsim.figures.style import COLOURS, save\n", module)
    assert not crossings("from mcsim._version import __version__\n", module)
    assert not crossings("from mcsim.figures import style\nstyle.__name__\n", module)
    assert not crossings("from mcsim.model import _rejection\n", "mcsim.model.distributions")
    assert not crossings("from mcsim.model._rejection import sample\n", "mcsim.model.distributions")
    # a module's own private names, and a private attribute of what is not a module
    assert not crossings("def _f(): ...\n_f()\n", module)
    assert not crossings("from mcsim.figures.style import save\nsave._cache\n", module)
