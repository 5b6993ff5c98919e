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
  if (data.scenes.length) {
    $("scenario").innerHTML = data.scenes[0].svg;
  } else {
    // A task without maps or figures (a plain task): its curves and tables only.
    ["drive", "scenarioheading", "scenario"].forEach(function (id) { $(id).style.display = "none"; });
    $("network").parentNode.style.display = "none";
  }
  if (data.maps.length) {
    $("scenarioheading").textContent = "Scenario (training map 1, " + data.maps[0] + ")";
    $("fitnessnote").textContent = "(a genome's fitness: the mean over the " + data.maps.length + " training maps)";
  }

  var gens = data.generations.map(function (r) { return r.generation; });
  // The colours of convergence.png's curves, so that the page and the figure agree.
  $("curves").innerHTML = VivaePlots.lines(gens, [
    { name: "best", color: data.curve_colours[0], values: data.generations.map(function (r) { return r.best; }) },
    { name: "mean", color: data.curve_colours[1], values: data.generations.map(function (r) { return r.mean; }) }
  ], "generation", data.task ? "fitness" : "fitness (px/step)");
  $("species").innerHTML = VivaePlots.stacked(data.species, 1);
  $("table").innerHTML = VivaePlots.table(data.generations);

  // A strategy beyond NEAT, by the shape of what it keeps (not by name): an
  // archive over behaviours as a heat map, or a Pareto front over
  // objectives, with a table of the members to drive (vivae view RUN
  // --elite / --front); else its heading and note; then its own columns of
  // generations.csv.
  function strategySection(st) {
    var P = VivaePlots, rows = "", head;
    $("strategysection").style.display = "";
    if (st.behaviour_names.length) {
      var cells = st.grid ? st.grid.bins[0] * st.grid.bins[1] : null;
      $("strategyheading").textContent = (st.heading || "MAP-Elites archive") + ": " + st.elites.length + " elites" +
        (cells ? " in " + cells + " cells" : "");
      $("strategynote").textContent = (st.grid_note ? st.grid_note + ". " : "Fitness in colour; hover a cell for its elite. ") +
        "Drive any elite: vivae view " + data.title + " --elite CELL (or vivae replay … --elite CELL).";
      if (st.grid) { $("strategyplot").innerHTML = P.heatmap(st.grid, st.elites, st.behaviour_names); }
      var best = st.elites.slice().sort(function (a, b) { return b[1] - a[1] || a[0] - b[0]; });
      head = ["cell"].concat(st.behaviour_names, ["fitness", "generation"]);
      best.slice(0, 200).forEach(function (e) {
        rows += "<tr><td>" + e[0] + "</td>" + e[3].map(function (v) { return "<td>" + v.toFixed(3) + "</td>"; }).join("") +
          "<td>" + e[1].toFixed(4) + "</td><td>" + e[2] + "</td></tr>";
      });
    } else if (st.objectives.length) {
      $("strategyheading").textContent = (st.heading || "NSGA-II Pareto front") + ": " + st.front.length + " members";
      $("strategynote").textContent = "The last generation's first front, numbered as front.csv (0 = the fittest)" +
        (st.objectives.length > 2 ? "; the first 2 of " + st.objectives.length + " objectives are drawn" : "") +
        ". figures/front.png adds the whole population. Drive any member: vivae view " + data.title + " --front N.";
      if (st.objectives.length >= 2) { $("strategyplot").innerHTML = P.front(st.front, st.objectives); }
      head = ["member", "fitness"].concat(st.objectives);
      st.front.forEach(function (f) {
        rows += "<tr><td>" + f[0] + "</td><td>" + f[1].toFixed(4) + "</td>" +
          f[2].map(function (v) { return "<td>" + P.esc(v.toFixed(3)) + "</td>"; }).join("") + "</tr>";
      });
    } else {
      $("strategyheading").textContent = st.heading || st.kind;
      $("strategynote").textContent = st.note;
    }
    if (head) {
      $("strategytable").innerHTML = "<table><thead><tr>" + head.map(function (h) { return "<th>" + P.esc(h) + "</th>"; }).join("") +
        "</tr></thead><tbody>" + rows + "</tbody></table>";
    }
    var gens = data.generations.map(function (r) { return r.generation; }).slice(0, st.values.length);
    st.columns.forEach(function (name, k) {
      if (name === "filled_cells" || name === "archive_best") { return; }
      var div = document.createElement("div");
      div.className = "col plot";
      div.style.maxWidth = "640px";
      div.id = "strategy-" + name;
      div.innerHTML = P.lines(gens, [{ name: name.replace("_", " "), color: data.curve_colours[0],
        values: st.values.map(function (r) { return r[k] === null ? NaN : r[k]; }) }], "generation", name.replace("_", " "));
      $("strategycurves").appendChild(div);
    });
  }
  if (data.strategy) { strategySection(data.strategy); }
  // A task whose champion is validated on fresh episodes: the verdict.
  if (data.validation) {
    $("validation").textContent = data.validation;
    $("validation").style.display = "";
  }
  // A task that draws its steps: the champion's replay, animated.
  if (data.film) { VivaeFilm.show(data.film, data.film.label); }

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

  var shownScene = -1;
  function choose(k) {
    state.episode = k;
    state.t = 0;
    var ep = data.episodes[k];
    if (ep.scene !== shownScene) {
      shownScene = ep.scene;
      scene.setScene(data.scenes[ep.scene], render);
    }
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
  // On several training maps: one panel per map, the champion's whole episode on it.
  function mapPanels() {
    var means = 0;
    data.maps.forEach(function (name, k) {
      var ep = data.episodes[k], sc = data.scenes[ep.scene];
      means += ep.fitness;
      var panel = document.createElement("div");
      panel.className = "mappanel";
      panel.id = "map-" + k;
      var title = document.createElement("h3");
      title.textContent = name + " (map " + (k + 1) + " of " + data.maps.length + ")";
      var canvas = document.createElement("canvas");
      var info = document.createElement("div");
      info.className = "muted";
      info.textContent = "fitness " + ep.fitness.toFixed(3) + " px/step, " + (100 * ep.on_road).toFixed(1) +
        "% on road; click to animate";
      panel.appendChild(title);
      panel.appendChild(canvas);
      panel.appendChild(info);
      panel.onclick = function () { choose(k); $("drive").scrollIntoView(); };
      $("mappanels").appendChild(panel);
      var s = new VivaeScene.Scene(canvas);
      s.setScene(sc, function () {
        var last = ep.paths.map(function (p) { return { x: p[p.length - 2], y: p[p.length - 1], h: 0 }; });
        s.draw(last, ep.paths, {});
      });
    });
    $("mapnote").textContent = "Its fitness, " + (means / data.maps.length).toFixed(3) +
      " px/step, is the mean of these " + data.maps.length + " maps' (files figures/trajectories-champion-<map>.png).";
    $("mapsection").style.display = "";
  }
  if (data.maps.length) { mapPanels(); }

  shownScene = 0;
  if (!data.scenes.length) { return; }
  scene.setScene(data.scenes[0], function () {
    if (data.episodes.length) { choose(0); }
    // "#t=STEP" opens the animation at that step.
    var at = /t=(\d+)/.exec(location.hash);
    if (at && data.episodes.length) { state.t = Math.min(parseInt(at[1], 10), steps()); render(); }
    window.requestAnimationFrame(tick);
  });
})();
