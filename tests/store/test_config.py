"""Surfaces and materials by preset name or from TOML files with units; bad files named in errors."""

import re
from pathlib import Path

import pytest
from tolerances import ROUNDING_FEW, ROUNDING_FORMULA

from mcsim.model.errors import MCSimError, ParameterError, UnitError
from mcsim.model.params import combine_surfaces
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.store.config import (
    load_material,
    load_surface,
    material_in_surface_file,
    surface_from_table,
)

RUNS = Path(__file__).resolve().parents[2] / "runs"

SMOOTH_TOML = """
[surface]
name = "my-smooth"
sigma = "1.4 nm"
R = "1.7 um"
eta = "17 um^-2"
"""

SILICON_TOML = """
[material]
name = "my-silicon"
E = "160 GPa"
nu = 0.22
gamma = "500 mJ/m^2"
H = "12.5 GPa"
"""


def write(tmp_path: Path, text: str, name: str = "run.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def fields(obj, names):
    return [getattr(obj, n) for n in names]


SURFACE_FIELDS = ("sigma", "R", "eta")
MATERIAL_FIELDS = ("E1", "E2", "nu1", "nu2", "gamma", "H")


# --- presets ----------------------------------------------------------------------------------


@pytest.mark.parametrize("name", list(SURFACES))
def test_surface_preset_name_gives_the_preset(name):
    assert load_surface(name) is SURFACES[name]


def test_material_preset_name_gives_the_preset():
    assert load_material("silicon") is MATERIALS["silicon"]


@pytest.mark.parametrize("name", ["smoth", "smooth.txt", "data.h5"])
def test_unknown_surface_name_lists_the_presets(name):
    with pytest.raises(ParameterError, match=rf"^unknown surface '{re.escape(name)}'.*: .*smooth"):
        load_surface(name)


@pytest.mark.parametrize("name", ["steel", "silicon.txt"])
def test_unknown_material_name_lists_the_presets(name):
    with pytest.raises(
        ParameterError, match=rf"^unknown material '{re.escape(name)}'.*: .*silicon"
    ):
        load_material(name)


# --- files that load --------------------------------------------------------------------------


def test_surface_file_with_units_gives_si_values(tmp_path):
    s = load_surface(write(tmp_path, SMOOTH_TOML))
    # decimal text times unit factors (um^-2 a power): ROUNDING_FORMULA
    assert fields(s, SURFACE_FIELDS) == pytest.approx([1.4e-9, 1.7e-6, 17e12], rel=ROUNDING_FORMULA)
    assert s.name == "my-smooth"


def test_surface_file_accepts_a_str_path(tmp_path):
    s = load_surface(str(write(tmp_path, SMOOTH_TOML)))
    assert s.sigma == pytest.approx(1.4e-9, rel=ROUNDING_FORMULA)


@pytest.mark.parametrize(
    ("line", "message"),
    [
        (
            "sigma = 1.4",
            'sigma = 1.4 has no unit .*; write it with its unit, e.g. sigma = "1.4 nm"',
        ),
        ('sigma = "1.4"', "sigma = '1.4' has no unit .*e.g. sigma = \"1.4 nm\""),
        ("sigma = 1.4e-9", 'sigma = 1.4e-09 has no unit .*e.g. sigma = "1.4e-09 m"'),
        ("sigma = 2", 'sigma = 2 has no unit .*e.g. sigma = "2 nm"'),
    ],
)
def test_a_bare_number_for_a_length_in_a_file_is_refused_with_a_hint(tmp_path, line, message):
    path = write(tmp_path, f'[surface]\n{line}\nR = "1.7 um"\neta = "17 um^-2"\n')
    where = re.escape(f"{path} [surface]")
    with pytest.raises(UnitError, match=rf"^{where}: {message}$"):
        load_surface(path)


@pytest.mark.parametrize(
    ("line", "field"),
    [('E = 160e9\nnu = 0.22\ngamma = "0.5 J/m^2"', "E"),
     ('E = "160 GPa"\nnu = 0.22\ngamma = 0.5', "gamma"),
     ('E1 = "160 GPa"\nE2 = 7e10\nnu = 0.22\ngamma = "0.5 J/m^2"', "E2"),
     ('E = "160 GPa"\nnu = 0.22\ngamma = "0.5 J/m^2"\nH = 12', "H")],
)  # fmt: skip
def test_a_bare_number_for_a_material_quantity_in_a_file_is_refused(tmp_path, line, field):
    path = write(tmp_path, f"[material]\n{line}\n")
    with pytest.raises(UnitError, match=rf"\[material\]: {field} = \S+ has no unit"):
        load_material(path)


def test_bare_numbers_stay_si_in_python_tables():
    s = surface_from_table({"sigma": 1.4e-9, "R": 1.7e-6, "eta": 17e12})
    assert fields(s, SURFACE_FIELDS) == [1.4e-9, 1.7e-6, 17e12]


def test_inline_histogram_edges_in_a_file_need_a_unit(tmp_path):
    path = write(tmp_path, '[surface]\nR = "1.7 um"\neta = "17 um^-2"\n'
                 "[surface.heights]\nedges = [0, 1, 2]\ncounts = [1, 2]\n")  # fmt: skip
    with pytest.raises(UnitError, match=r'heights: inline edges need their unit, e.g. unit = "nm"'):
        load_surface(path)


def test_a_unit_error_names_the_field_as_written_E_not_E1(tmp_path):
    path = write(tmp_path, '[material]\nE = "79 GPA"\nnu = 0.2\ngamma = "0.5 J/m^2"\n')
    where = re.escape(f"{path} [material]")
    with pytest.raises(
        UnitError, match=rf"^{where}: E: unknown unit 'GPA' .*; did you mean 'GPa'\?$"
    ):
        load_material(path)


@pytest.mark.parametrize(
    ("load", "name", "closest"),
    [(load_surface, "smoth", "smooth"), (load_surface, "Rough", "rough"),
     (load_surface, "super_smooth", "super-smooth"), (load_material, "silcon", "silicon")],
)  # fmt: skip
def test_a_mistyped_preset_name_suggests_the_closest(load, name, closest):
    with pytest.raises(
        ParameterError, match=rf"^unknown \w+ '{name}' \(did you mean '{closest}'\?\)"
    ):
        load(name)


def test_material_file_E_and_nu_set_both_solids(tmp_path):
    m = load_material(write(tmp_path, SILICON_TOML))
    assert fields(m, MATERIAL_FIELDS) == pytest.approx(
        [160e9, 160e9, 0.22, 0.22, 0.5, 12.5e9], rel=ROUNDING_FORMULA
    )
    assert m.name == "my-silicon"


def test_material_file_with_separate_solids(tmp_path):
    text = '[material]\nE1 = "160 GPa"\nE2 = "70 GPa"\nnu1 = 0.22\nnu2 = 0.35\ngamma = "0.1 N/m"\n'
    m = load_material(write(tmp_path, text))
    assert fields(m, MATERIAL_FIELDS[:5]) == pytest.approx(
        [160e9, 70e9, 0.22, 0.35, 0.1], rel=ROUNDING_FEW
    )


def test_material_file_without_hardness_has_none(tmp_path):
    m = load_material(write(tmp_path, SILICON_TOML.replace('H = "12.5 GPa"\n', "")))
    assert m.H is None


def test_material_table_in_a_surface_file_is_found(tmp_path):
    m = material_in_surface_file(write(tmp_path, SMOOTH_TOML + SILICON_TOML))
    assert m.E1 == pytest.approx(160e9, rel=ROUNDING_FEW)


def test_surface_file_without_material_table_has_no_material(tmp_path):
    assert material_in_surface_file(write(tmp_path, SMOOTH_TOML)) is None


def test_surface_preset_has_no_material():
    assert material_in_surface_file("smooth") is None


def test_combine_of_presets_equals_combine_surfaces(tmp_path):
    text = '[surface]\nname = "c"\ncombine = ["deposited-polysilicon", "typical-substrate"]\n'
    s = load_surface(write(tmp_path, text + 'eta = "14.7 um^-2"\n'))
    expected = combine_surfaces(
        SURFACES["deposited-polysilicon"], SURFACES["typical-substrate"], eta=14.7e12
    )
    assert fields(s, SURFACE_FIELDS) == pytest.approx(
        fields(expected, SURFACE_FIELDS), rel=ROUNDING_FORMULA
    )
    assert s.name == "c"


def test_combine_reads_a_file_relative_to_the_combining_file(tmp_path, monkeypatch):
    (tmp_path / "sub").mkdir()
    write(tmp_path / "sub", SMOOTH_TOML, "one.toml")
    text = '[surface]\ncombine = ["one.toml", "one.toml"]\neta = "17 um^-2"\n'
    path = write(tmp_path / "sub", text, "both.toml")
    monkeypatch.chdir(tmp_path)
    assert load_surface(path).sigma == pytest.approx(2**0.5 * 1.4e-9, rel=ROUNDING_FORMULA)


# --- files that do not load -------------------------------------------------------------------


def test_missing_file_is_named(tmp_path):
    path = tmp_path / "absent.toml"
    with pytest.raises(MCSimError, match=rf"^{re.escape(str(path))}: no such file$"):
        load_surface(path)


def test_bad_toml_syntax_names_the_file(tmp_path):
    path = write(tmp_path, '[surface\nsigma = "1 nm"\n')
    with pytest.raises(MCSimError, match=rf"^{re.escape(str(path))}: not a valid TOML file"):
        load_surface(path)


def test_non_toml_content_names_the_file(tmp_path):
    path = tmp_path / "run.toml"
    path.write_bytes(b"\x89HDF\r\n\x1a\n\xff\x00")
    with pytest.raises(MCSimError, match=rf"^{re.escape(str(path))}: not a valid TOML file"):
        load_surface(path)


def test_directory_named_toml_names_the_path(tmp_path):
    path = tmp_path / "dir.toml"
    path.mkdir()
    with pytest.raises(MCSimError, match=rf"^{re.escape(str(path))}: cannot read"):
        load_surface(path)


@pytest.mark.parametrize(
    ("load", "table"), [(load_surface, "surface"), (load_material, "material")]
)
def test_missing_table_names_file_and_table(tmp_path, load, table):
    path = write(tmp_path, 'title = "nothing here"\n')
    with pytest.raises(
        ParameterError, match=rf"^{re.escape(str(path))}: missing table \[{table}\]$"
    ):
        load(path)


@pytest.mark.parametrize(
    ("load", "table"), [(load_surface, "surface"), (load_material, "material")]
)
def test_table_that_is_not_a_table_names_file_and_table(tmp_path, load, table):
    path = write(tmp_path, f"{table} = 3\n")
    with pytest.raises(
        ParameterError, match=rf"^{re.escape(str(path))}: \[{table}\] must be a table, got 3$"
    ):
        load(path)


@pytest.mark.parametrize("key", ["sigma", "R", "eta"])
def test_missing_surface_key_names_file_and_key(tmp_path, key):
    text = "\n".join(line for line in SMOOTH_TOML.splitlines() if not line.startswith(key))
    path = write(tmp_path, text)
    where = re.escape(f"{path} [surface]")
    with pytest.raises(ParameterError, match=rf"^{where}: missing key '{key}'"):
        load_surface(path)


@pytest.mark.parametrize(("key", "missing"), [("E", "E1"), ("nu", "nu1"), ("gamma", "gamma")])
def test_missing_material_key_names_file_and_key(tmp_path, key, missing):
    text = "\n".join(line for line in SILICON_TOML.splitlines() if not line.startswith(f"{key} "))
    path = write(tmp_path, text)
    where = re.escape(f"{path} [material]")
    with pytest.raises(ParameterError, match=rf"^{where}: missing key '{missing}'"):
        load_material(path)


def test_unknown_surface_key_names_file_key_and_allowed_keys(tmp_path):
    path = write(tmp_path, SMOOTH_TOML + 'sigma_rms = "1 nm"\n')
    where = re.escape(f"{path} [surface]")
    with pytest.raises(
        ParameterError,
        match=rf"^{where}: unknown key\(s\) sigma_rms \(allowed: sigma, R, eta, rq, summit_offset, name\)$",
    ):
        load_surface(path)


def test_unknown_material_key_names_file_and_key(tmp_path):
    path = write(tmp_path, SILICON_TOML + 'hardness = "12 GPa"\n')
    where = re.escape(f"{path} [material]")
    with pytest.raises(ParameterError, match=rf"^{where}: unknown key\(s\) hardness \(allowed: "):
        load_material(path)


def test_shorthand_and_separate_values_together_are_refused(tmp_path):
    path = write(tmp_path, SILICON_TOML + 'E1 = "100 GPa"\n')
    where = re.escape(f"{path} [material]")
    with pytest.raises(ParameterError, match=rf"^{where}: give either E or E1 and E2, not both$"):
        load_material(path)


@pytest.mark.parametrize(
    ("line", "field", "message"),
    [
        ('R = "1.7 furlong"', "R", "unknown unit 'furlong' for a length"),
        ('R = "1.7 GPa"', "R", "unknown unit 'GPa' for a length"),
        ('eta = "17 um^2"', "eta", r"unknown unit 'um\^2' for a density"),
        ('sigma = "thin"', "sigma", "cannot read 'thin' as a number"),
        ('sigma = "inf nm"', "sigma", "'inf nm' is not finite"),
        ("sigma = true", "sigma", "expected a number"),
    ],
)
def test_bad_surface_quantity_names_file_and_field(tmp_path, line, field, message):
    text = "\n".join(
        line if old.startswith(f"{field} ") else old for old in SMOOTH_TOML.splitlines()
    )
    path = write(tmp_path, text)
    where = re.escape(f"{path} [surface]")
    with pytest.raises(UnitError, match=rf"^{where}: {field}: {message}"):
        load_surface(path)


def test_bad_material_unit_names_file_and_field(tmp_path):
    path = write(tmp_path, SILICON_TOML.replace('"500 mJ/m^2"', '"0.5 J"'))
    where = re.escape(f"{path} [material]")
    with pytest.raises(UnitError, match=rf"^{where}: gamma: unknown unit 'J' .*J/m\^2"):
        load_material(path)


def test_negative_surface_value_names_file_field_and_allowed_range(tmp_path):
    path = write(tmp_path, SMOOTH_TOML.replace('"1.4 nm"', '"-1.4 nm"'))
    where = re.escape(f"{path} [surface]")
    message = r"sigma = -1.4e-09 m is out of range \(allowed: \[1e-12, 0.01\] m\)"
    with pytest.raises(ParameterError, match=rf"^{where}: {message}$"):
        load_surface(path)


@pytest.mark.parametrize(("old", "new"), [('"1.7 um"', "nan"), ('"17 um^-2"', "-inf")])
def test_non_finite_toml_number_names_file_and_field(tmp_path, old, new):
    path = write(tmp_path, SMOOTH_TOML.replace(old, new))
    field = "R" if new == "nan" else "eta"
    where = re.escape(f"{path} [surface]")
    with pytest.raises(UnitError, match=rf"^{where}: {field}: {new} is not finite"):
        load_surface(path)


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("nu = 0.22", "nu = 0.5", r"nu1 = 0.5 is out of range \(allowed: \(-1, 0.5\)\)"),
        ('"160 GPa"', '"0 GPa"', r"E1 = 0.0 Pa is out of range \(allowed: >= 1 Pa\)"),
        (
            '"500 mJ/m^2"',
            '"-1 mJ/m^2"',
            r"gamma = -0.001 J/m\^2 is out of range \(allowed: \[0, 1000\] J/m\^2\)",
        ),
    ],
)
def test_out_of_range_material_value_names_file_and_field(tmp_path, old, new, message):
    path = write(tmp_path, SILICON_TOML.replace(old, new))
    where = re.escape(f"{path} [material]")
    with pytest.raises(ParameterError, match=rf"^{where}: {message}$"):
        load_material(path)


@pytest.mark.parametrize(
    "combine", ['["smooth"]', '["smooth", "smooth", "smooth"]', '"smooth"', "[1, 2]"]
)
def test_combine_of_other_than_two_names_is_refused(tmp_path, combine):
    path = write(tmp_path, f'[surface]\ncombine = {combine}\neta = "17 um^-2"\n')
    where = re.escape(f"{path} [surface]")
    with pytest.raises(ParameterError, match=rf"^{where}: combine must list two surfaces, got "):
        load_surface(path)


def test_combine_without_density_names_file_and_key(tmp_path):
    path = write(tmp_path, '[surface]\ncombine = ["smooth", "smooth"]\n')
    where = re.escape(f"{path} [surface]")
    with pytest.raises(ParameterError, match=rf"^{where}: missing key 'eta'"):
        load_surface(path)


def test_combine_with_sigma_is_refused(tmp_path):
    text = '[surface]\ncombine = ["smooth", "smooth"]\neta = "17 um^-2"\nsigma = "1 nm"\n'
    path = write(tmp_path, text)
    where = re.escape(f"{path} [surface]")
    with pytest.raises(ParameterError, match=rf"^{where}: unknown key\(s\) sigma \(allowed: eta"):
        load_surface(path)


def test_combine_of_an_unknown_surface_names_file_and_surface(tmp_path):
    path = write(tmp_path, '[surface]\ncombine = ["smooth", "glass"]\neta = "17 um^-2"\n')
    where = re.escape(f"{path} [surface]")
    with pytest.raises(ParameterError, match=rf"^{where}: combine: unknown surface 'glass'"):
        load_surface(path)


def test_combine_of_a_missing_file_names_both_files(tmp_path):
    path = write(tmp_path, '[surface]\ncombine = ["smooth", "gone.toml"]\neta = "17 um^-2"\n')
    where = re.escape(f"{path} [surface]")
    gone = re.escape(str(tmp_path / "gone.toml"))
    with pytest.raises(MCSimError, match=rf"^{where}: combine: {gone}: no such file$"):
        load_surface(path)


# --- the example files in runs/ ---------------------------------------------------------------


def test_example_smooth_file_equals_the_smooth_preset():
    s, preset = load_surface(RUNS / "smooth.toml"), SURFACES["smooth"]
    assert fields(s, SURFACE_FIELDS) == pytest.approx(
        fields(preset, SURFACE_FIELDS), rel=ROUNDING_FORMULA
    )
    assert s.name == preset.name


def test_example_silicon_file_equals_the_silicon_preset():
    m, preset = load_material(RUNS / "silicon.toml"), MATERIALS["silicon"]
    assert fields(m, MATERIAL_FIELDS) == pytest.approx(
        fields(preset, MATERIAL_FIELDS), rel=ROUNDING_FORMULA
    )
    assert m.name == preset.name


def test_example_combined_file_equals_smooth_within_table_1_rounding():
    # Table 1 prints σ = 1.4 nm and R = 1.7 µm: tolerance half a unit of the last digit
    s, preset = load_surface(RUNS / "combined.toml"), SURFACES["smooth"]
    assert s.sigma == pytest.approx(preset.sigma, abs=0.05e-9)
    assert s.R == pytest.approx(preset.R, abs=0.05e-6)
    assert s.eta == pytest.approx(preset.eta, rel=1e-14)


@pytest.mark.parametrize("path", sorted(RUNS.glob("*.toml")), ids=lambda p: p.name)
def test_every_example_file_loads(path):
    loaded = [
        load(path)
        for load, table in ((load_surface, "[surface]"), (load_material, "[material]"))
        if table in path.read_text(encoding="utf-8")
    ]
    assert loaded


def test_material_file_accepts_the_equilibrium_spacing_and_shear_strength(tmp_path):
    m = load_material(write(tmp_path, SILICON_TOML + 'z0 = "0.3 nm"\ntau = "100 MPa"\n'))
    assert (m.z0, m.tau, m.H) == pytest.approx((0.3e-9, 100e6, 12.5e9), rel=ROUNDING_FORMULA)
    assert load_material(write(tmp_path, SILICON_TOML, "b.toml")).z0 is None


@pytest.mark.parametrize(("line", "match"), [('z0 = "-1 nm"', "z0"), ('tau = "0 MPa"', "tau"),
                                             ('tau = "3 nm"', "tau")])  # fmt: skip
def test_material_file_refuses_a_bad_equilibrium_spacing_or_shear_strength(tmp_path, line, match):
    with pytest.raises((ParameterError, UnitError), match=match):
        load_material(write(tmp_path, SILICON_TOML + line + "\n"))


def test_surface_file_gives_rq_summit_offset_and_map_heights(tmp_path):
    text = SMOOTH_TOML + 'rq = "1.6 nm"\nsummit_offset = "1.5 nm"\n'
    text += '[surface.map_heights]\nedges = [-2, 0, 1, 3]\ncounts = [1, 4, 2]\nunit = "nm"\n'
    surface = load_surface(write(tmp_path, text))
    assert (surface.rq, surface.summit_offset) == (
        pytest.approx(1.6e-9, rel=ROUNDING_FEW),
        pytest.approx(1.5e-9, rel=ROUNDING_FEW),
    )
    # the histogram's shape, standardized: P(z > 0) = 2/7 of its mass lies above 1 nm (edge 1)
    z_edge = (1e-9 - surface.map_heights.mean) / surface.map_heights.sigma
    assert float(surface.map_heights.sf(z_edge)) == pytest.approx(2 / 7, rel=ROUNDING_FORMULA)


def test_rq_defaults_to_the_map_histograms_own_rms(tmp_path):
    text = SMOOTH_TOML + '[surface.map_heights]\nedges = [-1, 0, 1]\ncounts = [1, 1]\nunit = "nm"\n'
    surface = load_surface(write(tmp_path, text))
    assert surface.rq == pytest.approx(
        2e-9 / 12**0.5, rel=ROUNDING_FORMULA
    )  # uniform on [-1, 1] nm
    assert surface.summit_offset is None


def test_bare_rq_in_a_file_is_refused(tmp_path):
    with pytest.raises(UnitError, match=r"rq = 1.6 has no unit"):
        load_surface(write(tmp_path, SMOOTH_TOML + "rq = 1.6\n"))


def test_the_work_of_adhesion_is_given_as_w_or_by_the_papers_gamma(tmp_path):
    by_w = load_material(
        write(tmp_path, '[material]\nE = "160 GPa"\nnu = 0.22\nw = "0.5 J/m^2"\n', "w.toml")
    )
    by_gamma = load_material(write(tmp_path, '[material]\nE = "160 GPa"\nnu = 0.22\ngamma = "0.5 J/m^2"\n', "g.toml"))  # fmt: skip
    assert by_w == by_gamma and by_w.w == by_w.gamma == 0.5


def test_w_and_gamma_together_are_refused(tmp_path):
    path = write(
        tmp_path, '[material]\nE = "160 GPa"\nnu = 0.22\nw = "0.5 J/m^2"\ngamma = "0.5 J/m^2"\n'
    )
    with pytest.raises(ParameterError, match="give either w or gamma"):
        load_material(path)
