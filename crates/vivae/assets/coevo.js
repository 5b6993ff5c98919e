// The predator-prey viewer: a hunter and a prey of any generations meet; the
// prey can be driven with the arrow keys. Plain browser JavaScript.
"use strict";
(function () {
  var $ = function (id) { return document.getElementById(id); };
  var stats = { frames: 0, step: 0, robots: null, caught: null, hunter: -1, prey: -1, human: false,
    connected: false, errors: [], generations: 0, hunterIndex: -1, preyIndex: -1 };
  window.vivaeCoevo = stats;
  var scene = new VivaeScene.Scene($("scene"));
  var sceneInfo = null, info = null, frame = null, trails = [], colours = [], fresh = false;
  var keys = { up: false, down: false, left: false, right: false };

  var socket = VivaeSocket.open(stats, {
    info: onInfo, scene: onScene, frame: onFrame,
    error: function (m) {
      stats.errors.push(m.message);
      status("server: " + m.message, true);
      if (frame) { $("hunter").value = frame.hunter; $("prey").value = frame.prey; $("human").checked = frame.human; }
    }
  });
  var send = socket.send, act = socket.act, status = socket.status;

  function fill(select, fitness, champion) {
    select.innerHTML = "";
    for (var g = fitness.length - 1; g >= 0; g--) {
      var o = document.createElement("option");
      o.value = g;
      o.textContent = g + " (fitness " + fitness[g].toFixed(3) + ")" + (g === champion ? " · champion" : "");
      select.appendChild(o);
    }
  }
  function onInfo(m) {
    info = m;
    stats.generations = m.generations;
    $("source").textContent = m.source;
    var c = m.champions;
    fill($("hunter"), m.hunter_fitness, c ? c.hunter : -1);
    fill($("prey"), m.prey_fitness, c ? c.prey : -1);
    $("champions").disabled = !c;
    $("runinfo").textContent = m.generations + " generations of champions (each generation's best hunter and best prey, hall-of-fame.jsonl)" +
      (c ? "; master tournament champions: hunter of generation " + c.hunter + ", prey of generation " + c.prey + "."
         : "; no champions.json yet (the run has not stopped): reload to see newer generations.");
  }
  function onScene(m) {
    sceneInfo = m;
    stats.hunterIndex = m.hunter;
    stats.preyIndex = m.prey;
    colours = [];
    colours[m.hunter] = m.colours[0];
    colours[m.prey] = m.colours[1];
    $("huntercolour").style.background = m.colours[0];
    $("preycolour").style.background = m.colours[1];
    $("legend").innerHTML = "<span><i style='background:" + m.colours[0] + "'></i>hunter</span>" +
      "<span><i style='background:" + m.colours[1] + "'></i>prey</span><span>lines: their paths</span>";
    scene.setScene(m.scene, function () { fresh = true; });
  }
  function onFrame(m) {
    if (!frame || m.step < frame.step || m.hunter !== frame.hunter || m.prey !== frame.prey) { trails = []; }
    for (var i = 0; i < m.trace.length; i++) {
      trails[i] = trails[i] || [];
      for (var k = 0; k < m.trace[i].length; k++) { trails[i].push(m.trace[i][k][0], m.trace[i][k][1]); }
    }
    frame = m;
    stats.step = m.step;
    stats.caught = m.caught;
    stats.hunter = m.hunter;
    stats.prey = m.prey;
    stats.human = m.human;
    stats.robots = m.robots.map(function (r) { return [r[0], r[1]]; });
    $("hunter").value = m.hunter;
    $("prey").value = m.prey;
    $("human").checked = m.human;
    $("play").textContent = m.playing ? "Pause" : "Play";
    $("manualnote").textContent = m.human ? "you drive the prey: ↑ forward, ↓ back, ← → turn" : "";
    var who = "hunter of generation " + m.hunter + " against " + (m.human ? "you" : "the prey of generation " + m.prey);
    $("outcome").textContent = m.caught !== null ? "Caught at step " + m.caught + " (" + (m.caught / (info ? info.real_time_steps : 30)).toFixed(1) + " s)"
      : m.step >= m.max_steps ? "Escaped: no catch in " + m.max_steps + " steps" : m.playing ? "Running…" : "Paused";
    $("clock").textContent = who + " · step " + m.step + " of " + m.max_steps;
    fresh = true;
  }
  function draw() {
    if (fresh && frame && sceneInfo) {
      fresh = false;
      var robots = frame.robots.map(function (r) { return { x: r[0], y: r[1], h: r[2] }; });
      scene.draw(robots, trails, { colors: colours, selected: frame.human ? sceneInfo.prey : undefined });
      stats.frames += 1;
    }
    requestAnimationFrame(draw);
  }
  requestAnimationFrame(draw);

  $("play").onclick = function () { act({ type: frame && frame.playing ? "pause" : "play" }); };
  $("step").onclick = function () { act({ type: "step", n: 1 }); };
  $("reset").onclick = function () { act({ type: "reset" }); };
  $("speed").onchange = function () { act({ type: "speed", value: +this.value }); };
  function pick() { act({ type: "pick", hunter: +$("hunter").value, prey: +$("prey").value }); }
  $("hunter").onchange = pick;
  $("prey").onchange = pick;
  $("champions").onclick = function () {
    if (info && info.champions) { act({ type: "pick", hunter: info.champions.hunter, prey: info.champions.prey }); }
  };
  $("human").onchange = function () {
    keys = { up: false, down: false, left: false, right: false };
    act({ type: "human", on: this.checked });
    $("scene").focus();
  };
  var keyNames = { ArrowUp: "up", ArrowDown: "down", ArrowLeft: "left", ArrowRight: "right" };
  function onKey(ev, down) {
    var k = keyNames[ev.key];
    var el = document.activeElement;
    if (!k || (el && el.tagName === "SELECT")) { return; }
    ev.preventDefault();
    // An arrow key hands the prey to the person.
    if (down && frame && !frame.human && !$("human").checked) {
      $("human").checked = true;
      keys = { up: false, down: false, left: false, right: false };
      act({ type: "human", on: true });
    }
    if (keys[k] !== down) { keys[k] = down; send({ type: "keys", up: keys.up, down: keys.down, left: keys.left, right: keys.right }); }
  }
  window.addEventListener("keydown", function (ev) { onKey(ev, true); });
  window.addEventListener("keyup", function (ev) { onKey(ev, false); });
})();
