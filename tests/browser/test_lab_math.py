"""The lab's JavaScript (book/_assets/ddg-lab.js) against ddg, on random polygons, in Chromium.

Every quantity the lab computes (but total_curvature, a dot product of two compared arrays whose
summation order BLAS chooses: where it cancels to about 0 no relative bound holds), on polygons drawn in Python with a seeded rng: convex and not,
near reversals (a turn within 1e-6 of +pi or -pi) and exact ones, very unequal edges, scales of
1e-150 and 1e150, far from the origin, figure-eights (whose area ddg sums exactly), regular
2000-gons, and what ddg refuses (too few vertices, two consecutive equal vertices, a NaN). Each
value must agree with ddg's to 1e-12 relative (vectors row by row, in the norm); each refusal must
be a refusal of the same problem (the message's start) at the same vertex.

No looser bound is needed anywhere: the lab does ddg's floating-point operations in ddg's order,
numpy's pairwise order for np.sum included, so the only differences are the last bits of the
libraries' atan, sin and cos and the order of BLAS's dot products (a @ b), all well conditioned
here. (Near a reversal tan(psi/2) is ill-conditioned in the
vertices, but both compute it from the same bits by the same operations, so it agrees to the last
bit; see ddg/_numerics.py turns. Lengths outside _numerics.SAFE come from C's hypot, which
the lab computes as glibc does, numpy's on Linux: Math.hypot differs in the last bit, which a
nearly straight vertex magnifies in length_gradient to 1e-10. The flow step's cos(psi/2) near a
reversal is ill-conditioned too; on these polygons V8's atan and cos agree with glibc's to the
last bit, so it needs no looser bound either.) Only a value below the normal
range, such as the flow's step on a polygon of size 1e-150, is compared to its last bit instead.
Set DDG_LAB_JS to a changed copy of the script to see the test fail (mutation testing).
"""

import json
import os
import pathlib
import re

import numpy as np
import pytest
from browser_helpers import PROBES, ROOT

import ddg
from ddg.flow import flow

LAB = pathlib.Path(os.environ.get("DDG_LAB_JS", ROOT / "book" / "_assets" / "ddg-lab.js"))  # another copy: mutation tests
TOLERANCE = 1e-12
SUBNORMAL = 2 * 5e-324
"""Below 2.2e-308 a float has fewer bits (a dt of 1e-315 has 30): there two subnormal steps apart
is as equal as such values get. (Any difference this small is far below 1e-12 of a normal float.)"""
ROWS = ("edges", "tangents", "normals", "length_gradient", "bisector_normals")  # compared row by row


# ------------------------------------------------------------------------ the polygons


def star(rng, n, bumpy):
    """A polygon star-shaped about the origin: convex on an ellipse, or with random radii."""
    theta = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = rng.uniform(0.2, 1.0, n) if bumpy else np.ones(n)
    v = np.c_[rng.uniform(0.5, 2) * r * np.cos(theta), r * np.sin(theta)]
    return v if rng.integers(4) else v[::-1]  # counter-clockwise, mostly (see clockwise)


def clockwise(v):
    return v[::-1].copy()  # theta increases counter-clockwise; reversed, the polygon turns clockwise


def spike(rng, v, exact=False):
    """A thin spike out of an edge: its tip turns within 1e-6 of +pi or -pi (exactly pi if `exact`)."""
    i = int(rng.integers(len(v)))
    p = v[i]
    if exact:  # integer coordinates: the edges are exactly opposite
        v = np.round(v * 64)
        p = v[i]
        d = rng.integers(-5, 6, 2).astype(float)
        d = d if d.any() else np.array([1.0, 0.0])
        return np.insert(v, i + 1, [p + 8 * d, p + 4 * d], axis=0)  # out along 8 d, back along -4 d
    d = rng.normal(size=2)
    d /= np.linalg.norm(d)
    delta = rng.choice([-1, 1]) * 10 ** rng.uniform(-9, -6)
    back = np.array([[np.cos(delta), -np.sin(delta)], [np.sin(delta), np.cos(delta)]]) @ -d
    tip = p + rng.uniform(0.3, 1) * d
    return np.insert(v, i + 1, [tip, tip + rng.uniform(0.1, 0.25) * back], axis=0)


def unequal(rng, n):
    """Vertices on an ellipse at gaps from 1e-6 to 1: edges of very different lengths."""
    gaps = 10 ** rng.uniform(-6, 0, n)
    theta = 2 * np.pi * np.cumsum(gaps) / gaps.sum()
    return clockwise(np.c_[np.cos(theta), rng.uniform(0.3, 1) * np.sin(theta)])


def figure_eight(rng, n):
    t = 2 * np.pi * np.arange(n) / n + rng.uniform(0, 1e-3)
    v = np.c_[np.sin(t), np.sin(t) * np.cos(t) * rng.uniform(0.5, 2)]
    return v if rng.integers(2) else np.r_[v[:1], -v[1:][::-1] * [1, -1]][: n]


def polygons(seed=24):
    """(family, vertices) pairs, about 1200 of them."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(200):
        out.append(("convex", clockwise(star(rng, int(rng.integers(3, 60)), False))))
    for _ in range(200):
        out.append(("non-convex", clockwise(star(rng, int(rng.integers(4, 120)), True))))
    for _ in range(150):
        out.append(("near reversal", spike(rng, clockwise(star(rng, int(rng.integers(3, 40)), bool(rng.integers(2)))))))
    for _ in range(40):
        out.append(("exact reversal", spike(rng, clockwise(star(rng, int(rng.integers(3, 20)), True)), exact=True)))
    for _ in range(100):  # nearly equal edges: the flow takes a step (it stops where an edge is short)
        n = int(rng.integers(3, 200))
        v = ddg.regular_polygon(n).vertices * rng.uniform(0.5, 2, 2) + rng.normal(size=(n, 2)) * 0.2 / n
        out.append(("jittered regular", v if rng.integers(4) else v[::-1]))
    for _ in range(100):
        out.append(("unequal edges", unequal(rng, int(rng.integers(3, 80)))))
    shapes = [lambda: clockwise(star(rng, int(rng.integers(3, 50)), bool(rng.integers(2)))),
              lambda: ddg.regular_polygon(int(rng.integers(3, 50))).vertices * rng.uniform(0.5, 2, 2),
              lambda: unequal(rng, int(rng.integers(3, 50))),
              lambda: spike(rng, clockwise(star(rng, int(rng.integers(3, 30)), True)))]
    for family, scale in (("tiny (1e-150)", 1e-150), ("huge (1e150)", 1e150)):
        for _ in range(100):
            out.append((family, shapes[int(rng.integers(4))]() * scale * 10 ** rng.uniform(-2, 2)))
    for _ in range(100):
        shift = rng.choice([-1, 1], 2) * 10 ** rng.uniform(3, 12, 2)
        out.append(("far from the origin", shapes[int(rng.integers(4))]() * 10 ** rng.uniform(-3, 1) + shift))
    for _ in range(50):
        out.append(("figure-eight", figure_eight(rng, int(rng.integers(4, 60)))))
    for n in (1000, 2000, 2000):
        out.append(("regular n-gon", ddg.regular_polygon(n, rng.uniform(0.1, 10)).vertices.copy()))
    for _ in range(60):  # refusals: a repeated vertex (the last repeating the first, too), too few, a NaN
        v = clockwise(star(rng, int(rng.integers(3, 20)), True))
        i = int(rng.integers(len(v)))
        out.append(("repeated vertex", np.insert(v, i + 1, v[i], axis=0) if rng.integers(4) else np.r_[v, v[:1]]))
    for n in (0, 1, 2):
        out.append(("too few vertices", rng.normal(size=(n, 2))))
    for _ in range(10):
        v = clockwise(star(rng, int(rng.integers(3, 20)), True))
        v[int(rng.integers(len(v)))] = np.nan
        out.append(("NaN", v))
    return out


# ------------------------------------------------------------------------ ddg's values


def attempt(f):
    try:
        return f()
    except ValueError as problem:
        return {"error": str(problem)}


def flow_reference(curve, kind):
    """ddg.flow.flow with method="explicit" and max_steps=1: the step and the curve after it, or why not."""
    with np.errstate(over="ignore"):  # a t_end far beyond the curve's life (1000 in its own frame)
        t_end = min(float(np.ldexp(1000.0, 2 * int(np.frexp(curve.length)[1]))), 1e308)
    run = flow(curve, kind, t_end, max_steps=1, snapshots=2, progress=False)
    if run.steps == 0:
        return {"error": run.stopped}
    return {"dt": float(run.times[-1]), "vertices": run.snapshots[-1][1].vertices.tolist()}


def reference(vertices, eps):
    """What ddg computes, under the lab's names."""
    out = {}
    curve = attempt(lambda: ddg.DiscreteCurve(vertices))
    if isinstance(curve, dict):
        out["curve"] = curve
        for kind in ddg.CURVATURES:
            out[f"flow_step {kind}"] = curve
        return out
    out["curve"] = None
    for name in ("edges", "edge_lengths", "length", "tangents", "normals", "turning_angles", "dual_lengths",
                 "turning_number", "signed_area", "bisector_normals"):
        out[name] = attempt(lambda name=name: getattr(curve, name))
    out["tan_half_turn"] = curve.tan_half_psi
    out["length_gradient"] = curve.length_gradient()
    for kind in ddg.CURVATURES:
        out[f"curvature {kind}"] = attempt(lambda kind=kind: curve.curvature(kind))
        out[f"flow_step {kind}"] = attempt(lambda kind=kind: flow_reference(curve, kind))
    for method in ddg.INFLATIONS:
        for i, e in enumerate((0.0, eps)):
            out[f"inflated_area {method} {i}"] = attempt(lambda e=e, method=method: curve.inflated_area(e, method))
    return out


# ------------------------------------------------------------------------ comparing


def relative(js, py, rows=False):
    """The largest relative difference: entry by entry, or row by row in the norm."""
    js, py = np.asarray(js, dtype=float), np.asarray(py, dtype=float)
    if js.shape != py.shape:
        return np.inf
    if rows:
        js, py = np.linalg.norm(js - py, axis=-1), np.linalg.norm(py, axis=-1)
        diff, size = js, py
    else:
        same = (js == py) | (np.isnan(js) & np.isnan(py))
        with np.errstate(invalid="ignore"):
            diff, size = np.where(same, 0.0, np.abs(js - py)), np.abs(py)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(diff <= SUBNORMAL, 0.0, diff / size)
    return float(r.max()) if r.size else 0.0


VERTEX = re.compile(r"\bvert(?:ex|ices) (\d+)(?: and (\d+))?")
STOPPED = re.compile(r"^stopped at t = [^:]*: ")
BRACKETS = re.compile(r"\([^()]*\)")


def same_refusal(js, py):
    """Both refuse, for the same problem (the first 30 characters but numbers in brackets) at the same vertex."""
    a, b = (BRACKETS.sub("()", STOPPED.sub("", e["error"])) for e in (js, py))
    return a[:30] == b[:30] and VERTEX.findall(a) == VERTEX.findall(b), f"js: {a!r}\npy: {b!r}"


def difference(name, js, py):
    """(relative difference, or None where both refuse alike; a function that says what differs, for the
    failure message: printing every array would take most of the test's time)."""
    py_error, js_error = isinstance(py, dict) and "error" in py, isinstance(js, dict) and "error" in js
    if py_error or js_error:
        if py_error and js_error:
            same, why = same_refusal(js, py)
            return (None if same else np.inf), lambda: why
        return np.inf, lambda: f"js: {js!r:.300}\npy: {py!r:.300}"
    if name == "curve":  # made by both: compared quantity by quantity
        return 0.0, str
    if name.startswith("flow_step"):
        return max(relative(js["dt"], py["dt"]), relative(js["vertices"], py["vertices"], rows=True)), \
            lambda: f"js dt {js['dt']!r}, py dt {py['dt']!r}"
    if name == "turning_number":
        return (0.0 if js == py else np.inf), lambda: f"js {js}, py {py}"
    return relative(js, py, rows=name in ROWS), lambda: f"js: {np.asarray(js)!r:.300}\npy: {np.asarray(py)!r:.300}"


@pytest.fixture(scope="module")
def lab_page(browser):
    context = browser.new_context()
    page = context.new_page()
    page.route("**/*", lambda route: route.abort())  # nothing leaves the page
    page.set_content("<!doctype html><meta charset=utf-8><body></body>")
    page.add_script_tag(content=LAB.read_text())
    yield page
    context.close()


def test_the_lab_computes_what_ddg_computes(lab_page, capsys):
    rng = np.random.default_rng(2024)
    cases = polygons()
    assert len(cases) >= 1000
    eps = []
    for _, v in cases:
        size = np.abs(v - v[0]).max() if len(v) and np.isfinite(v).all() else 1.0
        eps.append(float(size * 10 ** rng.uniform(-3, 0)))
    found = []
    for start in range(0, len(cases), 100):
        batch = cases[start:start + 100]
        sent = json.dumps([{"vertices": v.tolist(), "eps": e} for (_, v), e in zip(batch, eps[start:], strict=False)])
        sent = re.sub(r"\b(NaN|-?Infinity)\b", r'"\1"', sent)  # JSON has no NaN: the probe reads these strings back
        found += json.loads(lab_page.evaluate(PROBES["LAB_QUANTITIES"], sent))
    worst, failures, compared, refused, near = {}, {}, {}, {}, 0
    for (family, v), e, js in zip(cases, eps, found, strict=True):
        py = reference(v, e)
        assert set(js) == set(py), f"{family}: the lab computes {sorted(js)}, ddg {sorted(py)}"
        gap = np.pi  # how near the polygon comes to turning straight back: min (pi - |psi_i|)
        if isinstance(py.get("turning_angles"), np.ndarray):
            gap = float(np.min(np.pi - np.abs(py["turning_angles"])))
            near += 0 < gap < 1e-6
        for name in py:
            d, why = difference(name, js[name], py[name])
            if d is None:
                refused[name] = refused.get(name, 0) + 1
                continue
            compared[name] = compared.get(name, 0) + 1
            worst[name] = max(worst.get(name, 0.0), d)
            if not d <= TOLERANCE:
                failures.setdefault(name, []).append(f"{name} on a {family} polygon of {len(v)} vertices: "
                                                     f"relative difference {d:.3g} (pi - |psi| >= {gap:.2g})\n{why()}")
    with capsys.disabled():
        print(f"\n{len(cases)} polygons ({near} with a turn within 1e-6 of +-pi); per quantity: the largest "
              "relative difference, on how many polygons, and how many both refused:")
        for name in sorted(set(worst) | set(refused)):
            print(f"  {name:27s} {worst.get(name, 0):8.2g} {compared.get(name, 0):5d} {refused.get(name, 0):5d}")
    assert near >= 100, f"only {near} polygons turn within 1e-6 of +-pi"
    assert not failures, "differences in " + ", ".join(f"{name} ({len(f)} polygons)" for name, f in failures.items()) \
        + "; the first of each:\n" + "\n\n".join(f[0] for f in failures.values())
