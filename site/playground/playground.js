// The playground: plclab's Python core in Pyodide, a plant beside it, a live timing diagram.
// The Python side is plclab/site/playground_api.py (Session) and plclab/site/lab_check.py.
"use strict";
(function () {
  const $ = (id) => document.getElementById(id);
  const el = {
    lang: $("pg-lang"), plant: $("pg-plant"), lab: $("pg-lab"), code: $("pg-code"),
    gutter: $("pg-gutter"), compile: $("pg-compile"), run60: $("pg-run60"), live: $("pg-live"),
    check: $("pg-check"), status: $("pg-status"), diags: $("pg-diagnostics"),
    canvas: $("pg-diagram"), summary: $("pg-summary"), results: $("pg-results"),
    buttons: $("pg-buttons"),
  };
  const MOTOR_BUTTONS = [["START", true], ["STOP", false], ["OL_RESET", true]];
  const state = { py: null, api: null, labApi: null, labs: {}, session: null, rows: [],
                  live: false, loadMs: null, errors: [] };
  const toJs = (p) => p.toJs({ dict_converter: Object.fromEntries });

  // ------------------------------------------------------------------ editor
  function renumber(bad) {
    const n = el.code.value.split("\n").length;
    const lines = [];
    for (let i = 1; i <= n; i++) {
      lines.push(bad && bad.has(i) ? `<span class="pg-bad" data-line="${i}">${i}</span>` : `${i}`);
    }
    el.gutter.innerHTML = lines.join("\n");
    el.gutter.scrollTop = el.code.scrollTop;
  }
  el.code.addEventListener("input", () => renumber());
  el.code.addEventListener("scroll", () => { el.gutter.scrollTop = el.code.scrollTop; });

  function fromHash() {
    const h = new URLSearchParams(location.hash.slice(1));
    if (h.get("code")) {
      const b64 = h.get("code").replace(/-/g, "+").replace(/_/g, "/");
      const bin = atob(b64 + "===".slice((b64.length + 3) % 4));
      el.code.value = new TextDecoder().decode(Uint8Array.from(bin, (c) => c.charCodeAt(0)));
    }
    if (h.get("lang")) el.lang.value = h.get("lang");
    if (h.get("lab")) state.wantLab = h.get("lab");
  }

  // ------------------------------------------------------------------ diagnostics
  function showDiagnostics(list) {
    el.diags.innerHTML = "";
    const bad = new Set();
    for (const d of list) {
      const li = document.createElement("li");
      li.className = "pg-" + d.severity;
      li.dataset.code = d.code;
      li.dataset.line = d.line;
      li.textContent = (d.line ? `line ${d.line}${d.col ? ":" + d.col : ""}: ` : "") +
        `${d.severity} ${d.code}: ${d.message}`;
      li.addEventListener("click", () => goToLine(d.line));
      el.diags.appendChild(li);
      if (d.severity === "error" && d.line) bad.add(d.line);
    }
    renumber(bad);
  }
  function goToLine(line) {
    if (!line) return;
    const lines = el.code.value.split("\n");
    const start = lines.slice(0, line - 1).join("\n").length + (line > 1 ? 1 : 0);
    el.code.focus();
    el.code.setSelectionRange(start, start + (lines[line - 1] || "").length);
  }

  // ------------------------------------------------------------------ timing diagram
  function draw() {
    const c = el.canvas, g = c.getContext("2d");
    const rows = state.rows;
    g.fillStyle = "#1e2430"; g.fillRect(0, 0, c.width, c.height);
    if (!rows.length) return;
    const names = Object.keys(rows[0]).filter((k) => k !== "t");
    const left = 90, lane = (c.height - 24) / names.length;
    const t1 = rows[rows.length - 1].t, t0 = Math.max(0, t1 - 60);
    const x = (t) => left + (c.width - left - 10) * (t - t0) / Math.max(t1 - t0, 1e-9);
    g.font = "12px sans-serif";
    names.forEach((name, i) => {
      const top = 6 + i * lane, h = lane - 8;
      const vals = rows.map((r) => (typeof r[name] === "boolean" ? (r[name] ? 1 : 0) : r[name]));
      const lo = Math.min(...vals), hi = Math.max(...vals);
      const y = (v) => top + h - h * (typeof rows[0][name] === "boolean" ? v : (v - lo) / Math.max(hi - lo, 1e-9));
      g.fillStyle = "#cfd8e3"; g.fillText(name, 6, top + h / 2 + 4);
      g.strokeStyle = typeof rows[0][name] === "boolean" ? "#5fd07a" : "#5ea8ff";
      g.lineWidth = 2; g.beginPath();
      let first = true, prev = null;
      rows.forEach((r, k) => {
        if (r.t < t0) return;
        const xv = x(r.t), yv = y(vals[k]);
        if (first) { g.moveTo(xv, yv); first = false; }
        else if (typeof rows[0][name] === "boolean") { g.lineTo(xv, prev); g.lineTo(xv, yv); }
        else g.lineTo(xv, yv);
        prev = yv;
      });
      g.stroke();
    });
    g.fillStyle = "#8a96a8";
    g.fillText(`${t0.toFixed(0)} s`, left, c.height - 6);
    g.fillText(`${t1.toFixed(1)} s`, c.width - 60, c.height - 6);
  }
  function switchings(name) {
    let n = 0;
    for (let i = 1; i < state.rows.length; i++) if (state.rows[i][name] !== state.rows[i - 1][name]) n++;
    return n;
  }
  function summarise() {
    if (!state.rows.length) { el.summary.textContent = ""; return; }
    const out = el.plant.value === "tank" ? "PUMP" : "K1";
    const last = state.rows[state.rows.length - 1];
    el.summary.textContent = `t = ${last.t.toFixed(1)} s, ${state.session.scans} scans: ` +
      `${out} switched ${switchings(out)} times, now ${last[out] ? "ON" : "OFF"}.`;
    el.summary.dataset.switchings = switchings(out);
  }

  // ------------------------------------------------------------------ running
  function compile() {
    stopLive();
    if (state.session) state.session.destroy();
    const t = performance.now();
    state.session = state.api.session(el.code.value, el.lang.value, el.plant.value, 20.0);
    const ms = performance.now() - t;
    showDiagnostics(toJs(state.session.diagnostics));
    state.rows = [state.session.sample().toJs({ dict_converter: Object.fromEntries })];
    draw(); summarise();
    const ok = state.session.ok;
    el.status.textContent = ok ? `Compiled in ${ms.toFixed(0)} ms; the ${el.plant.value} is at t = 0.`
      : "The program does not compile: see the messages below (click one to go to its line).";
    el.status.dataset.state = ok ? "compiled" : "error";
    return ok;
  }
  function advance(seconds) {
    const rows = toJs(state.session.advance(seconds, 0.1));
    state.rows.push(...rows);
    if (state.rows.length > 5000) state.rows.splice(0, state.rows.length - 5000);
    const diags = toJs(state.session.diagnostics);
    if (!state.session.ok) showDiagnostics(diags);
    draw(); summarise();
  }
  function run(seconds) {
    if (!compile()) return null;
    const t = performance.now();
    advance(seconds);
    const ms = performance.now() - t;
    const scans = state.session.scans;
    el.status.textContent = `Ran ${seconds} s of virtual time (${scans} scans) in ${ms.toFixed(0)} ms.`;
    el.status.dataset.state = "ran";
    return { ms, scans, scansPerSecond: scans / (ms / 1000) };
  }
  function stopLive() { state.live = false; el.live.textContent = "Run live"; }
  function liveLoop() {
    if (!state.live || !state.session || !state.session.ok) { stopLive(); return; }
    advance(0.2);
    requestAnimationFrame(liveLoop);
  }
  el.compile.onclick = compile;
  el.run60.onclick = () => run(60);
  el.live.onclick = () => {
    if (state.live) { stopLive(); return; }
    if (!compile()) return;
    state.live = true; el.live.textContent = "Stop"; requestAnimationFrame(liveLoop);
  };

  function motorButtons() {
    el.buttons.innerHTML = "";
    if (el.plant.value !== "motor") return;
    for (const [name, pressed] of MOTOR_BUTTONS) {
      const b = document.createElement("button");
      b.className = "md-button"; b.textContent = name; b.title = `hold to press ${name}`;
      const down = () => state.session && state.session.set_input(name, pressed);
      const up = () => state.session && state.session.release(name);
      b.addEventListener("pointerdown", down); b.addEventListener("pointerup", up);
      b.addEventListener("pointerleave", up);
      el.buttons.appendChild(b);
    }
  }
  el.plant.onchange = () => { motorButtons(); if (state.api) compile(); };

  // ------------------------------------------------------------------ lab check
  function checkLab() {
    const lab = state.labs[el.lab.value];
    if (!lab) { el.status.textContent = "Choose a lab first."; return null; }
    stopLive();
    const t = performance.now();
    const res = toJs(state.labApi.check_lab(el.code.value, el.lang.value, state.py.toPy(lab)));
    showDiagnostics(res.diagnostics);
    el.results.innerHTML = "<tr><th>scenario</th><th>criterion</th><th>result</th><th>points</th></tr>";
    for (const r of res.results) {
      const tr = document.createElement("tr");
      tr.className = r.passed === null ? "pg-skip" : r.passed ? "pg-pass" : "pg-fail";
      for (const v of [r.scenario, r.criterion, r.why, r.passed ? r.points : 0]) {
        const td = document.createElement("td"); td.textContent = v; tr.appendChild(td);
      }
      el.results.appendChild(tr);
    }
    el.status.textContent = `${lab.title}: ${res.points} of ${res.of} points in the visible ` +
      `scenarios (${((performance.now() - t) / 1000).toFixed(1)} s). The grader's hidden scenarios may find more.`;
    el.status.dataset.state = "checked";
    return res;
  }
  el.check.onclick = checkLab;
  el.lab.onchange = () => {
    const lab = state.labs[el.lab.value];
    if (lab) { el.plant.value = lab.plant; motorButtons(); }
  };

  // ------------------------------------------------------------------ start
  async function start() {
    const t0 = performance.now();
    fromHash();
    const [py, zip, labs] = await Promise.all([
      loadPyodide({ indexURL: new URL("../pyodide/", location.href).href }),
      fetch("plclab-core.zip").then((r) => r.arrayBuffer()),
      fetch("labs.json").then((r) => r.json()),
    ]);
    py.unpackArchive(zip, "zip", { extractDir: "/home/pyodide/core" });
    py.runPython("import sys; sys.path.insert(0, '/home/pyodide/core')");
    state.py = py;
    state.api = py.pyimport("plclab.site.playground_api");
    state.labApi = py.pyimport("plclab.site.lab_check");
    state.labs = labs;
    for (const [id, lab] of Object.entries(labs)) {
      const o = document.createElement("option"); o.value = id; o.textContent = lab.title;
      el.lab.appendChild(o);
    }
    if (!el.code.value) el.code.value = state.api.TANK_EXAMPLE;
    if (state.wantLab && labs[state.wantLab]) { el.lab.value = state.wantLab; el.lab.onchange(); }
    renumber(); motorButtons();
    state.loadMs = performance.now() - t0;
    for (const b of [el.compile, el.run60, el.live, el.check]) b.disabled = false;
    el.status.textContent = `Ready: Python and plclab loaded in ${(state.loadMs / 1000).toFixed(1)} s.`;
    el.status.dataset.state = "ready";
  }
  const ready = start().catch((e) => {
    el.status.textContent = "The playground could not start: " + e;
    el.status.dataset.state = "failed";
    throw e;
  });
  // for the browser tests and the benchmark
  window.plclabPlayground = { ready, state, compile, run, checkLab };
})();
