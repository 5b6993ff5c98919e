// Small SVG plots (lines, stacked areas) and the per-generation table.
// Shared by the viewer and report.html; plain browser JavaScript, no library.
"use strict";
var VivaePlots = (function () {
  // T leaves room above the plot for the series legend, so that it never covers a curve.
  var W = 640, H = 260, L = 52, R = 12, T = 26, B = 34, WIDE = W, HIGH = H;

  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (ch) {
      return { "&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;" }[ch];
    });
  }

  function niceTicks(lo, hi, n) {
    if (!(hi > lo)) { hi = lo + 1; }
    var step = Math.pow(10, Math.floor(Math.log10((hi - lo) / n)));
    var err = (hi - lo) / n / step;
    if (err >= 5) { step *= 5; } else if (err >= 2) { step *= 2; }
    var out = [];
    // Whole multiples of the step: 0 is 0, not the sum of steps' rounding errors (-5.6e-17).
    for (var k = Math.ceil(lo / step); k * step <= hi + 1e-9 * step; k++) { out.push(k * step); }
    return out;
  }

  function fmt(v) {
    var a = Math.abs(v);
    if (a !== 0 && (a < 0.01 || a >= 1e5)) { return v.toExponential(1); }
    return String(Math.round(v * 1000) / 1000);
  }

  // size: optional [width, height] of the plot (default W × H).
  function axes(x0, x1, y0, y1, xlabel, ylabel, size) {
    var W = size ? size[0] : WIDE, H = size ? size[1] : HIGH;
    var sx = function (x) { return L + (x - x0) / ((x1 - x0) || 1) * (W - L - R); };
    var sy = function (y) { return H - B - (y - y0) / ((y1 - y0) || 1) * (H - T - B); };
    var s = "<rect x='" + L + "' y='" + T + "' width='" + (W - L - R) + "' height='" + (H - T - B) +
      "' fill='#fff' stroke='#999'/>";
    niceTicks(y0, y1, 5).forEach(function (v) {
      s += "<line x1='" + L + "' x2='" + (W - R) + "' y1='" + sy(v) + "' y2='" + sy(v) + "' stroke='#eee'/>";
      s += "<text x='" + (L - 4) + "' y='" + (sy(v) + 4) + "' font-size='11' text-anchor='end'>" + fmt(v) + "</text>";
    });
    // Generations are whole: a short run's axis has no 1.5.
    niceTicks(x0, x1, 8).filter(function (v) { return xlabel !== "generation" || Math.abs(v - Math.round(v)) < 1e-9; }).forEach(function (v) {
      s += "<text x='" + sx(v) + "' y='" + (H - B + 14) + "' font-size='11' text-anchor='middle'>" + fmt(v) + "</text>";
    });
    s += "<text x='" + ((L + W - R) / 2) + "' y='" + (H - 4) + "' font-size='12' text-anchor='middle'>" + esc(xlabel) + "</text>";
    s += "<text x='12' y='" + ((T + H - B) / 2) + "' font-size='12' text-anchor='middle' transform='rotate(-90 12 " +
      ((T + H - B) / 2) + ")'>" + esc(ylabel) + "</text>";
    return { svg: s, sx: sx, sy: sy };
  }

  function wrap(inner, size) {
    return "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 " + (size ? size[0] : W) + " " + (size ? size[1] : H) +
      "' font-family='sans-serif'>" + inner + "</svg>";
  }

  // Matplotlib's viridis at t in [0, 1] (eleven samples, as the figures' colour scale).
  var VIRIDIS = [[68, 1, 84], [72, 36, 117], [65, 68, 135], [53, 95, 141], [42, 120, 142], [33, 145, 140],
    [34, 168, 132], [68, 191, 112], [122, 209, 81], [189, 223, 38], [253, 231, 37]];
  function viridis(t) {
    t = isFinite(t) ? Math.max(0, Math.min(1, t)) : 0;
    var x = t * 10, k = Math.min(9, Math.floor(x)), f = x - k, a = VIRIDIS[k], b = VIRIDIS[k + 1];
    return "rgb(" + [0, 1, 2].map(function (c) { return Math.round(a[c] + f * (b[c] - a[c])); }).join(",") + ")";
  }

  // "name value, …" of a member's coordinates.
  function named(names, values) {
    return values.map(function (v, i) { return (names[i] || "#" + i) + " " + fmt(v); }).join(", ");
  }

  // A MAP-Elites archive on a 2-D grid as a heat map: one square per cell
  // coloured by its elite's fitness (viridis), empty cells grey; each
  // square's tooltip names the elite. grid: {lower, upper, bins}; elites:
  // [[cell, fitness, generation, behaviour]]; names: the two coordinates'.
  function heatmap(grid, elites, names) {
    var size = [640, 480];
    var a = axes(grid.lower[0], grid.upper[0], grid.lower[1], grid.upper[1], names[0], names[1], size);
    var lo = Infinity, hi = -Infinity;
    elites.forEach(function (e) { if (isFinite(e[1])) { lo = Math.min(lo, e[1]); hi = Math.max(hi, e[1]); } });
    if (!(hi - lo > 1e-12)) { lo -= 0.5; hi += 0.5; }
    var byCell = {};
    elites.forEach(function (e) { byCell[e[0]] = e; });
    var w = [0, 1].map(function (d) { return (grid.upper[d] - grid.lower[d]) / grid.bins[d]; });
    var s = a.svg;
    for (var c = 0; c < grid.bins[0] * grid.bins[1]; c++) {
      var i = Math.floor(c / grid.bins[1]), j = c % grid.bins[1], e = byCell[c];
      var x0 = a.sx(grid.lower[0] + i * w[0]), x1 = a.sx(grid.lower[0] + (i + 1) * w[0]);
      var y0 = a.sy(grid.lower[1] + (j + 1) * w[1]), y1 = a.sy(grid.lower[1] + j * w[1]);
      var tip = e ? "cell " + c + ": fitness " + e[1].toFixed(3) + ", generation " + e[2] + " (" + named(names, e[3]) +
        "); drive it: vivae view RUN --elite " + c : "cell " + c + ": empty";
      s += "<rect class='cell" + (e ? " elite" : "") + "' data-cell='" + c + "' x='" + x0.toFixed(1) + "' y='" + y0.toFixed(1) +
        "' width='" + (x1 - x0).toFixed(1) + "' height='" + (y1 - y0).toFixed(1) + "' fill='" +
        (e ? viridis((e[1] - lo) / (hi - lo)) : "#ebebeb") + "' stroke='#fff' stroke-width='0.5'><title>" + esc(tip) +
        "</title></rect>";
    }
    // The colour scale, in the legend's place above the plot.
    var bar = 160, x = size[0] - R - bar - 44;
    for (var k = 0; k < 32; k++) {
      s += "<rect x='" + (x + k * bar / 32).toFixed(1) + "' y='" + (T - 17) + "' width='" + (bar / 32 + 0.3).toFixed(1) +
        "' height='10' fill='" + viridis(k / 31) + "'/>";
    }
    s += "<text x='" + (x - 4) + "' y='" + (T - 8) + "' font-size='11' text-anchor='end'>fitness " + fmt(lo) + "</text>";
    s += "<text x='" + (x + bar + 4) + "' y='" + (T - 8) + "' font-size='11'>" + fmt(hi) + "</text>";
    s += "<text x='" + L + "' y='" + (T - 8) + "' font-size='11'>" + elites.length + " of " + grid.bins[0] * grid.bins[1] +
      " cells filled</text>";
    return wrap(s, size);
  }

  // An NSGA-II front over its first two objectives: members as points joined
  // in order of the first, numbered as front.csv (equal points share a label).
  // front: [[member, fitness, objectives]]; names: the objectives' axis names.
  function front(members, names) {
    var size = [640, 420];
    if (!members.length) { return wrap("<text x='20' y='40'>no front recorded</text>", size); }
    var range = function (d) {
      var lo = Infinity, hi = -Infinity;
      members.forEach(function (m) { var v = m[2][d]; if (isFinite(v) && Math.abs(v) < 1e300) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
      var pad = hi - lo > 1e-12 ? 0.06 * (hi - lo) : 0.5;
      return [lo - pad, hi + pad];
    };
    var rx = range(0), ry = range(1);
    var a = axes(rx[0], rx[1], ry[0], ry[1], names[0], names[1], size), s = a.svg;
    var points = [];
    members.forEach(function (m) {
      var p = points.filter(function (q) { return q.x === m[2][0] && q.y === m[2][1]; })[0];
      if (p) { p.members.push(m[0]); } else { points.push({ x: m[2][0], y: m[2][1], members: [m[0]], m: m }); }
    });
    points = points.filter(function (p) { return isFinite(a.sx(p.x)) && isFinite(a.sy(p.y)) && Math.abs(p.x) < 1e300 && Math.abs(p.y) < 1e300; });
    var sorted = points.slice().sort(function (p, q) { return p.x - q.x || p.y - q.y; });
    s += "<polyline fill='none' stroke='#e66101' stroke-width='2' points='" +
      sorted.map(function (p) { return a.sx(p.x).toFixed(1) + "," + a.sy(p.y).toFixed(1); }).join(" ") + "'/>";
    points.forEach(function (p) {
      var ms = p.members, label = ms.length === 1 ? String(ms[0]) :
        (ms[ms.length - 1] - ms[0] + 1 === ms.length ? ms[0] + "\u2013" + ms[ms.length - 1] : ms[0] + ", \u2026");
      var tip = "front member" + (ms.length > 1 ? "s " : " ") + label + ": fitness " + p.m[1].toFixed(3) + " (" +
        named(names, p.m[2]) + "); drive it: vivae view RUN --front " + ms[0];
      s += "<circle class='member' cx='" + a.sx(p.x).toFixed(1) + "' cy='" + a.sy(p.y).toFixed(1) +
        "' r='6' fill='#e66101' stroke='#fff'><title>" + esc(tip) + "</title></circle>";
      if (points.length <= 16) {
        s += "<text x='" + (a.sx(p.x) + 8).toFixed(1) + "' y='" + (a.sy(p.y) - 8).toFixed(1) + "' font-size='12'>" + esc(label) + "</text>";
      }
    });
    s += "<text x='" + L + "' y='" + (T - 8) + "' font-size='11'>" + members.length + " members" +
      (points.length < members.length ? " at " + points.length + " points" : "") + "</text>";
    return wrap(s, size);
  }

  // series: [{name, color, values}] over xs (same length); returns SVG markup.
  function lines(xs, series, xlabel, ylabel) {
    if (!xs.length) { return wrap("<text x='20' y='40'>no generation yet</text>"); }
    var lo = Infinity, hi = -Infinity;
    series.forEach(function (s) {
      s.values.forEach(function (v) { if (isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
    });
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (lo > 0 && lo < (hi - lo)) { lo = 0; }
    // Headroom, so that a flat best curve is not drawn on the frame's top edge.
    hi += (hi - lo) * 0.05 || Math.max(Math.abs(hi) * 0.05, 0.05);
    var a = axes(xs[0], xs[xs.length - 1], lo, hi, xlabel, ylabel);
    var s = a.svg;
    series.forEach(function (ser, k) {
      var pts = [];
      for (var i = 0; i < xs.length; i++) {
        if (isFinite(ser.values[i])) { pts.push(a.sx(xs[i]).toFixed(1) + "," + a.sy(ser.values[i]).toFixed(1)); }
      }
      s += "<polyline fill='none' stroke='" + ser.color + "' stroke-width='1.6' points='" + pts.join(" ") + "'/>";
      s += "<rect class='legend' x='" + (L + k * 90) + "' y='" + (T - 17) + "' width='10' height='10' fill='" + ser.color + "'/>";
      s += "<text class='legend' x='" + (L + 14 + k * 90) + "' y='" + (T - 8) + "' font-size='11'>" + esc(ser.name) + "</text>";
    });
    return wrap(s);
  }

  // Species sizes over generations as the classic NEAT stacked-area plot.
  // perGen: one [[species id, members], ...] list per generation.
  function stacked(perGen, firstGeneration) {
    if (!perGen.length) { return wrap("<text x='20' y='40'>no generation yet</text>"); }
    var order = [], seen = {};
    perGen.forEach(function (g) {
      g.forEach(function (p) { if (!seen[p[0]]) { seen[p[0]] = true; order.push(p[0]); } });
    });
    var total = 0;
    perGen.forEach(function (g) { var t = 0; g.forEach(function (p) { t += p[1]; }); total = Math.max(total, t); });
    var x0 = firstGeneration, x1 = firstGeneration + Math.max(perGen.length - 1, 1);
    var a = axes(x0, x1, 0, total || 1, "generation", "individuals per species");
    var s = a.svg;
    var base = perGen.map(function () { return 0; });
    order.forEach(function (id, k) {
      var top = [], bottom = [];
      perGen.forEach(function (g, i) {
        var n = 0;
        g.forEach(function (p) { if (p[0] === id) { n = p[1]; } });
        bottom.push(base[i]);
        base[i] += n;
        top.push(base[i]);
      });
      var pts = [];
      var xAt = function (i) { return perGen.length === 1 ? a.sx(x0 + i) : a.sx(x0 + i); };
      for (var i = 0; i < perGen.length; i++) { pts.push(xAt(i).toFixed(1) + "," + a.sy(top[i]).toFixed(1)); }
      for (var j = perGen.length - 1; j >= 0; j--) { pts.push(xAt(j).toFixed(1) + "," + a.sy(bottom[j]).toFixed(1)); }
      var hue = (id * 137.508) % 360;
      s += "<polygon points='" + pts.join(" ") + "' fill='hsl(" + hue.toFixed(0) + ",60%," + (k % 2 ? 62 : 50) +
        "%)' stroke='#fff' stroke-width='0.3'><title>species " + id + "</title></polygon>";
    });
    return wrap(s);
  }

  // Decimals of each table column: fitnesses 4, mean CPPN sizes 2, counts none;
  // every cell of a column alike (8.0000, not 8 beside 8.0600).
  var DECIMALS = { best: 4, mean: 4, median: 4, worst: 4, cppn_nodes: 2, cppn_links: 2 };

  // The per-generation table from generations.csv rows.
  function table(rows) {
    var cols = ["generation", "best", "mean", "median", "worst", "species", "cppn_nodes", "cppn_links", "substrate_links"];
    var h = "<table><thead><tr>" + cols.map(function (c) { return "<th>" + esc(c.replace("_", " ")) + "</th>"; }).join("") +
      "</tr></thead><tbody>";
    rows.forEach(function (r) {
      h += "<tr>" + cols.map(function (c) {
        var v = r[c];
        var d = DECIMALS[c];
        return "<td>" + (typeof v === "number" && d !== undefined ? v.toFixed(d) : esc(v)) + "</td>";
      }).join("") + "</tr>";
    });
    return h + "</tbody></table>";
  }

  return { lines: lines, stacked: stacked, table: table, esc: esc, heatmap: heatmap, front: front, named: named };
})();
