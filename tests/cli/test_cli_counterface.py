"""A rough counter-surface on the command line (--counter-surface, --correlation, the
[counter_surface] table): the round trip, what run and sweep files record, two maps facing
each other (ingest, contact), bad input, and nothing changed without one."""

import io
import json

import h5py
import numpy as np
import pytest
from conftest import run_cli
from tolerances import ROUNDING_FORMULA

from mcsim.model.counterface import combine
from mcsim.model.presets import MATERIALS, SURFACES
from mcsim.physics.analytic import gw_curves
from mcsim.store.runfile import read_run
from mcsim.topography.synthesis import synthesize

SMOOTH, ROUGH = SURFACES["smooth"], SURFACES["rough"]
FILE_SURFACE = '[surface]\nname = "smooth"\nsigma = "1.4 nm"\nR = "1.7 um"\neta = "17 um^-2"\n'

#: Root attributes of a run file of `simulate --surface smooth --h ... --area ... --seed`, as
#: mcsim wrote them before counter-surfaces: a run without one has exactly these.
PLAIN_RUN_ATTRIBUTES = {
    "area", "area_unit", "block_size", "branches", "checksum", "command", "complete", "count",
    "created", "cycle", "device", "law", "law_outputs", "mcsim_version", "quantities",
    "realizations", "schema_version", "seed_entropy",
}  # fmt: skip


def _csv(text: str) -> np.ndarray:
    return np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)


def test_analytic_with_a_counter_surface_is_the_combined_surface(capsys):
    code, out, err = run_cli(capsys, "analytic", "--surface", "smooth", "--counter-surface",
                             "rough", "--correlation", "0.3", "--h=2,1,0", "--format", "csv")  # fmt: skip
    assert code == 0
    assert "counter-surface rough" in err and "correlation 0.3" in err
    want = gw_curves(combine(SMOOTH, ROUGH, 0.3), MATERIALS["silicon"], [2.0, 1.0, 0.0])
    got = _csv(out)
    for i, q in enumerate(("contact_fraction", "P", "F", "T", "mu"), start=1):
        np.testing.assert_array_equal(got[:, i], getattr(want, q), err_msg=q)


def test_a_flat_counter_surface_is_no_counter_surface(capsys):
    outs = [
        run_cli(capsys, "analytic", "--surface", "smooth", "--h=2,1,0", "--format", "csv", *extra)
        for extra in ((), ("--counter-surface", "flat"), ("--counter-surface", "flat",
                                                          "--correlation", "0"))
    ]  # fmt: skip
    assert outs[0] == outs[1] == outs[2]
    assert "counter-surface" not in outs[0][2]


@pytest.mark.parametrize(
    "table",
    [
        '[counter_surface]\nsurface = "rough"\ncorrelation = 0.3\n',
        '[counter_surface]\nname = "rough"\nsigma = "15.8 nm"\nR = "0.116 um"\n'
        'eta = "14.7 um^-2"\ncorrelation = 0.3\n',
    ],
)
def test_the_counter_surface_table_of_a_surface_file(capsys, tmp_path, table):
    f = tmp_path / "pair.toml"
    f.write_text(FILE_SURFACE + table)
    _, by_file, _ = run_cli(capsys, "analytic", "--surface", f, "--h=2,1,0", "--format", "csv")
    _, by_options, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--counter-surface",
                               "rough", "--correlation", "0.3", "--h=2,1,0", "--format", "csv")  # fmt: skip
    # decimal text times units against the presets: ROUNDING_FORMULA
    np.testing.assert_allclose(_csv(by_file), _csv(by_options), rtol=ROUNDING_FORMULA)


def test_options_override_the_file_and_a_counter_file_names_a_preset(capsys, tmp_path):
    f = tmp_path / "pair.toml"
    f.write_text(FILE_SURFACE + '[counter_surface]\nsurface = "rough"\ncorrelation = 0.3\n')
    counter = tmp_path / "counter.toml"
    counter.write_text(
        '[surface]\nname = "c"\nsigma = "6.8 nm"\nR = "0.45 um"\neta = "11.1 um^-2"\n'
    )
    args = ("analytic", "--surface", f, "--h=1,0", "--format", "csv")
    _, rho, _ = run_cli(capsys, *args, "--correlation", "-0.5")
    _, ref, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--counter-surface", "rough",
                        "--correlation", "-0.5", "--h=1,0", "--format", "csv")  # fmt: skip
    np.testing.assert_allclose(_csv(rho), _csv(ref), rtol=ROUNDING_FORMULA)
    # another counter-surface drops the file's correlation with its own (0 unless given)
    _, other, err = run_cli(capsys, *args, "--counter-surface", counter)
    _, ref, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--counter-surface",
                        "intermediate", "--h=1,0", "--format", "csv")  # fmt: skip
    np.testing.assert_allclose(_csv(other), _csv(ref), rtol=ROUNDING_FORMULA)
    assert "correlation 0:" in err
    _, flat, _ = run_cli(capsys, *args, "--counter-surface", "flat")
    _, ref, _ = run_cli(capsys, "analytic", "--surface", "smooth", "--h=1,0", "--format", "csv")
    np.testing.assert_allclose(_csv(flat), _csv(ref), rtol=ROUNDING_FORMULA)


def test_the_run_file_records_the_counter_surface_and_resumes_only_the_same(capsys, tmp_path):
    out = tmp_path / "pair.h5"
    args = ("simulate", "--surface", "smooth", "--counter-surface", "rough", "--correlation",
            "0.3", "--h=2,1,0", "--area", "20um^2", "--seed", "3", "--out", out)  # fmt: skip
    code, _, _ = run_cli(capsys, *args)
    assert code == 0
    run = read_run(out)
    combined = combine(SMOOTH, ROUGH, 0.3)
    for name in ("sigma", "R", "eta", "name"):
        assert getattr(run.spec.surface, name) == getattr(combined, name)
    with h5py.File(out) as f:
        attrs = dict(f.attrs)
    assert attrs["correlation"] == 0.3
    counter, given = json.loads(attrs["counter_surface"]), json.loads(attrs["surface_as_given"])
    assert {k: counter[k] for k in ("sigma", "R", "eta", "name")} == {
        "sigma": ROUGH.sigma, "R": ROUGH.R, "eta": ROUGH.eta, "name": "rough"}  # fmt: skip
    assert given["name"] == "smooth" and given["sigma"] == SMOOTH.sigma
    assert counter["units"] == {"sigma": "m", "R": "m", "eta": "m^-2"}
    # the record reproduces the run's surface
    again = combine(SMOOTH, SURFACES[counter["name"]], attrs["correlation"])
    assert (again.sigma, again.R, again.eta) == (run.spec.surface.sigma, run.spec.surface.R,
                                                 run.spec.surface.eta)  # fmt: skip
    code, shown, _ = run_cli(capsys, "show", out)
    assert "counter       the surface run is the gap's: smooth (sigma = 1.4 nm) facing rough " \
        "(sigma = 15.8 nm), correlation 0.3" in shown  # fmt: skip
    before = out.read_bytes()
    code, _, err = run_cli(capsys, *args, "--resume")
    assert code == 0 and "already holds this finished run" in err and out.read_bytes() == before
    code, _, err = run_cli(capsys, *args[:-2], "--out", out, "--resume", "--correlation", "0.4")
    assert code == 2 and "different" in err and out.read_bytes() == before


def test_the_python_api_records_the_counter_surface(tmp_path):
    from mcsim import simulate

    run = simulate("smooth", "silicon", [1.0, 0.0], "20um^2", seed=3, counter_surface="rough",
                   correlation=0.3, out=tmp_path / "api.h5")  # fmt: skip
    assert run.attrs["correlation"] == 0.3
    assert json.loads(run.attrs["counter_surface"])["name"] == "rough"
    assert "counter_surface='rough', correlation=0.3" in run.attrs["command"]
    assert run.spec.surface.sigma == combine(SMOOTH, ROUGH, 0.3).sigma


def test_without_a_counter_surface_the_run_file_is_as_before(capsys, tmp_path):
    """Bit-identical: every dataset and attribute of a run with a flat counter-surface (or
    none, the default) equal, the root attributes those of mcsim before counter-surfaces."""
    files = []
    for i, extra in enumerate(((), ("--counter-surface", "flat"))):
        out = tmp_path / f"r{i}.h5"
        code, _, _ = run_cli(capsys, "simulate", "--surface", "smooth", "--h=2,1,0", "--area",
                             "20um^2", "--seed", "3", "--out", out, *extra)  # fmt: skip
        assert code == 0
        files.append(out)
    with h5py.File(files[0]) as a, h5py.File(files[1]) as b:
        assert set(a.attrs) == PLAIN_RUN_ATTRIBUTES
        assert set(a.attrs) == set(b.attrs)
        for k in set(a.attrs) - {"created", "command", "checksum"}:
            np.testing.assert_array_equal(a.attrs[k], b.attrs[k], err_msg=k)
        names = []
        a.visit(names.append)
        for name in names:
            assert dict(a[name].attrs).keys() == dict(b[name].attrs).keys(), name
            if isinstance(a[name], h5py.Dataset):
                np.testing.assert_array_equal(a[name][()], b[name][()], err_msg=name)
        assert dict(a["input/surface"].attrs) == dict(b["input/surface"].attrs)


def test_a_sweep_records_the_counter_surface_and_refuses_to_vary_its_sigma(capsys, tmp_path):
    out = tmp_path / "s.h5"
    code, _, _ = run_cli(capsys, "sweep", "--surface", "smooth", "--counter-surface", "rough",
                         "--correlation", "0.2", "--vary", "gamma=0.1,0.5", "--h=1,0", "--out", out)  # fmt: skip
    assert code == 0
    with h5py.File(out) as f:
        assert f.attrs["correlation"] == 0.2
        assert json.loads(f.attrs["counter_surface"])["name"] == "rough"
        assert json.loads(f.attrs["surface"])["sigma"] == combine(SMOOTH, ROUGH, 0.2).sigma
    bad = tmp_path / "t.h5"
    code, _, err = run_cli(capsys, "sweep", "--surface", "smooth", "--counter-surface", "rough",
                           "--vary", "sigma=1nm,2nm", "--h=1,0", "--out", bad)  # fmt: skip
    assert code == 2 and "vary sigma: with a counter-surface" in err and not bad.exists()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--counter-surface", "rough", "--correlation", "1.5"],
         r"--correlation = 1.5 is out of range \(allowed: \[-1, 1\]\)"),
        (["--counter-surface", "rough", "--correlation", "nan"],
         r"--correlation = nan is out of range \(allowed: \[-1, 1\]\)"),
        (["--counter-surface", "rough", "--correlation", "-2"], r"--correlation = -2.0 is out of range"),
        (["--counter-surface", "rough", "--correlation", "high"],
         r"--correlation = 'high' is not a number \(allowed: a number in \[-1, 1\]"),
        (["--correlation", "0.5"], r"--correlation = 0.5 needs a rough counter-surface"),
        (["--counter-surface", "rouhg"],
         r"--counter-surface: unknown surface 'rouhg' \(did you mean 'rough'\?\)"),
        (["--counter-surface", "smooth", "--correlation", "1"], "the combined surface is flat"),
        (["--counter-surface", "missing.toml"], r"--counter-surface: missing.toml: no such file"),
    ],
)  # fmt: skip
def test_bad_counter_surface_input_is_one_line_and_writes_nothing(capsys, tmp_path, argv, message):
    out = tmp_path / "x.h5"
    for command in (
        ["analytic", "--h=1,0"],
        ["simulate", "--h=1,0", "--area", "1e-10", "--out", out],
    ):
        code, stdout, err = run_cli(capsys, *command, "--surface", "smooth", *argv)
        assert code == 2 and stdout == ""
        assert err.count("\n") == 1 and err.startswith("mcsim: error: ")
        assert __import__("re").search(message, err), err
        assert not out.exists() and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[counter_surface\nsurface = 1", r"bad.toml: not a valid TOML file"),
        ('[surface]\nsigma = "1 nm"\nR = "2 um"\neta = "10 um^-2"\ncolor = 3\n',
         r"bad.toml \[surface\]: unknown key\(s\) color"),
    ],
)  # fmt: skip
def test_a_counter_surface_file_that_does_not_parse(capsys, tmp_path, text, message):
    bad = tmp_path / "bad.toml"
    bad.write_text(text)
    code, _, err = run_cli(capsys, "analytic", "--surface", "smooth", "--counter-surface", bad,
                           "--h=1,0")  # fmt: skip
    assert code == 2 and err.startswith("mcsim: error: --counter-surface: ")
    assert err.count("\n") == 1 and __import__("re").search(message, err), err


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ('surface = "rough"\ncorrelation = 2', r"\[counter_surface\]: correlation = 2.0 is out of "
                                                r"range \(allowed: \[-1, 1\]\)"),
        ('surface = "rough"\ncorrelation = "nan"', r"\[counter_surface\]: correlation: 'nan' is not finite"),
        ('surface = "nope"', r"\[counter_surface\]: surface: unknown surface 'nope'"),
        ('surface = "rough"\nsigma = "1 nm"', "give either surface = "),
        ('sigma = "1 nm"\nR = "2 um"', r"\[counter_surface\]: missing key 'eta'"),
        ('sigma = 1\nR = "2 um"\neta = "3 um^-2"', r"sigma = 1 has no unit"),
    ],
)  # fmt: skip
def test_bad_counter_surface_tables(capsys, tmp_path, table, message):
    f = tmp_path / "pair.toml"
    f.write_text(FILE_SURFACE + "[counter_surface]\n" + table + "\n")
    code, _, err = run_cli(capsys, "analytic", "--surface", f, "--h=1,0")
    assert code == 2 and err.count("\n") == 1, err
    assert __import__("re").search(message, err), err


# --- two measured maps ----------------------------------------------------------------


@pytest.fixture
def maps(tmp_path):
    """Two independent periodic maps (nm, 10 nm pixels) and a third of another size."""

    def psd(q):
        return 1e-34 * np.minimum(1.0, (np.asarray(q) / 3e7) ** -3.6)

    z = synthesize((64, 64), 10e-9, psd, rng=np.random.SeedSequence(11), n=2) * 1e9
    paths = [tmp_path / name for name in ("a.npy", "b.npy", "small.npy")]
    for path, heights in zip(paths, (z[0], z[1], z[0][:32])):
        np.save(path, heights)
    return paths


def test_ingest_two_maps_writes_the_gap_surface_and_the_correlation(capsys, tmp_path, maps):
    from mcsim.store.config import load_surface
    from mcsim.studies.maps.ingest import ingest_file
    from mcsim.topography.summits import facing_gap

    a, b, _ = maps
    code, out, err = run_cli(capsys, "ingest", a, "--unit", "nm", "--pixel-size", "10nm",
                             "--counter-surface", b, "--out", tmp_path / "gap.toml")  # fmt: skip
    assert code == 0, err
    line = next(x for x in out.splitlines() if x.startswith("counter "))
    assert "b.npy turned over to face the map" in line and "rho = " in line
    text = (tmp_path / "gap.toml").read_text()
    assert "# counter-surface: " in text and 'name = "a-on-b"' in text
    surface = load_surface(tmp_path / "gap.toml")
    # the same surface as the gap's map ingested on its own
    np.save(tmp_path / "gap.npy", facing_gap(np.load(a), np.load(b)))
    alone = ingest_file(tmp_path / "gap.npy", unit="nm", pixel_size=10e-9).surface
    assert surface.rq == pytest.approx(alone.rq, rel=1e-11)
    assert surface.eta == pytest.approx(alone.eta, rel=1e-11)
    result = ingest_file(a, unit="nm", pixel_size=10e-9, counter=b)
    f = result.facing
    assert -0.2 < f.correlation < 0.2  # independent maps
    assert result.surface.rq == pytest.approx(
        (f.rms**2 + f.counter_rms**2 - 2 * f.correlation * f.rms * f.counter_rms) ** 0.5, rel=1e-12
    )


@pytest.mark.parametrize(
    ("counter", "extra", "message"),
    [
        (
            "small.npy",
            (),
            r"counter-surface .*small.npy: 64 x 32 pixels .* must have the same size",
        ),
        ("rough", (), "a Gaussian GW surface does not combine with a measured map"),
        ("missing.npy", (), r"counter-surface .*missing.npy: .*no such file"),
        ("b.npy", ("--synthesize", "2"), "--synthesize: .* not with --counter-surface"),
        ("b.npy", ("--calibrate",), "--calibrate solves the map file itself"),
    ],
)
def test_ingest_refuses_what_does_not_face_the_map(capsys, tmp_path, maps, counter, extra, message):
    a = maps[0]
    counter = str(tmp_path / counter) if counter.endswith(".npy") else counter
    code, _, err = run_cli(capsys, "ingest", a, "--unit", "nm", "--pixel-size", "10nm",
                           "--counter-surface", counter, "--out", tmp_path / "gap.toml", *extra)  # fmt: skip
    assert code == 2 and err.count("\n") == 1 and __import__("re").search(message, err), err
    assert not (tmp_path / "gap.toml").exists()


def test_contact_solves_the_gap_of_two_maps(capsys, tmp_path, maps):
    from mcsim.topography.summits import facing_gap

    a, b, _ = maps
    np.save(tmp_path / "gap.npy", facing_gap(np.load(a), np.load(b)))
    common = ("--unit", "nm", "--pixel-size", "10nm", "--pressure", "50MPa", "--format", "json",
              "--quiet")  # fmt: skip
    code, pair, err = run_cli(capsys, "contact", a, "--counter-surface", b, *common)
    assert code == 0, err
    code, alone, _ = run_cli(capsys, "contact", tmp_path / "gap.npy", *common)
    pair, alone = json.loads(pair), json.loads(alone)
    assert pair["counter_surface"].endswith("b.npy") and -1 <= pair["correlation"] <= 1
    assert "counter_surface" not in alone
    for key in ("area_fraction", "mean_gap", "gw_area_fraction"):
        assert pair["rows"][0][key] == pytest.approx(alone["rows"][0][key], rel=1e-9), key
