"""Every lab's README requirements map to its criteria (issue 31 item 1): each ``- **Rn**``
item of ``## Requirements`` is named by at least one criterion's ``requirements``, every id a
criterion names exists in the README, and at least one criterion is critical. The message
lists the gaps so a lab author sees what to add."""

import re

import pytest

from plclab.grade.lab import list_labs, load_lab, repo_labs_dir

from .lab_contract import REQUIREMENTS_MAPPED

LABS = [p.name for p in list_labs() if p.parent == repo_labs_dir()]


def test_the_contract_names_real_labs():
    assert REQUIREMENTS_MAPPED <= set(LABS)
SECTION = re.compile(r"^##\s+Requirements\s*$(.*?)(?=^##\s|\Z)", re.M | re.S)
ITEM = re.compile(r"^\s*[-*]\s+\*\*(R\d+)\*\*", re.M)


def readme_requirements(text: str) -> list[str]:
    """The ids ``R1``, ``R2``... of the items of the README's ``## Requirements`` section."""
    m = SECTION.search(text)
    return ITEM.findall(m.group(1)) if m else []


def gaps(readme: str, criteria) -> list[str]:
    ids = readme_requirements(readme)
    out = []
    if not ids:
        out.append("the README has no '## Requirements' section with items '- **R1** text'")
    named: dict[str, list[str]] = {}
    for c in criteria:
        for r in c.requirements:
            named.setdefault(r, []).append(c.name)
    out += [f"README requirement {r} is checked by no criterion (add requirements = "
            f'["{r}"] to one)' for r in ids if r not in named]
    out += [f"criterion {', '.join(sorted(set(names)))} names {r}, which the README does not list"
            for r, names in sorted(named.items()) if r not in ids]
    if not any(c.critical for c in criteria):
        out.append("no criterion is critical (critical = true: safety or the core function)")
    return out


@pytest.mark.parametrize("lab_id", sorted(REQUIREMENTS_MAPPED))
def test_readme_requirements_map_to_criteria(lab_id):
    lab = load_lab(lab_id)
    readme = (lab.path / "README.md").read_text(encoding="utf-8")
    problems = gaps(readme, lab.criteria)
    assert not problems, f"{lab_id}:\n  " + "\n  ".join(problems)


class _C:
    def __init__(self, name, requirements=(), critical=False):
        self.name, self.requirements, self.critical = name, list(requirements), critical


README = """# Lab\n\n## Requirements\n\n- **R1** the motor starts\n- **R2** STOP wins\n\n## Hints\n- **R9** not a requirement\n"""


def test_the_check_finds_every_kind_of_gap():
    assert readme_requirements(README) == ["R1", "R2"]
    assert gaps(README, [_C("starts", ["R1"]), _C("stop", ["R2"], critical=True)]) == []
    found = gaps(README, [_C("starts", ["R1", "R3"])])
    assert any("R2 is checked by no criterion" in g for g in found)
    assert any("names R3" in g for g in found)
    assert any("no criterion is critical" in g for g in found)
    assert gaps("# Lab\n", [_C("a", critical=True)])[0].startswith("the README has no")
