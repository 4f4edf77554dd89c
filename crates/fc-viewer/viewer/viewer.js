// The falling-chain viewer: draws the runs embedded in #fc-data (written by
// `falling-chain view`; the data model is described in src/viewer.rs) and lets
// the reader play, scrub and step through them. No network, no library.
// Lengths are the scene's length unit, times its time unit.
"use strict";
(function () {
  const DATA = JSON.parse(document.getElementById("fc-data").textContent);
  // Eight distinct colours, one per run (the CLI allows at most 8 runs).
  const COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd",
    "#ff7f0e", "#8c564b", "#e377c2", "#17becf"];
  const RED = "#d00000";

  // Joint positions of every kept frame: x, y of joints 0..n per frame.
  function prepare(r, i) {
    const n = r.links, frames = r.t.length, m = n + 1;
    const xs = new Float64Array(frames * m), ys = new Float64Array(frames * m);
    let xmin = r.anchor[0], xmax = xmin, ymin = r.anchor[1], ymax = ymin;
    for (let f = 0; f < frames; f++) {
      // A moving or released pivot has its place per frame (r.pivot).
      let x = r.pivot ? r.pivot[2 * f] : r.anchor[0];
      let y = r.pivot ? r.pivot[2 * f + 1] : r.anchor[1];
      xs[f * m] = x; ys[f * m] = y;
      if (x < xmin) xmin = x; if (x > xmax) xmax = x;
      if (y < ymin) ymin = y; if (y > ymax) ymax = y;
      for (let j = 0; j < n; j++) {
        const a = r.phi[f * n + j], l = r.rod_lengths ? r.rod_lengths[j] : r.rod;
        x += l * Math.cos(a); y += l * Math.sin(a);
        xs[f * m + j + 1] = x; ys[f * m + j + 1] = y;
        if (x < xmin) xmin = x; if (x > xmax) xmax = x;
        if (y < ymin) ymin = y; if (y > ymax) ymax = y;
      }
    }
    const e0 = r.energy.length ? r.energy[0] : 0;
    const balance = r.energy.map((e, k) => e + r.dissipated[k] - e0);
    const change = r.energy.map((e) => e - e0);
    // Line width of each rod (px), as the square root of its mass per
    // length over the mean (the diameter of a rod of one material); null
    // for equal rods, drawn at one width.
    const widths = r.density ? r.density.map((d) => Math.min(Math.max(3 * Math.sqrt(d), 0.75), 10)) : null;
    return Object.assign({}, r, { xs, ys, m, frames, widths, color: COLORS[i % COLORS.length],
      bounds: [xmin, xmax, ymin, ymax], balance, change });
  }

  const runs = DATA.runs.map(prepare);

  // The common time grid: every kept sample time of every run, sorted.
  const grid = (function () {
    const all = [];
    runs.forEach((r) => r.t.forEach((t) => all.push(t)));
    all.sort((a, b) => a - b);
    const out = [];
    for (const t of all) if (!out.length || t - out[out.length - 1] > 1e-12 * Math.max(1, Math.abs(t))) out.push(t);
    return out.length ? out : [0];
  })();

  // The frame of run r shown at time t: the last one at or before t.
  function frameAt(r, t) {
    let lo = 0, hi = r.frames - 1;
    if (hi < 0) return -1;
    if (t >= r.t[hi]) return hi;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (r.t[mid] <= t * (1 + 1e-14) + 1e-300) lo = mid; else hi = mid - 1;
    }
    return lo;
  }

  // ---- the chain canvas: equal scales, y up ----
  const chain = document.getElementById("chain");
  const cx = chain.getContext("2d");
  const view = (function () {
    let [xmin, xmax, ymin, ymax] = runs.length ? runs[0].bounds : [-1, 1, -1, 1];
    runs.forEach((r) => {
      xmin = Math.min(xmin, r.bounds[0]); xmax = Math.max(xmax, r.bounds[1]);
      ymin = Math.min(ymin, r.bounds[2]); ymax = Math.max(ymax, r.bounds[3]);
    });
    const span = Math.max(xmax - xmin, ymax - ymin, 1e-9);
    const pad = 0.04 * span;
    xmin -= pad; xmax += pad; ymin -= pad; ymax += pad;
    const margin = 24;
    const s = Math.min((chain.width - 2 * margin) / (xmax - xmin), (chain.height - 2 * margin) / (ymax - ymin));
    const ox = (chain.width - s * (xmax - xmin)) / 2, oy = (chain.height - s * (ymax - ymin)) / 2;
    return { s, px: (x) => ox + (x - xmin) * s, py: (y) => oy + (ymax - y) * s };
  })();

  // Joint forces (issue "elastic links"): one colour scale over all runs.
  const forceKinds = ["tension", "shear"].filter((k) => runs.some((r) => r.forces && r.forces[k]));
  let forceKind = forceKinds.length ? forceKinds[0] : null;
  function forceRange(kind) {
    let lo = Infinity, hi = -Infinity;
    runs.forEach((r) => {
      const v = r.forces && r.forces[kind];
      if (v) for (const x of v) { if (x < lo) lo = x; if (x > hi) hi = x; }
    });
    return hi > lo ? [lo, hi] : [lo - 1, lo + 1];
  }
  // A perceptual ramp (dark blue, teal, yellow) for u in [0, 1].
  function ramp(u) {
    const stops = [[48, 18, 59], [40, 120, 142], [53, 183, 121], [253, 231, 37]];
    const x = Math.min(Math.max(u, 0), 1) * (stops.length - 1);
    const k = Math.min(Math.floor(x), stops.length - 2), w = x - k;
    const c = stops[k].map((a, j) => Math.round(a + w * (stops[k + 1][j] - a)));
    return "rgb(" + c.join(",") + ")";
  }

  // The outline (px each side) of a chain coloured by its forces.
  const OUTLINE = 2.5;
  const drawnTip = runs.map(() => null);
  const drawnFrame = runs.map(() => -1);
  const drawnPivot = runs.map(() => null);
  const drawnFloor = runs.map(() => undefined);

  function drawChain(t) {
    cx.clearRect(0, 0, chain.width, chain.height);
    cx.fillStyle = "#fff";
    cx.fillRect(0, 0, chain.width, chain.height);
    const range = forceKind ? forceRange(forceKind) : null;
    // The floor of each run that has one, with its own run only: the line
    // y = h + x tan(a) under that run's chain (its own x extent and a
    // tenth more each side), in the run's colour, hatched below as ground.
    runs.forEach((r, i) => {
      if (!r.floor) return;
      const [h, a] = r.floor, [xmin, xmax] = r.bounds, pad = 0.1 * (xmax - xmin) + 0.02 * (r.rod * r.links);
      const x0 = xmin - pad, x1 = xmax + pad, k = Math.tan(a);
      drawnFloor[i] = [x0, h + x0 * k, x1, h + x1 * k];
      const [p0, p1] = [[view.px(x0), view.py(h + x0 * k)], [view.px(x1), view.py(h + x1 * k)]];
      cx.strokeStyle = r.color; cx.lineWidth = 3; cx.lineCap = "butt";
      cx.beginPath(); cx.moveTo(p0[0], p0[1]); cx.lineTo(p1[0], p1[1]); cx.stroke();
      const len = Math.hypot(p1[0] - p0[0], p1[1] - p0[1]), ticks = Math.floor(len / 12);
      cx.lineWidth = 1;
      cx.beginPath();
      for (let q = 0; q <= ticks; q++) {
        const x = p0[0] + (p1[0] - p0[0]) * q / Math.max(ticks, 1), y = p0[1] + (p1[1] - p0[1]) * q / Math.max(ticks, 1);
        cx.moveTo(x, y + 2); cx.lineTo(x - 6, y + 9);
      }
      cx.stroke();
    });
    runs.forEach((r, i) => {
      const f = frameAt(r, t);
      if (f < 0) return;
      const base = f * r.m;
      // The tip's path up to this frame.
      cx.strokeStyle = r.color; cx.globalAlpha = 0.45; cx.lineWidth = 1;
      cx.beginPath();
      for (let k = 0; k <= f; k++) {
        const j = k * r.m + r.links;
        if (k === 0) cx.moveTo(view.px(r.xs[j]), view.py(r.ys[j]));
        else cx.lineTo(view.px(r.xs[j]), view.py(r.ys[j]));
      }
      cx.stroke();
      cx.globalAlpha = 1;
      const forces = range && r.forces && r.forces[forceKind];
      cx.lineJoin = "round"; cx.lineCap = "round";
      if (forces) {
        // Outlined in the run's colour, so that runs coloured by their
        // forces are still told apart (the legend's colours).
        cx.strokeStyle = r.color;
        for (let j = 0; j < r.links; j++) {
          cx.lineWidth = (r.widths ? r.widths[j] * 1.75 : 3.5) + 2 * OUTLINE;
          cx.beginPath();
          cx.moveTo(view.px(r.xs[base + j]), view.py(r.ys[base + j]));
          cx.lineTo(view.px(r.xs[base + j + 1]), view.py(r.ys[base + j + 1]));
          cx.stroke();
        }
      }
      cx.lineWidth = forces ? 3.5 : 2;
      if (forces || r.widths) {
        // Rod by rod: its colour by the joint force, its width by its
        // mass per length.
        const w = range ? range[1] - range[0] : 1;
        cx.strokeStyle = r.color;
        for (let j = 0; j < r.links; j++) {
          if (forces) {
            const mean = 0.5 * (forces[f * r.m + j] + forces[f * r.m + j + 1]);
            cx.strokeStyle = ramp((mean - range[0]) / w);
          }
          if (r.widths) cx.lineWidth = r.widths[j] * (forces ? 1.75 : 1);
          cx.beginPath();
          cx.moveTo(view.px(r.xs[base + j]), view.py(r.ys[base + j]));
          cx.lineTo(view.px(r.xs[base + j + 1]), view.py(r.ys[base + j + 1]));
          cx.stroke();
        }
      } else {
        cx.strokeStyle = r.color;
        cx.beginPath();
        cx.moveTo(view.px(r.xs[base]), view.py(r.ys[base]));
        for (let j = 1; j < r.m; j++) cx.lineTo(view.px(r.xs[base + j]), view.py(r.ys[base + j]));
        cx.stroke();
      }
      const tx = r.xs[base + r.links], ty = r.ys[base + r.links];
      drawnTip[i] = [tx, ty];
      drawnFrame[i] = f;
      cx.fillStyle = r.color;
      cx.beginPath(); cx.arc(view.px(tx), view.py(ty), 4, 0, 2 * Math.PI); cx.fill();
      if (r.t_failed !== null && t >= r.t[r.frames - 1]) {
        cx.fillStyle = RED; cx.font = "bold 14px system-ui, sans-serif";
        cx.fillText(r.label + ": " + r.status + " at t = " + fmt(r.t_failed), 12, 20 + 18 * i);
      }
    });
    // The pivot P0 of each run where it is now (a moving or released
    // pivot moves; a fixed one is the run's anchor).
    runs.forEach((r, i) => {
      const f = drawnFrame[i];
      if (f < 0) return;
      drawnPivot[i] = [r.xs[f * r.m], r.ys[f * r.m]];
      cx.fillStyle = "#000";
      cx.fillRect(view.px(drawnPivot[i][0]) - 3, view.py(drawnPivot[i][1]) - 3, 6, 6);
    });
    if (range) drawColorBar(range);
  }

  function drawColorBar(range) {
    const x = chain.width - 30, y0 = 30, h = 160;
    for (let k = 0; k < h; k++) {
      cx.fillStyle = ramp(1 - k / (h - 1));
      cx.fillRect(x, y0 + k, 12, 1);
    }
    cx.fillStyle = "#222"; cx.font = "11px system-ui, sans-serif"; cx.textAlign = "right";
    cx.fillText(fmt(range[1]), x - 4, y0 + 8);
    cx.fillText(fmt(range[0]), x - 4, y0 + h);
    cx.fillText(forceKind, x + 12, y0 - 8);
    cx.textAlign = "left";
  }

  // ---- the curves: drawn once to an offscreen canvas, then a cursor ----
  const tMax = grid[grid.length - 1] > grid[0] ? grid[grid.length - 1] : grid[0] + 1;
  function niceTicks(lo, hi, count) {
    const step0 = (hi - lo) / Math.max(count, 1);
    const p = Math.pow(10, Math.floor(Math.log10(step0)));
    const step = [1, 2, 5, 10].map((k) => k * p).find((s) => s >= step0) || 10 * p;
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step && out.length < 50; v += step) out.push(v);
    return out;
  }
  function plotCurves(canvas, title, series) {
    const W = canvas.width, H = canvas.height;
    const box = { l: 62, r: W - 12, t: 26, b: H - 34 };
    let lo = Infinity, hi = -Infinity;
    series.forEach((s) => s.y.forEach((v) => { if (v < lo) lo = v; if (v > hi) hi = v; }));
    if (!(hi > lo)) { lo = (isFinite(lo) ? lo : 0) - 1; hi = lo + 2; }
    const pad = 0.05 * (hi - lo); lo -= pad; hi += pad;
    const X = (t) => box.l + (t - grid[0]) / (tMax - grid[0]) * (box.r - box.l);
    const Y = (v) => box.b - (v - lo) / (hi - lo) * (box.b - box.t);
    const back = document.createElement("canvas");
    back.width = W; back.height = H;
    const g = back.getContext("2d");
    g.fillStyle = "#fff"; g.fillRect(0, 0, W, H);
    g.strokeStyle = "#888"; g.lineWidth = 1; g.strokeRect(box.l, box.t, box.r - box.l, box.b - box.t);
    g.fillStyle = "#222"; g.font = "12px system-ui, sans-serif";
    g.fillText(title, box.l, 16);
    g.textAlign = "center";
    niceTicks(grid[0], tMax, 6).forEach((v) => {
      g.fillText(fmt(v), X(v), box.b + 16);
      g.beginPath(); g.moveTo(X(v), box.b); g.lineTo(X(v), box.b + 4); g.stroke();
    });
    g.fillText("t", (box.l + box.r) / 2, H - 4);
    g.textAlign = "right";
    niceTicks(lo, hi, 5).forEach((v) => {
      g.fillText(fmt(v), box.l - 6, Y(v) + 4);
      g.beginPath(); g.moveTo(box.l - 4, Y(v)); g.lineTo(box.l, Y(v)); g.stroke();
    });
    g.textAlign = "left";
    g.save(); g.beginPath(); g.rect(box.l, box.t, box.r - box.l, box.b - box.t); g.clip();
    series.forEach((s) => {
      g.strokeStyle = s.color; g.lineWidth = 1.5; g.setLineDash(s.dash || []);
      g.beginPath();
      s.t.forEach((t, k) => (k ? g.lineTo(X(t), Y(s.y[k])) : g.moveTo(X(t), Y(s.y[k]))));
      g.stroke();
    });
    g.restore();
    return { canvas, ctx: canvas.getContext("2d"), back, box, X,
      tOf: (px) => grid[0] + (px - box.l) / (box.r - box.l) * (tMax - grid[0]) };
  }
  const speedPlot = plotCurves(document.getElementById("speed"), "tip speed |v_tip|",
    runs.map((r) => ({ t: r.t, y: r.speed, color: r.color })));
  const energyPlot = plotCurves(document.getElementById("energy"),
    "energy: E − E(0) solid, balance E + W − E(0) dashed",
    runs.flatMap((r) => [{ t: r.t, y: r.change, color: r.color },
      { t: r.t, y: r.balance, color: r.color, dash: [5, 4] }]));
  function drawCursor(p, t) {
    p.ctx.drawImage(p.back, 0, 0);
    p.ctx.strokeStyle = "#000"; p.ctx.lineWidth = 1;
    p.ctx.beginPath(); p.ctx.moveTo(p.X(t), p.box.t); p.ctx.lineTo(p.X(t), p.box.b); p.ctx.stroke();
  }

  // ---- numbers, summary, legend ----
  function fmt(v) {
    if (typeof v !== "number" || !isFinite(v)) return String(v);
    if (v === 0) return "0";
    const a = Math.abs(v);
    return a >= 1e-3 && a < 1e5 ? String(Number(v.toPrecision(4))) : v.toExponential(3);
  }
  const SUMMARY_KEYS = ["status", "method", "model", "links", "steps", "tip_speed_max", "t_tip_speed_max",
    "t_reached", "t_failed", "tip_end", "energy_balance_error", "pivot_force_max", "tension_max",
    "floor_force_max", "forces_resolved"];
  function buildSummary() {
    const table = document.getElementById("summary");
    const head = table.insertRow();
    ["run"].concat(SUMMARY_KEYS).forEach((k) => {
      const th = document.createElement("th"); th.textContent = k; head.appendChild(th);
    });
    runs.forEach((r, i) => {
      const row = table.insertRow();
      row.dataset.run = String(i);
      const name = row.insertCell();
      name.innerHTML = '<span class="swatch"></span>';
      name.firstChild.style.background = r.color;
      name.appendChild(document.createTextNode(r.label));
      SUMMARY_KEYS.forEach((k) => {
        const cell = row.insertCell();
        cell.dataset.key = k;
        const v = r.summary[k];
        if (v === undefined || v === null) {
          cell.textContent = k === "status" ? r.status : "—";
          if (k === "status") cell.dataset.value = JSON.stringify(r.status);
          return;
        }
        cell.dataset.value = JSON.stringify(v);
        cell.textContent = Array.isArray(v) ? "(" + v.map(fmt).join(", ") + ")" : typeof v === "number" && !Number.isInteger(v) ? fmt(v) : String(v);
        if ((k === "status" && v !== "ok") || k === "t_failed") cell.className = "failed";
      });
    });
    const legend = document.getElementById("legend");
    runs.forEach((r) => {
      const s = document.createElement("span");
      s.innerHTML = '<span class="swatch"></span>';
      s.firstChild.style.background = r.color;
      s.appendChild(document.createTextNode(r.label));
      if (r.floor) {
        const f = document.createElement("span");
        f.className = "floor-mark"; f.style.borderColor = r.color; f.title = "this run's floor (hatched line)";
        f.textContent = "floor";
        s.appendChild(f);
      }
      legend.appendChild(s);
    });
    const notes = [];
    runs.forEach((r) => {
      if (r.stride > 1) notes.push(r.label + ": thinned to one sample in " + r.stride + " of its " + r.samples + ", and the last (" + r.frames + " shown)");
      if (r.source) notes.push(r.label + ": read from " + r.source + " (method, status and steps are not in that file; the maximum tip speed is over its samples)");
    });
    if (forceKinds.length) notes.push("chain colour: joint " + forceKinds.join(" / ") + ", mean of each rod's two joints, one scale over all runs" + (runs.length > 1 ? "; each chain outlined in its run's colour" : ""));
    if (runs.some((r) => r.floor)) notes.push("a floor is drawn under its own run only, in that run's colour, hatched");
    document.getElementById("notes").textContent = notes.join(". ");
    if (forceKinds.length) {
      const sel = document.getElementById("force");
      forceKinds.forEach((k) => { const o = document.createElement("option"); o.value = k; o.textContent = k; sel.appendChild(o); });
      document.getElementById("force-choice").hidden = false;
      sel.addEventListener("change", () => { forceKind = sel.value; render(); });
    }
  }

  // ---- state and controls ----
  const slider = document.getElementById("slider");
  const timeLabel = document.getElementById("time");
  const playButton = document.getElementById("play");
  const rateSelect = document.getElementById("rate");
  slider.max = String(grid.length - 1);
  let index = 0, playing = false, playTime = grid[0], lastStamp = null;
  const drawTimes = [];

  function render() {
    const start = performance.now();
    const t = grid[index];
    drawChain(t);
    drawCursor(speedPlot, t);
    drawCursor(energyPlot, t);
    slider.value = String(index);
    timeLabel.textContent = "t = " + t.toFixed(3);
    const failed = runs.some((r) => r.t_failed !== null && t >= r.t[r.frames - 1]);
    timeLabel.className = failed ? "failed" : "";
    drawTimes.push(performance.now() - start);
    if (drawTimes.length > 10000) drawTimes.shift();
  }
  function seek(i) {
    index = Math.min(Math.max(Math.round(i), 0), grid.length - 1);
    playTime = grid[index];
    render();
    remember();
  }
  // The time shown, in the page's URL (#t=2.76), so that a link opens the
  // page there; a page in an iframe without a URL of its own keeps none.
  let opened = false;
  function remember() {
    if (playing || !opened) return;
    try { history.replaceState(null, "", "#t=" + Number(grid[index].toPrecision(6))); } catch (e) { /* no URL */ }
  }
  // The time a URL asks for (#t=2.76), or null.
  function hashTime() {
    const m = /(?:^#|&)t=([^&]*)/.exec(location.hash);
    const t = m ? Number(decodeURIComponent(m[1])) : NaN;
    return isFinite(t) ? t : null;
  }
  window.addEventListener("hashchange", () => { const t = hashTime(); if (t !== null) { setPlaying(false); seekTime(t); } });
  function seekTime(t) {
    let lo = 0, hi = grid.length - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (grid[mid] <= t) lo = mid; else hi = mid - 1; }
    // The nearer of the two grid times around t.
    if (lo + 1 < grid.length && grid[lo + 1] - t < t - grid[lo]) lo += 1;
    seek(lo);
  }
  function setPlaying(on) {
    playing = on;
    playButton.textContent = on ? "Pause" : "Play";
    lastStamp = null;
    if (on && index >= grid.length - 1) seek(0);
    if (on) requestAnimationFrame(tick);
    else remember();
  }
  function tick(stamp) {
    if (!playing) return;
    if (lastStamp !== null) {
      playTime += (stamp - lastStamp) / 1000 * Number(rateSelect.value);
      let i = index;
      while (i + 1 < grid.length && grid[i + 1] <= playTime) i++;
      if (i !== index) { index = i; render(); }
      if (index >= grid.length - 1) { setPlaying(false); return; }
    }
    lastStamp = stamp;
    requestAnimationFrame(tick);
  }
  playButton.addEventListener("click", () => setPlaying(!playing));
  slider.addEventListener("input", () => { setPlaying(false); seek(Number(slider.value)); });
  document.addEventListener("keydown", (e) => {
    if (e.key === "ArrowRight" || e.key === "ArrowLeft") {
      e.preventDefault();
      setPlaying(false);
      seek(index + (e.key === "ArrowRight" ? 1 : -1));
    } else if (e.key === " ") {
      e.preventDefault();
      setPlaying(!playing);
    }
  });
  [speedPlot, energyPlot].forEach((p) => p.canvas.addEventListener("click", (e) => {
    const rect = p.canvas.getBoundingClientRect();
    const px = (e.clientX - rect.left) * p.canvas.width / rect.width;
    setPlaying(false);
    seekTime(p.tOf(px));
  }));

  buildSummary();
  // Opened at the time its URL asks for (#t=2.76), else at `view --at`'s,
  // else at the start: the sample nearest it.
  const opening = hashTime() !== null ? hashTime() : typeof DATA.at === "number" ? DATA.at : null;
  if (opening !== null) seekTime(opening); else seek(0);
  opened = true;

  // What a test or a notebook may read: the state the drawing used.
  window.fallingChain = {
    runs: runs.length,
    frames: grid.length,
    colors: runs.map((r) => r.color),
    time: () => grid[index],
    index: () => index,
    seek, seekTime,
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    playing: () => playing,
    drawnTip: (i) => drawnTip[i],
    drawnPivot: (i) => drawnPivot[i],
    // The floor line of run i as drawn, [x0, y0, x1, y1], or undefined.
    drawnFloor: (i) => drawnFloor[i],
    // Run i's extent over its frames, [xmin, xmax, ymin, ymax].
    bounds: (i) => runs[i].bounds,
    // The outline (px each side) of a chain coloured by its forces.
    outline: OUTLINE,
    // The line width (px) of rod j of run i, as drawn without forces.
    rodWidth: (i, j) => (runs[i].widths ? runs[i].widths[j] : 2),
    // Joint j (0 = P0) of run i as drawn now.
    joint: (i, j) => {
      const r = runs[i], f = drawnFrame[i];
      return f < 0 ? null : [r.xs[f * r.m + j], r.ys[f * r.m + j]];
    },
    toPixel: (x, y) => [view.px(x), view.py(y)],
    drawTimes: () => drawTimes.slice(),
  };
})();
