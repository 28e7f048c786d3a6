/* Small behaviours of the book's pages. */
document.addEventListener("DOMContentLoaded", function () {
  // The phone's buttons open the chapter list (☰) and the page's contents: the theme
  // (pydata-sphinx-theme 0.17, its issue #2451) binds only the first .primary-toggle and the first
  // .secondary-toggle, hidden ones; the others do here what those do there.
  ["primary", "secondary"].forEach(function (side) {
    var sidebar = document.getElementById("pst-" + side + "-sidebar"), modal = document.getElementById("pst-" + side + "-sidebar-modal");
    var bound = document.querySelector("." + side + "-toggle");
    if (!sidebar || !modal || !modal.showModal) { return; }
    document.querySelectorAll("." + side + "-toggle").forEach(function (button) {
      if (button === bound) { return; }
      button.addEventListener("click", function (event) {
        event.preventDefault();
        event.stopPropagation();
        var back = document.activeElement;
        Array.from(sidebar.childNodes).forEach(function (node) { modal.appendChild(node); });
        Array.from(sidebar.classList).forEach(function (name) { sidebar.classList.remove(name); modal.classList.add(name); });
        modal.showModal();  // the theme's own handlers close it and put the list back
        modal.addEventListener("close", function () { if (back && back.focus) { back.focus(); } }, {once: true});
      });
    });
    // a section of this page chosen there: the page scrolls to it, and the list closes
    modal.addEventListener("click", function (event) {
      var link = event.target.closest("a[href^='#']");
      if (link && modal.open) { modal.close(); }
    });
  });
  // A solution's title opens the solution: its link to the exercise would jump away instead.
  document.querySelectorAll(".solution > .admonition-title a").forEach(function (link) {
    link.addEventListener("click", function (event) {
      event.preventDefault();
      event.stopPropagation();
      var button = link.closest(".admonition-title").querySelector(".toggle-button");
      if (button) { button.click(); }
    });
  });
  // The bibliography's entries are the items of its list (ARIA has no "doc-biblioentry" in a list).
  document.querySelectorAll(".citation-list > [role='doc-biblioentry']").forEach(function (entry) {
    entry.setAttribute("role", "listitem");
  });
  // Wide tables scroll inside their own box, display equations and code in theirs (the theme's);
  // a shadow and a dashed line at the edge say so.
  document.querySelectorAll("main div.math, main table").forEach(function (element) {
    var box = element.closest(".ddg-scroll");
    if (!box) {
      box = document.createElement("div");
      box.className = "ddg-scroll";
      element.parentNode.insertBefore(box, element);
      box.appendChild(element);
    }
  });
  // An inline formula wider than its column (on a phone) gets a line of its own that scrolls.
  function wideInline() {
    var formulas = document.querySelectorAll('main mjx-container:not([display="true"])');
    formulas.forEach(function (m) { m.classList.remove("ddg-scroll", "ddg-inline-wide", "ddg-overflows"); });
    var wide = [];
    formulas.forEach(function (m) {
      var block = m.parentElement;
      while (block && getComputedStyle(block).display.indexOf("inline") === 0) { block = block.parentElement; }
      if (!block || !m.getClientRects().length) { return; }
      var style = getComputedStyle(block);
      var column = block.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
      if (m.getBoundingClientRect().width > column + 1) { wide.push(m); }
    });
    wide.forEach(function (m) { m.classList.add("ddg-scroll", "ddg-inline-wide"); });
  }
  function cue() {
    wideInline();
    var boxes = Array.prototype.slice.call(document.querySelectorAll(".ddg-scroll, main div.math mjx-container, main pre"));
    var overflows = boxes.map(function (box) { return box.scrollWidth > box.clientWidth + 1; });  // all read, then all set:
    boxes.forEach(function (box, i) {  // one layout, not one each
      box.classList.toggle("ddg-overflows", overflows[i]);
      if (overflows[i] && !box.hasAttribute("tabindex")) {  // a box that scrolls takes the keyboard's focus
        box.tabIndex = 0;
        box.dataset.ddgFocus = "";
      } else if (!overflows[i] && box.hasAttribute("data-ddg-focus")) {
        box.removeAttribute("tabindex");
        box.removeAttribute("data-ddg-focus");
      }
    });
  }
  cue();
  window.addEventListener("resize", cue);
  document.addEventListener("click", function (event) {  // an opened solution is measured again
    if (event.target.closest(".admonition-title, .toggle-button")) { setTimeout(cue, 0); }
  });
});

// Offline after one visit: once the page has loaded (never before its first paint), the service
// worker saves the whole book in the background (tools/sphinx_offline.py writes it, per build).
window.addEventListener("load", function () {
  if (!("serviceWorker" in navigator) || !/^https?:$/.test(location.protocol)) { return; }
  var root = new URL(document.documentElement.getAttribute("data-content_root") || "./", location.href);
  navigator.serviceWorker.register(new URL("sw.js", root).href).catch(function () {});
});

// Search results quote the prose: a formula is read as its text when that is a symbol or two
// ("ψi"), else "…"; code, outputs, figures and explorers are left out (their text reads as noise).
// Sphinx's search page calls Search.htmlToText on each page it quotes, after this deferred script.
if (typeof Search !== "undefined" && Search.htmlToText) {
  var sphinxToText = Search.htmlToText;
  Search.htmlToText = function (htmlString, anchor) {
    var doc = new DOMParser().parseFromString(htmlString, "text/html");
    doc.querySelectorAll("div.highlight, .cell_output, figure, .ddg-explorer, .ddg-lab, .bd-toc, .prev-next-area, details")
      .forEach(function (e) { e.remove(); });
    doc.querySelectorAll("mjx-container").forEach(function (m) {
      var spoken = (m.querySelector("mjx-assistive-mml") || m).textContent.replace(/\s+/g, "");
      m.replaceWith(spoken.length <= 3 && m.getAttribute("display") !== "true" ? spoken : "…");
    });
    return sphinxToText(doc.documentElement.outerHTML, anchor).replace(/\s+/g, " ");
  };
}
