"""Pads from a map's spectrum (mcsim.studies.maps.synthpads) and ``mcsim ingest --synthesize``."""

from pathlib import Path

import h5py
import numpy as np
import pytest
from conftest import run_cli

from mcsim.model.errors import ParameterError
from mcsim.studies.maps.synthpads import read_pads, synthesize_pads
from mcsim.topography.synthesis import radial_psd

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
SCAN = EXAMPLES / "scan.npy"  # periodic, 100 x 100 pixels of 10 nm, 3 nm rms
PIXEL = 10e-9


def pads(n=4, pixels=16, seed=7):
    return synthesize_pads(SCAN, n, pixels, seed, unit="m", pixel_size=PIXEL)


def test_pads_have_the_asked_shape_the_maps_pixel_size_and_zero_mean():
    p = pads()
    assert p.heights.shape == (4, 16, 16)
    assert p.pixel_size == PIXEL
    assert p.periodic_source
    np.testing.assert_allclose(p.heights.mean(axis=(1, 2)), 0, atol=1e-12 * 3e-9)


def test_the_same_seed_gives_the_same_pads_and_pad_i_does_not_depend_on_n():
    np.testing.assert_array_equal(pads(n=2).heights, pads(n=4).heights[:2])
    assert not np.array_equal(pads(seed=8).heights, pads().heights)


def test_the_pads_mean_square_is_the_maps_spectrum_over_the_pads_modes():
    # 300 pads of 16^2: each pad's mean square scatters by ~25 % (a few long-wavelength
    # modes dominate), so their mean has SE ~1.5 %; 5 SE = 7.5 %
    p = pads(n=300)
    expected, of_map = p.mean_square
    measured = float(np.mean(p.heights**2))
    assert abs(measured / expected - 1) < 0.075, (measured, expected)
    assert expected < of_map  # the pad lacks the map's longest wavelengths
    assert of_map == pytest.approx(np.mean(np.load(SCAN) ** 2) - np.mean(np.load(SCAN)) ** 2)


def test_the_pads_carry_the_maps_radial_psd():
    source = radial_psd(np.load(SCAN), PIXEL, periodic=True)
    p = pads(n=1)
    np.testing.assert_array_equal(p.psd.C, source.C)
    np.testing.assert_array_equal(p.psd.q, source.q)


def test_written_pads_read_back_with_units_seed_source_and_psd(tmp_path):
    p = pads()
    path = p.write(tmp_path / "pads.h5", command="test")
    back = read_pads(path)
    np.testing.assert_array_equal(back.heights, p.heights)
    np.testing.assert_array_equal(back.psd.C, p.psd.C)
    assert (back.seed, back.pixel_size, back.source) == (7, PIXEL, str(SCAN))
    with h5py.File(path) as f:
        for name in ("heights", "psd_q", "psd_C", "psd_modes", "psd_index"):
            assert {"units", "long_name"} <= set(f[name].attrs), name
        assert f["heights"].attrs["units"] == "m"
        assert f.attrs["command"] == "test"


def test_an_existing_pads_file_is_refused_unless_overwrite(tmp_path):
    path = tmp_path / "pads.h5"
    path.write_text("keep")
    with pytest.raises(Exception, match="file exists"):
        pads().write(path)
    assert path.read_text() == "keep"
    pads().write(path, overwrite=True)
    assert read_pads(path).heights.shape == (4, 16, 16)


@pytest.mark.parametrize(
    "n, pixels, seed, field",
    [(0, 16, 1, "`n`"), (-3, 16, 1, "`n`"), (2.5, 16, 1, "`n`"), (2, 7, 1, "`pixels`"),
     (2, 16, -1, "`seed`")],
)  # fmt: skip
def test_bad_counts_sizes_and_seeds_are_refused_naming_the_field(n, pixels, seed, field):
    with pytest.raises(ParameterError, match=field):
        synthesize_pads(SCAN, n, pixels, seed, unit="m", pixel_size=PIXEL)


def test_a_histogram_has_no_spectrum():
    with pytest.raises(ParameterError, match=r"`path`.*histogram"):
        synthesize_pads(EXAMPLES / "hist.csv", 2, 16, 1)


def test_ingest_synthesize_writes_the_pads_beside_the_surface(capsys, tmp_path):
    out = tmp_path / "scan.toml"
    code, stdout, err = run_cli(capsys, "ingest", SCAN, "--unit", "m", "--pixel-size", "10nm",
                                "--out", out, "--synthesize", 3, "--pad-pixels", 16,
                                "--seed", 7)  # fmt: skip
    assert code == 0, err
    written = read_pads(tmp_path / "scan-pads.h5")
    np.testing.assert_array_equal(written.heights, pads(n=3).heights)
    assert "3 periodic pads of 16 x 16" in stdout
    assert "scan-pads.h5" in err


@pytest.mark.parametrize(
    "extra, option",
    [(["--synthesize", "0"], "--synthesize"), (["--synthesize", "2", "--pad-pixels", "7"],
     "--pad-pixels"), (["--pad-pixels", "16"], "--pad-pixels"), (["--seed", "1"], "--seed")],
)  # fmt: skip
def test_ingest_refuses_bad_pad_options_in_one_line_before_writing(capsys, tmp_path, extra, option):
    code, _, err = run_cli(capsys, "ingest", SCAN, "--unit", "m", "--pixel-size", "10nm",
                           "--out", tmp_path / "scan.toml", *extra)  # fmt: skip
    assert code != 0
    assert err.strip().count("\n") == 0 and option in err, err
    assert list(tmp_path.iterdir()) == []


def test_ingest_refuses_synthesize_on_a_histogram_before_writing(capsys, tmp_path):
    code, _, err = run_cli(capsys, "ingest", EXAMPLES / "hist.csv", "--R", "1um", "--eta",
                           "10um^-2", "--out", tmp_path / "h.toml", "--synthesize", "2")  # fmt: skip
    assert code != 0 and "histogram" in err, err
    assert list(tmp_path.iterdir()) == []


def test_ingest_refuses_an_existing_pads_file_before_writing(capsys, tmp_path):
    (tmp_path / "p.h5").write_text("keep")
    code, _, err = run_cli(capsys, "ingest", SCAN, "--unit", "m", "--pixel-size", "10nm",
                           "--out", tmp_path / "scan.toml", "--synthesize", "2",
                           "--pads-out", tmp_path / "p.h5")  # fmt: skip
    assert code != 0 and "file exists" in err, err
    assert sorted(x.name for x in tmp_path.iterdir()) == ["p.h5"]
