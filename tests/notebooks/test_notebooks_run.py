"""Every lab notebook, English and Russian (``<lab>.ru.ipynb``), runs top to bottom headless
(nbclient) with the lab's reference solution in its program cell: no error, nothing written to
stderr (nbgrader zeroes such a cell), the timing diagram shown, and a full score. Also: the
committed notebooks are what ``notebooks/build.py`` generates, and a Russian notebook is the
English one with its Markdown in Russian: the same code cells (but for the language of the
feedback), the same program cell.

Needs nbclient, nbformat and ipykernel (skipped with a message when they are missing).
"""

from __future__ import annotations

import importlib.util
import re
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
NB_DIR = ROOT / "notebooks"
LABS = ROOT / "labs"

nbformat = pytest.importorskip("nbformat", reason="the notebook tests need nbformat "
                               "(pip install nbformat nbclient ipykernel)")
nbclient = pytest.importorskip("nbclient", reason="the notebook tests need nbclient "
                               "(pip install nbformat nbclient ipykernel)")
pytest.importorskip("ipykernel", reason="the notebook tests need a Python kernel "
                    "(pip install ipykernel)")


def _build_module():
    spec = importlib.util.spec_from_file_location("plclab_notebooks_build", NB_DIR / "build.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


BUILD = _build_module()
LAB_IDS = BUILD.lab_ids()
EDITIONS = [(lab_id, lang) for lab_id in LAB_IDS for lang in BUILD.editions(lab_id)]
"""(lab, language) of every notebook: the English one and its Russian edition."""
SCORE = re.compile(r"score: ([\d.]+)/([\d.]+)")


def _solution(lab_id: str, starter_ext: str) -> str:
    sols = sorted((LABS / lab_id / "solution").iterdir())
    sols = [p for p in sols if p.suffix in (".st", ".ld")]
    same = [p for p in sols if p.suffix == starter_ext]
    return (same or sols)[0].read_text(encoding="utf-8")


def _starter_ext(lab_id: str) -> str:
    for ext in (".st", ".ld", ".il"):
        if (LABS / lab_id / f"starter{ext}").is_file():
            return ext
    raise AssertionError(f"{lab_id}: no starter")


def _kernel_name() -> str:
    from jupyter_client.kernelspec import KernelSpecManager

    specs = KernelSpecManager().find_kernel_specs()
    if "python3" not in specs:
        pytest.skip("no 'python3' Jupyter kernel installed (pip install ipykernel)")
    return "python3"


def test_every_lab_has_a_notebook():
    labs = sorted(p.name for p in LABS.iterdir() if (p / "lab.toml").is_file())
    assert set(labs) <= set(LAB_IDS), f"labs without a notebook: {set(labs) - set(LAB_IDS)}"
    for lab_id in LAB_IDS:
        assert (NB_DIR / f"{lab_id}.ipynb").is_file(), "run: python notebooks/build.py"
        if (LABS / lab_id / "README.ru.md").is_file():
            assert (NB_DIR / f"{lab_id}.ru.ipynb").is_file(), "run: python notebooks/build.py"


@pytest.mark.parametrize("lab_id, lang", EDITIONS, ids=lambda x: x)
def test_notebook_is_up_to_date(lab_id, lang):
    text = BUILD.render(BUILD.build_notebook(lab_id, lang))
    have = BUILD.notebook_path(lab_id, lang).read_text(encoding="utf-8")
    assert have == text, "run: python notebooks/build.py"
    nb = nbformat.reads(have, as_version=4)
    nbformat.validate(nb)
    tagged = [c for c in nb.cells if BUILD.PROGRAM_TAG in c.metadata.get("tags", [])]
    assert len(tagged) == 1, "exactly one program cell"
    assert all(not c.get("outputs") for c in nb.cells if c.cell_type == "code"), \
        "committed without outputs"


@pytest.mark.parametrize("lab_id", [e[0] for e in EDITIONS if e[1] == "ru"])
def test_the_russian_notebook_is_the_english_one_in_russian(lab_id):
    en = nbformat.read(NB_DIR / f"{lab_id}.ipynb", as_version=4)
    ru = nbformat.read(NB_DIR / f"{lab_id}.ru.ipynb", as_version=4)
    assert [c.cell_type for c in en.cells] == [c.cell_type for c in ru.cells]
    for a, b in zip(en.cells, ru.cells, strict=True):
        if a.cell_type == "code":  # the same code; the set-up chooses the language
            assert a.source.replace("set_language('en')", "set_language('ru')") == b.source
        else:
            assert re.search("[А-Яа-яЁё]", b.source), f"not in Russian: {b.source[:80]!r}"
    questions = ru.cells[-3 if BUILD.quiz_chapter(lab_id) else -1].source
    assert len(re.findall(r"^\d+\. ", questions, re.M)) == len(BUILD.lab_config(lab_id)[
        "questions"])


def test_a_russian_notebook_needs_every_question_in_russian(monkeypatch):
    monkeypatch.setitem(BUILD.QUESTIONS_RU, "tank-two-position", ["только один вопрос"])
    with pytest.raises(ValueError, match="2 questions in English, 1 in ru"):
        BUILD.build_notebook("tank-two-position", "ru")


def _execute(lab_id, program=None, lang="en"):
    """Run a notebook (with ``program`` in its program cell): (notebook, wall seconds)."""
    kernel = _kernel_name()
    nb = nbformat.read(BUILD.notebook_path(lab_id, lang), as_version=4)
    if program is not None:
        cell = next(c for c in nb.cells if BUILD.PROGRAM_TAG in c.metadata.get("tags", []))
        cell.source = BUILD.program_source(program)
    client = nbclient.NotebookClient(nb, timeout=120, kernel_name=kernel,
                                     resources={"metadata": {"path": str(NB_DIR)}})
    t0 = time.perf_counter()
    client.execute()
    return nb, time.perf_counter() - t0


def _outputs(nb):
    """(stderr texts, errors, other texts, number of PNG images) of an executed notebook."""
    stderr, errors, texts, images = [], [], [], 0
    for i, c in enumerate(nb.cells):
        for out in c.get("outputs", []):
            if out.output_type == "stream":
                (stderr if out.name == "stderr" else texts).append(f"cell {i}: {out.text}")
            elif out.output_type == "error":
                errors.append(f"cell {i}: {out.ename}: {out.evalue}")
            else:
                data = out.get("data", {})
                images += "image/png" in data
                texts.append(data.get("text/markdown", "") + data.get("text/plain", ""))
    return stderr, errors, texts, images


@pytest.mark.parametrize("lab_id, lang", EDITIONS, ids=lambda x: x)
def test_notebook_runs_with_the_solution(lab_id, lang):
    nb, wall = _execute(lab_id, _solution(lab_id, _starter_ext(lab_id)), lang)
    stderr, errors, texts, images = _outputs(nb)
    print(f"{lab_id}: {wall:.1f} s")
    assert not errors, errors
    assert not stderr, f"output on stderr: {stderr}"
    assert images >= 1, "the timing diagram is shown"
    scores = SCORE.findall("\n".join(texts))
    assert scores, "the notebook prints its score"
    got, full = (float(x) for x in scores[-1])
    assert full > 0 and got == full, f"{lab_id}: score {got:g}/{full:g} with the solution"
    assert wall < 60, f"{lab_id}: the notebook took {wall:.1f} s"


@pytest.mark.parametrize("lab_id, lang", EDITIONS, ids=lambda x: x)
def test_notebook_runs_as_committed(lab_id, lang):
    """A student's first Run All, with the starter: no error, no stderr, a low score; in the
    Russian notebook the feedback is Russian."""
    nb, _ = _execute(lab_id, lang=lang)
    stderr, errors, texts, _ = _outputs(nb)
    assert not errors, errors
    assert not stderr, f"output on stderr: {stderr}"
    got, full = (float(x) for x in SCORE.findall("\n".join(texts))[-1])
    assert got <= 0.25 * full
    if lang == "ru":
        assert "Баллы:" in "\n".join(texts)


def test_a_broken_program_is_reported_not_raised():
    """A program that does not compile gives the compiler's messages, not a traceback."""
    nb, _ = _execute("tank-two-position", "PROGRAM Broken\nVAR x : BOOL END_VAR\nx := ;\n"
                     "END_PROGRAM")
    stderr, errors, texts, _ = _outputs(nb)
    assert not errors, errors
    assert not stderr, f"output on stderr: {stderr}"
    text = "\n".join(texts)
    assert "PLC0010" in text and "cannot run yet" in text
    assert "score: 0/" in text


def test_no_stderr_on_a_fresh_machine(tmp_path, monkeypatch):
    """On a fresh machine matplotlib builds its font cache at the first plot and says so on
    stderr, unless the notebook silences it: an empty config folder makes it happen here."""
    monkeypatch.setenv("MPLCONFIGDIR", str(tmp_path / "mpl"))
    nb, _ = _execute("motor-start-stop", _solution("motor-start-stop", ".ld"))
    stderr, errors, _, images = _outputs(nb)
    assert not errors, errors
    assert not stderr, f"output on stderr: {stderr}"
    assert images >= 1
    assert (tmp_path / "mpl").is_dir()


def test_a_mistake_opens_on_its_first_failure_with_the_criterions_limits():
    """After a failed check the notebook draws the first failing scenario at its first failure
    (what ``lab check --png`` draws: the scenario and criterion named, the failure's red line)."""
    import base64
    import io

    from PIL import Image

    from plclab.grade import check, load_lab
    from plclab.grade.commands import first_failure

    mistake = (LABS / "tank-two-position" / "mistakes" / "follows_ls1.st").read_text("utf-8")
    nb, _ = _execute("tank-two-position", mistake)
    stderr, errors, texts, images = _outputs(nb)
    assert not errors, errors
    assert not stderr, f"output on stderr: {stderr}"
    res = check("tank-two-position", mistake)
    first = first_failure(load_lab("tank-two-position"), res.tests, res.traces)
    assert first is not None, "the mistake fails"
    said = next(t for t in texts if "first failure:" in t)
    assert f"scenario '{first.scenario}'" in said and f"criterion '{first.criterion}'" in said
    grade_cell = next(c for c in nb.cells if "result = grade(PROGRAM)" in c.source)
    pngs = [base64.b64decode(o["data"]["image/png"]) for o in grade_cell.outputs
            if "image/png" in o.get("data", {})]
    assert len(pngs) == 1, "the first failure's picture"
    img = Image.open(io.BytesIO(pngs[0])).convert("RGB")
    assert f"{first.scenario}: {first.criterion} (FAILED)" == Image.open(
        io.BytesIO(pngs[0])).text.get("Title")
    px, (w, h) = img.load(), img.size
    red = [x for x in range(w) if sum(px[x, y][0] - px[x, y][1] > 45 and
                                      abs(px[x, y][1] - px[x, y][2]) < 30 for y in range(h)) > 30]
    assert red, "the failure's red line"
