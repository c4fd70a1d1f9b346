// The playground's editor: a textarea (the control a keyboard and a screen reader use) over a
// layer that shows the same text coloured as the course pages colour it (Pygments' classes,
// computed by plclab/site/editor_api.py in the worker), with diagnostics underlined in place.
// Hover (mouse) and the info line (keyboard caret) show the diagnostic and the language
// server's hover; Ctrl+Space or "." opens completion (ADR 0064). No library, nothing from a CDN.
"use strict";
window.PlcEditor = function (opts) {
  const ta = opts.textarea, layer = opts.layer, gutter = opts.gutter, tip = opts.tip;
  const info = opts.info, list = opts.list;
  // the page's texts in its language (playground.js's t); English when none is given
  const t = opts.t || ((s, p) => s.replace(/\{(\w+)\}/g, (all, k) => (p && k in p ? p[k] : all)));
  const st = { spans: [], marks: [], asking: false, again: false, hoverTimer: 0, caretTimer: 0,
               items: [], active: 0, from: 0, tipHold: false, hideTimer: 0, seq: 0 };
  const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;",
    ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
  const IDENT = /[A-Za-z0-9_]/;

  // ---------------------------------------------------------------- drawing
  function lineMarks(n) { return st.marks.filter((m) => m.line === n && m.end > m.col); }
  function renderLine(text, n) {
    const sp = st.spans[n - 1];
    let pieces = sp && sp.map((p) => p[1]).join("") === text ? sp : [["", text]];
    const marks = lineMarks(n);
    if (!marks.length) return pieces.map(([c, t]) => (c ? `<span class="${c}">${esc(t)}</span>` : esc(t))).join("");
    const cuts = new Set();
    for (const m of marks) { cuts.add(m.col - 1); cuts.add(m.end - 1); }
    const out = [];
    let at = 0;
    for (const [c, t] of pieces) {
      let a = 0;
      const inner = [...cuts].filter((x) => x > at && x < at + t.length).sort((x, y) => x - y);
      for (const cut of inner.concat([at + t.length])) {
        const part = t.slice(a, cut - at);
        const m = marks.find((mk) => at + a >= mk.col - 1 && at + a < mk.end - 1);
        const cls = [c, m ? `pg-mark pg-mark-${m.severity}` : ""].filter(Boolean).join(" ");
        out.push(cls ? `<span class="${cls}">${esc(part)}</span>` : esc(part));
        a = cut - at;
      }
      at += t.length;
    }
    return out.join("");
  }
  function draw() {
    const lines = ta.value.split("\n");
    layer.innerHTML = lines.map((l, i) => renderLine(l, i + 1)).join("\n") + "\n";
    const bad = new Map();
    for (const m of st.marks) {
      if (m.line && (!bad.has(m.line) || m.severity === "error")) bad.set(m.line, m.severity);
    }
    gutter.innerHTML = lines.map((_, i) => {
      const s = bad.get(i + 1), cls = s === "error" ? "pg-bad" : "pg-warn";
      return s ? `<span class="${cls}" data-line="${i + 1}">${i + 1}</span>` : `${i + 1}`;
    }).join("\n");
    sync();
  }
  function sync() {
    layer.style.transform = `translate(${-ta.scrollLeft}px, ${-ta.scrollTop}px)`;
    gutter.scrollTop = ta.scrollTop;
  }
  async function highlight() {  // one request at a time; the newest text wins
    if (st.asking) { st.again = true; return; }
    st.asking = true;
    try {
      const text = ta.value;
      const m = await opts.ask("highlight", { code: text, lang: opts.language() });
      st.spans = m.spans || [];
      draw();
    } catch (e) { /* the worker restarts: plain text until it is back */ }
    st.asking = false;
    if (st.again) { st.again = false; highlight(); }
  }

  // ---------------------------------------------------------------- where things are
  function metrics() {
    const cs = getComputedStyle(ta);
    const probe = document.createElement("span");
    probe.textContent = "M".repeat(20);
    probe.style.visibility = "hidden";
    layer.appendChild(probe);
    const w = probe.getBoundingClientRect().width / 20;
    probe.remove();
    return { w, h: parseFloat(cs.lineHeight) || 20, left: parseFloat(cs.paddingLeft) || 0,
             top: parseFloat(cs.paddingTop) || 0 };
  }
  function posAt(clientX, clientY) {
    const r = ta.getBoundingClientRect(), m = metrics();
    const line = Math.floor((clientY - r.top - m.top + ta.scrollTop) / m.h) + 1;
    const col = Math.floor((clientX - r.left - m.left + ta.scrollLeft) / m.w) + 1;
    const lines = ta.value.split("\n");
    if (line < 1 || line > lines.length || col < 1 || col > lines[line - 1].length + 1) return null;
    return { line, col };
  }
  function caret() {
    const before = ta.value.slice(0, ta.selectionStart).split("\n");
    return { line: before.length, col: before[before.length - 1].length + 1 };
  }
  function pixelOf(line, col) {
    const r = ta.getBoundingClientRect(), m = metrics(), host = ta.parentElement.getBoundingClientRect();
    return { x: r.left - host.left + m.left + (col - 1) * m.w - ta.scrollLeft,
             y: r.top - host.top + m.top + line * m.h - ta.scrollTop };
  }
  function marksAt(p, wholeLine) {
    return st.marks.filter((m) => m.line === p.line &&
      (wholeLine || m.end <= m.col || (p.col >= m.col && p.col < m.end)));
  }

  // ---------------------------------------------------------------- what is shown for a place
  function markdown(md) {  // the hover's small Markdown: a code fence, **bold**, `code`
    return md.split(/```[\w-]*\n?/).map((part, i) => (i % 2
      ? `<code class="pg-sig">${esc(part.trim())}</code>`
      : esc(part).replace(/\*\*([^*]+)\*\*/g, "<strong>$1</strong>")
        .replace(/`([^`]+)`/g, "<code>$1</code>").trim())).filter(Boolean).join("<br>");
  }
  function markHtml(m) {
    return `<span class="pg-tip-${m.severity}">${esc(m.severity)}</span> ` +
      `<a href="${opts.problemHref(m.code)}">${esc(m.code)}</a>: ${esc(m.message)}`;
  }
  async function describe(p, wholeLine) {
    const parts = marksAt(p, wholeLine).map(markHtml);
    let hover = "";
    try {
      const m = await opts.ask("hover", { code: ta.value, lang: opts.language(), line: p.line, col: p.col });
      hover = m.hover || "";
    } catch (e) { hover = ""; }
    if (hover) parts.push(markdown(hover));
    return parts;
  }
  function place(box, x) {  // at x, but never past the editor's right edge (a phone)
    box.style.left = "0px";
    box.style.left = Math.max(0, Math.min(x, ta.parentElement.clientWidth - box.offsetWidth)) + "px";
  }
  function hideTip() { tip.hidden = true; tip.innerHTML = ""; }
  ta.addEventListener("mousemove", (e) => {
    clearTimeout(st.hoverTimer);
    const p = posAt(e.clientX, e.clientY);
    if (!p) { st.hideTimer = setTimeout(() => { if (!st.tipHold) hideTip(); }, 300); return; }
    st.hoverTimer = setTimeout(async () => {
      const seq = ++st.seq;
      const parts = await describe(p, false);
      if (seq !== st.seq) return;
      if (!parts.length) { if (!st.tipHold) hideTip(); return; }
      clearTimeout(st.hideTimer);
      tip.innerHTML = parts.join("<hr>");
      const at = pixelOf(p.line, p.col);
      tip.style.top = at.y + 2 + "px";
      tip.hidden = false;
      place(tip, at.x);
    }, 250);
  });
  ta.addEventListener("mouseleave", () => {
    clearTimeout(st.hoverTimer);
    st.hideTimer = setTimeout(() => { if (!st.tipHold) hideTip(); }, 400);
  });
  tip.addEventListener("mouseenter", () => { st.tipHold = true; clearTimeout(st.hideTimer); });
  tip.addEventListener("mouseleave", () => { st.tipHold = false; hideTip(); });

  function caretMoved() {  // the info line: what the keyboard's caret stands on
    clearTimeout(st.caretTimer);
    st.caretTimer = setTimeout(async () => {
      const p = caret(), text = ta.value;
      const parts = await describe(p, true);
      if (ta.value !== text) return;
      info.innerHTML = parts.length ? `<span class="pg-info-where">${esc(t("line {line}:{col}", { line: p.line, col: p.col }))}</span> ` +
        parts.join(" · ") : "";
    }, 350);
  }

  // ---------------------------------------------------------------- completion
  function closeList() {
    list.hidden = true; list.innerHTML = ""; st.items = [];
    ta.removeAttribute("aria-activedescendant");
  }
  function showActive() {
    [...list.children].forEach((li, i) => li.setAttribute("aria-selected", String(i === st.active)));
    const li = list.children[st.active];
    if (!li) return;
    ta.setAttribute("aria-activedescendant", li.id);
    // scroll the list only (scrollIntoView would scroll the editor's box under the text too)
    if (li.offsetTop < list.scrollTop) list.scrollTop = li.offsetTop;
    else if (li.offsetTop + li.offsetHeight > list.scrollTop + list.clientHeight) {
      list.scrollTop = li.offsetTop + li.offsetHeight - list.clientHeight;
    }
  }
  async function complete() {
    const p = caret(), text = ta.value;
    let m;
    try { m = await opts.ask("complete", { code: text, lang: opts.language(), line: p.line, col: p.col }); }
    catch (e) { return; }
    if (ta.value !== text) return;
    st.items = m.items || [];
    if (!st.items.length) { closeList(); return; }
    st.from = st.items[0].from;
    st.active = 0;
    list.innerHTML = st.items.map((c, i) => `<li id="pg-complete-${i}" role="option" ` +
      `data-label="${esc(c.label)}"><span class="pg-c-label">${esc(c.label)}</span>` +
      `<span class="pg-c-kind">${esc(c.kind)}</span>${c.detail ? `<span class="pg-c-detail">${esc(c.detail)}</span>` : ""}</li>`).join("");
    const at = pixelOf(p.line, st.from);
    list.style.top = at.y + 2 + "px";
    list.hidden = false;
    place(list, at.x);
    showActive();
  }
  function accept(i) {
    const c = st.items[i];
    if (!c) return;
    const p = caret();
    const start = ta.selectionStart - (p.col - st.from);
    ta.setRangeText(c.label, start, ta.selectionStart, "end");
    closeList();
    ta.dispatchEvent(new Event("input", { bubbles: true }));
    ta.focus();
  }
  list.addEventListener("mousedown", (e) => {
    const li = e.target.closest("li");
    if (li) { e.preventDefault(); accept([...list.children].indexOf(li)); }
  });
  ta.addEventListener("keydown", (e) => {
    if (!list.hidden) {
      if (e.key === "ArrowDown" || e.key === "ArrowUp") {
        e.preventDefault();
        st.active = (st.active + (e.key === "ArrowDown" ? 1 : -1) + st.items.length) % st.items.length;
        showActive(); return;
      }
      if (e.key === "Enter" || e.key === "Tab") { e.preventDefault(); accept(st.active); return; }
      if (e.key === "Escape") { e.preventDefault(); closeList(); return; }
    }
    if (e.key === " " && e.ctrlKey) { e.preventDefault(); complete(); }
    if (e.key === "Escape") hideTip();
  });
  ta.addEventListener("input", (e) => {
    draw(); highlight();
    const ch = ta.value[ta.selectionStart - 1];
    if (e.inputType === "insertText" && ch === ".") complete();
    else if (!list.hidden && ch && IDENT.test(ch)) complete();
    else closeList();
    caretMoved();
  });
  ta.addEventListener("scroll", sync);
  ta.addEventListener("blur", () => setTimeout(closeList, 150));
  for (const ev of ["keyup", "click"]) ta.addEventListener(ev, (e) => {
    if (ev === "keyup" && !["ArrowLeft", "ArrowRight", "ArrowUp", "ArrowDown", "Home", "End",
      "PageUp", "PageDown"].includes(e.key)) return;
    caretMoved();
  });

  return {
    refresh() { draw(); highlight(); },
    setMarks(diags) {
      const lines = ta.value.split("\n");
      st.marks = (diags || []).filter((d) => d.line > 0).map((d) => {
        const s = lines[d.line - 1] || "", col = Math.max(d.col || 1, 1);
        let end = d.end;
        if (!end) { end = col; while (end - 1 < s.length && IDENT.test(s[end - 1])) end++; if (end === col) end = Math.min(col + 1, s.length + 1); }
        if (!d.col) return { ...d, col: 1, end: s.length + 1 };  // a line without a column
        return { ...d, col, end };
      });
      draw();
      caretMoved();
    },
    complete, caret, marks: () => st.marks, closeList,
  };
};
