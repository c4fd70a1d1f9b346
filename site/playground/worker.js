// The playground's worker: plclab's Python core in Pyodide, off the page's thread, so a long
// program never freezes the page. The page (playground.js) sends commands; long ones (run,
// live) go in short slices and look at the mailbox between slices, so Pause and Stop always
// get through. A slice that never ends (a loop inside one scan) is the page's to end: it
// terminates this worker and starts another (ADR 0028).
"use strict";
importScripts("../pyodide/pyodide.js");

let py = null, api = null, labApi = null, editorApi = null, session = null;
let job = null;          // the running run/live: {id, kind, paused, stop, speed}
const SLICE_MS = 40;     // wall-clock time of one Python call, about
const toJs = (p) => (p && p.toJs ? p.toJs({ dict_converter: Object.fromEntries }) : p);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

function reply(id, type, data) { postMessage(Object.assign({ id, type }, data || {})); }

async function init(msg) {
  const t0 = performance.now();
  const base = new URL("./", self.location.href);
  const [pyodide, zip] = await Promise.all([
    loadPyodide({ indexURL: new URL("../pyodide/", base).href }),
    fetch(new URL("plclab-core.zip", base)).then((r) => r.arrayBuffer()),
  ]);
  pyodide.unpackArchive(zip, "zip", { extractDir: "/home/pyodide/core" });
  pyodide.runPython("import sys; sys.path.insert(0, '/home/pyodide/core')");
  py = pyodide;
  api = py.pyimport("plclab.site.playground_api");
  labApi = py.pyimport("plclab.site.lab_check");
  editorApi = py.pyimport("plclab.site.editor_api");
  api.set_language(msg.lang || "en");  // plclab's messages in the page's language
  reply(msg.id, "ready", { example: api.TANK_EXAMPLE, loadMs: performance.now() - t0 });
}

function status() {
  if (!session) return { ok: false, t: 0, scans: 0, diagnostics: [] };
  return { ok: session.ok, t: session.time, scans: session.scans,
           diagnostics: toJs(session.diagnostics) };
}

function compile(msg) {
  if (job) job.stop = true;  // a run of the old session ends at its next slice
  job = null;
  if (session) session.destroy();
  const t = performance.now();
  session = api.session(msg.code, msg.lang, msg.plant, 20.0);
  if (msg.trend) session.set_trend(py.toPy(msg.trend));
  reply(msg.id, "compiled", Object.assign(status(), {
    ms: performance.now() - t, row: toJs(session.sample()), watch: toJs(session.watch()),
    mapped: toJs(session.mapped) }));
}

// Advance the session by `seconds` of virtual time in slices of about SLICE_MS of wall clock;
// between slices the mailbox is read (Pause, Stop, buttons). Returns the rows it sampled.
async function advanceSliced(me, seconds, every) {
  let left = seconds, slice = 0.1;
  while (left > 1e-9 && !me.stop && session.ok) {
    while (me.paused && !me.stop) await sleep(30);
    if (me.stop) break;
    const chunk = Math.min(left, slice);
    const t = performance.now();
    const rows = toJs(session.advance(chunk, every));
    const ms = performance.now() - t;
    left -= chunk;
    slice = Math.max(0.02, Math.min(5, chunk * SLICE_MS / Math.max(ms, 1)));
    postMessage({ type: "progress", id: me.id, rows, watch: toJs(session.watch()),
                  t: session.time, scans: session.scans, sliceMs: ms });
    await sleep(0);  // let the mailbox in
  }
}

async function run(msg) {
  const me = { id: msg.id, kind: "run", paused: false, stop: false };
  job = me;
  const t = performance.now();
  await advanceSliced(me, msg.seconds, 0.1);
  if (job === me) job = null;
  reply(msg.id, "ran", Object.assign(status(), { ms: performance.now() - t, stopped: me.stop }));
}

async function live(msg) {
  const me = { id: msg.id, kind: "live", paused: false, stop: false, speed: msg.speed || 1 };
  job = me;
  let wall = performance.now(), virt = session.time, behind = false;
  while (!me.stop && session.ok) {
    if (me.paused) { await sleep(30); wall = performance.now(); virt = session.time; continue; }
    const target = virt + (performance.now() - wall) / 1000 * me.speed;
    let due = target - session.time;
    if (due > 2) {  // the program cannot keep up with the clock: say so, do not race
      behind = true; due = 0.2; wall = performance.now(); virt = session.time + due;
    }
    if (due >= 0.02) await advanceSliced(me, due, 0.1);
    postMessage({ type: "clock", id: me.id, t: session.time, speed: me.speed, behind });
    behind = false;
    await sleep(50);
  }
  if (job === me) job = null;
  reply(msg.id, "ran", Object.assign(status(), { stopped: me.stop, live: true }));
}

function step(msg) {
  if (session && session.ok) session.step();
  reply(msg.id, "stepped", Object.assign(status(), {
    row: session ? toJs(session.sample()) : null, watch: session ? toJs(session.watch()) : [] }));
}

const handlers = {
  init, compile, run, live, step,
  pause: (m) => { if (job) job.paused = true; reply(m.id, "ok"); },
  resume: (m) => { if (job) job.paused = false; reply(m.id, "ok"); },
  stop: (m) => { if (job) job.stop = true; reply(m.id, "ok"); },
  speed: (m) => { if (job) job.speed = m.speed; reply(m.id, "ok"); },
  press: (m) => { if (session) session.set_input(m.signal, m.value); reply(m.id, "ok"); },
  release: (m) => { if (session) session.release(m.signal); reply(m.id, "ok"); },
  write: (m) => reply(m.id, "written", { diagnostics: session ? toJs(session.write(m.path, m.value)) : [] }),
  force: (m) => reply(m.id, "written", { diagnostics: session ? toJs(session.force(m.path, m.value)) : [] }),
  unforce: (m) => { if (session) session.unforce(m.path); reply(m.id, "ok"); },
  trend: (m) => { if (session) session.set_trend(py.toPy(m.paths)); reply(m.id, "ok"); },
  watch: (m) => reply(m.id, "watch", { watch: session ? toJs(session.watch()) : [] }),
  // the editor (plclab/site/editor_api.py): colours, diagnostics as you type, hover, completion
  highlight: (m) => reply(m.id, "highlighted", { spans: toJs(editorApi.highlight(m.code, m.lang)) }),
  lint: (m) => reply(m.id, "linted", { diagnostics: toJs(editorApi.lint(m.code, m.lang)) }),
  hover: (m) => reply(m.id, "hovered", { hover: editorApi.hover(m.code, m.lang, m.line, m.col) }),
  complete: (m) => reply(m.id, "completed", {
    items: toJs(editorApi.complete(m.code, m.lang, m.line, m.col)) }),
  analyse: (m) => reply(m.id, "analysed", toJs(api.analyse(m.code, m.lang))),
  tests: (m) => reply(m.id, "tested", toJs(api.run_tests(m.code, m.lang))),
  check: (m) => {
    if (job) job.stop = true;
    job = null;
    const t = performance.now();
    const res = toJs(labApi.check_lab(m.code, m.lang, py.toPy(m.lab)));
    reply(m.id, "checked", Object.assign(res, { ms: performance.now() - t }));
  },
};

onmessage = async (e) => {
  const msg = e.data, h = handlers[msg.type];
  try {
    if (!h) throw new Error("unknown command " + msg.type);
    await h(msg);
  } catch (err) {
    reply(msg.id, "failed", { error: String(err && err.message ? err.message : err) });
  }
};
