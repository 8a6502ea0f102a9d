"""The shipped sample inputs (examples/) are what examples/make_examples.py writes, and read back.

The generator is rerun into a temporary folder and every file compared with the shipped
one: text files exactly, maps through mcsim's readers. Binary maps are compared to
1e-12 of the map's rms, absolutely (the float32 .ibw also to one float32 step), not bit
for bit: the Fourier filter's last bits differ on another CPU (another SIMD width), which
is not a change of the surface; heights cross zero, so the bound is not relative.
"""

from __future__ import annotations

import importlib.util
import struct
from pathlib import Path

import numpy as np
import pytest

from mcsim.store.config import load_material, load_surface
from mcsim.topography.readers import read_height_map, read_histogram

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
_spec = importlib.util.spec_from_file_location("make_examples", EXAMPLES / "make_examples.py")
make_examples = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(make_examples)

#: How each map is read: the arguments its format needs beyond the file.
MAPS = {
    "scan.txt": {"unit": "nm", "pixel_size": make_examples.PIXEL_SIZE},
    "scan.npy": {"unit": "m", "pixel_size": make_examples.PIXEL_SIZE},
    "scan.gwy": {},
    "scan.nid": {},
    "scan.ibw": {},
}


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory) -> Path:
    pytest.importorskip("gwyfile", reason="gwyfile (test extra) writes scan.gwy")
    folder = tmp_path_factory.mktemp("examples")
    make_examples.main(folder)
    return folder


def test_generator_writes_exactly_the_shipped_files(regenerated):
    # files only: importing the generator above leaves examples/__pycache__ where Python
    # writes bytecode (no PYTHONDONTWRITEBYTECODE), as on a user's machine
    shipped = {p.name for p in EXAMPLES.iterdir() if p.is_file() and p.name != "make_examples.py"}
    assert {p.name for p in regenerated.iterdir()} == shipped


@pytest.mark.parametrize("name", ["hist-surface.toml", "gold.toml"])
def test_regenerated_text_file_equals_the_shipped_one(regenerated, name):
    assert (regenerated / name).read_text() == (EXAMPLES / name).read_text()


def test_regenerated_histogram_equals_the_shipped_one(regenerated):
    new, old = read_histogram(regenerated / "hist.csv"), read_histogram(EXAMPLES / "hist.csv")
    np.testing.assert_array_equal(new.edges, old.edges)
    # a height within an ulp of a bin edge could change bins on another CPU: one count
    assert np.abs(new.weights - old.weights).sum() <= 2


def assert_same_map(new: np.ndarray, old: np.ndarray, name: str) -> None:
    """The heights ``new`` (m) are the map ``old`` written by the generator on any CPU."""
    # the text matrix rounds to 1e-4 nm, the .nid to 2^-32 of its 1 µm range: the last
    # digit may differ where the unrounded value lies within an ulp of a rounding boundary
    step = {"scan.txt": 1e-13, "scan.nid": 1e-6 / 2**32}.get(name, 0.0)
    # the .ibw's float32: one step of a float32 is at most 2^-23 of the value
    rtol = {"scan.ibw": 2.0**-23}.get(name, 0.0)
    # the doubles (.npy, .gwy, and the .ibw before its rounding) differ on another CPU by
    # the Fourier filter's rounding, a few ulps of the map's rms wherever the height is
    # (heights cross zero: an absolute bound; measured 1.3e-25 m on 6e-14 m heights, an
    # AVX-512 CPU against AVX2): 1e-12 of the rms leaves that three orders of margin and
    # still fails any change of the surface larger than a millionth of a nanometre
    rounding = 1e-12 * float(np.std(old))
    np.testing.assert_allclose(new, old, rtol=rtol, atol=step * 1.01 + rounding)


@pytest.mark.parametrize("name", MAPS)
def test_regenerated_map_equals_the_shipped_one(regenerated, name):
    new = read_height_map(regenerated / name, **MAPS[name])
    old = read_height_map(EXAMPLES / name, **MAPS[name])
    assert_same_map(new.heights, old.heights, name)
    assert (new.dx, new.dy, new.shape) == (old.dx, old.dy, old.shape)


@pytest.mark.parametrize("name", ["scan.npy", "scan.gwy"])
def test_the_map_comparison_takes_another_cpus_rounding_and_refuses_a_change(name):
    old = read_height_map(EXAMPLES / name, **MAPS[name]).heights
    rng = np.random.default_rng(29)
    # another CPU's rounding: ±1.3e-25 m on every height, those near zero included (the
    # rtol = 1e-12 this test replaced refused it there)
    assert_same_map(old + rng.choice([-1.3e-25, 1.3e-25], old.shape), old, name)
    with pytest.raises(AssertionError):  # a change of a millionth of the rms on one pixel
        changed = old.copy()
        changed[7, 11] += 1e-6 * np.std(old)
        assert_same_map(changed, old, name)


@pytest.mark.parametrize("name", MAPS)
def test_every_format_holds_the_same_surface(name):
    m = read_height_map(EXAMPLES / name, **MAPS[name])
    reference = np.load(EXAMPLES / "scan.npy")
    # stored precision: the text matrix's 4 decimals in nm (half a step 5e-14 m), the
    # .nid's 32-bit integers (half a step 1e-6/2^33 m), the .ibw's float32 (rounding to
    # nearest: at most 2^-24 of the value); .npy and .gwy store the doubles
    tolerance = {"scan.txt": 5e-14, "scan.nid": 1e-6 / 2**33}.get(name, 0.0)
    rtol = {"scan.ibw": 2.0**-24}.get(name, 0.0)
    np.testing.assert_allclose(m.heights, reference, rtol=rtol, atol=tolerance * 1.01)
    assert m.dx == m.dy == make_examples.PIXEL_SIZE
    assert m.shape == (make_examples.PIXELS, make_examples.PIXELS)


def test_ibw_header_checksum_is_zero():
    # PTN003: the 16-bit sum of BinHeader5 (64 bytes) and WaveHeader5 (320 bytes) is 0
    header = (EXAMPLES / "scan.ibw").read_bytes()[:384]
    assert sum(struct.unpack("<192h", header)) % 2**16 == 0


def test_ibw_reads_back_through_igor2_with_its_scaling_and_units():
    binarywave = pytest.importorskip("igor2.binarywave")
    wave = binarywave.load(str(EXAMPLES / "scan.ibw"))["wave"]
    header = wave["wave_header"]
    # Igor's w[x, y] is the transpose of the rows-along-y map
    expected = np.load(EXAMPLES / "scan.npy").T.astype(np.float32)
    np.testing.assert_array_equal(wave["wData"], expected)
    assert list(header["sfA"][:2]) == [make_examples.PIXEL_SIZE] * 2
    assert header["dataUnits"][0] == b"m" and list(header["dimUnits"][:2, 0]) == [b"m", b"m"]


def test_scan_has_the_generator_statistics():
    z = np.load(EXAMPLES / "scan.npy")
    # the generator shifts to mean 0 and scales to the rms SIGMA: exact up to rounding, a
    # few ulps of the largest height (about 3 SIGMA) in the sum over the pixels
    assert abs(z.mean()) < 1e-13 * make_examples.SIGMA
    assert z.std() == pytest.approx(make_examples.SIGMA, rel=1e-12)


def test_backward_scan_differs_by_the_stated_noise():
    forward = read_height_map(EXAMPLES / "scan.nid")
    backward = read_height_map(EXAMPLES / "scan.nid", channel="Scan backward/Z-Axis")
    noise = (backward.heights - forward.heights).ravel()
    # the sample std of n normal values has relative standard error 1/sqrt(2(n - 1)); 5 of them
    assert noise.std() == pytest.approx(make_examples.NOISE, rel=5 / np.sqrt(2 * (noise.size - 1)))


def test_histogram_counts_every_pixel():
    hist = read_histogram(EXAMPLES / "hist.csv")
    assert hist.weights.sum() == make_examples.PIXELS**2
    assert np.allclose(np.diff(hist.edges), make_examples.BIN)


def test_toml_files_load():
    assert load_material(str(EXAMPLES / "gold.toml")).E1 == 79e9
    surface = load_surface(str(EXAMPLES / "hist-surface.toml"))
    # "1.7 um" and "17 um^-2" in SI: one rounding each
    assert surface.R == pytest.approx(1.7e-6, rel=1e-15) and surface.eta == pytest.approx(
        17e12, rel=1e-15
    )
