"""The snap-back study's sweep over the effective size H, in a few lines: the enriched point keeps
its traction-opening curve and dissipates G_F at every H; strain control snaps back beyond
h (E + E_p)/E_p. PYTHONPATH=build/python /usr/bin/python3 examples/size_sweep.py"""
import pathlib

import ecm

root = pathlib.Path(__file__).resolve().parents[1]
study = ecm.snapback_study({
    "material": {"file": str(root / "data/materials/den-concrete.yaml")},
    "effective_sizes": [1, 10, 50, 100, 195, 200, 400, 700],  # H (mm)
})
print(f"snap-back beyond H = {study['snapback_size']:.1f} mm (1D closed form {study['snapback_size_1d']:.1f} mm)")
print(f"{'H (mm)':>8} {'peak (MPa)':>11} {'H x diss / G_F':>15} {'snaps back':>11}")
rows = study["rows"]
for H, peak, ratio, snap in zip(rows["H"], rows["peak_stress"], rows["energy_ratio"], rows["strain_control_snapback"]):
    print(f"{H:8.0f} {peak:11.4f} {ratio:15.4f} {'yes' if snap else 'no':>11}")
