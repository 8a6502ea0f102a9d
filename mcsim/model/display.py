"""Short summaries of results for the console and Jupyter (``__repr__``, ``_repr_html_``).

A summary is a title and a few (label, text) rows; the arrays themselves are never printed.
"""

from __future__ import annotations

import html

import numpy as np


def inputs(surface, material, law: str, h: np.ndarray) -> list[tuple[str, str]]:
    """Rows describing a surface, a material, a law set and the separations h = d/σ."""
    s, m = surface, material
    h = np.asarray(h, dtype=float)
    if h.size == 1:
        sweep = f"1 value, {h[0]:g}"
    else:
        sweep = f"{h.size} values from {np.min(h):g} to {np.max(h):g}"
    return [
        ("surface", f"{s.name or '(unnamed)'}: σ = {s.sigma * 1e9:.4g} nm, R = {s.R * 1e6:.4g} µm, "
                    f"η = {s.eta * 1e-12:.4g} µm⁻², {s.heights.name} heights"
                    + ("" if s.radius_by_height is None else
                       f", radius by height (R × {min(s.radius_by_height.factors):.3g} … "
                       f"{max(s.radius_by_height.factors):.3g} in {len(s.radius_by_height.factors)} bands)")),
        ("material", f"{m.name or '(unnamed)'}: K = {m.K * 1e-9:.4g} GPa, G = {m.G * 1e-9:.4g} GPa, "
                     f"γ = {m.gamma:.4g} J/m²"),
        ("law set", law),
        ("h = d/σ", sweep),
    ]  # fmt: skip


def text(title: str, rows: list[tuple[str, str]]) -> str:
    """``title`` then one indented ``label: text`` line per row."""
    width = max(len(label) for label, _ in rows)
    return "\n".join([title, *(f"  {label:<{width}}  {value}" for label, value in rows)])


def table(title: str, rows: list[tuple[str, str]]) -> str:
    """The same summary as an HTML table."""
    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(label)}</th>"
        f"<td style='text-align:left'>{html.escape(value)}</td></tr>"
        for label, value in rows
    )
    return f"<table><caption style='text-align:left'><b>{html.escape(title)}</b></caption>{body}</table>"
