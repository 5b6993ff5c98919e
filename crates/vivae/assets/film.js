// A task's film: its replay's steps as shapes (lines, polygons, discs) in the
// task's own coordinates, y up, over a backdrop; drawn the same for any task.
"use strict";
var VivaeFilm = (function () {
  // Draws `shapes` of `film` on the 2-d context `g` of a `w` x `h` canvas;
  // a shape is [kind, colour, size, [x0, y0, x1, y1, ...]].
  function drawShapes(g, film, shapes, w, h) {
    var v = film.view, sx = w / (v[2] - v[0]), sy = h / (v[3] - v[1]);
    shapes.forEach(function (s) {
      var kind = s[0], size = s[2], p = s[3];
      g.fillStyle = s[1];
      g.strokeStyle = s[1];
      g.beginPath();
      for (var i = 0; i + 1 < p.length; i += 2) {
        var x = (p[i] - v[0]) * sx, y = (v[3] - p[i + 1]) * sy;
        if (kind === "circle") {
          g.arc(x, y, Math.max(size * sx, 0.5), 0, 2 * Math.PI);
        } else if (i === 0) {
          g.moveTo(x, y);
        } else {
          g.lineTo(x, y);
        }
      }
      if (kind === "line") {
        g.lineWidth = Math.max(size * sx, 1);
        g.lineCap = "round";
        g.lineJoin = "round";
        g.stroke();
      } else {
        g.closePath();
        g.fill();
      }
    });
  }

  // Animates `film` in the report's film section: a button per episode,
  // play/pause, a step slider and a speed; `window.vivaeFilm` shows its state.
  function show(film, label) {
    var $ = function (id) { return document.getElementById(id); };
    var canvas = $("filmcanvas"), g = canvas.getContext("2d");
    // Rendered pictures are shown at most twice their size; drawn films at 720 px.
    var rendered = film.frames.length > 0 && !!film.frames[0].image;
    var v = film.view, width = rendered ? Math.min(720, 2 * (v[2] - v[0])) : 720;
    canvas.width = width;
    canvas.height = Math.round(width * (v[3] - v[1]) / (v[2] - v[0]));
    // Each episode's first frame and its frame count, and its return.
    var episodes = [];
    film.frames.forEach(function (f, i) {
      var last = episodes[episodes.length - 1];
      if (!last || last.episode !== f.episode) {
        last = { episode: f.episode, start: i, steps: 0, total: 0 };
        episodes.push(last);
      }
      last.steps += 1;
      last.total += f.reward;
    });
    // A host's rendered frames carry their picture (a PNG data URL), decoded once.
    var images = film.frames.map(function (f) {
      if (!f.image) { return null; }
      var img = new Image();
      img.src = f.image;
      return img;
    });
    var state = { episode: 0, t: 0, playing: true, frames: 0, images: 0 };
    window.vivaeFilm = state;
    $("film").style.display = "";

    function render() {
      var ep = episodes[state.episode], f = film.frames[ep.start + state.t];
      g.fillStyle = "#ffffff";
      g.fillRect(0, 0, canvas.width, canvas.height);
      drawShapes(g, film, film.backdrop, canvas.width, canvas.height);
      drawShapes(g, film, f.shapes, canvas.width, canvas.height);
      var img = images[ep.start + state.t];
      if (img && img.complete && img.naturalWidth) {
        g.drawImage(img, 0, 0, canvas.width, canvas.height);
        state.images += 1;
      }
      var sofar = 0;
      for (var k = 0; k <= state.t; k++) { sofar += film.frames[ep.start + k].reward; }
      $("filmslider").value = state.t;
      $("filmstep").textContent = (state.t + 1) + " / " + ep.steps;
      $("filminfo").textContent = label + ". Episode " + (state.episode + 1) + " of " + episodes.length +
        " (return " + +ep.total.toFixed(3) + "): step " + (f.step === undefined ? state.t + 1 : f.step) + ", reward " + +f.reward.toFixed(3) +
        ", return so far " + +sofar.toFixed(3) + ".";
      state.frames += 1;
    }
    function choose(k) {
      state.episode = k;
      state.t = 0;
      $("filmslider").max = episodes[k].steps - 1;
      Array.prototype.forEach.call($("filmepisodes").children, function (b, i) { b.className = i === k ? "on" : ""; });
      render();
    }
    episodes.forEach(function (ep, k) {
      var b = document.createElement("button");
      b.textContent = "episode " + (k + 1) + ": " + +ep.total.toFixed(1);
      b.onclick = function () { choose(k); };
      $("filmepisodes").appendChild(b);
    });
    $("filmplay").onclick = function () {
      state.playing = !state.playing;
      $("filmplay").textContent = state.playing ? "Pause" : "Play";
    };
    $("filmslider").oninput = function () { state.t = parseInt($("filmslider").value, 10) || 0; render(); };
    // Plays each episode through, then the next one.
    function tick() {
      if (state.playing && episodes.length) {
        var speed = parseInt($("filmspeed").value, 10) || 1;
        if (state.t + speed < episodes[state.episode].steps) {
          state.t += speed;
          render();
        } else {
          choose((state.episode + 1) % episodes.length);
        }
      }
      window.requestAnimationFrame(tick);
    }
    if (!episodes.length) { return; }
    choose(0);
    window.requestAnimationFrame(tick);
  }

  return { show: show, drawShapes: drawShapes };
})();
