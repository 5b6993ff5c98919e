// The viewer page: shows what the server simulates and sends back the user's commands.
"use strict";
(function () {
  var $ = function (id) { return document.getElementById(id); };
  var scene = new VivaeScene.Scene($("scene"));
  // Tests and the curious read this: frames drawn, frame rate, last step, errors.
  var stats = { frames: 0, fps: 0, step: 0, neurons: 0, sensors: 0, errors: [], connected: false, trails: [] };
  window.vivaeView = stats;
  // Robot i's trail as drawn, [x0, y0, x1, y1, …].
  stats.trail = function (i) { return (trails[i] || []).slice(); };
  var sceneInfo = null, frame = null, fresh = false;
  // Per robot, its trail [x0, y0, x1, y1, …] and the jump count it started at.
  var trails = [], trailJumps = [], lastStep = -1;
  var progress = null, knownChampion = null, progressSeen = 0, info = null;
  var dragging = -1, dragMoved = false;
  var keys = { up: false, down: false, left: false, right: false };

  var socket = VivaeSocket.open(stats, {
    info: onInfo, scene: onScene, frame: onFrame, progress: onProgress, error: onError
  });
  var send = socket.send, act = socket.act, status = socket.status;

  // Shows the error and puts the page's choices back to what the server runs.
  function onError(m) {
    stats.errors.push(m.message);
    status("server: " + m.message, true);
    if (sceneInfo) { $("scenario").value = sceneInfo.scenario_index; }
    if (frame) { $("controller").value = frame.choice; }
  }

  function onInfo(m) {
    info = m;
    $("source").textContent = m.source;
    var sel = $("scenario");
    sel.innerHTML = "";
    var unusable = m.unusable || [];
    m.scenarios.forEach(function (name, i) {
      var o = document.createElement("option");
      o.value = i;
      o.textContent = unusable[i] ? name + " \u2014 cannot be driven: " + unusable[i] : name;
      o.disabled = !!unusable[i];
      sel.appendChild(o);
    });
    var n = unusable.filter(function (u) { return u; }).length;
    $("scenarionote").textContent = n ? n + " of " + m.scenarios.length +
      " scenarios cannot be driven (no robots, or not a scenario): listed greyed out" : "";
  }

  function onScene(m) {
    sceneInfo = m;
    trails = [];
    trailJumps = [];
    lastStep = -1;
    $("scenario").value = m.scenario_index;
    $("sensors").value = m.sensors;
    $("neurons").value = m.neurons;
    var net = m.network;
    stats.neurons = net ? net.nodes.length : m.neuron_nodes.length;
    stats.sensors = m.sensor_nodes.length;
    stats.hidden = net ? net.hidden : 0;
    $("sensorcount").textContent = m.sensors + " = " + m.sensor_nodes.length + " surface sensors";
    $("neuroncount").textContent = net
      ? "ES-HyperNEAT: " + net.hidden + " hidden neurons found, " + net.links + " links"
      : m.neurons + " = " + m.neuron_nodes.length + " neurons";
    // The ES plane is a square (neurons may sit behind the robot), the dense sheet a half-disc.
    $("neuronpanel").height = net ? 280 : 150;
    $("neuronlegend").lastChild.textContent = net
      ? " blue \u22121 \u2026 white 0 \u2026 red +1; the ES plane from above (ahead up): grey dots are the sensors, " +
        "L and R the wheel neurons, the others the hidden neurons where the CPPN put them"
      : " blue \u22121 \u2026 white 0 \u2026 red +1; L and R are the wheel neurons";
    var rs = $("robot"), keep = rs.value;
    rs.innerHTML = "";
    for (var i = 0; i < m.robots; i++) {
      var o = document.createElement("option");
      o.value = i;
      o.textContent = String(i + 1);
      o.style.background = VivaeScene.color(i);
      rs.appendChild(o);
    }
    if (keep !== "" && keep < m.robots) { rs.value = keep; }
    scene.setScene(m.scene, function () { fresh = true; });
  }

  function onFrame(m) {
    if (m.step < lastStep) { trails = []; trailJumps = []; }
    m.robots.forEach(function (r, i) {
      // A robot put somewhere by hand starts its trail afresh; a fast one
      // (many steps a frame) keeps it, however far it went.
      if (trailJumps[i] !== r.j) { trails[i] = []; trailJumps[i] = r.j; }
    });
    if ($("trails").checked && m.step !== lastStep) {
      m.robots.forEach(function (r, i) {
        var t = trails[i] || (trails[i] = []);
        // Where it went since the last frame, then where it is.
        if (r.p) { for (var k = 0; k + 1 < r.p.length; k += 2) { t.push(r.p[k], r.p[k + 1]); } }
        t.push(r.x, r.y);
        if (t.length > 40000) { t.splice(0, t.length - 40000); }
      });
    }
    stats.trails = trails.map(function (t) { return t ? t.length / 2 : 0; });
    lastStep = m.step;
    fresh = true;
    stats.step = m.step;
    $("play").textContent = m.playing ? "Pause" : "Play";
    var byHand = m.manual !== null && m.manual === m.selected;
    $("driver").textContent = byHand
      ? "driven by you with the arrow keys" + (m.choice === "none" ? "" : " (the other robots: " + m.driver + ")")
      : "controller: " + m.driver + (m.manual !== null ? "; robot " + (m.manual + 1) + " driven by you" : "");
    $("driver").className = byHand ? "manual" : "muted";
    if (String(m.selected) !== $("robot").value) { $("robot").value = m.selected; }
    var generationChanged = !frame || frame.generation !== m.generation || frame.choice !== m.choice;
    frame = m;
    if (generationChanged && progress) { controllerOptions(progress); }
    if (document.activeElement !== $("controller") && $("controller").value !== m.choice) {
      $("controller").value = m.choice;
    }
    $("drive").checked = byHand;
  }

  // The champion this page's robots drive: its generation (from the server), or null.
  function drivingChampion() {
    return frame && frame.choice === "champion" ? frame.generation : null;
  }

  // The controller list. "champion" names the champion that drives here, which
  // stays the one loaded until "watch it" loads a newer one.
  function controllerOptions(m) {
    var sel = $("controller"), keep = frame ? frame.choice : sel.value;
    sel.innerHTML = "";
    var add = function (v, t) { var o = document.createElement("option"); o.value = v; o.textContent = t; sel.appendChild(o); };
    add("none", "none (keyboard only)");
    var driving = drivingChampion();
    if (driving !== null && (!m.champion || driving !== m.champion[0])) {
      add("champion", "champion of generation " + driving + " (driving; newest: generation " +
        (m.champion ? m.champion[0] : "?") + ")");
    } else if (m.champion) {
      add("champion", "champion (generation " + m.champion[0] + ", fitness " + m.champion[1].toFixed(3) + ")");
    }
    for (var i = m.genomes.length - 1; i >= 0; i--) { add(String(m.genomes[i]), "best of generation " + m.genomes[i]); }
    memberOptions(sel, m);
    if (keep && Array.prototype.some.call(sel.options, function (o) { return o.value === keep; })) { sel.value = keep; }
    else if (m.champion) { sel.value = "champion"; }
  }

  // "name value, …" of a member's behaviour or objectives.
  function named(names, values) {
    return values.map(function (v, i) { return (names[i] || "#" + i) + " " + v.toFixed(2); }).join(", ");
  }

  // A map-elites run's elites (fittest first) and an nsga2 run's front, as
  // groups of the controller list: values "elite:CELL" and "front:N".
  function memberOptions(sel, m) {
    var group = function (label, items, value, text) {
      if (!items || !items.length) { return; }
      var g = document.createElement("optgroup");
      g.label = label;
      items.forEach(function (it) {
        var o = document.createElement("option");
        o.value = value(it);
        o.textContent = text(it);
        g.appendChild(o);
      });
      sel.appendChild(g);
    };
    var names = info || {};
    var elites = (m.elites || []).slice().sort(function (a, b) { return b.fitness - a.fitness || a.cell - b.cell; });
    group("MAP-Elites archive: " + elites.length + " elites, fittest first", elites,
      function (e) { return "elite:" + e.cell; },
      function (e) {
        return "elite of cell " + e.cell + ": fitness " + e.fitness.toFixed(3) + " (" +
          named(names.behaviour_names || [], e.behaviour) + ")";
      });
    group("Pareto front: " + (m.front || []).length + " members", m.front,
      function (f) { return "front:" + f.member; },
      function (f) {
        return "front member " + f.member + ": fitness " + f.fitness.toFixed(3) + " (" +
          named(names.objective_names || [], f.objectives) + ")";
      });
  }

  function onProgress(m) {
    progress = m;
    controllerOptions(m);
    var gens = m.generations.map(function (r) { return r.generation; });
    $("gencount").textContent = m.generations.length ? ("generation " + gens[gens.length - 1] + (m.total ? " of " + m.total : "") +
      (m.champion ? "; champion from generation " + m.champion[0] : "")) : "";
    $("curves").innerHTML = VivaePlots.lines(gens, [
      { name: "best", color: "#d62728", values: m.generations.map(function (r) { return r.best; }) },
      { name: "mean", color: "#1f77b4", values: m.generations.map(function (r) { return r.mean; }) }
    ], "generation", "fitness (px/step)");
    $("species").innerHTML = VivaePlots.stacked(m.species, m.genomes.length ? m.genomes[0] : 1);
    var firstChampion = m.champion && !knownChampion && progressSeen > 0;
    progressSeen += 1;
    if (firstChampion || (m.champion && knownChampion &&
        (m.champion[0] !== knownChampion[0] || m.champion[1] !== knownChampion[1]))) {
      var driving = drivingChampion();
      $("newchamptext").textContent = "New champion: generation " + m.champion[0] + ", fitness " + m.champion[1].toFixed(3) +
        (driving !== null ? " (the champion of generation " + driving + " drives now)" : "");
      $("newchamp").style.display = "";
    }
    knownChampion = m.champion;
  }

  // Heat colour for an activation in [-1, 1].
  function activationColor(v) {
    v = Math.max(-1, Math.min(1, v));
    var k = Math.round(255 * (1 - Math.abs(v)));
    return v >= 0 ? "rgb(255," + k + "," + k + ")" : "rgb(" + k + "," + k + ",255)";
  }

  // A half-disc of polar nodes [rho, phi] coloured by values (as the network figure).
  function polarPanel(canvas, nodes, values, colorOf, marks) {
    var c = canvas.getContext("2d"), w = canvas.width, h = canvas.height;
    var cx = w / 2, cy = h - 8, rad = Math.min(w / 2 - 10, h - 16);
    c.clearRect(0, 0, w, h);
    c.strokeStyle = "#ccc";
    c.beginPath();
    c.arc(cx, cy, rad, Math.PI, 2 * Math.PI);
    c.stroke();
    var dot = Math.max(1.5, Math.min(7, 0.45 * rad / Math.sqrt(Math.max(nodes.length, 1))));
    var dots = nodes.map(function (n, i) {
      return {
        x: cx + n[0] * Math.sin(n[1]) * rad,
        y: cy - n[0] * Math.cos(n[1]) * rad,
        v: values && i < values.length ? values[i] : 0
      };
    });
    VivaeScene.drawDots(c, dots, dot, colorOf);
    c.fillStyle = "#000";
    c.font = "10px sans-serif";
    Object.keys(marks || {}).forEach(function (i) {
      var p = dots[i];
      if (p) { c.fillText(marks[i], p.x + dot + 1, p.y - dot); }
    });
  }

  // An ES network in its plane [-1, 1]² (x right, y ahead): sensors grey, the
  // wheel (L, R) and hidden neurons coloured by their activations `values`
  // (wheels first, as the scene's `network.nodes`).
  function esPanel(canvas, net, values) {
    var c = canvas.getContext("2d"), w = canvas.width, h = canvas.height;
    var half = Math.min(w, h) / 2 - 10, cx = w / 2, cy = h / 2;
    var at = function (p) { return { x: cx + p[0] * half, y: cy - p[1] * half }; };
    c.clearRect(0, 0, w, h);
    c.strokeStyle = "#ccc";
    c.strokeRect(cx - half, cy - half, 2 * half, 2 * half);
    c.beginPath();
    c.moveTo(cx - half, cy); c.lineTo(cx + half, cy);
    c.moveTo(cx, cy - half); c.lineTo(cx, cy + half);
    c.stroke();
    c.fillStyle = "#888";
    var s = Math.max(0.8, Math.min(2.5, 12 / Math.sqrt(Math.max(net.sensors.length, 1))));
    net.sensors.forEach(function (p) { var q = at(p); c.fillRect(q.x - s, q.y - s, 2 * s, 2 * s); });
    var dot = Math.max(2.5, Math.min(6, 0.8 * half / Math.sqrt(Math.max(net.nodes.length, 1))));
    var dots = net.nodes.map(function (p, i) {
      var q = at(p);
      return { x: q.x, y: q.y, v: values && i < values.length ? values[i] : 0 };
    });
    VivaeScene.drawDots(c, dots.slice(2), dot, activationColor);
    VivaeScene.drawDots(c, dots.slice(0, 2), dot + 1.5, activationColor);
    c.strokeStyle = "#d62728";
    c.lineWidth = 1.5;
    c.fillStyle = "#d62728";
    c.font = "bold 11px sans-serif";
    dots.slice(0, 2).forEach(function (p, k) {
      c.beginPath();
      c.arc(p.x, p.y, dot + 4, 0, 2 * Math.PI);
      c.stroke();
      c.fillText(k === 0 ? "L" : "R", p.x - 3, p.y + dot + 15);
    });
    c.lineWidth = 1;
    stats.hiddenDrawn = dots.length - 2;
  }

  function drawPanels() {
    if (!sceneInfo || !frame) { return; }
    var readings = [];
    if (frame.sensors) { for (var k = 2; k < frame.sensors.length; k += 3) { readings.push(frame.sensors[k]); } }
    polarPanel($("sensorpanel"), sceneInfo.sensor_nodes, readings, VivaeScene.readingColor);
    var activity = frame.neurons && frame.neurons.length ? frame.neurons : null;
    stats.activations = activity ? activity.length : 0;
    if (sceneInfo.network) {
      esPanel($("neuronpanel"), sceneInfo.network, activity);
    } else {
      var marks = {};
      marks[sceneInfo.wheels[0]] = "L";
      marks[sceneInfo.wheels[1]] = "R";
      polarPanel($("neuronpanel"), sceneInfo.neuron_nodes, activity, activationColor, marks);
      stats.hiddenDrawn = 0;
    }
    var r = frame.robots[frame.selected];
    if (r) {
      $("robotinfo").textContent = "position " + r.x.toFixed(1) + ", " + r.y.toFixed(1) +
        "  speed " + r.v.toFixed(2) + " px/step  odometer " + r.odo.toFixed(0) + " px" +
        (frame.wheels ? "  wheels L " + frame.wheels[0].toFixed(2) + " R " + frame.wheels[1].toFixed(2) : "");
    }
  }

  var fpsFrames = 0, fpsSince = performance.now();
  function loop(now) {
    if (fresh && frame && sceneInfo) {
      fresh = false;
      var sensors = null;
      if (frame.sensors) {
        sensors = [];
        for (var k = 0; k + 2 < frame.sensors.length; k += 3) {
          sensors.push({ x: frame.sensors[k], y: frame.sensors[k + 1], v: frame.sensors[k + 2] });
        }
      }
      scene.draw(frame.robots, $("trails").checked ? trails : null, { selected: frame.selected, sensors: sensors });
      drawPanels();
      stats.frames += 1;
      stats.robots = frame.robots.map(function (r) { return [r.x, r.y]; });
      fpsFrames += 1;
    }
    if (now - fpsSince >= 1000) {
      stats.fps = fpsFrames * 1000 / (now - fpsSince);
      fpsFrames = 0;
      fpsSince = now;
      if (stats.connected && $("status").className.indexOf("error") < 0) {
        status("step " + stats.step + " · " + stats.fps.toFixed(0) + " frames/s");
      }
    }
    window.requestAnimationFrame(loop);
  }
  window.requestAnimationFrame(loop);

  $("play").onclick = function () { act({ type: frame && frame.playing ? "pause" : "play" }); };
  $("step").onclick = function () { act({ type: "step", n: 1 }); };
  $("reset").onclick = function () { trails = []; act({ type: "reset" }); };
  $("speed").onchange = function () { act({ type: "speed", value: parseFloat($("speed").value) }); };
  $("controller").onchange = function () {
    var v = $("controller").value, member = /^(elite|front):(\d+)$/.exec(v), which;
    if (member) { which = {}; which[member[1]] = parseInt(member[2], 10); }
    else { which = v === "none" || v === "champion" ? v : parseInt(v, 10); }
    act({ type: "controller", which: which });
    trails = [];
  };
  $("scenario").onchange = function () { act({ type: "scenario", index: parseInt($("scenario").value, 10) }); };
  $("apply").onclick = function () { act({ type: "resolution", sensors: $("sensors").value.trim(), neurons: $("neurons").value.trim() }); };
  Array.prototype.forEach.call(document.querySelectorAll(".preset"), function (b) {
    b.onclick = function () {
      $("sensors").value = b.getAttribute("data-s");
      $("neurons").value = b.getAttribute("data-n");
      $("apply").onclick();
    };
  });
  $("cleartrails").onclick = function () { trails = []; fresh = true; };
  $("trails").onchange = function () { fresh = true; };
  $("robot").onchange = function () { act({ type: "select", robot: parseInt($("robot").value, 10) }); };
  $("drive").onchange = function () {
    act({ type: "drive", robot: $("drive").checked ? parseInt($("robot").value, 10) || 0 : null });
    $("scene").focus();
  };
  $("watchnew").onclick = function () {
    $("newchamp").style.display = "none";
    act({ type: "controller", which: "champion" });
    trails = [];
  };

  var canvas = $("scene");
  canvas.addEventListener("mousedown", function (ev) {
    if (!frame) { return; }
    var i = scene.robotAt(frame.robots, scene.toWorld(ev));
    if (i >= 0) { dragging = i; dragMoved = false; act({ type: "select", robot: i }); ev.preventDefault(); }
  });
  window.addEventListener("mousemove", function (ev) {
    if (dragging < 0) { return; }
    var p = scene.toWorld(ev);
    if (sceneInfo && p.x >= 0 && p.y >= 0 && p.x <= sceneInfo.scene.width && p.y <= sceneInfo.scene.height) {
      dragMoved = true;
      send({ type: "drag", robot: dragging, x: p.x, y: p.y });
    }
  });
  window.addEventListener("mouseup", function () { dragging = -1; });

  var keyNames = { ArrowUp: "up", ArrowDown: "down", ArrowLeft: "left", ArrowRight: "right" };
  // Controls that use the arrow keys themselves keep them.
  function keepsArrows(el) {
    return !!el && (el.tagName === "SELECT" || el.tagName === "TEXTAREA" ||
      (el.tagName === "INPUT" && el.type !== "checkbox" && el.type !== "button"));
  }
  function onKey(ev, down) {
    var k = keyNames[ev.key];
    if (!k || keepsArrows(document.activeElement)) { return; }
    ev.preventDefault();
    // An arrow key takes the selected robot over ("drive it myself").
    if (down && !$("drive").checked && frame) {
      $("drive").checked = true;
      keys = { up: false, down: false, left: false, right: false };
      act({ type: "drive", robot: frame.selected });
    }
    if (keys[k] !== down) { keys[k] = down; send({ type: "keys", up: keys.up, down: keys.down, left: keys.left, right: keys.right }); }
  }
  window.addEventListener("keydown", function (ev) { onKey(ev, true); });
  window.addEventListener("keyup", function (ev) { onKey(ev, false); });
})();
