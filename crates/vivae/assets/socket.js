// The viewers' WebSocket: JSON messages to and from this server, and the
// connection's status in the page's header (#status). Plain browser JavaScript.
"use strict";
var VivaeSocket = (function () {
  // Connects to this server's /ws. `stats` (the page's object for tests) gets
  // `connected`; each message the server sends goes to `handlers[its type]`.
  // Returns the page's `send`, `act` (a user's action) and `status`.
  function open(stats, handlers) {
    var $ = function (id) { return document.getElementById(id); };
    var proto = location.protocol === "https:" ? "wss://" : "ws://";
    var ws = new WebSocket(proto + location.host + "/ws");
    function send(msg) { if (ws.readyState === 1) { ws.send(JSON.stringify(msg)); } }
    // A user's action: an error shown for an earlier one is over (the server
    // answers in order, so an error for this one arrives after this).
    function act(msg) {
      if (stats.connected && $("status").className.indexOf("error") >= 0) { status("connected"); }
      send(msg);
    }
    function status(text, isError) {
      $("status").textContent = text;
      $("status").className = "sub" + (isError ? " error" : "");
    }
    ws.onopen = function () { stats.connected = true; status("connected"); };
    ws.onclose = function () { stats.connected = false; status("disconnected: reload the page to reconnect", true); };
    ws.onmessage = function (ev) {
      var m;
      try { m = JSON.parse(ev.data); } catch (e) { return; }
      if (Object.prototype.hasOwnProperty.call(handlers, m.type)) { handlers[m.type](m); }
    };
    return { send: send, act: act, status: status };
  }
  return { open: open };
})();
