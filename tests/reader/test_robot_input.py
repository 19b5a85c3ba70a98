"""The robot input: made once by the command line from its shared options (the path, name:=value words, --package,
--trust and XACROKIT_TRUST_XACRO), frozen, its mappings copied (a caller's dict changed later changes nothing), and
picklable for a worker process."""

from __future__ import annotations

import argparse
import dataclasses
import pickle
from pathlib import Path

import pytest

from xacrokit.cli.arguments import robot_input
from xacrokit.errors import ExpandError, XacrokitError
from xacrokit.reader.robot_input import RobotInput, as_input


def arguments(**given: object) -> argparse.Namespace:
    return argparse.Namespace(**{"mappings": [], "package": [], "trust": False, **given})


def test_the_command_line_makes_one_input_of_its_options(monkeypatch):
    monkeypatch.delenv("XACROKIT_TRUST_XACRO", raising=False)
    made = robot_input(arguments(mappings=["arm:=left", "n:=2"], package=["kit=../kit"]), "robot.urdf.xacro")
    assert made == RobotInput(Path("robot.urdf.xacro"), {"arm": "left", "n": "2"}, {"kit": "../kit"}, False)
    assert robot_input(arguments(trust=True), "r.xacro").trust is True


def test_the_environment_trusts_as_the_flag_does(monkeypatch):
    monkeypatch.setenv("XACROKIT_TRUST_XACRO", "1")
    assert robot_input(arguments(), "r.xacro").trust is True
    monkeypatch.setenv("XACROKIT_TRUST_XACRO", "0")
    assert robot_input(arguments(), "r.xacro").trust is False


def test_bad_words_are_refused_with_what_is_right():
    with pytest.raises(ExpandError, match="name:=value"):
        robot_input(arguments(mappings=["arm=left"]), "r.xacro")
    with pytest.raises(XacrokitError, match="NAME=PATH"):
        robot_input(arguments(package=["no_folder"]), "r.xacro")


def test_an_input_is_frozen_copied_and_pickles():
    given = {"arm": "left"}
    made = RobotInput("r.xacro", given)
    given["arm"] = "right"
    assert made.mappings == {"arm": "left"} and isinstance(made.path, Path)
    with pytest.raises(dataclasses.FrozenInstanceError):
        made.trust = True  # type: ignore[misc]
    assert pickle.loads(pickle.dumps(made)) == made
    assert as_input(made) is made and as_input("r.urdf") == RobotInput(Path("r.urdf"))
