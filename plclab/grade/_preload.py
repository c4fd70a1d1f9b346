"""Imported once by the grader's forkserver: loads and warms up what every child needs."""

from .worker import preload

preload()
