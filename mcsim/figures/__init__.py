"""Every plot, drawn from results and files; one module per kind of figure.

matplotlib is imported only inside the functions. The public figure functions are also
reachable here by name (``mcsim.figures.curve_figure``, and as ``mcsim.plotting.*`` for
code written for mcsim 0.2), imported on first use.
"""

import importlib

#: Public figure functions and the module of each.
_WHERE = {
    "curve_figure": "curves",
    "save": "style",
    "run_figure": "runs",
    "histogram_figure": "topography",
    "comparison_figure": "topography",
    "adhesion_figure": "adhesion",
    "fuller_tabor_figure": "adhesion",
    "load_control_figure": "loadcontrol",
    "load_run_figure": "loadcontrol",
    "sweep_figure": "sweeps",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str):
    if name in _WHERE:
        return getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    raise AttributeError(f"module 'mcsim.figures' has no attribute {name!r}")
