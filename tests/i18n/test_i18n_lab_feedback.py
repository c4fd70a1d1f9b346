"""`plclab --lang ru lab check` speaks Russian for every lab: the feedback of each lab's first
typical mistake (criterion names, scenario titles, verdicts, hints, the messages of the lab's
own ``checks.py``, the ``feedback.md`` of ``--out``) holds no English sentence; and every
message ``checks.py`` can return has a Russian template in the lab's ``lab.ru.toml``."""

import shutil
import tomllib
from pathlib import Path

import pytest

from plclab import i18n
from plclab.cli import main
from plclab.i18n_check import check_messages, english_runs, untranslated_check_messages

ROOT = Path(__file__).resolve().parents[2]
LABS = sorted(p.parent for p in (ROOT / "labs").glob("*/lab.toml"))


@pytest.fixture(autouse=True)
def _english_again():
    yield
    i18n.set_language(None)


def first_mistake(lab: Path) -> Path:
    """The first ``[[mistake]]`` of the lab's ``lab.toml`` (else the first file in mistakes/)."""
    spec = tomllib.loads((lab / "lab.toml").read_text(encoding="utf-8-sig"))
    listed = [m["file"] for m in spec.get("mistake", []) if m.get("file")]
    return lab / "mistakes" / listed[0] if listed else sorted((lab / "mistakes").iterdir())[0]


def english_lines(text: str) -> list[str]:
    return [f"{line.strip()}  <- {runs}" for line in text.splitlines()
            if (runs := english_runs(line))]


def check_in_russian(capsys, lab: Path, *more: str) -> str:
    main(["--lang", "ru", "lab", "check", str(lab), str(first_mistake(lab)), "--hint", "2",
          *more])
    return capsys.readouterr().out


@pytest.mark.parametrize("lab", LABS, ids=lambda p: p.name)
def test_the_feedback_of_the_first_mistake_is_russian(capsys, tmp_path, lab):
    printed = check_in_russian(capsys, lab)
    assert "Баллы:" in printed or "баллов" in printed, printed[:500]
    left = english_lines(printed)
    assert not left, "English left in the feedback:\n" + "\n".join(left)


def test_feedback_md_is_the_russian_feedback(capsys, tmp_path):
    lab = ROOT / "labs" / "motor-start-stop"
    printed = check_in_russian(capsys, lab, "--out", str(tmp_path / "out"))
    written = (tmp_path / "out" / "feedback.md").read_text(encoding="utf-8")
    assert "Критерий" in written and written.strip() in printed
    assert not english_lines(written), english_lines(written)


def test_the_check_finds_an_english_message_a_lab_text_file_lacks(capsys, tmp_path):
    """Test of the test: without its checks.py templates, bottle-packing's first mistake prints
    English ("box 1 was closed at t = 3.35 s after 1 bottle(s)") and the check says so."""
    lab = tmp_path / "bottle-packing"
    shutil.copytree(ROOT / "labs" / "bottle-packing", lab)
    texts = (lab / "lab.ru.toml").read_text(encoding="utf-8")
    start = texts.index("messages = [")
    end = texts.index("]\n", start) + 2
    (lab / "lab.ru.toml").write_text(texts[:start] + texts[end:], encoding="utf-8")
    left = english_lines(check_in_russian(capsys, lab))
    assert any("box 1 was closed at t" in line for line in left), left
    assert untranslated_check_messages(lab, "ru")  # and the static check finds it too


def test_english_runs_catches_sentences_and_spares_code_names_and_units():
    assert english_runs("the belt stood still for every box change") != []
    assert english_runs("| НЕТ | ящики | 0/3 | box 2 was closed at t = 22.80 s |") != []
    assert english_runs("Hint: the pump must stop") != []
    for russian in ("насос включается ниже LS1: `PUMP and not LS2` при t = 3,5 с",
                    "`RUN or %QX0.0` ни разу не выполнялось между 0,00 с и 0,95 с",
                    "Файлы: `ignores_overload.st`; score: 11/22",
                    "K1, BELT_FWD, %MW0 = 3, 27648 counts = 100 %, T#1.5s"):
        assert english_runs(russian) == [], russian


@pytest.mark.parametrize("lab", [p for p in LABS if (p / "checks.py").is_file()],
                         ids=lambda p: p.name)
def test_every_message_of_checks_py_has_a_russian_template(lab):
    assert check_messages(lab / "checks.py")
    missing = untranslated_check_messages(lab, "ru")
    assert not missing, "\n".join(missing)


def test_a_new_check_message_without_a_template_is_named(tmp_path):
    lab = tmp_path / "demo"
    lab.mkdir()
    (lab / "checks.py").write_text(
        "def c(trace):\n"
        "    if trace:\n"
        "        return False, f'the pump ran {trace.t:.1f} s too long', 1.0\n"
        "    return True, f'the pump stopped at {trace.t:.2f} s'\n", encoding="utf-8")
    (lab / "lab.ru.toml").write_text(
        'title = "Демо"\nmessages = [\n'
        '  { en = "the pump stopped at {t:num} s", ru = "насос остановился при {t:num} с" },\n'
        ']\n', encoding="utf-8")
    missing = untranslated_check_messages(lab, "ru")
    assert len(missing) == 1 and "'the pump ran 1.5 s too long'" in missing[0]
    assert "labs/demo/lab.ru.toml" in missing[0]
