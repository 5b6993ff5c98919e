// Small SVG plots (lines, stacked areas) and the per-generation table.
// Shared by the viewer and report.html; plain browser JavaScript, no library.
"use strict";
var VivaePlots = (function () {
  // T leaves room above the plot for the series legend, so that it never covers a curve.
  var W = 640, H = 260, L = 52, R = 12, T = 26, B = 34;

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
    for (var v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) { out.push(v); }
    return out;
  }

  function fmt(v) {
    var a = Math.abs(v);
    if (a !== 0 && (a < 0.01 || a >= 1e5)) { return v.toExponential(1); }
    return String(Math.round(v * 1000) / 1000);
  }

  function axes(x0, x1, y0, y1, xlabel, ylabel) {
    var sx = function (x) { return L + (x - x0) / ((x1 - x0) || 1) * (W - L - R); };
    var sy = function (y) { return H - B - (y - y0) / ((y1 - y0) || 1) * (H - T - B); };
    var s = "<rect x='" + L + "' y='" + T + "' width='" + (W - L - R) + "' height='" + (H - T - B) +
      "' fill='#fff' stroke='#999'/>";
    niceTicks(y0, y1, 5).forEach(function (v) {
      s += "<line x1='" + L + "' x2='" + (W - R) + "' y1='" + sy(v) + "' y2='" + sy(v) + "' stroke='#eee'/>";
      s += "<text x='" + (L - 4) + "' y='" + (sy(v) + 4) + "' font-size='11' text-anchor='end'>" + fmt(v) + "</text>";
    });
    niceTicks(x0, x1, 8).forEach(function (v) {
      s += "<text x='" + sx(v) + "' y='" + (H - B + 14) + "' font-size='11' text-anchor='middle'>" + fmt(v) + "</text>";
    });
    s += "<text x='" + ((L + W - R) / 2) + "' y='" + (H - 4) + "' font-size='12' text-anchor='middle'>" + esc(xlabel) + "</text>";
    s += "<text x='12' y='" + ((T + H - B) / 2) + "' font-size='12' text-anchor='middle' transform='rotate(-90 12 " +
      ((T + H - B) / 2) + ")'>" + esc(ylabel) + "</text>";
    return { svg: s, sx: sx, sy: sy };
  }

  function wrap(inner) {
    return "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 " + W + " " + H + "' font-family='sans-serif'>" + inner + "</svg>";
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

  return { lines: lines, stacked: stacked, table: table, esc: esc };
})();
