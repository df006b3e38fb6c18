// The live view's page (@TOKEN@ stands for the token, put in by the server): plain HTML and JavaScript of ours; the
// plots are Debian's dygraphs, served by beltsim from where Debian installs it (live_server.cpp).
#include "live/live_server.hpp"

namespace beltsim::live {

const char* page_html() {
  return R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>beltsim live</title>
<link rel="stylesheet" href="dygraph.css?token=@TOKEN@">
<style>
body { font-family: sans-serif; margin: 1em; }
#bar span { margin-right: 1.5em; }
#bar b { font-variant-numeric: tabular-nums; }
#plot { width: 100%; height: 420px; }
#frame { display: block; max-width: 100%; height: auto; background: #222; }
#columns label, #controls span { margin-right: 1em; white-space: nowrap; }
</style>
</head>
<body>
<div id="bar">
<span>run <b id="name">-</b></span>
<span>t = <b id="t">-</b> s</span>
<span>wall / simulated <b id="ratio">-</b></span>
<span>step <b id="h">-</b> s</span>
<span>status <b id="status">connecting</b></span>
</div>
<div id="controls">
<button id="pause">Pause</button> <button id="continue">Continue</button>
<span>run to t = <input id="target" type="number" step="any" size="6"> s <button id="runto">Run</button></span>
<span>torque of <select id="pulley"></select> <input id="torque" type="number" step="any" size="8"> N·m
<button id="settorque">Set</button></span>
<span>wet s from <input id="from" type="number" step="any" size="6"> to <input id="to" type="number" step="any"
size="6"> m, μ <input id="mu" type="number" step="any" size="5"> <button id="wet">Wet</button></span>
<span>checkpoint <input id="ckpt" type="text" size="12" value="live.ckpt"> <button id="save">Save</button></span>
<span id="reply"></span>
</div>
<img id="frame" alt="the belt as the renderer draws it (frames come while a page is open)" width="960" height="540">
<div id="plot"></div>
<div id="columns"></div>
<script src="dygraph.js?token=@TOKEN@"></script>
<script>
"use strict";
const q = "?token=@TOKEN@";
let columns = [], data = [], graph = null, drawn = true, shown = [];
function fmt(x, digits) { return x === null ? "-" : Number(x).toPrecision(digits); }
// the columns plotted at first: pulley speeds, span tensions, slip
function chosen(name) { return /\.omega$|tension|slip/.test(name); }
function setup() {
  const box = document.getElementById("columns");
  box.innerHTML = "";
  shown = columns.map(chosen);
  if (!shown.some(x => x)) shown = columns.map((c, k) => k < 4);
  columns.forEach((c, k) => {
    const l = document.createElement("label"), cb = document.createElement("input");
    cb.type = "checkbox"; cb.checked = shown[k]; cb.dataset.column = c;
    cb.onchange = () => { shown[k] = cb.checked; if (graph) graph.setVisibility(k, cb.checked); };
    l.appendChild(cb); l.appendChild(document.createTextNode(" " + c)); box.appendChild(l);
  });
  if (graph) graph.destroy();
  graph = null;
}
function draw() {
  drawn = true;
  if (data.length === 0 || columns.length === 0) return;
  if (!graph) {
    graph = new Dygraph(document.getElementById("plot"), data,
                        { labels: ["t"].concat(columns), visibility: shown, xlabel: "t [s]", legend: "always",
                          labelsSeparateLines: false });
  } else {
    graph.updateOptions({ file: data });
  }
}
const es = new EventSource("events" + q);
es.addEventListener("run", e => {
  const r = JSON.parse(e.data);
  document.getElementById("name").textContent = r.name || "-";
  columns = r.columns; data = []; setup();
  const sel = document.getElementById("pulley");
  sel.innerHTML = "";
  for (const p of r.pulleys || []) { const o = document.createElement("option"); o.textContent = p; sel.appendChild(o); }
});
es.addEventListener("samples", e => {
  const rows = JSON.parse(e.data);
  if (rows.length === 0) return;
  for (const r of rows) data.push([r[0]].concat(r.slice(3)));
  const last = rows[rows.length - 1];
  document.getElementById("t").textContent = fmt(last[0], 6);
  document.getElementById("ratio").textContent = fmt(last[1], 3);
  document.getElementById("h").textContent = fmt(last[2], 3);
  if (drawn) { drawn = false; requestAnimationFrame(draw); }
});
es.addEventListener("status", e => { document.getElementById("status").textContent = JSON.parse(e.data); });
// the latest frame, asked for when the stream says one was drawn and the one before has arrived
// (a slow link gets fewer, never a queue); the picture's t is in its data-t once shown
const img = document.getElementById("frame");
let frames = 0, loading = null, latest = null;
function load() {
  if (loading !== null || latest === null) return;
  loading = latest; latest = null;
  img.src = "frame.png" + q + "&n=" + (++frames);
}
img.onload = () => { img.dataset.t = loading; loading = null; load(); };
img.onerror = () => { loading = null; load(); };
es.addEventListener("frame", e => { latest = JSON.parse(e.data); load(); });
// controls: queued by the server, applied by the run between two steps, as the console's commands
// are (its status says so)
function control(params) {
  fetch("control" + q + "&" + new URLSearchParams(params), { method: "POST" })
    .then(r => r.text()).then(t => { document.getElementById("reply").textContent = t; });
}
document.getElementById("pause").onclick = () => control({ do: "pause" });
document.getElementById("continue").onclick = () => control({ do: "continue" });
const val = id => document.getElementById(id).value;
document.getElementById("runto").onclick = () => control({ do: "run_to", value: val("target") });
document.getElementById("settorque").onclick = () => control({ do: "torque", pulley: val("pulley"), value: val("torque") });
document.getElementById("wet").onclick = () => control({ do: "wet", from: val("from"), to: val("to"), value: val("mu") });
document.getElementById("save").onclick = () => control({ do: "save", name: val("ckpt") });
es.onerror = () => { document.getElementById("status").textContent = "disconnected (the run has ended?)"; };
</script>
</body>
</html>
)html";
}

}  // namespace beltsim::live
