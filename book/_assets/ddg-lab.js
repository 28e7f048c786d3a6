/* ddg-lab.js: ddg's formulas for closed plane curves, computed in the reader's browser (window.ddgLab).
 *
 * One for one with ddg/curve.py, ddg/_numerics.py and the explicit step of ddg/flow.py, under the
 * same names and with the same guards; tests/browser/test_lab_math.py compares the two on random
 * polygons. Python is the reference: where they disagree this file is wrong. The lecture's
 * conventions: clockwise is positive, psi_i is the clockwise turn at v_i from e_{i-1/2} to e_{i+1/2},
 * in (-pi, pi]; N = J T with J(x, y) = (-y, x). Closed curves only (ddg also has open ones).
 * Errors are Errors whose messages are ddg's ValueErrors' (the same vertex named).
 */
(function () {
  "use strict";
  var CURVATURES = ["angle", "sine", "tangent"], INFLATIONS = ["minkowski", "offset"];
  var SAFE = [1e-150, 1e150], ABOVE_MINUS_PI = -Math.PI + Math.pow(2, -51), EPS = Math.pow(2, -52);
  var bits = new DataView(new ArrayBuffer(8));

  function fail(message) { throw new Error(message); }
  function choose(value, valid, what) {
    if (valid.indexOf(value) < 0) fail("unknown " + what + " " + JSON.stringify(value) + "; choose one of " + valid.join(", "));
    return value;
  }
  function pow2(k) { bits.setUint32(0, (k + 1023) << 20); bits.setUint32(4, 0); return bits.getFloat64(0); }
  function ldexp(x, e) {  // x 2^e, exactly (np.ldexp)
    for (; e > 1000; e -= 1000) x *= pow2(1000);
    for (; e < -1000; e += 1000) x *= pow2(-1000);
    return x * pow2(e);
  }
  function exponent(x) {  // np.frexp(x)[1]: |x| = m 2^e with m in [1/2, 1); 0 for 0, inf, NaN
    if (x === 0 || !isFinite(x)) return 0;
    bits.setFloat64(0, x);
    var biased = (bits.getUint32(0) >>> 20) & 0x7ff;
    return biased ? biased - 1022 : exponent(x * pow2(64)) - 64;
  }
  function sum(values) {  // np.sum, in its order: numpy's pairwise summation (8 accumulators, blocks of 128)
    var n = values.length, i, h, r, res = 0;
    if (n < 8) { for (i = 0; i < n; i++) res += values[i]; return res; }
    if (n > 128) { h = n >> 1; h -= h % 8; return sum(values.slice(0, h)) + sum(values.slice(h)); }
    for (r = values.slice(0, 8), i = 8; i < n - n % 8; i += 8) for (h = 0; h < 8; h++) r[h] += values[i + h];
    for (res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7])); i < n; i++) res += values[i];
    return res;
  }
  function dot(a, b) {  // numpy's a @ b is BLAS's, in an order of its own: here compensated (Neumaier), as accurate
    var s = 0, c = 0;
    a.forEach(function (x, i) { var y = x * b[i], t = s + y; c += Math.abs(s) >= Math.abs(y) ? (s - t) + y : (y - t) + s; s = t; });
    return s + c;
  }
  function previous(values) { return values.slice(-1).concat(values.slice(0, -1)); }  // entry i: values[i - 1]
  function J(u) { return u.map(function (p) { return [-p[1], p[0]]; }); }  // +90 degrees

  function lengths(vectors) {  // _numerics.lengths: sqrt(x x + y y) where every length lies in SAFE, else hypot
    var fast = vectors.map(function (p) { return Math.sqrt(p[0] * p[0] + p[1] * p[1]); });
    var lo = Math.min.apply(null, fast), hi = Math.max.apply(null, fast);
    if (SAFE[0] < lo && hi < SAFE[1]) return fast;
    return vectors.map(function (p) { return hypot(p[0], p[1]); });
  }
  /* np.hypot is C's hypot; Math.hypot differs from glibc's in the last bit for a quarter of all
   * inputs, which a nearly straight vertex's T_{i-1/2} - T_{i+1/2} magnifies. This is glibc's
   * (since 2.35, without FMA): Borges' corrected sqrt(x^2 + y^2), arXiv:1904.09481, scaled by 2^600. */
  function hypot(x, y) {
    var ax = Math.max(Math.abs(x), Math.abs(y)), ay = Math.min(Math.abs(x), Math.abs(y)), s = Math.pow(2, 600);
    if (!isFinite(ax)) return ax;
    if (ax > Math.pow(2, 511)) return ay <= ax * Math.pow(2, -54) ? ax + ay : corrected(ax / s, ay / s) * s;
    if (ay < Math.pow(2, -459)) return ax >= ay * Math.pow(2, 54) ? ax + ay : corrected(ax * s, ay * s) / s;
    return ay <= ax * Math.pow(2, -54) ? ax + ay : corrected(ax, ay);
  }
  function corrected(ax, ay) {
    var h = Math.sqrt(ax * ax + ay * ay), d;
    if (h <= 2 * ay) { d = h - ay; return h - (ax * (2 * d - ax) + (d - 2 * (ax - ay)) * d) / (2 * h); }
    d = h - ax;
    return h - (2 * d * (ax - 2 * ay) + ((4 * d - ay) * ay + d * d)) / (2 * h);
  }

  /* _numerics.turns and tan_half_turn: tan(psi/2) for the clockwise turn from a[i] to b[i], the edges into and out
   * of vertex v[first + i]. With |a||b| sin psi = -(a x b) and |a||b| cos psi = a . b:
   *   tan(psi/2) = -(a x b) / (|a||b| + a . b)  where a . b >= 0,  (|a||b| - a . b) / -(a x b)  where not.
   * Where an edge length lies outside SAFE each row is first scaled by a power of two (exact). Within
   * about 7 degrees of pi (a . b < 0 and 8 |a x b| < |a||b|) the cross product is recomputed exactly
   * from the vertices (exact_tan_half_turn); +inf where the edges point exactly opposite (psi = pi). */
  function tan_half_turn(a, b, la, lb, v, first) {
    var lo = Math.min(Math.min.apply(null, la), Math.min.apply(null, lb));
    var hi = Math.max(Math.max.apply(null, la), Math.max.apply(null, lb));
    var safe = SAFE[0] < lo && hi < SAFE[1];
    return a.map(function (p, i) {
      var ea = safe ? 0 : exponent(la[i]), eb = safe ? 0 : exponent(lb[i]);
      var ax = ldexp(p[0], -ea), ay = ldexp(p[1], -ea), bx = ldexp(b[i][0], -eb), by = ldexp(b[i][1], -eb);
      var ll = ldexp(la[i], -ea) * ldexp(lb[i], -eb);
      var d = ax * bx + ay * by, minus_cross = ay * bx - ax * by;
      if (d < 0 && 8 * Math.abs(minus_cross) < ll) return exact_tan_half_turn(v, first + i);
      return d >= 0 ? minus_cross / (ll + d) : (ll - d) / minus_cross;
    });
  }
  /* _numerics._exact_tan_half_turn: the three vertices scaled by a power of two to at most 1 (exact),
   * each edge kept with its rounding error (two-difference), the cross product's 16 exact terms
   * (Dekker) added without error (exact_sum); then (|a||b| - a . b) / -(a x b). */
  function exact_tan_half_turn(v, at) {
    var n = v.length, p = v[(at - 1 + n) % n], q = v[at], r = v[(at + 1) % n];
    var ax = two_difference(q[0], p[0]), ay = two_difference(q[1], p[1]);
    var bx = two_difference(r[0], q[0]), by = two_difference(r[1], q[1]);
    [[ax, ay], [bx, by]].forEach(function (edge) {  // each edge scaled by a power of two to at most 1
      var s = -exponent(Math.max(Math.abs(edge[0][0]), Math.abs(edge[1][0])));
      edge.forEach(function (c) { c[0] = ldexp(c[0], s); c[1] = ldexp(c[1], s); });
    });
    var terms = [];
    [[ay, bx, 1], [ax, by, -1]].forEach(function (g) {
      g[0].forEach(function (u) { g[1].forEach(function (w) { terms.push.apply(terms, two_product(g[2] * u, w)); }); });
    });
    var minus_cross = exact_sum(terms);
    var la = hypot(ax[0], ay[0]), lb = hypot(bx[0], by[0]), d = ax[0] * bx[0] + ay[0] * by[0];
    if (minus_cross === 0) return Infinity;  // exactly opposite: psi = +pi
    var t = (la * lb - d) / minus_cross, max = Number.MAX_VALUE;
    return Math.min(Math.max(t, -max), max);  // beyond the floats, but not a reversal
  }
  function sin_half(t) {  // _numerics.sin_half: sin(psi/2) = t / sqrt(1 + t^2) from t = tan(psi/2); sign(t) past 1e150
    return Math.abs(t) > 1e150 ? Math.sign(t) : t / Math.sqrt(t * t + 1);
  }
  function unit(vectors, norms) {  // _numerics.unit: outside SAFE, each row scaled to at most 1 and divided by its own norm
    var lo = Math.min.apply(null, norms), hi = Math.max.apply(null, norms);
    if (SAFE[0] < lo && hi < SAFE[1]) return vectors.map(function (p, i) { return [p[0] / norms[i], p[1] / norms[i]]; });
    return vectors.map(function (p) {
      var s = -exponent(Math.max(Math.abs(p[0]), Math.abs(p[1]))), x = ldexp(p[0], s), y = ldexp(p[1], s), h = hypot(x, y);
      return [x / h, y / h];
    });
  }
  function two_difference(x, y) { var d = x - y, z = d - x; return [d, (x - (d - z)) - (y + z)]; }  // d + e == x - y
  function exact_sum(terms) {  // _numerics.exact_sum: error-free cascades until nothing changes; the last holds the sum
    terms = terms.slice();
    for (var pass = 0; pass < 4 * terms.length + 8; pass++) {
      var changed = false;
      for (var j = 1; j < terms.length; j++) {
        var x = terms[j - 1], y = terms[j], s = x + y, z = s - x, e = (x - (s - z)) + (y - z);
        if (e !== x || s !== y) changed = true;
        terms[j - 1] = e; terms[j] = s;
      }
      if (!changed) break;
    }
    return terms[terms.length - 1];
  }

  /* _numerics.signed_area_ccw: 1/2 sum_i v_i x v_{i+1}, counter-clockwise positive, as edges times
   * heights relative to y_0, with a bound on its rounding; where the bound could matter the exact sum
   * (_exact_area). Differs from ddg only in how the first sum is added (compensated here, numpy's dot
   * there): both are within the bound, 1e-13 of the area, of the exact area, which both then return. */
  function signed_area_ccw(v) {
    var n = v.length, y0 = v[0][1], dx = [], s = [], ys = [];
    v.forEach(function (p, i) {
      var q = v[(i + 1) % n], y = p[1] - y0, yn = q[1] - y0;
      dx.push(p[0] - q[0]); s.push(y + yn); ys.push(Math.abs(y) + Math.abs(yn));
    });
    var twice = dot(dx, s);
    var bound = (6 + Math.log2(n)) * EPS * dot(dx.map(Math.abs), ys) + 8 * n * 5e-324;
    if (isFinite(twice) && isFinite(bound) && bound <= 1e-13 * Math.abs(twice)) return 0.5 * twice;
    return exact_area(v);
  }
  function split(x) { var c = 134217729 * x, high = c - (c - x); return [high, x - high]; }  // Veltkamp
  function two_product(x, y) {  // Dekker: p + e == x y exactly
    var p = x * y, a = split(x), b = split(y);
    return [p, ((a[0] * b[0] - p) + a[0] * b[1] + a[1] * b[0]) + a[1] * b[1]];
  }
  function fsum(xs) {  // math.fsum: the exact sum, rounded once (Shewchuk's partials, as CPython)
    var p = [], n, hi = 0, lo = 0, x, y;
    xs.forEach(function (x) {
      var i = 0;
      p.forEach(function (y) {
        if (Math.abs(x) < Math.abs(y)) { var t = x; x = y; y = t; }
        var h = x + y, l = y - (h - x);
        if (l) p[i++] = l;
        x = h;
      });
      p.length = i; p.push(x);
    });
    if ((n = p.length)) {
      hi = p[--n];
      while (n > 0) { x = hi; y = p[--n]; hi = x + y; lo = y - (hi - x); if (lo) break; }
      if (n > 0 && ((lo < 0 && p[n - 1] < 0) || (lo > 0 && p[n - 1] > 0))) {
        y = lo * 2; x = hi + y;
        if (y === x - hi) hi = x;
      }
    }
    return hi;
  }
  function exact_area(v) {  // _numerics._exact_area: mantissa products exactly (Dekker), summed exactly (fsum)
    var parts = [], powers = [], n = v.length;
    [[1, 0, 1, 1], [-1, 1, 0, 0]].forEach(function (f) {  // + x_i y_{i+1}, - x_{i+1} y_i
      v.forEach(function (p, i) {
        var a = v[(i + f[1]) % n][0], b = v[(i + f[2]) % n][1], ea = exponent(a), eb = exponent(b);
        two_product(ldexp(a, -ea), ldexp(b, -eb)).forEach(function (t) { parts.push(f[0] * t); powers.push(ea + eb); });
      });
    });
    var top = -Infinity;
    parts.forEach(function (t, i) { if (t !== 0) top = Math.max(top, powers[i]); });
    var shift = top === -Infinity ? 0 : top - 1000;
    return ldexp(fsum(parts.map(function (t, i) { return ldexp(t, powers[i] - shift); })), shift - 1);
  }

  /* DiscreteCurve (ddg/curve.py), closed: the same checks, in the same order, the same messages. */
  function DiscreteCurve(vertices) {
    var v = vertices, n = v.length;
    if (!Array.isArray(v) || v.some(function (p) { return !Array.isArray(p) || p.length !== 2; })) fail("vertices must have shape (n, 2)");
    if (n < 3) fail("a closed discrete curve needs at least 3 vertices, got " + n);
    v.forEach(function (p, i) { if (!isFinite(p[0]) || !isFinite(p[1])) fail("vertex " + i + " has a NaN or infinite coordinate: " + p); });
    this.vertices = v = v.map(function (p) { return [+p[0], +p[1]]; });
    this.edges = v.map(function (p, i) { var q = v[(i + 1) % n]; return [q[0] - p[0], q[1] - p[1]]; });  // e_{i+1/2} = v_{i+1} - v_i
    var l = this.edge_lengths = lengths(this.edges);                             // |e_{i+1/2}|
    var i = l.indexOf(0);  // ddg's order: equal vertices first, then an edge or a length beyond the floats
    if (i === n - 1) fail("the last vertex " + i + " repeats the first vertex 0 (" + v[0] + "); a closed curve's closing edge is implied, so leave the repeated vertex out");
    if (i >= 0) fail("vertices " + i + " and " + (i + 1) + " are equal (" + v[i] + ", as floats); consecutive vertices must differ");
    var far = l.findIndex(function (x) { return !isFinite(x); });
    if (far >= 0) fail("the edge from vertex " + far + " to vertex " + (far + 1) % n + " is longer than the largest float (about 1.8e308): scale the curve down");
    this.length = sum(l);                                                        // L = sum_i |e_{i+1/2}| (§3)
    if (!isFinite(this.length)) fail("the curve's length is beyond the largest float (about 1.8e308): scale it down");
    this.tangents = unit(this.edges, l);                                         // T = e / |e|
    this.normals = J(this.tangents);                                             // N_{i+1/2} = J T_{i+1/2}
    this.tan_half_psi = tan_half_turn(previous(this.edges), this.edges, previous(l), l, v, 0);  // tan(psi_i / 2)
    this.reversals = [];
    this.tan_half_psi.forEach(function (t, i) { if (t === Infinity) this.reversals.push(i); }, this);
    this.turning_angles = this.tan_half_psi.map(function (t) { return Math.max(2 * Math.atan(t), ABOVE_MINUS_PI); });  // psi_i (§3.1)
    var half = l.map(function (x) { return x / 2; }), hp = previous(half);
    this.dual_lengths = half.map(function (h, i) { return hp[i] + h; });        // A_i = (|e_{i-1/2}| + |e_{i+1/2}|) / 2 (§3)
  }
  var C = DiscreteCurve.prototype;
  function getter(name, f) { Object.defineProperty(C, name, {get: f}); }

  getter("turning_number", function () {  // sum_i psi_i / (2 pi) (§3.2), undefined where psi = pi
    if (this.reversals.length) fail("the turning number is not defined: the curve turns straight back at vertex " + this.reversals[0] + " (its two edges point in exactly opposite directions), where a turn of +pi and one of -pi are equally right");
    return Math.round(sum(this.turning_angles) / (2 * Math.PI));
  });
  getter("signed_area", function () {  // -1/2 sum_i v_i x v_{i+1}, positive for a clockwise curve
    var area = -signed_area_ccw(this.vertices);
    if (!isFinite(area)) fail("the enclosed area is larger than the largest float (about 1.8e308); scale the curve down");
    return area;
  });
  getter("bisector_normals", function () {  // N_i: N_{i-1/2} turned clockwise by psi_i / 2, the direction of grad L
    var Np = previous(this.normals), Tp = previous(this.tangents);
    return this.tan_half_psi.map(function (t, i) {
      var cos = 1 / hypot(1, t), sin = Math.sign(t) / hypot(1, 1 / t);
      return [cos * Np[i][0] + sin * Tp[i][0], cos * Np[i][1] + sin * Tp[i][1]];
    });
  });
  C.curvature = function (kind) {  // k_i by the lecture's formulas, with 2 A_i = |e_{i-1/2}| + |e_{i+1/2}|
    choose(kind === undefined ? "angle" : kind, CURVATURES, "curvature kind");
    kind = kind || "angle";
    // _numerics.curvature: psi/2, sin(psi/2) or tan(psi/2) over A_i / 2 = (|e_{i-1/2}| + |e_{i+1/2}|) / 4
    var psi = this.turning_angles, t = this.tan_half_psi, l = this.edge_lengths, lp = previous(l);
    var k = t.map(function (ti, i) {
      var half_A = (lp[i] + l[i]) * 0.25;
      if (kind === "angle") return Math.max(Math.atan(ti), ABOVE_MINUS_PI / 2) / half_A;  // eq. (1): 2 psi / (2 A)
      if (kind === "sine") return sin_half(ti) / half_A;                                  // eq. (3): 4 sin(psi/2) / (2 A)
      return ti / half_A;                                                                 // eq. (4): 4 tan(psi/2) / (2 A)
    });
    if (kind === "tangent" && this.reversals.length) fail("the tangent curvature (eq. 4) diverges at vertex " + this.reversals[0] + ": the curve turns straight back there (psi = pi)");
    var j = k.findIndex(function (x) { return !isFinite(x); });
    if (j >= 0) fail("the " + kind + " curvature at vertex " + j + " is beyond the largest float (a turn of " + (psi[j] * 180 / Math.PI).toPrecision(6) + " degrees between edges " + this.dual_lengths[j].toPrecision(3) + " long on average)");
    return k;
  };
  C.total_curvature = function (kind) {  // <k, 1> = sum_i A_i k_i, summed from the angles
    kind = kind || "angle";
    this.curvature(kind);  // its refusals
    if (kind === "angle") return sum(this.turning_angles);
    var total = 2 * sum(kind === "sine" ? this.tan_half_psi.map(sin_half) : this.tan_half_psi);
    if (!isFinite(total)) fail("the total " + kind + " curvature is beyond the largest float (about 1.8e308)");
    return total;
  };
  C.length_gradient = function () {  // (grad L)_j = (T_{j-1/2} - T_{j+1/2}) / A_j (§3.3, eq. 2)
    var T = this.tangents, Tp = previous(T), A = this.dual_lengths;
    var g = T.map(function (t, i) { return [(Tp[i][0] - t[0]) / A[i], (Tp[i][1] - t[1]) / A[i]]; });
    var j = g.findIndex(function (x) { return !isFinite(x[0]) || !isFinite(x[1]); });
    if (j >= 0) fail("the gradient of length at vertex " + j + " is beyond the largest float (its edges are " + A[j].toPrecision(3) + " long on average)");
    return g;
  };
  C.inflated_area = function (eps, method) {  // the area inflated by eps >= 0 along the normals (§3.4)
    method = choose(method === undefined ? "minkowski" : method, INFLATIONS, "inflation method");
    if (typeof eps !== "number") fail("eps must be a real number, got " + eps);
    if (!isFinite(eps)) fail("eps must be finite, got " + eps);
    if (eps < 0) fail("eps must be >= 0, got " + eps + ": erosion is not supported (the lecture's formulas hold only until an edge collapses); inflating the reversed curve moves the edges the other way");
    if (eps > 0 && this.signed_area < 0) fail("the curve is counter-clockwise (its signed area is negative): its normals point inward, so inflating it would erode it, which the formulas describe only until an edge collapses; reverse it (vertices[::-1]) to inflate it outward");
    if (eps === 0) return this.signed_area;
    if (method === "offset" && this.reversals.length) fail("no offset corner at vertex " + this.reversals[0] + ": the curve turns straight back there (psi = pi), so eps^2 tan(psi/2) is infinite");
    var corners = method === "minkowski"
      ? 0.5 * sum(this.turning_angles)               // A_0 + eps L + eps^2 / 2 sum_i psi_i (disk sectors)
      : sum(this.tan_half_psi);                      // A_0 + eps L + eps^2 sum_i tan(psi_i / 2) (kites)
    var area = this.signed_area + eps * this.length + eps * eps * corners;
    if (!isFinite(area)) fail("the inflated area is larger than the largest float (about 1.8e308); scale the curve or eps down");
    return area;
  };

  /* ddg/flow.py: dv_i/dt = -k_i N_i, one forward Euler step with the step of flow(method="explicit"). */
  function speed_factor(c, kind) {  // g_i = k_i / k_i^sine
    return c.turning_angles.map(function (psi) {
      var half = psi / 2, y = Math.PI * (half / Math.PI || 1e-20);  // np.sinc(half / pi)
      return kind === "sine" ? 1 : kind === "angle" ? 1 / (Math.sin(y) / y) : 1 / Math.cos(half);
    });
  }
  function stable_step(c, kind, safety) {  // safety * min(h A / (2 g), h / |k|) at the worst vertex
    var l = c.edge_lengths, lp = previous(l), A = c.dual_lengths, g = speed_factor(c, kind), k = c.curvature(kind);
    var shorter = l.map(function (x, i) { return Math.min(x, lp[i]); });
    var diffusion = Math.min.apply(null, shorter.map(function (h, i) { return h * A[i] / (2 * g[i]); }));
    var travel = Math.min.apply(null, shorter.map(function (h, i) { return h / Math.abs(k[i]); }));
    return safety * Math.min(diffusion, travel);
  }
  function remaining_lifetime(c, kind) {  // A / |dA/dt| with dA/dt = -sum_i A_i k_i cos(psi_i/2), else L / |dL/dt|
    var k = c.curvature(kind), A = c.dual_lengths, psi = c.turning_angles, area = c.signed_area;
    var rate = -sum(A.map(function (a, i) { return a * k[i] * Math.cos(psi[i] / 2); }));
    if (c.turning_number !== 0 && area * rate < 0) return -area / rate;
    var ks = c.curvature("sine");
    return c.length / sum(A.map(function (a, i) { return a * k[i] * ks[i]; }));
  }
  function velocity(c, kind) {  // -k_i N_i
    var k = c.curvature(kind);
    return c.bisector_normals.map(function (N, i) { return [-k[i] * N[0], -k[i] * N[1]]; });
  }
  function reversal(c) {
    if (c.reversals.length) fail("the curve turns straight back at vertex " + c.reversals[0] + " (psi = pi): neither its turning number nor the tangent curvature is defined there");
  }
  /* flow(curve, kind, method="explicit", max_steps=1): in the curve's frame ((v - v_0) / 2^e, t / 4^e,
   * 2^e about its length) the step min(stable_step(safety 0.25), 0.02 remaining_lifetime); the same
   * refusals and stop rules (length0: the length the run started with). Returns {dt, vertices}. */
  function flow_step(vertices, kind, length0) {
    choose(kind, CURVATURES, "curvature kind");
    var c = new DiscreteCurve(vertices), o = c.vertices[0], e = exponent(c.length), n = c.vertices.length;
    reversal(c);
    if (c.length < 0.05 * length0) fail("the curve has nearly vanished (its length fell below 0.05 of the initial length)");
    if (Math.min.apply(null, c.edge_lengths) < 0.02 * c.length / n) fail("an edge fell below 0.02 of the mean edge (vertices bunch up)");
    var local = new DiscreteCurve(c.vertices.map(function (p) { return [ldexp(p[0] - o[0], -e), ldexp(p[1] - o[1], -e)]; }));
    reversal(local);
    var lifetime = remaining_lifetime(local, kind);
    if (!(lifetime > 0 && lifetime < Infinity)) fail("stopped at t = 0: the curve is degenerate (its remaining lifetime is 0 to rounding)");
    var life = ldexp(lifetime, 2 * e);
    if (!(life > 2.2250738585072014e-308 && life < Infinity)) fail("the curve's lifetime under the flow is beyond the range of floats in which its steps can be told apart: scale the curve (times scale with the square of its size)");
    var step = Math.min(stable_step(local, kind, 0.25), 0.02 * lifetime);
    if (!(step > 1e-12 * lifetime)) fail("the step fell below 1e-12 of the curve's expected lifetime: the curve is about to vanish or degenerate");
    var vel = velocity(local, kind);
    var next = new DiscreteCurve(local.vertices.map(function (p, i) { return [p[0] + step * vel[i][0], p[1] + step * vel[i][1]]; }));
    reversal(next);
    if (next.turning_number !== local.turning_number) fail("the turning number changed (the step was too large)");
    return {dt: ldexp(step, 2 * e), vertices: next.vertices.map(function (p) { return [ldexp(p[0], e) + o[0], ldexp(p[1], e) + o[1]]; })};
  }

  window.ddgLab = {CURVATURES: CURVATURES, INFLATIONS: INFLATIONS, DiscreteCurve: DiscreteCurve, tan_half_turn: tan_half_turn,
                   lengths: lengths, signed_area_ccw: signed_area_ccw, flow_step: flow_step, ldexp: ldexp, exponent: exponent};
})();
