// The playground page: an editor, a plant, a live timing diagram and a watch panel. plclab's
// Python core runs in a Web Worker (worker.js; its Python side is plclab/site/playground_api.py
// and plclab/site/lab_check.py), so the page answers whatever the program does: Run, Pause,
// Step and Stop always work, and a call that takes too long is ended by the page (ADR 0028).
"use strict";
(function () {
  // The page's language: the English edition has no ui.js; another edition's ui.js (made by
  // plclab site build from plclab/locale/<lang>/ui.toml) sets window.PLCLAB_UI to its language
  // and the texts of every t(text) below. The worker gets the language too, so that plclab's
  // messages come from the problem catalogue of that language (ADR 0071).
  const UI = window.PLCLAB_UI || { lang: "en", texts: {} };
  const LANG = UI.lang;
  function t(text, params) {
    return (UI.texts[text] || text).replace(/\{(\w+)\}/g, (all, k) =>
      (params && k in params ? String(params[k]) : all));
  }
  // a number in prose: a decimal comma where the language writes one (never in ST)
  const num = (x, digits) => (LANG === "ru" ? x.toFixed(digits).replace(".", ",") : x.toFixed(digits));
  // the scripts, the worker and Python are the English edition's (one copy for every edition)
  const SCRIPTS = new URL(".", document.currentScript.src);
  const SEVERITY = { error: t("error"), warning: t("warning") };
  const $ = (id) => document.getElementById(id);
  const el = {
    lang: $("pg-lang"), plant: $("pg-plant"), lab: $("pg-lab"), code: $("pg-code"),
    gutter: $("pg-gutter"), compile: $("pg-compile"), run60: $("pg-run60"), live: $("pg-live"),
    pause: $("pg-pause"), step: $("pg-step"), stop: $("pg-stop"), speed: $("pg-speed"),
    tests: $("pg-tests"), share: $("pg-share"), check: $("pg-check"), status: $("pg-status"),
    clock: $("pg-clock"), diags: $("pg-diagnostics"), canvas: $("pg-diagram"),
    summary: $("pg-summary"), results: $("pg-results"), buttons: $("pg-buttons"),
    watch: $("pg-watch"), testOut: $("pg-test-output"), layer: $("pg-layer"), tip: $("pg-tip"),
    info: $("pg-info"), complete: $("pg-complete"),
  };
  const MOTOR_BUTTONS = [["START", true], ["STOP", false], ["OL_RESET", true]];
  // the page's limit for one silent call of the worker: a run reports every slice, so 10 s
  // of silence is a scan that does not end; a lab check or the tests report only at the end
  const BUDGET_MS = { run: 10000, live: 10000, check: 180000, tests: 60000 };
  const STOP_GRACE_MS = 150;  // Stop waits this long for the worker before ending it
  const state = { worker: null, nextId: 1, pending: new Map(), busy: null, lastHeard: 0,
                  labs: {}, rows: [], loadMs: null, example: "", trend: [], watch: [],
                  compiled: false, scans: 0, t: 0, ok: false, paused: false,
                  edits: 0, compiledAt: -1, lintTimer: 0, lastDiagnostics: [] };

  // ------------------------------------------------------------------ the worker
  function startWorker() {
    const w = new Worker(new URL("worker.js", SCRIPTS));
    state.worker = w;
    state.pending = new Map();
    w.onmessage = (e) => {
      const m = e.data;
      state.lastHeard = performance.now();
      if (m.type === "progress") return onProgress(m);
      if (m.type === "clock") return onClock(m);
      const p = state.pending.get(m.id);
      if (!p) return;
      state.pending.delete(m.id);
      if (m.type === "failed") p.reject(new Error(m.error)); else p.resolve(m);
    };
    w.onerror = (e) => { setStatus("failed", t("The playground's worker failed: {error}", { error: e.message })); };
    return call("init", { lang: LANG }).then((m) => { state.example = m.example; return m; });
  }
  function call(type, data) {
    const id = state.nextId++;
    return new Promise((resolve, reject) => {
      state.pending.set(id, { resolve, reject });
      state.worker.postMessage(Object.assign({ id, type }, data || {}));
    });
  }
  // A long call (run, live, check, tests): the page shows it is busy and watches the worker.
  function busyCall(type, data, label) {
    const p = call(type, data);
    const me = { type, label, promise: p };
    state.busy = me; state.lastHeard = performance.now(); buttons();
    const done = () => { if (state.busy === me) { state.busy = null; buttons(); } };
    p.then(done, done);
    return p;
  }
  setInterval(() => {  // the wall-clock budget, separate from the PLC's own watchdog
    const budget = state.busy && BUDGET_MS[state.busy.type];
    if (budget && performance.now() - state.lastHeard > budget) {
      restart(t("Stopped: one call of the program took more than {seconds} s of real time " +
        "(loops that are long for a browser). This is the page's limit, not the PLC's watchdog " +
        "(PLC2003 counts the PLC's own, virtual, time). Python restarts.", { seconds: budget / 1000 }));
    }
  }, 250);
  function restart(message) {
    state.worker.terminate();
    for (const p of state.pending.values()) p.reject(new Error("stopped"));
    state.busy = null; state.compiled = false; state.ok = false; buttons();
    setStatus("stopped", message);
    const wasReady = ready;
    ready = startWorker().then(() => {
      if (el.status.dataset.state === "stopped") el.status.textContent += t(" Ready again.");
      buttons();
    });
    return wasReady;
  }
  async function stop() {
    if (!state.busy) return;
    const busy = state.busy;
    call("stop").catch(() => {});
    const answered = await Promise.race([busy.promise.then(() => true, () => true),
      new Promise((r) => setTimeout(() => r(false), STOP_GRACE_MS))]);
    if (!answered) {
      restart(t("Stopped at t = {t} s. Python was inside one long scan, so it restarts (a few " +
        "seconds).", { t: num(state.t, 2) }));
    } else {
      setStatus("stopped", t("Stopped at t = {t} s after {scans} scans.", { t: num(state.t, 2), scans: state.scans }));
    }
  }

  // ------------------------------------------------------------------ editor (editor.js)
  const problemHref = (code) => `../problems/${encodeURIComponent(code)}/`;
  const editor = window.PlcEditor({
    textarea: el.code, layer: el.layer, gutter: el.gutter, tip: el.tip, info: el.info,
    list: el.complete, problemHref, language: () => el.lang.value, t,
    ask: (type, data) => (state.example ? call(type, data) : Promise.reject(new Error("loading"))),
  });
  function renumber() { editor.refresh(); }
  // diagnostics as you type: plclab check's (the language server's), unless a compile, run or
  // check of this very text has spoken since
  function lintSoon() {
    clearTimeout(state.lintTimer);
    const seq = state.edits;
    state.lintTimer = setTimeout(async () => {
      if (!state.example) return;
      let m;
      try { m = await call("lint", { code: el.code.value, lang: el.lang.value }); } catch (e) { return; }
      if (seq === state.edits && state.compiledAt < seq) showDiagnostics(m.diagnostics);
    }, 400);
  }
  el.code.addEventListener("input", () => { state.compiled = false; state.edits++; lintSoon(); });
  el.lang.addEventListener("change", () => { state.edits++; renumber(); lintSoon(); });

  function decode(b64) {
    const s = b64.replace(/-/g, "+").replace(/_/g, "/");
    const bin = atob(s + "===".slice((s.length + 3) % 4));
    return new TextDecoder().decode(Uint8Array.from(bin, (c) => c.charCodeAt(0)));
  }
  function encode(text) {
    const bytes = new TextEncoder().encode(text);
    let bin = "";
    bytes.forEach((b) => { bin += String.fromCharCode(b); });
    return btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
  }
  function fromHash() {
    const h = new URLSearchParams(location.hash.slice(1));
    const has = { code: !!h.get("code"), plant: h.get("plant"), lab: h.get("lab"),
                  expect: (h.get("expect") || "").split(",").filter(Boolean) };
    if (h.get("code")) el.code.value = decode(h.get("code"));
    if (h.get("lang")) el.lang.value = h.get("lang");
    if (has.plant && [...el.plant.options].some((o) => o.value === has.plant)) el.plant.value = has.plant;
    state.wantLab = has.lab;
    return has;
  }
  function shareLink() {
    const h = new URLSearchParams();
    h.set("lang", el.lang.value); h.set("plant", el.plant.value);
    if (el.lab.value) h.set("lab", el.lab.value);
    h.set("code", encode(el.code.value));
    return location.href.split("#")[0] + "#" + h.toString();
  }

  // ------------------------------------------------------------------ messages
  function setStatus(kind, text) {
    el.status.textContent = text;
    el.status.dataset.state = kind;
  }
  function escapeHtml(s) {
    return String(s).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;",
      '"': "&quot;", "'": "&#39;" })[c]);
  }
  function withCode(text) {  // `x` in a message as code, everything else as text
    return escapeHtml(text).replace(/`([^`]+)`/g, "<code>$1</code>");
  }
  function showDiagnostics(list) {
    state.lastDiagnostics = list || [];
    el.diags.innerHTML = "";
    for (const d of list) {
      const li = document.createElement("li");
      li.className = "pg-" + d.severity;
      li.dataset.code = d.code;
      li.dataset.line = d.line;
      const where = !d.line ? "" : d.col ? t("line {line}:{col}: ", { line: d.line, col: d.col })
        : t("line {line}: ", { line: d.line });
      li.innerHTML = `${escapeHtml(where)}${escapeHtml(SEVERITY[d.severity] || d.severity)} ` +
        `<a href="${problemHref(d.code)}">${escapeHtml(d.code)}</a>: ` +
        withCode(d.message);
      li.tabIndex = 0;
      li.addEventListener("click", (e) => { if (e.target.tagName !== "A") goToLine(d.line); });
      li.addEventListener("keydown", (e) => { if (e.key === "Enter") goToLine(d.line); });
      el.diags.appendChild(li);
    }
    editor.setMarks(list);
  }
  function goToLine(line) {
    if (!line) return;
    const lines = el.code.value.split("\n");
    const start = lines.slice(0, line - 1).join("\n").length + (line > 1 ? 1 : 0);
    el.code.focus();
    el.code.setSelectionRange(start, start + (lines[line - 1] || "").length);
  }
  function faultText(diags) {
    const e = (diags || []).find((d) => d.severity === "error");
    return e ? `${e.code}: ${e.message}` : "";
  }

  // ------------------------------------------------------------------ timing diagram
  function fitCanvas() {
    const c = el.canvas, ratio = window.devicePixelRatio || 1;
    const w = Math.max(280, Math.round(c.clientWidth || 900));
    const lanes = Math.max(1, state.rows.length ? Object.keys(state.rows[0]).length - 1 : 1);
    const h = Math.max(120, Math.min(480, 28 + lanes * 44));
    c.style.height = h + "px";
    if (c.width !== Math.round(w * ratio) || c.height !== Math.round(h * ratio)) {
      c.width = Math.round(w * ratio); c.height = Math.round(h * ratio);
    }
    return { w, h, ratio };
  }
  function draw() {
    const { w, h, ratio } = fitCanvas();
    const g = el.canvas.getContext("2d");
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.fillStyle = "#1e2430"; g.fillRect(0, 0, w, h);
    const rows = state.rows;
    const names = rows.length ? Object.keys(rows[0]).filter((k) => k !== "t") : [];
    if (!names.length) {
      g.fillStyle = "#c3ccd8"; g.font = "14px sans-serif";
      g.fillText(el.plant.value === "none" && state.compiled
        ? t("Tick a variable's trend box below to draw it here.") : "", 16, h / 2);
      return;
    }
    const left = Math.min(130, Math.max(70, w * 0.18)), lane = (h - 24) / Math.max(names.length, 1);
    const t1 = rows[rows.length - 1].t, t0 = Math.max(0, t1 - 60);
    const x = (t) => left + (w - left - 10) * (t - t0) / Math.max(t1 - t0, 1e-9);
    g.font = "13px sans-serif";
    names.forEach((name, i) => {
      const top = 6 + i * lane, hh = lane - 8;
      const isBool = typeof rows[0][name] === "boolean";
      const vals = rows.map((r) => (isBool ? (r[name] ? 1 : 0) : r[name]));
      const lo = Math.min(...vals), hi = Math.max(...vals);
      const y = (v) => top + hh - hh * (isBool ? v : (v - lo) / Math.max(hi - lo, 1e-9));
      g.fillStyle = "#e6edf5";
      g.fillText(name.length > 16 ? "\u2026" + name.slice(-15) : name, 6, top + hh / 2 + 4);
      g.strokeStyle = isBool ? "#5fd07a" : "#7db7ff";
      g.lineWidth = 2; g.beginPath();
      let first = true, prev = null;
      rows.forEach((r, k) => {
        if (r.t < t0) return;
        const xv = x(r.t), yv = y(vals[k]);
        if (first) { g.moveTo(xv, yv); first = false; }
        else if (isBool) { g.lineTo(xv, prev); g.lineTo(xv, yv); }
        else g.lineTo(xv, yv);
        prev = yv;
      });
      g.stroke();
    });
    g.fillStyle = "#c3ccd8";
    g.fillText(t("{t} s", { t: num(t0, 0) }), left, h - 6);
    g.fillText(t("{t} s", { t: num(t1, 1) }), w - 60, h - 6);
  }
  function switchings(name) {
    let n = 0;
    for (let i = 1; i < state.rows.length; i++) if (state.rows[i][name] !== state.rows[i - 1][name]) n++;
    return n;
  }
  function summarise() {
    if (!state.rows.length || el.plant.value === "none") {
      el.summary.textContent = "";  // the clock line says where the run is
      return;
    }
    const out = el.plant.value === "tank" ? "PUMP" : "K1";
    const last = state.rows[state.rows.length - 1];
    if (!(out in last)) return;
    el.summary.textContent = t("t = {t} s, {scans} scans: {signal} switched {n} times, now {state}.",
      { t: num(last.t, 1), scans: state.scans, signal: out, n: switchings(out),
        state: last[out] ? t("ON") : t("OFF") });
    el.summary.dataset.switchings = switchings(out);
  }
  function addRows(rows) {
    state.rows.push(...rows);
    if (state.rows.length > 5000) state.rows.splice(0, state.rows.length - 5000);
  }
  function onProgress(m) {
    addRows(m.rows); state.t = m.t; state.scans = m.scans;
    showWatch(m.watch); clock(); draw(); summarise();
  }
  function onClock(m) {
    state.t = m.t;
    clock(m.behind ? t(" (the program runs slower than the clock)") : "");
  }
  function clock(note) {
    const live = state.busy && state.busy.type === "live";
    el.clock.textContent = t("t = {t} s", { t: num(state.t, 2) }) +
      (live ? t(", live at {speed}x", { speed: el.speed.value }) : "") + (note || "");
  }

  // ------------------------------------------------------------------ watch panel
  function showWatch(list) {
    if (!list) return;
    const known = state.watch.map((w) => w.path).join("\n");
    state.watch = list;
    if (known !== list.map((w) => w.path).join("\n")) buildWatch(list);
    for (const w of list) {
      const row = el.watch.querySelector(`tr[data-path="${CSS.escape(w.path)}"]`);
      if (!row) continue;
      row.querySelector(".pg-value").textContent = w.value;
      row.classList.toggle("pg-forced", w.forced);
    }
  }
  function buildWatch(list) {
    el.watch.innerHTML = "";
    if (!list.length) return;
    const head = document.createElement("tr");
    head.innerHTML = [t("variable"), t("type"), t("value"), t("new value"), "", t("trend")].map(
      (h) => `<th>${escapeHtml(h)}</th>`).join("");
    el.watch.appendChild(head);
    for (const w of list) {
      const tr = document.createElement("tr");
      tr.dataset.path = w.path;
      tr.innerHTML = `<td>${escapeHtml(w.path)}</td><td>${escapeHtml(w.type)}</td>` +
        "<td class=\"pg-value\"></td><td><input class=\"pg-new\" size=\"8\" " +
        `aria-label="${escapeHtml(t("new value of {path}", { path: w.path }))}"></td><td></td><td></td>`;
      const input = tr.querySelector(".pg-new");
      const cells = tr.querySelectorAll("td");
      const write = document.createElement("button");
      write.textContent = t("Write"); write.className = "md-button pg-small";
      write.onclick = () => writeVar(w.path, input.value, "write");
      const force = document.createElement("button");
      force.textContent = t("Force"); force.className = "md-button pg-small";
      force.onclick = () => (tr.classList.contains("pg-forced")
        ? unforceVar(w.path) : writeVar(w.path, input.value, "force"));
      cells[4].append(write, force);
      if (w.trendable) {
        const box = document.createElement("input");
        box.type = "checkbox"; box.checked = state.trend.includes(w.path);
        box.setAttribute("aria-label", t("draw {path} in the diagram", { path: w.path }));
        box.onchange = () => setTrend(w.path, box.checked);
        cells[5].appendChild(box);
      }
      input.addEventListener("keydown", (e) => { if (e.key === "Enter") write.click(); });
      el.watch.appendChild(tr);
    }
  }
  async function writeVar(path, value, how) {
    if (!state.compiled) return;
    const m = await call(how, { path, value });
    if (m.diagnostics && m.diagnostics.length) showDiagnostics(m.diagnostics);
    else if (!state.busy) refreshWatch();
  }
  async function unforceVar(path) { await call("unforce", { path }); if (!state.busy) refreshWatch(); }
  async function refreshWatch() { showWatch((await call("watch")).watch); }
  async function setTrend(path, on) {
    state.trend = state.trend.filter((p) => p !== path);
    if (on) state.trend.push(path);
    await call("trend", { paths: state.trend });
    state.rows = [];
  }

  // ------------------------------------------------------------------ running
  function buttons() {
    const busy = !!state.busy, up = !!state.example;
    for (const b of [el.compile, el.run60, el.live, el.check, el.tests, el.step]) b.disabled = !up || busy;
    el.pause.disabled = !busy || !["run", "live"].includes(state.busy && state.busy.type);
    el.stop.disabled = !busy;
    el.live.textContent = t("Run live");
    el.pause.textContent = state.paused ? t("Resume") : t("Pause");
  }
  async function compile() {
    if (state.busy) await stop();
    await ready;
    el.results.innerHTML = ""; el.testOut.textContent = "";
    state.compiledAt = state.edits;
    const m = await call("compile", { code: el.code.value, lang: el.lang.value,
                                      plant: el.plant.value, trend: state.trend });
    state.compiled = true; state.ok = m.ok; state.t = m.t; state.scans = m.scans;
    state.rows = m.row ? [m.row] : [];
    state.watch = []; showWatch(m.watch);
    showDiagnostics(m.diagnostics);
    draw(); summarise(); clock();
    const where = el.plant.value === "none" ? t("it runs without a plant")
      : t("the {plant} is at t = 0", { plant: el.plant.value });
    setStatus(m.ok ? "compiled" : "error", m.ok ? t("Compiled in {ms} ms; {where}.", { ms: num(m.ms, 0), where })
      : t("The program does not compile: see the messages below (click one to go to its line)."));
    return m.ok;
  }
  function endOfRun(m, seconds, ms) {
    state.t = m.t; state.scans = m.scans;
    showDiagnostics(m.diagnostics); summarise(); clock();
    const fault = m.ok ? "" : faultText(m.diagnostics);
    if (fault) {
      setStatus("fault", t("Stopped at t = {t} s ({scans} scans) by a run-time fault: {fault}",
        { t: num(m.t, 2), scans: m.scans, fault }));
    } else if (m.stopped) {
      setStatus("stopped", t("Stopped at t = {t} s after {scans} scans.", { t: num(m.t, 2), scans: m.scans }));
    } else {
      setStatus("ran", t("Ran {seconds} s of virtual time ({scans} scans) in {ms} ms.",
        { seconds: LANG === "ru" ? String(seconds).replace(".", ",") : seconds, scans: m.scans, ms: num(ms, 0) }));
    }
  }
  async function run(seconds) {
    if (!(await compile())) return null;
    const t = performance.now();
    let m;
    try { m = await busyCall("run", { seconds }, "run"); } catch (e) { return null; }
    const ms = performance.now() - t;
    endOfRun(m, seconds, ms);
    return { ms, scans: m.scans, scansPerSecond: m.scans / (ms / 1000) };
  }
  async function runLive() {
    if (!(await compile())) return;
    state.paused = false;
    let m;
    try { m = await busyCall("live", { speed: Number(el.speed.value) }, "live"); } catch (e) { return; }
    endOfRun(m, m.t, 0);
  }
  async function stepOnce() {
    if (!state.compiled && !(await compile())) return;
    const m = await call("step");
    if (m.row) addRows([m.row]);
    state.t = m.t; state.scans = m.scans; showWatch(m.watch); draw(); summarise(); clock();
    if (!m.ok) showDiagnostics(m.diagnostics);  // the run-time fault, at its line
    setStatus(m.ok ? "stepped" : "fault", m.ok ? t("One scan: t = {t} s.", { t: num(m.t, 2) })
      : t("Stopped by a run-time fault: {fault}", { fault: faultText(m.diagnostics) }));
  }
  async function pause() {
    state.paused = !state.paused;
    await call(state.paused ? "pause" : "resume");
    buttons();
    setStatus(state.paused ? "paused" : "running", state.paused
      ? t("Paused at t = {t} s.", { t: num(state.t, 2) }) : t("Running."));
  }
  el.compile.onclick = compile;
  el.run60.onclick = () => run(60);
  el.live.onclick = runLive;
  el.pause.onclick = pause;
  el.step.onclick = stepOnce;
  el.stop.onclick = stop;
  el.speed.onchange = () => { if (state.busy) call("speed", { speed: Number(el.speed.value) }); };
  el.share.onclick = async () => {
    const url = shareLink();
    history.replaceState(null, "", url);
    try { await navigator.clipboard.writeText(url); setStatus(el.status.dataset.state, t("The link to this program is copied (and in the address bar).")); }
    catch (e) { setStatus(el.status.dataset.state, t("The link to this program is in the address bar.")); }
  };

  function motorButtons() {
    el.buttons.innerHTML = "";
    if (el.plant.value !== "motor") return;
    for (const [name, pressed] of MOTOR_BUTTONS) {
      const b = document.createElement("button");
      b.className = "md-button"; b.textContent = name;
      b.title = t("hold to press {name} (mouse, touch, Space or Enter)", { name });
      const down = () => call("press", { signal: name, value: pressed });
      const up = () => call("release", { signal: name });
      b.addEventListener("pointerdown", down); b.addEventListener("pointerup", up);
      b.addEventListener("pointerleave", up);
      b.addEventListener("keydown", (e) => {
        if ((e.key === " " || e.key === "Enter") && !e.repeat) { e.preventDefault(); down(); }
      });
      b.addEventListener("keyup", (e) => {
        if (e.key === " " || e.key === "Enter") { e.preventDefault(); up(); }
      });
      el.buttons.appendChild(b);
    }
  }
  el.plant.onchange = () => { motorButtons(); if (state.example) compile(); };

  // ------------------------------------------------------------------ lab check and tests
  async function checkLab() {
    const lab = state.labs[el.lab.value];
    if (!lab) { setStatus("ready", t("Choose a lab first.")); return null; }
    if (state.busy) await stop();
    state.rows = []; draw(); el.summary.textContent = ""; el.testOut.textContent = "";
    setStatus("checking", t("Checking against {title}...", { title: lab.title }));
    state.compiledAt = state.edits;
    let res;
    try { res = await busyCall("check", { code: el.code.value, lang: el.lang.value, lab }, "check"); }
    catch (e) { return null; }
    showDiagnostics(res.diagnostics);
    el.results.innerHTML = "<tr>" + [t("scenario"), t("criterion"), t("result"), t("points")].map(
      (h) => `<th>${escapeHtml(h)}</th>`).join("") + "</tr>";
    for (const r of res.results) {
      const tr = document.createElement("tr");
      tr.className = r.passed === null ? "pg-skip" : r.passed ? "pg-pass" : "pg-fail";
      tr.innerHTML = `<td>${escapeHtml(r.scenario)}</td><td>${withCode(r.criterion)}</td>` +
        `<td>${withCode(r.why)}</td><td>${r.passed ? r.points : 0}</td>`;
      el.results.appendChild(tr);
    }
    setStatus("checked", t("{title}: {points} of {of} points in the visible scenarios ({seconds} s). " +
      "The grader's hidden scenarios may find more.", { title: lab.title, points: res.points,
        of: res.of, seconds: num(res.ms / 1000, 1) }));
    return res;
  }
  async function runTests() {
    if (state.busy) await stop();
    el.results.innerHTML = "";
    state.compiledAt = state.edits;
    let res;
    try { res = await busyCall("tests", { code: el.code.value, lang: el.lang.value }, "tests"); }
    catch (e) { return null; }
    showDiagnostics(res.diagnostics);
    el.testOut.textContent = res.summary ? res.lines.concat([res.summary]).join("\n") : "";
    el.testOut.dataset.failed = res.failed;
    setStatus(res.summary ? "tested" : "error", res.summary
      ? t("TEST blocks: {summary}.", { summary: res.summary })
      : t("The program does not compile: see the messages below."));
    return res;
  }
  el.check.onclick = checkLab;
  el.tests.onclick = runTests;
  el.lab.onchange = () => {
    const lab = state.labs[el.lab.value];
    if (lab) { el.plant.value = lab.plant; motorButtons(); }
  };

  // ------------------------------------------------------------------ what an example needs
  // A try-it link opens what its example needs: its TEST results, its plant, or the watch panel
  // with its variables (one scan run); a deliberate mistake (``expect=PLC...``) is announced.
  // The page then says what it showed (the event "pg-example", for the browser tests).
  async function openExample(asked) {
    if (!asked.code) { await compile(); return; }
    const a = await call("analyse", { code: el.code.value, lang: el.lang.value });
    if (!asked.plant && !asked.lab) { el.plant.value = a.plant; motorButtons(); }
    let shown;
    if (a.tests > 0 && a.ok) {
      await compile(); await runTests(); shown = "tests";
    } else {
      await compile();
      shown = !state.ok ? "error" : el.plant.value === "none" ? "watch" : "plant";
      const codes = () => [...el.diags.querySelectorAll("li")].map((li) => li.dataset.code);
      if (state.ok && (el.plant.value === "none" ||
          asked.expect.some((c) => !codes().includes(c)))) {
        await stepOnce();  // the watch shows its values; a run-time mistake shows itself
      }
    }
    let codes = [...el.diags.querySelectorAll("li")].map((li) => li.dataset.code);
    if (asked.expect.some((c) => !codes.includes(c))) {
      // a mistake only plclab check's rules see (a double coil...): add what the checker says
      const lint = await call("lint", { code: el.code.value, lang: el.lang.value });
      const shownNow = [...el.diags.querySelectorAll("li")].map((li) => ({
        code: li.dataset.code, line: Number(li.dataset.line) }));
      const more = lint.diagnostics.filter((d) => !shownNow.some((x) => x.code === d.code && x.line === d.line));
      if (more.length) {
        showDiagnostics(state.lastDiagnostics.concat(more));
        codes = [...el.diags.querySelectorAll("li")].map((li) => li.dataset.code);
      }
    }
    if (asked.expect.length) {
      const seen = asked.expect.filter((c) => codes.includes(c));
      if (seen.length) {
        setStatus(el.status.dataset.state, el.status.textContent +
          t(" This example makes the mistake {codes} on purpose.", { codes: seen.join(", ") }));
      }
    }
    const detail = { shown, plant: el.plant.value, codes, expect: asked.expect,
                     tests: el.testOut.textContent, watch: state.watch.length,
                     rows: state.rows.length, status: el.status.dataset.state };
    window.dispatchEvent(new CustomEvent("pg-example", { detail }));
    return detail;
  }
  window.addEventListener("hashchange", async () => {
    const asked = fromHash();
    renumber();
    if (state.wantLab && state.labs[state.wantLab]) { el.lab.value = state.wantLab; el.lab.onchange(); }
    await ready;
    await openExample(asked);
  });

  // ------------------------------------------------------------------ start
  let ready = null;
  async function start() {
    const t0 = performance.now();
    const asked = fromHash();
    const labs = fetch("labs.json").then((r) => r.json());  // the edition's (its language)
    ready = startWorker();
    state.labs = await labs;
    for (const [id, lab] of Object.entries(state.labs)) {
      const o = document.createElement("option"); o.value = id; o.textContent = lab.title;
      el.lab.appendChild(o);
    }
    if (state.wantLab && state.labs[state.wantLab]) { el.lab.value = state.wantLab; el.lab.onchange(); }
    renumber(); motorButtons();
    await ready;
    if (!el.code.value) el.code.value = state.example;
    renumber(); lintSoon();
    state.loadMs = performance.now() - t0;
    buttons();
    if (asked.code) await openExample(asked);
    if (!["fault", "error", "tested"].includes(el.status.dataset.state)) {
      setStatus("ready", t("Ready: Python and plclab loaded in {seconds} s.", { seconds: num(state.loadMs / 1000, 1) }));
    }
  }
  const started = start().catch((e) => {
    setStatus("failed", t("The playground could not start: {error}", { error: String(e) }));
    throw e;
  });
  window.addEventListener("resize", draw);
  // for the browser tests and the benchmark
  window.plclabPlayground = { ready: started, state, compile, run, checkLab, runTests, stop,
                              stepOnce, shareLink, call, editor, lang: LANG };
})();
