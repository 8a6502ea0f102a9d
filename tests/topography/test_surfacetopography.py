"""The optional SurfaceTopography reader: axis order, units and sizes against other readers."""

import tarfile
from pathlib import Path

import numpy as np
import pytest
from tolerances import ROUNDING_FEW, ROUNDING_SUM

from mcsim.topography.readers import ReaderError, gwy, ibw, read_height_map, surfacetopography

pytest.importorskip(
    "SurfaceTopography", reason="SurfaceTopography (extra 'topography') not installed"
)

#: AFMReader 0.0.7's own test values (tests/test_spm.py, tests/test_jpk.py): image sum
#: in nm, pixel size in nm and shape of sample_0.spm channel "Height" and of
#: sample_0.jpk channel "height_trace" (JPK's "Height").
AFMREADER_SPM = (30695369.188316286, 0.4940029296875, (1024, 1024))
AFMREADER_JPK = (219242202.8256843, 1.2770176335964876, (256, 256))


@pytest.fixture(scope="session")
def other_formats(afm_resources) -> Path:
    """AFMReader's real .spm and .jpk files, taken from the sdist that conftest.py fetched."""
    names = ("sample_0.spm", "sample_0.jpk")
    if not all((afm_resources / name).is_file() for name in names):
        top = afm_resources.parents[1]  # afmreader-0.0.7/
        with tarfile.open(top.parent / f"{top.name}.tar.gz") as tar:
            wanted = {f"{top.name}/tests/resources/{name}" for name in names}
            members = [m for m in tar.getmembers() if m.name in wanted]
            tar.extractall(top.parent, members=members, filter="data")
    return afm_resources


@pytest.mark.parametrize("channel", ["Height", "ZSensor"])
def test_gwy_matches_mcsim_gwy_reader(afm_resources, channel):
    path = afm_resources / "sample_0.gwy"
    ours, theirs = gwy.read(path, channel=channel), surfacetopography.read(path, channel=channel)
    # Gwyddion stores float64 and both readers keep the stored row order: bit-identical
    np.testing.assert_array_equal(theirs.heights, ours.heights, err_msg=channel)
    assert (theirs.dx, theirs.dy) == pytest.approx((ours.dx, ours.dy), rel=1e-15)
    assert theirs.size == pytest.approx(ours.size, rel=1e-15)


def test_default_channel_is_the_height_channel_like_gwy(afm_resources):
    assert surfacetopography.read(afm_resources / "sample_0.gwy").channel == "Height"


def test_ibw_is_the_up_down_mirror_of_mcsim_ibw_reader(afm_resources):
    path = afm_resources / "sample_0.ibw"
    ours, theirs = ibw.read(path), surfacetopography.read(path)
    assert theirs.channel == ours.channel == "HeightTracee"
    # SurfaceTopography orients rows like Gwyddion's display (its IBW reader flips y);
    # mcsim's ibw reader keeps Igor's storage order. Same float32 values, exactly.
    np.testing.assert_array_equal(theirs.heights, np.flipud(ours.heights))
    assert (theirs.dx, theirs.dy) == pytest.approx((ours.dx, ours.dy), rel=1e-15)
    assert theirs.size == pytest.approx(ours.size, rel=1e-15)


def test_spm_matches_afmreader_values(other_formats):
    m = read_height_map(other_formats / "sample_0.spm")  # no built-in .spm reader
    total, pixel_nm, shape = AFMREADER_SPM
    assert m.channel == "Height" and m.shape == shape
    assert m.heights.sum() * 1e9 == pytest.approx(total, rel=1e-12)
    # independent: the header's scan size 505.859 nm over 1024 pixels
    assert (m.dx, m.dy) == pytest.approx((505.859e-9 / 1024, 505.859e-9 / 1024), rel=1e-12)
    assert m.dx * 1e9 == pytest.approx(pixel_nm, rel=1e-12)


def test_jpk_matches_afmreader_values(other_formats):
    m = surfacetopography.read(other_formats / "sample_0.jpk", channel="Height")
    total, pixel_nm, shape = AFMREADER_JPK
    assert m.shape == shape
    # AFMReader's numbers, printed to repr; the sum over the map's pixels: ROUNDING_SUM
    assert m.heights.sum() * 1e9 == pytest.approx(total, rel=ROUNDING_SUM)
    assert m.dx * 1e9 == pytest.approx(pixel_nm, rel=ROUNDING_FEW) and m.dy == pytest.approx(
        m.dx, rel=ROUNDING_FEW
    )


def test_masked_pixels_become_nan_and_axes_are_x_first(tmp_path):
    # SurfaceTopography's .npy reader takes axis 0 as x (mcsim's npy reader: axis 0 is y)
    z = np.arange(20.0).reshape(4, 5)
    z[1, 2] = np.nan
    np.save(tmp_path / "m.npy", z)
    m = surfacetopography.read(tmp_path / "m.npy", unit="nm", pixel_size=(1e-9, 2e-9))
    np.testing.assert_array_equal(m.heights, z.T * 1e-9)
    assert np.isnan(m.heights[2, 1]) and np.isnan(m.heights).sum() == 1
    assert (m.dx, m.dy) == (1e-9, 2e-9)


def test_unknown_extension_goes_to_surfacetopography(other_formats, tmp_path):
    renamed = tmp_path / "scan.bruker"
    renamed.write_bytes((other_formats / "sample_0.spm").read_bytes())
    assert read_height_map(renamed).shape == AFMREADER_SPM[2]


def test_line_scan_is_refused(tmp_path):
    path = tmp_path / "line.prof"
    path.write_text("0 1\n0.5 2\n2 3\n3.5 1\n4 0\n")
    with pytest.raises(ReaderError, match=r"line\.prof: channel .* is a line scan or non-uniform"):
        surfacetopography.read(path, unit="nm")


def test_missing_pixel_size_is_refused(tmp_path):
    np.save(tmp_path / "m.npy", np.ones((4, 4)))
    with pytest.raises(ReaderError, match="missing pixel size: pass --pixel-size"):
        surfacetopography.read(tmp_path / "m.npy", unit="nm")


def test_pixel_size_stored_in_the_file_cannot_be_overridden(afm_resources):
    with pytest.raises(ReaderError, match="stores its pixel-size; do not pass --pixel-size"):
        surfacetopography.read(afm_resources / "sample_0.gwy", pixel_size=1e-9)


def test_unknown_channel_lists_the_channels(afm_resources):
    with pytest.raises(ReaderError, match=r"no channel 'Phase' \(channels: 'ZSensor'"):
        surfacetopography.read(afm_resources / "sample_0.gwy", channel="Phase")


def test_undetectable_file_is_refused_in_one_line(tmp_path):
    path = tmp_path / "m.foo"
    path.write_bytes(b"\x00\x01garbage" * 10)
    with pytest.raises(ReaderError, match=r"m\.foo: unknown file type '\.foo'") as info:
        read_height_map(path)
    assert "\n" not in str(info.value)


def test_truncated_real_file_is_refused_in_one_line(other_formats, tmp_path):
    data = (other_formats / "sample_0.spm").read_bytes()
    cut = tmp_path / "cut.spm"
    cut.write_bytes(data[: len(data) // 3])
    with pytest.raises(ReaderError, match=r"cut\.spm: ") as info:
        read_height_map(cut)
    assert "\n" not in str(info.value)


def test_missing_file_is_named(tmp_path):
    with pytest.raises(ReaderError, match=r"nope\.spm: no such file"):
        read_height_map(tmp_path / "nope.spm")


def test_without_the_package_unknown_extension_names_the_extra(monkeypatch, tmp_path):
    monkeypatch.setattr(surfacetopography, "available", lambda: False)
    with pytest.raises(ReaderError, match=r"unknown file type '\.spm'.*mcsim\[topography\]"):
        read_height_map(tmp_path / "m.spm")
