// The viewer page: shows what the server simulates and sends back the user's commands.
"use strict";
(function () {
  var $ = function (id) { return document.getElementById(id); };
  var scene = new VivaeScene.Scene($("scene"));
  // Tests and the curious read this: frames drawn, frame rate, last step, errors.
  var stats = { frames: 0, fps: 0, step: 0, neurons: 0, sensors: 0, errors: [], connected: false };
  window.vivaeView = stats;
  var sceneInfo = null, frame = null, fresh = false;
  var trails = [], lastStep = -1;
  var progress = null, knownChampion = null, progressSeen = 0;
  var dragging = -1, dragMoved = false;
  var keys = { up: false, down: false, left: false, right: false };

  var proto = location.protocol === "https:" ? "wss://" : "ws://";
  var ws = new WebSocket(proto + location.host + "/ws");
  function send(msg) { if (ws.readyState === 1) { ws.send(JSON.stringify(msg)); } }

  function status(text, isError) {
    $("status").textContent = text;
    $("status").className = "sub" + (isError ? " error" : "");
  }

  ws.onopen = function () { stats.connected = true; status("connected"); };
  ws.onclose = function () { stats.connected = false; status("disconnected: reload the page to reconnect", true); };
  ws.onmessage = function (ev) {
    var m;
    try { m = JSON.parse(ev.data); } catch (e) { return; }
    if (m.type === "info") { onInfo(m); }
    else if (m.type === "scene") { onScene(m); }
    else if (m.type === "frame") { onFrame(m); }
    else if (m.type === "progress") { onProgress(m); }
    else if (m.type === "error") { stats.errors.push(m.message); status("server: " + m.message, true); }
  };

  function onInfo(m) {
    $("source").textContent = m.source;
    var sel = $("scenario");
    sel.innerHTML = "";
    m.scenarios.forEach(function (name, i) {
      var o = document.createElement("option");
      o.value = i;
      o.textContent = name;
      sel.appendChild(o);
    });
  }

  function onScene(m) {
    sceneInfo = m;
    trails = [];
    lastStep = -1;
    $("scenario").value = m.scenario_index;
    $("sensors").value = m.sensors;
    $("neurons").value = m.neurons;
    stats.neurons = m.neuron_nodes.length;
    stats.sensors = m.sensor_nodes.length;
    $("sensorcount").textContent = m.sensors + " = " + m.sensor_nodes.length + " surface sensors";
    $("neuroncount").textContent = m.neurons + " = " + m.neuron_nodes.length + " neurons";
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
    if (m.step < lastStep) { trails = []; }
    if ($("trails").checked && m.step !== lastStep) {
      m.robots.forEach(function (r, i) {
        var t = trails[i] || (trails[i] = []);
        var n = t.length;
        // A jump (a drag) starts the trail afresh.
        if (n >= 2 && Math.abs(t[n - 2] - r.x) + Math.abs(t[n - 1] - r.y) > 40) { t.length = 0; }
        t.push(r.x, r.y);
        if (t.length > 40000) { t.splice(0, t.length - 40000); }
      });
    }
    lastStep = m.step;
    frame = m;
    fresh = true;
    stats.step = m.step;
    $("play").textContent = m.playing ? "Pause" : "Play";
    $("driver").textContent = "controller: " + m.driver;
    if (String(m.selected) !== $("robot").value) { $("robot").value = m.selected; }
    if (document.activeElement !== $("controller") && $("controller").value !== m.choice) {
      $("controller").value = m.choice;
    }
    $("drive").checked = m.manual !== null && m.manual === m.selected;
  }

  function onProgress(m) {
    progress = m;
    var sel = $("controller"), keep = sel.value;
    sel.innerHTML = "";
    var add = function (v, t) { var o = document.createElement("option"); o.value = v; o.textContent = t; sel.appendChild(o); };
    add("none", "none (keyboard only)");
    if (m.champion) { add("champion", "champion (gen " + m.champion[0] + ", " + m.champion[1].toFixed(3) + ")"); }
    for (var i = m.genomes.length - 1; i >= 0; i--) { add(String(m.genomes[i]), "best of generation " + m.genomes[i]); }
    if (keep && Array.prototype.some.call(sel.options, function (o) { return o.value === keep; })) { sel.value = keep; }
    else if (m.champion) { sel.value = "champion"; }
    var gens = m.generations.map(function (r) { return r.generation; });
    $("gencount").textContent = m.generations.length ? ("generation " + gens[gens.length - 1] + (m.total ? " of " + m.total : "")) : "";
    $("curves").innerHTML = VivaePlots.lines(gens, [
      { name: "best", color: "#d62728", values: m.generations.map(function (r) { return r.best; }) },
      { name: "mean", color: "#1f77b4", values: m.generations.map(function (r) { return r.mean; }) }
    ], "generation", "fitness (px/step)");
    $("species").innerHTML = VivaePlots.stacked(m.species, m.genomes.length ? m.genomes[0] : 1);
    var firstChampion = m.champion && !knownChampion && progressSeen > 0;
    progressSeen += 1;
    if (firstChampion || (m.champion && knownChampion &&
        (m.champion[0] !== knownChampion[0] || m.champion[1] !== knownChampion[1]))) {
      $("newchamptext").textContent = "New champion: generation " + m.champion[0] + ", fitness " + m.champion[1].toFixed(3);
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

  function drawPanels() {
    if (!sceneInfo || !frame) { return; }
    var readings = [];
    if (frame.sensors) { for (var k = 2; k < frame.sensors.length; k += 3) { readings.push(frame.sensors[k]); } }
    polarPanel($("sensorpanel"), sceneInfo.sensor_nodes, readings, VivaeScene.readingColor);
    var marks = {};
    marks[sceneInfo.wheels[0]] = "L";
    marks[sceneInfo.wheels[1]] = "R";
    polarPanel($("neuronpanel"), sceneInfo.neuron_nodes, frame.neurons && frame.neurons.length ? frame.neurons : null,
      activationColor, marks);
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

  $("play").onclick = function () { send({ type: frame && frame.playing ? "pause" : "play" }); };
  $("step").onclick = function () { send({ type: "step", n: 1 }); };
  $("reset").onclick = function () { trails = []; send({ type: "reset" }); };
  $("speed").onchange = function () { send({ type: "speed", value: parseFloat($("speed").value) }); };
  $("controller").onchange = function () {
    var v = $("controller").value;
    send({ type: "controller", which: v === "none" || v === "champion" ? v : parseInt(v, 10) });
    trails = [];
  };
  $("scenario").onchange = function () { send({ type: "scenario", index: parseInt($("scenario").value, 10) }); };
  $("apply").onclick = function () { send({ type: "resolution", sensors: $("sensors").value.trim(), neurons: $("neurons").value.trim() }); };
  Array.prototype.forEach.call(document.querySelectorAll(".preset"), function (b) {
    b.onclick = function () {
      $("sensors").value = b.getAttribute("data-s");
      $("neurons").value = b.getAttribute("data-n");
      $("apply").onclick();
    };
  });
  $("cleartrails").onclick = function () { trails = []; fresh = true; };
  $("trails").onchange = function () { fresh = true; };
  $("robot").onchange = function () { send({ type: "select", robot: parseInt($("robot").value, 10) }); };
  $("drive").onchange = function () {
    send({ type: "drive", robot: $("drive").checked ? parseInt($("robot").value, 10) || 0 : null });
    $("scene").focus();
  };
  $("watchnew").onclick = function () {
    $("newchamp").style.display = "none";
    $("controller").value = "champion";
    $("controller").onchange();
  };

  var canvas = $("scene");
  canvas.addEventListener("mousedown", function (ev) {
    if (!frame) { return; }
    var i = scene.robotAt(frame.robots, scene.toWorld(ev));
    if (i >= 0) { dragging = i; dragMoved = false; send({ type: "select", robot: i }); ev.preventDefault(); }
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
  function onKey(ev, down) {
    var k = keyNames[ev.key];
    if (!k || !$("drive").checked) { return; }
    ev.preventDefault();
    if (keys[k] !== down) { keys[k] = down; send({ type: "keys", up: keys.up, down: keys.down, left: keys.left, right: keys.right }); }
  }
  window.addEventListener("keydown", function (ev) { onKey(ev, true); });
  window.addEventListener("keyup", function (ev) { onKey(ev, false); });
})();
