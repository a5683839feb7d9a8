"""The project's error types' common base.

``InputError`` means the user's input is wrong (a file, an option, a setting, a message):
``fowt-sim`` ends the command with one line naming the problem (exit 2). Every other
exception is a defect and keeps its traceback.
"""
from __future__ import annotations


class InputError(ValueError):
    """The user's input cannot be used; the message names the input and the problem."""


class ConfigError(InputError):
    """A configuration file or value that cannot be used; the message names the field."""


class ClusterError(RuntimeError):
    """The Dask cluster lost runs under way (a worker died or stalled, the scheduler forgot
    a task): no fault of the input. ``fowt-sim`` ends the command with one line (exit 1);
    the commands that keep their results as they go (``sweep``, ``diagnose-benchmark``)
    resume when run again into the same folder."""
