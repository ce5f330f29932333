"""Make the measured-format sample of the topography tests: a self-affine surface written by
SurfaceTopography's own X3P writer (ISO 25178-72), 64 x 64 points over 0.4 mm, heights in um,
16-bit integers with a height increment.  Run with the topography environment's python
(tools/setup_topography.sh) from this folder:  python make_sample.py
Also writes corrupt.x3p, the sample cut short (a zip archive without its end)."""
import numpy as np
from SurfaceTopography.Generation import fourier_synthesis

n, size = 64, 400.0                                     # points, um
t = fourier_synthesis((n, n), (size, size), hurst=0.8, rms_height=0.5, short_cutoff=size / 16,
                      long_cutoff=size / 4, rng=np.random.default_rng(27), unit="um").squeeze()
t.to_x3p("sample.x3p", dtype="I")
with open("sample.x3p", "rb") as f:
    data = f.read()
with open("corrupt.x3p", "wb") as f:
    f.write(data[: len(data) // 2])
