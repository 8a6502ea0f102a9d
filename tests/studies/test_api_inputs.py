"""The Python API takes what the command line takes, and refuses the rest in one clear error.

``simulate``, ``sweep``, ``gw_curves``, ``adhesion_summary`` and ``load_control`` validate their
seed and environment as the CLI does; ``simulate(preload=...)`` is ``--preload``.
"""

import numpy as np
import pytest

import mcsim
from mcsim.cli.main import main
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.model.units import parse_quantity
from mcsim.physics.adhesion import adhesion_summary
from mcsim.physics.environment import Environment, as_environment
from mcsim.store.runfile import read_run

SMOOTH, SILICON = SURFACES["smooth"], MATERIALS["silicon"]


@pytest.mark.parametrize("seed", [-1, 1.5, "7"])
def test_a_bad_seed_is_refused_naming_it_before_any_file_is_claimed(tmp_path, seed):
    out = tmp_path / "run.h5"
    with pytest.raises(ParameterError, match=r"^seed = .* \(allowed: None or an integer >= 0\)"):
        mcsim.simulate(SMOOTH, SILICON, [1.0], "1 um^2", seed=seed, out=out)
    with pytest.raises(ParameterError, match=r"^seed = "):
        mcsim.sweep(SMOOTH, SILICON, {"sigma": [1e-9]}, law="jkr", mc=True, area="1 um^2",
                    seed=seed, out=tmp_path / "sweep.h5")  # fmt: skip
    assert list(tmp_path.iterdir()) == []


@pytest.mark.filterwarnings("ignore::mcsim.physics.adhesion.RegimeWarning")  # jkr at lambda 1.5
def test_an_environment_may_be_given_as_a_mapping_of_its_fields_as_in_a_toml_file():
    fields = {"hamaker": "1.6e-19 J", "rh": "60%", "contact_angle": "17 deg"}
    # "17 deg" is the decimal product rounded once (mcsim.model.units), not np.radians(17)
    angle = parse_quantity("17 deg", "angle", "contact_angle")
    assert angle == pytest.approx(np.radians(17), rel=1e-15)
    env = Environment(hamaker=1.6e-19, rh=0.6, contact_angle=angle)
    by_map = mcsim.gw_curves(SMOOTH, SILICON, [2.0, 0.5], law="jkr", environment=fields)
    by_obj = mcsim.gw_curves(SMOOTH, SILICON, [2.0, 0.5], law="jkr", environment=env)
    assert np.array_equal(by_map.load, by_obj.load) and by_map.environment == env
    # a bare angle is in degrees, the same float as "17 deg" (it was np.radians(17), an ulp off)
    assert as_environment({"rh": 0.6, "contact_angle": 17}).contact_angle == angle
    summary = adhesion_summary(SMOOTH, SILICON, "jkr", environment=fields)
    assert summary.pull_off == adhesion_summary(SMOOTH, SILICON, "jkr", environment=env).pull_off


def test_a_mapping_takes_the_keys_of_a_toml_environment_table(tmp_path):
    # README: "a mapping of its fields, as written in a TOML file"; one resolver for both
    from mcsim.store.config import environment_from_values, environment_in_file

    table = {"hamaker": "1.6e-19 J", "rh": 0.6, "liquid_surface_tension": "50 mJ/m^2"}
    surface = tmp_path / "s.toml"
    surface.write_text('[surface]\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n'
                       '[environment]\nhamaker = "1.6e-19 J"\nrh = 0.6\n'
                       'liquid_surface_tension = "50 mJ/m^2"\n')  # fmt: skip
    from_file = environment_from_values(environment_in_file(surface))
    assert as_environment(table) == from_file
    assert from_file == Environment(hamaker=1.6e-19, rh=0.6, surface_tension=0.05)
    # the field's own name still works, in a mapping and in a file
    renamed = {
        "surface_tension" if k == "liquid_surface_tension" else k: v for k, v in table.items()
    }
    assert as_environment(renamed) == from_file
    surface.write_text(surface.read_text().replace("liquid_surface_tension", "surface_tension"))
    assert environment_in_file(surface) == table


@pytest.mark.parametrize(
    ("environment", "says"),
    [({"rh": 0.5, "humidity": 0.5}, r"environment: unknown key\(s\) humidity \(allowed: hamaker, "),
     (0.5, r"environment must be an Environment or a mapping of its fields .*got float 0.5"),
     ({"rh": 1.2}, r"rh = 1.2 is out of range"),
     ({"surface_tension": 0.05, "liquid_surface_tension": "50 mJ/m^2"},
      r"^environment: surface_tension and liquid_surface_tension set the same field: give one$")],
)  # fmt: skip
def test_an_environment_that_is_not_one_is_a_parameter_error_naming_it(environment, says):
    with pytest.raises(ParameterError, match=says):
        mcsim.simulate(SMOOTH, SILICON, [1.0], "1 um^2", seed=1, environment=environment)
    with pytest.raises(ParameterError, match=says):
        mcsim.load_control(SMOOTH, SILICON, [1e6], "jkr", environment=environment)


def test_simulate_with_a_preload_is_the_command_line_preload(tmp_path):
    options = {"law": "jkr", "cycle": True, "realizations": 6, "seed": 5, "workers": 1}
    api = mcsim.simulate(SMOOTH, SILICON, np.linspace(3, -1, 9), "3 um^2", preload="1 MPa",
                         out=tmp_path / "api.h5", **options)  # fmt: skip
    code = main(["simulate", "--surface", "smooth", "--law", "jkr", "--area", "3um^2",
                 "--h=3:-1:9", "--cycle", "--preload", "1MPa", "--realizations", "6", "--seed",
                 "5", "--workers", "1", "--quiet", "--out", str(tmp_path / "cli.h5")])  # fmt: skip
    cli = read_run(tmp_path / "cli.h5")
    assert code == 0 and np.array_equal(api.sums, cli.sums)
    for key in ("preload", "preload_unit", "preload_turn_mean_field"):
        assert api.attrs[key] == cli.attrs[key]
    pull_api, pull_cli = api.pull_off(), cli.pull_off()
    assert pull_api.preload == 1e6 and np.array_equal(pull_api.h_turn, pull_cli.h_turn)
    assert np.array_equal(pull_api.force, pull_cli.force)
    # in memory (no file) the run keeps its preload too, and pulls off the same
    memory = mcsim.simulate(SMOOTH, SILICON, np.linspace(3, -1, 9), "3 um^2", preload="1 MPa",
                            **options)  # fmt: skip
    assert memory.path is None and memory.pull_off().preload == 1e6
    assert np.array_equal(memory.pull_off().h_turn, pull_cli.h_turn)


@pytest.mark.parametrize(
    ("kwargs", "says"),
    [({"law": "jkr"}, r"needs cycle=True \(--cycle\)"),
     ({"law": "seed", "cycle": True}, r"law = 'seed' has no signed load .*allowed: jkr, dmt, maugis-dugdale, elastic-plastic"),
     ({"law": "jkr", "cycle": True, "preload": "-1 MPa"}, r"^preload = -1000000.0 Pa is out of range"),
     ({"law": "jkr", "cycle": True, "preload": "1e30 Pa"}, r"^preload: pressure = 1e\+30 Pa is out of range \(allowed: up to "),
     ({"law": "jkr", "cycle": True, "h": [3.0, 2.5]}, r"below the lowest h = 2.5; extend h \(--h\) down")],
)  # fmt: skip
def test_a_preload_the_run_cannot_honour_is_refused_before_the_run(tmp_path, kwargs, says):
    kwargs = {"h": [3.0, 0.0], "preload": "1 MPa"} | kwargs
    with pytest.raises(ParameterError, match=says):
        mcsim.simulate(SMOOTH, SILICON, area="3 um^2", seed=1, out=tmp_path / "x.h5", **kwargs)
    assert list(tmp_path.iterdir()) == []


def test_simulate_law_auto_runs_the_law_set_the_adhesion_map_chooses(tmp_path, capsys):
    from mcsim.physics.adhesion import choose_law

    code = main(["simulate", "--surface", "smooth", "--law", "auto", "--h", "1", "--area",
                 "1um^2", "--seed", "1", "--out", str(tmp_path / "a.h5")])  # fmt: skip
    chosen, _ = choose_law(SMOOTH, SILICON)
    err = capsys.readouterr().err
    assert code == 0 and read_run(tmp_path / "a.h5").spec.law == chosen == "maugis-dugdale"
    assert err.startswith(f"mcsim: law auto: {chosen} (") and "1 realization x 1 separation," in err


def test_simulate_and_sweep_take_preset_names_as_the_command_line_does():
    by_name = mcsim.simulate("smooth", "silicon", [1.0, 0.0], "1 um^2", realizations=2, seed=3)
    by_obj = mcsim.simulate(SMOOTH, SILICON, [1.0, 0.0], "1 um^2", realizations=2, seed=3)
    assert by_name.spec == by_obj.spec and np.array_equal(by_name.sums, by_obj.sums)
    swept = mcsim.sweep("smooth", "silicon", {"gamma": [0.5, 1.0]}, h=[1.0, 0.0])
    same = mcsim.sweep(SMOOTH, SILICON, {"gamma": [0.5, 1.0]}, h=[1.0, 0.0])
    assert swept.attrs["definition"] == same.attrs["definition"]
    assert np.array_equal(swept.data["F"], same.data["F"])


@pytest.mark.parametrize(
    ("inputs", "says"),
    [(("glass", SILICON), r"^surface must be a Surface or a preset name \(rough, .*got 'glass'"),
     ((SMOOTH, 5), r"^material must be a Material or a preset name \(.*got 5")],
)  # fmt: skip
def test_a_surface_or_material_that_is_neither_nor_a_preset_is_refused_naming_it(inputs, says):
    with pytest.raises(ParameterError, match=says):
        mcsim.simulate(*inputs, [1.0], "1 um^2", seed=1)
    with pytest.raises(ParameterError, match=says):
        mcsim.sweep(*inputs, {"gamma": [0.5]})


@pytest.mark.parametrize(
    ("options", "says"),
    [({"checkpoint_every": "5"}, r"^checkpoint_every must be a number of seconds, got '5'"),
     ({"checkpoint_every": -1}, r"^checkpoint_every = -1.0 s is out of range \(allowed: >= 0 s\)"),
     ({"workers": 10**30}, r"^workers = 10{30} is out of range \(allowed: None or an integer from 1 to 1024\)"),
     ({"workers": 0}, r"^workers = 0 is out of range"),
     ({"workers": 2.0}, r"^workers = 2.0 is out of range"),
     ({"workers": True}, r"^workers = True is out of range")],
)  # fmt: skip
def test_run_options_the_command_line_refuses_are_refused_before_any_file_is_claimed(
    tmp_path, options, says
):
    with pytest.raises(ParameterError, match=says):
        mcsim.simulate(SMOOTH, SILICON, [1.0], "1 um^2", seed=1, out=tmp_path / "r.h5", **options)
    with pytest.raises(ParameterError, match=says):
        mcsim.sweep(SMOOTH, SILICON, {"gamma": [0.5]}, out=tmp_path / "s.h5", **options)
    assert list(tmp_path.iterdir()) == []
