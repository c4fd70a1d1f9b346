"""Which chapters teach a diagnostic code (they show it as a marked mistake), for
``plclab explain CODE``."""

from __future__ import annotations

from .model import chapters, default_course_dir


def chapters_teaching(code: str) -> list[str]:
    """Lines naming each chapter that shows *code* as a deliberate mistake (none when the course
    folder is not there, e.g. in an installed package)."""
    if not default_course_dir().is_dir():
        return []
    lines = []
    for c in chapters():
        try:
            if any(b.expected_code == code for b in c.blocks):
                from plclab.i18n import tr

                lines.append(tr("Taught in chapter {number}, {title}: {path}", number=c.number,
                                title=c.title, path=f"course/{c.slug}/chapter.md"))
        except Exception:  # noqa: BLE001 - a broken chapter must not break explain
            continue
    return lines
