"""The Python module's cost: per-call overhead of Material.update, and update_many's throughput
on the same points and increments as the C++ benchmark BM_MaterialUpdateMany
(bench/material_bench.cpp). Run:

    PYTHONPATH=build/python /usr/bin/python3 bench/python_update_bench.py
    build/bench/bench_material --benchmark_filter=BM_MaterialUpdateMany
"""
import time

import numpy as np

import ecm

concrete = ecm.Material(name="concrete", model="enriched", hypothesis="plane_stress", youngs_modulus=32000, poisson_ratio=0.2, tensile_strength=3.0,
                        softening_modulus=8.184, softening_exponent=0.128, band_width=0.05)
step = np.array([2e-7, -2e-8, 3e-8])
H = 2.5


def best(f, repeat=5):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


# Per call: an intact point (the C++ update itself costs a few ns), tangent off and on.
point = ecm.PointState([2e-5, -1e-6, 1e-7])
calls = 100000
for tangent in (False, True):
    def loop():
        for i in range(calls):
            concrete.update(point, step if i % 2 == 0 else -step, H, tangent=tangent)
    print(f"update() per call, intact, tangent={tangent}: {best(loop) / calls * 1e6:.2f} us")

# update_many: 100,000 intact points (an increment and back) and 10,000 cracked points softening.
for cracked, n in ((False, 100000), (True, 10000)):
    points = ecm.PointArray([ecm.PointState([2e-5, -1e-6, 1e-7]) for _ in range(n)])
    if cracked:
        for _ in range(40):
            concrete.update_many(points, np.tile([5e-6, -1e-6, 1e-6], (n, 1)), H)
    up, down = np.tile(step, (n, 1)), np.tile(-step, (n, 1))
    sign = [1]

    def many():
        concrete.update_many(points, up if cracked or sign[0] > 0 else down, H)
        sign[0] = -sign[0]
    t = best(many, repeat=9)
    print(f"update_many, {'cracked' if cracked else 'intact'} ({n} points): {n / t / 1e6:.2f} M updates/s "
          f"({t / n * 1e9:.0f} ns per update)")
