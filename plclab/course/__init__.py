"""The course: chapters in ``course/`` with runnable examples, figures from real runs, quizzes.

Layer ``course`` (above ``grade``, below the command line; ``docs/adr/0013-layers-and-lazy-cli.md``)
reads the chapter folders (:mod:`.model`), runs their code (:mod:`.blocks`), draws their figures
(:mod:`.figures`), grades and checks their quizzes (:mod:`.quiz`) and builds the readable course
(:mod:`.build`). The format: ``docs/adr/0018-course-format.md``.
"""

from __future__ import annotations

from .model import Chapter, chapters, find_chapter

__all__ = ["Chapter", "chapters", "find_chapter"]
