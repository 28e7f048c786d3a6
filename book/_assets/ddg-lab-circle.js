/* Chapter 6's fourth curvature for the lab of chapter 10, in the instructor's edition only: the
 * student edition and its site leave this file out (instructor/edition.py), as it answers the
 * exercise ex-circle-curvature; the lab then shows ddg's three curvatures. Loaded after ddg-lab.js,
 * before ddg-lab-page.js, where there is a .ddg-lab (tools/sphinx_assets.py).
 */
(function () {
  "use strict";
  /* Chapter 6's fourth curvature (its exercise ex-circle-curvature), which ddg leaves to the reader:
   * the signed reciprocal radius of the circle through v_{i-1}, v_i, v_{i+1}, 2 sin(psi_i) / |v_{i+1} - v_{i-1}|
   * (law of sines; positive where the polygon turns clockwise). The tests compare it with the grader's
   * own, measured from the circle's centre. */
  window.ddgLab.circle_curvature = function (curve) {
    var v = curve.vertices, n = v.length;
    return curve.turning_angles.map(function (psi, i) {
      var p = v[(i + n - 1) % n], q = v[(i + 1) % n], chord = Math.hypot(q[0] - p[0], q[1] - p[1]);
      if (!(chord > 0)) throw new Error("no circle through vertices " + ((i + n - 1) % n) + ", " + i + " and " + ((i + 1) % n) + ": the first and the last coincide");
      return 2 * Math.sin(psi) / chord;
    });
  };
})();
