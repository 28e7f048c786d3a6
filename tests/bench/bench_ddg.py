"""`make bench`: how fast ddg builds a curve and its three curvatures, against one np.copy.

For n = 10^3 ... 10^7 vertices of a regular polygon it times, in this one run,
  copy   : np.copy of the (n, 2) vertex array (the cheapest thing that touches every vertex),
  curve  : DiscreteCurve(vertices) and curvature(kind) for the three kinds, from scratch,
and prints the best of several repeats of each and their ratio. It then checks the accuracy the
input allows on a regular 10^6-gon, the peak memory of the n = 10^7 run, the time one slider
move of each explorer takes (ddg.explore), and how many curve-shortening steps per second
ddg.flow takes at n = 10^2, 10^4, 10^6, explicit and semi-implicit (with the peak memory of one
semi-implicit step: its linear solve is cyclic reduction, O(n)).

Ratios compare between machines better than seconds, but not fully: a new curve and its three
curvatures write about 3.5 times the vertices' bytes to memory that the process has just had back
from the operating system (glibc returns what a dropped curve freed), and the first touch of such
memory costs from almost nothing to more than the copy itself (on a small virtual machine, about
1.3 ms for 8 MB, where the copy of 16 MB takes 1.1 ms), while the copy up to n = 10^6 reuses the
memory it freed. At n = 10^7 the copy gets new memory too. The machines are shared, so run it
twice before believing a difference of 20%.
"""

import gc
import time
import tracemalloc

import numpy as np

import ddg


def best_time(f, repeats):
    times = []
    for _ in range(repeats):
        gc.collect()
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def build_and_curvatures(vertices):
    curve = ddg.DiscreteCurve(vertices)
    return [curve.curvature(kind) for kind in ddg.CURVATURES]


def explorer_updates():
    """One slider move of each explorer (recompute the scene and draw it as SVG), n <= 1000: target well under 100 ms."""
    from ddg.explore import InflationExplorer, PolygonExplorer, VertexExplorer, svg

    cases = [
        (PolygonExplorer(), "n", [10, 100, 1000], "polygon explorer, n = {}"),
        (InflationExplorer(), "eps", [0.1, 0.5, 1.0], "inflation explorer, eps = {}"),
        (VertexExplorer(), "dx", [0.2, -0.4, 0.8], "vertex explorer, dx = {}"),
    ]
    print(f"\n{'explorer update (scene + SVG)':40s} {'best [ms]':>10} {'median [ms]':>12}")
    for explorer, name, values, label in cases:
        for value in values:
            times = []
            for _ in range(15):
                start = time.perf_counter()
                scene = explorer.scene(**{**explorer.values(), name: value})
                [svg(scene, i) for i in range(len(scene.panels))]
                times.append(time.perf_counter() - start)
            print(f"{label.format(value):40s} {min(times) * 1e3:>10.1f} {np.median(times) * 1e3:>12.1f}")


def flow_steps_per_second():
    """Steps per second of whole ddg.flow runs (step choice, move, checks, records) on a regular n-gon."""
    from ddg.flow import semi_implicit_step, flow

    print(f"\n{'flow, sine, regular n-gon':>26} {'explicit [steps/s]':>19} {'semi-implicit [steps/s]':>24} "
          f"{'semi-implicit step peak [MB]':>29}")
    for exponent, steps in ((2, 400), (4, 100), (6, 4)):
        n = 10**exponent
        curve = ddg.regular_polygon(n)
        rates = [flow(curve, "sine", 0.45, method=method, max_steps=steps, snapshots=0, progress=False)
                 for method in ("explicit", "semi-implicit")]
        gc.collect()
        tracemalloc.start()
        semi_implicit_step(curve, "sine", 1e-3)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        print(f"{f'n = 10^{exponent}':>26} " + " ".join(f"{run.steps / run.seconds:>{width}.1f}" for run, width
                                                         in zip(rates, (19, 24), strict=True)) + f" {peak / 1e6:>29.2f}")


def main():
    print(f"ddg {ddg.__version__}, numpy {np.__version__}")
    print(f"{'n':>10} {'copy [ms]':>11} {'curve + 3 curvatures [ms]':>27} {'ratio':>7}")
    for exponent in range(3, 8):
        n = 10**exponent
        vertices = np.array(ddg.regular_polygon(n, 0.7).vertices)
        repeats = max(3, min(200, 10**7 // n))
        copy = best_time(lambda v=vertices: np.copy(v), repeats)
        curve = best_time(lambda v=vertices: build_and_curvatures(v), repeats)
        print(f"{n:>10} {copy * 1e3:>11.3f} {curve * 1e3:>27.3f} {curve / copy:>7.1f}")

    c = ddg.regular_polygon(10**6, 0.7)
    print(f"\nregular 10^6-gon, r = 0.7: |sum psi - 2 pi| = {abs(c.turning_angles.sum() - 2 * np.pi):.1e} (need < 1e-9), "
          f"max |k_sine - 1/r| = {np.abs(c.curvature('sine') - 1 / 0.7).max():.1e} (need < 1e-4)")

    vertices = np.array(ddg.regular_polygon(10**7, 0.7).vertices)
    del c
    gc.collect()
    tracemalloc.start()
    result = build_and_curvatures(vertices)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    del result
    print(f"n = 10^7: peak memory of build + curvatures {peak / 2**30:.2f} GiB "
          f"(+ {vertices.nbytes / 2**30:.2f} GiB input; need < 2 GB in all)")
    explorer_updates()
    flow_steps_per_second()


if __name__ == "__main__":
    main()
