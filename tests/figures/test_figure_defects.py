"""The figure defects of issue 44 (point 7), each as what a reader must see: a marker where its
number says, a promise in a title kept, every value counted that the axis does not show, no
legend over data, axes that hug their data, no "e+03" and no hyphen for a minus sign."""

import dataclasses
import re

import numpy as np
import pytest
from conftest import run_cli

from mcsim.model.presets import MATERIALS, SURFACES

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]


def _renderer(fig):
    """Draw the figure (Agg) and return its renderer: text extents are then final."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def _texts(fig) -> list[str]:
    """Every text of the drawn figure: titles, labels, tick labels, legends, annotations."""
    from matplotlib.text import Text

    _renderer(fig)
    return [t.get_text() for t in fig.findobj(Text) if t.get_visible() and t.get_text()]


def _overlaps(a, b) -> bool:
    """Whether two display-space boxes share an area (touching edges do not count)."""
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


#: A number written with an exponent ("1e+03", "-5e-06"): a reader wants 1000 or 10³.
E_NOTATION = re.compile(r"\d[eE][+-]?\d")
#: A hyphen used as a minus sign (outside mathtext, which draws "-" as U+2212).
HYPHEN_MINUS = re.compile(r"(^|[\s=(\[,])-\d")


def _outside_math(text: str) -> str:
    return re.sub(r"\$[^$]*\$", "", text)


def _assert_plain_numbers(fig) -> None:
    for text in _texts(fig):
        plain = _outside_math(text)
        assert not E_NOTATION.search(plain), text
        assert not HYPHEN_MINUS.search(plain), text


# --- pads: p_stick against one input ----------------------------------------------------------


@pytest.fixture
def pads_sweep():
    """A pads sweep over σ as the sweep file holds it (numbers chosen, not computed: the
    figure is the subject): 40 pads, p_stick 0.3 to 0.9, the model 0.1 to 0.95."""
    from mcsim.store.sweepfile import Sweep

    data = {"p_stick": np.array([0.9, 0.5, 0.3]), "p_stick_low": np.array([0.76, 0.34, 0.17]),
            "p_stick_high": np.array([0.97, 0.66, 0.46]),
            "p_stick_model": np.array([0.95, 0.45, 0.1]),
            "p_stick_method": np.array(["pads"] * 3, dtype=object),
            "contacting_summits": np.array([50.0, 20.0, 5.0]),
            "error": np.array([""] * 3, dtype=object)}  # fmt: skip
    attrs = {"varied": '["sigma"]', "pads": 40, "area": 30e-12, "law": "jkr",
             "surface": '{"name": "smooth"}', "restoring_force": 20e-6, "preload": 1e6}  # fmt: skip
    return Sweep(coords={"sigma": np.array([1.5e-9, 2e-9, 2.5e-9]), "h": np.array([0.0])},
                 data=data, dims={k: ("sigma",) for k in data}, units={"sigma": "m"},
                 long_names={"sigma": "standard deviation of the summit heights"}, attrs=attrs)  # fmt: skip


def test_the_few_summits_cross_sits_on_the_model_line_it_qualifies(pads_sweep):
    from mcsim.figures.stiction import stiction_figure

    ax = stiction_figure(pads_sweep).axes[0]
    (cross,) = [line for line in ax.get_lines() if line.get_marker() == "x"]
    assert list(cross.get_ydata()) == [0.1]  # the model at the one point with 5 summits, not 0.3


def test_the_p_stick_axis_reaches_half_the_lowest_value_drawn_and_no_further(pads_sweep):
    from mcsim.figures.stiction import stiction_figure

    fig = stiction_figure(pads_sweep)
    ax = fig.axes[0]
    renderer = _renderer(fig)
    # the lowest value drawn is the model's 0.1 (not the floor of 40 pads, 0.0025)
    assert ax.get_ylim()[0] == pytest.approx(0.1 / 2, rel=1e-12)
    # the legend (below the axes) covers no bar, no point
    (legend,) = fig.legends
    box = legend.get_window_extent(renderer)
    for container in ax.containers:
        for artist in (*container.lines[2], container.lines[0]):
            assert not _overlaps(box, artist.get_window_extent(renderer))
    title = ax.get_title()
    assert "surface smooth" in title and "law jkr" in title


def test_the_pads_survival_panel_draws_p_stick_at_p_not_one_minus_p():
    from mcsim.figures.stiction import pads_figure

    force = np.linspace(1e-6, 10e-6, 10)  # 3 of 10 above 7.5 µN: p_stick = 0.3
    fig = pads_figure(force, restoring_force=7.5e-6, p_stick=0.3, interval=(0.1, 0.6))
    (bars,) = fig.axes[1].containers
    assert bars.lines[0].get_ydata()[0] == 0.3
    (segment,) = bars.lines[2][0].get_segments()
    assert sorted(segment[:, 1]) == pytest.approx([0.1, 0.6], abs=1e-15)


# --- design curves: the Table-1 diamonds and the values below a log axis ---------------------


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
@pytest.mark.parametrize(("grid", "diamonds"), [("0.3nm:20nm:9:log", 0), ("1nm,1.4nm,2nm", 1)])
def test_the_title_promises_a_diamond_only_where_one_is_drawn(grid, diamonds):
    from mcsim.figures.sweeps import sweep_figure
    from mcsim.studies.sweeps import sweep

    fig = sweep_figure(sweep(SMOOTH, SILICON, {"sigma": grid}, law="dmt", workers=1))
    drawn = [line for ax in fig.axes for line in ax.get_lines() if line.get_marker() == "D"]
    assert len(drawn) == diamonds * 2  # one per panel (pull-off, work of separation)
    assert ("◆" in fig.get_suptitle()) == bool(diamonds)


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")
def test_every_value_below_a_log_axis_is_marked_at_its_edge_and_counted():
    from mcsim.figures.sweeps import sweep_figure
    from mcsim.studies.sweeps import sweep

    result = sweep(SMOOTH, SILICON, {"sigma": "0.3nm:20nm:9:log"}, law="dmt", workers=1)
    fig = sweep_figure(result)
    counted = 0
    for ax, key in zip(fig.axes, ("pull_off_pressure", "work_of_separation")):
        y = result.data[key]
        bottom = ax.get_ylim()[0]
        below = int(np.sum((y > 0) & (y < bottom)))
        marks = [line for line in ax.get_lines() if line.get_gid() == "below-axis"]
        assert sum(line.get_xdata().size for line in marks) == below
        if below:
            assert f"{below} of {y.size} points below the axis" in ax.get_title()
        counted += below
    assert counted > 0  # the grid reaches σ where the pull-off is below 1e-9 of its top


@pytest.fixture(scope="module")
def design_map():
    """σ × w over the smooth surface (law auto): DMT, Maugis-Dugdale and JKR cells, some 0."""
    from mcsim.studies.sweeps import sweep

    vary = {"sigma": "0.3nm:100nm:6:log", "gamma": "0.002:5:4:log"}
    return sweep(SMOOTH, SILICON, vary, law="auto", workers=1)


def test_the_region_names_of_a_design_map_cover_no_coloured_cell(design_map):
    from mcsim.figures.grid import cell_edges, is_log_grid
    from mcsim.figures.sweeps import REGIONS, sweep_figure

    fig = sweep_figure(design_map, kind="map")
    renderer = _renderer(fig)
    sigma, w = design_map.coords["sigma"] * 1e9, design_map.coords["gamma"]
    xe = cell_edges(sigma, is_log_grid(design_map.coords["sigma"]))
    ye = cell_edges(w, is_log_grid(w))
    names = {name for name, *_ in REGIONS}
    checked = 0
    for ax, key in zip(fig.axes[:2], ("pull_off_pressure", "work_of_separation")):  # not the bars
        z = (
            design_map.data[key][:, :, 0]
            if design_map.data[key].ndim == 3
            else design_map.data[key]
        )
        coloured = np.isfinite(z) & (z > 0)  # rows σ, columns w
        for text in (t for t in ax.texts if t.get_text() in names):
            box = text.get_window_extent(renderer)
            for i, j in zip(*np.nonzero(coloured)):
                corners = ax.transData.transform([(xe[i], ye[j]), (xe[i + 1], ye[j + 1])])
                cell = type(box).from_extents(*corners.min(axis=0), *corners.max(axis=0))
                assert not _overlaps(box, cell), (text.get_text(), sigma[i], w[j])
            checked += 1
    assert checked == 6  # DMT, Maugis-Dugdale and JKR on each panel, all in blank cells


# --- humidity ----------------------------------------------------------------------------------


def test_the_humidity_figure_counts_the_points_it_does_not_draw_and_says_what_dominates():
    from mcsim.figures.environment import humidity_figure
    from mcsim.studies.sweeps import sweep

    result = sweep(SURFACES["intermediate"], SILICON, {"rh": [0.05, 0.85, 0.95]}, law="auto",
                   environment={"hamaker": 1.6e-19}, workers=1)  # fmt: skip
    capillary = np.ravel(result.data["work_of_separation_capillary"])
    assert capillary[0] == 0 and capillary[-1] > 0  # nothing condenses at 5 %: not drawn
    fig = humidity_figure(result)
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    (entry,) = [t for t in texts if t.startswith("capillary")]
    assert "1 of 3 RH ≤ 0 (not drawn)" in entry
    title = fig.axes[0].get_title()
    others = np.max([np.ravel(result.data[k]) for k in ("work_of_separation_contact",
                                                        "work_of_separation_vdw")], axis=0)  # fmt: skip
    largest = capillary > np.maximum(others, 0)
    assert largest[-1]
    first = next(i for i in range(3) if largest[i:].all())  # from there on the largest part
    assert f"capillary the largest part of the work from RH = {[5, 85, 95][first]} %" in title


# --- runs: a cycle ----------------------------------------------------------------------------


def test_the_cycle_run_figure_keeps_its_legend_off_the_curves_and_its_axes_near_them(
    capsys, tmp_path
):
    from mcsim.figures.runs import run_figure
    from mcsim.store.runfile import read_run

    out = tmp_path / "c.h5"
    code, _, err = run_cli(capsys, "simulate", "--surface", "smooth", "--material", "examples/gold.toml",
                           "--law", "jkr", "--cycle", "--area", "1e-10", "--h=3:-1:5",
                           "--realizations", "3", "--seed", "1", "--workers", "1", "--quiet",
                           "--out", out)  # fmt: skip
    assert code == 0, err
    run = read_run(out)
    fig = run_figure(run)
    data_axes = [ax for ax in fig.axes if ax.axison]
    assert all(ax.get_legend() is None for ax in data_axes)
    assert sum(ax.get_legend() is not None for ax in fig.axes) == 1  # in the spare panel
    for ax in data_axes:
        if ax.get_yscale() == "log":  # limits from the means and curves, not a bar's 0.999
            y = np.concatenate([line.get_ydata() for line in ax.get_lines()])
            y = y[np.isfinite(y) & (y > 0)]
            assert ax.get_ylim()[0] >= y.min() / 2 * (1 - 1e-12)
    assert any("A_n\\,K" in ax.get_ylabel() for ax in data_axes)
    _assert_plain_numbers(fig)
    assert any("$h = -1$" in t for t in _texts(fig))


# --- contact laws, contact maps, load control ------------------------------------------------


def test_the_adhesion_cycle_has_its_legend_below_and_no_hyphen_or_exponent_in_its_numbers():
    from toy_laws import MATERIAL, TOY

    from mcsim.figures.adhesion import adhesion_figure

    fig = adhesion_figure(SURFACES["super-smooth"], MATERIAL, TOY, points=100)
    renderer = _renderer(fig)
    (legend,) = fig.legends
    assert fig.axes[0].get_legend() is None
    assert not _overlaps(
        legend.get_window_extent(renderer), fig.axes[0].get_window_extent(renderer)
    )
    _assert_plain_numbers(fig)
    ticks = [t.get_text() for ax in fig.axes for t in ax.get_yticklabels()]
    assert any("\u2212" in t for t in ticks)  # the tensile loads, with a true minus sign


def test_the_contact_figure_writes_a_pressure_of_1000_mpa_as_1_gpa(tmp_path):
    from mcsim.figures.contact import _pressure_text, contact_figure
    from mcsim.studies.maps.contact import contact_map

    heights = np.random.default_rng(1).normal(0.0, 1e-9, (32, 32))
    np.save(tmp_path / "map.npy", heights)
    result = contact_map(tmp_path / "map.npy", SILICON, [1e8, 1e9], unit="m", pixel_size=10e-9,
                         keep_fields=True)  # fmt: skip
    fig = contact_figure(result)
    assert fig.axes[0].get_title().startswith("$p$ = 1 GPa")
    _assert_plain_numbers(fig)
    assert [_pressure_text(v) for v in (999.6e6, 999e6, 1.5e3)] == ["1 GPa", "999 MPa", "1.5 kPa"]


def test_the_load_control_figure_labels_in_mathtext_and_hugs_its_curve():
    from mcsim.figures.loadcontrol import load_control_figure
    from mcsim.physics.loadcontrol import load_control

    material = dataclasses.replace(SILICON, tau=1e8)
    result = load_control(SMOOTH, material, np.geomspace(1e4, 1e8, 5), "maugis-dugdale")
    fig = load_control_figure(result)
    area, friction = fig.axes
    for ax in (area, friction):
        assert "$" in ax.get_xlabel() and "$" in ax.get_ylabel()
    assert "A_r/A_n" in area.get_ylabel() and "(MPa)" in friction.get_ylabel()
    curve = area.get_lines()[0].get_ydata()
    low, high = area.get_ylim()
    assert curve.min() / 1.5 == pytest.approx(low, rel=1e-12)
    assert curve.max() * 1.5 == pytest.approx(high, rel=1e-12)
    _assert_plain_numbers(fig)
