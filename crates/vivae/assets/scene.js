// Draws a scenario with robots, trails and sensor readings on a canvas.
// Shared by the viewer and report.html; plain browser JavaScript, no library.
"use strict";
var VivaeScene = (function () {
  // The robot colours of vivae_sim::draw::robot_color (figures use the same).
  var COLORS = ["#e41a1c", "#377eb8", "#ff7f00", "#984ea3", "#ffff33", "#00d0d0",
    "#f781bf", "#a65628", "#4daf4a", "#ffffff"];

  function color(i) { return COLORS[i % COLORS.length]; }

  // Red (0: grass / far) to white (1: road / near), as the PNG figures.
  function readingColor(v) {
    v = Math.max(0, Math.min(1, v));
    var g = Math.round(48 + v * 207);
    return "rgb(255," + g + "," + g + ")";
  }

  // Draws dots [{x, y, v}] coloured by reading. Many dots are batched into 16
  // colour levels (one fill per level) so that 32x96 sensors stay cheap.
  function drawDots(c, dots, size, colorOf) {
    colorOf = colorOf || readingColor;
    if (dots.length <= 400) {
      c.lineWidth = 0.4;
      c.strokeStyle = "#000";
      for (var k = 0; k < dots.length; k++) {
        c.fillStyle = colorOf(dots[k].v);
        c.beginPath();
        c.arc(dots[k].x, dots[k].y, size, 0, 2 * Math.PI);
        c.fill();
        c.stroke();
      }
      return;
    }
    var levels = 16, paths = [];
    for (var l = 0; l < levels; l++) { paths.push(new Path2D()); }
    var lo = colorOf === readingColor ? 0 : -1;
    var d = Math.max(1.2, size);
    for (var j = 0; j < dots.length; j++) {
      var t = (Math.max(lo, Math.min(1, dots[j].v)) - lo) / (1 - lo);
      paths[Math.min(levels - 1, Math.floor(t * levels))].rect(dots[j].x - d / 2, dots[j].y - d / 2, d, d);
    }
    for (var m = 0; m < levels; m++) {
      c.fillStyle = colorOf(lo + (m + 0.5) / levels * (1 - lo));
      c.fill(paths[m]);
    }
  }

  function Scene(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.ready = false;
    this.scene = null;
    this.bg = null;
  }

  // Sets the arena picture ({width, height, robot_radius, svg}); calls back once it is drawable.
  Scene.prototype.setScene = function (scene, onready) {
    var self = this;
    this.scene = scene;
    this.ready = false;
    this.canvas.width = Math.round(scene.width);
    this.canvas.height = Math.round(scene.height);
    var img = new Image();
    img.onload = function () { self.ready = true; if (onready) { onready(); } };
    img.onerror = function () { self.ready = true; if (onready) { onready(); } };
    img.src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(scene.svg);
    this.bg = img;
  };

  // World coordinates of a mouse event on the canvas.
  Scene.prototype.toWorld = function (ev) {
    var r = this.canvas.getBoundingClientRect();
    return {
      x: (ev.clientX - r.left) * this.canvas.width / r.width,
      y: (ev.clientY - r.top) * this.canvas.height / r.height
    };
  };

  // Index of the robot under world point p, or -1.
  Scene.prototype.robotAt = function (robots, p) {
    var r = this.scene ? this.scene.robot_radius * 2.5 : 15;
    for (var i = 0; i < robots.length; i++) {
      var dx = robots[i].x - p.x, dy = robots[i].y - p.y;
      if (dx * dx + dy * dy <= r * r) { return i; }
    }
    return -1;
  };

  // robots: [{x, y, h}] (h: heading in radians, 0 = up, clockwise);
  // trails: per robot [x0, y0, x1, y1, ...] or null; opts: {selected, sensors: [{x, y, v}],
  // colors: per robot a CSS colour (default: the figures' robot colours)}.
  Scene.prototype.draw = function (robots, trails, opts) {
    var c = this.ctx, w = this.canvas.width, h = this.canvas.height;
    opts = opts || {};
    c.clearRect(0, 0, w, h);
    if (this.bg && this.ready) { c.drawImage(this.bg, 0, 0, w, h); }
    var rr = this.scene ? this.scene.robot_radius : 6;
    var i, k;
    if (trails) {
      c.lineWidth = 1.5;
      c.lineJoin = "round";
      for (i = 0; i < trails.length; i++) {
        var t = trails[i];
        if (!t || t.length < 4) { continue; }
        c.strokeStyle = opts.colors ? opts.colors[i] : color(i);
        c.globalAlpha = 0.9;
        c.beginPath();
        c.moveTo(t[0], t[1]);
        for (k = 2; k + 1 < t.length; k += 2) { c.lineTo(t[k], t[k + 1]); }
        c.stroke();
        c.globalAlpha = 1;
      }
    }
    if (opts.sensors) { drawDots(c, opts.sensors, Math.max(1, Math.min(3, rr * 0.35))); }
    for (i = 0; i < robots.length; i++) {
      var r = robots[i];
      var ax = Math.sin(r.h), ay = -Math.cos(r.h);
      if (opts.selected === i) {
        c.strokeStyle = "#000";
        c.lineWidth = 1.5;
        c.setLineDash([3, 2]);
        c.beginPath();
        c.arc(r.x, r.y, rr * 2.2, 0, 2 * Math.PI);
        c.stroke();
        c.setLineDash([]);
      }
      c.fillStyle = opts.colors ? opts.colors[i] : color(i);
      c.strokeStyle = "#000";
      c.lineWidth = 1;
      c.beginPath();
      c.arc(r.x, r.y, rr, 0, 2 * Math.PI);
      c.fill();
      c.stroke();
      c.lineWidth = 1.5;
      c.beginPath();
      c.moveTo(r.x, r.y);
      c.lineTo(r.x + ax * rr, r.y + ay * rr);
      c.stroke();
    }
  };

  return { Scene: Scene, color: color, readingColor: readingColor, drawDots: drawDots };
})();
