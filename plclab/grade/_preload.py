"""Imported once by the grader's forkserver: ends with the grader, then loads and warms up
what every child needs."""

import os

from .sandbox import MARKER, set_pdeathsig
from .worker import preload

if os.environ.get(MARKER) == "forkserver":  # not when a test or a doc tool imports this
    set_pdeathsig()  # the forkserver must not outlive the grader that started it
preload()
