"""The quiz pool exported for learning platforms: Moodle GIFT and IMS QTI 1.2 (Canvas, and the
QTI importers of Moodle plug-ins, Blackboard, Brightspace). ``plclab quiz export OUT``.

Every key is recomputed on the way out (a numeric item's answer by plclab, an output item's by
running its program), never copied from ``quiz.toml``. How each kind of item maps:

=========  ==========================  =============================================
kind       GIFT                        QTI 1.2 (Canvas ``question_type``)
=========  ==========================  =============================================
choice     ``{=right ~wrong ...}``     ``multiple_choice_question``, ``response_lid``
numeric    ``{#key:tolerance}``        ``numerical_question``, a ``vargte``/``varlte`` range
output     ``{=key =alias}``           ``short_answer_question``, one ``varequal`` per form
write      ``{}`` (an essay)           ``essay_question``: graded by ``plclab quiz N``
=========  ==========================  =============================================

Text goes out as HTML (``[html]`` in GIFT, ``texttype="text/html"`` in QTI), programs in
``<pre>``, so indentation survives; a program's lines are joined with ``<br>`` so a blank line
in it cannot end a GIFT question. GIFT's special characters ``~ = # { } :`` and the backslash
are escaped with a backslash wherever text appears. Both writers check what they made before
it is written: :func:`parse_gift` reads the GIFT back with a strict grammar, and
:func:`check_qti` checks the XML's structure (every response referenced exists, every key
lies within its item); a problem is PLC3082, never a file a platform would half import.
Exports go only where the user asks, never into the course sources (PLC3081). ADR 0062.
"""

from __future__ import annotations

import html
import re
import xml.etree.ElementTree as ET
import zipfile
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import PlcError
from .model import Chapter
from .quiz import Item, evaluate_output, items, numeric_key

FORMATS = ("gift", "qti")
QTI_NS = "http://www.imsglobal.org/xsd/ims_qtiasiv1p2"
CP_NS = "http://www.imsglobal.org/xsd/imscp_v1p1"
GIFT_SPECIAL = "~=#{}:"


# ------------------------------------------------------------------------- one exported item

@dataclass
class Exported:
    """An item with its key recomputed, in the terms both formats need."""

    item: Item
    chapter: Chapter
    question_html: str
    choices: list[str] = field(default_factory=list)
    right: int = 0                       # choice: 0-based index of the right choice
    value: float = 0.0                   # numeric key
    tolerance: float = 0.0
    accepted: list[str] = field(default_factory=list)   # output: the accepted answers

    @property
    def ident(self) -> str:
        return f"ch{self.chapter.number:02d}-{re.sub(r'[^A-Za-z0-9_-]', '-', self.item.id)}"

    @property
    def title(self) -> str:
        return f"Chapter {self.chapter.number}, item {self.item.number} ({self.item.id})"


def _html(text: str) -> str:
    """Plain quiz text as HTML: paragraphs, `code` spans, nothing the source could inject."""
    out = []
    for para in re.split(r"\n\s*\n", text.strip()):
        esc = html.escape(" ".join(para.split()), quote=False)
        out.append(re.sub(r"`([^`]+)`", r"<code>\1</code>", esc))
    return "".join(f"<p>{p}</p>" for p in out)


def _pre(program: str) -> str:
    lines = program.strip("\n").splitlines()
    return "<pre>" + "<br>".join(html.escape(line, quote=False) for line in lines) + "</pre>"


def _accepted(key: str) -> list[str]:
    """An output item's accepted answers: the key, and 1/0 for TRUE/FALSE."""
    k = key.strip()
    extra = {"TRUE": ["1"], "FALSE": ["0"]}.get(k.upper(), [])
    return [k, *extra]


def export_item(chapter: Chapter, item: Item) -> Exported:
    """An item with its key recomputed (PlcError when a key cannot be computed)."""
    d = item.data
    q = _html(item.question)
    if item.kind == "output":
        q += _pre(d["program"])
        return Exported(item, chapter, q, accepted=_accepted(evaluate_output(d)))
    if item.kind == "write":
        if "starter" in d:
            q += "<p>Starter:</p>" + _pre(d["starter"])
        q += (f"<p>Write the program, then check it with <code>plclab quiz {chapter.number}"
              "</code>, which runs it against the grading scenario.</p>")
        return Exported(item, chapter, q)
    if item.kind == "choice":
        return Exported(item, chapter, q, choices=[str(c) for c in d["choices"]],
                        right=int(d["answer"]) - 1)
    value = numeric_key(d)
    tol = float(d.get("tolerance", 1e-6 * max(1.0, abs(value))))
    if "unit" in d:
        q += f"<p>Answer in {html.escape(str(d['unit']), quote=False)}.</p>"
    return Exported(item, chapter, q, value=value, tolerance=tol)


def export_items(chs: Iterable[Chapter]) -> list[Exported]:
    return [export_item(c, it) for c in chs for it in items(c)]


def _num(x: float) -> str:
    return repr(round(x, 12)).removesuffix(".0") if float(x).is_integer() else repr(x)


# ----------------------------------------------------------------------------------- GIFT

def gift_escape(text: str) -> str:
    """Escape GIFT's special characters (and the backslash) and keep the text on one line."""
    text = text.replace("\\", "\\\\")
    for ch in GIFT_SPECIAL:
        text = text.replace(ch, "\\" + ch)
    return text.replace("\r", " ").replace("\n", "\\n")


def to_gift(exported: list[Exported]) -> str:
    """The items as one GIFT file, a ``$CATEGORY`` per chapter."""
    out = ["// plclab quiz pool: plclab quiz export --format gift (answer keys recomputed)", ""]
    chapter = None
    for e in exported:
        if e.chapter is not chapter:
            chapter = e.chapter
            out += [f"$CATEGORY: $course$/plclab/{chapter.number:02d} {_one_line(chapter.title)}",
                    ""]
        fb = "####" + gift_escape(_html(e.item.explain))
        if e.item.kind == "choice":
            ans = " ".join(("=" if k == e.right else "~") + gift_escape(_html_inline(c))
                           for k, c in enumerate(e.choices))
        elif e.item.kind == "numeric":
            ans = f"#{_num(e.value)}:{_num(e.tolerance)}"
        elif e.item.kind == "output":
            ans = " ".join("=" + gift_escape(html.escape(a, quote=False)) for a in e.accepted)
        else:
            ans = ""
        out.append(f"// {e.ident}")
        out.append(f"::{gift_escape(e.title)}::[html]{gift_escape(e.question_html)}"
                   f"{{{ans}{fb if ans else ''}}}")
        out.append("")
    return "\n".join(out)


def _one_line(text: str) -> str:
    return " ".join(text.split()).replace("$", "")


def _html_inline(text: str) -> str:
    esc = html.escape(" ".join(str(text).split()), quote=False)
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", esc)


@dataclass
class GiftQuestion:
    """A question as :func:`parse_gift` reads it (escapes decoded)."""

    title: str
    text: str
    kind: str                                   # choice | numeric | short | essay
    answers: list[tuple[bool, str]] = field(default_factory=list)
    numeric: tuple[float, float] | None = None
    feedback: str = ""
    category: str = ""


_UNESC = re.compile(r"\\(.)", re.S)


def _unescape(text: str) -> str:
    return _UNESC.sub(lambda m: "\n" if m.group(1) == "n" else m.group(1), text)


def _split_unescaped(text: str, seps: str) -> list[tuple[str, str]]:
    """Split at unescaped characters of *seps*: [(separator, piece), ...]; the first piece has
    the separator ''."""
    out, cur, sep, i = [], [], "", 0
    while i < len(text):
        c = text[i]
        if c == "\\" and i + 1 < len(text):
            cur.append(text[i:i + 2])
            i += 2
            continue
        if c in seps:
            out.append((sep, "".join(cur)))
            cur, sep = [], c
        else:
            cur.append(c)
        i += 1
    out.append((sep, "".join(cur)))
    return out


def _bare(text: str, chars: str) -> str | None:
    """The first special character of *chars* in *text* that is not escaped, or None."""
    i = 0
    while i < len(text):
        if text[i] == "\\":
            i += 2
            continue
        if text[i] in chars:
            return text[i]
        i += 1
    return None


def parse_gift(source: str) -> list[GiftQuestion]:
    """Read GIFT with a strict grammar: the subset :func:`to_gift` writes, every deviation an
    error (PlcError PLC3082 naming the line). Questions are separated by blank lines; ``//``
    lines are comments; a question is ``::title::[html]text{answers}`` where the title and the
    text contain no unescaped special character and the braces hold ``=``/``~`` answers, a
    ``#value:tolerance`` number, or nothing, then an optional ``####`` general feedback."""
    questions: list[GiftQuestion] = []
    category = ""
    block: list[tuple[int, str]] = []

    def fail(line: int, why: str) -> PlcError:
        return PlcError("PLC3082", f"GIFT line {line}: {why}")

    def flush() -> None:
        nonlocal category
        if not block:
            return
        first = block[0][0]
        text = "\n".join(s for _, s in block)
        block.clear()
        if text.startswith("$CATEGORY:"):
            if "\n" in text:
                raise fail(first, "a $CATEGORY line must stand alone")
            category = text[len("$CATEGORY:"):].strip()
            return
        m = re.fullmatch(r"::(.*?)(?<!\\)::\[html\](.*)", text, re.S)
        if not m:
            raise fail(first, "a question must start with ::title::[html]")
        title, rest = m.group(1), m.group(2)
        if (c := _bare(title, GIFT_SPECIAL)) is not None:
            raise fail(first, f"unescaped {c!r} in the title")
        parts = _split_unescaped(rest, "{}")
        if [s for s, _ in parts] != ["", "{", "}"] or parts[2][1].strip():
            raise fail(first, f"the answers must be one {{...}} at the end, found "
                       f"{''.join(s for s, _ in parts)!r} and {parts[-1][1].strip()[:20]!r}")
        qtext, body = parts[0][1], parts[1][1]
        if (c := _bare(qtext, GIFT_SPECIAL)) is not None:
            raise fail(first, f"unescaped {c!r} in the question text")
        body, _, fb = body.partition("####") if "####" in body else (body, "", "")
        if _bare(fb, GIFT_SPECIAL) is not None:
            raise fail(first, f"unescaped {_bare(fb, GIFT_SPECIAL)!r} in the feedback")
        q = GiftQuestion(_unescape(title), _unescape(qtext), "essay", feedback=_unescape(fb),
                         category=category)
        b = body.strip()
        if not b:
            questions.append(q)
            return
        if b.startswith("#"):
            nm = re.fullmatch(r"#(-?\d+(?:\.\d+)?(?:[eE]-?\d+)?):(\d+(?:\.\d+)?(?:[eE]-?\d+)?)", b)
            if not nm:
                raise fail(first, f"a numeric answer must be #value:tolerance, not {b!r}")
            q.kind, q.numeric = "numeric", (float(nm.group(1)), float(nm.group(2)))
            questions.append(q)
            return
        pieces = _split_unescaped(b, "=~")
        if pieces[0][1].strip():
            raise fail(first, f"text before the first answer: {pieces[0][1].strip()!r}")
        for sep, piece in pieces[1:]:
            if _bare(piece, "#:") is not None:
                raise fail(first, f"unescaped {_bare(piece, '#:')!r} in an answer")
            if not piece.strip():
                raise fail(first, "an empty answer")
            q.answers.append((sep == "=", _unescape(piece.strip())))
        rights = sum(r for r, _ in q.answers)
        if rights == 0:
            raise fail(first, "no right answer (=)")
        q.kind = "short" if all(r for r, _ in q.answers) else "choice"
        if q.kind == "choice" and rights != 1:
            raise fail(first, "a multiple-choice question needs exactly one =")
        questions.append(q)

    for n, line in enumerate(source.splitlines(), 1):
        if not line.strip():
            flush()
        elif line.lstrip().startswith("//"):
            continue
        else:
            block.append((n, line))
    flush()
    return questions


# ------------------------------------------------------------------------------------ QTI 1.2

def _q(tag: str) -> str:
    return f"{{{QTI_NS}}}{tag}"


def _sub(parent: ET.Element, tag: str, attrs: dict[str, str] | None = None,
         text: str | None = None) -> ET.Element:
    el = ET.SubElement(parent, _q(tag), attrs or {})
    if text is not None:
        el.text = text
    return el


def _material(parent: ET.Element, html_text: str) -> None:
    _sub(_sub(parent, "material"), "mattext", {"texttype": "text/html"}, html_text)


_CANVAS_TYPE = {"choice": "multiple_choice_question", "numeric": "numerical_question",
                "output": "short_answer_question", "write": "essay_question"}


def _qti_item(section: ET.Element, e: Exported) -> None:
    it = _sub(section, "item", {"ident": e.ident, "title": e.title})
    meta = _sub(_sub(it, "itemmetadata"), "qtimetadata")
    for label, entry in (("question_type", _CANVAS_TYPE[e.item.kind]), ("points_possible", "1"),
                         ("plclab_kind", e.item.kind)):
        f = _sub(meta, "qtimetadatafield")
        _sub(f, "fieldlabel", text=label)
        _sub(f, "fieldentry", text=entry)
    pres = _sub(it, "presentation")
    _material(pres, e.question_html)
    if e.item.kind == "choice":
        lid = _sub(pres, "response_lid", {"ident": "response1", "rcardinality": "Single"})
        rc = _sub(lid, "render_choice")
        for k, c in enumerate(e.choices):
            _material(_sub(rc, "response_label", {"ident": f"{e.ident}-c{k + 1}"}),
                      _html_inline(c))
    else:
        rs = _sub(pres, "response_str", {"ident": "response1", "rcardinality": "Single"})
        fib = {"numeric": {"fibtype": "Decimal"}, "write": {"fibtype": "String", "rows": "15"}}
        _sub(_sub(rs, "render_fib", fib.get(e.item.kind, {"fibtype": "String"})),
             "response_label", {"ident": "answer1", "rshuffle": "No"})
    proc = _sub(it, "resprocessing")
    _sub(_sub(proc, "outcomes"), "decvar", {"maxvalue": "100", "minvalue": "0",
                                            "varname": "SCORE", "vartype": "Decimal"})
    general = _sub(proc, "respcondition", {"continue": "Yes"})
    _sub(_sub(general, "conditionvar"), "other")
    _sub(general, "displayfeedback", {"feedbacktype": "Response", "linkrefid": "general_fb"})
    if e.item.kind != "write":
        cond = _sub(proc, "respcondition", {"continue": "No"})
        var = _sub(cond, "conditionvar")
        if e.item.kind == "choice":
            _sub(var, "varequal", {"respident": "response1"}, f"{e.ident}-c{e.right + 1}")
        elif e.item.kind == "numeric":
            _sub(var, "vargte", {"respident": "response1"}, _num(e.value - e.tolerance))
            _sub(var, "varlte", {"respident": "response1"}, _num(e.value + e.tolerance))
        else:
            for a in e.accepted:
                _sub(var, "varequal", {"respident": "response1", "case": "No"}, a)
        _sub(cond, "setvar", {"action": "Set", "varname": "SCORE"}, "100")
    fb = _sub(it, "itemfeedback", {"ident": "general_fb"})
    _material(_sub(fb, "flow_mat"), _html(e.item.explain))


def to_qti(exported: list[Exported]) -> dict[str, bytes]:
    """The items as a QTI 1.2 content package: ``imsmanifest.xml`` and one assessment per
    chapter (``{file name: bytes}``; :func:`write_export` zips it)."""
    ET.register_namespace("", QTI_NS)
    files: dict[str, bytes] = {}
    by_chapter: dict[int, list[Exported]] = {}
    for e in exported:
        by_chapter.setdefault(e.chapter.number, []).append(e)
    for number, its in by_chapter.items():
        ch = its[0].chapter
        root = ET.Element(_q("questestinterop"))
        asmt = _sub(root, "assessment", {"ident": f"plclab-ch{number:02d}",
                                         "title": f"plclab {number}: {_one_line(ch.title)}"})
        section = _sub(asmt, "section", {"ident": "root_section"})
        for e in its:
            _qti_item(section, e)
        ET.indent(root)
        files[f"plclab-ch{number:02d}.xml"] = ET.tostring(root, encoding="utf-8",
                                                          xml_declaration=True)
    ET.register_namespace("", CP_NS)
    man = ET.Element(f"{{{CP_NS}}}manifest", {"identifier": "plclab-quiz-pool"})
    ET.SubElement(man, f"{{{CP_NS}}}organizations")
    res = ET.SubElement(man, f"{{{CP_NS}}}resources")
    for name in files:
        r = ET.SubElement(res, f"{{{CP_NS}}}resource", {"identifier": name.removesuffix(".xml"),
                                                        "type": "imsqti_xmlv1p2", "href": name})
        ET.SubElement(r, f"{{{CP_NS}}}file", {"href": name})
    ET.indent(man)
    files = {"imsmanifest.xml": ET.tostring(man, encoding="utf-8", xml_declaration=True),
             **files}
    return files


def check_qti(files: dict[str, bytes]) -> list[str]:
    """Structural problems of a QTI 1.2 package (empty: none). Checks what an importer relies
    on: well-formed XML in the QTI namespace; a manifest whose resources name the package's
    assessment files; unique item idents; a question text, one response and a question_type
    per item; every condition's ``respident`` naming the item's response; a choice key naming
    one of the item's labels; a numeric range with its low end below its high end; short
    answers with at least one accepted text; feedback that the conditions link exists."""
    problems: list[str] = []
    try:
        man = ET.fromstring(files["imsmanifest.xml"])
    except KeyError:
        return ["no imsmanifest.xml"]
    except ET.ParseError as e:
        return [f"imsmanifest.xml: not well-formed XML ({e})"]
    hrefs = [r.get("href") for r in man.iter(f"{{{CP_NS}}}resource")]
    others = sorted(n for n in files if n != "imsmanifest.xml")
    if sorted(h or "" for h in hrefs) != others:
        problems.append(f"the manifest lists {sorted(h or '' for h in hrefs)}, the package "
                        f"has {others}")
    seen: set[str] = set()
    for name in others:
        try:
            root = ET.fromstring(files[name])
        except ET.ParseError as e:
            problems.append(f"{name}: not well-formed XML ({e})")
            continue
        if root.tag != _q("questestinterop"):
            problems.append(f"{name}: the root is {root.tag}, not questestinterop in {QTI_NS}")
            continue
        for it in root.iter(_q("item")):
            problems += [f"{name} {it.get('ident')}: {p}" for p in _item_problems(it, seen)]
    return problems


def _item_problems(it: ET.Element, seen: set[str]) -> list[str]:
    out = []
    ident = it.get("ident") or ""
    if not ident or ident in seen:
        out.append("missing or repeated ident")
    seen.add(ident)
    fields = {f.findtext(_q("fieldlabel")): f.findtext(_q("fieldentry"))
              for f in it.iter(_q("qtimetadatafield"))}
    qtype = fields.get("question_type")
    if qtype not in _CANVAS_TYPE.values():
        out.append(f"question_type {qtype!r}")
    pres = it.find(_q("presentation"))
    if pres is None or not (pres.findtext(f"{_q('material')}/{_q('mattext')}") or "").strip():
        return out + ["no question text"]
    responses = list(pres.iter(_q("response_lid"))) + list(pres.iter(_q("response_str")))
    if len(responses) != 1:
        return out + [f"{len(responses)} responses, not 1"]
    resp = responses[0].get("ident")
    labels = {lab.get("ident") for lab in responses[0].iter(_q("response_label"))}
    conds = [c for c in it.iter(_q("respcondition"))
             if c.find(f"{_q('conditionvar')}/{_q('other')}") is None]
    for c in it.iter(_q("conditionvar")):
        for v in c:
            if v.tag != _q("other") and v.get("respident") != resp:
                out.append(f"a condition names response {v.get('respident')!r}, not {resp!r}")
    fb_ids = {f.get("ident") for f in it.iter(_q("itemfeedback"))}
    for d in it.iter(_q("displayfeedback")):
        if d.get("linkrefid") not in fb_ids:
            out.append(f"feedback {d.get('linkrefid')!r} does not exist")
    if qtype == "essay_question":
        return out
    if len(conds) != 1:
        return out + [f"{len(conds)} scoring conditions, not 1"]
    var = conds[0].find(_q("conditionvar"))
    assert var is not None
    if qtype == "multiple_choice_question":
        keys = [v.text for v in var.iter(_q("varequal"))]
        if len(labels) < 2 or len(keys) != 1 or keys[0] not in labels:
            out.append(f"the key {keys} is not one of the labels {sorted(labels)}")
    elif qtype == "numerical_question":
        try:
            lo = float(var.findtext(_q("vargte")) or "nan")
            hi = float(var.findtext(_q("varlte")) or "nan")
            if not lo <= hi:
                out.append(f"the range {lo}..{hi} is empty")
        except ValueError:
            out.append("the numeric range is not a number")
    elif not [v for v in var.iter(_q("varequal")) if (v.text or "").strip()]:
        out.append("a short answer without an accepted text")
    if conds[0].findtext(_q("setvar")) != "100":
        out.append("the right answer does not score 100")
    return out


# ------------------------------------------------------------------------------- writing out

def write_export(chs: list[Chapter], fmt: str, out: str | Path,
                 course_dir: str | Path | None = None) -> tuple[Path, int]:
    """Export the quizzes of *chs* as *fmt* into *out* (a ``.gift`` text file, or a QTI
    ``.zip``); returns (path written, number of items). Checks the result first."""
    if fmt not in FORMATS:
        raise PlcError("PLC3080", f"quiz export: format {fmt!r}; use --format gift or "
                       "--format qti")
    path = Path(out).expanduser()
    if path.is_dir():
        path = path / ("plclab-quiz.gift" if fmt == "gift" else "plclab-quiz-qti.zip")
    sources = {Path(c.folder).resolve().parent for c in chs}
    if course_dir:
        sources.add(Path(course_dir).resolve())
    target = path.resolve()
    for src in sources:
        if target == src or src in target.parents:
            raise PlcError("PLC3081", f"quiz export: {path} is inside the course sources "
                           f"({src}); write it elsewhere, e.g. plclab quiz export "
                           f"~/quiz.{'gift' if fmt == 'gift' else 'zip'}")
    exported = export_items(chs)
    if fmt == "gift":
        text = to_gift(exported)
        back = parse_gift(text)  # raises PLC3082 on a grammar problem
        if len(back) != len(exported):
            raise PlcError("PLC3082", f"quiz export: {len(exported)} items but the GIFT reads "
                           f"back as {len(back)} questions")
        data = text.encode("utf-8")
    else:
        files = to_qti(exported)
        problems = check_qti(files)
        if problems:
            raise PlcError("PLC3082", "quiz export: the QTI package is not sound: "
                           + "; ".join(problems[:5]))
        data = b""
    if not path.parent.is_dir():
        raise PlcError("PLC3080", f"quiz export: the folder {path.parent} does not exist; "
                       "create it or give another path")
    try:
        if fmt == "gift":
            path.write_bytes(data)
        else:
            with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
                for name, content in files.items():
                    z.writestr(name, content)
    except OSError as e:
        raise PlcError("PLC3080", f"quiz export: cannot write {path}: {e.strerror}") from None
    return path, len(exported)


def read_qti_zip(path: str | Path) -> dict[str, bytes]:
    """The files of a QTI package written by :func:`write_export`."""
    with zipfile.ZipFile(path) as z:
        return {n: z.read(n) for n in z.namelist()}


__all__ = ["FORMATS", "Exported", "GiftQuestion", "check_qti", "export_item", "export_items",
           "gift_escape", "parse_gift", "read_qti_zip", "to_gift", "to_qti", "write_export"]
