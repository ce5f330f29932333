"""The figures of docs/calibration.md's validation of the topography route (run with the
topography environment's python, tools/setup_topography.sh):

    build/venv-topography/bin/python -m k2d.topography_validation [--out DIR] [--exe PROGRAM]

(with tools/ on PYTHONPATH).  A self-affine synthetic surface (Hurst 0.8, rms height 1 um,
wavelengths 1/8 mm down to 16 grid points of the fine grid, E* of steel on steel): the base
sample, 256 x 256 points over 1 mm, is the fine one (512 x 512 over 1 mm) at half resolution;
the larger sample is another draw of 512 x 512 over 2 mm at the base's pixel.  The constants
of each over one pressure range, the power law's range, the contact-area slope kappa against
Persson's and Bush-Gibson-Thomas' asymptotes, and the base's law replayed through Kontakt2D.
"""
import argparse
import math
import os
import time

import numpy as np

from k2d import calibration as cal
from k2d import topography as tp


def surface(n, size, seed, resolve):
    from SurfaceTopography.Generation import fourier_synthesis
    t = fourier_synthesis((n, n), (size, size), hurst=0.8, rms_height=1.0e-3, short_cutoff=resolve * size / n,
                          long_cutoff=1.0 / 8, rng=np.random.default_rng(seed), unit="mm").squeeze()
    return tp.Surface(t.heights(), (size, size), "self-affine %dx%d over %g mm" % (n, n, size))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="results/topography_validation")
    ap.add_argument("--exe", help="the kontakt2d program for the replay")
    ap.add_argument("--pressure-range", type=float, nargs=2, default=(1000.0, 3000.0),
                    help="kgf/cm2 (default 1000 3000: A/A0 about 3 %% to 9 %%)")
    args = ap.parse_args(argv)
    units = cal.Units("KGF_UM")
    Es = tp.contact_modulus(2.1e5, 0.3)
    pmin, pmax = (v * units.pressure for v in args.pressure_range)
    fine = surface(512, 1.0, 1, 16)
    base = fine.coarsened()
    base.name = "self-affine 256x256 over 1 mm"
    larger = surface(512, 2.0, 2, 8)
    rows = {}
    for label, s in (("base", base), ("finer grid", fine), ("larger sample", larger)):
        t0 = time.process_time()
        tf = tp.calibrate(s, "%s.x3p" % label.replace(" ", "_"), Es, pmin, pmax, units, points=12, out=args.out,
                          stem=label.replace(" ", "_"))
        cpu = time.process_time() - t0
        p, u, area, _ = tf.curve.arrays()
        kappa = area * Es * s.rms_gradient() / p
        rows[label] = tf
        print(tf.report())
        print("%s: kappa from %.3f to %.3f (Persson %.3f, Bush-Gibson-Thomas %.3f); CPU %.1f s"
              % (label, kappa.max(), kappa.min(), math.sqrt(8 / math.pi), math.sqrt(2 * math.pi), cpu))
        u0, _, worst = tp.log_law(p, u)
        print("%s: closure slope against ln p %.4g um = %.3f h_rms (Persson 2007: 0.4-0.5), log law worst %.2g %%"
              % (label, u0 * 1e3, u0 / s.rms_height(), 100 * worst))
    ref = {c.name: c.value for c in rows["base"].fit.constants}
    for label in ("finer grid", "larger sample"):
        print("%s against base: %s" % (label, ", ".join(
            "%s %+.2g %%" % (c.name, 100 * (c.value / ref[c.name] - 1)) for c in rows[label].fit.constants)))
    from k2d import calibration_replay as rep
    r = rep.replay_normal(rows["base"].fit, os.path.join(args.out, "replay"), exe=args.exe)
    print(rep.summary(r, "closure").replace("computed - data", "computed - BEM"))
    rel = np.abs(r.computed[r.rows] / rows["base"].fit.u[r.rows] - 1.0)
    print("replay: worst |Kontakt2D / BEM - 1| = %.3g" % rel.max())
    from k2d import topography_plots as plots
    plots.plot_topography(rows["base"], os.path.join(args.out, "base.png"), r)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
