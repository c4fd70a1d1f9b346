"""The operator panel's page: plain HTML, CSS and JavaScript, no library, no network beyond the
panel's own server. It polls ``/state`` four times a second and posts the operator's actions.
Text from the server is inserted with ``textContent`` only (never as HTML)."""

PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>plclab operator panel</title>
<style>
  body { font-family: system-ui, sans-serif; margin: 0; background: #eef1f4; color: #1c2430; }
  header { background: #1c3d5a; color: white; padding: 10px 16px; display: flex;
           align-items: center; gap: 16px; }
  header h1 { font-size: 18px; margin: 0; flex: 1; }
  main { display: grid; grid-template-columns: 1fr 1fr; gap: 12px; padding: 12px; }
  section { background: white; border-radius: 6px; padding: 10px 12px;
            box-shadow: 0 1px 3px #0002; }
  h2 { font-size: 15px; margin: 0 0 8px 0; }
  table { border-collapse: collapse; width: 100%; font-size: 14px; }
  td, th { padding: 3px 6px; border-bottom: 1px solid #e3e7ec; text-align: left; }
  .on { color: #0a7d2c; font-weight: 600; } .off { color: #8a94a0; }
  button { margin: 2px; padding: 5px 10px; border-radius: 4px; border: 1px solid #1c3d5a;
           background: #f7fafc; cursor: pointer; }
  button:disabled { opacity: .4; cursor: not-allowed; }
  .alarm td { font-weight: 600; }
  #message { color: #b00020; min-height: 1.2em; font-size: 14px; }
  .state-I, .state-IO { animation: blink 1s steps(2) infinite; }
  @keyframes blink { 50% { opacity: .55; } }
  #log { max-height: 220px; overflow-y: auto; }
</style>
</head>
<body>
<header>
  <h1 id="title">operator panel</h1>
  <span>t = <b id="time">0</b> s</span>
  <span>PLC <b id="plc">?</b></span>
  <label>user <select id="user"></select></label>
</header>
<main>
  <section>
    <h2>Signals</h2>
    <table id="signals"><thead><tr><th>signal</th><th>value</th><th></th></tr></thead>
    <tbody></tbody></table>
  </section>
  <section>
    <h2>Alarms <button id="ack-all">Acknowledge all</button></h2>
    <table id="alarms"><thead><tr><th>id</th><th>state</th><th>class</th><th>text</th><th></th>
    </tr></thead><tbody></tbody></table>
    <div id="message"></div>
    <h2>Alarm log</h2>
    <div id="log"><table><tbody id="log-body"></tbody></table></div>
    <h2>Recipe</h2>
    <div id="recipes"></div>
  </section>
</main>
<script>
"use strict";
let state = null;
function el(tag, text, cls) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = String(text);
  if (cls) e.className = cls;
  return e;
}
async function post(path, body) {
  const r = await fetch(path, {method: "POST", headers: {"Content-Type": "application/json",
                               "X-Plclab-Token": "__PLCLAB_TOKEN__"},
                               body: JSON.stringify(body)});
  const data = await r.json();
  document.getElementById("message").textContent = data.error || "";
  refresh();
}
function can(right) { return state && state.rights.includes(right); }
function render() {
  document.getElementById("title").textContent = state.title;
  document.getElementById("time").textContent = state.t.toFixed(1);
  document.getElementById("plc").textContent = state.plc;
  const users = document.getElementById("user");
  if (!users.options.length) {
    for (const u of state.users) users.appendChild(el("option", u));
    users.onchange = () => post("/login", {user: users.value});
  }
  users.value = state.user;
  const sb = document.querySelector("#signals tbody");
  sb.replaceChildren();
  for (const s of state.signals) {
    const tr = el("tr");
    tr.appendChild(el("td", s.name));
    const v = s.type === "bool" ? (s.value ? "ON" : "off") : s.value.toFixed(3) + " " + s.unit;
    tr.appendChild(el("td", v, s.type === "bool" ? (s.value ? "on" : "off") : ""));
    const td = el("td");
    if (s.kind === "panel" && s.type === "bool") {
      const b = el("button", "press " + s.name);
      b.id = "press-" + s.name;
      b.disabled = !can("operate");
      b.onclick = () => post("/press", {signal: s.name});
      td.appendChild(b);
    }
    tr.appendChild(td);
    sb.appendChild(tr);
  }
  const ab = document.querySelector("#alarms tbody");
  ab.replaceChildren();
  for (const a of state.alarms) {
    const tr = el("tr", undefined, "alarm state-" + a.state);
    tr.id = "alarm-" + a.id;
    tr.style.background = a.color;
    for (const x of [a.id, a.state, a["class"], a.text]) tr.appendChild(el("td", x));
    const td = el("td");
    if (a.ack && (a.state === "I" || a.state === "IO")) {
      const b = el("button", "Acknowledge");
      b.id = "ack-" + a.id;
      b.disabled = !can("ack");
      b.onclick = () => post("/ack", {id: a.id});
      td.appendChild(b);
    }
    tr.appendChild(td);
    ab.appendChild(tr);
  }
  document.getElementById("ack-all").disabled = !can("ack");
  const lb = document.getElementById("log-body");
  lb.replaceChildren();
  for (const e of state.log.slice().reverse()) {
    const tr = el("tr");
    for (const x of [e.t.toFixed(2) + " s", e.id, e.state, e.user, e.text])
      tr.appendChild(el("td", x));
    lb.appendChild(tr);
  }
  const rb = document.getElementById("recipes");
  rb.replaceChildren();
  if (!state.records.length) rb.appendChild(el("span", "(no recipe)", "off"));
  for (const r of state.records) {
    const b = el("button", "load " + r + (r === state.record ? " (active)" : ""));
    b.id = "recipe-" + r;
    b.onclick = () => post("/recipe", {record: r});
    rb.appendChild(b);
  }
}
async function refresh() {
  try {
    state = await (await fetch("/state")).json();
    render();
  } catch (e) { document.getElementById("message").textContent = "no connection"; }
}
document.getElementById("ack-all").onclick = () => post("/ack", {});
refresh();
setInterval(refresh, 250);
</script>
</body>
</html>
"""
