"""plclab quiz export: the quiz pool as Moodle GIFT and as an IMS QTI 1.2 package.

The GIFT is read back with the strict grammar of ``parse_gift`` (the subset Moodle's own
``qformat_gift`` reads: ``::title::[html]text{answers####feedback}``, the special characters
``~ = # { } :`` and ``\\`` escaped); the QTI is parsed as XML and checked by ``check_qti``.
Both checkers are shown wrong documents they must refuse, and the keys that come out are
compared with the keys written in quiz.toml (recomputed on the way out, so a drifting key
shows here)."""

import html
import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plclab.cli import main
from plclab.course.model import chapters
from plclab.course.quiz import items
from plclab.course.quiz_export import (
    QTI_NS,
    check_qti,
    export_items,
    gift_escape,
    parse_gift,
    read_qti_zip,
    to_gift,
    to_qti,
)
from plclab.errors import PlcError

ROOT = Path(__file__).resolve().parents[2]

# An item of each kind whose every text is full of what GIFT and XML must escape.
NASTY = r"""a := b; x{1} ~ y = z # 50 % : done \ back-slash <tag> & ]]> "quoted" 'single'"""
QUIZ = '''
[[item]]
id = "nasty-choice"
kind = "choice"
question = @QUESTION@
choices = ["=right? {no}", "~tilde: #1", "plain \\\\ text"]
answer = 2
explain = "Because {x} = 1 # and : too"

[[item]]
id = "nasty-numeric"
kind = "numeric"
question = "What is -3 * 4? ~ = # { } :"
compute = "-3.0 * 4.0"
answer = -12
tolerance = 0.5
unit = "m/s: {per} #"
explain = "-12; a minus sign is not GIFT's ~"

[[item]]
id = "nasty-output"
kind = "output"
question = "What is Q after one scan? (= not ~)"
program = """
PROGRAM P
VAR
    Q : BOOL;
    S : STRING := 'a{=}#:~';
END_VAR

(* a blank line above and a comment with { braces } *)
Q := LEN(S) = 7;
END_PROGRAM
"""
show = "P.Q"
answer = "TRUE"
explain = "LEN('a{=}#:~') is 7"

[[item]]
id = "nasty-write"
kind = "write"
question = "Write Y := A OR B (with {} and = in the text)"
solution = "PROGRAM P VAR A, B, Y : BOOL; END_VAR Y := A OR B; END_PROGRAM"
step = [ { set = { "P.A" = true }, expect = { "P.Y" = true } } ]
explain = "OR: # = ~"
'''.replace("@QUESTION@", json.dumps(NASTY + "\n\nSecond paragraph with `code := {x}`."))


@pytest.fixture
def nasty_course(tmp_path):
    ch = tmp_path / "course" / "01-nasty"
    ch.mkdir(parents=True)
    (ch / "chapter.md").write_text("# Nasty: {braces} = #1\n\nText.\n", encoding="utf-8")
    (ch / "quiz.toml").write_text(QUIZ, encoding="utf-8")
    return tmp_path / "course"


def test_the_nasty_items_survive_gift(nasty_course):
    chs = chapters(nasty_course)
    gift = to_gift(export_items(chs))
    qs = parse_gift(gift)
    assert [q.kind for q in qs] == ["choice", "numeric", "short", "essay"]
    choice, numeric, short, essay = qs
    # the decoded text is the HTML of the source text, every special character back in place
    assert html.escape(NASTY, quote=False) in choice.text
    assert "<code>code := {x}</code>" in choice.text
    assert [a for _, a in choice.answers] == ["=right? {no}", "~tilde: #1", "plain \\ text"]
    assert [r for r, _ in choice.answers] == [False, True, False]
    assert "Because {x} = 1 # and : too" in choice.feedback
    assert numeric.numeric == (-12.0, 0.5)
    assert "m/s: {per} #" in numeric.text
    assert [a for _, a in short.answers] == ["TRUE", "1"]
    # the program keeps its lines (joined by <br> inside <pre>), blank line included
    assert "<pre>PROGRAM P<br>VAR<br>    Q : BOOL;" in short.text
    assert "END_VAR<br><br>(* a blank line" in short.text
    assert "S : STRING := 'a{=}#:~';" in html.unescape(short.text)
    assert "plclab quiz 1" in essay.text
    # one question per paragraph of the file: no blank line inside a question
    assert len(re.findall(r"^::", gift, re.M)) == 4


def test_the_nasty_items_survive_qti(nasty_course):
    files = to_qti(export_items(chapters(nasty_course)))
    assert check_qti(files) == []
    root = ET.fromstring(files["plclab-ch01.xml"])
    texts = [m.text for m in root.iter(f"{{{QTI_NS}}}mattext")]
    assert any(html.escape(NASTY, quote=False) in (t or "") for t in texts)
    assert any("]]&gt;" in (t or "") for t in texts)  # the text, not a CDATA end
    kinds = [f.findtext(f"{{{QTI_NS}}}fieldentry") for f in root.iter(f"{{{QTI_NS}}}qtimetadatafield")
             if f.findtext(f"{{{QTI_NS}}}fieldlabel") == "question_type"]
    assert kinds == ["multiple_choice_question", "numerical_question", "short_answer_question",
                     "essay_question"]
    ranges = [float(v.text) for v in root.iter() if v.tag in (f"{{{QTI_NS}}}vargte",
                                                              f"{{{QTI_NS}}}varlte")]
    assert ranges == [-12.5, -11.5]


# ------------------------------------------------------------------ the real pool, both ways

def _plain(text: str) -> str:
    return html.unescape(re.sub(r"</?code>", "", text))


@pytest.fixture(scope="module")
def pool():
    return export_items(chapters())


def test_the_whole_pool_reads_back_from_gift(pool):
    qs = parse_gift(to_gift(pool))
    assert len(qs) == len(pool) == sum(len(items(c)) for c in chapters())
    for e, q in zip(pool, qs, strict=True):
        d = e.item.data
        assert q.category.startswith(f"$course$/plclab/{e.chapter.number:02d} ")
        if e.item.kind == "choice":
            right = [_plain(a) for r, a in q.answers if r]
            assert right == [" ".join(d["choices"][d["answer"] - 1].split()).replace("`", "")]
            assert len(q.answers) == len(d["choices"])
        elif e.item.kind == "numeric":
            value, tol = q.numeric
            assert abs(value - float(d["answer"])) <= tol + 1e-9, e.ident  # quiz.toml's key
        elif e.item.kind == "output":
            if "answer" in d:
                assert str(d["answer"]).upper() in {a.upper() for _, a in q.answers}
        else:
            assert q.kind == "essay"


def test_the_whole_pool_is_a_sound_qti_package(pool):
    files = to_qti(pool)
    assert check_qti(files) == []
    assert len(files) == 1 + len(chapters())
    n = sum(len(list(ET.fromstring(b).iter(f"{{{QTI_NS}}}item")))
            for name, b in files.items() if name != "imsmanifest.xml")
    assert n == len(pool)


# ---------------------------------------------------------------- checkers on wrong inputs

@pytest.mark.parametrize("wrong,why", [
    ("::t::[html]a = b{=x ~y}", "unescaped '=' in the question text"),
    ("::t::[html]a: b{=x ~y}", "unescaped ':' in the question text"),
    ("::t::[html]a {b} c{=x ~y}", "one {...} at the end"),
    ("::t::[html]a{=x ~y}tail", "one {...} at the end"),
    ("::t::[html]a{=x ~y =z}", "exactly one ="),
    ("::t::[html]a{~x ~y}", "no right answer"),
    ("::t::[html]a{=x#y ~z}", "unescaped '#' in an answer"),
    ("::t::[html]a{#abc:1}", "#value:tolerance"),
    ("::t::[html]a{#1:}", "#value:tolerance"),
    ("::t::a{=x ~y}", "::title::[html]"),
    ("::t#1::[html]a{=x ~y}", "unescaped '#' in the title"),
    ("::t::[html]a{=x ~y####fb: x}", "in the feedback"),
    ("::t::[html]a{=x ~y####fb {x}}", "one {...} at the end"),
    ("::t::[html]a{=x ~}", "an empty answer"),
])
def test_parse_gift_refuses_what_moodle_would_misread(wrong, why):
    with pytest.raises(PlcError) as e:
        parse_gift(f"// a wrong question\n{wrong}\n")
    assert e.value.code == "PLC3082" and why in str(e.value), str(e.value)


def test_parse_gift_accepts_the_escaped_forms():
    text = "::t::[html]" + gift_escape("a = b: {c} ~d #e \\f") + "{=" + gift_escape("x=1") + \
           " ~" + gift_escape("y:2") + "####" + gift_escape("why: #") + "}"
    (q,) = parse_gift(text)
    assert q.text == "a = b: {c} ~d #e \\f" and q.answers == [(True, "x=1"), (False, "y:2")]
    assert q.feedback == "why: #"


def _mutated(files, name, old, new):
    out = dict(files)
    assert old.encode() in out[name]
    out[name] = out[name].replace(old.encode(), new.encode(), 1)
    return out


def test_check_qti_refuses_broken_packages(nasty_course):
    files = to_qti(export_items(chapters(nasty_course)))
    x = "plclab-ch01.xml"
    wrong = {
        "a key naming no label": _mutated(files, x, ">ch01-nasty-choice-c2<", ">ch01-nasty-choice-c9<"),
        "a condition on another response": _mutated(files, x, 'respident="response1"',
                                                    'respident="response2"'),
        "an empty numeric range": _mutated(files, x, "<varlte respident=\"response1\">-11.5",
                                           "<varlte respident=\"response1\">-13"),
        "feedback that does not exist": _mutated(files, x, 'linkrefid="general_fb"',
                                                 'linkrefid="nowhere"'),
        "not well-formed": _mutated(files, x, "</questestinterop>", "</questestinterp>"),
        "a question type Canvas does not know": _mutated(files, x, "essay_question", "poem"),
        "the manifest misses a file": {**files, "extra.xml": files[x]},
        "a wrong namespace": _mutated(files, x, QTI_NS, "http://example.org/qti"),
    }
    for why, package in wrong.items():
        assert check_qti(package), why
    assert check_qti({k: v for k, v in files.items() if k != "imsmanifest.xml"})


# ------------------------------------------------------------------------- the command line

def test_the_command_writes_both_formats_where_asked(tmp_path, capsys, nasty_course):
    assert main(["quiz", "export", str(tmp_path / "q.gift"), "--course", str(nasty_course)]) == 0
    assert len(parse_gift((tmp_path / "q.gift").read_text(encoding="utf-8"))) == 4
    # --format before OUT, as in "plclab quiz export --format qti OUT"
    assert main(["quiz", "export", "--format", "qti", str(tmp_path / "q.zip"),
                 "--course", str(nasty_course)]) == 0
    assert check_qti(read_qti_zip(tmp_path / "q.zip")) == []
    assert main(["quiz", "export", str(tmp_path), "--format", "gift", "1",
                 "--course", str(nasty_course)]) == 0
    assert (tmp_path / "plclab-quiz.gift").exists()
    assert "4 quiz items of 1 chapter(s)" in capsys.readouterr().out


@pytest.mark.parametrize("args,code", [
    (["quiz", "export"], "PLC3080"),
    (["quiz", "export", "{tmp}/q.docx", "--format", "docx"], "PLC3080"),
    (["quiz", "export", "{tmp}/no/such/folder/q.gift"], "PLC3080"),
    (["quiz", "export", "{course}/q.gift"], "PLC3081"),
    (["quiz", "export", "{course}/01-nasty/q.gift"], "PLC3081"),
    (["quiz", "1", "--format", "qti"], "PLC3002"),
])
def test_the_command_refuses_with_a_code(tmp_path, capsys, nasty_course, args, code):
    args = [a.format(tmp=tmp_path, course=nasty_course) for a in args]
    assert main([*args, "--course", str(nasty_course)]) != 0
    assert code in capsys.readouterr().err
    assert not list(nasty_course.rglob("q.gift"))
