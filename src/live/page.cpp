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
#plots .plot { width: 100%; height: 300px; margin-bottom: 0.6em; }
#plots .legend { min-height: 1.4em; margin: 0.3em 0; }
#plots .legend span { margin-right: 1em; white-space: nowrap; }
#frame { display: block; max-width: 100%; height: auto; background: #222; cursor: crosshair; }
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
<img id="frame" alt="the belt as the renderer draws it (frames come while a page is open)" width="960" height="540"
 draggable="false" title="drag along the belt (or click an element) to choose the stretch to wet">
<div id="plots"></div>
<div id="columns"></div>
<script src="dygraph.js?token=@TOKEN@"></script>
<script>
"use strict";
const q = "?token=@TOKEN@";
let columns = [], units = [], data = [], graphs = [], drawn = true, shown = [];
function fmt(x, digits) { return x === null ? "-" : Number(x).toPrecision(digits); }
// the columns plotted at first: the pulleys' speeds and the span tensions
function chosen(name) { return /\.omega$/.test(name) || /^span_.*\.tension$/.test(name); }
// the shown series' colours, given in the order they are shown, so that no two shown look alike
// (dygraphs' own spread its hues over every column, shown or not: neighbours came out the same)
const palette = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
                 "#7f7f7f", "#bcbd22", "#000080", "#800000", "#008080", "#808000", "#ff00ff", "#00a000"];
function colours() {
  const s = {};
  let n = 0;
  columns.forEach((c, k) => { if (shown[k]) s[c] = palette[n++ % palette.length]; });
  return s;
}
// one plot for each unit of the shown columns, as beltsim plot draws them (speeds in rad/s beside
// tensions in N on one axis flattened the speeds into a line at zero), in the order of their first
// column; each with its legend above it
function rebuild() {
  for (const g of graphs) g.destroy();
  graphs = [];
  const plots = document.getElementById("plots");
  plots.innerHTML = "";
  if (data.length === 0 || columns.length === 0) return;
  const colour = colours(), seen = [];
  columns.forEach((c, k) => { if (shown[k] && !seen.includes(units[k])) seen.push(units[k]); });
  for (const u of seen) {
    const labels = document.createElement("div"), div = document.createElement("div");
    labels.className = "legend";
    div.className = "plot";
    plots.appendChild(labels);
    plots.appendChild(div);
    const visible = columns.map((c, k) => shown[k] && units[k] === u), series = {};
    columns.forEach((c, k) => { if (visible[k]) series[c] = { color: colour[c] }; });
    graphs.push(new Dygraph(div, data, { labels: ["t"].concat(columns), visibility: visible, series: series,
                                         xlabel: "t [s]", ylabel: u === "" ? "" : "[" + u + "]", legend: "always",
                                         labelsDiv: labels, labelsSeparateLines: false }));
  }
}
function setup() {
  const box = document.getElementById("columns");
  box.innerHTML = "";
  shown = columns.map(chosen);
  if (!shown.some(x => x)) shown = columns.map((c, k) => k < 4);
  columns.forEach((c, k) => {
    const l = document.createElement("label"), cb = document.createElement("input");
    cb.type = "checkbox"; cb.checked = shown[k]; cb.dataset.column = c;
    cb.onchange = () => { shown[k] = cb.checked; rebuild(); };
    l.appendChild(cb); l.appendChild(document.createTextNode(" " + c)); box.appendChild(l);
  });
  rebuild();
}
function draw() {
  drawn = true;
  if (graphs.length === 0) rebuild();
  else for (const g of graphs) g.updateOptions({ file: data });
}
const es = new EventSource("events" + q);
es.addEventListener("run", e => {
  const r = JSON.parse(e.data);
  document.getElementById("name").textContent = r.name || "-";
  columns = r.columns; units = r.units || columns.map(() => ""); data = []; setup();
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
// the status says what became of each control (applied, refused): the server's answer "queued"
// beside the controls is cleared by the status that follows it (it stayed there, stale, after the
// control had been applied); a refusal the server answered at once stays
let statuses = 0;  // status events so far
const reply = document.getElementById("reply");
es.addEventListener("status", e => {
  document.getElementById("status").textContent = JSON.parse(e.data);
  statuses++;
  if (reply.textContent.trim() === "queued") reply.textContent = "";
});
// the latest frame, asked for when the stream says one was drawn and the one before has arrived
// (a slow link gets fewer, never a queue); the picture's t is in its data-t once shown
const img = document.getElementById("frame");
let frames = 0, loading = null, latest = null;
function load() {
  if (loading !== null || latest === null) return;
  loading = latest; latest = null;
  img.src = "frame.jpg" + q + "&n=" + (++frames);
}
// where the shown picture's elements are (/frame.json, the one of the same t), for picking
let placed = null;
function place() {
  const t = img.dataset.t;
  fetch("frame.json" + q).then(r => r.ok ? r.json() : null).then(j => {
    if (j && String(j.t) === t && img.dataset.t === t) placed = j;
  }).catch(() => {});
}
img.onload = () => { img.dataset.t = loading; loading = null; placed = null; place(); load(); };
img.onerror = () => { loading = null; load(); };
es.addEventListener("frame", e => { latest = JSON.parse(e.data); load(); });
// picking the wet stretch on the picture: the element nearest where the mouse went down and the
// one nearest where it came up (the same for a click) give s0 and s1 of the wet form, the shorter
// way round the belt between them; the stretch is wetted with the form's Wet, as any change
function nearest(e) {
  if (!placed) return null;
  const r = img.getBoundingClientRect();
  const x = (e.clientX - r.left) * img.naturalWidth / r.width, y = (e.clientY - r.top) * img.naturalHeight / r.height;
  let best = null, d2 = 20 * 20;  // [px of the picture] at most this far from an element's centre
  for (const el of placed.elements) {
    const d = (el[0] - x) ** 2 + (el[1] - y) ** 2;
    if (d <= d2) { d2 = d; best = el[2]; }
  }
  return best;
}
let down = null;
img.onmousedown = e => { e.preventDefault(); down = nearest(e); };
img.onmouseup = e => {
  const a = down, b = nearest(e), L = placed ? placed.length : 0;
  down = null;
  if (a === null || b === null) {
    reply.textContent = placed ? "no element there: pick on the belt" : "the picture is moving: pause to pick";
    return;
  }
  const forward = ((b - a) % L + L) % L;  // [m] from a to b in the direction of travel
  const [s0, s1] = forward <= L / 2 ? [a, b] : [b, a];
  document.getElementById("from").value = s0;
  document.getElementById("to").value = s1;
  reply.textContent = "picked s from " + fmt(s0, 4) + " to " + fmt(s1, 4) + " m";
};
// controls: queued by the server, applied by the run between two steps, as the console's commands
// are (its status says so); "queued" not shown when the status has changed since the control was
// sent (the stream can bring it before the answer)
function control(params) {
  const sent = statuses;
  fetch("control" + q + "&" + new URLSearchParams(params), { method: "POST" })
    .then(r => r.text().then(t => { reply.textContent = r.status === 202 && statuses !== sent ? "" : t; }));
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
