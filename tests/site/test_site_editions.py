"""The site's two editions (ADR 0071): the Russian one has every page the English one has, at
the same path, made from the Russian sources where they exist (chapters, quizzes, lab texts,
the problem catalogue, the playground's texts) and says so where they do not yet."""

import json
import re
from pathlib import Path

import pytest

from plclab import i18n
from plclab.problems import catalogue
from plclab.site import build as site_build
from plclab.site import pages
from plclab.site.links import relink

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def editions(tmp_path_factory):
    root = tmp_path_factory.mktemp("site-editions")
    navs = {}
    for lang in site_build.EDITIONS:
        docs = root / lang
        navs[lang], _ = site_build.generate(
            docs, playground=False, figures=False, lang=lang,
            english=None if lang == "en" else root / "en")
        assert not relink(docs, figures=False).broken
    return root / "en", root / "ru", navs


def md_pages(docs: Path) -> set[str]:
    return {p.relative_to(docs).as_posix() for p in docs.rglob("*.md")}


def test_every_english_page_has_its_russian_page_at_the_same_path(editions):
    en, ru, navs = editions
    assert md_pages(en) == md_pages(ru)
    assert len(md_pages(ru)) > 150
    flat = lambda nav: re.findall(r"'([\w/.-]+\.md)'", repr(nav))  # noqa: E731
    assert flat(navs["en"]) == flat(navs["ru"])  # the same nav, in Russian words
    assert "Курс" in repr(navs["ru"]) and "Course" in repr(navs["en"])


def test_a_russian_link_never_leaves_the_russian_edition(editions):
    _, ru, _ = editions
    links = 0
    for md in ru.rglob("*.md"):
        text = re.sub(r"^```.*?^```", "", md.read_text("utf-8"), flags=re.S | re.M)
        for target in re.findall(r'\]\(([^)\s#]+)[^)]*\)|href="([^"#]+)', text):
            target = next(t for t in target if t)
            if re.match(r"^[a-z]+:", target) or "pyodide" in target:
                continue
            links += 1
            where = (md.parent / target.split("#")[0]).resolve()
            assert where.is_relative_to(ru.resolve()), (md, target)
    assert links > 1000


def test_the_check_of_links_leaving_the_edition_can_fail(tmp_path):
    (tmp_path / "ru").mkdir()
    page = tmp_path / "ru" / "index.md"
    page.write_text("[x](../course/index.md)", "utf-8")
    target = re.findall(r"\]\(([^)\s#]+)\)", page.read_text("utf-8"))[0]
    assert not (page.parent / target).resolve().is_relative_to((tmp_path / "ru").resolve())


def test_chapters_come_from_chapter_ru_md_with_their_try_links_in_russian(editions):
    en, ru, _ = editions
    for ch in sorted((REPO / "course").glob("[0-9][0-9]-*/chapter.ru.md")):
        title = ch.read_text("utf-8").splitlines()[0]
        page_ru = (ru / "course" / ch.parent.name / "index.md").read_text("utf-8")
        page_en = (en / "course" / ch.parent.name / "index.md").read_text("utf-8")
        assert page_ru.startswith(title + "\n")
        # the same programs, so the same try-it links, with Russian words
        links = re.findall(r'href="(\.\./\.\./playground/#[^"]+)"', page_ru)
        assert links == re.findall(r'href="(\.\./\.\./playground/#[^"]+)"', page_en), ch
        assert page_ru.count("Попробовать в песочнице") == len(links)
        assert "Try it in the playground" not in page_ru
    index = (ru / "course" / "index.md").read_text("utf-8")
    assert index.startswith("# Курс") and "[Рабочий цикл ПЛК" in index


def test_quizzes_in_both_languages_with_the_same_answers(editions):
    en, ru, _ = editions
    quizzes = sorted((REPO / "course").glob("[0-9][0-9]-*/quiz.toml"))
    assert quizzes
    for q in quizzes:
        slug = q.parent.name
        page_en = (en / "course" / slug / "quiz.md").read_text("utf-8")
        page_ru = (ru / "course" / slug / "quiz.md").read_text("utf-8")
        answers = [re.findall(r'^\?\?\? question "[^"]+"\n    \*\*(.*)\*\*$', p, re.M)
                   for p in (page_en, page_ru)]
        n = len(re.findall(r"^\[\[item\]\]", q.read_text("utf-8"), re.M))
        assert len(answers[0]) == len(answers[1]) == n, slug
        # a choice's number and a computed key are the same in both: a value shown as ST
        # (`7.0`) as it is, a number in prose with the Russian decimal comma
        for a, b in zip(*answers, strict=True):
            if a.startswith("`"):
                assert a.split("`")[1] == b.split("`")[1], slug
                continue
            key = lambda s: re.match(r"^(-?\d+(?:[.,]\d+)?)", s)  # noqa: E731
            if key(a):
                assert key(b) and key(a).group(1).replace(".", ",") == key(b).group(1), slug
        assert "](quiz.md)" in (ru / "course" / slug / "index.md").read_text("utf-8")
    # a program is shown in its own language (quiz.ld is ladder text, not ST)
    ladder = (en / "course" / "06-ladder" / "quiz.md").read_text("utf-8")
    assert "```ld\n" in ladder and "```il\n" in (en / "course" / "08-instruction-list" /
                                                 "quiz.md").read_text("utf-8")
    page = (ru / "course" / "10-timers-counters" / "quiz.md").read_text("utf-8")
    assert page.startswith("# Тест: Таймеры") and '??? question "Ответ"' in page
    assert "Почему TON — функциональный блок" in page


def test_lab_pages_take_the_russian_texts_and_say_what_is_not_translated(editions):
    _, ru, _ = editions
    page = (ru / "labs" / "tank-two-position" / "index.md").read_text("utf-8")
    assert page.startswith("# Бак: двухпозиционное регулирование")
    assert "насос включается ниже LS1" in page or (
        REPO / "labs" / "tank-two-position" / "README.ru.md").exists()
    assert "почти пустой бак" in page  # a scenario from lab.ru.toml
    for lab in sorted((REPO / "labs").glob("*/lab.toml")):
        text = (ru / "labs" / lab.parent.name / "index.md").read_text("utf-8")
        has_own = (lab.parent / "README.ru.md").exists()
        assert ("Ещё не переведено" in text) is not has_own, lab.parent.name
    labs = json.loads((ru / "playground" / "labs.json").read_text("utf-8"))
    crit = labs["tank-two-position"]["criteria"][0]
    assert crit["label"] != crit["name"] and re.search("[а-я]", crit["label"])


def test_a_lab_readme_ru_md_is_the_russian_page(tmp_path):
    (tmp_path / "README.md").write_text("# Tank\n", "utf-8")
    assert pages.localized(tmp_path / "README.md") == tmp_path / "README.md"
    (tmp_path / "README.ru.md").write_text("# Бак\n", "utf-8")
    with site_build.speaking("ru"):
        assert pages.localized(tmp_path / "README.md") == tmp_path / "README.ru.md"
        notice = pages._untranslated_readme("# Tank\n\nFill it.\n", "Бак")
    with site_build.speaking("en"):
        assert pages.localized(tmp_path / "README.md") == tmp_path / "README.md"
    assert notice.startswith("# Бак\n") and "Ещё не переведено" in notice
    assert "*Tank*" in notice and "Fill it." in notice


def test_problem_pages_in_russian(editions):
    _, ru, _ = editions
    ru_titles = i18n.catalogue("ru", "problems")
    page = (ru / "problems" / "PLC0113" / "index.md").read_text("utf-8")
    assert page.startswith(f"# PLC0113: {ru_titles['PLC0113']['title']}\n")
    assert "## Неправильно" in page or not catalogue()["PLC0113"].wrong
    index = (ru / "problems" / "index.md").read_text("utf-8")
    assert index.startswith("# Коды диагностики")
    assert sum(1 for code in catalogue() if f"[{code}]({code}/index.md)" in index) == \
        len(catalogue())


def test_untranslated_sections_say_so_in_russian(editions):
    _, ru, _ = editions
    for page in ("adr/index.md", "reference/blocks.md", "notebooks/index.md"):
        text = (ru / page).read_text("utf-8")
        assert "Эта страница ещё не переведена" in text, page
        assert text.startswith("---\nsearch:\n  exclude: true\n---\n")  # not in ru search
    glossary = (ru / "course" / "glossary.md").read_text("utf-8")
    assert glossary.startswith("# Глоссарий") and "| **PLC** |" in glossary


def test_the_russian_playground_page_has_every_control_of_the_english_one(editions):
    en, ru, _ = editions
    ids = [set(re.findall(r'\bid="([\w-]+)"', (d / "playground" / "index.md").read_text("utf-8")))
           for d in (en, ru)]
    assert ids[0] == ids[1] and len(ids[0]) > 20
    page = (ru / "playground" / "index.md").read_text("utf-8")
    assert '<script src="ui.js"></script>' in page
    assert '<script src="../../playground/playground.js"></script>' in page
    ui = (ru / "playground" / "ui.js").read_text("utf-8")
    data = json.loads(ui.split("window.PLCLAB_UI = ", 1)[1].rstrip().rstrip(";"))
    assert data["lang"] == "ru" and data["texts"]["Pause"] == "Пауза"


def test_every_text_of_the_playground_scripts_is_translated():
    keys = site_build.playground_keys()
    assert len(keys) > 40 and "Ran {seconds} s of virtual time ({scans} scans) in {ms} ms." in keys
    texts = site_build.playground_texts("ru")
    missing = [k for k in keys if k not in texts]
    assert not missing, "add to plclab/locale/ru/ui.toml: " + repr(missing)
    for key in keys:  # the same placeholders
        assert sorted(i18n.fields(key)) == sorted(i18n.fields(texts[key])), key


def test_the_playground_key_scan_finds_joined_and_new_texts(tmp_path, monkeypatch):
    (tmp_path / "playground").mkdir()
    (tmp_path / "playground" / "playground.js").write_text(
        'x = t("A " +\n  "b {n}", { n }); y = t(\'no\'); z = t("new \\"one\\"");', "utf-8")
    (tmp_path / "playground" / "editor.js").write_text("", "utf-8")
    monkeypatch.setattr(site_build, "SITE_SOURCES", tmp_path)
    assert site_build.playground_keys() == ["A b {n}", 'new "one"']
    assert site_build.playground_texts("ru") == {}  # nothing of it is translated


def test_mkdocs_config_of_each_edition(tmp_path):
    en = site_build.mkdocs_config(tmp_path, tmp_path / "out", [], "en")
    ru = site_build.mkdocs_config(tmp_path, tmp_path / "out", [], "ru")
    assert en["theme"]["language"] == "en" and ru["theme"]["language"] == "ru"
    assert ru["plugins"] == [{"search": {"lang": ["ru", "en"]}}]
    assert [(e["lang"], e["link"], e["current"]) for e in ru["extra"]["editions"]] == \
        [("en", "../", False), ("ru", "", True)]
    assert [(e["lang"], e["link"]) for e in en["extra"]["editions"]] == [("en", ""), ("ru", "ru/")]
    assert ru["site_description"].startswith("Программирование ПЛК")
    assert (Path(en["theme"]["custom_dir"]) / "partials" / "alternate.html").exists()


def test_a_translated_edition_needs_the_english_one(tmp_path):
    with pytest.raises(ValueError):
        site_build.generate(tmp_path, playground=False, figures=False, lang="ru")
