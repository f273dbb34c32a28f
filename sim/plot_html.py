"""`--plot run.html`: the run as one self-contained interactive page.

The page carries its data as JSON and a small script that draws SVG: no library, no CDN, nothing
fetched (it opens on a machine without a network, and can be mailed or attached to a ticket).
Per moving axis a position and a speed chart against time; the I/O lanes with each change; the
XY path of interpolated moves. Scroll over a chart to zoom in time around the pointer, drag to
pan, double-click (or "reset zoom") to see the whole run; hovering shows every axis's position
and speed at that time, and each input or output change names itself (value, time, source line).
Every change marker also has an SVG <title>, so the browser's own tooltip names it too.

A page opened with `#selftest` at the end of its address exercises zoom, hover and tooltips on
itself and writes what it found into the element `#selftest` (tests/sim/test_plot_cli.py reads it
through headless Chromium).
"""

from __future__ import annotations

import html
import json

from mcc.sim.plot import signal_colours
from mcc.sim.plotdata import PlotData

MAX_POINTS = 20000  # per axis; a longer run is thinned evenly (the CSV trace keeps every sample)


def payload(data: PlotData) -> dict:
    colours = signal_colours(data)
    axes = []
    for s in data.axes:
        step = max(1, len(s.times) // MAX_POINTS)
        keep = range(0, len(s.times), step)
        axes.append({"name": s.name, "unit": s.scale.unit, "speedUnit": s.scale.speed_unit,
                     "t": [round(s.times[i], 6) for i in keep], "p": [round(s.positions[i], 6) for i in keep],
                     "v": [round(s.speeds[i], 6) for i in keep]})
    xy = None
    if data.xy:
        units = {s.name: s.scale.unit for s in data.axes}
        xy = {"x": data.xy[0], "y": data.xy[1], "xUnit": units[data.xy[0]], "yUnit": units[data.xy[1]],
              "paths": [[[round(x, 6), round(y, 6)] for x, y in path] for path in data.xy_paths],
              "track": [[round(x, 6), round(y, 6)] for x, y in data.xy_track]}
    return {
        "title": data.title, "subtitle": data.subtitle, "duration": data.duration, "still": data.still,
        "axes": axes, "xy": xy,
        "signals": [{"name": name, "colour": colour} for name, colour in colours.items()],
        "changes": [{"t": c.t, "signal": c.signal, "value": c.value, "label": c.label,
                     "colour": colours[c.signal]} for c in data.changes],
    }


def script_json(value: dict) -> str:
    """JSON that cannot end its <script> element early."""
    return json.dumps(value, ensure_ascii=True, separators=(",", ":")).replace("</", "<\\/")


def render(data: PlotData) -> str:
    title = html.escape(f"{data.title} \u2014 mcc sim")
    still = (f"<p class=\"note\">Axes that never move (not shown): {html.escape(', '.join(data.still))}</p>"
             if data.still else "")
    return PAGE.format(title=title, heading=html.escape(data.title), subtitle=html.escape(data.subtitle),
                       still=still, data=script_json(payload(data)), style=STYLE, script=SCRIPT)


PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>{style}</style>
<script>window.mccErrors = []; window.addEventListener("error", function (e) {{ window.mccErrors.push(String(e.message)); }});</script>
</head>
<body>
<h1>{heading}</h1>
<p class="sub">{subtitle}</p>
{still}
<p class="help">Scroll over a chart to zoom in time, drag to pan, double-click to see the whole run.
<button type="button" id="reset">reset zoom</button></p>
<div id="readout">&nbsp;</div>
<div id="charts"></div>
<div id="legend"></div>
<div id="xy"></div>
<div id="tip" role="tooltip"></div>
<noscript><p>This page draws its charts with JavaScript; the same run is available as an image
with <code>mcc sim --plot run.svg</code>.</p></noscript>
<pre id="selftest" hidden></pre>
<script type="application/json" id="mcc-data">{data}</script>
<script>{script}</script>
</body>
</html>
"""

STYLE = """
body { font: 13px/1.4 system-ui, sans-serif; margin: 16px; color: #222; }
h1 { font-size: 17px; margin: 0; } .sub, .note, .help { margin: 2px 0; color: #555; }
#readout { font-family: ui-monospace, monospace; min-height: 1.4em; margin: 6px 0; white-space: pre; }
svg { display: block; background: #fff; user-select: none; }
svg.time { cursor: crosshair; }
.grid { stroke: #e4e4e4; } .frame { fill: none; stroke: #999; }
.tick { font-size: 10px; fill: #555; } .label { font-size: 11px; fill: #333; }
.pos { fill: none; stroke: #1f77b4; stroke-width: 1.4; } .speed { fill: none; stroke: #ff7f0e; stroke-width: 1.4; }
.cursor { stroke: #333; stroke-dasharray: 3 3; }
.event { cursor: help; } .hit { stroke: transparent; stroke-width: 9; }
#tip { position: fixed; display: none; background: #fffbe6; border: 1px solid #c9b458; padding: 3px 6px;
       font-size: 12px; pointer-events: none; }
#legend ul { columns: 2; list-style: none; padding: 0; } #legend li { margin: 1px 0; }
#legend .swatch { display: inline-block; width: 10px; height: 10px; margin-right: 6px; }
.xyline { fill: none; stroke: #1f77b4; stroke-width: 1.4; }
"""

SCRIPT = r"""
(function () {
  "use strict";
  var D = JSON.parse(document.getElementById("mcc-data").textContent);
  var NS = "http://www.w3.org/2000/svg";
  var W = 920, H = 150, L = 78, R = 16, T = 8, B = 24;
  var first = Infinity, last = -Infinity;
  D.axes.forEach(function (a) { if (a.t.length) { first = Math.min(first, a.t[0]); last = Math.max(last, a.t[a.t.length - 1]); } });
  D.changes.forEach(function (c) { first = Math.min(first, c.t); last = Math.max(last, c.t); });
  if (!isFinite(first)) { first = 0; last = D.duration; }
  first = Math.min(first, 0); last = Math.max(last, D.duration, first + 1e-3);
  var view = [first, last], panels = [], tip = document.getElementById("tip");

  function el(name, attrs, parent, text) {
    var node = document.createElementNS(NS, name);
    for (var k in attrs) { node.setAttribute(k, attrs[k]); }
    if (text !== undefined) { node.textContent = text; }
    if (parent) { parent.appendChild(node); }
    return node;
  }
  function num(v) { return Math.abs(v) < 1e-9 ? "0" : String(Number(v.toPrecision(6))); }
  function ticks(lo, hi, n) {
    var span = hi - lo || 1, step = Math.pow(10, Math.floor(Math.log10(span / n))), out = [];
    [1, 2, 5, 10].some(function (m) { if (span / (step * m) <= n) { step *= m; return true; } return false; });
    for (var v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) { out.push(v); }
    return out;
  }
  function xOf(t) { return L + (t - view[0]) / (view[1] - view[0]) * (W - L - R); }
  function tOf(x) { return view[0] + (x - L) / (W - L - R) * (view[1] - view[0]); }
  function valueAt(ts, vs, t) {
    var lo = 0, hi = ts.length - 1;
    if (!ts.length) { return 0; }
    if (t <= ts[0]) { return vs[0]; }
    if (t >= ts[hi]) { return vs[hi]; }
    while (hi - lo > 1) { var mid = (lo + hi) >> 1; if (ts[mid] <= t) { lo = mid; } else { hi = mid; } }
    var f = ts[hi] > ts[lo] ? (t - ts[lo]) / (ts[hi] - ts[lo]) : 1;
    return vs[lo] + (vs[hi] - vs[lo]) * f;
  }
  function visible(ts, vs) {
    var xs = [], ys = [];
    for (var i = 0; i < ts.length; i++) {
      var inside = ts[i] >= view[0] && ts[i] <= view[1];
      var edge = (i + 1 < ts.length && ts[i + 1] >= view[0] && ts[i] < view[0]) || (i > 0 && ts[i - 1] <= view[1] && ts[i] > view[1]);
      if (inside || edge) { xs.push(ts[i]); ys.push(vs[i]); }
    }
    return [xs, ys];
  }
  function markChanges(svg, top, bottom) {
    D.changes.forEach(function (c) {
      if (c.t < view[0] || c.t > view[1]) { return; }
      var x = xOf(c.t), g = el("g", {"class": "event", "data-label": c.label}, svg);
      el("title", {}, g, c.label);
      el("line", {x1: x, x2: x, y1: top, y2: bottom, stroke: c.colour, "stroke-dasharray": c.value ? "" : "4 3", opacity: 0.7}, g);
      el("line", {x1: x, x2: x, y1: top, y2: bottom, "class": "hit"}, g);
    });
  }
  function frame(svg, ys, label) {
    var lo = Math.min.apply(null, ys.concat([0])), hi = Math.max.apply(null, ys.concat([0]));
    if (hi - lo < 1e-12) { hi = lo + 1; }
    var pad = (hi - lo) * 0.08; lo -= pad; hi += pad;
    var yOf = function (v) { return T + (hi - v) / (hi - lo) * (H - T - B); };
    ticks(view[0], view[1], 8).forEach(function (t) {
      el("line", {x1: xOf(t), x2: xOf(t), y1: T, y2: H - B, "class": "grid"}, svg);
      el("text", {x: xOf(t), y: H - B + 14, "text-anchor": "middle", "class": "tick"}, svg, num(t));
    });
    ticks(lo, hi, 4).forEach(function (v) {
      el("line", {x1: L, x2: W - R, y1: yOf(v), y2: yOf(v), "class": "grid"}, svg);
      el("text", {x: L - 4, y: yOf(v) + 3, "text-anchor": "end", "class": "tick"}, svg, num(v));
    });
    el("rect", {x: L, y: T, width: W - L - R, height: H - T - B, "class": "frame"}, svg);
    el("text", {x: 12, y: T + (H - T - B) / 2, transform: "rotate(-90 12 " + (T + (H - T - B) / 2) + ")", "text-anchor": "middle", "class": "label"}, svg, label);
    return yOf;
  }
  function drawSeries(p) {
    var svg = p.svg, a = p.axis;
    while (svg.firstChild) { svg.removeChild(svg.firstChild); }
    var pts = visible(a.t, p.key === "p" ? a.p : a.v);
    var yOf = frame(svg, pts[1], p.label);
    var clip = "clip" + p.id;
    var defs = el("defs", {}, svg), cp = el("clipPath", {id: clip}, defs);
    el("rect", {x: L, y: T, width: W - L - R, height: H - T - B}, cp);
    var d = pts[0].map(function (t, i) { return xOf(t).toFixed(2) + "," + yOf(pts[1][i]).toFixed(2); }).join(" ");
    el("polyline", {points: d, "class": p.key === "p" ? "pos" : "speed", "clip-path": "url(#" + clip + ")"}, svg);
    markChanges(svg, T, H - B);
    p.cursor = el("line", {x1: -10, x2: -10, y1: T, y2: H - B, "class": "cursor"}, svg);
  }
  function drawLanes(p) {
    var svg = p.svg, n = D.signals.length;
    while (svg.firstChild) { svg.removeChild(svg.firstChild); }
    var lane = 30, h = T + B + lane * n;
    svg.setAttribute("viewBox", "0 0 " + W + " " + h); svg.setAttribute("height", h);
    ticks(view[0], view[1], 8).forEach(function (t) {
      el("line", {x1: xOf(t), x2: xOf(t), y1: T, y2: h - B, "class": "grid"}, svg);
      el("text", {x: xOf(t), y: h - B + 14, "text-anchor": "middle", "class": "tick"}, svg, num(t));
    });
    el("rect", {x: L, y: T, width: W - L - R, height: h - T - B, "class": "frame"}, svg);
    D.signals.forEach(function (s, k) {
      var base = T + lane * (k + 1) - 6, mine = D.changes.filter(function (c) { return c.signal === s.name; });
      el("text", {x: L - 4, y: base - 5, "text-anchor": "end", "class": "tick"}, svg, s.name);
      var d = "", prev = null;
      mine.forEach(function (c) {
        var x = Math.max(L, Math.min(W - R, xOf(c.t))), y = base - c.value * 16;
        d += prev === null ? "M" + x + "," + y : " H" + x + " V" + y;
        prev = c;
      });
      if (prev !== null) { d += " H" + (W - R); el("path", {d: d, fill: "none", stroke: s.colour, "stroke-width": 1.6}, svg); }
      mine.forEach(function (c) {
        if (c.t < view[0] || c.t > view[1]) { return; }
        var g = el("g", {"class": "event", "data-label": c.label}, svg);
        el("title", {}, g, c.label);
        el("circle", {cx: xOf(c.t), cy: base - c.value * 16, r: 4, fill: s.colour}, g);
      });
    });
    el("text", {x: W - R, y: h - 4, "text-anchor": "end", "class": "label"}, svg, "time (s)");
    p.cursor = el("line", {x1: -10, x2: -10, y1: T, y2: h - B, "class": "cursor"}, svg);
  }
  function redraw() { panels.forEach(function (p) { p.draw(p); }); }
  function readout(t) {
    var parts = ["t = " + num(t) + " s"];
    D.axes.forEach(function (a) {
      parts.push(a.name + " " + num(valueAt(a.t, a.p, t)) + " " + a.unit + ", " + num(valueAt(a.t, a.v, t)) + " " + a.speedUnit);
    });
    document.getElementById("readout").textContent = parts.join("   ");
    panels.forEach(function (p) { var x = xOf(t); p.cursor.setAttribute("x1", x); p.cursor.setAttribute("x2", x); });
  }
  function pointerT(svg, ev) {
    var r = svg.getBoundingClientRect();
    return tOf((ev.clientX - r.left) * W / r.width);
  }
  function zoom(t, factor) {
    var lo = t - (t - view[0]) * factor, hi = t + (view[1] - t) * factor;
    if (hi - lo > last - first) { lo = first; hi = last; }
    if (lo < first) { hi += first - lo; lo = first; }
    if (hi > last) { lo -= hi - last; hi = last; }
    if (hi - lo < 1e-6) { return; }
    view = [Math.max(first, lo), Math.min(last, hi)]; redraw();
  }
  function attach(svg) {
    var drag = null;
    svg.addEventListener("wheel", function (ev) { ev.preventDefault(); zoom(pointerT(svg, ev), ev.deltaY < 0 ? 0.8 : 1.25); }, {passive: false});
    svg.addEventListener("mousedown", function (ev) { drag = {x: ev.clientX, view: view.slice()}; });
    window.addEventListener("mouseup", function () { drag = null; });
    svg.addEventListener("mousemove", function (ev) {
      if (drag) {
        var r = svg.getBoundingClientRect(), dt = (ev.clientX - drag.x) * W / r.width / (W - L - R) * (drag.view[1] - drag.view[0]);
        var lo = drag.view[0] - dt, hi = drag.view[1] - dt;
        if (lo < first) { hi += first - lo; lo = first; }
        if (hi > last) { lo -= hi - last; hi = last; }
        view = [lo, hi]; redraw();
      }
      readout(pointerT(svg, ev));
    });
    svg.addEventListener("dblclick", function () { view = [first, last]; redraw(); });
  }
  var charts = document.getElementById("charts");
  D.axes.forEach(function (a, i) {
    [["p", "axis " + a.name + " (" + a.unit + ")"], ["v", a.name + " speed (" + a.speedUnit + ")"]].forEach(function (k) {
      var svg = el("svg", {"class": "time", viewBox: "0 0 " + W + " " + H, width: W, height: H, "data-axis": a.name, "data-kind": k[0]}, charts);
      panels.push({svg: svg, axis: a, key: k[0], label: k[1], id: panels.length, draw: drawSeries});
      attach(svg);
    });
  });
  if (D.signals.length) {
    var lanes = el("svg", {"class": "time lanes", viewBox: "0 0 " + W + " " + H, width: W, height: H}, charts);
    panels.push({svg: lanes, id: panels.length, draw: drawLanes});
    attach(lanes);
  }
  if (!panels.length) { charts.textContent = "No axis moved and no input or output changed."; }
  redraw();
  document.getElementById("reset").addEventListener("click", function () { view = [first, last]; redraw(); });

  document.addEventListener("mouseover", function (ev) {
    var g = ev.target.closest ? ev.target.closest(".event") : null;
    if (!g) { tip.style.display = "none"; return; }
    tip.textContent = g.getAttribute("data-label");
    tip.style.left = (ev.clientX + 12) + "px"; tip.style.top = (ev.clientY + 12) + "px"; tip.style.display = "block";
  });

  if (D.changes.length) {
    var legend = document.getElementById("legend");
    var h = document.createElement("h2"); h.textContent = "Input and output changes"; h.style.fontSize = "14px";
    var ul = document.createElement("ul");
    D.changes.forEach(function (c) {
      var li = document.createElement("li"), sw = document.createElement("span");
      sw.className = "swatch"; sw.style.background = c.colour; li.appendChild(sw);
      li.appendChild(document.createTextNode(c.label)); ul.appendChild(li);
    });
    legend.appendChild(h); legend.appendChild(ul);
  }

  if (D.xy) {
    var box = document.getElementById("xy"), S = 460, M = 50;
    var xs = [], ys = [];
    D.xy.paths.concat([D.xy.track]).forEach(function (path) { path.forEach(function (p) { xs.push(p[0]); ys.push(p[1]); }); });
    var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs), y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
    var span = Math.max(x1 - x0, y1 - y0) || 1, k = (S - 2 * M) / span;
    var X = function (v) { return M + (v - x0) * k; }, Y = function (v) { return S - M - (v - y0) * k; };
    var svg = el("svg", {"class": "xy", viewBox: "0 0 " + S + " " + S, width: S, height: S}, box);
    el("text", {x: S / 2, y: 16, "text-anchor": "middle", "class": "label"}, svg, "XY path of the moves that drive " + D.xy.x + " and " + D.xy.y + " together");
    ticks(x0, x0 + span, 5).forEach(function (v) { el("line", {x1: X(v), x2: X(v), y1: M, y2: S - M, "class": "grid"}, svg); el("text", {x: X(v), y: S - M + 14, "text-anchor": "middle", "class": "tick"}, svg, num(v)); });
    ticks(y0, y0 + span, 5).forEach(function (v) { el("line", {x1: M, x2: S - M, y1: Y(v), y2: Y(v), "class": "grid"}, svg); el("text", {x: M - 4, y: Y(v) + 3, "text-anchor": "end", "class": "tick"}, svg, num(v)); });
    if (D.xy.track.length) {
      el("polyline", {points: D.xy.track.map(function (p) { return X(p[0]).toFixed(2) + "," + Y(p[1]).toFixed(2); }).join(" "), fill: "none", stroke: "#bbb", "stroke-dasharray": "4 3"}, svg);
    }
    D.xy.paths.forEach(function (path, n) {
      var g = el("g", {"class": "event", "data-label": "path " + (n + 1) + ": (" + num(path[0][0]) + ", " + num(path[0][1]) + ") to (" + num(path[path.length - 1][0]) + ", " + num(path[path.length - 1][1]) + ") " + D.xy.xUnit}, svg);
      el("title", {}, g, g.getAttribute("data-label"));
      el("polyline", {points: path.map(function (p) { return X(p[0]).toFixed(2) + "," + Y(p[1]).toFixed(2); }).join(" "), "class": "xyline"}, g);
      el("circle", {cx: X(path[0][0]), cy: Y(path[0][1]), r: 3, fill: "#2ca02c"}, g);
    });
    el("text", {x: S / 2, y: S - 8, "text-anchor": "middle", "class": "label"}, svg, D.xy.x + " (" + D.xy.xUnit + ")");
    el("text", {x: 12, y: S / 2, transform: "rotate(-90 12 " + S / 2 + ")", "text-anchor": "middle", "class": "label"}, svg, D.xy.y + " (" + D.xy.yUnit + ")");
  }

  function selftest() {
    var out = {errors: window.mccErrors, panels: document.querySelectorAll("svg.time").length,
               events: document.querySelectorAll(".event").length, xy: document.querySelectorAll("svg.xy polyline").length,
               title: document.title};
    var ev = document.querySelector("svg.time .event");
    if (ev) {
      var box = ev.getBoundingClientRect();
      ev.lastChild.dispatchEvent(new MouseEvent("mouseover", {bubbles: true, clientX: box.left + 1, clientY: box.top + 1}));
      out.tooltip = tip.style.display === "block" ? tip.textContent : "";
      out.svgTitle = ev.querySelector("title").textContent;
    }
    var svg = document.querySelector("svg.time");
    if (svg) {
      var r = svg.getBoundingClientRect(), whole = last - first, at = {bubbles: true, cancelable: true, clientX: r.left + r.width / 2, clientY: r.top + r.height / 2};
      svg.dispatchEvent(new WheelEvent("wheel", Object.assign({deltaY: -100}, at)));
      out.zoomedIn = (view[1] - view[0]) < whole * 0.9;
      svg.dispatchEvent(new MouseEvent("mousemove", at));
      out.readout = document.getElementById("readout").textContent;
      svg.dispatchEvent(new MouseEvent("dblclick", at));
      out.reset = view[0] === first && view[1] === last;
    }
    var pre = document.getElementById("selftest");
    pre.textContent = JSON.stringify(out); pre.setAttribute("data-done", "1");
  }
  if (location.hash === "#selftest") { selftest(); }
})();
"""
