"""The class at a glance: ``report.html``, one page with figures, written after grading.

Per coding exercise: the histogram of scores, the share of students whose answer passed its check,
and the most common first failure (what the check said first, with the numbers taken out, so that
the same mistake on different input counts once). Written exercises show once they are scored.
"""

import base64
import collections
import html
import io
import re


def failure_kind(problem):
    """What a check's first problem says, without the input it was seen on or the numbers."""
    if problem is None:
        return None
    text = re.split(r" \(on | \(expected |: on | \(Expecting", problem, maxsplit=1)[0]
    if text.startswith("on "):  # the plain facts: "on <input>[, at vertex i]: expected ..., got ..." and the like
        raised = re.search(r" raised (\w+)", text)
        text = (f"raised {raised.group(1)}" if raised else "wrong shape" if "should have shape" in text
                else "NaN or infinity" if "NaN" in text else "not real numbers" if "not real numbers" in text
                else "wrong values (no known mistake)" if "expected" in text else text)
    text = re.sub(r"`[^`]*`", "`…`", text) if text.startswith(("no `", "cell")) else text
    return re.sub(r"\d+(\.\d+)?", "#", text)[:160]


def _figure(chapters, table, records, rows):
    """The scores of each coding exercise and the totals as small histograms, and the share passing each check."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = [label for c in chapters for label in table[c]["coding"]]
    if not labels:
        return None
    panels = [(label, [r["points"][label] for r in records if label in r["points"]],
               max([r["max"][label] for r in records if label in r["max"]], default=1)) for label in labels]
    panels.append(("total", [row["total"] for row in rows], None))
    columns = min(3, len(panels) + 1)
    lines = -(-(len(panels) + 1) // columns)
    fig, axes = plt.subplots(lines, columns, figsize=(3.2 * columns, 2.4 * lines), layout="constrained", squeeze=False)
    axes = axes.ravel()
    for ax, (label, points, top) in zip(axes, panels, strict=False):  # axes has spare panels
        counts = collections.Counter(points)
        values = sorted(set(points) | ({0, top} if top is not None else set()))
        ax.bar([f"{v:g}" for v in values], [counts[v] for v in values], color="#3b6ea5")
        ax.set_title(f"{label}" + (f" (of {top:g})" if top is not None else ""), loc="left", fontsize=9)
        ax.set_ylabel("students", fontsize=8)
        ax.tick_params(labelsize=8)
        ax.yaxis.get_major_locator().set_params(integer=True)
    passing = [sum(r["problem"][label] is None for r in records if label in r["problem"])
               / max(1, sum(label in r["problem"] for r in records)) for label in labels]
    ax = axes[len(panels)]
    ax.barh(labels[::-1], [100 * p for p in passing[::-1]], color="#2f7d4f")
    ax.set_xlim(0, 100)
    ax.set_title("passed the check (% of students)", loc="left", fontsize=9)
    ax.tick_params(labelsize=8)
    for ax in axes[len(panels) + 1:]:
        ax.set_visible(False)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110)
    plt.close(fig)
    alt = "; ".join(f"{label}: {100 * p:.0f}% passed" for label, p in zip(labels, passing, strict=True))
    return base64.b64encode(buffer.getvalue()).decode(), alt


def write(path, records, rows, chapters, table):
    """Write the report for ``records`` (as ``grade`` makes them) and the gradebook ``rows``."""
    e = html.escape
    parts = [f"<h1>Class report: {e(', '.join(chapters))}</h1>",
             f"<p>{len(records)} submissions graded, {len(rows)} students.</p>"]
    figure = _figure(chapters, table, records, rows)
    if figure:
        parts.append(f'<img src="data:image/png;base64,{figure[0]}" alt="Scores per exercise and in total, and the '
                     f'share of students whose answer passed each check: {e(figure[1])}">')
    parts.append("<h2>Per exercise</h2><table><tr><th>exercise</th><th>points</th><th>mean</th><th>passed</th>"
                 "<th>most common first failure</th><th>students</th></tr>")
    for chapter in chapters:
        for label, meta in table[chapter]["coding"].items():
            graded = [r for r in records if label in r["points"]]
            if not graded:
                continue
            kinds = collections.Counter(failure_kind(r["problem"][label]) for r in graded if r["problem"][label])
            common = kinds.most_common(1)[0] if kinds else ("none", 0)
            mean = sum(r["points"][label] for r in graded) / len(graded)
            passed = sum(r["problem"][label] is None for r in graded)
            parts.append(f"<tr><td>{e(label)}</td><td>{meta.get('points', 1):g}</td><td>{mean:.2f}</td>"
                         f"<td>{passed} of {len(graded)} ({100 * passed / len(graded):.0f}%)</td>"
                         f"<td>{e(common[0])}</td><td>{common[1]}</td></tr>")
        for label, points in table[chapter]["written"].items():
            scored = [row[label] for row in rows if row.get(label) is not None]
            mean = f"{sum(scored) / len(scored):.2f}" if scored else "not scored yet"
            parts.append(f"<tr><td>{e(label)} (written)</td><td>{points:g}</td><td>{mean}</td>"
                         f"<td>{len(scored)} scored</td><td></td><td></td></tr>")
    parts.append("</table><h2>First failures, all</h2><ul>")
    for chapter in chapters:
        for label in table[chapter]["coding"]:
            kinds = collections.Counter(failure_kind(r["problem"][label]) for r in records
                                        if r["problem"].get(label))
            for kind, count in kinds.most_common():
                parts.append(f"<li><b>{e(label)}</b> ({count}): {e(kind)}</li>")
    parts.append("</ul>")
    style = ("body{font-family:system-ui,sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;color:#1a1a1a}"
             "table{border-collapse:collapse}td,th{border-bottom:1px solid #ccc;padding:.3rem .6rem;text-align:left;"
             "vertical-align:top}img{max-width:100%}")
    path.write_text(f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>Class report</title>'
                    f"<style>{style}</style></head><body>{''.join(parts)}</body></html>\n", encoding="utf-8")
