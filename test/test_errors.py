"""Which errors end a command in one line: only the project's ``InputError`` (the user's
input is wrong); any other exception is a defect and keeps its traceback."""
from __future__ import annotations

import argparse

import pytest

from fowt_hydro_sim.cli import compile as compile_command
from fowt_hydro_sim.cli import main
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import ConfigError, SampleError
from fowt_hydro_sim.rosbag.schemas import SchemaError
from fowt_hydro_sim.rosbag.writer import BagError, RecordingStopped
from fowt_hydro_sim.settings import SettingError


def _command_raising(monkeypatch: pytest.MonkeyPatch, error: Exception) -> None:
    """``fowt-sim compile`` replaced by a function raising ``error``."""
    def command(args: argparse.Namespace) -> int:
        raise error

    monkeypatch.setattr(compile_command, "compile_kernels", command)


@pytest.mark.parametrize("error_type", [ConfigError, SampleError, SettingError, BagError, RecordingStopped,
                                        SchemaError])
def test_the_project_error_types_are_input_errors(error_type: type):
    assert issubclass(error_type, InputError) and issubclass(error_type, ValueError)


def test_an_input_error_is_one_line(monkeypatch, capsys):
    _command_raising(monkeypatch, ConfigError("platform.yaml: mass.mass_kg: must be a positive number"))
    assert main(["compile"]) == 2
    assert capsys.readouterr().err.splitlines() == [
        "fowt-sim compile: error: platform.yaml: mass.mass_kg: must be a positive number"]


def test_an_internal_value_error_keeps_its_traceback(monkeypatch):
    _command_raising(monkeypatch, ValueError("operands could not be broadcast together"))
    with pytest.raises(ValueError, match="broadcast"):
        main(["compile"])


def test_verbose_shows_the_traceback_of_an_input_error(monkeypatch, capsys):
    _command_raising(monkeypatch, InputError("--transient: must not be negative, got -1"))
    assert main(["-v", "compile"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0] == "Traceback (most recent call last):" and "in command" in "\n".join(err)
    assert err[-1] == "fowt-sim compile: error: --transient: must not be negative, got -1"
