"""A map is read once (issue 44, point 2): ``ingest --calibrate``, ``contact`` and the adhesive
cycle read their file once and hand the one :class:`HeightMap` (read, levelled, its periodicity
decided) to summit statistics, the exact contact and the calibration. (One radius for every
summit: a radius by height changes the calibration's cost, not its reads.)"""

import io
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np
import pytest

import mcsim.topography.readers.npy as npy_reader
from mcsim.cli.main import main
from mcsim.model.errors import ParameterError
from mcsim.model.presets import MATERIALS
from mcsim.studies.maps.calibration import calibrate
from mcsim.studies.maps.contact import contact_map
from mcsim.studies.maps.ingest import ingest_file
from mcsim.topography.maps import read_map
from mcsim.topography.readers import read_height_map

SCAN = Path(__file__).resolve().parents[2] / "examples" / "scan.npy"
SILICON = MATERIALS["silicon"]


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """examples/scan.npy downsampled 4x: periodic, 25 x 25 pixels of 40 nm (fast solves)."""
    path = tmp_path_factory.mktemp("once") / "small.npy"
    np.save(path, np.load(SCAN)[::4, ::4])
    return path


@pytest.fixture
def reads(monkeypatch):
    """The files the .npy reader opens, in order."""
    opened = []
    read = npy_reader.read

    def counting(path, *args, **kwargs):
        opened.append(Path(path))
        return read(path, *args, **kwargs)

    monkeypatch.setattr(npy_reader, "read", counting)
    return opened


def test_ingest_calibrate_on_the_command_line_reads_the_map_once(small, reads, tmp_path):
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main(["ingest", str(small), "--unit", "m", "--pixel-size", "4e-8", "--calibrate",
                     "--no-radius-by-height", "--out", str(tmp_path / "s.toml")])  # fmt: skip
    assert code == 0, err.getvalue()
    assert reads == [small]


def test_ingest_calibrate_in_python_reads_the_map_once(small, reads):
    result = ingest_file(
        small, unit="m", pixel_size=4e-8, calibrate=SILICON, radius_by_height=False
    )
    assert result.calibration is not None
    assert reads == [small]


def test_contact_reads_the_map_once_and_a_map_read_already_not_again(small, reads):
    contact_map(small, SILICON, [1e8], unit="m", pixel_size=4e-8)
    assert reads == [small]
    hmap = read_map(small, unit="m", pixel_size=4e-8)
    calibrate(hmap, SILICON)
    contact_map(hmap, SILICON, [1e8])
    assert reads == [small, small]


def test_a_map_read_already_gives_the_numbers_its_file_gives(small):
    by_file = contact_map(small, SILICON, [1e8, 1e9], unit="m", pixel_size=4e-8)
    by_map = contact_map(read_map(small, unit="m", pixel_size=4e-8), SILICON, [1e8, 1e9])
    np.testing.assert_array_equal(by_map.area_fraction, by_file.area_fraction)
    np.testing.assert_array_equal(by_map.gw_area_fraction, by_file.gw_area_fraction)
    assert (by_map.level, by_map.periodic) == (by_file.level, by_file.periodic) == ("none", True)


def test_read_options_with_a_map_read_already_are_refused(small):
    hmap = read_map(small, unit="m", pixel_size=4e-8)
    with pytest.raises(ParameterError, match=r"^level: .* is read already"):
        contact_map(hmap, SILICON, [1e8], level="plane")
    raw = read_height_map(small, unit="m", pixel_size=4e-8)
    with pytest.raises(ParameterError, match="a map as a reader returns it"):
        contact_map(raw, SILICON, [1e8])


def test_the_ingested_map_is_the_one_analysed_and_studies_on_it_read_nothing(small, reads):
    result = ingest_file(small, unit="m", pixel_size=4e-8)
    hmap = result.height_map
    assert (hmap.level, hmap.periodic, hmap.dx) == (result.level, result.periodic, result.dx)
    on_map = contact_map(hmap, SILICON, [1e8]).surface  # GW's surface of the same map
    assert (on_map.sigma, on_map.R, on_map.eta) == (result.surface.sigma, result.surface.R,
                                                    result.surface.eta)  # fmt: skip
    assert reads == [small]
