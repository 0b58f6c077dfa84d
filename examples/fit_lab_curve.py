"""Fit the band's damage law (E_p, n) to a measured traction-opening curve while it dissipates
exactly G_F, and plot fit and data.

    PYTHONPATH=build/python /usr/bin/python3 examples/fit_lab_curve.py [CURVE.csv] [--out DIR]

The default curve, data/lab/hordijk-ft3-gf011.csv, is generated from Hordijk's law for the
paper's concrete with a 3 % scatter (its header says how). Units: mm, MPa, N/mm.
"""
import argparse
import os
import pathlib
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import ecm

root = pathlib.Path(__file__).resolve().parents[1]
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("curve", nargs="?", default=root / "data/lab/hordijk-ft3-gf011.csv")
parser.add_argument("--out", default="out/fit-lab-curve")
args = parser.parse_args()

# two columns, w (mm) and traction (MPa); '#' lines and a header line of names are skipped
lines = [l for l in open(args.curve, encoding="utf-8") if l.strip() and not l.startswith("#")]
w, traction = np.loadtxt(lines[1:] if not lines[0][0].isdigit() else lines, delimiter=",", unpack=True)
concrete = dict(youngs_modulus=32000, tensile_strength=3.0, fracture_energy=0.11, band_width=0.05)  # MPa, MPa, N/mm, mm
fit = ecm.fit_softening(w, traction, **concrete)
print(f"n = {fit['n']:.4f}, E_p = {fit['Ep']:.4f} MPa, G_F = {fit['GF']:.6f} N/mm, "
      f"RMS misfit = {fit['fit_residual']:.4f} f_t'")

with tempfile.TemporaryDirectory() as tmp:  # the fitted law's own curve, as ecm-calibrate writes it
    ecm.calibrate(softening_exponent=fit["n"], out=tmp, **concrete)
    model = np.loadtxt(os.path.join(tmp, "softening.csv"), delimiter=",", skiprows=1)

os.makedirs(args.out, exist_ok=True)
plt.plot(w, traction, "o", label=f"data: {pathlib.Path(args.curve).name}")
plt.plot(model[:, 0], model[:, 1], "-", label=f"band law, n = {fit['n']:.3f}, $E_p$ = {fit['Ep']:.2f} MPa")
plt.xlim(0, 1.1 * w.max())
plt.xlabel("opening w (mm)")
plt.ylabel("traction (MPa)")
plt.legend()
plt.savefig(os.path.join(args.out, "fit.png"), dpi=120)
print(f"plot: {os.path.join(args.out, 'fit.png')}")
