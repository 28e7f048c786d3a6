/* Small behaviours of the book's pages. */
document.addEventListener("DOMContentLoaded", function () {
  // A solution's title opens the solution: its link to the exercise would jump away instead.
  document.querySelectorAll(".solution > .admonition-title a").forEach(function (link) {
    link.addEventListener("click", function (event) { event.preventDefault(); });
  });
});
