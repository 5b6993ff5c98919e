// report.html: animates the recorded trajectories and draws the run's plots.
"use strict";
(function () {
  var data = JSON.parse(document.getElementById("vivae-data").textContent);
  var $ = function (id) { return document.getElementById(id); };
  $("runname").textContent = data.title;
  document.title = "vivae report: " + data.title;
  $("config").textContent = data.config;
  $("convergence").innerHTML = data.convergence_svg;
  $("network").innerHTML = data.network_svg;
  $("scenario").innerHTML = data.scene.svg;

  var gens = data.generations.map(function (r) { return r.generation; });
  // The colours of convergence.png's curves, so that the page and the figure agree.
  $("curves").innerHTML = VivaePlots.lines(gens, [
    { name: "best", color: data.curve_colours[0], values: data.generations.map(function (r) { return r.best; }) },
    { name: "mean", color: data.curve_colours[1], values: data.generations.map(function (r) { return r.mean; }) }
  ], "generation", "fitness (px/step)");
  $("species").innerHTML = VivaePlots.stacked(data.species, 1);
  $("table").innerHTML = VivaePlots.table(data.generations);

  var scene = new VivaeScene.Scene($("scene"));
  var state = { episode: 0, t: 0, playing: true, frames: 0 };
  // Tests read this to see the animation advance.
  window.vivaeReport = state;

  function steps() { return data.episodes.length ? data.episodes[state.episode].paths[0].length / 2 - 1 : 0; }

  function robotsAt(t) {
    var ep = data.episodes[state.episode];
    return ep.paths.map(function (p) {
      var i = 2 * t, x = p[i], y = p[i + 1], h = 0;
      // Heading from the last move (the record holds positions only).
      for (var k = i; k >= 2; k -= 2) {
        var dx = p[k] - p[k - 2], dy = p[k + 1] - p[k - 1];
        if (dx * dx + dy * dy > 1e-6) { h = Math.atan2(dx, -dy); break; }
      }
      if (k < 2) {
        for (var j = i + 2; j + 1 < p.length; j += 2) {
          var ex = p[j] - p[i], ey = p[j + 1] - p[i + 1];
          if (ex * ex + ey * ey > 1e-6) { h = Math.atan2(ex, -ey); break; }
        }
      }
      return { x: x, y: y, h: h };
    });
  }

  function render() {
    if (!data.episodes.length) { return; }
    var ep = data.episodes[state.episode];
    var trails = ep.paths.map(function (p) { return p.slice(0, 2 * state.t + 2); });
    scene.draw(robotsAt(state.t), trails, {});
    $("slider").value = state.t;
    $("stepno").textContent = state.t + " / " + steps();
    state.frames += 1;
  }

  function choose(k) {
    state.episode = k;
    state.t = 0;
    var ep = data.episodes[k];
    $("slider").max = steps();
    $("epinfo").textContent = ep.label + ": fitness " + ep.fitness.toFixed(3) + " px/step, " +
      (100 * ep.on_road).toFixed(1) + "% of robot-steps on road";
    Array.prototype.forEach.call($("episodes").children, function (b, i) { b.className = i === k ? "on" : ""; });
    render();
  }

  data.episodes.forEach(function (ep, k) {
    var b = document.createElement("button");
    b.textContent = ep.label;
    b.onclick = function () { choose(k); };
    $("episodes").appendChild(b);
  });
  $("play").onclick = function () {
    state.playing = !state.playing;
    $("play").textContent = state.playing ? "Pause" : "Play";
  };
  $("slider").oninput = function () { state.t = parseInt($("slider").value, 10) || 0; render(); };

  function tick() {
    if (state.playing && data.episodes.length) {
      var speed = parseInt($("speed").value, 10) || 1;
      state.t = state.t + speed > steps() ? 0 : state.t + speed;
      render();
    }
    window.requestAnimationFrame(tick);
  }
  scene.setScene(data.scene, function () {
    if (data.episodes.length) { choose(0); }
    // "#t=STEP" opens the animation at that step.
    var at = /t=(\d+)/.exec(location.hash);
    if (at && data.episodes.length) { state.t = Math.min(parseInt(at[1], 10), steps()); render(); }
    window.requestAnimationFrame(tick);
  });
})();
