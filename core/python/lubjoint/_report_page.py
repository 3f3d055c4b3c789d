"""The page of ``lubjoint.report``: HTML, CSS and the page's own script, with three slots
(``@TITLE@``, ``@CHARTJS@``: Chart.js's text, ``@DATA@``: the study as JSON). Charts are
Chart.js's; this script only builds tables, select boxes and Chart.js configurations, and
adds one small plugin that draws error bars from a dataset's ``errors``."""

PAGE = r"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>@TITLE@</title>
<style>
:root { --fg: #1d2733; --muted: #5b6876; --line: #d8dee6; --bg: #f5f7fa; --card: #fff; --accent: #1f5f8b;
        --ok: #e3f4ea; --ok-fg: #1d6b3a; --bad: #fbe3e1; --bad-fg: #a1261b; }
* { box-sizing: border-box; }
body { margin: 0; font: 14px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", sans-serif;
       color: var(--fg); background: var(--bg); }
header { background: #16324a; color: #fff; padding: 18px 28px 14px; }
header h1 { margin: 0 0 4px; font-size: 21px; font-weight: 600; }
header .sub { color: #c5d5e4; font-size: 13px; }
nav { position: sticky; top: 0; z-index: 5; background: #fff; border-bottom: 1px solid var(--line);
      padding: 7px 28px; font-size: 13px; }
nav a { color: var(--accent); text-decoration: none; margin-right: 18px; }
main { max-width: 1320px; margin: 0 auto; padding: 16px 24px 40px; }
section { background: var(--card); border: 1px solid var(--line); border-radius: 6px; padding: 14px 20px 18px;
          margin: 16px 0; }
h2 { font-size: 17px; margin: 2px 0 8px; color: #16324a; }
h3 { font-size: 14px; margin: 14px 0 4px; }
p.note, .note { color: var(--muted); font-size: 12.5px; margin: 4px 0 8px; }
.facts { display: flex; flex-wrap: wrap; gap: 8px 22px; margin: 6px 0 2px; font-size: 13px; }
.facts b { font-weight: 600; }
.pill { display: inline-block; padding: 1px 8px; border-radius: 10px; font-size: 12px; margin: 1px 4px 1px 0;
        background: #eef2f6; }
.swatch { display: inline-block; width: 11px; height: 11px; border-radius: 2px; margin-right: 4px;
          vertical-align: -1px; }
.verdict { font-weight: 600; padding: 8px 12px; border-radius: 5px; margin: 6px 0 10px; }
.verdict.ok { background: var(--ok); color: var(--ok-fg); } .verdict.bad { background: var(--bad); color: var(--bad-fg); }
.tools { display: flex; gap: 10px; align-items: center; margin: 6px 0 8px; flex-wrap: wrap; font-size: 13px; }
input[type=search], select { font: inherit; padding: 4px 7px; border: 1px solid #b9c3ce; border-radius: 4px; }
.scroll { overflow-x: auto; max-height: 560px; overflow-y: auto; border: 1px solid var(--line); border-radius: 4px; }
table { border-collapse: collapse; font-size: 12.5px; width: 100%; }
th, td { padding: 4px 8px; border-bottom: 1px solid #e8ecf1; text-align: right; white-space: nowrap; }
th { background: #eef2f6; position: sticky; top: 0; z-index: 1; }
th button { font: inherit; font-weight: 600; background: none; border: 0; padding: 0; cursor: pointer; color: inherit; }
th[aria-sort=ascending] button::after { content: " ▲"; } th[aria-sort=descending] button::after { content: " ▼"; }
td.text, th.text { text-align: left; } td.msg { max-width: 420px; overflow: hidden; text-overflow: ellipsis; color: var(--muted); }
p.description { margin: 0 0 10px; max-width: 980px; }
details summary { cursor: pointer; color: var(--accent); margin: 8px 0 4px; font-size: 13px; }
tr:hover td { background: #f7fafc; }
td .err { color: var(--muted); font-size: 11.5px; }
td.within { background: var(--ok); color: var(--ok-fg); } td.outside { background: var(--bad); color: var(--bad-fg); font-weight: 600; }
td.none { color: #a0a8b0; }
.grid2 { display: grid; grid-template-columns: repeat(auto-fit, minmax(380px, 1fr)); gap: 14px 22px; }
.chart { position: relative; width: 100%; }
.chartbox h3 { margin-top: 4px; }
.casegrid { display: grid; grid-template-columns: 380px 1fr; gap: 10px 24px; align-items: start; }
#page-errors { background: var(--bad); color: var(--bad-fg); padding: 10px 14px; white-space: pre-wrap; margin: 10px 24px; }
#selftest { display: none; }
footer { color: var(--muted); font-size: 12px; text-align: center; padding: 10px; }
</style>
</head>
<body>
<div id="page-errors" hidden></div>
<header><h1 id="title"></h1><div class="sub" id="subtitle"></div></header>
<nav id="nav"></nav>
<main>
<section id="overview"><h2>Study</h2><div id="overview-body"></div></section>
<section id="comparison-section" hidden><h2>Nightly comparison against the baseline</h2><div id="comparison"></div></section>
<section id="summary-section"><h2>Cases</h2>
  <p class="note">One row per case. Click a column's header to sort by it (again: the other way); type to filter the rows.
  Steady-cycle metrics with their error bars (±); a case without a steady cycle has none (its <i>last h</i>: the last cycle's film).</p>
  <div class="tools"><input type="search" id="summary-filter" placeholder="filter: any text of a row" size="32">
  <label>classification <select id="summary-class"><option value="">all</option></select></label>
  <span id="summary-count" class="note"></span></div>
  <div class="scroll"><table id="summary-table"></table></div></section>
<section id="maps-section"><h2>Classification over the grid</h2>
  <p class="note">Each sub-grid's cells, coloured by the steady-cycle classification; a case that is not <code>ok</code> has a red border. Hover a cell for its case.</p>
  <div id="maps" class="grid2"></div></section>
<section id="metrics-section"><h2>Steady metrics over the grid</h2>
  <div class="tools"><label>metric <select id="metric-select"></select></label>
  <span class="note">a line per force law (and per value of the sub-grid's other axes), error bars from <code>&lt;metric&gt;_error</code></span></div>
  <div id="metrics" class="grid2"></div></section>
<section id="case-section"><h2>One case</h2>
  <div class="tools"><label>case <select id="case-select"></select></label></div>
  <div id="case-info"></div>
  <div class="casegrid"><div class="chartbox"><h3>Journal centre orbit</h3><div class="chart" style="height:370px;width:370px"><canvas id="chart-orbit"></canvas></div><p class="note" id="orbit-note"></p></div>
  <div><div class="chartbox"><h3>Minimum film thickness and eccentricity ratio</h3><div class="chart" style="height:230px"><canvas id="chart-film"></canvas></div></div>
  <div class="chartbox"><h3>Joint reaction</h3><div class="chart" style="height:190px"><canvas id="chart-reaction"></canvas></div></div></div></div>
  <p class="note" id="case-note"></p></section>
<section id="edges-section"><h2>Bifurcation edges</h2><div id="edges"></div></section>
<section id="boundaries-section"><h2>Boundaries and refinement</h2><div id="boundaries"></div></section>
<section id="solver-section"><h2>Solver statistics</h2>
  <p class="note">Wall time of each case (bars, coloured by its classification) and the integrator's steps (line); the table has every statistic the study records.</p>
  <div class="chart" style="height:240px"><canvas id="chart-solver"></canvas></div>
  <div class="tools"><input type="search" id="solver-filter" placeholder="filter" size="24"></div>
  <div class="scroll"><table id="solver-table"></table></div></section>
</main>
<footer id="footer"></footer>
<pre id="selftest"></pre>
<script>@CHARTJS@</script>
<script type="application/json" id="report-data">@DATA@</script>
<script>
"use strict";
const ERRORS = [];
function pageError(msg) {
  ERRORS.push(String(msg));
  const e = document.getElementById("page-errors");
  e.hidden = false;
  e.textContent = "This page met errors:\n" + ERRORS.join("\n");
  document.body.dataset.errors = String(ERRORS.length);
}
window.addEventListener("error", e => pageError(e.message + (e.filename ? " (" + e.lineno + ")" : "")));
window.addEventListener("unhandledrejection", e => pageError(e.reason));
const consoleError = console.error.bind(console);
console.error = (...a) => { pageError(a.join(" ")); consoleError(...a); };

const D = JSON.parse(document.getElementById("report-data").textContent);
const PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];
const CLASS_COLOUR = Object.fromEntries(D.classes.map(c => [c.name, c.colour]));
const charts = {};

function el(tag, attrs, ...kids) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "class") e.className = v; else if (k === "text") e.textContent = v; else e.setAttribute(k, v);
  }
  for (const k of kids) e.append(k);
  return e;
}
function fmt(v, digits) {
  if (v === null || v === undefined) return "";
  if (typeof v !== "number") return String(v);
  if (Number.isInteger(v) && Math.abs(v) < 1e7) return String(v);
  const a = Math.abs(v);
  return (a !== 0 && (a < 1e-3 || a >= 1e6)) ? v.toExponential((digits || 4) - 1) : String(+v.toPrecision(digits || 4));
}
const yOf = d => (d !== null && typeof d === "object") ? d.y : d;

// Chart.js plugins: error bars from a dataset's `errors` (one per point), and what each chart drew.
const errorBars = {
  id: "errorBars",
  afterDatasetsDraw(chart) {
    const ctx = chart.ctx, ys = chart.scales.y;
    chart.data.datasets.forEach((ds, i) => {
      if (!ds.errors || !chart.isDatasetVisible(i)) return;
      ctx.save();
      ctx.strokeStyle = ds.borderColor;
      ctx.lineWidth = 1.3;
      chart.getDatasetMeta(i).data.forEach((pt, j) => {
        const v = yOf(ds.data[j]), e = ds.errors[j];
        if (v === null || v === undefined || !(e > 0) || pt.skip) return;
        const lo = ys.type === "logarithmic" ? Math.max(v - e, v * 1e-3) : v - e;
        const y0 = ys.getPixelForValue(lo), y1 = ys.getPixelForValue(v + e);
        ctx.beginPath();
        ctx.moveTo(pt.x, y0); ctx.lineTo(pt.x, y1);
        ctx.moveTo(pt.x - 4, y0); ctx.lineTo(pt.x + 4, y0);
        ctx.moveTo(pt.x - 4, y1); ctx.lineTo(pt.x + 4, y1);
        ctx.stroke();
      });
      ctx.restore();
    });
  }
};
const drawnState = {
  id: "drawnState",
  afterRender(chart) {
    let n = 0;
    chart.data.datasets.forEach((ds, i) => {
      if (!chart.isDatasetVisible(i) || ds.decoration) return;
      chart.getDatasetMeta(i).data.forEach((pt, j) => {
        const v = ds.data[j];
        if (v !== null && v !== undefined && yOf(v) !== null && !pt.skip) n++;
      });
    });
    chart.canvas.dataset.drawn = String(n);
  }
};
Chart.register(errorBars, drawnState);
Chart.defaults.animation = false;
Chart.defaults.maintainAspectRatio = false;
Chart.defaults.font.size = 12;
Chart.defaults.plugins.legend.labels.boxWidth = 14;

function makeChart(canvas, name, config) {
  if (charts[name]) charts[name].destroy();
  canvas.dataset.chart = name;
  charts[name] = new Chart(canvas, config);
  return charts[name];
}
function chartBox(parent, name, title, height, note) {
  const canvas = el("canvas");
  parent.append(el("div", {class: "chartbox"}, el("h3", {text: title}),
                   el("div", {class: "chart", style: "height:" + height + "px"}, canvas), el("p", {class: "note", text: note || ""})));
  return canvas;
}

// --- tables: sortable (click a header), filterable (a text box, a select) --------------------
function buildTable(table, spec, filters) {
  const thead = el("thead"), tr = el("tr"), tbody = el("tbody");
  spec.columns.forEach((c, i) => {
    const b = el("button", {type: "button", text: c.label});
    const th = el("th", {"data-col": c.name, class: c.kind === "text" ? "text" : ""}, b);
    b.addEventListener("click", () => sortTable(table, i, th));
    tr.append(th);
  });
  thead.append(tr);
  for (const row of spec.rows) {
    const r = el("tr");
    row.forEach((cell, i) => {
      const c = spec.columns[i], v = cell[0];
      const td = el("td", {class: c.kind === "text" ? (c.name === "message" ? "text msg" : "text") : ""});
      td.dataset.v = v === null ? "" : String(v);
      if (c.name === "message" && v) td.title = v;
      if (c.name === "classification" && CLASS_COLOUR[v]) td.append(el("span", {class: "swatch", style: "background:" + CLASS_COLOUR[v]}));
      td.append(fmt(v, 5));
      if (cell.length > 1 && cell[1] !== null && v !== null) td.append(" ", el("span", {class: "err", text: "± " + fmt(cell[1], 2)}));
      r.append(td);
    });
    r.dataset.text = row.map(c => String(c[0] === null ? "" : c[0])).join(" ").toLowerCase();
    tbody.append(r);
  }
  table.replaceChildren(thead, tbody);
  const apply = () => {
    let shown = 0;
    for (const r of tbody.rows) {
      const ok = filters.every(f => f(r));
      r.hidden = !ok;
      shown += ok;
    }
    table.dataset.shown = String(shown);
    return shown;
  };
  apply();
  return apply;
}
function sortTable(table, col, th) {
  const dir = th.getAttribute("aria-sort") === "ascending" ? "descending" : "ascending";
  table.querySelectorAll("th").forEach(h => h.removeAttribute("aria-sort"));
  th.setAttribute("aria-sort", dir);
  const tbody = table.tBodies[0], sign = dir === "ascending" ? 1 : -1;
  const key = r => r.cells[col].dataset.v;
  const rows = Array.from(tbody.rows).sort((a, b) => {
    const x = key(a), y = key(b);
    if (x === "" || y === "") return (x === "") - (y === "");   // blanks last, either way
    const nx = Number(x), ny = Number(y);
    const c = (!isNaN(nx) && !isNaN(ny)) ? nx - ny : x.localeCompare(y);
    return sign * c;
  });
  tbody.append(...rows);
  table.dataset.sortedBy = th.dataset.col + " " + dir;
}

// --- the page's parts --------------------------------------------------------------------
function overview() {
  const m = D.meta;
  document.getElementById("title").textContent = "Study " + m.file;
  document.getElementById("subtitle").textContent = [m.program + " " + m.version, "revision " + m.revision,
    "grid " + m.grid_file, m.format, "report written " + m.written].join("  ·  ");
  const body = document.getElementById("overview-body");
  if (m.description) body.append(el("p", {class: "description", text: m.description}));
  const facts = el("div", {class: "facts"});
  facts.append(el("span", {}, el("b", {text: m.cases + " of " + m.cases_total}), " cases" + (m.complete ? " (complete)" : " (not complete)")));
  facts.append(el("span", {}, "axes: ", el("b", {text: D.axes.join(", ")})));
  facts.append(el("span", {}, "sub-grids: ", el("b", {text: D.grids.map(g => g.name).join(", ")})));
  body.append(facts);
  const pills = el("div", {class: "facts"});
  for (const [k, n] of Object.entries(m.classifications))
    pills.append(el("span", {class: "pill"}, el("span", {class: "swatch", style: "background:" + (CLASS_COLOUR[k] || "#bbb")}), k + ": " + n));
  for (const [k, n] of Object.entries(m.statuses)) pills.append(el("span", {class: "pill", text: "status " + k + ": " + n}));
  body.append(pills);
  for (const [what, list] of [["Plausibility warnings", m.warnings], ["Validity notes", m.notes]])
    if (list.length) body.append(el("h3", {text: what}), el("ul", {}, ...list.map(w => el("li", {class: "note", text: w}))));
  body.append(el("p", {class: "note", text: "File: " + m.path}));
  const nav = document.getElementById("nav");
  for (const [id, t] of [["overview", "Study"], ["comparison-section", "Nightly comparison"], ["summary-section", "Cases"],
                         ["maps-section", "Classification"], ["metrics-section", "Metrics"], ["case-section", "One case"],
                         ["edges-section", "Bifurcation edges"], ["boundaries-section", "Boundaries"],
                         ["solver-section", "Solver"]])
    if (id !== "comparison-section" || D.comparison) nav.append(el("a", {href: "#" + id, text: t}));
}

function summary() {
  const text = document.getElementById("summary-filter"), cls = document.getElementById("summary-class");
  for (const c of D.classes) cls.append(el("option", {value: c.name, text: c.name}));
  const ci = D.summary.columns.findIndex(c => c.name === "classification");
  const table = document.getElementById("summary-table");
  const apply = buildTable(table, D.summary, [
    r => r.dataset.text.includes(text.value.trim().toLowerCase()),
    r => !cls.value || r.cells[ci].dataset.v === cls.value]);
  const count = () => { document.getElementById("summary-count").textContent = apply() + " of " + D.summary.rows.length + " cases shown"; };
  text.addEventListener("input", count);
  cls.addEventListener("change", count);
  count();
}

function mapChart(canvas, g) {
  const present = D.classes.filter(c => g.cells.some(k => k.cls === c.name));
  const datasets = [];
  g.rows.forEach((row, i) => present.forEach(c => {
    const cells = g.xs.map(x => g.cells.find(k => k.x === x && k.y === row && k.cls === c.name) || null);
    if (!cells.some(k => k)) return;
    datasets.push({label: c.name, first: !datasets.some(d => d.label === c.name), cells,
      data: cells.map(k => k ? [i - 0.46, i + 0.46] : null), backgroundColor: c.colour,
      borderColor: cells.map(k => k && k.status !== "ok" ? "#c0392b" : c.colour), borderWidth: cells.map(k => k && k.status !== "ok" ? 3 : 0),
      grouped: false, barPercentage: 0.96, categoryPercentage: 1.0});
  }));
  return makeChart(canvas, "map-" + g.name, {type: "bar", data: {labels: g.xs, datasets},
    options: {scales: {x: {title: {display: true, text: g.axis_label}, grid: {display: false}, ticks: {autoSkip: false}},
                       y: {min: -0.5, max: g.rows.length - 0.5, grid: {display: false},
                           title: {display: !!g.rows_title, text: g.rows_title},
                           afterBuildTicks: a => { a.ticks = g.rows.map((_, i) => ({value: i})); },
                           ticks: {callback: v => g.rows[v] === undefined ? "" : g.rows[v]}}},
      plugins: {legend: {position: "bottom", labels: {filter: (item, d) => d.datasets[item.datasetIndex].first}},
                tooltip: {callbacks: {title: items => { const k = items[0].dataset.cells[items[0].dataIndex]; return k.name + " (case " + k.case + ")"; },
                                      label: it => { const k = it.dataset.cells[it.dataIndex]; return [(g.rows_title ? g.rows_title + " " + k.y + ", " : "") + g.axis_label + " " + k.x, k.cls + ", status " + k.status]; }}}}}});
}

function maps() {
  const box = document.getElementById("maps");
  for (const g of D.grids) mapChart(chartBox(box, "map-" + g.name, "sub-grid " + g.name, 100 + 42 * g.rows.length), g);
}

function metricChart(canvas, g, name) {
  const M = g.metrics[name];
  const datasets = M.series.map((s, k) => ({label: s.label, errors: s.err,
    data: g.numeric ? s.y.map((y, j) => ({x: g.x[j], y})) : s.y,
    borderColor: PALETTE[k % 10], backgroundColor: PALETTE[k % 10], showLine: g.numeric, pointRadius: 3.5, borderWidth: 1.6}));
  const x = g.numeric ? {type: g.log_x ? "logarithmic" : "linear", title: {display: true, text: g.axis_label},
                         afterBuildTicks: a => { a.ticks = g.x.map(v => ({value: v})); }, ticks: {callback: v => fmt(v)}}
                      : {type: "category", title: {display: true, text: g.axis_label}, offset: true, ticks: {autoSkip: false}};
  return makeChart(canvas, "metric-" + g.name, {type: "line", data: {labels: g.numeric ? undefined : g.xs, datasets},
    options: {scales: {x, y: {type: M.log ? "logarithmic" : "linear", title: {display: true, text: M.label},
                              ticks: {callback: v => fmt(v, 4)}}},
              plugins: {legend: {position: "bottom"}, tooltip: {callbacks: {label: it => {
                const e = it.dataset.errors[it.dataIndex];
                return it.dataset.label + ": " + fmt(yOf(it.raw), 5) + (e ? " ± " + fmt(e, 2) : "") + " " + M.unit; }}}}}});
}

function metrics() {
  const sel = document.getElementById("metric-select"), box = document.getElementById("metrics");
  const names = [...new Set(D.grids.flatMap(g => Object.keys(g.metrics)))];
  for (const m of names) sel.append(el("option", {value: m, text: m}));
  if (names.includes("min_film_thickness_m")) sel.value = "min_film_thickness_m";
  const draw = () => {
    box.replaceChildren();
    for (const g of D.grids) {
      if (!g.metrics[sel.value]) continue;
      const M = g.metrics[sel.value];
      const note = M.missing.length ? "no value (no steady cycle): " + M.missing.join(", ") : "";
      metricChart(chartBox(box, "metric-" + g.name, "sub-grid " + g.name, 300, note), g, sel.value);
    }
  };
  sel.addEventListener("change", draw);
  draw();
}

function caseCharts(c) {
  const s = c.series;
  const note = document.getElementById("case-note");
  if (!s) {
    note.textContent = D.cases.some(x => x.series)
      ? "This study stores no channels for " + c.name + ": its metrics above are all the file holds for it."
      : "This study stores no channels for any case (the grid's study.channels is empty): its metrics, here and above, are all the file holds.";
    for (const n of ["orbit", "film", "reaction"]) if (charts[n]) { charts[n].destroy(); delete charts[n]; }
    return;
  }
  note.textContent = "Drawn: " + s.what + "; " + s.samples + " samples (every k-th and each channel's extremes). Channels stored: " + s.channels.join(", ") + "." +
    (s.not_stored.length ? " Not stored, so not drawn: " + s.not_stored.join(", ") + " (the grid's study.channels)." : "");
  const circle = Array.from({length: 121}, (_, i) => ({x: Math.cos(i * Math.PI / 60), y: Math.sin(i * Math.PI / 60)}));
  const path = s.orbit ? s.orbit.x.map((x, i) => ({x, y: s.orbit.y[i]})) : [];
  makeChart(document.getElementById("chart-orbit"), "orbit", {type: "scatter", data: {datasets: [
      {label: "clearance circle" + (s.orbit ? ", c = " + fmt(s.orbit.clearance_um) + " µm" : ""), data: circle, showLine: true,
       pointRadius: 0, borderColor: "#333", borderWidth: 1, decoration: true},
      {label: "journal centre", data: path, showLine: true, pointRadius: 0, borderColor: PALETTE[0], borderWidth: 1.4},
      {label: "first sample", data: path.slice(0, 1), pointRadius: 4, backgroundColor: PALETTE[3], borderColor: PALETTE[3]}]},
    options: {scales: {x: {min: -1.05, max: 1.05, title: {display: true, text: "e_x / c [–]"}},
      y: {min: -1.05, max: 1.05, title: {display: true, text: "e_y / c [–]"}}}, plugins: {legend: {display: false}}}});
  document.getElementById("orbit-note").textContent = s.orbit
    ? "Inside the clearance circle (c = " + fmt(s.orbit.clearance_um) + " µm), in units of c; the red dot: the first sample."
    : "No orbit drawn: " + (s.orbit_note || "no channels e_x, e_y") + ".";
  const along = k => s.angle.map((a, i) => ({x: a, y: s[k] ? s[k][i] : null}));
  const film = [];
  if (s.h_min) film.push({label: "h_min [µm]", data: along("h_min"), yAxisID: "y", borderColor: PALETTE[0], pointRadius: 0, borderWidth: 1.4});
  if (s.eps) film.push({label: "ε [–]", data: along("eps"), yAxisID: "y2", borderColor: PALETTE[1], pointRadius: 0, borderWidth: 1.2});
  if (s.h_min && c.safe_film_um !== null)
    film.push({label: "safe film " + fmt(c.safe_film_um) + " µm", data: [{x: 0, y: c.safe_film_um}, {x: 360, y: c.safe_film_um}], yAxisID: "y",
               borderColor: "#b22222", borderDash: [6, 4], pointRadius: 0, borderWidth: 1, decoration: true});
  const angleAxis = {type: "linear", min: 0, max: 360, title: {display: true, text: "crank angle [deg]"},
                     afterBuildTicks: a => { a.ticks = [0, 60, 120, 180, 240, 300, 360].map(v => ({value: v})); }};
  if (s.angle) {
    makeChart(document.getElementById("chart-film"), "film", {type: "line", data: {datasets: film},
      options: {scales: {x: angleAxis, y: {position: "left", title: {display: true, text: "h_min [µm]"}},
                         y2: {position: "right", title: {display: true, text: "ε [–]"}, grid: {drawOnChartArea: false}}},
                plugins: {legend: {position: "bottom"}}}});
    makeChart(document.getElementById("chart-reaction"), "reaction", {type: "line", data: {datasets: [
        {label: "reaction force [N]", data: along("reaction_force"), borderColor: PALETTE[2], pointRadius: 0, borderWidth: 1.3}]},
      options: {scales: {x: angleAxis, y: {title: {display: true, text: "|F| [N]"}, ticks: {callback: v => fmt(v, 3)}}},
                plugins: {legend: {display: false}}}});
  }
}

function cases() {
  const sel = document.getElementById("case-select");
  D.cases.forEach((c, i) => sel.append(el("option", {value: String(i), text: c.name + ": " + c.label + " (" + c.classification + ")"})));
  const show = () => {
    const c = D.cases[Number(sel.value)];
    const info = document.getElementById("case-info");
    const facts = el("div", {class: "facts"});
    facts.append(el("span", {}, el("span", {class: "swatch", style: "background:" + (CLASS_COLOUR[c.classification] || "#bbb")}),
                    el("b", {text: c.classification}), ", status " + c.status));
    for (const [label, v, e] of c.facts) if (v !== null) facts.append(el("span", {}, label + " = ", el("b", {text: fmt(v, 5)}), e ? " ± " + fmt(e, 2) : ""));
    info.replaceChildren(facts);
    if (c.message) info.append(el("p", {class: "note", text: c.message}));
    caseCharts(c);
  };
  sel.addEventListener("change", show);
  show();
}

function edges() {
  const box = document.getElementById("edges"), E = D.edges;
  box.append(el("p", {class: "note", text: "Lattice neighbours (one step apart on one numeric axis) whose periodic orbits differ: one end stable, the other not (fold, period doubling, Neimark–Sacker from the multiplier that left the unit circle), or one end without an orbit (orbit_lost). The crossing value interpolates |μ|max − 1."}));
  if (E.note) { box.append(el("p", {class: "note", text: "No edges: " + E.note})); return; }
  if (!E.rows.length) { box.append(el("p", {text: "None: no two neighbouring cells differ in their orbit."})); return; }
  const cols = ["case a", "case b", "axis", "value a", "value b", "kind", "crossing", "classification", "|μ|max a", "|μ|max b"];
  const spec = {columns: cols.map((c, i) => ({name: c, label: c, kind: i < 8 ? "text" : "num"})), rows: E.rows.map(r => r.map(v => [v]))};
  const t = el("table", {id: "edges-table"});
  box.append(el("div", {class: "scroll"}, t));
  buildTable(t, spec, []);
}

function boundaries() {
  const box = document.getElementById("boundaries"), B = D.boundaries;
  const tables = [
    ["Boundaries located between grid points", "Where the minimum film reaches the safe film (safe_film) or the dominant multiplier leaves the unit circle (fold, period_doubling, neimark_sacker), on the line between two lattice neighbours; following a stable safe orbit towards a neighbour without one, where it turns unstable (the crossing's kind) or its branch ends (orbit_end); for those, what the run just beyond found.",
     "boundaries-table", B.boundaries, B.boundaries_note,
     [["kind", "text"], ["axis", "text"], ["value", "num"], ["line", "text"], ["between", "text"], ["runs", "num"], ["periods", "num"], ["converged", "text"], ["beyond an edge", "text"]]],
    ["Cases a refinement added", "Each at the midpoint of a lattice edge whose labels differ or whose metric bends (lubsweep refine).",
     "refinement-table", B.refinement, B.refinement_note,
     [["case", "text"], ["edge", "text"], ["axis", "text"], ["value", "text"], ["reason", "text"], ["classification", "text"], ["h_min [µm]", "num"]]]];
  for (const [title, about, id, rows, note, cols] of tables) {
    box.append(el("h3", {text: title}), el("p", {class: "note", text: about}));
    if (!rows.length) { box.append(el("p", {class: "note", text: note})); continue; }
    const spec = {columns: cols.map(([n, k]) => ({name: n === "classification" ? n : n.replace(/\W+/g, "_"), label: n, kind: k})),
                  rows: rows.map(r => r.map(v => [v]))};
    if (id === "boundaries-table") spec.rows = rows.map(r => [[r[0]], [r[1]], [r[2], r[3]], ...r.slice(4).map(v => [v])]);  // value ± error
    const t = el("table", {id});
    box.append(el("div", {class: "scroll"}, t));
    buildTable(t, spec, []);
  }
}

function solver() {
  const S = D.solver, wi = S.columns.findIndex(c => c.name === "wall_time_s"), si = S.columns.findIndex(c => c.name === "steps");
  const names = S.rows.map(r => r[0][0]), cls = S.rows.map(r => r[1][0]);
  const datasets = [];
  if (wi >= 0) datasets.push({label: "wall time [s]", data: S.rows.map(r => r[wi][0]), backgroundColor: cls.map(c => CLASS_COLOUR[c] || "#bbb"), yAxisID: "y"});
  if (si >= 0) datasets.push({label: "integrator steps", type: "line", data: S.rows.map(r => r[si][0]), borderColor: "#333", backgroundColor: "#333",
                              pointRadius: 3, borderWidth: 1, yAxisID: "y2"});
  makeChart(document.getElementById("chart-solver"), "solver", {type: "bar", data: {labels: names, datasets},
    options: {scales: {y: {title: {display: true, text: "wall time [s]"}},
                       y2: {position: "right", title: {display: true, text: "steps"}, grid: {drawOnChartArea: false}, ticks: {callback: v => fmt(v, 3)}}},
              plugins: {legend: {position: "bottom"}}}});
  const f = document.getElementById("solver-filter"), t = document.getElementById("solver-table");
  const apply = buildTable(t, S, [r => r.dataset.text.includes(f.value.trim().toLowerCase())]);
  f.addEventListener("input", apply);
}

function comparison() {
  const C = D.comparison;
  if (!C) return;
  document.getElementById("comparison-section").hidden = false;
  const box = document.getElementById("comparison"), n = C.regressions.length;
  box.append(el("div", {class: "verdict " + (n ? "bad" : "ok"), id: "verdict",
    text: (n ? "REGRESSION: " + n + " regression" + (n > 1 ? "s" : "") : "ok: every metric within its tolerance") +
          " (" + C.cases + " baseline cases, " + C.in_study + " in the study; baseline " + C.baseline + ")"}));
  if (n) box.append(el("ul", {}, ...C.regressions.map(r => el("li", {text: r}))));
  box.append(el("p", {class: "note", text: "Each cell: |now − baseline| / tolerance (tolerance = atol + rtol · |baseline|; for max_eps of 1 − ε; crank angles modulo 2π). Green within (≤ 1), red outside. Hover a cell for the values."}));
  const t = el("table", {id: "comparison-table"}), head = el("tr", {}, el("th", {class: "text", text: "case"}), el("th", {class: "text", text: "axes"}));
  for (const m of C.metrics) head.append(el("th", {title: "rtol " + C.tolerances[m][0] + ", atol " + C.tolerances[m][1], text: m}));
  const body = el("tbody");
  for (const r of C.rows) {
    const tr = el("tr", {}, el("td", {class: "text", text: r.case}), el("td", {class: "text", text: r.key}));
    if (r.changed.length) { tr.append(el("td", {class: "outside text", colspan: String(C.metrics.length), text: r.changed.join("; ")})); body.append(tr); continue; }
    for (const m of C.metrics) {
      const c = r.cells[m];
      if (!c) { tr.append(el("td", {class: "none", text: "–", title: "no value in either (no steady cycle)"})); continue; }
      tr.append(el("td", {class: c.within ? "within" : "outside", "data-metric": m, text: fmt(c.ratio, 2),
        title: m + ": now " + fmt(c.now, 9) + ", baseline " + fmt(c.baseline, 9) + ", |Δ| " + fmt(c.deviation, 3) + ", tolerance " + fmt(c.tolerance, 3)}));
    }
    body.append(tr);
  }
  t.append(el("thead", {}, head), body);
  box.append(el("div", {class: "scroll"}, t));
  if (C.notes.length) box.append(el("details", {}, el("summary", {text: C.notes.length + " notes: counts that changed (reported, not compared)"}),
                                    el("ul", {}, ...C.notes.map(x => el("li", {class: "note", text: x})))));
}

function selftest() {
  const out = {};
  const table = document.getElementById("summary-table");
  const names = () => Array.from(table.tBodies[0].rows).filter(r => !r.hidden).map(r => r.cells[1].dataset.v);
  const button = table.querySelector('th[data-col="min_film_thickness_m"] button');
  out.before = names();
  button.click(); out.ascending = names(); out.sortedBy = table.dataset.sortedBy;
  button.click(); out.descending = names();
  const f = document.getElementById("summary-filter");
  f.value = "frene"; f.dispatchEvent(new Event("input")); out.filtered = names();
  f.value = ""; f.dispatchEvent(new Event("input"));
  const sel = document.getElementById("case-select"), drawn = {};
  for (const o of sel.options) {
    sel.value = o.value; sel.dispatchEvent(new Event("change"));
    drawn[D.cases[Number(o.value)].name] = ["orbit", "film", "reaction"].map(n => charts[n] ? Number(charts[n].canvas.dataset.drawn || 0) : -1);
  }
  sel.value = "0"; sel.dispatchEvent(new Event("change"));
  out.caseDrawn = drawn;
  const ms = document.getElementById("metric-select"), metricDrawn = {};
  for (const o of ms.options) {
    ms.value = o.value; ms.dispatchEvent(new Event("change"));
    metricDrawn[o.value] = Object.keys(charts).filter(k => k.startsWith("metric-")).map(k => Number(charts[k].canvas.dataset.drawn || 0));
  }
  ms.value = "min_film_thickness_m"; ms.dispatchEvent(new Event("change"));
  out.metricDrawn = metricDrawn;
  const cells = (id, k) => { const t = document.getElementById(id); return t ? Array.from(t.tBodies[0].rows).map(r => r.cells[k].dataset.v) : []; };
  out.boundaryKinds = cells("boundaries-table", 0);
  out.boundaryLost = cells("boundaries-table", 8);
  out.refinementCases = cells("refinement-table", 0);
  return out;
}

function main() {
  const parts = [overview, comparison, summary, maps, metrics, cases, edges, boundaries, solver];
  for (const p of parts) {
    try { p(); } catch (e) { pageError(p.name + ": " + (e && e.stack ? e.stack : e)); }
  }
  if (new URLSearchParams(location.search).get("selftest")) {
    try { document.getElementById("selftest").textContent = JSON.stringify(selftest()); }
    catch (e) { pageError("selftest: " + (e && e.stack ? e.stack : e)); }
  }
  const drawn = {};
  for (const [k, c] of Object.entries(charts)) drawn[k] = Number(c.canvas.dataset.drawn || 0);
  document.body.dataset.charts = JSON.stringify(drawn);
  document.body.dataset.errors = String(ERRORS.length);
  document.body.dataset.ready = "1";
  document.getElementById("footer").textContent = "lubjoint.report · charts: Chart.js " + Chart.version + " (inlined) · " + D.meta.file;
}
main();
</script>
</body>
</html>
"""
