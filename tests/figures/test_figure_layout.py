"""What a reader sees (issue 33, "Figures and text"): legends name only what is drawn and
cover no data, no text is cut at the figure's edge or sits on the line it names, bars on a
log axis do not run off to its edge, and figure and printout give one σ."""

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest
from conftest import run_cli

from mcsim.model.presets import MATERIALS, PAPER_SURFACES, SURFACES
from mcsim.physics.analytic import gw_curves

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]


def _renderer(fig):
    """Draw the figure (Agg) and return its renderer: text extents are then final."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def _legend_texts(ax) -> list[str]:
    legend = ax.get_legend()
    return [] if legend is None else [t.get_text() for t in legend.get_texts()]


def test_simulate_help_states_the_defaults_of_count_and_chunk_size(capsys):
    from mcsim.engine.montecarlo import DEFAULT_CHUNK

    code, out, _ = run_cli(capsys, "simulate", "--help")
    text = " ".join(out.split())
    assert code == 0
    assert re.search(r"--count \{poisson,fixed\} N ~ Poisson\(eta A\) or round\(eta A\) "
                     r"\(default: poisson\)", text), text  # fmt: skip
    assert f"summits per task (default: {DEFAULT_CHUNK};" in text


def test_fig6_draws_the_single_summit_limit_as_a_broad_band_under_the_curves():
    from mcsim.figures.curves import curve_figure

    h = np.linspace(4, -1, 11)
    curves = {name: gw_curves(name, "silicon", h) for name in PAPER_SURFACES}
    ax = curve_figure("mu", curves).axes[0]
    lines = {line.get_label(): line for line in ax.get_lines()}
    (limit,) = [v for k, v in lines.items() if k.startswith("single-summit limit")]
    surfaces = [v for k, v in lines.items() if not k.startswith("single-summit limit")]
    assert len(surfaces) == 4
    # super-smooth runs along the limit (mu within 1 % of it): drawn over it, it stays
    # visible (issue 44), and the limit shows on both sides of it, in a colour of its own
    assert limit.get_zorder() < min(line.get_zorder() for line in surfaces)
    assert limit.get_linewidth() >= 2.5 * max(line.get_linewidth() for line in surfaces)
    assert limit.get_color() not in {line.get_color() for line in surfaces}


def test_load_control_legend_names_no_jump_where_no_point_jumped():
    from mcsim.figures.loadcontrol import load_control_figure
    from mcsim.physics.loadcontrol import load_control

    material = dataclasses.replace(SILICON, tau=1e8)  # a friction panel with its legend
    result = load_control(SMOOTH, material, np.geomspace(1e4, 1e8, 5), "maugis-dugdale")
    assert not result.jump.any()
    area_ax, friction_ax = load_control_figure(result).axes
    assert _legend_texts(friction_ax)[0] == "maugis-dugdale"
    assert not any("jump" in text for ax in (area_ax, friction_ax) for text in _legend_texts(ax))


def test_load_run_figure_cuts_a_bar_that_reaches_zero_on_the_log_panel_and_marks_it(
    capsys, tmp_path
):
    from mcsim.figures.loadcontrol import ARROW_DECADES, load_run_figure
    from mcsim.store.runfile import read_run

    out = tmp_path / "load.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--law", "maugis-dugdale",
                           "--pressure", "100kPa,10MPa", "--area", "100um^2", "--realizations",
                           "20", "--seed", "1", "--workers", "1", "--quiet", "--out", out)  # fmt: skip
    assert code == 0, err
    run = read_run(out)
    material = run.spec.material
    x = run.summary.mean["load"] * material.K / material.E_star
    xe = 2 * run.summary.se["load"] * material.K / material.E_star
    assert x[0] - xe[0] <= 0 < x[1] - xe[1]  # at 100 kPa the 2-SE bar reaches p <= 0 (seed 1)
    ax = load_run_figure(run).axes[0]
    bars = ax.containers[0]
    segments = np.concatenate([c.get_segments() for c in bars.lines[2]])
    assert np.all(segments > 0), "a bar on the log-log panel reaches p <= 0"
    # the same product computed twice, once through matplotlib's float arrays: a few roundings
    np.testing.assert_allclose(segments[:, :, 0].min(), x[0] * 10**-ARROW_DECADES, rtol=1e-12)
    (arrow,) = [line for line in ax.get_lines() if line.get_marker() == "<"]
    np.testing.assert_allclose(arrow.get_xdata(), [x[0] * 10**-ARROW_DECADES], rtol=1e-12)  # idem
    assert "2 SE reaches 0: bar cut, arrow" in _legend_texts(ax)


def test_ingest_histogram_legend_gives_the_sigma_the_printout_gives(capsys, tmp_path, monkeypatch):
    import mcsim.figures.style

    drawn = []
    monkeypatch.setattr(mcsim.figures.style, "save", lambda fig, path, **_: drawn.append(fig))
    scan = Path(__file__).parents[2] / "examples" / "scan.gwy"
    code, out, err = run_cli(capsys, "ingest", scan, "--out", tmp_path / "scan.toml")
    assert code == 0, err
    (printed,) = re.findall(r"^surface +sigma = ([0-9.]+) nm", out, flags=re.MULTILINE)
    texts = [t.get_text() for t in drawn[0].legends[0].get_texts()]
    # 2.521 nm (the summits' standard deviation); the binned histogram's own is 2.56 nm
    assert re.findall(r"sigma\$ = ([0-9.]+) nm", " ".join(texts)) == [printed], (texts, out)


def _overlaps(a, b) -> bool:
    """Whether two display-space boxes share an area (touching edges do not count)."""
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_the_pads_figure_has_one_legend_below_its_panels_covering_neither():
    from mcsim.figures.stiction import pads_figure
    from mcsim.studies.pads import pad_statistics

    force = np.random.default_rng(1).normal(93e-6, 30e-6, 300)
    stats = pad_statistics(force, 130e-6)
    fig = pads_figure(force, 81e-6, restoring_force=130e-6, p_stick=stats.p_stick,
                      interval=stats.p_stick_ci, interval_name="Clopper-Pearson 95 %")  # fmt: skip
    renderer = _renderer(fig)
    assert all(ax.get_legend() is None for ax in fig.axes)
    (legend,) = fig.legends
    texts = [t.get_text() for t in legend.get_texts()]
    assert len(texts) == len(set(texts)) == 6  # bars, CDF, 3 lines shared by both panels, p_stick
    box = legend.get_window_extent(renderer)
    for ax in fig.axes:
        assert not _overlaps(box, ax.get_window_extent(renderer)), ax.get_ylabel()
    assert fig.bbox.x0 <= box.x0 and box.x1 <= fig.bbox.x1 and fig.bbox.y0 <= box.y0


def _rh_sweep(surface: str, rh):
    from mcsim.studies.sweeps import sweep

    return sweep(SURFACES[surface], SILICON, {"rh": rh}, law="auto",
                 environment={"hamaker": 1.6e-19}, workers=1)  # fmt: skip


def _line_points(ax, renderer) -> np.ndarray:
    """Every drawn data point of the axes' lines (and 40 points along each segment), in pixels."""
    points = []
    for line in ax.get_lines():
        xy = ax.transData.transform(np.column_stack(line.get_data()).astype(float))
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        t = np.linspace(0, 1, 40)[:, None, None]
        points.append(xy if len(xy) < 2 else (xy[:-1] + t * (xy[1:] - xy[:-1])).reshape(-1, 2))
    return np.concatenate(points)


def _covers(box, points) -> bool:
    x, y = points[:, 0], points[:, 1]
    return bool(np.any((box.x0 < x) & (x < box.x1) & (box.y0 < y) & (y < box.y1)))


def test_humidity_figure_draws_no_empty_part_no_single_regime_and_no_cut_title_or_end_point():
    from mcsim.figures.environment import humidity_figure

    # intermediate: the contacts give back more than they take at rest (contact work < 0:
    # the attraction presses them), and up to RH 0.3 (the films' onset, RH_dry) nothing
    # condenses: dry over the whole sweep
    result = _rh_sweep("intermediate", [0.05, 0.15, 0.3])
    assert np.all(result.data["work_of_separation_contact"] < 0)
    fig = humidity_figure(result)
    ax = fig.axes[0]
    renderer = _renderer(fig)
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    assert texts[0] == "total" and "contact (summits)" not in texts
    title = ax.title.get_text()
    assert "contact (summits): <= 0 at every RH" in title
    assert "regime: dry (capillary work < 10 % of the ceiling) over the whole sweep" in title
    assert len(ax.patches) == len(ax.texts) == 0  # no shading, no regime name, for one regime
    box = ax.title.get_window_extent(renderer)
    assert fig.bbox.x0 <= box.x0 and box.x1 <= fig.bbox.x1 and box.y1 <= fig.bbox.y1
    low, high = ax.get_xlim()
    assert low < 5 and high > 30  # the markers at 5 % and 30 % are drawn whole


def test_humidity_figure_names_its_regimes_where_no_curve_runs():
    from mcsim.figures.environment import humidity_figure

    fig = humidity_figure(_rh_sweep("smooth", [0.05, 0.5, 0.85, 0.95]))
    ax = fig.axes[0]
    renderer = _renderer(fig)
    names = {t.get_text(): t for t in ax.texts}
    assert set(names) == {"dry", "transition", "saturated"}
    points, frame = _line_points(ax, renderer), ax.get_window_extent(renderer)
    for text in names.values():
        box = text.get_window_extent(renderer)
        assert not _covers(box, points), text.get_text()
        assert frame.x0 <= box.x0 and box.x1 <= frame.x1, text.get_text()


def test_the_rh_sweep_note_says_rh_is_varied_and_gives_no_kelvin_radius_at_rh_0(capsys, tmp_path):
    code, out, err = run_cli(capsys, "sweep", "--surface", "smooth", "--law", "dmt", "--hamaker",
                             "1.6e-19 J", "--vary", "rh=0.3,0.6", "--h=1,0", "--out",
                             tmp_path / "rh.h5")  # fmt: skip
    assert code == 0, err
    (note,) = [line for line in (out + err).splitlines() if "environment: Hamaker" in line]
    assert "RH = varied (--vary rh)" in note and "RH = 0," not in note
    assert note.endswith("Kelvin radius = per point (kelvin_radius in the sweep file)")
    code, out, err = run_cli(capsys, "adhesion", "--surface", "smooth", "--hamaker", "1.6e-19 J")
    (note,) = [line for line in (out + err).splitlines() if "environment: Hamaker" in line]
    assert code == 0 and note.endswith("Kelvin radius = none (RH = 0: no condensation)")


@pytest.fixture(scope="module")
def design_map():
    """σ × w over the smooth surface (law auto), crossing λ = 0.1 and 5 and ψ = 1."""
    from mcsim.studies.sweeps import sweep

    vary = {"sigma": "0.3nm:100nm:6:log", "gamma": "0.002:5:4:log"}
    return sweep(SMOOTH, SILICON, vary, law="auto", workers=1)


def _contour_points(ax, gid: str) -> np.ndarray:
    """The contour lines with this gid, 40 points along each segment, in pixels."""
    (cs,) = [c for c in ax.collections if c.get_gid() == gid]
    points = []
    for path in cs.get_paths():
        for piece in path.to_polygons(closed_only=False):
            xy = ax.transData.transform(piece)
            t = np.linspace(0, 1, 40)[:, None, None]
            points.append((xy[:-1] + t * (xy[1:] - xy[:-1])).reshape(-1, 2))
    return np.concatenate(points)


def test_the_design_map_names_each_boundary_beside_its_line_not_over_it(design_map):
    from mcsim.figures.sweeps import sweep_figure

    fig = sweep_figure(design_map, kind="map")
    renderer = _renderer(fig)
    ax = fig.axes[0]
    texts = {t.get_text(): t for t in ax.texts}
    for gid, names in (("plasticity-boundary", ["ψ = 1"]),
                       ("regime-boundaries", ["λ = 0.1", "λ = 5"])):  # fmt: skip
        points = _contour_points(ax, gid)
        for name in names:
            box = texts[name].get_window_extent(renderer)
            assert not _covers(box, points), name
            # beside it: within 12 points of the line
            gap = min(np.hypot(np.clip(points[:, 0], box.x0, box.x1) - points[:, 0],
                               np.clip(points[:, 1], box.y0, box.y1) - points[:, 1]))  # fmt: skip
            assert gap < 12 * fig.dpi / 72, name


def test_the_design_lines_put_no_text_over_a_curve(design_map):
    from mcsim.figures.sweeps import sweep_figure

    fig = sweep_figure(design_map, kind="lines")
    renderer = _renderer(fig)
    for ax in fig.axes:
        if not ax.get_lines():
            continue  # a colour bar
        points = _line_points(ax, renderer)
        for text in ax.texts:
            assert not _covers(text.get_window_extent(renderer), points), text.get_text()
    assert "no adhesive contact at rest" in fig.axes[0].get_title()
