// The predator-prey report: the champions' table and their match, animated.
"use strict";
(function () {
  var data = JSON.parse(document.getElementById("vivae-data").textContent);
  var $ = function (id) { return document.getElementById(id); };
  $("runname").textContent = data.title + " — " + data.generations + " generations";
  $("config").textContent = data.config;
  var c = data.champions;
  window.vivaeReport = { frames: 0, t: 0 };
  if (!c) {
    $("championtable").textContent = "No champions.json yet: the run has not stopped.";
    return;
  }
  var row = function (cells, tag) {
    return "<tr>" + cells.map(function (x) { return "<" + tag + ">" + x + "</" + tag + ">"; }).join("") + "</tr>";
  };
  $("championtable").innerHTML = "<table>" +
    row(["side", "generation", "master tournament fitness", "hidden neurons", "links"], "th") +
    row(["hunter", c.hunter_generation, c.hunter_master_fitness.toFixed(3), c.hunter_hidden, c.hunter_links], "td") +
    row(["prey", c.prey_generation, c.prey_master_fitness.toFixed(3), c.prey_hidden, c.prey_links], "td") +
    "</table>";
  var g = data.game;
  var colours = [];
  colours[g.hunter] = g.colours[0];
  colours[g.prey] = g.colours[1];
  $("legend").innerHTML = "<span><i style='background:" + g.colours[0] + "'></i>hunter (generation " +
    c.hunter_generation + ")</span><span><i style='background:" + g.colours[1] + "'></i>prey (generation " +
    c.prey_generation + ")</span>";
  $("matchinfo").textContent = g.caught
    ? "The hunter catches the prey at step " + g.steps + " of " + g.max_steps + "."
    : "The prey escapes: no catch in " + g.max_steps + " steps.";
  var scene = new VivaeScene.Scene($("scene"));
  var slider = $("slider");
  slider.max = g.frames.length - 1;
  var t = 0, playing = true;
  function draw() {
    var f = g.frames[t];
    var robots = f.map(function (r) { return { x: r[0], y: r[1], h: r[2] }; });
    var trails = f.map(function (_, i) {
      var out = [];
      for (var k = 0; k <= t; k++) { out.push(g.frames[k][i][0], g.frames[k][i][1]); }
      return out;
    });
    scene.draw(robots, trails, { colors: colours });
    slider.value = t;
    $("stepno").textContent = t + " / " + (g.frames.length - 1);
    window.vivaeReport.frames += 1;
    window.vivaeReport.t = t;
  }
  scene.setScene(g.scene, draw);
  $("play").onclick = function () {
    playing = !playing;
    this.textContent = playing ? "Pause" : "Play";
  };
  slider.oninput = function () { t = +slider.value; draw(); };
  var pause = 0;
  function tick() {
    if (playing) {
      if (t + 2 < g.frames.length) { t += 2; } else if (++pause > 60) { t = 0; pause = 0; }
      draw();
    }
    requestAnimationFrame(tick);
  }
  requestAnimationFrame(tick);
})();
