// The JavaScript the browser tests run in the page, one function per `//# NAME` line;
// tests/browser/browser_helpers.py reads them into PROBES[NAME].

//# SCROLL_THROUGH
async waitingSource => {  // WAITING below, as text
    const waiting = eval(`(${waitingSource})`);
    const settle = () => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(done, 30))));
    for (let y = 0; y < document.documentElement.scrollHeight; y += 2 * innerHeight) {
        scrollTo(0, y);
        await settle();
    }
    // On a busy machine a section may be drawn only after the reader has scrolled past it, and its
    // lazy images never asked for: the reader goes back to each such figure and waits up to 10 s.
    for (const element of waiting()) {
        element.scrollIntoView({block: "center"});
        for (const until = performance.now() + 10_000; waiting().includes(element) && performance.now() < until;) await settle();
    }
    scrollTo(0, 0);
}

//# WAITING
() => [...document.images].filter(image => !image.complete && image.getClientRects().length)  // shown, not loaded
    .concat([...document.querySelectorAll(".ddg-explorer")].filter(root => !root.player || root.player === "loading"))

//# CONTRAST_SAMPLE
() => {
    document.querySelectorAll("[data-ddg-contrast]").forEach(e => e.removeAttribute("data-ddg-contrast"));
    const kind = e => { const s = getComputedStyle(e);
        return [e.tagName, e.className, s.color, s.backgroundColor, s.backgroundImage, s.opacity,
                s.fontSize, s.fontWeight, s.textShadow, s.filter, s.visibility].join("|"); };
    // an element's kind together with its ancestors' kinds, as a number: each element's style is
    // read once, and (its kind, its parent's number) names it
    const numbers = new Map(), ofElement = new Map();
    const number = e => {
        if (!e || e === document.documentElement) return 0;
        if (!ofElement.has(e)) {
            const key = kind(e) + ">" + number(e.parentElement);
            if (!numbers.has(key)) numbers.set(key, numbers.size + 1);
            ofElement.set(e, numbers.get(key));
        }
        return ofElement.get(e);
    };
    // what axe judges: drawn text, and it passes over text of punctuation only (so does the sample
    // where a kind has text with letters or digits too)
    const own = e => [...e.childNodes].filter(n => n.nodeType === Node.TEXT_NODE).map(n => n.textContent).join("");
    const texts = [...document.body.querySelectorAll("*")].filter(e => own(e).trim() && e.getClientRects().length);
    const seen = new Set();
    for (const pass of [/[\p{L}\p{N}]/u, /./]) {
        for (const e of texts) {
            const key = number(e);
            if (!seen.has(key) && pass.test(own(e))) { seen.add(key); e.setAttribute("data-ddg-contrast", ""); }
        }
    }
    return seen.size;
}

//# TEX_LEFT
() => {
    const found = [];
    const walker = document.createTreeWalker(document.querySelector("main") || document.body, NodeFilter.SHOW_TEXT);
    while (walker.nextNode()) {
        const node = walker.currentNode, element = node.parentElement;
        if (!element || element.closest("mjx-container, code, pre, script, style, svg, .ddg-explorer, .ddg-alt")) continue;
        if (!element.getClientRects().length) continue;  // not shown (a folded solution)
        if (/\\[a-zA-Z]{2,}|\$[^$\s][^$]*\$|\\\(|\\\[/.test(node.textContent)) found.push(node.textContent.trim().slice(0, 80));
    }
    return found;
}

//# UNREADABLE_MATH
() => [...document.querySelectorAll("main .math")].filter(m => {
    const drawn = m.querySelector("mjx-container > mjx-math[aria-hidden=true]");
    const text = m.querySelector("mjx-container > mjx-assistive-mml > math");
    return !drawn || !text || !text.textContent.trim();
}).map(m => "in: " + m.parentElement.textContent.trim().slice(0, 60))

//# FONTS_FAILED
() => [...document.fonts].filter(f => f.status === 'error').map(f => f.family)

//# MATH_FONTS
() => [...document.fonts].filter(f => f.family.startsWith("MJX")).reduce((count, f) =>
    (count[f.status] = (count[f.status] || 0) + 1, count), {})

//# ICONS_UNDRAWN
() => [...document.querySelectorAll('.fa:not(svg), [class*="fa-"]:not(svg)'),
    ...[...document.querySelectorAll("svg.svg-inline--fa")].filter(i => i.getClientRects().length
                                                                    && !i.getBoundingClientRect().width)]
    .map(e => e.outerHTML.slice(0, 80))

//# SIDEWAYS
(selector) => [...document.querySelectorAll(selector)]
    .filter(e => e.getClientRects().length && e.scrollWidth > e.clientWidth + 1)
    .map(e => (e.className || e.tagName) + ": " + e.textContent.trim().slice(0, 60))

//# OPEN_SOLUTIONS
() => {  // every folded block, as a reader opens them: solutions, and the code behind a figure
    document.querySelectorAll(".toggle-hidden > .admonition-title .toggle-button").forEach(b => b.click());
    document.querySelectorAll("main details:not([open])").forEach(d => { d.open = true; });
}

//# SHOWN_SOLUTIONS
() => [...document.querySelectorAll(".solution")].filter(s =>
    [...s.querySelectorAll(":scope > :not(.admonition-title)")].some(e => {
        const box = e.getBoundingClientRect();
        return box.width > 0 && box.height > 0 && getComputedStyle(e).visibility !== "hidden";
    })).length

//# NO_TRANSITION
() => document.getAnimations().every(a => !(a instanceof CSSTransition) || a.playState !== 'running')

//# NOTHING_MOVES
() => document.getAnimations().every(a => a.playState !== 'running')

//# PAGE_IS_WIDER
() => document.documentElement.scrollWidth - window.innerWidth

//# UNCUED
() => [...document.querySelectorAll(`main .ddg-scroll, main div.math, main div.math mjx-container,
        main mjx-container[display=true], main pre`)]
    .filter(e => e.getClientRects().length && e.scrollWidth > e.clientWidth + 1)
    .filter(e => { const overflow = getComputedStyle(e).overflowX;
        return overflow === "hidden" || overflow === "clip"
            || (overflow !== "visible" && !e.classList.contains("ddg-overflows")); })
    .map(e => e.tagName + ": " + e.textContent.trim().slice(0, 60))

//# FALSE_CUE
() => [...document.querySelectorAll(".ddg-overflows")]
    .filter(e => e.scrollWidth <= e.clientWidth + 1).map(e => e.tagName + ": " + e.textContent.trim().slice(0, 60))

//# CUT_INLINE
() => [...document.querySelectorAll('main mjx-container:not([display="true"])')]
    .filter(m => m.getClientRects().length).filter(m => {
        let block = m.parentElement;
        while (block && getComputedStyle(block).display.startsWith("inline")) block = block.parentElement;
        const style = getComputedStyle(block);
        return m.getBoundingClientRect().right > block.getBoundingClientRect().right - parseFloat(style.paddingRight) + 1;
    }).map(m => (m.getAttribute("aria-label") || m.textContent).slice(0, 60))

//# SHRUNK
() => [...document.querySelectorAll("main .cell_output img")]
    .filter(img => img.naturalWidth > 0 && img.getBoundingClientRect().width < 0.9 * img.naturalWidth)
    .map(img => img.alt.slice(0, 50) + " at " + Math.round(100 * img.getBoundingClientRect().width / img.naturalWidth) + "%")

//# DIMMED
() => [...document.querySelectorAll("main .cell_output img, main figure img")]
    .filter(img => getComputedStyle(img).filter !== "none").map(img => img.alt.slice(0, 50))

//# STACKED
() => [...document.querySelectorAll("main .cell_output")]
    .map(out => [...out.querySelectorAll(":scope > figure.ddg-figure-caption")])
    .filter(figs => figs.length >= 2 && figs.every(f => f.getBoundingClientRect().width <= 340))
    .filter(figs => figs[0].getBoundingClientRect().top !== figs[1].getBoundingClientRect().top)
    .map(figs => figs[0].textContent.trim().slice(0, 50))

//# VISIBLE_H1
() => [...document.querySelectorAll('h1')].filter(h => h.getClientRects().length).map(h => h.textContent.trim())

//# SWEEP
([index, k]) => {  // every step of one slider, timed: the page looks up and draws synchronously
    const root = document.querySelectorAll(".ddg-explorer")[index];
    const input = [...root.querySelectorAll(".ddg-controls select, .ddg-controls input")][k];
    const times = [], start = Number(input.value);
    for (let value = 0; value <= Number(input.max); value++) {
        const t0 = performance.now();
        input.value = value;
        input.dispatchEvent(new Event("input"));
        times.push(performance.now() - t0);
    }
    input.value = start;
    input.dispatchEvent(new Event("input"));
    return times;
}

//# COMPARE
(python) => {
    const input = document.querySelector(".ddg-controls input");
    const bare = (svg) => {  // the player's panel without what it adds for interaction
        const copy = svg.cloneNode(true);
        copy.querySelectorAll("title").forEach((t) => t.remove());
        copy.querySelectorAll("circle").forEach((c) => {
            for (const a of ["tabindex", "role", "aria-label", "data-label", "class"]) c.removeAttribute(a);
        });
        return copy.innerHTML;
    };
    const parsed = (markup) => {  // Python's markup, serialised by the same browser
        const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
        svg.innerHTML = markup;
        return svg.innerHTML;
    };
    const differ = [];
    python.forEach((panels, frame) => {
        input.value = frame;
        input.dispatchEvent(new Event("input"));
        document.querySelectorAll(".ddg-figure svg").forEach((svg, i) => {
            const js = bare(svg), py = parsed(panels[i]);
            if (js !== py) differ.push({frame, panel: i, js: js.slice(0, 400), py: py.slice(0, 400)});
        });
    });
    return differ;
}

//# LAB_QUANTITIES
(polygons) => JSON.stringify(JSON.parse(polygons, (key, x) => ["NaN", "Infinity", "-Infinity"].includes(x) ? Number(x) : x).map(({vertices, eps}) => {  // ddg-lab.js on each polygon: every quantity, or its error
    const lab = window.ddgLab, out = {};
    const get = (name, f) => { try { out[name] = f(); } catch (e) { out[name] = {error: e.message}; } };
    let c = null;
    get("curve", () => { c = new lab.DiscreteCurve(vertices); return null; });
    for (const kind of lab.CURVATURES) get("flow_step " + kind, () => lab.flow_step(vertices, kind));
    if (!c) return out;
    for (const name of ["edges", "edge_lengths", "length", "tangents", "normals", "turning_angles", "dual_lengths",
                        "turning_number", "signed_area", "bisector_normals"]) get(name, () => c[name]);
    get("tan_half_turn", () => lab.tan_half_turn(c.edges.slice(-1).concat(c.edges.slice(0, -1)), c.edges,
                                                 c.edge_lengths.slice(-1).concat(c.edge_lengths.slice(0, -1)),
                                                 c.edge_lengths, c.vertices, 0));
    get("length_gradient", () => c.length_gradient());
    for (const kind of lab.CURVATURES) get("curvature " + kind, () => c.curvature(kind));
    for (const method of lab.INFLATIONS) [0, eps].forEach((e, i) => get(`inflated_area ${method} ${i}`, () => c.inflated_area(e, method)));
    return out;
}), (key, x) => typeof x === "number" && !isFinite(x) ? `@${x}@` : x).replace(/"@(NaN|-?Infinity)@"/g, "$1")
// JSON text both ways, NaN and infinities written as Python's json reads them: Playwright's own
// transfer of so many numbers takes seconds
