"""Write the sample inputs of the README into this folder: ``python examples/make_examples.py``.

One synthetic AFM scan, a Gaussian-correlated random surface, is written in each map
format mcsim reads without an instrument's software: a text matrix (``scan.txt``,
heights in nm, no header: the README passes ``--unit nm --pixel-size 10nm``), NumPy
(``scan.npy``, heights in m), Gwyddion (``scan.gwy``: channel ``Height``, sizes and
units stored), Nanosurf (``scan.nid``: channels ``Scan forward/Z-Axis`` and ``Scan
backward/Z-Axis``, 32-bit) and an Igor binary wave (``scan.ibw``: version 5, one 2-D
float32 wave in m, pixel size in the wave scaling; written here, as igor2 only reads).
Beside them: ``hist.csv``, the histogram of the scan's heights (centre in nm, count),
``hist-surface.toml``, a surface file that uses it, and ``gold.toml``, a material file.

The surface is white noise filtered by a Gaussian in Fourier space (a periodic field
whose height autocorrelation is Gaussian with correlation length ``CORRELATION``;
e.g. Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), Sec. 3), shifted to zero
mean and scaled to the rms height ``SIGMA``. The backward scan is the same surface with
white measurement noise of ``NOISE`` rms. Everything is drawn from one seeded
generator, so the files are the same on every run (to the last bit on one machine;
across CPUs the Fourier transform may differ in the last bits of the binary maps).

Writing ``scan.gwy`` needs ``gwyfile`` (in the ``test`` extra: ``pip install -e
'.[test]'``); the other files need only mcsim's own dependencies.
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

#: Seed of the one random generator all files come from.
SEED = 2026
#: Pixels per side.
PIXELS = 100
#: Pixel size, m (the map is 1 µm × 1 µm).
PIXEL_SIZE = 10e-9
#: Rms height of the map, m.
SIGMA = 3e-9
#: Correlation length of the heights (Gaussian autocorrelation exp(-r²/ℓ²)), m.
CORRELATION = 40e-9
#: Rms of the white noise added to the backward scan, m.
NOISE = 0.05e-9
#: Height histogram: bins of this width, m, centred on multiples of it.
BIN = 0.5e-9
#: The folder the files are written to (this script's own).
HERE = Path(__file__).resolve().parent

GOLD = """\
# Gold on gold, illustrative values for a MEMS switch contact: E and nu of bulk gold
# (handbook values), a thin-film hardness, and a work of adhesion typical of gold
# surfaces in air (clean gold in vacuum adheres far more strongly). Give your own.
[material]
name = "gold"
E = "79 GPa"         # Young's modulus of both solids
nu = 0.42            # Poisson's ratio of both solids
w = "0.3 J/m^2"  # work of adhesion
H = "1.5 GPa"        # hardness, only for the plasticity index
z0 = "0.3 nm"        # equilibrium spacing (dmt, maugis-dugdale, Tabor parameter)
"""

HIST_SURFACE = """\
# A surface whose summit heights follow the measured histogram hist.csv (the heights of
# examples/scan.*) instead of a Gaussian; sigma defaults to the histogram's own.
[surface]
name = "hist"
R = "1.7 um"          # summit radius
eta = "17 um^-2"      # summit density
heights = "hist.csv"  # path relative to this file
"""


def surface(rng: np.random.Generator) -> np.ndarray:
    """Heights, m, of a periodic Gaussian-correlated surface, PIXELS × PIXELS."""
    k = 2 * np.pi * np.fft.fftfreq(PIXELS, d=PIXEL_SIZE)  # rad/m
    k2 = k[:, None] ** 2 + k[None, :] ** 2
    # the power spectrum of exp(-r²/ℓ²) is ∝ exp(-k²ℓ²/4); the filter is its square root
    filtered = np.fft.ifft2(np.fft.fft2(rng.standard_normal((PIXELS, PIXELS)))
                            * np.exp(-k2 * CORRELATION**2 / 8)).real  # fmt: skip
    filtered -= filtered.mean()
    return filtered * (SIGMA / filtered.std())


def write_nid(path: Path, forward: np.ndarray, backward: np.ndarray) -> None:
    """A Nanosurf .nid file: INI header, ``#!``, two 32-bit Z-Axis images (mcsim.topography.readers.nid)."""
    height_range = 1e-6  # m; raw r maps to (r + 2³¹)/2³² · range + min, min = -range/2
    blocks = []
    header = [
        "[DataSet]", "Version=2", "GroupCount=2",
        "Gr0-Name=Scan forward", "Gr0-ID=0", "Gr0-Count=1",
        "Gr1-Name=Scan backward", "Gr1-ID=0", "Gr1-Count=1",
        "Gr0-Ch0=DataSet-0:0", "Gr1-Ch0=DataSet-1:0", "",
        "[DataSet-Info]", "Scan direction=Up", f"Points={PIXELS}", f"Lines={PIXELS}", "",
    ]  # fmt: skip
    for group, (frame, z) in enumerate((("Scan forward", forward), ("Scan backward", backward))):
        header += [
            f"[DataSet-{group}:0]", "Version=2", f"Points={z.shape[1]}", f"Lines={z.shape[0]}",
            f"Frame={frame}", "Dim0Name=X*", "Dim0Unit=m", f"Dim0Range={z.shape[1] * PIXEL_SIZE!r}",
            "Dim0Min=0", "Dim1Name=Y*", "Dim1Unit=m", f"Dim1Range={z.shape[0] * PIXEL_SIZE!r}",
            "Dim1Min=0", "Dim2Name=Z-Axis", "Dim2Unit=m", f"Dim2Range={height_range!r}",
            f"Dim2Min={-height_range / 2!r}", "SaveMode=Binary", "SaveBits=32",
            "SaveSign=Signed", "SaveOrder=Intel", "",
        ]  # fmt: skip
        blocks.append(np.round(z / height_range * 2.0**32).astype("<i4").tobytes())
    path.write_bytes("\r\n".join(header).encode("latin-1") + b"#!" + b"".join(blocks))


def write_ibw(path: Path, z: np.ndarray) -> None:
    """An Igor binary wave, version 5, little-endian: one 2-D float32 wave of heights in m.

    The layout is WaveMetrics' Technical Note PTN003: a 64-byte BinHeader5, a 320-byte
    WaveHeader5, then the data; fields not set here are zero (no note, formula, extended
    units or labels). Igor's ``w[x, y]`` has x fastest, so nDim is (columns, rows) and the
    rows of ``z`` are written in order.
    """
    data = z.astype("<f4").tobytes()
    header = bytearray(64 + 320)
    # BinHeader5: version, checksum (set last), wfmSize = WaveHeader5 + data
    struct.pack_into("<hhl", header, 0, 5, 0, 320 + len(data))
    wave = 64  # WaveHeader5 offsets below are from its start
    struct.pack_into("<lh", header, wave + 12, z.size, 2)  # npnts, type NT_FP32
    struct.pack_into("<h32s", header, wave + 26, 1, b"scan")  # whVersion, bname
    struct.pack_into("<4l", header, wave + 68, z.shape[1], z.shape[0], 0, 0)  # nDim
    struct.pack_into("<4d", header, wave + 84, PIXEL_SIZE, PIXEL_SIZE, 0, 0)  # sfA, m/pixel
    struct.pack_into("4s4s4s", header, wave + 148, b"m", b"m", b"m")  # dataUnits, dimUnits x, y
    # the 16-bit sum of BinHeader5 and WaveHeader5 must be 0 (PTN003)
    total = sum(struct.unpack("<192h", header))
    struct.pack_into("<h", header, 2, (-total + 2**15) % 2**16 - 2**15)
    path.write_bytes(bytes(header) + data)


def write_gwy(path: Path, z: np.ndarray) -> None:
    """A Gwyddion .gwy file with one channel, ``Height``, in m (needs gwyfile)."""
    from gwyfile.objects import GwyContainer, GwyDataField, GwySIUnit

    container = GwyContainer()
    container["/0/data"] = GwyDataField(
        z, xreal=z.shape[1] * PIXEL_SIZE, yreal=z.shape[0] * PIXEL_SIZE,
        si_unit_xy=GwySIUnit(unitstr="m"), si_unit_z=GwySIUnit(unitstr="m"),
    )  # fmt: skip
    container["/0/data/title"] = "Height"
    container.tofile(str(path))


def write_histogram(path: Path, z: np.ndarray) -> None:
    """Two columns, bin centre (nm) and count, of the heights ``z`` (m) in bins of BIN."""
    index = np.round(z.ravel() / BIN).astype(int)
    centres = np.arange(index.min(), index.max() + 1)
    counts = np.bincount(index - index.min())
    lines = ["height (nm),count"] + [
        f"{c * BIN * 1e9:g},{n}" for c, n in zip(centres, counts, strict=True)
    ]
    path.write_text("\n".join(lines) + "\n")


def main(folder: Path = HERE) -> list[Path]:
    """Write every sample file into ``folder``; return their paths."""
    rng = np.random.default_rng(SEED)
    z = surface(rng)
    backward = z + NOISE * rng.standard_normal(z.shape)
    folder.mkdir(parents=True, exist_ok=True)
    paths = {name: folder / name for name in (
        "scan.txt", "scan.npy", "scan.gwy", "scan.nid", "scan.ibw", "hist.csv", "hist-surface.toml", "gold.toml",
    )}  # fmt: skip
    np.savetxt(paths["scan.txt"], z * 1e9, fmt="%.4f")
    np.save(paths["scan.npy"], z)
    write_gwy(paths["scan.gwy"], z)
    write_nid(paths["scan.nid"], z, backward)
    write_ibw(paths["scan.ibw"], z)
    write_histogram(paths["hist.csv"], z)
    paths["hist-surface.toml"].write_text(HIST_SURFACE)
    paths["gold.toml"].write_text(GOLD)
    return list(paths.values())


if __name__ == "__main__":
    for written in main():
        print(f"wrote {written} ({written.stat().st_size} bytes)")
