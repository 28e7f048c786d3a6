"""One scene, drawn twice: by Python (ddg.scene.render) and by the book's player in Chromium.

Random polygons, dots coloured on the ramp, arrows, bars below and above zero, rotated text and
labels full of characters HTML must escape: every element and attribute the player writes must
be the one Python writes (the player adds only focus and hover to labelled dots).
"""

import numpy as np
from browser_helpers import PROBES, ROOT

from ddg.scene import COLORS, Animation, Scene, render

PLAYER = ROOT / "book" / "_assets" / "ddg-player.js"
COMPARE = PROBES["COMPARE"]


def random_scene(rng):
    panels = []
    for title in ("a random polygon", 'ψ & "k" <i>'):
        x0, y0 = rng.uniform(-5, 5, 2)
        w, h = rng.uniform(0.5, 20, 2)
        panels.append({"box": (x0, y0, x0 + w, y0 + h), "px": (int(rng.integers(80, 400)), int(rng.integers(80, 400))),
                       "title": title})
    scene = Scene(panels, "summary", "alt")
    for panel, p in enumerate(panels):
        x0, y0, x1, y1 = p["box"]
        n = int(rng.integers(3, 40))
        points = np.c_[rng.uniform(x0, x1, n), rng.uniform(y0, y1, n)]
        scene.line(panel, points, COLORS["blue"], float(rng.choice([0.5, 1, 1.5])), bool(rng.integers(2)),
                   fill=COLORS["grey"] if rng.integers(2) else None, dash="4 3" if rng.integers(2) else None,
                   opacity=float(rng.choice([0.35, 0.6])) if rng.integers(2) else None)
        scene.dots(panel, points, r=float(rng.choice([3, 3.5, 7])), values=rng.uniform(-0.2, 1.2, n))
        scene.dots(panel, points[:3], COLORS["red"], labels=["v0: ψ = +1.0'", 'v1 "&" <b>', "v2"], handle=True)
        scene.arrows(panel, points, rng.normal(size=(n, 2)), COLORS["red"])
        scene.bars(panel, rng.uniform(x0, x1, 4), rng.uniform(-(y1 - y0), y1 - y0, 4), (x1 - x0) / 20, list(COLORS.values())[:4])
        scene.text(panel, *rng.uniform(x0, x1, 2), "it's <k> & \"ψ\"", "end", 13, COLORS["green"])
        scene.text(panel, rng.uniform(-40, 40), rng.uniform(-40, 40), "log₁₀ error", "middle", 14, space="px",
                   rotate=-90)
        scene.axes(panel, [x0, (x0 + x1) / 2], [y0, y1], "x", "y")
    return scene


def test_python_and_the_player_draw_the_same_scene(browser):
    rng = np.random.default_rng(2026)
    scenes = [random_scene(rng) for _ in range(60)]
    animation = Animation(scenes, "scene", range(len(scenes)))
    context = browser.new_context()
    page = context.new_page()
    try:
        page.route("**/*", lambda route: route.abort())  # nothing leaves the page
        page.set_content(f"<!doctype html><meta charset=utf-8><body>{animation.html()}</body>")
        page.add_script_tag(content=PLAYER.read_text())
        page.wait_for_selector(".ddg-figure svg path")
        python = [[render(i, panel, scene.items) for i, panel in enumerate(scene.panels)] for scene in scenes]
        differ = page.evaluate(COMPARE, python)
        assert not differ, f"{len(differ)} panels differ; the first: {differ[0]}"
    finally:
        context.close()
