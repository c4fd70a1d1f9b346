// Load plclab's core in Pyodide under node and run the tank program for 60 s of virtual time;
// then ask the editor's side (plclab/site/editor_api.py) what the page asks it.
// Usage: node node_check.mjs PYODIDE_DIR CORE_ZIP  -> prints one JSON line.
import { readFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
import path from "node:path";

const [pyodideDir, coreZip] = process.argv.slice(2);
const { loadPyodide } = await import(pathToFileURL(path.join(pyodideDir, "pyodide.mjs")).href);
const t0 = performance.now();
const pyodide = await loadPyodide({ indexURL: pyodideDir + path.sep });
pyodide.unpackArchive(new Uint8Array(readFileSync(coreZip)), "zip", { extractDir: "/home/pyodide/core" });
const result = pyodide.runPython(`
import json, sys, time
sys.path.insert(0, "/home/pyodide/core")
from plclab.site import playground_api as api
s = api.session(api.TANK_EXAMPLE, "st", "tank", 20.0)
t = time.perf_counter()
rows = s.advance(60.0, 1.0)
dt = time.perf_counter() - t
bad = api.check("PROGRAM P\\nVAR x : INT; END_VAR\\nx := 1 +;\\nEND_PROGRAM\\n", "st")
from plclab.site import editor_api as ed
src = "PROGRAM P\\nVAR t1 : TON; n : INT; END_VAR (* note *)\\nt1(IN := TRUE, PT := T#1s);\\nn := ABS(n);\\nIF t1.\\nEND_PROGRAM\\n"
t = time.perf_counter()
spans = ed.highlight(src, "st")
hl_ms = (time.perf_counter() - t) * 1000
t = time.perf_counter()
lint = ed.lint(src, "st")
lint_ms = (time.perf_counter() - t) * 1000
json.dumps({"ok": s.ok, "scans": s.scans, "pump": [r["PUMP"] for r in rows],
            "level": rows[-1]["LEVEL"], "scans_per_s": s.scans / dt, "bad": bad[:1],
            "spans": spans, "lint": lint, "hover_var": ed.hover(src, "st", 3, 2),
            "hover_fn": ed.hover(src, "st", 4, 7),
            "members": [c["label"] for c in ed.complete(src, "st", 5, 7)],
            "highlight_ms": hl_ms, "lint_ms": lint_ms})
`);
const out = JSON.parse(result);
out.load_ms = performance.now() - t0;
console.log(JSON.stringify(out));
